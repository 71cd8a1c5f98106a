"""The multiple-scales engine against the paper's closed forms (Putelat et al. 2010, eqs 32, 33, 44, 45)
and its laziness (only the derivative orders a quantity needs are built)."""

import random

import mpmath
import numpy as np
import pytest
import sympy as sp

from landau.derivation.multiscale import Derivation, derive
from landau.errors import NoHopfError
from landau.laws import TABLE1, get_law
from landau.systems.system import M, SpringBlock, V, sigma

a, b, L, V_s = (TABLE1[n].symbol for n in ("a", "b", "L", "V_s"))
c = sp.Symbol("c", positive=True)


def agree_at_random_points(d, name, reference, symbols, n=20, dps=50, seed=1, rel=1e-35):
    """The engine's compiled coefficient ``name`` (evaluated with mpmath at ``dps`` digits) against the
    paper's closed form at ``n`` random points (parameters perturbed ±50 % around Table 1)."""
    rng = random.Random(seed)
    base = {"a": 0.0349, "b": 0.0489, "L": 0.9e-6, "V_s": 1e-6, "sigma": 11.772, "M": 1.2, "c": 3e-4}
    ref = sp.lambdify(list(symbols) + [V], reference, "mpmath")
    checked = draws = 0
    while checked < n:
        draws += 1
        assert draws < 10 * n, "too few draws with a Hopf point"
        pt = {str(s): base[str(s)] * rng.uniform(0.5, 1.5) for s in symbols}
        V0 = 10 ** rng.uniform(-7, -3)
        with mpmath.workdps(dps):
            try:
                got = d.evaluate_mp(V0, pt, [name], dps=dps)[name]
            except NoHopfError:      # no Hopf point at this draw (velocity strengthening)
                continue
            want = ref(*[mpmath.mpf(pt[str(s)]) for s in symbols], mpmath.mpf(V0))
            assert abs(got - want) <= rel * abs(want), (pt, V0, got, want)
        checked += 1


def test_gamma_dieterich_ruina_eq32():
    for name in ("dieterich", "ruina"):
        d = Derivation(SpringBlock(get_law(name)))
        # eq. (32): Γ_DR = −k₂ (σa/V)/((σa/V)² + M[M(b/a)(V/L)² + 2σa/L]); Γ = −2Γ̄k₂
        eq32 = (sigma * a / V) / ((sigma * a / V) ** 2 + M * (M * (b / a) * (V / L) ** 2 + 2 * sigma * a / L)) / 2
        agree_at_random_points(d, "Gamma_bar", eq32, [a, b, L, sigma, M])


def test_landau_dieterich_eq33():
    d = Derivation(SpringBlock(get_law("dieterich")))
    eq33 = (sigma * M * (b - a) ** 2 * V ** 3 * (-M ** 2 * (4 * b + 3 * a) * V ** 4
                                               - 6 * L * sigma * a ** 2 * M * V ** 2
                                               + L ** 2 * sigma ** 2 * a ** 3)
            / (L ** 2 * (M ** 2 * b * V ** 4 + 2 * L * sigma * a ** 2 * M * V ** 2 + L ** 2 * sigma ** 2 * a ** 3)
               * (M ** 2 * (4 * b - 3 * a) * V ** 4 + 2 * L * sigma * a ** 2 * M * V ** 2
                  + L ** 2 * sigma ** 2 * a ** 3)))
    agree_at_random_points(d, "Lambda", eq33, [a, b, L, sigma, M])


