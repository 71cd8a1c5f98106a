"""The spring–block chain: its Hopf point against the eigenvalues of the Jacobian assembled in the
test, the single block's closed form for identical blocks, and a check of its critical cycle."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.optimize

from landau.analyses.chain import chain_hopf
from landau.errors import InputError, NoHopfError
from landau.systems.chain import SpringBlockChain

# Putelat et al. (2010) Table 1 (the dieterich law's defaults)
A_, B_, L_ = 0.0349, 0.0489, 9e-7


def assembled_jacobian(k, V, Ms, sigmas, kc):
    """ẏ = J y at steady sliding, y = (X_i, u_i, φ_i): aging law μ = a ln(v/V_s) + a_v + b ln(V_s φ/L),
    dφ/dt = 1 − φv/L (φ_ss = L/V): μ_v = a/V, μ_φ = bV/L, ∂rate/∂v = −1/V, ∂rate/∂φ = −V/L."""
    n = len(Ms)
    J = np.zeros((3 * n, 3 * n))
    for i in range(n):
        x, u, f = 3 * i, 3 * i + 1, 3 * i + 2
        J[x, u] = 1.0
        neighbours = [j for j in (i - 1, i + 1) if 0 <= j < n]
        J[u, x] = -(k + kc * len(neighbours)) / Ms[i]
        for j in neighbours:
            J[u, 3 * j] = kc / Ms[i]
        J[u, u] = -sigmas[i] * A_ / V / Ms[i]
        J[u, f] = -sigmas[i] * B_ * V / L_ / Ms[i]
        J[f, u] = -1.0 / V
        J[f, f] = -V / L_
    return J


def first_crossing(V, Ms, sigmas, kc, k_hi=1e7):
    """The largest k where max Re λ crosses 0 (a scan down from k_hi, then Brent)."""
    g = lambda k: np.max(np.linalg.eigvals(assembled_jacobian(k, V, Ms, sigmas, kc)).real)
    ks = np.geomspace(k_hi, k_hi * 1e-4, 2000)
    vals = [g(k) for k in ks]
    i = next(i for i in range(len(ks) - 1) if vals[i] < 0 <= vals[i + 1])
    return scipy.optimize.brentq(g, ks[i + 1], ks[i], xtol=1e-12, rtol=1e-14)


@pytest.mark.parametrize("V, Ms, sigmas, kc", [
    (1e-4, (1.2, 0.6), (11.772, 8.0), 3e4),
    (3e-5, (1.0, 1.5, 0.8), (10.0, 14.0, 9.0), 5e4),
    (2e-4, (0.5, 2.0, 1.0), (6.0, 20.0, 12.0), 1e3),
])
def test_hopf_point_against_the_assembled_jacobian(V, Ms, sigmas, kc):
    n = len(Ms)
    over = {"V": V, "k_coupling": kc, **{f"M_{i + 1}": m for i, m in enumerate(Ms)},
            **{f"sigma_{i + 1}": s for i, s in enumerate(sigmas)}}
    r = chain_hopf(SpringBlockChain("dieterich", n), over)
    k_ref = first_crossing(V, Ms, sigmas, kc)
    assert r.p_c == pytest.approx(k_ref, rel=1e-9)       # float64 eigenvalues vs 50-digit Newton
    lam = np.linalg.eigvals(assembled_jacobian(k_ref, V, Ms, sigmas, kc))
    assert r.omega_c == pytest.approx(np.max(np.abs(lam[np.abs(lam.real) < 1e-6 * np.abs(lam)].imag)), rel=1e-7)
    assert len(r.extra["mode_shape"]) == n
    assert max(abs(complex(*z)) for z in r.extra["mode_shape"]) == pytest.approx(1.0, rel=1e-12)


@pytest.mark.parametrize("n", [2, 3])
def test_identical_blocks_have_the_single_block_kc_in_phase(n):
    # Putelat et al. (2010) eq. (30), aging law: k_c = σ(b − a)/L · (1 + M V²/(σ a L))
    M, sigma, V = 0.8, 15.0, 2e-4
    over = {"V": V, "k_coupling": 4e4, **{f"M_{i}": M for i in range(1, n + 1)},
            **{f"sigma_{i}": sigma for i in range(1, n + 1)}}
    r = chain_hopf(SpringBlockChain("dieterich", n), over)
    kc = sigma * (B_ - A_) / L_ * (1 + M * V ** 2 / (sigma * A_ * L_))
    assert r.p_c == pytest.approx(kc, rel=1e-12)
    assert r.extra["mode"] == "in-phase"
    assert all(z == pytest.approx([1.0, 0.0], abs=1e-12) for z in r.extra["mode_shape"])
    # the in-phase subspace is invariant and is the single block: the same Landau coefficient
    one = chain_hopf(SpringBlockChain("dieterich", 1), {"V": V, "M_1": M, "sigma_1": sigma})
    assert r.Lambda == pytest.approx(one.Lambda, rel=1e-9)


def test_velocity_strengthening_has_no_hopf_point():
    with pytest.raises(NoHopfError):
        chain_hopf(SpringBlockChain("dieterich", 2), {"b": 0.02})


@pytest.mark.parametrize("blocks, over, message", [
    (0, {}, "number of blocks"),
    (101, {}, "number of blocks"),
    (2, {"M": 1.0}, "one M per block"),
    (2, {"M_3": 1.0}, "unknown parameter 'M_3'"),
    (2, {"sigma_1": 0.0}, "sigma_1"),
    (2, {"k_coupling": -1.0}, "k_coupling"),
    (2, {"M_1": float("inf")}, "finite"),
])
def test_bad_chain_input(blocks, over, message):
    with pytest.raises(InputError, match=message):
        chain_hopf(SpringBlockChain("dieterich", blocks), over)


@pytest.mark.slow
def test_check_follows_the_critical_cycle():
    """``landau.check`` on the chain's DynamicalSystem: the cycle of the critical mode.

    The measured amplitude error is -6.1 % at ε² = 1e-3 and -1.6 % at 2.5e-4 (linear in ε²: the
    next order of the amplitude expansion), hence the tolerance."""
    from landau.analyses.checking import check

    chain = SpringBlockChain("dieterich", 2)
    over = {"M_2": 0.6, "k_coupling": 3e4}
    r = chain_hopf(chain, over)
    c = check(chain.system, params=chain.resolve(over), bracket=(0.99 * r.p_c, 1.01 * r.p_c), eps2=1e-3,
              tolerance=0.08)
    # the amplitude and frequency of the simulated cycle (its Floquet multipliers come from finite
    # differences of absolute step 1e-6, larger than this 1e-6 m cycle: not asserted here)
    assert abs(c.rel_error) <= 0.08, c
    assert c.amplitude_simulated > 0.5 * c.amplitude_predicted
    assert abs(c.frequency_rel_error) <= 1e-2, c
