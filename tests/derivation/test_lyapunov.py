"""Fredholm route (landau.derivation.multiscale) vs Kuznetsov's projection formula (landau.derivation.lyapunov).

Two independent routes must agree: sign(l₁) = sign(Λ) and the
normalisation-free slip amplitude C (Putelat et al. 2010, eq. 23: max|x − x₀| ≈
C sqrt|k_c − k|) equal to 1e-8 relative, for every built-in law at ≥ 5 velocities inside
its velocity-weakening range, and for a two-state law.

The two routes share only the symbolic jets: the Kuznetsov route re-locates the Hopf
point and computes q, p from mpmath's eigen-solver (40 digits), and the transversality
from eigenvalues at k_c ± h.  Observed agreement is ~1e-12 (limited by the float64
evaluation of the engine's C); 1e-8 leaves room for conditioning near the range ends.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from vw_ranges import LAWS, vw_range

from landau.derivation.hopf import Criticality, HopfResult
from landau.derivation.lyapunov import first_lyapunov, spring_block_lyapunov
from landau.derivation.multiscale import derive
from landau.errors import InputError
from landau.laws import get_law
from landau.systems.system import DynamicalSystem, SpringBlock

REL = 1e-8
#: positions inside the log-velocity range (fractions of log(V_hi/V_lo)), away from the ends
FRACTIONS = (0.05, 0.25, 0.45, 0.65, 0.85, 0.97)
NAMES = ["kc", "omega_c", "Gamma_bar", "Lambda", "C"]


def _velocities(name: str) -> list[float]:
    lo, hi, _ = vw_range(name)
    return [lo * (hi / lo) ** f for f in FRACTIONS]


def _compare(name: str, Vs) -> None:
    d = derive(SpringBlock(get_law(name)), NAMES)
    eng = d.evaluate(np.asarray(Vs), {}, NAMES)
    for i, V0 in enumerate(Vs):
        k = spring_block_lyapunov(d.block, float(V0), jets=d.jets)
        # the Fredholm formulas evaluated at 50 digits: this compares the two *routes*; the
        # float64 compiled values are compared with these in test_numerical_stability.py and,
        # against Kuznetsov directly, in test_compiled_route_matches_kuznetsov below
        if d.hopf.closed_form is not None:
            mp = d.evaluate_mp(float(V0), {}, ["Lambda", "C"])
            lam, C = float(mp["Lambda"]), float(mp["C"])
        else:  # several states: evaluate_mp needs a closed-form Hopf line; use the compiled values
            lam, C = float(eng["Lambda"][i]), float(eng["C"][i])
        ctx = f"{name} V={V0:.6g}: engine Lambda={lam:.12g} C={C:.15g}; Kuznetsov l1={k.l1:.12g} C={k.C:.15g}"
        assert np.sign(lam) == k.sign != 0, ctx
        assert math.isclose(k.C, C, rel_tol=REL), ctx
        # the Hopf point itself, re-located from the eigenvalues (Putelat eqs 7-8)
        assert math.isclose(k.p_c, eng["kc"][i], rel_tol=1e-10), ctx
        assert math.isclose(k.omega, eng["omega_c"][i], rel_tol=1e-10), ctx
        # steady sliding is stable for k > k_c: Re λ decreases with k
        assert k.dmu_dp < 0, ctx


@pytest.mark.parametrize("name", LAWS)
def test_fredholm_matches_kuznetsov(name):
    _compare(name, _velocities(name))


def test_two_state_law_fredholm_matches_kuznetsov():
    # two Dieterich-type states (4 state variables, numeric Hopf line); both criticalities occur
    _compare("two-state-dieterich", [1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2])


def test_compiled_route_matches_kuznetsov():
    # the vectorised values (float64 with the engine's 50-digit fallback) themselves
    for name in LAWS:
        Vs = [_velocities(name)[j] for j in (0, 2, 5)]
        d = derive(SpringBlock(get_law(name)), NAMES)
        eng = d.evaluate(np.asarray(Vs), {}, ["C"])
        for i, V0 in enumerate(Vs):
            k = spring_block_lyapunov(d.block, V0, jets=d.jets)
            assert math.isclose(k.C, eng["C"][i], rel_tol=REL), (name, V0, k.C, eng["C"][i])


def test_both_signs_are_exercised():
    # Dieterich (Putelat Sec. 3.2): Λ_D > 0 at low V, < 0 at high V — the check must see both
    d = derive(SpringBlock(get_law("dieterich")), ["Lambda"])
    signs = {spring_block_lyapunov(d.block, V0, jets=d.jets).sign for V0 in (1e-6, 1e-3)}
    assert signs == {-1, 1}


def _normal_form_system(s_val):
    """ẋ = p x − y + s x r², ẏ = x + p y + s y r²: z = x + iy obeys ż = (p + i) z + s z|z|²."""
    x, y, p, s = sp.symbols("x y p s", real=True)
    r2 = x ** 2 + y ** 2
    return DynamicalSystem("hopf-normal-form", (x, y), (p * x - y + s * x * r2, x + p * y + s * y * r2),
                           (sp.Integer(1), sp.Integer(1)), p, (sp.Integer(0), sp.Integer(0)))


@pytest.mark.parametrize("s_val", [-0.7, 2.5])
def test_generic_entry_point_on_the_normal_form(s_val):
    # closed form: ω = 1, dRe λ/dp = 1, cycle radius sqrt(-p/s), so max|x| / sqrt|p| = 1/sqrt|s|.
    # With Kuznetsov's ⟨q, q⟩ = 1, q = (1, −i)/√2 (up to a phase), x + iy = √2 z_K, so
    # ż_K = (p + i) z_K + 2s z_K|z_K|²: c₁ = 2s, l₁ = 2s.  Fixes every factor of 2 in the route.
    res = first_lyapunov(_normal_form_system(s_val), {"s": s_val}, 0.01)
    assert isinstance(res, HopfResult)
    assert abs(res.p_c) < 1e-30
    assert math.isclose(res.omega, 1.0, rel_tol=1e-25)
    assert math.isclose(res.l1, 2 * s_val, rel_tol=1e-25)
    assert math.isclose(res.dmu_dp, 1.0, rel_tol=1e-15)
    assert math.isclose(res.C, 1 / math.sqrt(abs(s_val)), rel_tol=1e-15)
    assert res.as_dict()["criticality"] == ("supercritical" if s_val < 0 else "subcritical")
    assert res.criticality is (Criticality.SUPERCRITICAL if s_val < 0 else Criticality.SUBCRITICAL)
    assert "HopfResult(hopf-normal-form: p_c = " in repr(res)
    # landau's convention (mode (1, −i), x component 1): (x, y) = A e^{it}(1, −i) + c.c., so
    # x + iy = 2A e^{it} and Ȧ = (p + i)A + 4s A|A|²: Λ = 2 Re b = 8s, χ = 0, dλ/dp = 1 (closed
    # form; dλ/dp by finite differences of λ(p) at 40 digits)
    assert math.isclose(res.Lambda, 8 * s_val, rel_tol=1e-25)
    assert abs(res.chi) < 1e-25
    assert abs(res.dlambda_dp - 1) < 1e-15
    assert res.equilibrium == (0.0, 0.0) and res.normalise == "x"


def test_quasi_static_limit_is_refused():
    # M = 0 makes E·ẏ = f a DAE: the ODE route must say so, not return a number
    with pytest.raises(InputError, match="M > 0"):
        spring_block_lyapunov(SpringBlock(get_law("ruina")), 1e-5, {"M": 0.0})


def test_low_precision_is_refused():
    with pytest.raises(InputError):
        first_lyapunov(_normal_form_system(-1.0), {"s": -1.0}, 0.0, dps=15)


@pytest.mark.parametrize("V0", [1e-4, 1e-3])
def test_both_routes_return_the_same_result_field_by_field(V0):
    # One result type for both routes: the Fredholm engine's point (Derivation.points) and
    # Kuznetsov's projection (spring_block_lyapunov) are HopfResults in the spring–block
    # convention, so every field compares directly — Λ, χ, k_c, ω_c, Γ̄ = −d Re λ/dk and
    # Ω̄ = d Im λ/dk (the latter two from eigenvalues at k_c ± h, ±2h), C.  Dieterich's law is
    # subcritical at 1e-4 m/s and supercritical at 1e-3 m/s (Putelat et al. 2010, Sec. 3.2).
    # Observed agreement ≤ 2e-13; 1e-10 is the engine's accuracy target for every value.
    d = derive(SpringBlock(get_law("dieterich")))
    eng = d.points([V0])[0]
    kuz = spring_block_lyapunov(d.block, V0, jets=d.jets)
    assert isinstance(eng, HopfResult) and isinstance(kuz, HopfResult)
    assert eng.convention == kuz.convention and eng.normalise == kuz.normalise == "X"
    assert eng.V == kuz.V == V0 and eng.criticality is kuz.criticality
    for name in ("p_c", "kc", "omega_c", "Lambda", "chi", "C", "Gamma_bar", "Omega_bar"):
        assert math.isclose(getattr(eng, name), getattr(kuz, name), rel_tol=1e-10), name
    assert eng.equilibrium == pytest.approx(kuz.equilibrium, rel=1e-14)      # (X, u, φ) = (0, 0, L/V)
    assert eng.equilibrium[2] == pytest.approx(d.block.resolve()["L"] / V0, rel=1e-14)
    assert kuz.l1 == pytest.approx(kuz.c1.real / kuz.omega_c, rel=1e-14)
    # l₁ and c₁ on the engine's route: c₁ = (Λ + iχ)/(2‖q‖²) with the critical eigenvector q of
    # slip component 1 — the same numbers as Kuznetsov's c₁ here, by an independent route
    assert eng.l1 == pytest.approx(kuz.l1, rel=1e-10)
    assert eng.c1.real == pytest.approx(kuz.c1.real, rel=1e-10)
    assert eng.c1.imag == pytest.approx(kuz.c1.imag, rel=1e-10)
