"""The hybrid engine's result is the common :class:`Simulation` (verify/hybrid/simulate.py).

``simulate`` returns a :class:`HybridSolution`, a subclass of
:class:`~landau.verify.hybrid.result.Simulation`: ``t``/``y`` are the recorded segments end to end,
``t_final``/``y_final`` where the run ended, ``status`` a :class:`Status`, ``regimes`` read off
the mode changes; the engine's extras are ``final_mode``, ``segments`` and ``zeno``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from landau.verify.hybrid import (
    DOP853Stepper,
    EngineOptions,
    Guard,
    HybridModel,
    HybridSolution,
    Mode,
    Simulation,
    Status,
    simulate,
)

STEP = DOP853Stepper(1e-12, 1e-14)


def _oscillator(terminal: bool = False) -> HybridModel:
    """x'' = -x with the section x = 0 crossed downwards (x = cos t: at t = π/2 + 2πk)."""
    down = Guard("x=0 down", lambda t, y: y[0], terminal=terminal)
    return HybridModel.from_modes(Mode("osc", lambda t, y: np.array([y[1], -y[0]]), (down,)), name="oscillator")


def _clock() -> HybridModel:
    """y' = 1 through three modes, switching at y = 1 and y = 2 (so at t = 1 and t = 2)."""
    one = lambda t, y: np.array([1.0])  # noqa: E731
    return HybridModel.from_modes(
        Mode("stick", one, (Guard("y=1", lambda t, y: 1.0 - y[0], lambda t, y: ("flight", y)),)),
        Mode("flight", one, (Guard("y=2", lambda t, y: 2.0 - y[0], lambda t, y: ("slip", y)),)),
        Mode("slip", one), name="clock")


def test_a_recorded_run_is_a_simulation_on_the_closed_form():
    sol = simulate(_oscillator(), "osc", [1.0, 0.0], (0.0, 10.0), STEP)
    assert isinstance(sol, Simulation) and type(sol) is HybridSolution
    assert sol.model == "oscillator" and sol.status is Status.FINISHED and sol.success
    assert sol.message == Status.FINISHED.advice and sol.zeno is None and sol.final_mode == "osc"
    # where the run ended: t_end, on (cos t, -sin t) to the integration tolerance (rtol 1e-12 over 1.6 periods)
    assert sol.t_final == 10.0
    np.testing.assert_allclose(sol.y_final, [math.cos(10.0), -math.sin(10.0)], rtol=0, atol=1e-10)
    # the recorded series: shape (n, m), from t0 to t_final, the last point the final state
    assert sol.y.shape == (2, len(sol.t)) and len(sol.t) > 20
    assert sol.t[0] == 0.0 and sol.t[-1] == sol.t_final
    np.testing.assert_array_equal(sol.y[:, -1], sol.y_final)
    np.testing.assert_allclose(sol.y, [np.cos(sol.t), -np.sin(sol.t)], rtol=0, atol=1e-10)
    # the section events at π/2 + 2πk (k = 0, 1), logged inside the one segment of the run
    assert sol.events.times() == pytest.approx([math.pi / 2, 5 * math.pi / 2], abs=1e-10)
    assert len(sol.segments) == 1 and np.all(np.diff(sol.t) > 0)
    np.testing.assert_array_equal(sol.t, sol.segments[0].t)
    assert sol.regimes == ((0.0, 10.0, "slip"),)   # one mode, no switch
    assert (sol.nsteps, sol.nfev) > (0, 0)
    # the mode of each recorded point, beside the same arrays
    t, y, modes = sol.trajectory()
    assert t is sol.t and y is sol.y and modes == ["osc"] * len(sol.t)
    # interpolating the recorded series (linear between samples) stays near the closed form
    assert sol.at(1.0) == pytest.approx([math.cos(1.0), -math.sin(1.0)], abs=0.02)


def test_the_status_follows_how_the_run_ended():
    # a terminal guard: stopped at the first downward crossing of x = 0, t = π/2 (closed form)
    sol = simulate(_oscillator(terminal=True), "osc", [1.0, 0.0], (0.0, 10.0), STEP)
    assert sol.status is Status.STOPPED and sol.success
    assert sol.t_final == pytest.approx(math.pi / 2, abs=1e-10) and sol.t[-1] == sol.t_final
    assert sol.y_final == pytest.approx([0.0, -1.0], abs=1e-10)
    # the event budget: ends at the first switch, y = t = 1
    sol = simulate(_clock(), "stick", [0.0], (0.0, 3.0), STEP, EngineOptions(max_events=1))
    assert sol.status is Status.MAX_EVENTS and not sol.success and sol.message == Status.MAX_EVENTS.advice
    assert sol.t_final == pytest.approx(1.0, abs=1e-13) and sol.final_mode == "flight"
    # the step budget
    sol = simulate(_oscillator(), "osc", [1.0, 0.0], (0.0, 100.0), STEP, EngineOptions(max_steps=20))
    assert sol.status is Status.MAX_STEPS and sol.nsteps == 20 and 0.0 < sol.t_final < 100.0


