"""Fifth order: the quintic amplitude coefficient Λ₅ and the second Lyapunov coefficient l₂.

Two independent routes — the Fredholm condition at O(ε⁵) (landau.derivation.fredholm.quintic_coefficient, closed
forms in the law's derivatives for the spring–block) and Kuznetsov's normal form with multilinear
forms up to fifth order (landau.derivation.lyapunov.lyapunov_coefficients, eigenvectors from mpmath.eig,
⟨q, q⟩ = 1) — must agree on every built-in law at its codimension-two points, and both must give the
closed forms of systems whose normal form is known exactly.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from landau import SpringBlock
from landau.analyses.bautin import cycle_amplitudes, fold_of_cycles, quintic_normal_form
from landau.analyses.transition import codim2_points
from landau.derivation.lyapunov import lyapunov_coefficients
from landau.derivation.multiscale import Derivation, derive
from landau.laws import get_law
from landau.systems.system import DynamicalSystem

R = sp.Rational
mu, a_, b_, om_ = sp.symbols("mu a b omega", real=True)
#: the normal form ż = (μ + iω)z + a z|z|² + b z|z|⁴ used below
NF = {"a": -0.3, "b": 0.7, "omega": 2.0}
#: both routes run at ≥ 40 digits: they agree to round-off of the compiled/mp evaluation; 1e-8 is the brief's bound
REL = 1e-8


def _polar(x, y):
    z = x + sp.I * y
    r2 = x ** 2 + y ** 2
    zd = sp.expand((mu + sp.I * om_) * z + a_ * z * r2 + b_ * z * r2 ** 2)
    return sp.re(zd), sp.im(zd)


def polar_normal_form() -> DynamicalSystem:
    """ż = (μ + iω)z + a z|z|² + b z|z|⁴ in Cartesian coordinates z = x + iy."""
    x, y = sp.symbols("x y", real=True)
    return DynamicalSystem("polar-normal-form", (x, y), _polar(x, y), (sp.Integer(1),) * 2, mu, (sp.Integer(0),) * 2)


def linear_image(T, E) -> DynamicalSystem:
    """y = T x of the normal form, written as E·ẏ = E·T g(T⁻¹y) (non-orthogonal T, non-unit mass E)."""
    y1, y2 = sp.symbols("y1 y2", real=True)
    x = sp.Matrix(T).inv() * sp.Matrix([y1, y2])
    f = sp.Matrix(T) * sp.Matrix(_polar(x[0], x[1]))
    return DynamicalSystem("linear-image", (y1, y2), tuple(sp.expand(E[i] * f[i]) for i in range(2)),
                           tuple(E), mu, (sp.Integer(0),) * 2)


def warped_3d() -> DynamicalSystem:
    """The normal form with a stable direction ẇ = −2w + xy, seen through the nonlinear change of
    variables (x, y, w) = Ψ₁(Ψ₂(u, v, s)) (unit linear part, so q and the normal form are unchanged):
    Ψ₂ = (u, v + u²/2, s + 3uv/10), Ψ₁ = (a₁ + 3a₂²/10 + a₃²/5, a₂ + a₃²/10, a₃).  The right-hand
    side is truncated at degree 5 (the 5-jet decides Λ₅ and l₂)."""
    u, v, s = sp.symbols("u v s", real=True)
    A1, A2, A3 = sp.symbols("A1 A2 A3")
    Y = sp.Matrix([u, v + u ** 2 / 2, s + R(3, 10) * u * v])
    X = sp.Matrix([A1 + R(3, 10) * A2 ** 2 + R(1, 5) * A3 ** 2, A2 + R(1, 10) * A3 ** 2, A3])
    sub = dict(zip((A1, A2, A3), Y, strict=True))
    x, y, w = (e.xreplace(sub) for e in X)
    fx, fy = _polar(x, y)
    D1 = X.jacobian([A1, A2, A3]).xreplace(sub)
    D2 = Y.jacobian([u, v, s])
    rhs = D2.LUsolve(D1.upper_triangular_solve(sp.Matrix([fx, fy, -2 * w + x * y])))
    trunc = []
    for e in rhs:
        P = sp.Poly(sp.expand(e), u, v, s)
        trunc.append(sum((c * u ** m[0] * v ** m[1] * s ** m[2] for m, c in P.terms() if sum(m) <= 5), sp.Integer(0)))
    return DynamicalSystem("warped-3d", (u, v, s), tuple(trunc), (sp.Integer(1),) * 3, mu, (sp.Integer(0),) * 3)


def _both(system):
    from landau.derivation.jets import Jets

    jets = Jets(system)
    k = lyapunov_coefficients(system, NF, 0.0, dps=40, relocate=False, jets=jets)
    f = quintic_normal_form(system, NF, 0.0, NF["omega"], jets=jets)
    return k, f


def test_polar_normal_form_exact():
    """z = x + iy = 2A e^{iωt} (x normalised to 1): Λ = 8a, Λ₅ = 32b; Kuznetsov q = (1, −i)/√2:
    c₁ = 2a, c₂ = 4b, so l₁ = 2a/ω and l₂ = Re c₂ = 4b (MatCont/BifurcationKit convention)."""
    k, f = _both(polar_normal_form())
    for r in (k, f):
        assert r.Lambda == pytest.approx(8 * NF["a"], rel=1e-14)
        assert r.Lambda5 == pytest.approx(32 * NF["b"], rel=1e-14)
    assert k.l1 == pytest.approx(2 * NF["a"] / NF["omega"], rel=1e-14)
    assert k.l2 == pytest.approx(4 * NF["b"], rel=1e-14)
    assert k.l2_over_omega == pytest.approx(4 * NF["b"] / NF["omega"], rel=1e-14)
    assert f.dlambda_dp == pytest.approx(1.0, rel=1e-14)


def test_polar_normal_form_fold_of_cycles_exact():
    """Cycles: μ + a r² + b r⁴ = 0 (|z| = r): the fold is at μ = a²/(4b) exactly (the 5-jet is the
    whole field, so the truncated amplitude equation is exact), with |z|² = −a/(2b), i.e. max|x| = |z|."""
    _, f = _both(polar_normal_form())
    fold = fold_of_cycles(f.Lambda, f.Lambda5, f.dlambda_dp.real, f.p_c)
    assert fold.p_fold == pytest.approx(NF["a"] ** 2 / (4 * NF["b"]), rel=1e-10)
    assert fold.amplitude == pytest.approx(math.sqrt(-NF["a"] / (2 * NF["b"])), rel=1e-10)
    # the two cycles at μ between 0 and the fold: |z|² roots of b r⁴ + a r² + μ = 0
    m = 0.5 * fold.p_fold
    disc = math.sqrt(NF["a"] ** 2 - 4 * NF["b"] * m)
    exact = sorted(math.sqrt((-NF["a"] + s * disc) / (2 * NF["b"])) for s in (-1, 1))
    assert cycle_amplitudes(f.Lambda, f.Lambda5, f.dlambda_dp.real, f.p_c, m) == pytest.approx(exact, rel=1e-12)


def test_linear_image_with_mass_matrix():
    """y = T x, E = diag(2, 1/2): with y₁ normalised, A = (T q_x)₁ A_x, so Λ₅ = 32b/|T₁₁ − iT₁₂|⁴;
    Kuznetsov's unit q gives l₂ = 4b/|T q̂|⁴ with q̂ = (1, −i)/√2."""
    T = [[1, R(3, 10)], [R(1, 5), R(3, 2)]]
    k, f = _both(linear_image(T, (sp.Integer(2), R(1, 2))))
    Tf = np.array(T, dtype=float)
    qh = np.array([1, -1j]) / math.sqrt(2)
    assert f.Lambda5 == pytest.approx(32 * NF["b"] / abs(Tf[0, 0] - 1j * Tf[0, 1]) ** 4, rel=1e-12)
    assert k.Lambda5 == pytest.approx(f.Lambda5, rel=REL)
    assert k.l2 == pytest.approx(4 * NF["b"] / np.linalg.norm(Tf @ qh) ** 4, rel=1e-12)


