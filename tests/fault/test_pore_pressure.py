"""Pore pressure and dilatancy on the spring–block (Segall & Rice 1995): the drained and undrained
limits and the dilatancy-stabilised threshold against closed forms derived for the aging law.

Linearising M u̇ = −kX − σ̄_ss(μ − μ_ss) + (p − p_∞)μ, θ̇ = 1 − vθ/L,
ṗ = −(p − p_∞)/t_f + (ε/β)θ̇/θ about steady sliding gives, with c = 1/t_f and E = μ_ss ε/β,

    MVλ + kV/λ + σ̄a − (V/L)[σ̄b − Eλ/(λ + c)]/(λ + V/L) = 0,

so t_f → 0 is the plain block at σ̄ = σ − p_∞ and t_f → ∞ the plain block at σ̄ with b → b − E/σ̄:
k_c = [σ̄(b − a) − E]/L · [1 + MV²/(Lσ̄a)] (the plain k_c, Putelat et al. 2010 eq. 30 with η = 0), which
vanishes at ε_c = βσ̄(b − a)/μ_ss.  The engine's k_c is the stiffest Hopf root of the 4-state block's
characteristic polynomial: the limits are reached with an error of order ω_c t_f (drained) and
1/(ω_c t_f) (undrained), ω_c ≈ 50 rad/s here, so t_f = 1e-10 s and 1e10 s put them below 1e-8.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from landau.derivation.linear import HopfLine
from landau.errors import NoSteadySlidingError
from landau.systems import fault_terms as F
from landau.systems.system import SpringBlock

V = 1e-4
LAW = "dieterich"
P = dict(sigma=20.0, p_inf=5.0, eps_dil=3e-4, beta=1e-3, M=0.7)


def _kc(params, block=None):
    block = block or SpringBlock.for_params(LAW, params)
    return float(HopfLine(block).evaluate(np.array([V]), params)[0][0])


def _law_values():
    b = SpringBlock(LAW)
    return {k: v for k, v in b.defaults.items()}


def _closed(eps, M):
    d = _law_values()
    a, b, L = d["a"], d["b"], d["L"]
    s = P["sigma"] - P["p_inf"]
    mu_ss = d["a_v"] + (a - b) * math.log(V / d["V_s"])
    E = mu_ss * eps / P["beta"]
    return (s * (b - a) - E) / L * (1 + M * V ** 2 / (L * s * a)), P["beta"] * s * (b - a) / mu_ss


def test_drained_kc_is_the_plain_kc_at_the_effective_stress():
    drained = _kc({**P, "t_drain": 1e-10})
    plain = _kc({"sigma": P["sigma"] - P["p_inf"], "M": P["M"]}, SpringBlock(LAW))
    assert drained == pytest.approx(plain, rel=1e-8)
    assert F.drained_kc(V, SpringBlock.for_params(LAW, P).resolve({**P, "t_drain": 1e-10})) == \
        pytest.approx(plain, rel=1e-12)
    assert drained != pytest.approx(_kc({"sigma": P["sigma"], "M": P["M"]}, SpringBlock(LAW)), rel=1e-2)


def test_undrained_kc_against_its_closed_form():
    want, _ = _closed(P["eps_dil"], P["M"])
    got = _kc({**P, "t_drain": 1e10})
    assert got == pytest.approx(want, rel=1e-8)
    assert F.undrained_kc(V, SpringBlock.for_params(LAW, P).resolve(P)) == pytest.approx(want, rel=1e-12)
    assert got < 0.7 * _kc({**P, "t_drain": 1e-10})       # dilatancy hardening: a real effect here


def test_undrained_quasistatic_kc():
    """M = 0: k_c = [σ̄(b − a) − E]/L (no inertia factor)."""
    want, _ = _closed(P["eps_dil"], 0.0)
    assert _kc({**P, "M": 0.0, "t_drain": 1e10}) == pytest.approx(want, rel=1e-8)


def test_dilatancy_stabilised_threshold_of_eps():
    """Bisect ε on whether the nearly undrained block keeps a Hopf point at a stiffness above 1e-4 of the
    drained one: beyond ε_c its k_c is of order c = 1/t_f (no Hopf point in the undrained limit)."""
    _, eps_c = _closed(0.0, P["M"])
    floor = 1e-4 * _kc({**P, "t_drain": 1e-10})
    block = SpringBlock.for_params(LAW, P)

    def unstable_somewhere(eps):
        k = _kc({**P, "eps_dil": eps, "t_drain": 1e10}, block)
        return np.isfinite(k) and k > floor

    lo, hi = 0.5 * eps_c, 2.0 * eps_c
    assert unstable_somewhere(lo) and not unstable_somewhere(hi)
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if unstable_somewhere(mid) else (lo, mid)
    # k_c is linear in ε near ε_c: the floor 1e-4 k_c(drained) moves the located ε by ~1e-4 ε_c
    assert 0.5 * (lo + hi) == pytest.approx(eps_c, rel=5e-4)
    resolved = block.resolve(P)
    assert F.stabilising_eps(V, resolved) == pytest.approx(eps_c, rel=1e-12)
    assert F.dilatancy_regime(V, {**resolved, "eps_dil": 1.1 * eps_c}) == "dilatancy-stabilised"
    assert F.dilatancy_regime(V, {**resolved, "eps_dil": 0.9 * eps_c}) == "unstable below k_c"


def test_finite_drainage_keeps_a_hopf_point_above_the_quasistatic_bound():
    """M = 0, ε > ε_c, finite t_f: the Routh–Hurwitz condition of the cubic (derived in the module docstring)
    has a root above k₀ = cσ̄(b − a)/(L(c + V/L)), falling like 1/t_f."""
    _, eps_c = _closed(0.0, 0.0)
    d = _law_values()
    s = P["sigma"] - P["p_inf"]
    ks = []
    for tf in (1e3, 1e5):
        k = _kc({**P, "M": 0.0, "eps_dil": 1.5 * eps_c, "t_drain": tf})
        c = 1 / tf
        assert k > c * s * (d["b"] - d["a"]) / (d["L"] * (c + V / d["L"]))
        ks.append(k)
    assert ks[1] / ks[0] == pytest.approx(1e-2, rel=0.05)


def test_no_steady_sliding_without_effective_stress():
    with pytest.raises(NoSteadySlidingError, match="sigma - p_inf"):
        _kc({**P, "p_inf": 25.0, "t_drain": 1.0})
