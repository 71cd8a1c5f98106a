"""Every compiled stepper against closed-form solutions, with a cost budget.

Problems (in the style of scipy's ``integrate/_ivp/tests/test_ivp.py``), each integrated over
[0, 10] at rtol = 1e-8, atol = 1e-10 by stepping the solver through the engine's stepper
contract (``step()``, ``t``, ``y``, ``t_old``, ``dense_output()``, ``nfev``):

* decay y' = −y, y = e^{−t};
* harmonic oscillator x'' = −ω²x (ω = 2), x = cos ωt, ẋ = −ω sin ωt;
* stiff linear y' = A y, A = [[998, 1998], [−999, −1999]] (eigenvalues −1, −1000; Hairer &
  Wanner, *Solving ODEs II*, IV.1), y(0) = (1, 0): y = (2e^{−t} − e^{−1000t}, −e^{−t} + e^{−1000t}).

The fields are declared in sympy and compiled by :func:`landau.codegen.kernels.generate_kernel`; the
cost budgets compare with scipy's implementation of the same method run on the same kernel
(an independent code: its step and evaluation counts are the reference).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import sympy as sp
from support_dopri5 import CompiledDOPRI5

from landau.codegen.kernels import check_source, generate_kernel
from landau.errors import InputError
from landau.verify.hybrid.dop853 import CompiledDOP853
from landau.verify.hybrid.steppers import ScipyStepper

RTOL, ATOL, T_END, OMEGA = 1e-8, 1e-10, 10.0, 2.0

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
    """Step to T_END; return (solver, steps, max error/tol at step ends, at step midpoints)."""
    s = factory(kernel, 0.0, y0, T_END, lambda t, y: kernel.jacobian(t, y))
    steps, e_end, e_mid = 0, 0.0, 0.0
    while s.status == "running":
        assert s.step() is None
        steps += 1
        assert s.t_old < s.t
        e_end = max(e_end, np.max(np.abs(s.y - exact(s.t)) / (ATOL + RTOL * np.abs(exact(s.t)))))
        tm = 0.5 * (s.t_old + s.t)
        ym = s.dense_output()(tm)
        e_mid = max(e_mid, np.max(np.abs(ym - exact(tm)) / (ATOL + RTOL * np.abs(exact(tm)))))
        assert s.dense_output()(np.array([s.t_old, tm])).shape == (len(y0), 2)
    assert s.status == "finished" and s.t == T_END
    return s, steps, e_end, e_mid


#: global error bounds in units of the local tolerance (atol + rtol|y|): the decay and stiff
#: solutions contract, so the global error stays at the local level (scipy's test_ivp asserts
#: < 5 in the same units); the oscillator accumulates a phase error over three periods
#: (scipy's RK45 measures 23 and BDF 600 on this problem) — 200 allows that, while a wrong
#: field or a method of the wrong order is off by ≥ 1e4.  Dense outputs: DOP853's continuous
#: extension has order 7; the cubic Hermite interpolant (DOPRI5) is third order, measured ≤ 90
#: at the midpoints.
ERR_END = {"decay": 5.0, "harmonic": 200.0, "stiff": 5.0}
ERR_MID = {"decay": 50.0, "harmonic": 300.0, "stiff": 300.0}

#: (compiled factory, scipy's implementation of the same method or None)
METHODS = {"DOPRI5": (CompiledDOPRI5, "RK45"), "DOP853": (CompiledDOP853, "DOP853")}


@pytest.mark.parametrize("problem", ["decay", "harmonic", "stiff"])
@pytest.mark.parametrize("method", list(METHODS))
def test_stepper_accuracy_and_cost(problems, method, problem):
    kernel, y0, exact = problems[problem]
    make, scipy_name = METHODS[method]
    s, steps, e_end, e_mid = _drive(make(rtol=RTOL, atol=ATOL), kernel, y0, exact)
    assert e_end < ERR_END[problem]
    assert e_mid < ERR_MID[problem]
    # same method, same error control: the step count matches scipy's to a few per cent
    # (measured DOPRI5/RK45 0.99–1.0; DOP853 takes scipy's steps: its controller and initial step
    # are scipy's); 1.25 catches a controller or an error estimate of the wrong order (which
    # changes the count by ≥ 2×)
    ref, ref_steps, _, _ = _drive(ScipyStepper(scipy_name, RTOL, ATOL), kernel, y0, exact)
    assert steps <= 1.25 * ref_steps
    assert s.nfev <= 1.25 * ref.nfev
    if method == "DOP853":
        assert steps == ref_steps
        # equal to scipy's DOP853 up to round-off: the stiff solution decays from O(1) to 1e-4, so
        # the sums of a few hundred steps of O(1) values leave an absolute floor of
        # ~steps·eps·max|y0| ≈ 1e-14 (measured 1.07e-14 with scipy 1.17.1 / numpy 2.4.6, within
        # 1e-14 with the releases of the previous CI); a wrong stage or weight is off by ≥ 1e-8
        floor = 1e-12 * float(np.max(np.abs(y0)))
        np.testing.assert_allclose(s.y, ref.y, rtol=1e-12, atol=floor)


def test_compiled_dopri5_integrates_the_kernel_it_is_given(problems):
    # a kernel other than the Skurativskyi field: y' = −y must come out as e^{−t}
    kernel, y0, exact = problems["decay"]
    s = CompiledDOPRI5(rtol=RTOL, atol=ATOL)(kernel, 0.0, y0, 1.0)
    while s.status == "running":
        s.step()
    assert s.y[0] == pytest.approx(np.exp(-1.0), rel=1e-8)


def test_compiled_steppers_refuse_what_they_cannot_integrate(problems):
    # (a plain Python field given to CompiledDOP853 runs on scipy's DOP853: see test_hybrid_compiled_run)
    with pytest.raises(InputError, match="Kernel"):
        CompiledDOPRI5()(lambda t, y: -y, 0.0, [1.0], 1.0)
    with pytest.raises(InputError, match="rtol"):
        CompiledDOP853(rtol=2.0)(problems["decay"][0], 0.0, [1.0], 1.0)


def test_generated_kernel_and_jacobian_match_sympy():
    x, v, k, c = sp.symbols("x v k c")
    f = [v, -k * sp.sin(x) - c * v * sp.exp(-x ** 2)]
    ker = generate_kernel([x, v], f, [k, c], {k: 3.0, c: 0.5})
    pt = {x: 0.3, v: -1.2, k: 3.0, c: 0.5}
    expect_f = [float(e.subs(pt)) for e in f]
    expect_j = np.array(sp.Matrix(f).jacobian([x, v]).subs(pt), dtype=float)
    assert np.allclose(ker(0.0, [0.3, -1.2]), expect_f, rtol=1e-14)
    assert np.allclose(ker.jacobian(0.0, [0.3, -1.2]), expect_j, rtol=1e-14)
    with pytest.raises(InputError, match="undeclared"):
        generate_kernel([x], [k * x], [], name="missing-parameter")


def test_generated_source_whitelist_refuses_other_code():
    with pytest.raises(InputError, match="calls"):
        check_source("def fun(t, y, p, out):\n    out[0] = open('f')\n")
    with pytest.raises(InputError, match="attribute"):
        check_source("def fun(t, y, p, out):\n    out[0] = y.__class__\n")


# --- the common result type ----------------------------------------------------------------
def test_forced_oscillator_run_has_a_dense_time_series():
    # Skurativskyi et al. (2019) eq. (1) with the obstacle far away and no dry friction: the
    # linear forced oscillator m x'' + c x' + k x = m0e ω² sin ωt, solved in closed form
    # (particular solution + the homogeneous flow exp(At) of the initial mismatch)
    from scipy.linalg import expm

    from landau.verify.hybrid.result import Status
    from landau.verify.skurativskyi.model import PAPER
    from landau.verify.skurativskyi.simulate import run

    p = PAPER.with_(xI=1.0, T=0.0, omega=16.0)
    y0 = np.array([1e-3, 0.0])
    sim = run(p, 2, y0, rtol=1e-10, record=100_000)
    assert sim.status is Status.FINISHED and sim.success
    assert sim.t[0] == 0.0 and sim.t[-1] == sim.t_final and np.array_equal(sim.y[:, -1], sim.y_final)
    F, w = p.m0e * p.omega ** 2, p.omega
    M = np.array([[p.k - p.m * w * w, -p.c * w], [p.c * w, p.k - p.m * w * w]])
    a, b = np.linalg.solve(M, [F, 0.0])  # x_p = a sin ωt + b cos ωt
    A = np.array([[0.0, 1.0], [-p.k / p.m, -p.c / p.m]])
    d0 = y0 - [b, a * w]
    ts = np.linspace(0.0, sim.t_final, 57)
    exact = np.array([expm(A * t) @ d0 + [a * np.sin(w * t) + b * np.cos(w * t),
                                          w * (a * np.cos(w * t) - b * np.sin(w * t))] for t in ts]).T
    # between step ends the series is a cubic Hermite interpolant: error ~ h⁴|x⁗|/384 with
    # steps ≲ 0.02 s here, i.e. ≲ 1e-9 m on a 1 mm motion (the integration error at rtol
    # 1e-10 is smaller); 1e-8 m leaves a margin of 10
    assert np.max(np.abs(sim.at(ts)[0] - exact[0])) < 1e-8
    assert sim.at(0.5 * sim.t_final).shape == (2,)
    assert len(sim.events) == 0  # the obstacle at 1 m is never reached


def test_impacts_are_events_of_the_forced_oscillator_result():
    from landau.verify.skurativskyi.model import PAPER
    from landau.verify.skurativskyi.simulate import run

    p = PAPER.with_(omega=16.0)
    r = run(p, 2, rtol=1e-8, record=500)
    sim = r
    imp = [e for e in sim.events if e.guard == "impact"]
    assert np.array_equal([e.t for e in imp], r.impacts)
    assert all(e.y[0] == p.xI for e in imp)
    assert np.all(np.diff([e.t for e in sim.events]) >= 0)
    assert len(sim.t) == 500 < r.nsteps  # capped at the requested number of points


def test_hybrid_solution_is_the_common_result():
    from landau.verify.hybrid import DOP853Stepper, Guard, HybridModel, Jump, Mode, simulate
    from landau.verify.hybrid.result import Status

    g, e = 9.81, 0.5
    fly = Mode("fly", lambda t, y: np.array([y[1], -g]),
               (Guard("floor", lambda t, y: y[0], lambda t, y: Jump("fly", np.array([y[0], -e * y[1]]))),))
    sol = simulate(HybridModel.from_modes(fly, name="ball"), "fly", [1.0, 0.0], (0.0, 1.0),
                   DOP853Stepper(1e-12, 1e-14))
    sim = sol
    assert sim.model == "ball" and sim.status is Status.FINISHED and sim.success
    # first impact of a ball dropped from 1 m: t = sqrt(2/g) (closed form)
    assert sim.events[0].t == pytest.approx(np.sqrt(2 / g), rel=1e-12)
    # free fall is quadratic: the recorded samples lie on the parabola before the impact
    before = sim.t < sim.events[0].t
    assert np.allclose(sim.y[0, before], 1.0 - 0.5 * g * sim.t[before] ** 2, atol=1e-12)


# --- the compiled event locator ----------------------------------------------------------
def test_cubic_locator_finds_a_double_crossing_inside_one_step():
    from landau.verify.hybrid.crossing import cubic_crossing

    # g(s) = 0.1 − s + s²: positive at both ends of the step, below zero on
    # ((1 − √0.6)/2, (1 + √0.6)/2) — a dip that sampling at the step ends misses
    root = (1 - np.sqrt(0.6)) / 2
    s = cubic_crossing(0.1, -1.0, 1.0, 0.0, 0.0, -1.0, False)
    assert 0 <= s - root <= 4 * np.finfo(float).eps  # on the new side, to rounding
    g = lambda x: 0.1 + x * (-1.0 + x)  # the locator's (Horner) evaluation
    assert g(s) < 0
    # the next crossing, back to the positive side, searched from the first one
    s2 = cubic_crossing(0.1, -1.0, 1.0, 0.0, s, 1.0, False)
    assert s2 == pytest.approx((1 + np.sqrt(0.6)) / 2, abs=4e-16) and g(s2) > 0
    # a guard that stays positive has no crossing
    assert cubic_crossing(0.1, -0.2, 0.2, 0.0, 0.0, -1.0, False) == -1.0


# --- the periodic-orbit toolkit -------------------------------------------------------------
def test_shooting_finds_the_fixed_point_and_multipliers_of_a_return_map():
    # the time-2π map of the damped oscillator x'' + 2ζx' + x = 0 (closed form: exp(2πA)) with a
    # constant shift b: fixed point (I − P)⁻¹b, multipliers e^{2π(−ζ ± i√(1−ζ²))}
    from scipy.linalg import expm

    from landau.verify.hybrid.analysis import ShootingError, bisect_change, shoot_fixed_point

    zeta = 0.05
    A = np.array([[0.0, 1.0], [-1.0, -2 * zeta]])
    P = expm(2 * np.pi * A)
    b = np.array([0.3, -0.1])
    fp = shoot_fixed_point(lambda z: (P @ z + b, P), [1.0, 1.0], tol=1e-13)
    assert np.allclose(fp.z, np.linalg.solve(np.eye(2) - P, b), rtol=1e-12, atol=1e-14)
    mu = np.exp(2 * np.pi * complex(-zeta, np.sqrt(1 - zeta ** 2)))
    assert sorted(abs(m - mu) for m in fp.multipliers)[0] < 1e-12
    assert fp.iterations <= 3  # Newton is exact for an affine map: one step, then the check
    with pytest.raises(ShootingError, match="did not converge"):
        shoot_fixed_point(lambda z: (z ** 3 + 1.0, np.diag(3 * z ** 2)), [5.0], maxiter=2)
    # locate-by-bisection: where x² > 2 starts, to 2⁻⁴⁰ of the bracket
    lo, hi = bisect_change(lambda x: x * x > 2.0, 1.0, 2.0, 40)
    assert lo <= np.sqrt(2.0) <= hi and hi - lo <= 2.0 ** -40


def test_contact_run_is_the_common_result():
    # a block thrown along a slope (tan θ < μ) with the shared contact mechanics: decelerates at
    # g(μ cos θ − sin θ), stops at t* = u0/(g(μ cos θ − sin θ)) and sticks (closed form)
    import math

    from landau.verify.hybrid import DOP853Stepper, simulate
    from landau.verify.hybrid.contact import ContactModel, PointMassOnPlane, default_options
    from landau.verify.hybrid.result import Status

    g, th, mu, u0 = 9.81, 0.2, 0.5, 1.0
    cm = ContactModel(PointMassOnPlane(g=g, theta=th, mu=mu))
    sol = simulate(cm.model, "slip+", [0.0, 0.0, u0, 0.0], (0.0, 1.0), DOP853Stepper(1e-12, 1e-14),
                   default_options())
    sim = sol
    assert sim.status is Status.FINISHED
    dec = g * (mu * math.cos(th) - math.sin(th))
    t_stop = u0 / dec
    stop = [e for e in sim.events if e.to_mode == "stick"]
    assert len(stop) == 1 and stop[0].t == pytest.approx(t_stop, rel=1e-12)
    # the recorded series follows x = u0 t − dec t²/2 while sliding, then rests at u0²/(2 dec)
    slide = sim.t < t_stop
    assert np.allclose(sim.y[0, slide], u0 * sim.t[slide] - 0.5 * dec * sim.t[slide] ** 2, atol=1e-12)
    assert sim.y_final[0] == pytest.approx(u0 ** 2 / (2 * dec), rel=1e-12)