@pytest.mark.slow
def test_warped_3d_invariance():
    """A near-identity nonlinear change of variables with a coupled stable direction leaves Λ, Λ₅ and
    l₂ unchanged (8a, 32b, 4b): exercises every multilinear form up to fifth order (~45 s: the
    symbolic fifth derivatives of the dense 3-state field)."""
    k, f = _both(warped_3d())
    for r in (k, f):
        assert r.Lambda == pytest.approx(8 * NF["a"], rel=1e-12)
        assert r.Lambda5 == pytest.approx(32 * NF["b"], rel=1e-12)
    assert k.l2 == pytest.approx(4 * NF["b"], rel=1e-12)


# the two-state-like laws (nanoscale, micron-scale: two codimension-two points each; spinodal:
# a large Kuznetsov jet) take 10–30 s each: opt-in
_LAWS = [("dieterich", {}), ("modified-dieterich", {"c": 3e-4}),
         pytest.param("nanoscale", {}, marks=pytest.mark.slow),
         pytest.param("micron-scale", {}, marks=pytest.mark.slow),
         pytest.param("spinodal", {"c": 3e-4}, marks=pytest.mark.slow)]


@pytest.fixture(scope="module")
def derivations():
    return {}


@pytest.mark.parametrize("name,params", _LAWS)
def test_spring_block_quintic_both_routes_at_codim2(derivations, name, params):
    """Every built-in law with a codimension-two point: Λ₅ from the compiled Fredholm formula (float64),
    the same formula at 50 digits, and Kuznetsov's route (40 digits, independent eigenvectors) agree
    to 1e-8; Λ there is ~0 in both routes (|Λ|·r² ≪ |Λ₅|·r⁴ at any r ≳ 1e-5 m)."""
    d = derivations.setdefault(name, derive(SpringBlock(get_law(name)), ["Lambda"]))
    p = d.block.resolve(params)
    pts = codim2_points(d, 1e-9, 1e-1, p)
    assert pts, name
    for pt in pts:
        mp = d.evaluate_mp(pt.V, p, ["Lambda", "Lambda5"])
        f64 = d.evaluate(np.array([pt.V]), p, ["Lambda5"])["Lambda5"][0]
        k = lyapunov_coefficients(d.block.system, {**p, "V": pt.V}, float(mp["kc"]),
                                  omega_c=float(mp["omega_c"]), jets=d.jets)
        ctx = (f"{name} V*={pt.V:.8g}: Fredholm {float(mp['Lambda5']):.15g}, float64 {f64:.15g}, "
               f"Kuznetsov {k.Lambda5:.15g}")
        assert k.Lambda5 == pytest.approx(float(mp["Lambda5"]), rel=REL), ctx
        assert f64 == pytest.approx(float(mp["Lambda5"]), rel=REL), ctx
        assert k.Lambda == pytest.approx(float(mp["Lambda"]), rel=1e-6, abs=1e-12 * abs(k.Lambda5) * 1e-6)
        # l₂ = Re c₂ with Kuznetsov's unit q: Λ₅ |q_X|⁴ / 2
        assert k.l2 == pytest.approx(k.Lambda5 * k.q_norm ** 4 / 2, rel=1e-12)


