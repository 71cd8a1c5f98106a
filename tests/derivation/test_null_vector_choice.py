"""The Fredholm solve's minors chosen from float64 null vectors (adj A = c q pᵀ, so |minor(A, i, j)| ∝
|p_i||q_j|) instead of 2n to n² determinants at the working precision: the same amplitude equation, and
no working-precision determinant where float64 shows a clear null space (a 5-block chain took 512 of
them, 31 CPU-s under a profiler; 12 blocks did not finish in 300 s, now about 20 s)."""

from __future__ import annotations

import mpmath
import pytest

from landau.analyses.chain import chain_hopf
from landau.derivation import general
from landau.laws import get_law
from landau.systems.chain import SpringBlockChain

#: an asymmetric 2-block chain (the masses differ, so the blocks do not tie in the critical mode)
PARAMS = {"V": 1e-4, "M_1": 1.2, "M_2": 0.7, "k_coupling": 3e4}


def _count_dets(monkeypatch) -> list[int]:
    calls = [0]
    det = mpmath.det

    def counted(m):
        calls[0] += 1
        return det(m)

    monkeypatch.setattr(general.mpmath, "det", counted)
    return calls


def test_the_float64_choice_gives_the_working_precision_choices_result(monkeypatch):
    chain = SpringBlockChain(get_law("dieterich"), 2)
    fast = chain_hopf(chain, PARAMS)
    # the previous route: every minor's determinant at the working precision
    monkeypatch.setattr(general, "float64_drop", lambda A, normalise: None)
    slow = chain_hopf(chain, PARAMS)
    for name in ("p_c", "omega_c", "Lambda", "chi"):
        # both are 50-digit computations rounded to float64; the minors dropped differ at most
        assert getattr(fast, name) == pytest.approx(getattr(slow, name), rel=1e-13, abs=0), name
    flat = lambda r: [x for pair in r.extra["mode_shape"] for x in pair]  # noqa: E731
    assert flat(fast) == pytest.approx(flat(slow), rel=1e-12, abs=1e-14)


def test_no_working_precision_determinant_where_float64_shows_the_null_space(monkeypatch):
    chain = SpringBlockChain(get_law("dieterich"), 3)
    p = chain.resolve({"V": 1e-4})
    num = general.NumericSystem(chain.system, p, chain.equilibrium_values(p))
    res = chain_hopf(chain, {"V": 1e-4})
    calls = _count_dets(monkeypatch)
    with mpmath.workdps(30):
        pc, wc, y = general.refine_hopf(num, res.p_c, res.omega_c, list(res.equilibrium))
        calls[0] = 0
        general.normal_form_at(num, pc, wc, y, params=p)
    assert calls[0] == 0
    monkeypatch.setattr(general, "float64_drop", lambda A, normalise: None)
    with mpmath.workdps(30):
        general.normal_form_at(num, pc, wc, y, params=p)
    n = num.n
    assert calls[0] >= 2 * n   # best_drop's 2n minors, and the normalise check's when the crude scale trips
