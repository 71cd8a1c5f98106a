"""The compiled RODAS4 Rosenbrock method and the s-stage Radau IIA against closed forms.

* The coefficients: RODAS4's classical form satisfies the Rosenbrock order conditions up to
  order 4 and its embedded solution those up to order 3 (Hairer & Wanner 1996, IV.7,
  Table 7.1); the Radau IIA tableaux computed from their definition satisfy the simplifying
  conditions B(2s − 1) and C(s) and reproduce the radau5 constants for s = 3.
* The stepper contract (scipy ``test_ivp``-style problems with exact solutions, cost budgets):
  in ``test_steppers.py`` with the other compiled steppers.
* Fixed steps on a nonlinear, non-autonomous problem: the error falls 2⁴ = 16-fold per halving.
* One period of the Fig. 3 stick–slip cycle of Putelat et al. (2010) against the order-5
  Radau IIA at a tight tolerance.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from landau.errors import InputError
from landau.codegen.kernels import generate_kernel
from landau.verify.hybrid.collocation import radau_tableau
from landau.verify.hybrid.fastcall import addresses, rosenbrock_at
from landau.verify.hybrid.radau import A_RADAU, E_ERR, MU_REAL, VINV
from landau.verify.hybrid.rosenbrock import (RODAS4_A, RODAS4_C, RODAS4_CNODES, RODAS4_D, RODAS4_E, RODAS4_GAMMA,
                                             RODAS4_M, tableau_classical)


# --------------------------------------------------------------------------------------------
# coefficients
def _conditions(b, alpha, gamma, g):
    """Residuals of the order conditions of Hairer & Wanner (1996), Table IV.7.1, orders 1–4."""
    beta = alpha + gamma
    np.fill_diagonal(beta, 0.0)
    bp, a = beta.sum(1), alpha.sum(1)
    return np.array([
        b.sum() - 1,
        b @ bp - (0.5 - g),
        b @ a ** 2 - 1 / 3,
        b @ beta @ bp - (1 / 6 - g + g ** 2),
        b @ a ** 3 - 1 / 4,
        (b * a) @ alpha @ bp - (1 / 8 - g / 3),
        b @ beta @ a ** 2 - (1 / 12 - g / 3),
        b @ beta @ beta @ bp - (1 / 24 - g / 2 + 1.5 * g ** 2 - g ** 3),
    ])


def test_rodas4_satisfies_the_order_conditions():
    tc = tableau_classical()
    g = RODAS4_GAMMA
    # 16-digit coefficients: the residuals are at rounding level (measured ≤ 2e-15)
    assert np.max(np.abs(_conditions(tc.b, tc.alpha, tc.gamma, g))) < 1e-13
    emb = _conditions(tc.b_hat, tc.alpha, tc.gamma, g)
    assert np.max(np.abs(emb[:4])) < 1e-13          # the embedded solution has order 3 ...
    assert np.max(np.abs(emb[4:])) > 1e-3           # ... and not 4 (else the estimate would vanish)
    # the nodes are the row sums of α and the ∂f/∂t weights those of Γ
    assert np.allclose(tc.alpha.sum(1), RODAS4_CNODES, atol=1e-13)
    assert np.allclose(tc.gamma.sum(1), RODAS4_D, atol=1e-13)


def test_radau_tableaux_from_their_definition():
    t3 = radau_tableau(3)
    # the hand-coded radau5 constants (closed forms in √6) are reproduced
    assert np.allclose(t3.A, A_RADAU, atol=1e-14)
    assert np.allclose(t3.e, E_ERR, rtol=1e-12)
    assert abs(t3.mu - MU_REAL) < 1e-12
    assert np.allclose(t3.vinv, VINV, rtol=1e-12)
    for s in (2, 4, 5):
        t = radau_tableau(s)
        b = t.A[-1]
        # B(2s − 1): the quadrature is exact to degree 2s − 2; C(s): stage order s
        for k in range(1, 2 * s):
            assert abs(b @ t.c ** (k - 1) - 1 / k) < 1e-12
        for k in range(1, s + 1):
            assert np.allclose(t.A @ t.c ** (k - 1), t.c ** k / k, atol=1e-12)


# --------------------------------------------------------------------------------------------
# the stepper contract (problems with exact solutions, cost budgets): tests/test_steppers.py


# --------------------------------------------------------------------------------------------
# order
def test_rodas4_has_order_four_with_fixed_steps():
    """Fixed steps on x'' = −x − x³/2 + cos(t)/10 (nonlinear, non-autonomous: the ∂f/∂t terms
    count): the error at t = 5 falls 16-fold per halving (order 4)."""
    x, v, t = sp.symbols("x v t")
    k = generate_kernel([x, v], [v, -x - x ** 3 / 2 + sp.cos(t) / 10], [], [], time=t, name="duffing_forced")
    from scipy.integrate import solve_ivp

    ref = solve_ivp(lambda tt, y: k(tt, y), (0, 5), [1.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]
    af, aj = addresses(k.fun, k.jac)
    errs = []
    for nsteps in (40, 80, 160):
        h = 5.0 / nsteps
        # rtol = atol = 0.9: every step is accepted and h stays at max_step
        out = rosenbrock_at(af, aj, 0.0, np.array([1.0, 0.0]), 5.0, k.p, 0.9, np.full(2, 0.9), h, h, 10 ** 5, -1,
                            0.0, 0, 0, 0, 0, 0, RODAS4_A, RODAS4_C, RODAS4_CNODES, RODAS4_D, RODAS4_M, RODAS4_E,
                            np.empty((1, 3)), np.empty(1))
        assert out[3][0] == nsteps and out[3][1] == 0
        errs.append(np.max(np.abs(out[2] - ref)))
    ratios = np.array(errs[:-1]) / np.array(errs[1:])
    # measured 15.2, 15.6; an order-3 method gives 8, order 5 gives 32
    assert np.all((ratios > 13) & (ratios < 19)), ratios


# --------------------------------------------------------------------------------------------
# the spring-block period (Putelat et al. 2010, Fig. 3)
@pytest.fixture(scope="module")
def fig3():
    from landau.verify.springblock.simulate import W_INDEX, integrate
    from landau.verify.springblock.workprecision import fig3_cycle, fig3_model

    model = fig3_model()
    orbit = fig3_cycle(model)
    y0 = np.insert(orbit.z, W_INDEX, 0.0)
    ref = integrate(model, y0, (0.0, orbit.period), rtol=1e-13).y
    return model, y0, orbit.period, ref


def test_springblock_period_with_every_method(fig3):
    from landau.verify.springblock.simulate import integrate
    from landau.verify.springblock.workprecision import error

    model, y0, T, ref = fig3
    # the end of one period against the order-5 Radau IIA at rtol 1e-13; bounds ≈ 5× the
    # measured errors (rodas4 2.3e-5, radau9 1.5e-7, radau5 4.4e-7 at rtol 1e-8): the
    # stick–slip transitions amplify local errors ~100-fold, a wrong method is off by O(1)
    bounds = {"rodas4": 1e-4, "radau9": 1e-6, "radau5": 2e-6}
    for method, bound in bounds.items():
        run = integrate(model, y0, (0.0, T), rtol=1e-8, method=method)
        assert run.status == "finished"
        assert error(run.y, ref) < bound, (method, error(run.y, ref))
    # the order-9 method takes fewer steps than the order-5 one at the same tolerance (measured 239 vs 996)
    assert (integrate(model, y0, (0.0, T), rtol=1e-8, method="radau9").steps
            < 0.5 * integrate(model, y0, (0.0, T), rtol=1e-8).steps)


def test_rodas4_locates_the_same_crossings(fig3):
    from landau.verify.springblock.simulate import W_INDEX, integrate

    model, y0, T, _ = fig3
    kw = dict(event_index=W_INDEX, event_direction=-1, stop_after=2)
    a = integrate(model, y0, (0.0, 3 * T), rtol=1e-10, **kw)
    b = integrate(model, y0, (0.0, 3 * T), rtol=1e-8, method="rodas4", **kw)
    assert b.status == "terminal event"
    down_a = a.event_t[a.event_dir < 0]
    down_b = b.event_t[b.event_dir < 0]
    # both return to the section after one and two periods; rodas4 at rtol 1e-8 within
    # 1e-6 s (measured 2e-7 s at rtol 1e-6 over one period)
    assert np.allclose(down_b, down_a, atol=1e-6)
    assert abs(down_a[0] - T) < 1e-8


def test_integrate_method_choice_and_refusals(fig3):
    from landau.verify.springblock.simulate import AUTO_HIGH_ORDER_RTOL, W_INDEX, choose_method, integrate

    model, y0, T, _ = fig3
    assert choose_method(1e-4, False) == "radau5t"
    assert choose_method(AUTO_HIGH_ORDER_RTOL, False) == "radau9"
    assert choose_method(1e-10, True) == "radau5t"
    # "auto" is exactly the method it chooses
    a = integrate(model, y0, (0.0, T), rtol=1e-9, method="auto")
    b = integrate(model, y0, (0.0, T), rtol=1e-9, method="radau9")
    assert np.array_equal(a.y, b.y)
    with pytest.raises(InputError, match="method"):
        integrate(model, y0, (0.0, T), method="euler")
    with pytest.raises(InputError, match="radau9"):
        integrate(model, y0, (0.0, T), method="radau9", event_index=W_INDEX)


# --------------------------------------------------------------------------------------------
# the step loop the three stiff methods share (landau.verify.hybrid.stiffdriver)
@pytest.fixture(scope="module")
def oscillator():
    x, v = sp.symbols("x v")
    k = generate_kernel([x, v], [v, -4 * x], [], [], name="oscillator_omega2")
    return k, addresses(k.fun, k.jac)


def _cores(k, af, aj, y0, t_end, rtol, max_steps, ev_idx=-1, ev_dir=0, ev_stop=0, rec_cap=0):
    """(name, status, t, y, counters, ev_t, ev_y, ev_dir) of the three compiled stiff cores."""
    from landau.verify.hybrid.fastcall import collocation_at, radau_at

    n = len(y0)
    y0 = np.asarray(y0, dtype=float)
    at = np.full(n, rtol)
    out = []
    for name in ("radau5", "rodas4", "radau9"):
        buf, dirs = np.empty((20, n + 1)), np.zeros(20)
        common = (af, aj, 0.0, y0, t_end, k.p, rtol, at, 1e-4, np.inf, max_steps)
        if name == "radau5":
            r = radau_at(*common, ev_idx, 0.0, ev_dir, ev_stop, rec_cap, A_RADAU, VINV, buf, dirs)
        elif name == "rodas4":
            r = rosenbrock_at(*common, ev_idx, 0.0, ev_dir, ev_stop, rec_cap, 1, 0, RODAS4_A, RODAS4_C,
                              RODAS4_CNODES, RODAS4_D, RODAS4_M, RODAS4_E, buf, dirs)
        elif ev_idx < 0:
            tb = radau_tableau(5)
            r = collocation_at(*common, tb.A, tb.c, tb.e, tb.mu, tb.vinv)
            r = (*r, np.empty(0), np.empty((0, n)))
        else:
            continue
        out.append((name, int(r[0]), r[1], r[2], r[3], r[4], r[5], dirs[:len(r[4])]))
    return out


def test_shared_loop_locates_crossings_on_both_dense_outputs(oscillator):
    """x'' = −4x from (1, 0): x = cos 2t crosses 0 at t = π/4 + jπ/2, downward for even j.
    Stopping at the second downward crossing records three crossings, on the Radau IIA's
    collocation cubic and on RODAS4's Hermite cubic alike."""
    k, (af, aj) = oscillator
    runs = _cores(k, af, aj, [1.0, 0.0], 10.0, 1e-10, 10 ** 6, ev_idx=0, ev_dir=-1, ev_stop=2)
    assert [r[0] for r in runs] == ["radau5", "rodas4"]
    exact_t = np.pi / 4 + np.pi / 2 * np.arange(3)
    for name, st, t, y, cnt, ev_t, ev_y, ev_d in runs:
        assert st == 1, name                       # terminal event
        assert cnt[6] == 3 and list(ev_d) == [-1, 1, -1], name
        # cubic dense outputs at rtol 1e-10: measured 5e-14 s (radau5) and 8e-11 s (rodas4), ẋ
        # within 3e-11 and 1.5e-10; the bounds leave a factor ≥ 10, a crossing located on
        # the wrong step or a wrong dense output is off by ≥ 1e-4 s
        assert np.max(np.abs(ev_t - exact_t)) < 1e-9, (name, ev_t - exact_t)
        assert np.allclose(ev_y[:, 1], [-2.0, 2.0, -2.0], rtol=0.0, atol=2e-9), name   # ẋ = −2 sin 2t
        assert ev_t[-1] <= t < ev_t[-1] + 0.1, name    # stopped at the end of that step