def _P(n):
    P4 = (b * V_s * M ** 2 * V ** 4 + 2 * a ** 2 * c * sigma * L * M * V ** 3
          + 2 * a ** 2 * sigma * V_s * L * M * V ** 2
          + a ** 3 * c * sigma ** 2 * L ** 2 * V + a ** 3 * sigma ** 2 * V_s * L ** 2)
    P5 = (3 * a * c * L * M ** 2 * V ** 5 + (3 * a - 4 * b) * V_s * L * M ** 2 * V ** 4
          - 2 * a ** 2 * c * sigma * L ** 2 * M * V ** 3
          - 2 * a ** 2 * sigma * V_s * L ** 2 * M * V ** 2 - a ** 3 * c * sigma ** 2 * L ** 3 * V
          - a ** 3 * sigma ** 2 * V_s * L ** 3)
    P7 = ((6 * a * b + 6 * a ** 2) * c ** 2 * L ** 2 * M ** 3 * V ** 7
          + (-4 * b ** 2 + 3 * a * b + 9 * a ** 2) * c * V_s * L ** 2 * M ** 3 * V ** 6
          + ((-4 * b ** 2 + a * b + 3 * a ** 2) * V_s ** 2 * L ** 2 * M ** 3
             + (3 * a ** 2 * b + 7 * a ** 3) * c ** 2 * sigma * L ** 3 * M ** 2) * V ** 5
          + (13 * a ** 3 - 6 * a ** 2 * b) * c * sigma * V_s * L ** 3 * M ** 2 * V ** 4
          + ((6 * a ** 3 - 6 * a ** 2 * b) * sigma * V_s ** 2 * L ** 3 * M ** 2
             + (a ** 3 * b - 4 * a ** 4) * c ** 2 * sigma ** 2 * L ** 4 * M) * V ** 3
          + (3 * a ** 3 * b - 5 * a ** 4) * c * sigma ** 2 * V_s * L ** 4 * M * V ** 2
          + ((a ** 3 * b - a ** 4) * sigma ** 2 * V_s ** 2 * L ** 4 * M - a ** 5 * c ** 2 * sigma ** 3 * L ** 5) * V
          - a ** 5 * c * sigma ** 3 * V_s * L ** 5)
    return {4: P4, 5: P5, 7: P7}[n]


def test_modified_dieterich_eqs44_45():
    d = Derivation(SpringBlock(get_law("modified-dieterich")))
    syms = [a, b, L, V_s, sigma, M, c]
    # eq. (44): Γ = −k₂ σa²L²V(cV + V_*)/P₄
    eq44 = sigma * a ** 2 * L ** 2 * V * (c * V + V_s) / _P(4) / 2
    agree_at_random_points(d, "Gamma_bar", eq44, syms)
    # eq. (45) with the denominator L³(cV + V_*)²P₄P₅ (the print has L; zeros and sign unaffected)
    Vm = (b / a - 1) * V_s / c
    eq45 = a * c * sigma * V_s * V ** 2 * (V - Vm) * _P(7) / (L ** 3 * (c * V + V_s) ** 2 * _P(4) * _P(5))
    agree_at_random_points(d, "Lambda", eq45, syms)


def test_dieterich_quasi_static_lambda_is_exactly_zero():
    # Sec. 3.2: without inertia Λ_D = 0 (Baumberger et al. 1995; Ranjith & Rice 1999).
    d = Derivation(SpringBlock(get_law("dieterich")))
    lam = d.coefficient("Lambda").expr
    # exact zero: at 100 digits Λ(M = 0) vanishes to round-off at random rational points, while Λ(M = 1.2) does not
    # (the tree form evaluated by mpmath with its common subexpressions shared: 1 ms a point, not 0.2 s)
    args = (a, b, L, sigma, V, M)
    f = sp.lambdify(args, lam, "mpmath", cse=True)
    rng = random.Random(7)
    with mpmath.workdps(100):
        for _ in range(5):
            pt = {a: sp.Rational(349, 10000), b: sp.Rational(489, 10000), L: sp.Rational(9, 10 ** 7),
                  sigma: sp.Rational(11772, 1000), V: sp.Rational(rng.randint(1, 10 ** 4), 10 ** 7)}
            x = [mpmath.mpf(pt[sym].p) / pt[sym].q for sym in args[:-1]]
            assert abs(f(*x, mpmath.mpf(0))) < mpmath.mpf("1e-80") * abs(f(*x, mpmath.mpf(6) / 5))
    # the compiled path returns 0 and flags the point degenerate instead of returning round-off
    r = d.evaluate([1e-5, 1e-4, 1e-3], {"M": 0.0}, ["Lambda", "C"])
    assert list(r["Lambda"]) == [0.0, 0.0, 0.0] and r["degenerate"].all()


