"""The error-bounded evaluation of :mod:`landau.codegen.bounded` and the double-double arithmetic
of :mod:`landau.codegen.ddarith`, against 50-digit mpmath.

Tolerances: a double-double operation is within its unit (proven 3u² for the sum and 7u² for
the product, Joldes, Muller & Popescu 2017; the units of ``ddarith`` allow for more); a value of
the interpreters is within the bound it returns (first order in float64: the tests take the
bound times 1.01, the second-order terms being ~1e-10 of it here)."""

import mpmath
import numpy as np
import pytest
import sympy as sp

from landau.codegen import ddarith as D
from landau.codegen.bounded import BoundedKernels, linearise

mpmath.mp.dps = 50


def _mp(h, lo):
    return mpmath.mpf(h) + mpmath.mpf(lo)


def _dd_pairs(rng, n, lo_exp, hi_exp):
    x = np.exp(rng.uniform(lo_exp, hi_exp, n)) * np.where(rng.random(n) < 0.5, -1, 1)
    return [D.fast_two_sum(float(a), float(a) * 1e-17 * float(rng.uniform(-1, 1))) for a in x]


def test_double_double_operations_within_their_units():
    rng = np.random.default_rng(7)
    xs, ys = _dd_pairs(rng, 300, -20, 20), _dd_pairs(rng, 300, -5, 5)
    worst = {k: 0.0 for k in ("add", "mul", "div", "sqrt", "exp", "log", "pow", "asinh")}
    for (xh, xl), (yh, yl) in zip(xs, ys, strict=True):
        X, Y = _mp(xh, xl), _mp(yh, yl)
        ax = (abs(xh), xl if xh > 0 else -xl)
        cases = {"add": (D.dd_add(xh, xl, yh, yl), X + Y), "mul": (D.dd_mul(xh, xl, yh, yl), X * Y),
                 "div": (D.dd_div(xh, xl, yh, yl), X / Y), "sqrt": (D.dd_sqrt(*ax), mpmath.sqrt(abs(X))),
                 "exp": (D.dd_exp(yh * 4, yl * 4), mpmath.exp(4 * Y)), "log": (D.dd_log(*ax), mpmath.log(abs(X))),
                 "pow": (D.dd_pow(*ax, yh / 4, yl / 4), abs(X) ** (Y / 4)),
                 "asinh": (D.dd_asinh(xh * 1024, xl * 1024), mpmath.asinh(1024 * X))}
        for k, (got, want) in cases.items():
            worst[k] = max(worst[k], float(abs(_mp(*got) - want) / abs(want)))
    assert worst["add"] <= D.UNIT and worst["mul"] <= D.UNIT, worst
    assert worst["div"] <= D.UNIT_DIV and worst["sqrt"] <= D.UNIT_DIV, worst
    for k in ("exp", "log", "pow", "asinh"):
        assert worst[k] <= D.UNIT_FUNC, (k, worst[k])


def _kernels(expr, x):
    return BoundedKernels(linearise([expr], [x], [True], {}))


def _check(kern, f_mp, xs, mode):
    out, rb = getattr(kern, mode)(np.array([xs]), np.zeros(1))
    errs = []
    for x0, got, bound in zip(xs, out[0], rb[0], strict=True):
        want = f_mp(mpmath.mpf(float(x0)))
        err = float(abs(mpmath.mpf(float(got)) - want) / abs(want))
        # the value returned is rounded to float64 once: 2^-53 on top of the bound
        assert err <= 1.01 * bound + 2.0 ** -53, (mode, x0, err, bound)
        errs.append(err)
    return np.array(errs), rb[0]


def test_cancellation_the_float64_bound_holds_and_double_double_removes_it():
    """(e^x − 1 − x)/x² near x = 0 (cancellation of 1/x): float64 loses up to ~1e-6 at x = 1e-5,
    its bound says so; the double-double value, rounded to float64, is within 2⁻⁵³ (1.1e-16) of
    the exact value and certified by its own bound far below 1e-10."""
    x = sp.Symbol("x")
    expr = (sp.exp(x) - 1 - x) / x**2
    xs = np.concatenate([np.logspace(-6, -1, 25), -np.logspace(-6, -1, 25)])
    kern = _kernels(expr, x)

    def f(t):
        return (mpmath.exp(t) - 1 - t) / t**2

    e64, b64 = _check(kern, f, xs, "f64")
    assert b64.max() > 1e-6 and e64.max() > 1e-9       # a genuinely ill-conditioned formula, seen by the bound
    edd, bdd = _check(kern, f, xs, "dd")
    assert edd.max() <= 2.0 ** -53 * (1 + 1e-10) and bdd.max() <= 1e-15, (edd.max(), bdd.max())


