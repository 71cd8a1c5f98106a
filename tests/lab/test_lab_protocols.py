"""The protocol builders (landau.lab.protocols): the load-point histories they make, their bad inputs,
and the run of a step whose time lands a few ulps past a round number (a defect of the Radau IIA's
last step, fixed)."""

from __future__ import annotations

import pytest

from landau.errors import InputError
from landau.lab.preset import SI
from landau.lab.protocols import slide_hold_slide, velocity_history, velocity_step, velocity_steps


def test_a_velocity_step_by_time_or_by_displacement():
    p = velocity_step("1um/s", "10um/s", at="20s")
    assert p.history.velocities == (1e-6, 1e-5) and p.history.times == (0.0, 20.0) and p.t_end == 40.0
    q = velocity_step(1, 10, displacement=100, after="5min")     # lab units: um/s, um
    assert q.history.times[1] == pytest.approx(100.0, rel=1e-15) and q.t_end == pytest.approx(400.0, rel=1e-15)
    r = velocity_step(1e-6, 1e-5, at=10, preset=SI)
    assert r.history.velocities == (1e-6, 1e-5)
    with pytest.raises(InputError, match="one of them"):
        velocity_step(1, 10, at=1, displacement=1)
    with pytest.raises(InputError, match="V2: a load-point velocity must be > 0"):
        velocity_step(1, 0, at=1)


def test_velocity_steps_and_slide_hold_slide():
    p = velocity_steps(["1um/s", "10um/s", "1um/s"], displacement="50um")
    assert p.history.times == pytest.approx((0.0, 50.0, 55.0), rel=1e-15) and p.t_end == pytest.approx(105.0)
    s = slide_hold_slide("10um/s", [3, "30s"], slide="20s")
    assert s.history.velocities == (1e-5, 0.0, 1e-5, 0.0, 1e-5)
    assert s.history.times == (0.0, 20.0, 23.0, 43.0, 73.0) and s.t_end == 93.0
    assert [v for v, _, _ in s.pieces()] == list(s.history.velocities)
    with pytest.raises(InputError, match="one or more hold times > 0"):
        slide_hold_slide("10um/s", [0], slide=1)
    with pytest.raises(InputError, match="at least two"):
        velocity_steps(["1um/s"], every=1)


def test_a_velocity_history_with_units():
    p = velocity_history("1um/s@0,10um/s@10")
    assert p.history.velocities == (1e-6, 1e-5) and p.history.times == (0.0, 10.0)
    assert velocity_history("1@0,0@1min,1@2min").history.times == (0.0, 60.0, 120.0)   # bare: um/s
    assert velocity_history([(1e-6, 0), (1e-5, 10)], preset=SI).history.velocities == (1e-6, 1e-5)
    for text, words in [("1um@0", "is a length, expected a velocity"), ("1um/s", "is not 'V@t'"),
                        ("x@0", "must be numbers"), ("1um/s@0,-1um/s@3", ">= 0"),
                        ("1um/s@0,2um/s@0", "increasing"), ("0@0,1@1", "first")]:
        with pytest.raises(InputError, match=words):
            velocity_history(text)


def test_a_step_a_few_ulps_past_a_round_time_runs():
    # 100 um at 1 um/s is t = 100.00000000000001 s; the steady piece before it ends in one long step
    # from t < 50, and t + (t_end - t) rounded one ulp short of t_end, leaving a last step below the
    # Radau IIA's underflow bound: "step size too small" before the fix (checked), the end now
    from landau.laws import get_law
    from landau.verify.springblock.history import simulate_history

    P = {"a_v": 0.6, "a": 0.005, "b": 0.01, "L": 1e-5, "V_s": 1e-6, "M": 0.0, "sigma": 1.0, "eta": 1e-12}
    t_step = velocity_step(1, 10, displacement=100).history.times[1]
    assert t_step > 100.0
    sim = simulate_history(get_law("dieterich"), f"1e-6@0,1e-5@{t_step!r}", 1e3, P, t_end=200.0, rtol=1e-9)
    assert sim.t[-1] == 200.0
    mu = sim.y[sim.state_names.index("mu")]
    assert mu[-1] - mu[0] == pytest.approx(-0.005 * 2.302585092994046, abs=1e-9)


def test_below_k_c_the_quasi_static_run_stops_with_a_named_error():
    # k' = 1e-4/um < k_c = (b - a)/L = 5e-4/um: after the step the quasi-static slip rate blows up in
    # finite time (no inertia to bound it); the run stops there with that reason, not a bare integrator status
    from landau.errors import IntegratorError
    from landau.lab.protocols import run_protocol

    P = {"a_v": 0.6, "a": 0.005, "b": 0.01, "L": 1e-5, "V_s": 1e-6}
    with pytest.raises(IntegratorError, match="blows up in finite time") as exc:
        run_protocol(velocity_step(1, 10, at=100, after=200), "dieterich", "1e-4/um", P)
    assert exc.value.t > 100.0
