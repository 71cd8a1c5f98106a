"""The forced oscillator's run (Skurativskyi et al. 2019, eq. 1) is a :class:`Simulation`.

``landau.verify.skurativskyi.simulate.run`` returns a :class:`ForcedRun`, a subclass of the common
result: the base fields carry the recorded series, the end of the run, its status and the contact
events; the loop's own results (impacts, stroboscopic samples, Lyapunov sums, counters) are the
subclass's fields.
"""

from __future__ import annotations

import pickle

import numpy as np
import pytest
from scipy.linalg import expm


def test_forced_run_is_a_simulation_ending_at_the_closed_form_state():
    """Out of reach of the obstacle (x_I = 1 m) and without the dry friction (T = 0) eq. (1) is the
    linear forced oscillator m ẍ + c ẋ + k x = m₀e ω² sin ωt, whose solution is closed-form
    (particular solution plus the homogeneous flow expm(A t)).  At rtol 1e-10 over two periods
    the end state agrees to 1e-11 m and 1e-9 m/s (the integration error; measured ~1e-13 m)."""
    from landau.verify.hybrid.result import Simulation, Status
    from landau.verify.skurativskyi.model import PAPER
    from landau.verify.skurativskyi.simulate import ForcedRun, run

    p = PAPER.with_(xI=1.0, T=0.0, omega=16.0)
    y0 = np.array([1e-3, 0.0])
    rec = run(p, 2, y0, rtol=1e-10, record=100_000)
    assert isinstance(rec, Simulation) and type(rec) is ForcedRun
    assert rec.status is Status.FINISHED and rec.success and rec.message == Status.FINISHED.advice
    assert rec.t_final == pytest.approx(2 * p.period, rel=1e-12)
    w = p.omega
    M = np.array([[p.k - p.m * w * w, -p.c * w], [p.c * w, p.k - p.m * w * w]])
    a, b = np.linalg.solve(M, [p.m0e * w * w, 0.0])  # x_p = a sin ωt + b cos ωt
    A = np.array([[0.0, 1.0], [-p.k / p.m, -p.c / p.m]])
    T = rec.t_final
    exact = expm(A * T) @ (y0 - [b, a * w]) + [a * np.sin(w * T) + b * np.cos(w * T),
                                               w * (a * np.cos(w * T) - b * np.sin(w * T))]
    assert abs(rec.y_final[0] - exact[0]) < 1e-11 and abs(rec.y_final[1] - exact[1]) < 1e-9
    # the recorded series: every accepted step end, from the start to the end of the run
    assert rec.t[0] == 0.0 and rec.t[-1] == rec.t_final and np.all(np.diff(rec.t) > 0)
    assert rec.y.shape == rec.f.shape == (2, len(rec.t)) == (2, rec.nsteps + 1)
    np.testing.assert_array_equal(rec.y[:, 0], y0)
    np.testing.assert_array_equal(rec.y[:, -1], rec.y_final)
    assert rec.state_names == ("x", "xdot") and rec.nfev > rec.nsteps > 0
    assert len(rec.events) == 0 and rec.regimes == ((0.0, rec.t_final, "free"),)


def test_impacts_and_detachments_are_the_events_and_regimes():
    """ω = 16 from rest: the cart hits the obstacle three times a period; each impact (x ↑ x_I) and
    detachment (x ↓ x_I) is an event on x = x_I, and the regimes alternate free/contact between
    them, covering the run."""
    from landau.verify.hybrid.result import Simulation
    from landau.verify.skurativskyi.model import PAPER
    from landau.verify.skurativskyi.simulate import run

    p = PAPER.with_(omega=16.0)
    rec = run(p, 3, record=10 ** 5)
    assert isinstance(rec, Simulation) and repr(rec).startswith("ForcedRun(ω=16")
    assert len(rec.impacts) > 0 and len(rec.detachments) > 0
    assert len(rec.events) == len(rec.impacts) + len(rec.detachments)
    imp = [e for e in rec.events if e.guard == "impact"]
    np.testing.assert_array_equal([e.t for e in imp], rec.impacts)
    np.testing.assert_array_equal([e.y[1] for e in imp], rec.impact_v)
    assert all(e.y[0] == p.xI and (e.from_mode, e.to_mode) == ("free", "contact") for e in imp)
    np.testing.assert_array_equal(rec.events.times(guard="detach"), rec.detachments)
    assert np.all(np.diff(rec.events.times()) >= 0)
    starts, ends, names = zip(*rec.regimes, strict=True)
    assert starts[0] == 0.0 and ends[-1] == rec.t_final and starts[1:] == ends[:-1]
    assert all(u != v for u, v in zip(names, names[1:], strict=False))
    # the stroboscopic samples of the record: the strobe points the loop took
    ts, ys = rec.section_points(period=p.period)
    n = min(len(ts), len(rec.strobe_t))
    np.testing.assert_allclose(ts[:n], rec.strobe_t[:n], rtol=1e-12)
    # a record is picklable (sweeps run in worker processes), events included
    back = pickle.loads(pickle.dumps(rec))
    np.testing.assert_array_equal(back.events.times(), rec.events.times())
    np.testing.assert_array_equal(back.y, rec.y)


def test_a_run_cut_short_carries_its_status_and_the_deprecated_conversion_returns_itself():
    from landau.verify.hybrid.result import Status
    from landau.verify.skurativskyi.model import PAPER
    from landau.verify.skurativskyi.simulate import run

    rec = run(PAPER, 3, max_steps=200, at_limit="return", record=10)
    assert rec.status is Status.MAX_STEPS and not rec.success and rec.nsteps == 200
    assert rec.t_final < 3 * PAPER.period and "by its limit" in rec.message
    assert len(rec.t) == 10 and rec.y.shape == (2, 10)
    for old in ("rec_t", "rec_y", "rec_f"):
        assert not hasattr(rec, old)
    with pytest.warns(DeprecationWarning, match="already a Simulation"):
        assert rec.simulation() is rec