def test_product_bound_is_the_closed_form_with_zero_factors():
    """The float64 bound of z = a·b·c·d over four varying inputs with given errors e: first order,
    Σ_q |Π_{r≠q} x_r|·e_q + 3u|z| (three roundings of the product), the closed form of Higham
    (2002), Sec. 3.3.  The interpreter's adjoints of an n-factor product are products of the other
    factors (no division), so the closed form holds to rounding also where factors are exactly 0:
    one zero factor leaves only its own term, two leave none."""
    a, b, c, dd = sp.symbols("a b c d")
    kern = BoundedKernels(linearise([a * b * c * dd], [a, b, c, dd], [True] * 4, {}))
    rng = np.random.default_rng(3)
    X = rng.uniform(-3.0, 3.0, (4, 400))
    X[1, :50] = 0.0                     # one zero factor
    X[2, 25:75] = 0.0                   # and two zero factors where both sets overlap
    EX = np.abs(X) * 1e-9 + 1e-12 * rng.random((4, 400))
    out, rb, oe = kern.f64_parts(X, np.zeros(4), EX)
    z = X.prod(axis=0)
    others = np.stack([np.prod(np.delete(X, q, axis=0), axis=0) for q in range(4)])
    want = (np.abs(others) * EX).sum(axis=0) + 3 * 2.0 ** -53 * np.abs(z)
    assert np.array_equal(out[0], X[0] * X[1] * X[2] * X[3])
    np.testing.assert_allclose(oe[0], want, rtol=1e-12, atol=0)
    assert np.all(oe[0, 25:50] == 0.0)                  # two zero factors: nothing to propagate
    assert np.all(oe[0, :25] > 0.0) and np.all(np.isfinite(rb[0, 75:]))


def test_log_power_and_asinh_chain_within_the_bounds():
    """A chain of the operations the friction laws use (log, x^y with a symbolic exponent,
    asinh, rational powers) near a cancellation between two logarithms."""
    x = sp.Symbol("x", positive=True)
    expr = ((sp.log(1 + x) - sp.log(1 + 2 * x) + x) * sp.asinh(x * 3e4) ** sp.Rational(3, 2)
            / (1 + x) ** (x + sp.Rational(1, 3)))
    xs = np.logspace(-7, 1, 40)
    kern = _kernels(expr, x)

    def f(t):
        return (mpmath.log(1 + t) - mpmath.log(1 + 2 * t) + t) * mpmath.asinh(t * mpmath.mpf(3e4)) ** 1.5 \
            / (1 + t) ** (t + mpmath.mpf(1) / 3)

    _check(kern, f, xs, "f64")
    edd, bdd = _check(kern, f, xs, "dd")
    # at x = 1e-7 the logarithms cancel over 7 orders: the bound, with 2⁻⁹⁶ allowed per logarithm,
    # is then ~1e-15, still far below the 1e-10 it must certify
    assert edd.max() <= 2.0 ** -53 * (1 + 1e-10) and bdd.max() <= 1e-13, (edd.max(), bdd.max())


@pytest.mark.parametrize("name", ["spinodal", "nanoscale", "dieterich"])
def test_law_bounds_hold_for_lambda(name):
    """Λ(V) of a built-in law (Putelat et al. 2010, eqs 26–39, 48): on 10 log-spaced velocities
    of its velocity-weakening range the float64 and double-double values are within their bounds
    of 40-digit mpmath (``Derivation.evaluate_mp``), and the double-double bound is below 1e-15."""
    from vw_ranges import vw_range

    import landau.derivation.precision as pr
    from landau.derivation.multiscale import derive
    from landau.laws import get_law
    from landau.systems.system import SpringBlock

    d = derive(SpringBlock(get_law(name)), ["Lambda"])
    lo, hi, ends = vw_range(name)
    lo, hi = (lo * (1 + 1e-3) if lo in ends else lo), (hi * (1 - 1e-3) if hi in ends else hi)
    Vs = np.logspace(np.log10(lo), np.log10(hi), 10)
    vals = [np.broadcast_to(np.asarray(v, dtype=float), Vs.shape) for v in d.block.argvals(Vs, d.block.resolve())]
    kern = pr.bounded_kernels(d, ["Lambda"], pr._varying(vals))
    X = np.stack([v for v, var in zip(vals, pr._varying(vals), strict=True) if var])
    Q = np.array([float(np.ravel(v)[0]) for v in vals])
    want = [d.evaluate_mp(float(V0), {}, ["Lambda"], dps=40) for V0 in Vs]
    for mode in ("f64", "dd"):
        out, _ = getattr(kern, mode)(X, Q)
        # the bound of Λ alone: evaluate the program for Λ's slot only
        for j, (V0, w) in enumerate(zip(Vs, want, strict=True)):
            for row, key in ((0, "kc"), (2, "Lambda")):
                err = float(abs(mpmath.mpf(float(out[row, j])) - w[key]) / abs(w[key]))
                _, rb = getattr(kern, mode)(X[:, j:j + 1], Q)
                assert err <= 1.01 * rb[0, 0] + 2.0 ** -53, (mode, V0, key, err, rb[0, 0])
                if mode == "dd":
                    assert rb[0, 0] <= 1e-15, (V0, rb[0, 0])


