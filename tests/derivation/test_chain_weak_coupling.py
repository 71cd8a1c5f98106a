"""The chain's first Hopf crossing at any coupling: weakly coupled identical blocks have their two
(or three) modes' crossings within one scan interval, where the bialternate test function's sign
changes cancel; the scan must still find the in-phase crossing, whose k_c is the single block's
closed form (Putelat, Dawes & Willis 2010 eq. (30)), and name the double crossing of uncoupled blocks."""

from __future__ import annotations

import pytest

from landau.analyses.chain import chain_hopf
from landau.errors import NoHopfError, NonSimpleHopfError
from landau.systems.chain import SpringBlockChain

# Putelat et al. (2010) Table 1 (the dieterich law's defaults); the chain's default blocks
A_, B_, L_ = 0.0349, 0.0489, 9e-7
M_, SIGMA_ = 1.2, 1.2 * 9.81


def single_block_kc(V: float) -> float:
    """Putelat et al. (2010) eq. (30), aging law: k_c = σ(b − a)/L · (1 + M V²/(σ a L))."""
    return SIGMA_ * (B_ - A_) / L_ * (1 + M_ * V ** 2 / (SIGMA_ * A_ * L_))


def test_the_closed_form_is_the_reported_single_block_value():
    assert single_block_kc(1e-4) == pytest.approx(189062.9056563727, rel=1e-12)


@pytest.mark.parametrize("n, kc", [(2, 1e3), (2, 1e2), (2, 1e-2), (2, 1e-6), (3, 1e3), (3, 1e-2),
                                   (2, 1e5), (3, 1e7)])
def test_the_first_crossing_is_in_phase_at_the_single_block_kc(n, kc):
    # the other modes stretch the coupling springs (k + 2k_c(1 − cos(jπ/n)) in place of k), so they
    # cross at k_c − 2k_coupling(1 − cos(jπ/n)) < k_c: weak coupling puts them within one scan step
    r = chain_hopf(SpringBlockChain("dieterich", n), {"k_coupling": kc, "V": 1e-4})
    assert r.p_c == pytest.approx(single_block_kc(1e-4), rel=1e-9)
    assert r.extra["mode"] == "in-phase"
    assert all(z == pytest.approx([1.0, 0.0], abs=1e-9) for z in r.extra["mode_shape"])


@pytest.mark.parametrize("n", [2, 3])
def test_uncoupled_identical_blocks_are_a_double_crossing(n):
    # k_coupling = 0: n identical, independent blocks lose stability together at the single k_c
    with pytest.raises(NonSimpleHopfError, match=rf"{n} complex pairs cross .* together at k = 189062\.9"):
        chain_hopf(SpringBlockChain("dieterich", n), {"k_coupling": 0.0, "V": 1e-4})


def test_the_double_crossing_is_not_reported_as_no_crossing():
    assert not issubclass(NonSimpleHopfError, NoHopfError)