@pytest.mark.usefixtures("cache_off")
def test_only_needed_derivative_orders_are_built():
    d = derive(SpringBlock(get_law("spinodal")), ["kc", "omega_c"])
    d.evaluate([1e-5, 1e-4], None, ["kc", "omega_c"])
    assert d.jets.built == [1]
    d.evaluate([1e-5], None, ["Gamma_bar"])
    assert d.jets.built == [1]                       # ∂/∂k of the Jacobian only: no second derivatives
    d.evaluate([1e-5], None, ["Lambda"])
    assert sorted(d.jets.built) == [1, 2, 3]
    # a sweep does not re-derive: formulas and compiled code are cached
    f = d._compiled_formula("Lambda")
    d.evaluate(np.logspace(-6, -4, 50), None, ["Lambda"])
    assert d._compiled_formula("Lambda") is f and sorted(d.jets.built) == [1, 2, 3]


def test_vectorised_over_a_parameter():
    d = derive(SpringBlock(get_law("modified-dieterich")), ["Lambda"])
    cs = np.array([1e-4, 3e-4, 1e-3])
    vec = d.evaluate(1e-4, {"c": cs}, ["Lambda"])["Lambda"]
    one = [d.evaluate([1e-4], {"c": cv}, ["Lambda"])["Lambda"][0] for cv in cs]
    assert vec == pytest.approx(one, rel=1e-13)


def test_general_route_reproduces_the_spring_block():
    """landau.derivation.general (numeric Hopf point + 50-digit Fredholm) against the closed-form route."""
    from landau.derivation.general import hopf_normal_form

    block = SpringBlock(get_law("spinodal"))
    d = derive(block)
    V0 = 1e-4
    r = d.evaluate([V0], None, ["kc", "omega_c", "Gamma_bar", "Omega_bar", "Lambda", "chi", "C"])
    h = hopf_normal_form(block.system, {**block.resolve(), "V": V0}, (0.9 * r["kc"][0], 1.1 * r["kc"][0]))
    assert h.p_c == pytest.approx(r["kc"][0], rel=1e-12)
    assert h.omega_c == pytest.approx(r["omega_c"][0], rel=1e-12)
    assert -h.dlambda_dp.real == pytest.approx(r["Gamma_bar"][0], rel=1e-10)
    assert h.dlambda_dp.imag == pytest.approx(r["Omega_bar"][0], rel=1e-10)
    assert h.Lambda == pytest.approx(r["Lambda"][0], rel=1e-10)
    assert h.chi == pytest.approx(r["chi"][0], rel=1e-10)
    assert h.C == pytest.approx(r["C"][0], rel=1e-10)


def test_exactly_cancelled_route_matches_50_digits_and_finds_the_zero():
    """landau.derivation.rational (field ℚ(V, ω)) against the general formula at 50 digits: Dieterich at
    Table 1, where float64 loses ~10 digits below 1e-6 m/s, and Λ ≡ 0 at M = 0 (Sec. 3.2)."""
    from landau.derivation.rational import rational_forms

    d = Derivation(SpringBlock(get_law("dieterich")))
    params = d.block.resolve()
    rc = rational_forms(d, ["Gamma_bar", "Lambda", "chi"], params)
    Vs = np.array([1e-8, 3e-7, 1e-5, 2e-4, 1e-2])
    om = d.evaluate(Vs, None, ["kc"])["omega_c"]
    for n in ("Gamma_bar", "Lambda", "chi"):
        got = rc[n](Vs, om)
        want = [float(d.evaluate_mp(float(V0), {}, [n])[n]) for V0 in Vs]
        assert got == pytest.approx(want, rel=1e-12)
    assert rational_forms(d, ["Lambda"], d.block.resolve({"M": 0.0}))["Lambda"].identically_zero
    assert rational_forms(Derivation(SpringBlock(get_law("spinodal"))), ["Lambda"],
                                 SpringBlock(get_law("spinodal")).resolve()) is None   # not rational in V