def test_zeno_accumulation_is_the_zeno_status_with_its_diagnosis():
    # a ball dropped from 1 m, restitution 1/2: impacts accumulate at
    # T = √(2/g) (1 + 2e/(1 − e)) (closed form); the run ends there with the diagnosis in the message
    g, e = 9.81, 0.5
    fly = Mode("fly", lambda t, y: np.array([y[1], -g]),
               (Guard("floor", lambda t, y: y[0], lambda t, y: ("fly", np.array([y[0], -e * y[1]]))),))
    sol = simulate(HybridModel.from_modes(fly, name="ball"), "fly", [1.0, 0.0], (0.0, 10.0), STEP)
    assert sol.status is Status.ZENO and not sol.success
    assert sol.zeno is not None and sol.zeno.t_accumulation == pytest.approx(
        math.sqrt(2 / g) * (1 + 2 * e / (1 - e)), rel=1e-9)
    assert sol.message == f"{Status.ZENO.advice} ({sol.zeno!r})"
    assert sol.t_final < sol.zeno.t_accumulation and sol.t[-1] <= sol.t_final


def test_regimes_follow_the_mode_changes_and_nothing_is_recorded_in_maps():
    for record in (True, False):
        sol = simulate(_clock(), "stick", [0.0], (0.0, 3.0), STEP, EngineOptions(record=record))
        assert sol.status is Status.FINISHED and sol.final_mode == "slip"
        assert [(e.from_mode, e.to_mode) for e in sol.events] == [("stick", "flight"), ("flight", "slip")]
        (a0, b0, r0), (a1, b1, r1), (a2, b2, r2) = sol.regimes
        assert (r0, r1, r2) == ("stick", "flight", "slip") and a0 == 0.0 and b2 == 3.0
        assert b0 == a1 == pytest.approx(1.0, abs=1e-13) and b1 == a2 == pytest.approx(2.0, abs=1e-13)
        assert sol.y_final == pytest.approx([3.0], abs=1e-12)
        if record:
            np.testing.assert_allclose(sol.y[0], sol.t, rtol=0, atol=1e-12)  # y = t
            assert [m for m in sol.trajectory()[2] if m not in ("stick", "flight", "slip")] == []
        else:   # an unrecorded run (event maps) carries empty series of the right shape
            assert sol.t.shape == (0,) and sol.y.shape == (1, 0) and sol.segments == ()
            assert sol.trajectory()[2] == []


def test_the_former_names_are_gone_and_simulation_warns():
    sol = simulate(_clock(), "stick", [0.0], (0.0, 3.0), STEP)
    # the final mode is ``final_mode``, the final time and state ``t_final``/``y_final``, the regimes a field
    assert not hasattr(sol, "mode") and isinstance(sol.regimes, tuple)
    assert isinstance(sol.t, np.ndarray) and isinstance(sol.t_final, float) and isinstance(sol.status, Status)
    with pytest.warns(DeprecationWarning, match="already a Simulation"):
        assert sol.simulation() is sol
    with pytest.warns(DeprecationWarning, match="already a Simulation"):
        renamed = sol.simulation("a clock")
    assert renamed.model == "a clock" and renamed.t is sol.t and renamed.final_mode == sol.final_mode
    assert repr(sol).startswith("HybridSolution(clock, finished, t_final=3, final_mode='slip'")


@pytest.mark.parametrize("with_field", [False, True])
def test_one_time_is_interpolated_as_the_array_of_times_is(with_field):
    """``at`` of one time (its scalar path) equals, bit for bit, the same time read through the
    array path; a recorded time returns the recorded state; outside the span (and NaN) is an
    error."""
    t = np.array([0.0, 0.5, 0.5, 1.25, 2.0])            # a repeated time: an interval of length 0
    y = np.vstack([np.cos(t), np.sin(3 * t)])
    f = np.vstack([-np.sin(t), 3 * np.cos(3 * t)]) if with_field else None
    sim = Simulation("closed form", t, y, None, Status.FINISHED, "", 2.0, y[:, -1], f=f)
    times = np.r_[np.linspace(0.0, 2.0, 41), 0.5, 1.25, 1e-300, np.nextafter(2.0, 0.0)]
    many = sim.at(times)
    for k, tk in enumerate(times):
        np.testing.assert_array_equal(sim.at(float(tk)), many[:, k])
    # at a recorded time the recorded state (to rounding: y0 + 1·(y1 − y0) on the linear path)
    np.testing.assert_allclose(sim.at(2.0), y[:, -1], rtol=1e-15, atol=0)
    np.testing.assert_allclose(sim.at(1.25), y[:, 3], rtol=1e-15, atol=0)
    for bad in (-1e-9, 2.0 + 1e-9, math.nan):
        with pytest.raises(ValueError, match="outside the recorded span"):
            sim.at(bad)
