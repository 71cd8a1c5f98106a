"""The Hopf line without closed form (several state variables) at full speed: the roots of every
point's Hopf polynomial at once (``landau.derivation.hopf_roots``), their error bounds in float64
and double-double (``landau.codegen.bounded_hopf``) and the bounded route of ``Derivation.evaluate``
built on them (``landau.derivation.precision_numeric.bounded_numeric_route``).

Independent references: ``numpy.roots`` point by point (the previous route), and 40-digit mpmath
(``HopfLine.numeric_point_mp``: the Hopf polynomial's roots by ``mpmath.polyroots``, and
``Derivation.evaluate_mp``: every coefficient in mpmath at that root)."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

import landau.derivation.precision as pr
import landau.derivation.precision_numeric as pn
from landau.codegen.bounded_hopf import hopf_dd, hopf_f64
from landau.derivation import hopf_roots
from landau.derivation.linear import _stiffest_hopf_root
from landau.derivation.multiscale import derive
from landau.laws import get_law
from landau.systems.system import SpringBlock


@pytest.fixture(scope="module")
def two_state():
    return derive(SpringBlock(get_law("two-state-dieterich")), ["Gamma_bar", "Lambda"])


def _sorted(r):
    r = r[np.isfinite(r)]
    return r[np.lexsort((r.imag, r.real))]


@pytest.mark.parametrize("degree", [1, 2, 3, 4])
def test_roots_of_every_row_equal_numpy_roots_row_by_row(degree):
    rng = np.random.default_rng(degree)
    C = rng.normal(size=(400, degree + 1)) * 10.0 ** rng.integers(-3, 4, size=(400, 1))
    C[::7, 0] = 0.0                       # rows of lower degree: leading zeros stripped
    C[::11, :2] = 0.0
    C[5, 1] = np.nan                      # a row with a non-finite coefficient has no root
    R = hopf_roots.roots(C)
    assert np.all(np.isnan(R[5]))
    for i in range(C.shape[0]):
        if i == 5:
            continue
        want = _sorted(np.roots(C[i]).astype(complex))
        got = _sorted(R[i])
        assert got.size == want.size, (i, got, want)
        # both are backward-stable; the roots of these well-separated random polynomials agree to
        # a few hundred ulps of the largest root
        scale = max(1.0, np.abs(want).max()) if want.size else 1.0
        assert np.allclose(got, want, rtol=1e-10, atol=1e-12 * scale), (i, got, want)


def test_stiffest_root_is_the_one_point_rule_on_every_row():
    rng = np.random.default_rng(7)
    C = rng.normal(size=(2000, 3))
    a = rng.normal(size=2000)

    def stiffness(W, rows):
        return a[rows] * (W - 0.3)

    kc, W = hopf_roots.stiffest(C, stiffness, 1e-9)
    found = 0
    for i in range(C.shape[0]):
        k1, W1 = _stiffest_hopf_root(np.roots(C[i]).astype(complex), lambda x, i=i: a[i] * (x - 0.3), 1e-9, np.nan)
        if np.isnan(k1):
            assert np.isnan(kc[i]) and np.isnan(W[i])
        else:
            found += 1
            assert kc[i] == pytest.approx(k1, rel=1e-12) and W[i] == pytest.approx(W1, rel=1e-12)
    assert 300 < found < 1900           # both outcomes exercised


def test_hopf_line_of_two_states_vectorised_equals_40_digits(two_state):
    Vs = np.logspace(-8, -1, 200)
    kc, om = two_state.hopf.evaluate(Vs)
    p = two_state.block.resolve({})
    worst = 0.0
    for V, k, o in zip(Vs, kc, om, strict=True):
        with mpmath.workdps(40):
            vals = [mpmath.mpf(float(np.ravel(x)[0])) for x in two_state.block.argvals(np.array([V]), p)]
            km, Wm = two_state.hopf.numeric_point_mp(vals)
        assert np.isfinite(k) == (km == km)
        if km == km:
            worst = max(worst, abs(k / float(km) - 1), abs(o * o / float(Wm) - 1))
    # a few ulps: the roots of a quadratic by the formula without cancellation, k_c by Horner
    assert worst <= 1e-14, worst


def _hopf_inputs(d, Vs):
    vals = [np.broadcast_to(np.asarray(x, dtype=float), Vs.shape) for x in d.block.argvals(Vs, d.block.resolve({}))]
    varying = pr._varying(vals)
    kern, sizes = pn.hopf_coefficient_kernels(d, varying)
    X = np.stack([np.ravel(x) for x, var in zip(vals, varying, strict=True) if var])
    Q = np.array([0.0 if var else float(np.ravel(x)[0]) for x, var in zip(vals, varying, strict=True)])
    return kern, sizes, X, Q


def test_root_bounds_hold_in_float64_and_double_double(two_state):
    """ω_c and k_c with their bounds (float64, and double-double after two Newton steps) against
    40 digits on 150 log-spaced velocities: every error within its bound, the double-double bound
    below 1e-25 relative."""
    d = two_state
    Vs = np.logspace(-8, -1, 150)
    kern, sizes, X, Q = _hopf_inputs(d, Vs)
    cv, _, ce = kern.f64_parts(X, Q)
    (C, R, S), (EC, ER, ES) = pn._split(cv, sizes), pn._split(ce, sizes)
    _, W0 = hopf_roots.stiffest(C.T, lambda Wr, rows: -pn._polyval(R[:, rows], Wr) / pn._polyval(S[:, rows], Wr))
    f64 = hopf_f64(C, EC, R, ER, S, ES, W0)
    _, _, ch, cl, cde = kern.dd_parts(X, Q)
    parts = [tuple(pn._split(a, sizes)[i] for a in (ch, cl, cde)) for i in range(3)]
    dd = hopf_dd(parts[0], parts[1], parts[2], W0)
    p = d.block.resolve({})
    checked = 0
    for j, V in enumerate(Vs):
        with mpmath.workdps(40):
            vals = [mpmath.mpf(float(np.ravel(x)[0])) for x in d.block.argvals(np.array([V]), p)]
            km, Wm = d.hopf.numeric_point_mp(vals)
            if km != km:
                assert np.isnan(f64[2, j])
                continue
            om = mpmath.sqrt(Wm)
            checked += 1
            assert abs(f64[0, j] - om) <= f64[1, j] and abs(f64[2, j] - km) <= f64[3, j], (V, f64[:, j])
            assert f64[1, j] <= 1e-12 * f64[0, j] and f64[3, j] <= 1e-12 * abs(f64[2, j])
            err_om = abs(mpmath.mpf(dd[0, j]) + mpmath.mpf(dd[1, j]) - om)
            err_k = abs(mpmath.mpf(dd[3, j]) + mpmath.mpf(dd[4, j]) - km)
            assert err_om <= dd[2, j] and err_k <= dd[5, j], (V, float(err_om), dd[2, j], float(err_k), dd[5, j])
            assert dd[2, j] <= 1e-25 * dd[0, j] and dd[5, j] <= 1e-25 * abs(dd[3, j]), (V, dd[:, j])
    assert checked > 100


def test_two_state_coefficients_by_the_bounded_route_within_1e_10_of_40_digits(two_state, monkeypatch):
    """Γ̄ and Λ of the two-state law on 120 log-spaced velocities and the five where Λ amplifies
    the error of k_c a millionfold (tests/derivation/test_numeric_hopf_inputs.py), through the
    bounded route (the batch threshold lowered to reach it): some points certified in float64,
    the others in double-double, none left to mpmath, every value within 1e-10 of 40 digits."""
    monkeypatch.setattr(pr, "BOUNDED_MIN", 0)
    sensitive = [2.5728259674479322e-06, 2.9749075472144434e-06, 3.0724688427090035e-06,
                 3.1224428230928577e-06, 3.913745601980384e-06]
    Vs = np.concatenate([np.logspace(-8, -1, 120), sensitive])
    for k in pr.BOUNDED_STATS:
        pr.BOUNDED_STATS[k] = 0
    got = two_state.evaluate(Vs, {}, ["k_c", "omega_c", "Gamma_bar", "Lambda"])
    stats = dict(pr.BOUNDED_STATS)
    assert stats["f64"] == Vs.size and 0 < stats["dd"] < Vs.size and stats["left"] == 0, stats
    for i, V in enumerate(Vs):
        want = two_state.evaluate_mp(float(V), {}, ["kc", "omega_c", "Gamma_bar", "Lambda"], dps=40)
        for name, key in (("k_c", "kc"), ("omega_c", "omega_c"), ("Gamma_bar", "Gamma_bar"), ("Lambda", "Lambda")):
            w = want[key]
            if w != w:
                assert np.isnan(got[name][i]), (V, name)
                continue
            assert abs(got[name][i] - w) <= 1e-10 * abs(w), (V, name, got[name][i], float(w))


@pytest.mark.parametrize("bounded_min", [0, 10**9])
def test_two_state_map_over_a_parameter_array(two_state, monkeypatch, bounded_min):
    """A map over (V, b₂) for the two-state law (array-valued parameters were refused for a Hopf line
    without closed form): each value equal to 40 digits at its own (V, b₂), by the bounded route and
    by the long double screen of small batches."""
    monkeypatch.setattr(pr, "BOUNDED_MIN", bounded_min)
    Vs = np.logspace(-7, -2, 6)[:, None]
    b2 = np.array([0.010, 0.0189, 0.030])[None, :]
    got = two_state.evaluate(Vs, {"b2": b2}, ["k_c", "Lambda"])
    assert got["Lambda"].shape == (6, 3)
    for i in range(6):
        for j in range(3):
            want = two_state.evaluate_mp(float(Vs[i, 0]), {"b2": float(b2[0, j])}, ["kc", "Lambda"], dps=40)
            for name, key in (("k_c", "kc"), ("Lambda", "Lambda")):
                w = want[key]
                if w != w:
                    assert np.isnan(got[name][i, j])
                else:
                    assert abs(got[name][i, j] - w) <= 1e-10 * abs(w), (i, j, name, got[name][i, j], float(w))
    # b₂ matters: the three columns differ
    assert np.all(np.abs(np.diff(got["k_c"], axis=1)) > 0)


def _mp_longdouble(x) -> mpmath.mpf:
    """A long double exactly as an mpmath number (mpmath takes no numpy long double)."""
    m, e = np.frexp(x)
    return mpmath.mpf(int(np.ldexp(m, 64))) * mpmath.mpf(2) ** (int(e) - 64)


@pytest.mark.skipif(not pr.EXTENDED, reason="no extended long double on this platform")
def test_long_double_polish_within_its_stated_error(two_state):
    """``polish_extended`` (the small-batch route's (k_c, ω_c)): within ``INPUT_REL_EXT`` of 40 digits
    on 120 log-spaced velocities, where the float64 roots are off by up to ~2e-15."""
    d = two_state
    Vs = np.logspace(-8, -1, 120)
    vals = [np.broadcast_to(np.asarray(x, dtype=float), Vs.shape) for x in d.block.argvals(Vs, d.block.resolve({}))]
    kc, om = d.hopf.numeric_at(vals)
    ld = np.longdouble
    k80, o80, polished = pn.polish_extended(d, [v.astype(ld) for v in vals], kc.astype(ld), om.astype(ld))
    assert np.array_equal(polished, np.isfinite(kc))     # simple roots: every Hopf point polished
    worst64 = worst80 = 0.0
    for i in range(Vs.size):
        if not np.isfinite(kc[i]):
            continue
        with mpmath.workdps(40):
            km, Wm = d.hopf.numeric_point_mp([mpmath.mpf(float(np.ravel(x)[i])) for x in vals])
            wm = mpmath.sqrt(Wm)
            worst64 = max(worst64, float(abs(kc[i] / km - 1)), float(abs(om[i] / wm - 1)))
            worst80 = max(worst80, float(abs(_mp_longdouble(k80[i]) / km - 1)),
                          float(abs(_mp_longdouble(o80[i]) / wm - 1)))
    assert worst80 <= pn.INPUT_REL_EXT, worst80
    assert worst64 > 100 * worst80          # the polish is what makes the screen's input error small


def test_root_bounds_hold_or_are_refused_near_a_double_root():
    """H(W) = (W − 1)(W − 1 − δ) with δ from 1e-16 to 1e-2, and p(W) = W (Re(P Q̄) = −W, |Q|² = 1):
    from each float64 root, every finite bound of ω = √W and k = W (float64 and double-double)
    contains a true root's values, and the float64 bounds are refused where the roots are closer than
    float64 resolves (δ ≤ 1e-9)."""
    deltas = 10.0 ** -np.linspace(2, 16, 57)
    C = np.stack([np.ones_like(deltas), -(2.0 + deltas), 1.0 + deltas])
    zeros = np.zeros_like(C)
    R, S = np.stack([-np.ones_like(deltas), np.zeros_like(deltas)]), np.ones((1, deltas.size))
    W0 = hopf_roots.roots(C.T).real.max(axis=1)
    f64 = hopf_f64(C, zeros, R, np.zeros_like(R), S, np.zeros_like(S), W0)
    dd = hopf_dd((C, zeros, zeros), (R, np.zeros_like(R), np.zeros_like(R)),
                 (S, np.zeros_like(S), np.zeros_like(S)), W0)
    refused = 0
    for j, dl in enumerate(deltas):
        # the exact roots of the float64 coefficients (1 + δ rounded, 2 + δ rounded): by the exact
        # quadratic formula in 60 digits
        with mpmath.workdps(60):
            a, b, c = (mpmath.mpf(float(x)) for x in C[:, j])     # exact
            disc = b * b - 4 * a * c
            roots = [(-b + s * mpmath.sqrt(disc)) / (2 * a) for s in (1, -1)] if disc >= 0 else []
            for om, eom, k, ek in ((f64[0, j], f64[1, j], f64[2, j], f64[3, j]),
                                   (mpmath.mpf(dd[0, j]) + mpmath.mpf(dd[1, j]), dd[2, j],
                                    mpmath.mpf(dd[3, j]) + mpmath.mpf(dd[4, j]), dd[5, j])):
                if not np.isfinite(ek) or not np.isfinite(eom):
                    refused += 1
                    continue
                assert any(abs(k - r) <= ek and abs(om - mpmath.sqrt(r)) <= eom for r in roots), (dl, k, ek)
        # float64 cannot resolve roots closer than ~1e-8 (√u): refused there
        if dl <= 1e-9:
            assert not np.isfinite(f64[3, j]), (dl, f64[:, j])
    assert refused > 0
