"""The stick–slip blocks of Galvanetto (2004) simulated from plain values: :func:`simulate_one_block`
and :func:`simulate_two_blocks` (the models' ``simulate`` offerings).

Dimensionless blocks on a belt at velocity V (Galvanetto 2004, eq. 1), kinetic friction eq. (7)
or the user's law of the relative velocity r = Ẋ − V (the ``kinetic``/``kinetic_pos`` options),
integrated by the hybrid engine with the stick and slip modes, started stuck at the origin.
The ``hopf`` option (one block) adds the damped block's Hopf point c₁ = F_k'(−V) with its
normal form to the parameters.

References
----------
Galvanetto, U. (2004), Sliding bifurcations in the dynamics of mechanical systems with dry friction,
J. Sound Vib. 276, 121–139.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from landau.errors import InputError
from landau.models import Setup
from landau.verify.hybrid.run_inputs import end_time, initial_state, interpolated, no_history, step_budget

#: the step budget of a run where none is given
MAX_STEPS = 300_000
#: events kept (the run ends with status max-events past it)
MAX_EVENTS = 200_000
#: recorded points kept (thinned past it)
MAX_POINTS = 200_000
#: the run's end where none is given (dimensionless time)
T_END = 60.0
#: fractions of the belt velocity where a user's kinetic branch is checked to be finite
_R_PROBE = np.array([1e-9, 1e-3, 0.25, 0.5, 0.75, 1.0])


def _kinetic_law(setup: Setup, name: str, over: dict):
    """The kinetic law: eq. (7), the setup's law object or the ``kinetic`` option; its own parameters
    taken from ``over``."""
    from landau.laws.kinetic import KineticFriction
    from landau.verify.galvanetto.declaration import _own_names

    kinetic, kinetic_pos = setup.option("kinetic"), setup.option("kinetic_pos")
    if kinetic_pos is not None and kinetic is None:
        raise InputError(f"{name}: --kinetic-pos needs --kinetic (the r < 0 branch)")
    own = _own_names(setup)
    extra = {k: over.pop(k) for k in list(over) if k in own and k not in ("V", "gamma", "delta", "c", "alpha", "beta")}
    if setup.law is not None:
        if not isinstance(setup.law, KineticFriction):
            raise InputError(f"{name}: the law must be a kinetic law of r = Xdot - V (a KineticFriction or the "
                             f"kinetic= option), got {type(setup.law).__name__}")
        return setup.law, extra
    if kinetic is None:
        return KineticFriction(), extra
    return KineticFriction.from_expression(kinetic, kinetic_pos, names=("--kinetic", "--kinetic-pos"),   # parsed
                                           **extra), extra


def _run(setup: Setup, n: int, *, t_end, y0, history, t_eval, max_steps, sections):
    from landau.verify.galvanetto.analysis import FIG_STEPPER
    from landau.verify.galvanetto.maps import model_for
    from landau.verify.galvanetto.model import StickSlipParams
    from landau.verify.hybrid import EngineOptions, simulate

    name = ("galvanetto-one-block", "galvanetto-two-blocks")[n - 1]
    no_history(history, name)
    t_end = end_time(t_end, T_END)
    known = ["V", "gamma", "delta", "c"] + (["alpha", "beta"] if n == 2 else [])
    over = dict(setup.params)
    from landau.verify.galvanetto.declaration import _own_names
    from landau.verify.hybrid.run_inputs import unknown_parameters

    unknown_parameters(over, known + sorted(_own_names(setup) - set(known)), name)
    if setup.option("hopf") and n != 1:
        raise InputError(f"{name}: --hopf applies to galvanetto-one-block (the damped one block)")
    law, extra = _kinetic_law(setup, name, over)
    p = StickSlipParams(n=n, law=law).with_(**over)
    if not p.V > 0:
        raise InputError(f"{name}: belt velocity V must be > 0, got {p.V!r}")
    for side, r in (("--kinetic", -p.V), ("--kinetic-pos", p.V)):
        with np.errstate(all="ignore"):
            vals = p.law.neg(r * _R_PROBE) if side == "--kinetic" else p.law.pos(r * _R_PROBE)
        if not np.all(np.isfinite(vals)):
            raise InputError(f"{name}: the kinetic law's {side} branch is not finite on the slip velocities "
                             f"0 < |r| <= {p.V:g} ({p.law!r})")
        # kinetic friction opposes the relative slip (Galvanetto 2004, eq. 7): F > 0 for r < 0, F < 0 for r > 0
        if not np.all(np.sign(vals) == -np.sign(r)):
            raise InputError(f"{name}: the kinetic law's {side} branch must be {'> 0' if r < 0 else '< 0'} on the "
                             f"slip velocities {'-' if r < 0 else ''}{p.V:g} <= r {'< 0' if r < 0 else '> 0'} "
                             f"(friction opposes the relative slip; {p.law!r})")
    names = ("X", "Xdot") if n == 1 else ("X1", "X2", "X1dot", "X2dot")
    if y0 is not None:
        y = initial_state(y0, names)
        # each block sticks where it moves with the belt, else slips on the side of its relative velocity
        mode = "".join("s" if y[n + i] == p.V else ("n" if y[n + i] < p.V else "p") for i in range(n))
        start = f"starts at the given y0 (--y0) in mode {mode!r} (s: stuck, n/p: slipping with r = Xdot - V < 0 / > 0)"
    else:
        mode = "s" * n
        y = np.array([0.0] * n + [p.V] * n)
        start = "starts stuck at X = 0"
    sol = simulate(model_for(p), mode, y, (0.0, t_end), FIG_STEPPER,
                   EngineOptions(record=True, samples=8, max_steps=step_budget(max_steps, MAX_STEPS),
                                 max_events=MAX_EVENTS, max_samples=MAX_POINTS))
    sim = replace(sol, model=name, state_names=names)
    sim = interpolated(sim, t_eval, t_end, "the engine's dense-output samples (8 per step)")
    used = {k: getattr(p, k) for k in known}
    used.update(extra)
    notes = ["dimensionless time and displacements; " + start, *sim.notes]
    if not p.law.is_paper_law:
        used["kinetic"] = str(p.law.neg_expr)
        used["kinetic_pos"] = str(p.law.pos_expr)
        notes.append(f"kinetic friction: {p.law!r}")
    if setup.option("hopf"):
        used["hopf"] = hopf_summary(p)
        h = used["hopf"]
        notes.append(f"damped one block at V = {p.V:g}: Hopf point c1 = {h['c1']:.10g} (omega = {h['omega']:.6g}), "
                     f"{h['criticality']}" if h["c1"] is not None else h["note"])
    units = {"t": "1", **{nm: "1" for nm in names}}   # dimensionless (Galvanetto 2004, eq. 1)
    law_name = "galvanetto2004-eq7" if p.law.is_paper_law else "user-kinetic"
    return replace(sim, law=law_name, units=units, parameters=used, notes=tuple(notes),
                   plot_hints={"phase": (0, 1) if n == 1 else (0, 2)})


def hopf_summary(p) -> dict:
    """The damped one block's Hopf analysis for the law of ``p`` (landau engine on the slip field)."""
    from landau.errors import NoHopfError
    from landau.verify.galvanetto.bifurcations import hopf_c1, hopf_c1_normal_form

    c1 = hopf_c1(p.V, law=p.law)
    if not (math.isfinite(c1) and c1 > 0):
        return {"c1": None, "note": f"no Hopf point: F_k'(-V) = {c1:.6g} <= 0, steady sliding is stable for c >= 0"}
    try:
        h = hopf_c1_normal_form(p.V, law=p.law)
    except NoHopfError as exc:
        return {"c1": None, "note": f"no Hopf point: {exc}"}
    return {"c1": float(h.p_c), "c1_closed_form": float(c1), "omega": float(h.omega_c),
            "Lambda": float(h.Lambda), "criticality": str(h.criticality), "C": float(h.C),
            "formula": "c1 = F_k'(-V), the slope of the r<0 branch at r = -V",
            "engine": "landau.derivation.general.hopf_normal_form on the smooth slip field"}


def simulate_one_block(setup: Setup, *, t_end: float | None = None, y0=None, history=None, t_eval=None,
                       max_steps: int | None = None, sections: bool = False):
    """The one block's run (module docstring): series X, Xdot (dimensionless); ``setup.params`` V,
    gamma, delta, c and the user law's parameters; the ``hopf`` option adds the Hopf point."""
    return _run(setup, 1, t_end=t_end, y0=y0, history=history, t_eval=t_eval, max_steps=max_steps,
                sections=sections)


def simulate_two_blocks(setup: Setup, *, t_end: float | None = None, y0=None, history=None, t_eval=None,
                        max_steps: int | None = None, sections: bool = False):
    """The two blocks' run (module docstring): series X1, X2, X1dot, X2dot; ``setup.params`` V, gamma,
    delta, c, alpha, beta and the user law's parameters."""
    return _run(setup, 2, t_end=t_end, y0=y0, history=history, t_eval=t_eval, max_steps=max_steps,
                sections=sections)


__all__ = ["MAX_STEPS", "hopf_summary", "simulate_one_block", "simulate_two_blocks"]
