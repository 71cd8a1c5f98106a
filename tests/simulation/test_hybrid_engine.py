"""Hybrid engine on hand-built systems with known answers (verify/hybrid).

Tolerances: event times are located by Brent's method to xtol = 1e-14 on a DOP853 dense
output run at rtol 1e-12; for polynomial trajectories (free fall, constant velocity) the
dense output is exact, so event times agree with the closed forms to ~1e-12 (a few
hundred ulps after tens of events).
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from landau.errors import IntegratorError
from landau.verify.hybrid import DOP853Stepper, EngineOptions, Guard, HybridModel, Jump, Mode, ScipyStepper, simulate
from landau.verify.hybrid.result import Status

G = 9.81


def ball(e: float, rest: bool = False) -> HybridModel:
    def bounce(t, y):
        return Jump("fly", np.array([y[0], -e * y[1]]), "impact")

    fly = Mode("fly", lambda t, y: np.array([y[1], -G]), (Guard("floor", lambda t, y: y[0], bounce),),
               on_zeno=(lambda t, y: Jump("rest", np.array([0.0, 0.0]))) if rest else None)
    still = Mode("rest", lambda t, y: np.zeros(2))
    return HybridModel.from_modes(fly, still, name="ball")


@pytest.mark.parametrize("e", [0.5, 0.8])
def test_bouncing_ball_zeno_time_closed_form(e):
    # Dropped from h at rest: first impact at sqrt(2h/g), then flights 2 e^k v1/g, so the
    # impacts accumulate at T = sqrt(2h/g) + 2 e v1 / (g (1 - e)), v1 = sqrt(2 g h).
    h = 1.0
    v1 = math.sqrt(2 * G * h)
    T = math.sqrt(2 * h / G) + 2 * e * v1 / (G * (1 - e))
    sol = simulate(ball(e), "fly", [h, 0.0], (0.0, 10.0), DOP853Stepper(1e-12, 1e-14))
    assert sol.status is Status.ZENO  # the engine stops and reports instead of hanging
    assert sol.zeno.t_accumulation == pytest.approx(T, rel=1e-9)
    assert sol.zeno.ratio == pytest.approx(e, rel=1e-6)
    # each impact time against the closed form t_k = t1 + 2 v1/g * sum_{j=1..k-1} e^j
    t = sol.events.times()
    k = np.arange(len(t))
    tk = math.sqrt(2 * h / G) + 2 * v1 / G * e * (1 - e ** k) / (1 - e)
    assert np.max(np.abs(t - tk)) < 1e-11
    # cost budget: a failing event loop would explode the evaluation count
    assert sol.nfev < 200 * len(t)


def test_bouncing_ball_chattering_ended_and_logged():
    sol = simulate(ball(0.5, rest=True), "fly", [1.0, 0.0], (0.0, 3.0), DOP853Stepper(1e-12, 1e-14))
    assert sol.status is Status.FINISHED and sol.final_mode == "rest"
    z = sol.events.filter(kind="zeno")
    assert len(z) == 1 and "chattering ended" in z[0].note


def test_switch_state_is_on_the_new_side():
    sol = simulate(ball(0.7), "fly", [1.0, 0.0], (0.0, 10.0), DOP853Stepper(1e-12, 1e-14))
    for ev in sol.events:
        assert ev.y[0] <= 0.0  # the root is accepted on the side where the guard is violated


def _dip_model():
    # y' = 1 from 0; guard (y-5)^2 - 0.01 is negative only on (4.9, 5.1): two roots 0.2 apart
    a = Mode("a", lambda t, y: np.array([1.0]),
             (Guard("dip", lambda t, y: (y[0] - 5.0) ** 2 - 0.01, lambda t, y: ("b", y)),))
    b = Mode("b", lambda t, y: np.array([0.0]))
    return HybridModel.from_modes(a, b)


@pytest.mark.parametrize("record", [True, False])  # False: steps are screened on the Hermite cubic first
def test_double_crossing_inside_one_step_is_caught(record):
    st = ScipyStepper("RK45", rtol=1e-6, atol=1e-9)  # steps grow to ~10 on this linear field
    sol = simulate(_dip_model(), "a", [0.0], (0.0, 20.0), st, EngineOptions(record=record))
    assert len(sol.events) == 1
    assert sol.events[0].t == pytest.approx(4.9, abs=1e-12)
    assert sol.final_mode == "b"
    # the baseline takes the same big step and misses both roots (why the engine owns the loop)
    base = solve_ivp(lambda t, y: [1.0], (0.0, 20.0), [0.0], method="RK45", rtol=1e-6, atol=1e-9,
                     events=lambda t, y: (y[0] - 5.0) ** 2 - 0.01)
    assert np.max(np.diff(base.t)) > 1.0 and len(base.t_events[0]) == 0


def _grazing_oscillators(rng):
    # two (lightly damped) oscillators and a linear guard c·y + d whose offset d puts the guard
    # within 1e-8…1e-1 of zero, above or below, at one of its local minima: a dip that may
    # cross and come back inside one step
    w1, w2 = rng.uniform(0.5, 3.0, 2)
    A = np.zeros((4, 4))
    A[0, 1] = A[2, 3] = 1.0
    A[1, 0], A[3, 2], A[1, 1] = -w1 ** 2, -w2 ** 2, -0.05
    c, y0 = rng.normal(size=4), rng.normal(size=4)
    ref = solve_ivp(lambda t, y: A @ y, (0.0, 10.0), y0, rtol=1e-11, atol=1e-13, dense_output=True)
    g = c @ ref.sol(np.linspace(0.0, 10.0, 4001))
    mins = np.nonzero((g[1:-1] < g[:-2]) & (g[1:-1] < g[2:]))[0] + 1
    d = -g[rng.choice(mins)] + rng.choice([-1.0, 1.0]) * 10.0 ** rng.uniform(-8, -1)
    a = Mode("a", lambda t, y: A @ y, (Guard("g", lambda t, y: c @ y + d, lambda t, y: ("b", y)),))
    return HybridModel.from_modes(a, Mode("b", lambda t, y: np.zeros(4))), y0


def test_hermite_screen_skips_only_steps_the_dense_scan_passes():
    # Independent computation: with record=True every step is scanned on the dense output
    # (samples of the solver's interpolant + dip refinement); with record=False a step is first
    # screened on the cubic Hermite interpolant with an error bound.  The screen may only skip
    # steps the dense scan passes, so both runs must log exactly the same events (bit for bit:
    # same steps, same brackets, same root search) — on grazing guards at very loose
    # tolerances and few samples, where steps are long, the Hermite cubic is far from the
    # solution and double crossings inside one step are common.  (Without the error bound,
    # i.e. screening the bare Hermite samples, several of these cases lose an event.)
    rng = np.random.default_rng(1)
    n_events = 0
    for _ in range(36):
        m, y0 = _grazing_oscillators(rng)
        for method, rtol, samples in (("DOP853", 1e-2, 1), ("DOP853", 1e-3, 1), ("RK45", 1e-2, 4),
                                      ("RK45", 1e-3, 2)):
            st = ScipyStepper(method, rtol, rtol * 1e-2)
            full, screened = (simulate(m, "a", y0, (0.0, 10.0), st, EngineOptions(record=rec, samples=samples))
                              for rec in (True, False))
            assert [e.t for e in screened.events] == [e.t for e in full.events]
            n_events += len(full.events)
    assert n_events > 50  # the grazing cases do produce events


def test_hermite_screen_saves_the_dense_output_stages():
    # harmonic oscillator with a guard that never fires: the screened run takes the same
    # DOP853 steps as solve_ivp and builds no dense output (3 extra stages per step in Hairer's
    # DOP853); its only extra evaluation is y'' at the phase start (first-step error estimate)
    m = HybridModel.from_modes(Mode("o", lambda t, y: np.array([y[1], -y[0]]),
                                    (Guard("far", lambda t, y: 2.0 + y[0], lambda t, y: ("o", y)),)))
    sol = simulate(m, "o", [1.0, 0.0], (0.0, 50.0), DOP853Stepper(1e-10, 1e-12), EngineOptions(record=False))
    base = solve_ivp(lambda t, y: [y[1], -y[0]], (0.0, 50.0), [1.0, 0.0], method="DOP853", rtol=1e-10, atol=1e-12)
    assert sol.status is Status.FINISHED and len(sol.events) == 0
    assert sol.nfev == base.nfev + 1
    unscreened = simulate(m, "o", [1.0, 0.0], (0.0, 50.0), DOP853Stepper(1e-10, 1e-12),
                          EngineOptions(record=False, screen=False))
    assert unscreened.nfev == base.nfev + 3 * unscreened.nsteps


def test_two_guards_at_the_same_instant():
    # x' = -1 from 1 and y' = -2 from 2 both vanish at t = 1; each guard stops its coordinate.
    def rhs(sx, sy):
        return lambda t, u: np.array([-1.0 * sx, -2.0 * sy])

    gx = lambda to: Guard("x=0", lambda t, u: u[0], lambda t, u: (to, u))
    gy = lambda to: Guard("y=0", lambda t, u: u[1], lambda t, u: (to, u))
    m = HybridModel.from_modes(
        Mode("A", rhs(1, 1), (gx("B"), gy("C"))),
        Mode("B", rhs(0, 1), (gy("D"),)),
        Mode("C", rhs(1, 0), (gx("D"),)),
        Mode("D", rhs(0, 0)))
    sol = simulate(m, "A", [1.0, 2.0], (0.0, 3.0), DOP853Stepper(1e-12, 1e-14))
    assert sol.final_mode == "D"
    assert [e.guard for e in sol.events] == ["x=0", "y=0"]
    assert all(abs(e.t - 1.0) < 1e-12 for e in sol.events)
    assert "simultaneous" in sol.events[0].note and sol.events[1].kind == "zero-length"
    assert np.allclose(sol.y_final, 0.0, atol=1e-12)


def test_section_events_poincare_period():
    # harmonic oscillator: upward crossings of x = 0 are 2π apart
    m = HybridModel.from_modes(Mode("o", lambda t, y: np.array([y[1], -y[0]]),
                                    (Guard("x=0 up", lambda t, y: -y[0]),)))
    sol = simulate(m, "o", [-1.0, 0.0], (0.0, 40.0), DOP853Stepper(1e-12, 1e-14))
    t = sol.events.times(kind="section")
    assert len(t) == 7  # π/2 + 2πk < 40 for k = 0..6
    assert np.allclose(np.diff(t), 2 * np.pi, atol=1e-9)
    assert t[0] == pytest.approx(np.pi / 2, abs=1e-10)


def test_zero_length_phase_fires_at_once():
    # the transition lands where the next mode's guard is already violated
    m = HybridModel.from_modes(
        Mode("A", lambda t, y: np.array([-1.0]), (Guard("g", lambda t, y: y[0], lambda t, y: ("B", y)),)),
        Mode("B", lambda t, y: np.array([1.0]), (Guard("h", lambda t, y: 0.5 - y[0], lambda t, y: ("C", y)),)),
        Mode("C", lambda t, y: np.array([0.0])))
    sol = simulate(m, "A", [1.0], (0.0, 2.0), DOP853Stepper())
    assert [e.kind for e in sol.events] == ["switch", "switch"]  # regular phases: A -> B at 1, B -> C at 1.5
    assert sol.events.times() == pytest.approx([1.0, 1.5], abs=1e-12)
    sol = simulate(m, "B", [0.75], (0.0, 2.0), DOP853Stepper())
    assert sol.events[0].kind == "zero-length" and sol.events[0].t == 0.0 and sol.final_mode == "C"


def test_integrator_failure_raises_with_time_and_state():
    m = HybridModel.from_modes(Mode("blow", lambda t, y: y ** 2))  # y = 1/(1 - t) blows up at t = 1
    with pytest.raises(IntegratorError) as exc:
        simulate(m, "blow", [1.0], (0.0, 2.0), DOP853Stepper())
    assert exc.value.t == pytest.approx(1.0, abs=1e-3)
    assert exc.value.state is not None


def test_transition_loop_is_reported():
    m = HybridModel.from_modes(
        Mode("A", lambda t, y: np.array([0.0]), (Guard("g", lambda t, y: -1.0, lambda t, y: ("B", y)),)),
        Mode("B", lambda t, y: np.array([0.0]), (Guard("h", lambda t, y: -1.0, lambda t, y: ("A", y)),)))
    with pytest.raises(IntegratorError, match="zero-length"):
        simulate(m, "A", [0.0], (0.0, 1.0), DOP853Stepper(), EngineOptions(max_zero_length=10))


def test_event_log_records_time_state_guard_modes():
    sol = simulate(ball(0.5), "fly", [1.0, 0.0], (0.0, 1.0), DOP853Stepper(1e-12, 1e-14))
    ev = sol.events[0]
    assert (ev.guard, ev.from_mode, ev.to_mode, ev.kind) == ("floor", "fly", "fly", "switch")
    assert ev.y_after[1] == pytest.approx(-0.5 * ev.y[1])
    assert "floor" in repr(sol.events)


def test_poincare_and_sweep_tools():
    from landau.verify.hybrid.analysis import event_map_orbit, map_bifurcation_diagram, poincare, sweep
    m = HybridModel.from_modes(Mode("o", lambda t, y: np.array([y[1], -y[0]]),
                                    (Guard("x=0 up", lambda t, y: -y[0]),)))
    sec = poincare(m, "o", [-1.0, 0.0], (0.0, 30.0), "x=0 up", DOP853Stepper(1e-12, 1e-14), t_transient=5.0)
    assert np.allclose(sec.y[1], 1.0, atol=1e-9) and sec.t[0] > 5.0   # |v| = 1 at x = 0
    # logistic map: period-2 attractor at r = 3.2 is {(r+1 ± sqrt((r-3)(r+1)))/(2r)} (closed form)
    res = map_bifurcation_diagram(lambda r: (lambda x: r * x * (1 - x)), [3.2], 0.3, 400, 2)
    r = 3.2
    exact = sorted([(r + 1 - math.sqrt((r - 3) * (r + 1))) / (2 * r), (r + 1 + math.sqrt((r - 3) * (r + 1))) / (2 * r)])
    assert np.allclose(sorted(res.values[0]), exact, atol=1e-12)
    assert event_map_orbit(lambda x: x / 2, 1.0, 3)[-1] == 0.125

    def fails_at_2(q, warm):
        if q == 2:
            from landau.errors import LandauError
            raise LandauError("boom")
        return q
    out = sweep(fails_at_2, [1, 2, 3])
    assert out.values == [1, None, 3] and 2.0 in out.failures


def test_stiff_contact_mode_with_radau_and_jacobian():
    # A mass at speed v0 hits a linear contact spring of stiffness k (penalty contact, the
    # shape of the Hertz contact of Skurativskyi et al. 2019): inside contact x'' = -k x, so the contact lasts
    # exactly π/sqrt(k) and the mass leaves with -v0 (closed form).  The contact mode is run
    # with the implicit Radau stepper and the mode's analytic Jacobian.
    from landau.verify.hybrid import RadauStepper
    k, v0 = 1e6, 1.0
    free = Mode("free", lambda t, y: np.array([y[1], 0.0]),
                (Guard("touch", lambda t, y: -y[0], lambda t, y: ("contact", y)),))
    contact = Mode("contact", lambda t, y: np.array([y[1], -k * y[0]]),
                   (Guard("release", lambda t, y: y[0], lambda t, y: ("free", y)),),
                   jac=lambda t, y: np.array([[0.0, 1.0], [-k, 0.0]]))
    m = HybridModel.from_modes(free, contact)
    sol = simulate(m, "free", [-1.0, v0], (0.0, 3.0), RadauStepper(rtol=1e-10, atol=1e-13))
    t_in, t_out = sol.events.times()
    assert t_in == pytest.approx(1.0, abs=1e-10)
    assert t_out - t_in == pytest.approx(math.pi / math.sqrt(k), rel=1e-6)
    assert sol.events[1].y[1] == pytest.approx(-v0, rel=1e-6)
    assert sol.y_final[0] == pytest.approx(-(3.0 - t_out) * v0, abs=1e-6)


def test_hermite_screen_on_a_multi_phase_run_matches_the_dense_scan():
    # Galvanetto (2004) two blocks, one step of the event map: eight switching events, most
    # phases starting with a guard exactly on its surface (pending) — the screen arms those
    # and screens the first step of every phase.  Independent computation: the same run with
    # the screen off (dense-output scan on every step) must log the same events at the same
    # times, and the screen must build no dense output on quiet steps (fewer evaluations).
    from landau.verify.galvanetto.maps import gsp_start, model_for
    from landau.verify.galvanetto.model import two_blocks

    p = two_blocks(0.25, beta=1.722)
    mode, y0 = gsp_start(p, -0.3)
    runs = [simulate(model_for(p), mode, y0, (0.0, 300.0), DOP853Stepper(1e-10, 1e-12),
                     EngineOptions(record=False, screen=screen), stop=lambda ev: ev.to_mode == "ss")
            for screen in (False, True)]
    full, screened = runs
    assert len(full.events) == 8 and full.final_mode == "ss"
    assert [(e.guard, e.to_mode, e.t) for e in screened.events] == [(e.guard, e.to_mode, e.t) for e in full.events]
    assert screened.nfev < full.nfev - 2 * full.nsteps  # 3 dense-output stages saved on most steps


@pytest.mark.parametrize("compiled", [False, True])
def test_a_long_run_ends_at_its_step_budget_with_bounded_samples(compiled):
    # the undamped oscillator x'' = -x never switches: a run to t = 1e12 must end at the step
    # budget with the named status, its recorded trajectory thinned to the sample bound and still
    # spanning the run, the state on the exact solution (cos t, -sin t)
    import sympy as sp

    from landau.codegen.kernels import generate_kernel
    from landau.verify.hybrid.dop853 import CompiledDOP853

    x, v = sp.symbols("x v")
    k = generate_kernel([x, v], [v, -x], name="harmonic")
    far = Guard("far", lambda t, y: 10.0 - y[0], lambda t, y: ("osc", y), affine=((-1.0, 0.0), 10.0))
    model = HybridModel.from_modes(Mode("osc", lambda t, y: np.array([y[1], -y[0]]), (far,), kernel=lambda: k))
    stepper = CompiledDOP853(1e-10, 1e-12) if compiled else DOP853Stepper(1e-10, 1e-12)
    for record in (True, False):
        opts = EngineOptions(record=record, max_steps=3000, max_samples=500)
        sol = simulate(model, "osc", [1.0, 0.0], (0.0, 1e12), stepper, opts)
        assert sol.status is Status.MAX_STEPS and sol.nsteps == 3000
        assert not sol.success and "max_steps" in sol.message
        assert 0 < sol.t_final < 1e12
        np.testing.assert_allclose(sol.y_final, [math.cos(sol.t_final), -math.sin(sol.t_final)], atol=1e-6)
        if record:
            t, y = sol.t, sol.y
            assert 250 <= len(t) <= 600            # ≤ max_samples (+ one step's samples)
            assert t[0] == 0.0 and t[-1] == sol.t_final  # spread over the whole run
            assert np.all(np.diff(t) > 0)
            np.testing.assert_allclose(y[0], np.cos(t), atol=1e-6)


def test_a_long_stick_slip_run_keeps_its_samples_bounded_across_many_phases():
    # Galvanetto (2004) one block from rest on the belt: a stick–slip cycle every ~14 steps, so
    # the record is thousands of short phases; thinning must drop whole phases to stay bounded
    from landau.verify.galvanetto.analysis import FIG_STEPPER
    from landau.verify.galvanetto.maps import model_for
    from landau.verify.galvanetto.model import one_block

    p = one_block(0.25)
    opts = EngineOptions(record=True, samples=8, max_steps=20_000, max_samples=1000)
    sol = simulate(model_for(p), "s", np.array([0.0, p.V]), (0.0, 1e12), FIG_STEPPER, opts)
    assert sol.status is Status.MAX_STEPS and len(sol.events) > 1000
    t = sol.t
    assert len(t) <= 1100 and t[0] == 0.0 and t[-1] == sol.t_final and np.all(np.diff(t) >= 0)