@pytest.mark.usefixtures("cache_off")
def test_quintic_is_lazy():
    """A derivation asked only for Λ builds derivatives up to third order; Λ₅ adds the fourth and fifth."""
    d = Derivation(SpringBlock(get_law("dieterich")))
    d.evaluate(np.array([1e-4]), {}, ["Lambda"])
    assert max(d.jets.built) == 3
    d.coefficient("Lambda5")
    assert max(d.jets.built) == 5


def test_cli_codim2_prints_l2_and_Lambda5(capsys):
    """`landau derive dieterich --codim2` reports Λ₅ and l₂ at V* (the same numbers as the Kuznetsov route:
    l₂ = Λ₅|q_X|⁴/2 with |q_X| from an independent eigen-solve) and the fold-of-cycles expansion, whose
    coefficient is −Λ'(V*)²/(8Λ₅Γ̄) by definition — checked here against the fold predicted at a nearby V
    from the coefficients there (they differ at O(V − V*))."""
    import json

    from landau.analyses.bautin import spring_block_fold
    from landau.cli import main

    assert main(["derive", "dieterich", "--codim2", "1e-7:1e-2", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    (pt,) = doc["codim2"]
    d = Derivation(SpringBlock(get_law("dieterich")))
    mp = d.evaluate_mp(pt["V"], d.block.resolve({}), ["Lambda5"])
    assert pt["Lambda5"] == pytest.approx(float(mp["Lambda5"]), rel=1e-12)
    k = lyapunov_coefficients(d.block.system, {**d.block.resolve({}), "V": pt["V"]}, pt["kc"],
                              omega_c=pt["omega_c"], jets=d.jets)
    assert pt["l2"] == pytest.approx(k.l2, rel=1e-9)
    fc = pt["fold_of_cycles"]
    assert fc["side"] == "V < V*"          # Λ > 0 below V* (subcritical) and Λ₅ < 0
    V = pt["V"] * (1 - 1e-3)
    fold = spring_block_fold(d, V)
    dv2 = (V - pt["V"]) ** 2
    assert fold.offset == pytest.approx(fc["k_minus_kc_per_dV2"] * dv2, rel=5e-3)
    assert fold.amplitude == pytest.approx(fc["amplitude_per_sqrt_dV"] * math.sqrt(abs(V - pt["V"])), rel=5e-3)


def test_quintic_extreme_regimes_against_50_digits():
    """Law (39), c = 3e-4: the compiled float64 Λ₅ (with its round-off screens) against the same formula at
    50 digits just below the minimum of μ_ss (V_m(1 − 1e-6), where k_c → 0) and in the inertia-free limit
    (M = 1e-6, 1e-8 kg); the quasi-static DAE (M = 0) is the M → 0 limit of the ODE's value."""
    from landau.analyses.transition import extrema

    d = Derivation(SpringBlock(get_law("modified-dieterich")))
    p = {"c": 3e-4}
    (vm,) = [e.V for e in extrema(d, p, 1e-9, 1e-1) if e.kind == "minimum"]
    for V, pp in [(vm * (1 - 1e-6), p), (1e-4, {**p, "M": 1e-6}), (1e-3, {**p, "M": 1e-8})]:
        f = d.evaluate(np.array([V]), pp, ["Lambda5"])["Lambda5"][0]
        ref = float(d.evaluate_mp(V, pp, ["Lambda5"], dps=50)["Lambda5"])
        assert f == pytest.approx(ref, rel=1e-10), (V, pp)
    at0 = d.evaluate(np.array([1e-3]), {**p, "M": 0.0}, ["Lambda5"])["Lambda5"][0]
    at_small = d.evaluate(np.array([1e-3]), {**p, "M": 1e-12}, ["Lambda5"])["Lambda5"][0]
    assert at0 == pytest.approx(at_small, rel=1e-6)


def test_fold_of_cycles_cases():
    """No fold where Λ and Λ₅ have the same sign; a named error for a zero Λ₅."""
    from landau.errors import InputError

    assert fold_of_cycles(-1.0, -2.0, 1.0, 0.0) is None
    with pytest.raises(InputError):
        fold_of_cycles(1.0, 0.0, 1.0, 0.0)
    assert cycle_amplitudes(-1.0, -2.0, 1.0, 0.0, -1.0) == ()