def _lambda_worst(name: str, n: int) -> tuple[float, int]:
    from vw_ranges import vw_range

    from landau.derivation.multiscale import derive
    from landau.laws import get_law
    from landau.systems.system import SpringBlock

    d = derive(SpringBlock(get_law(name)), ["Lambda"])
    lo, hi, ends = vw_range(name)
    lo, hi = (lo * (1 + 1e-3) if lo in ends else lo), (hi * (1 - 1e-3) if hi in ends else hi)
    Vs = np.logspace(np.log10(lo), np.log10(hi), n)
    got = d.evaluate(Vs, {}, ["Lambda"])["Lambda"]
    want = [d.evaluate_mp(float(V0), {}, ["Lambda"], dps=40)["Lambda"] for V0 in Vs]
    errs = [float(abs(g - w) / abs(w)) for g, w in zip(got, want, strict=True)]
    return max(errs), sum(e > 1e-10 for e in errs)


LAWS6 = ("dieterich", "ruina", "spinodal", "modified-dieterich", "nanoscale", "micron-scale")


@pytest.mark.parametrize("name", LAWS6)
def test_every_law_lambda_within_1e_10_of_40_digits_small_sample(name, monkeypatch):
    """The default route of a large batch (bounded float64, double-double, exact rational form)
    on 8 log-spaced velocities of each one-state law's velocity-weakening range: within 1e-10 of
    40 digits."""
    import landau.derivation.precision as pr

    monkeypatch.setattr(pr, "BOUNDED_MIN", 0)
    worst, bad = _lambda_worst(name, 8)
    assert bad == 0, worst


@pytest.mark.slow
@pytest.mark.parametrize("name", [*LAWS6, "two-state-dieterich"])
def test_every_law_lambda_within_1e_10_of_40_digits_1000_points(name):
    """The same on 1000 points (the benchmark's sample; ~5–20 CPU-s a law), and for the two-state law
    (a Hopf line without closed form: ``landau.derivation.precision_numeric.bounded_numeric_route``)."""
    worst, bad = _lambda_worst(name, 1000)
    assert bad == 0, worst


def test_given_errors_as_a_read_only_view_build_no_second_interpreter():
    """Errors given as arrays of X's shape (which ``np.broadcast_to`` hands on as read-only
    views: another array type for numba), as a read-only broadcast and as None run the one
    compiled interpreter of each precision: a second build of both cost ~8 CPU-s on a fresh
    machine (the numeric Hopf route gives its errors, the closed-form route none).  The values do
    not depend on how the zeros were given."""
    from landau.codegen import bounded

    a, b = sp.symbols("a b")
    kern = BoundedKernels(linearise([a * b + a], [a, b], [True, True], {}))
    X = np.array([[1.5, -2.0, 3.0], [0.25, 4.0, -1.0]])
    Q = np.zeros(2)
    runs = []
    for given in (None, np.zeros_like(X), np.broadcast_to(0.0, X.shape)):
        out, _, oe = kern.f64_parts(X, Q, given)
        hi = kern.dd_parts(X, Q, given, given)[2]
        runs.append((out, oe, hi))
    for out, oe, hi in runs[1:]:
        assert np.array_equal(out, runs[0][0]) and np.array_equal(oe, runs[0][1]) and np.array_equal(hi, runs[0][2])
    np.testing.assert_array_equal(runs[0][0][0], X[0] * X[1] + X[0])
    assert len(bounded.run_f64.signatures) == 1 and len(bounded.run_dd.signatures) == 1
