"""The spring–block's compiled Radau IIA run is the common :class:`Simulation` (a :class:`RadauRecord`).

Eq. (4) of Putelat, Dawes & Willis (2010) with the Dieterich law at V = 1e-4 m/s and
k = 1.7e5 N/m (below k_c: the slip oscillation grows from the perturbed steady state).
"""

from __future__ import annotations

import numpy as np
import pytest


@pytest.fixture(scope="module")
def model():
    from landau.laws import get_law
    from landau.verify.springblock import SpringBlockModel

    return SpringBlockModel.build(get_law("dieterich"), 1e-4, 1.7e5)


def test_integrate_returns_a_simulation_with_the_engine_counters(model):
    """The record is a Simulation: the recorded steps start at (0, y0), increase strictly and end
    at (t_final, y_final); the end state agrees with an independent scipy DOP853 run; the located
    crossings are both the arrays and the section events."""
    from scipy.integrate import solve_ivp

    from landau.verify.hybrid.result import Simulation, Status
    from landau.verify.springblock import RadauRecord, integrate
    from landau.verify.springblock.simulate import W_INDEX

    y0 = model.perturbed(0.01 * model.ell)
    rec = integrate(model, y0, (0.0, 2.0), rtol=1e-10, event_index=W_INDEX, record=10 ** 5)
    assert isinstance(rec, Simulation) and type(rec) is RadauRecord
    assert rec.status is Status.FINISHED and rec.success and rec.message == Status.FINISHED.advice
    assert rec.t_final == 2.0 and rec.model == "spring-block"
    assert repr(rec).startswith("RadauRecord(spring-block, finished, t_final=2 s")
    # the recorded series: every accepted step end after the initial point, y of shape (n, m)
    assert rec.y.shape == (model.n, len(rec.t)) and len(rec.t) == rec.nsteps + 1
    assert rec.t[0] == 0.0 and rec.t[-1] == rec.t_final and np.all(np.diff(rec.t) > 0)
    np.testing.assert_array_equal(rec.y[:, 0], y0)
    np.testing.assert_array_equal(rec.y[:, -1], rec.y_final)
    assert rec.nsteps > 100 and rec.nfev > rec.nsteps and rec.njev > 0 and rec.nlu > 0 and rec.rejected >= 0
    assert rec.cpu_seconds >= 0.0
    # independent: scipy's DOP853 on the model's right-hand side at rtol = atol = 1e-12; both runs
    # are accurate to about 1e-9 (Radau IIA at rtol 1e-10 over a few hundred steps)
    ref = solve_ivp(lambda t, y: model.f(y), (0.0, 2.0 / model.time_unit), y0, method="DOP853",
                    rtol=1e-12, atol=1e-12)
    assert ref.status == 0
    np.testing.assert_allclose(rec.y_final, ref.y[:, -1], rtol=0, atol=1e-7)
    # the crossings of w = 0: arrays and events agree, the direction is the sign of the w change
    assert len(rec.event_t) >= 2 and rec.event_y.shape == (len(rec.event_t), model.n)
    assert len(rec.events) == len(rec.event_t)
    assert all(e.kind == "section" and e.guard == "crossing" for e in rec.events)
    np.testing.assert_array_equal([e.t for e in rec.events], rec.event_t)
    assert [e.note for e in rec.events] == ["up" if d > 0 else "down" for d in rec.event_dir]
    np.testing.assert_allclose(rec.event_y[:, W_INDEX], 0.0, atol=1e-12)
    for te, d in zip(rec.event_t, rec.event_dir, strict=True):   # w changes sign as event_dir says
        w = rec.at([te * (1 - 1e-6), min(te * (1 + 1e-6), rec.t[-1])])[W_INDEX]
        assert np.sign(w[1] - w[0]) == d
    ts, ys = rec.section_points()
    np.testing.assert_array_equal(ts, rec.event_t)
    np.testing.assert_array_equal(ys, rec.event_y.T)


def test_a_run_stopped_after_crossings_is_stopped(model):
    """``stop_after`` ends the run at the step containing the last wanted crossing: status STOPPED,
    that many crossings in the wanted direction (the others are located too), nothing recorded by
    default (empty ``t``, ``y`` of shape (n, 0))."""
    from landau.verify.hybrid.result import Status
    from landau.verify.springblock import integrate
    from landau.verify.springblock.simulate import W_INDEX

    rec = integrate(model, model.perturbed(0.01 * model.ell), (0.0, 100.0), event_index=W_INDEX,
                    event_direction=-1, stop_after=3)
    assert rec.status is Status.STOPPED and rec.success
    down = rec.event_t[rec.event_dir < 0]
    assert len(down) == 3 and down[-1] == rec.event_t[-1] <= rec.t_final < 100.0
    assert rec.t.shape == (0,) and rec.y.shape == (model.n, 0)


def test_simulation_is_deprecated_and_returns_the_record(model):
    """``.simulation()`` warns (the record is already a Simulation) and returns the record itself."""
    from landau.verify.springblock import integrate

    rec = integrate(model, model.perturbed(0.01 * model.ell), (0.0, 0.5))
    with pytest.warns(DeprecationWarning, match="already a Simulation"):
        assert rec.simulation() is rec
    with pytest.warns(DeprecationWarning):
        named = rec.simulation("dieterich block")
    assert named.model == "dieterich block" and named.t_final == rec.t_final and named.nsteps == rec.nsteps


def test_record_run_builds_the_same_record_as_integrate(model):
    """A run shorter than one compiled call: ``record_run`` is the same computation as ``integrate``
    with every step recorded, and returns the same record (bit for bit)."""
    from landau.verify.springblock import RadauRecord, integrate
    from landau.verify.springblock.simulate import W_INDEX, record_run

    y0 = model.perturbed(0.01 * model.ell)
    one = integrate(model, y0, (0.0, 2.0), event_index=W_INDEX, record=10 ** 5)
    rr = record_run(model, y0, (0.0, 2.0), event_index=W_INDEX)
    assert type(rr) is RadauRecord and rr.status is one.status
    for name in ("t", "y", "y_final", "event_t", "event_y", "event_dir"):
        np.testing.assert_array_equal(getattr(rr, name), getattr(one, name), err_msg=name)
    assert (rr.t_final, rr.nsteps, rr.rejected, rr.nfev, rr.njev, rr.nlu) == \
        (one.t_final, one.nsteps, one.rejected, one.nfev, one.njev, one.nlu)
    assert [(e.t, e.note) for e in rr.events] == [(e.t, e.note) for e in one.events]