def test_blocked_evaluation_equals_pointwise_pieces():
    """Large batches run in cache-sized blocks (multiscale._BLOCK): the result must be the same
    numbers as small pieces taken by the same route (elementwise arithmetic, per-point screening:
    bitwise identical).  A batch below precision.BOUNDED_MIN points takes the numpy route instead of
    the float64-with-a-bound one: equal to the certified 1e-10, not bitwise."""
    from landau.derivation import multiscale, precision

    d = derive(SpringBlock(get_law("spinodal")), ["Lambda", "Gamma_bar"])
    Vs = np.logspace(-7.5, -3.4, 3 * multiscale._BLOCK + 17)
    names = ["kc", "omega_c", "Gamma_bar", "Lambda"]
    whole = d.evaluate(Vs, None, names)
    size = precision.BOUNDED_MIN
    cuts = list(range(0, Vs.size - size, size)) + [Vs.size]    # the short tail joins the last piece
    pieces = [d.evaluate(Vs[a:b], None, names) for a, b in zip(cuts[:-1], cuts[1:], strict=True)]
    for n in names:
        assert np.array_equal(whole[n], np.concatenate([p[n] for p in pieces]), equal_nan=True), n
    small = d.evaluate(Vs[-17:], None, names)
    for n in names:
        np.testing.assert_allclose(small[n], whole[n][-17:], rtol=1e-10, atol=0, err_msg=n)


def test_a_sign_scan_below_bounded_min_sign_takes_the_numpy_route_with_the_same_signs():
    """A sign scan (``sign_only``) of fewer than precision.BOUNDED_MIN_SIGN points stays on the
    numpy route, never building the bounded interpreters (~8 CPU-s on a fresh machine, which a
    cold ``landau figures putelat2010`` paid for its 37 scans of ~1000–1300 points); its signs are
    those of the certified values of the bounded route on the same points (Dieterich law, whose
    Λ changes sign between 1e-9 and 1e-1 m/s)."""
    from landau.derivation import precision

    d = derive(SpringBlock(get_law("dieterich")), ["Lambda"])
    Vs = np.logspace(-9, -1, 1300)
    assert precision.BOUNDED_MIN <= Vs.size < precision.BOUNDED_MIN_SIGN
    before = dict(precision.BOUNDED_STATS)
    signs = d.evaluate(Vs, None, ["Lambda"], sign_only=True)["Lambda"]
    assert precision.BOUNDED_STATS == before                    # not one point through the interpreters
    values = d.evaluate(Vs, None, ["Lambda"])["Lambda"]         # the bounded route (values)
    assert precision.BOUNDED_STATS["f64"] == before["f64"] + Vs.size
    assert (np.sign(values) > 0).any() and (np.sign(values) < 0).any()
    np.testing.assert_array_equal(np.sign(signs), np.sign(values))


def test_compiled_horner_equals_numpys_bit_for_bit():
    """From precision.BOUNDED_MIN points a Polynomial of the exactly cancelled forms is evaluated by
    the compiled Horner of landau.codegen.horner (one pass for p and Σ|cᵢ|sⁱ): its values and bounds
    are those of numpy.polyval bit for bit, over the whole float range (subnormal and huge V,
    coefficients beyond 1e300 scaled by 2^k, 2^e; a zero and a cancelling polynomial)."""
    from fractions import Fraction

    from landau.derivation import precision
    from landau.derivation.rational import Polynomial

    rng = np.random.default_rng(7)
    x = np.concatenate([10.0 ** rng.uniform(-320, 300, 2000), [5e-324, 1.0, 2.0, 1e308, np.inf]])
    polys = [Polynomial(tuple(Fraction(int(c)) * Fraction(10) ** (40 * i) for i, c in enumerate([3, -7, 0, 2, 5]))),
             Polynomial((Fraction(1, 3), Fraction(-2, 3), Fraction(1, 3))),       # (1 − V)²/3: cancels near V = 1
             Polynomial((Fraction(0),)), Polynomial((Fraction(-5, 7),))]
    small = precision.BOUNDED_MIN - 1
    for p in polys:
        whole = p.evaluate(x)
        parts = [p.evaluate(x[i:i + small]) for i in range(0, x.size, small)]
        for j in range(2):
            assert np.array_equal(whole[j], np.concatenate([q[j] for q in parts]), equal_nan=True)
        assert whole[2] == parts[0][2]
