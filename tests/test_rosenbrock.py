"""The compiled RODAS4 Rosenbrock method and the s-stage Radau IIA against closed forms.

* The coefficients: RODAS4's classical form satisfies the Rosenbrock order conditions up to
  order 4 and its embedded solution those up to order 3 (Hairer & Wanner 1996, IV.7,
  Table 7.1); the Radau IIA tableaux computed from their definition satisfy the simplifying
  conditions B(2s − 1) and C(s) and reproduce the radau5 constants for s = 3.
* The stepper contract (scipy ``test_ivp``-style problems with exact solutions, cost budgets).
* Fixed steps on a nonlinear, non-autonomous problem: the error falls 2⁴ = 16-fold per halving.
* One period of the Fig. 3 stick–slip cycle of Putelat et al. (2010) against the order-5
  Radau IIA at a tight tolerance.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import sympy as sp

from landau.errors import InputError
from landau.kernels import generate_kernel
from landau.verify.hybrid.collocation import radau_tableau
from landau.verify.hybrid.fastcall import addresses, rosenbrock_at
from landau.verify.hybrid.radau import A_RADAU, E_ERR, MU_REAL, VINV
from landau.verify.hybrid.rosenbrock import (RODAS4_A, RODAS4_C, RODAS4_CNODES, RODAS4_D, RODAS4_E, RODAS4_GAMMA,
                                             RODAS4_M, CompiledRODAS4, tableau_classical)
from landau.verify.hybrid.steppers import ScipyStepper

RTOL, ATOL, T_END, OMEGA = 1e-8, 1e-10, 10.0, 2.0


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
# stepper contract: problems of scipy's test_ivp with exact solutions
_y, _lam = sp.symbols("y lam")
_y1, _y2, _a, _b, _c, _d = sp.symbols("y1 y2 a b c d")


@pytest.fixture(scope="module")
def problems():
    decay = generate_kernel([_y], [-_lam * _y], [_lam], [1.0], name="decay")
    linear = generate_kernel([_y1, _y2], [_a * _y1 + _b * _y2, _c * _y1 + _d * _y2], [_a, _b, _c, _d],
                             [0.0, 1.0, -OMEGA ** 2, 0.0], name="linear")
    stiff = dataclasses.replace(linear, p=np.array([998.0, 1998.0, -999.0, -1999.0]), name="stiff")
    return {
        "decay": (decay, [1.0], lambda t: np.array([np.exp(-t)])),
        "harmonic": (linear, [1.0, 0.0], lambda t: np.array([np.cos(OMEGA * t), -OMEGA * np.sin(OMEGA * t)])),
        "stiff": (stiff, [1.0, 0.0], lambda t: np.array([2 * np.exp(-t) - np.exp(-1000 * t),
                                                         -np.exp(-t) + np.exp(-1000 * t)])),
    }


def _drive(factory, kernel, y0, exact):
    s = factory(kernel, 0.0, y0, T_END, lambda t, y: kernel.jacobian(t, y))
    steps, e_end, e_mid = 0, 0.0, 0.0
    while s.status == "running":
        assert s.step() is None
        steps += 1
        assert s.t_old < s.t
        e_end = max(e_end, np.max(np.abs(s.y - exact(s.t)) / (ATOL + RTOL * np.abs(exact(s.t)))))
        tm = 0.5 * (s.t_old + s.t)
        e_mid = max(e_mid, np.max(np.abs(s.dense_output()(tm) - exact(tm)) / (ATOL + RTOL * np.abs(exact(tm)))))
        assert s.dense_output()(np.array([s.t_old, tm])).shape == (len(y0), 2)
    assert s.status == "finished" and s.t == T_END
    return s, steps, e_end, e_mid


#: global error in units of the local tolerance: as for the other compiled steppers
#: (test_steppers.py: scipy's test_ivp asserts < 5 on contracting problems; the oscillator
#: accumulates a phase error over three periods); the Hermite dense output is third order
ERR_END = {"decay": 5.0, "harmonic": 200.0, "stiff": 5.0}
ERR_MID = {"decay": 50.0, "harmonic": 300.0, "stiff": 300.0}


@pytest.mark.parametrize("problem", ["decay", "harmonic", "stiff"])
def test_rodas4_stepper_accuracy_and_cost(problems, problem):
    kernel, y0, exact = problems[problem]
    s, steps, e_end, e_mid = _drive(CompiledRODAS4(rtol=RTOL, atol=ATOL), kernel, y0, exact)
    assert e_end < ERR_END[problem]
    assert e_mid < ERR_MID[problem]
    ref, ref_steps, _, _ = _drive(ScipyStepper("Radau", RTOL, ATOL), kernel, y0, exact)
    # measured 0.88–0.93× scipy Radau's steps at rtol 1e-8 (errors at the end 0.3, 169, 0.36 in
    # units of the tolerance); 1.5× catches an estimate or a controller of the wrong order
    # (which changes the count by ≥ 2×)
    assert steps <= 1.5 * ref_steps
    # per attempt: stages 2–6 (stage 1 reuses f at the start), ∂f/∂t by a difference (a general
    # kernel) and f at the new point; plus the first evaluation
    assert s.nfev <= 7 * (steps + s.nrejected) + 1
    assert s.njev == steps  # a rejected attempt reuses the step's Jacobian
    if problem == "stiff":
        assert steps < 500  # L-stable: follows the slow mode (an explicit method needs ≈ 3000)


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
    assert choose_method(1e-4, False) == "radau5"
    assert choose_method(AUTO_HIGH_ORDER_RTOL, False) == "radau9"
    assert choose_method(1e-10, True) == "radau5"
    # "auto" is exactly the method it chooses
    a = integrate(model, y0, (0.0, T), rtol=1e-9, method="auto")
    b = integrate(model, y0, (0.0, T), rtol=1e-9, method="radau9")
    assert np.array_equal(a.y, b.y)
    with pytest.raises(InputError, match="method"):
        integrate(model, y0, (0.0, T), method="euler")
    with pytest.raises(InputError, match="radau9"):
        integrate(model, y0, (0.0, T), method="radau9", event_index=W_INDEX)
