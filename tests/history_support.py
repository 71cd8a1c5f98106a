"""The comparison the load-history tests share: a run of ``simulate_history`` just after a velocity
step against the compiled spring–block started from the state the step leaves."""

from __future__ import annotations

import pytest


def assert_transient_matches(sim, model, run, force_after, k, V_before, f_rel):
    """The history run ``sim`` and the compiled run ``run`` of ``model`` end in the same state.

    Parameters
    ----------
    sim : Simulation
        The ``simulate_history`` run, with state names ``v``, ``phi`` and ``F``.
    model : SpringBlockModel
        The spring–block at the velocity after the step.
    run : RadauRecord
        ``integrate(model, …)`` over the same time after the step.
    force_after : float
        The steady-state friction force F_ss after the step (N); the spring force is
        F = F_ss − k X with X = x − x₀(t).
    k : float
        Spring stiffness (N/m).
    V_before : float
        The load-point velocity before the step (m/s): the run must still be mid-transient.
    f_rel : float
        Relative tolerance on F.
    """
    ph = model.to_physical(run.y_final)
    col = {n: i for i, n in enumerate(sim.state_names)}
    assert abs(sim.y_final[col["v"]] / V_before - 1) > 0.5        # mid-transient
    assert sim.y_final[col["v"]] == pytest.approx(float(ph["v"]), rel=1e-7)
    assert sim.y_final[col["phi"]] == pytest.approx(float(ph["phi"]), rel=1e-7)
    assert sim.y_final[col["F"]] == pytest.approx(force_after - k * float(ph["X"]), rel=f_rel)
