"""The mode-coupling model simulated from plain values: :func:`simulate` (the model ``mode-coupling``'s
``simulate`` offering) and :func:`bounded_run` (every non-smooth run of the model: step, event and
wall-clock budgets, a named outcome).

The 2-DOF model of Hoffmann, Fischer, Allgaier & Gaul (2002) from its parameters (or an N-DOF
structure given by its matrices, the ``mass_matrix``, ``damping_matrix``, ``stiffness_matrix``, ``normal``,
``tangential`` options), the contact law of the ``contact`` option (``cubic`` by default, ``linear``,
``hertz``) and the friction
coefficient Coulomb ``mu`` or a velocity law F(v_rel) (``friction`` options), started 1e-3 off the
steady sliding equilibrium along the tangential coordinate and integrated by the hybrid engine with
the compiled DOP853 (:mod:`landau.verify.modecoupling.nonsmooth`): flutter grows, and the contact
opens (flight) or the mass sticks to the belt.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from landau.errors import InputError
from landau.models import Setup
from landau.verify.hybrid.run_inputs import end_time, initial_state, interpolated, no_history, step_budget

NAME = "mode-coupling"
#: the step budget of a run where none is given
MAX_STEPS = 300_000
#: events kept (the run ends with status max-events past it)
MAX_EVENTS = 100_000
#: recorded points kept (thinned past it)
MAX_POINTS = 200_000
#: the wall-clock budget of a run (s)
WALL_S = 120.0
#: the run's end where none is given (s)
T_END = 300.0
def structure(setup: Setup):
    """The :class:`~landau.verify.modecoupling.nonsmooth.Structure` of a setup: the model's system
    (:func:`landau.verify.modecoupling.declaration.system_of`: the 2-DOF model's parameters with the
    declared defaults, or the matrices of the ``mass_matrix``, ``damping_matrix``, ``stiffness_matrix``
    options with ``normal`` and ``tangential``; the ``contact`` option; Coulomb ``mu`` or the setup's
    velocity law), with the simulation's contact and friction objects."""
    from landau.verify.modecoupling.declaration import system_of
    from landau.verify.modecoupling.nonsmooth import Contact, Structure

    mc = system_of(setup)
    law = None if isinstance(mc.friction, (int, float)) else mc.friction
    mu = float(mc.friction) if law is None else None
    M, C, K = (np.array(a, dtype=float) for a in (mc.M, mc.C, mc.K))
    return Structure(M, C, K, int(mc.normal), int(mc.tangential), float(mc.preload), float(mc.v0),
                     # k_NL is the cubic law's only (the model's default k_NL stands beside a linear or Hertz law)
                     Contact(mc.contact.kind, float(mc.contact.kH),
                             float(mc.contact.kNL) if mc.contact.kind == "cubic" else 0.0), law, mu)


