"""The general Hopf engine (landau.derivation.general, landau.analyses.continuation): closed forms, independent
routes, defects.

Every check compares with a closed form, or with an independent computation: sympy's exact
derivatives against the Taylor-arithmetic jets, Kuznetsov's projection formula
(landau.derivation.lyapunov) against the Fredholm numbers, a system multiplied by its mass matrix against
the plain one, a system with E(p) against the same system written as ẏ = E(p)⁻¹f.
"""

from __future__ import annotations

import importlib.util
import json
import math
import pathlib

import mpmath
import pytest
import sympy as sp

from landau.analyses.continuation import equilibrium_branch, generalised_hopf
from landau.derivation.general import hopf_normal_form, kuznetsov_check
from landau.derivation.hopf import HopfResult
from landau.derivation.lyapunov import first_lyapunov
from landau.errors import InputError, NoHopfError
from landau.systems.system import DynamicalSystem

x, y, z, w = sp.symbols("x y z w", real=True)
mu, a, b, c = sp.symbols("mu a b c", real=True)


def _bench():
    path = pathlib.Path(__file__).resolve().parents[2] / "benchmarks" / "bench_general.py"
    spec = importlib.util.spec_from_file_location("bench_general", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def bautin_cartesian(omega=1) -> DynamicalSystem:
    """ż = (μ + iω)z + a z|z|² + b z|z|⁴ in Cartesian coordinates (Hopf parameter μ)."""
    omega = sp.nsimplify(omega)  # exact: a float coefficient would limit every check to 1e-16
    r2 = x**2 + y**2
    return DynamicalSystem("bautin", (x, y), (mu*x - omega*y + (a*r2 + b*r2**2)*x, omega*x + mu*y + (a*r2 + b*r2**2)*y),
                           (1, 1), mu, (0, 0))


# --- the result type -------------------------------------------------------------------------------------

def test_result_type_is_the_unified_hopf_result():
    h = hopf_normal_form(bautin_cartesian(), {"a": -0.5, "b": 1.0}, (-0.3, 0.2))
    assert isinstance(h, HopfResult)
    # closed form: q = (1, −i) (x-component 1), y = A q e^{it} + c.c., so z = 2A e^{it} and
    # dA/dt = μA + 4a A|A|²: Λ = 8a; Kuznetsov: q = (1, −i)/√2, c₁ = 2a, l₁ = 2a/ω
    assert h.Lambda == pytest.approx(8 * -0.5, rel=1e-14)
    assert h.chi == pytest.approx(0.0, abs=1e-14)
    assert h.dlambda_dp == pytest.approx(1.0, rel=1e-14)
    assert h.l1 == pytest.approx(2 * -0.5, rel=1e-14)
    assert h.c1 == pytest.approx(complex(-1.0, 0.0), abs=1e-14)
    assert h.criticality == "supercritical"
    json.dumps(h.as_dict())


def test_l1_in_matcont_normalisation_divides_by_omega():
    h = hopf_normal_form(bautin_cartesian(omega=2.5), {"a": 0.3, "b": 1.0}, (-0.3, 0.2))
    assert h.omega_c == pytest.approx(2.5, rel=1e-14)
    assert h.c1.real == pytest.approx(2 * 0.3, rel=1e-14)
    assert h.l1 == pytest.approx(2 * 0.3 / 2.5, rel=1e-14)


# --- defects ---------------------------------------------------------------------------------------------

def test_result_with_zero_landau_coefficient_prints():
    lin = DynamicalSystem("linear", (x, y), (mu*x - y, x + mu*y), (1, 1), mu, (0, 0))
    h = hopf_normal_form(lin, None, (-1.0, 0.5))
    assert h.Lambda == 0 and h.l1 == 0
    assert h.criticality == "degenerate"
    assert math.isinf(h.C)
    assert "degenerate" in repr(h)
    d = h.as_dict()
    assert d["Lambda"] == 0 and math.isinf(d["C"])
    json.dumps(d)
    assert math.isnan(h.amplitude(0.1)) and math.isnan(h.frequency(0.1))


def test_system_whose_only_parameter_is_the_hopf_parameter():
    sys1 = bautin_cartesian().__class__(  # a and b fixed numbers: μ is the only symbol
        "bautin-fixed", (x, y), tuple(e.subs({a: -1, b: 0}) for e in bautin_cartesian().rhs), (1, 1), mu, (0, 0))
    assert sys1.parameters == ()
    h = hopf_normal_form(sys1, None, (-0.3, 0.2))
    assert h.l1 == pytest.approx(-2.0, rel=1e-14)
    h2 = hopf_normal_form(sys1, {}, (-0.3, 0.2))
    assert h2.l1 == h.l1


def test_equilibrium_given_as_constants_is_refined():
    # Brusselator ẋ = a − (b + 1)x + x²y, ẏ = bx − x²y: equilibrium (a, b/a), Hopf at b = 1 + a²
    # (Strogatz, Nonlinear Dynamics and Chaos, ex. 8.3.1); given only as the numbers (1.9, 2.1)
    # at a = 2 (exact (2, b/2)), it is found by Newton's method all along the bracket
    rhs = (a - (b + 1)*x + x**2*y, b*x - x**2*y)
    guess = DynamicalSystem("brusselator-guess", (x, y), rhs, (1, 1), b, (sp.Float(1.9), sp.Float(2.1)))
    exact = DynamicalSystem("brusselator", (x, y), rhs, (1, 1), b, (a, b / a))
    hg = hopf_normal_form(guess, {"a": 2.0}, (4.0, 6.0))
    he = hopf_normal_form(exact, {"a": 2.0}, (4.0, 6.0))
    assert hg.p_c == pytest.approx(5.0, rel=1e-14) and he.p_c == pytest.approx(5.0, rel=1e-14)
    assert hg.omega_c == pytest.approx(2.0, rel=1e-14)          # ω² = det J = a²
    assert hg.equilibrium == pytest.approx((2.0, 2.5), rel=1e-14)
    assert hg.Lambda == pytest.approx(he.Lambda, rel=1e-14)
    assert hg.l1 == pytest.approx(he.l1, rel=1e-14)


def test_kuznetsov_route_agrees_with_fredholm_l1_closed_form_equilibrium():
    # the Brusselator has a closed-form equilibrium: Kuznetsov's projection formula (mpmath eigen-
    # solver, 40 digits, re-located point) against the Fredholm numbers rescaled to ⟨q, q⟩ = 1
    rhs = (a - (b + 1)*x + x**2*y, b*x - x**2*y)
    sysb = DynamicalSystem("brusselator", (x, y), rhs, (1, 1), b, (a, b / a))
    h = hopf_normal_form(sysb, {"a": 1.5}, (2.0, 4.0))
    k = first_lyapunov(sysb, {"a": 1.5}, h.p_c, omega_c=h.omega_c)
    assert k.l1 == pytest.approx(h.l1, rel=1e-12)
    assert k.c1 == pytest.approx(h.c1, rel=1e-12)
    assert k.C == pytest.approx(h.C, rel=1e-8)  # the projection route's μ' is a finite difference
    assert k.p_c == pytest.approx(h.p_c, rel=1e-14)


def test_kuznetsov_route_without_closed_form_equilibrium():
    # Lorenz-84 (three states; the equilibrium solves a cubic): Lorenz (1984), Tellus 36A, 98-110
    X, Y, Z = sp.symbols("X Y Z", real=True)
    al, be, F, G = sp.symbols("alpha beta F G", real=True)
    rhs = (-Y**2 - Z**2 - al*X + al*F, X*Y - be*X*Z - Y + G, be*X*Y + X*Z - Z)
    lor = DynamicalSystem("lorenz84", (X, Y, Z), rhs, (1, 1, 1), F, (sp.Float(1.0), sp.Float(0.5), sp.Float(0.5)))
    par = {"alpha": 0.25, "beta": 4.0, "G": 0.5}
    br = equilibrium_branch(lor, par, (0.0, 2.0), start=0.0)
    assert br.hopf
    for h in br.hopf:
        k = kuznetsov_check(lor, par, h)
        assert isinstance(k, HopfResult) and k.dlambda_dp == h.dlambda_dp
        assert k.l1 == pytest.approx(h.l1, rel=1e-12)
        assert k.c1 == pytest.approx(h.c1, rel=1e-12)
        assert k.C == pytest.approx(h.C, rel=1e-12)


def test_hopf_point_found_when_another_pair_is_already_unstable():
    # two decoupled oscillators: (x, y) always unstable (Re λ = 1), (z, w) crosses at μ = 0.3
    rhs = (x - 2*y - x*(x**2 + y**2), 2*x + y - y*(x**2 + y**2),
           (mu - sp.Rational(3, 10))*z - w + a*z*(z**2 + w**2), z + (mu - sp.Rational(3, 10))*w + a*w*(z**2 + w**2))
    sys4 = DynamicalSystem("two-oscillators", (x, y, z, w), rhs, (1, 1, 1, 1), mu, (0, 0, 0, 0), normalise=2)
    h = hopf_normal_form(sys4, {"a": -0.7}, (-1.0, 1.0))
    assert h.p_c == pytest.approx(0.3, rel=1e-14)
    assert h.omega_c == pytest.approx(1.0, rel=1e-14)
    assert h.l1 == pytest.approx(2 * -0.7, rel=1e-13)


def test_several_hopf_points_in_the_bracket_are_named():
    rhs = (sp.sin(mu)*x - y - x*(x**2 + y**2), x + sp.sin(mu)*y - y*(x**2 + y**2))
    s = DynamicalSystem("periodic", (x, y), rhs, (1, 1), mu, (0, 0))
    with pytest.raises(InputError, match="2 Hopf points"):
        hopf_normal_form(s, None, (-1.0, 4.0))
    with pytest.raises(NoHopfError):
        hopf_normal_form(s, None, (0.5, 2.5))


# --- derivative routes -----------------------------------------------------------------------------------

def test_taylor_jets_equal_symbolic_jets():
    rhs = (mu*x - y + sp.tanh(x*y) * x + sp.exp(y) - 1 - y + c*x**2*sp.log(1 + y**2 + x),
           x + mu*y - y**3 + sp.sin(x)**2 / (2 + x))
    s = DynamicalSystem("mixed", (x, y), rhs, (1, 1), mu, (0, 0))
    with mpmath.workdps(50):
        ht = hopf_normal_form(s, {"c": 0.3}, (-0.5, 0.5), jets="taylor")
        hs = hopf_normal_form(s, {"c": 0.3}, (-0.5, 0.5), jets="symbolic")
    for name in ("p_c", "omega_c", "Lambda", "chi", "l1"):
        assert getattr(ht, name) == pytest.approx(getattr(hs, name), rel=1e-14, abs=1e-40)
    assert ht.dlambda_dp == pytest.approx(hs.dlambda_dp, rel=1e-14)


def test_dense_system_taylor_matches_kuznetsov():
    # n = 3 keeps the projection route's symbolic jets cheap (its cost grows like n^4)
    dense = _bench().dense_test_system(3)
    h = hopf_normal_form(dense, None, (-1.0, 1.0))
    # the projection route computes its own (symbolic) jets at the constant equilibrium y = 0
    k = first_lyapunov(dense, {}, h.p_c, omega_c=h.omega_c)
    assert k.l1 == pytest.approx(h.l1, rel=1e-12)


# --- mass matrices ---------------------------------------------------------------------------------------

def test_full_mass_matrix_gives_the_same_normal_form():
    base = bautin_cartesian()
    Em = sp.Matrix([[2, sp.Rational(1, 3)], [sp.Rational(-1, 2), 1]])
    mixed = DynamicalSystem("bautin-E", (x, y), tuple(Em * sp.Matrix(base.rhs)), Em, mu, (0, 0))
    assert not mixed.mass_is_diagonal
    h0 = hopf_normal_form(base, {"a": -0.5, "b": 1.0}, (-0.3, 0.2))
    h1 = hopf_normal_form(mixed, {"a": -0.5, "b": 1.0}, (-0.3, 0.2))
    for name in ("p_c", "omega_c", "Lambda", "chi", "l1"):
        assert getattr(h1, name) == pytest.approx(getattr(h0, name), rel=1e-14, abs=1e-40)
    assert h1.dlambda_dp == pytest.approx(h0.dlambda_dp, rel=1e-14)


def test_parameter_dependent_mass_matrix_against_inverted_system():
    # E(μ)·ẏ = f(y; μ) against ẏ = E(μ)⁻¹ f(y; μ) built symbolically (identity mass): the
    # E_p term of the linear coefficient a = dλ/dμ is the only place E(μ) enters
    f = (mu*x - y + c*x**2 - x*(x**2 + y**2), x + mu*y + x*y - y*(x**2 + y**2))
    for Em in (sp.Matrix([[1 + mu**2, mu / 2], [-mu / 3, 2 - mu]]), sp.diag(1 + mu, 3 + mu**2)):
        with_E = DynamicalSystem("E(mu)", (x, y), f, Em, mu, (0, 0))
        inverted = DynamicalSystem("inverse", (x, y), tuple(sp.simplify(e) for e in Em.inv() * sp.Matrix(f)),
                                   (1, 1), mu, (0, 0))
        h1 = hopf_normal_form(with_E, {"c": 0.4}, (-0.5, 0.5))
        h2 = hopf_normal_form(inverted, {"c": 0.4}, (-0.5, 0.5))
        assert h1.p_c == pytest.approx(h2.p_c, abs=1e-30)
        assert h1.omega_c == pytest.approx(h2.omega_c, rel=1e-14)
        assert h1.dlambda_dp == pytest.approx(h2.dlambda_dp, rel=1e-13)
        assert h1.Lambda == pytest.approx(h2.Lambda, rel=1e-13)
        assert h1.l1 == pytest.approx(h2.l1, rel=1e-13)


def test_singular_full_mass_matrix_is_a_named_error():
    Em = sp.Matrix([[1, 1], [1, 1]])
    s = DynamicalSystem("singular", (x, y), (mu*x - y, x + mu*y - x**3), Em, mu, (0, 0))
    with pytest.raises((InputError, NoHopfError)):
        hopf_normal_form(s, None, (-0.5, 0.5))


# --- continuation ----------------------------------------------------------------------------------------

def test_equilibrium_branch_finds_the_brusselator_hopf_point():
    rhs = (a - (b + 1)*x + x**2*y, b*x - x**2*y)
    sysb = DynamicalSystem("brusselator", (x, y), rhs, (1, 1), b, (a, b / a))
    br = equilibrium_branch(sysb, {"a": 1.5}, (1.0, 5.0))
    assert len(br.hopf) == 1 and not br.folds
    assert br.hopf[0].p_c == pytest.approx(1 + 1.5**2, rel=1e-14)
    # stable before, unstable (one complex pair) after
    assert br.n_unstable[0] == 0 and br.n_unstable[-1] == 2
    assert "Hopf at" in repr(br)
    json.dumps(br.as_dict())


def test_generalised_hopf_point_of_the_bautin_normal_form():
    # the Hopf curve is μ = 0 and l₁ = 2a/ω: the generalised-Hopf point is (μ, a) = (0, 0) exactly
    g = generalised_hopf(bautin_cartesian(), {"b": 1.0}, "a", (-0.5, 0.3), (-0.2, 0.2), l2=False)
    assert abs(g.p1) < 1e-13 and abs(g.p2) < 1e-13
    assert g.omega == pytest.approx(1.0, rel=1e-13)
    assert g.l2 is None
    assert "GeneralisedHopfPoint" in repr(g)
    with pytest.raises(NoHopfError):
        generalised_hopf(bautin_cartesian(), {"b": 1.0}, "a", (0.1, 0.3), (-0.2, 0.2), l2=False)


def test_generalised_hopf_l2_of_the_bautin_normal_form():
    # at a = 0: ẇ = iωw + 4b w|w|⁴ for q = (1, −i)/√2, so c₂ = 4b and l₂ = Re c₂ = 4b (not divided by ω,
    # as MatCont and BifurcationKit print it; ω = 2 here tells the two readings apart)
    g = generalised_hopf(bautin_cartesian(omega=2), {"b": 0.75}, "a", (-0.5, 0.3), (-0.2, 0.2))
    assert g.l2 == pytest.approx(4 * 0.75, rel=1e-10)
    assert g.hopf.l2 == g.l2


def test_l2_request_without_or_with_the_quintic_route():
    h = hopf_normal_form(bautin_cartesian(), {"a": 0.0, "b": 1.0}, (-0.3, 0.2), l2=True)
    assert h.l2 == pytest.approx(4.0, rel=1e-10)
