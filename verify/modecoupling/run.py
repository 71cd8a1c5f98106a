"""The mode-coupling model simulated from plain values: :func:`simulate` (the model ``mode-coupling``'s
``simulate`` offering) and :func:`bounded_run` (every non-smooth run of the model: step, event and
wall-clock budgets, a named outcome).

The 2-DOF model of Hoffmann, Fischer, Begley & Gaul (2002) from its parameters (or an N-DOF
structure given by its matrices, the ``M``, ``C``, ``K``, ``normal``, ``tangential`` options), the
contact law of the ``contact`` option (``linear`` by default, ``cubic``, ``hertz``) and the friction
coefficient Coulomb ``mu`` or a velocity law F(v_rel) (``friction`` options), started 1e-3 off the
steady sliding equilibrium along the tangential coordinate and integrated by the hybrid engine with
the compiled DOP853 (:mod:`landau.verify.modecoupling.nonsmooth`): flutter grows, and the contact
opens (flight) or the mass sticks to the belt.
"""

from __future__ import annotations

import ast
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
#: the parameters of the 2-DOF model (Hoffmann et al. 2002) and their defaults (SI units, angles in degrees)
HOFFMANN = {"m": 1.0, "k1": 1.0, "k2": 0.5, "alpha1": 30.0, "alpha2": 60.0, "kH": 1.0, "kNL": 0.0, "P": 1.0,
            "c1": 0.02, "c2": 0.04, "mu": 0.9, "v0": 1.0}
#: the matrix family's options
MATRIX_OPTIONS = ("M", "C", "K", "normal", "tangential")


def matrix(value, what: str) -> np.ndarray:
    """A matrix from an array or a string such as ``"[[2,0],[0,1]]"`` (literal numbers only)."""
    if isinstance(value, str):
        try:
            value = ast.literal_eval(value.strip())
        except (ValueError, SyntaxError):
            raise InputError(f"{what}: expected a matrix of numbers like [[2,0],[0,1]], got {value!r}") from None
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{what}: expected a matrix of numbers, got {value!r}") from None
    if a.ndim != 2:
        raise InputError(f"{what}: expected a square matrix (rows of numbers), got {value!r}")
    return a


def _index(value, what: str) -> int:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what}: expected a coordinate index, got {value!r}") from None
    if not (math.isfinite(x) and x == int(x)):
        raise InputError(f"{what}: expected a whole coordinate index, got {value!r}")
    return int(x)


def structure(setup: Setup):
    """The :class:`~landau.verify.modecoupling.nonsmooth.Structure` of a setup: the 2-DOF model's parameters
    (defaults :data:`HOFFMANN`), or the matrices of the ``M``, ``C``, ``K`` options with ``normal``,
    ``tangential`` and the parameters ``P``, ``v0``, ``kH``, ``kNL``, ``mu``; the ``contact`` option;
    Coulomb ``mu`` or the setup's velocity law."""
    from landau.laws.velocity import coulomb
    from landau.verify.lancioni.run import velocity_law
    from landau.verify.modecoupling.nonsmooth import Contact, Structure, hoffmann_structure

    over = dict(setup.params)
    user_law = setup.law is not None or setup.option("friction") is not None
    law = velocity_law(setup, coulomb(over.get("mu", HOFFMANN["mu"])), over, model=NAME) if user_law else None
    contact = str(setup.option("contact", "linear"))
    mats = {k: setup.option(k) for k in MATRIX_OPTIONS if setup.option(k) is not None}
    if mats:
        missing = [k for k in MATRIX_OPTIONS if k not in mats and k != "C"]
        if missing:
            raise InputError(f"{NAME}: the matrix family needs {', '.join(missing)} as well")
        known = ("P", "v0", "kH", "kNL", "mu")
        unknown = sorted(set(over) - set(known))
        if unknown:
            raise InputError(f"{NAME}: unknown parameter(s) {', '.join(unknown)} with matrices (known: "
                             f"{', '.join(known)})")
        vals = {k: over.get(k, HOFFMANN[k]) for k in known}
        M, K = matrix(mats["M"], "M"), matrix(mats["K"], "K")
        C = matrix(mats["C"], "C") if "C" in mats else np.zeros_like(M)
        mu = None if user_law else vals["mu"]
        return Structure(M, C, K, _index(mats["normal"], "normal"), _index(mats["tangential"], "tangential"),
                         float(vals["P"]), float(vals["v0"]), Contact(contact, float(vals["kH"]), float(vals["kNL"])),
                         law, mu)
    unknown = sorted(set(over) - set(HOFFMANN))
    if unknown:
        raise InputError(f"{NAME}: unknown parameter(s) {', '.join(unknown)} (known: {', '.join(HOFFMANN)})")
    vals = {**HOFFMANN, **over}
    if user_law:
        vals.pop("mu")
    return hoffmann_structure(**{k: float(v) for k, v in vals.items()}, contact=contact, friction=law)


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


__all__ = ["HOFFMANN", "MATRIX_OPTIONS", "bounded_run", "matrix", "simulate", "state_names", "structure"]