def bounded_run(s, y0, t_end: float, *, max_steps: int = MAX_STEPS, wall_s: float = WALL_S, record: bool = True,
                sections: tuple = (), rtol: float = 1e-10, atol: float = 1e-12, max_events: int = MAX_EVENTS,
                t0: float = 0.0):
    """One non-smooth run of the structure ``s`` from ``y0`` to ``t_end``, bounded by ``max_steps`` (status
    ``max-steps``), ``max_events`` (``max-events``) and ``wall_s`` seconds of wall clock (``wall-time``,
    tested at every logged event: a run without ``sections`` logs the maxima and minima of the tangential
    coordinate, ``x-max`` and ``x-min``).  A
    softening contact that collapses ends the run with status ``stopped`` in mode ``collapse``.

    Returns
    -------
    HybridSolution
    """
    from landau.verify.hybrid import EngineOptions, Status
    from landau.verify.hybrid import simulate as run_hybrid
    from landau.verify.hybrid.dop853 import CompiledDOP853
    from landau.verify.modecoupling.nonsmooth import hybrid_model, initial_mode

    if not (math.isfinite(wall_s) and wall_s > 0):
        raise InputError(f"{NAME}: the wall-clock budget must be a finite number of seconds > 0, got {wall_s!r}")
    vt = s.n + s.tangential
    beats = (("x-max", vt, 1.0), ("x-min", vt, -1.0)) if not sections else ()
    model = hybrid_model(s, tuple(sections) + beats)
    y0 = np.asarray(y0, dtype=float)
    deadline = time.perf_counter() + wall_s
    out = {"wall": False}

    def stop(ev) -> bool:
        if time.perf_counter() > deadline:
            out["wall"] = True
        return out["wall"]

    opts = EngineOptions(record=record, max_steps=max_steps, max_events=max_events, max_samples=MAX_POINTS)
    sol = run_hybrid(model, initial_mode(s, y0), y0, (t0, t_end), CompiledDOP853(rtol, atol), opts, stop=stop)
    if out["wall"] and sol.t_final < t_end:
        sol = replace(sol, status=Status.WALL_TIME,
                      message=f"{Status.WALL_TIME.advice} ({wall_s:g} s, at t = {sol.t_final:.6g})")
    return sol


def state_names(n: int) -> tuple[str, ...]:
    """x (tangential), y (the penetration) for the 2-DOF model; x0…, then xdot0… for the matrix family."""
    if n == 2:
        return ("x", "y", "xdot", "ydot")
    return (*(f"x{i}" for i in range(n)), *(f"xdot{i}" for i in range(n)))


def simulate(setup: Setup, *, t_end: float | None = None, y0=None, history=None, t_eval=None,
             max_steps: int | None = None, sections: bool = False):
    """The mode-coupling run (module docstring): series x, y [m], xdot, ydot [m/s] (matrix family: x0…, xdot0…).

    Parameters
    ----------
    setup : Setup
        The parameters of the 2-DOF model (or the matrix options), the ``contact`` option, ``mu`` or a
        velocity law.
    t_end, y0, history, t_eval, max_steps, sections
        As :func:`landau.simulate` (no velocity history; the maxima and minima of the tangential
        coordinate are logged always).

    Returns
    -------
    Simulation
    """
    from landau.verify.modecoupling.nonsmooth import sliding_equilibrium

    no_history(history, NAME)
    t_end = end_time(t_end, T_END)
    s = structure(setup)
    names = state_names(s.n)
    ye = sliding_equilibrium(s)
    if y0 is not None:
        y = initial_state(y0, names)
        start = "starts at the given y0 (--y0)"
    else:
        y = ye.copy()
        y[s.tangential] += 1e-3
        start = "starts 1e-3 m off the steady sliding equilibrium along the tangential coordinate"
    sol = bounded_run(s, y, t_end, max_steps=step_budget(max_steps, MAX_STEPS))
    sim = replace(sol, model=NAME, state_names=names)
    sim = interpolated(sim, t_eval, t_end, "the engine's recorded samples")
    units = {nm: ("m/s" if "dot" in nm else "m") for nm in names}
    used: dict = {"contact": s.contact.law, "kH": s.contact.kH, "kNL": s.contact.kNL, "P": s.preload, "v0": s.v0,
                  "friction": s.law.name}
    used.update({k: float(v) for k, v in setup.params.items()})
    if setup.law is None and setup.option("friction") is None:
        used["mu"] = s.static[0]
    notes = [start, f"steady sliding equilibrium: penetration {ye[s.normal]:.6g} m"]
    if sol.final_mode == "collapse":
        notes.append(f"the softening contact collapsed (penetration reached delta_max = {s.contact.delta_max:.6g} m, "
                     "where N'(delta) = 0): the run ends there")
    return replace(sim, law=s.law.name, units={"t": "s", **units}, parameters=used,
                   notes=(*notes, *sim.notes), plot_hints={"phase": (0, s.n)})


__all__ = ["bounded_run", "simulate", "state_names", "structure"]