def test_shared_loop_status_codes(oscillator):
    k, (af, aj) = oscillator
    for name, st, t, y, cnt, *_ in _cores(k, af, aj, [np.nan, 0.0], 1.0, 1e-8, 100):
        assert (st, t, cnt[0] + cnt[1]) == (-3, 0.0, 0), name           # non-finite start: no step
    for name, st, t, y, cnt, *_ in _cores(k, af, aj, [1.0, 0.0], 100.0, 1e-8, 5):
        assert (st, cnt[0] + cnt[1]) == (-2, 5) and 0.0 < t < 100.0, name  # step budget
    for name, st, t, y, cnt, *_ in _cores(k, af, aj, [1.0, 0.0], 1.0, 1e-8, 10 ** 6):
        assert (st, t) == (0, 1.0), name                                   # the end is hit exactly
        # x(1) = cos 2 at rtol 1e-8: measured errors 1e-11 (radau5), 3.7e-9 (rodas4), 3e-14 (radau9)
        assert abs(y[0] - np.cos(2.0)) < 4e-8, name


def test_s_stage_core_refuses_events_without_a_cubic(oscillator):
    from landau.verify.hybrid.collocation import radau_iia_core
    from landau.verify.hybrid.radau import pointers

    k, _ = oscillator
    fun, jac = pointers(k.fun, k.jac)
    tb = radau_tableau(5)
    with pytest.raises(InputError, match="three stages"):
        radau_iia_core(fun, jac, 0.0, np.array([1.0, 0.0]), 1.0, k.p, 1e-6, np.full(2, 1e-6), 1e-3, np.inf, 100, 0,
                       0.0, 0, 0, 0, tb.A, tb.c, tb.e, tb.mu, tb.vinv, False, False, np.empty((1, 3)), np.empty(1))
