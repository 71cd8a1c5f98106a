"""The spring–block's simulation from plain values: :func:`simulate` (the model's ``simulate`` offering).

One call assembles the run that ``landau simulate spring-block`` makes and :func:`landau.simulate`
returns, a :class:`~landau.verify.hybrid.result.Simulation` in physical units with its units,
parameters and notes:

* ``M > 0`` — the block on a driven spring, eq. (4) of Putelat, Dawes & Willis (2010), by the
  compiled Radau IIA (:func:`~landau.verify.springblock.simulate.record_run`), started from steady
  sliding displaced along the critical mode; series X = x − x₀(t), v and the law's states;
* ``M = 0`` — the quasi-dynamic cell (Rice 1993: the force balance solved for v;
  :func:`~landau.verify.springblock.quasidynamic.simulate_quasidynamic`); series X, v, μ and the states;
* a load-point velocity ``history`` — velocity steps and slide-hold-slide (Marone 1998;
  :func:`~landau.verify.springblock.history.simulate_history`); series V, v, μ, the states (F, σ).

The stiffness k defaults to 0.9 k_c(V) (steady sliding unstable), and for a history to
2 max k_c(Vᵢ) (stable at every velocity of it).

References
----------
Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), J. Mech. Phys. Solids 58, 27–53.
Rice, J. R. (1993), Spatio-temporal complexity of slip on a fault, J. Geophys. Res. 98, 9885–9907.
Marone, C. (1998), Annu. Rev. Earth Planet. Sci. 26, 643–696.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from landau.errors import InputError
from landau.models import Setup
from landau.verify.hybrid.run_inputs import (
    end_time,
    initial_state,
    interpolated,
    output_times,
    positive,
    step_budget,
)

#: the step budget of a run where none is given (about 1–3 minutes of CPU time)
MAX_STEPS = 5_000_000
#: recorded points kept (decimated past it)
MAX_POINTS = 200_000
#: the "stick" phases shaded in the plots: slip rate below this fraction of V
STICK_FRACTION = 0.01
#: what the Poincaré section is (the crossings logged with ``sections=True``)
SECTION_LABEL = "v = V with v rising (X minimal)"
#: the run's end where none is given (s)
T_END = 20.0


def law_state_units(law) -> dict:
    """The units of the law's states, inferred by dimensional analysis (:func:`infer_state_units`)."""
    from landau.verify.springblock.units import infer_state_units

    return infer_state_units(law)


def _law(setup: Setup):
    from landau.laws import FrictionLaw, get_law

    law = setup.law if setup.law is not None else "dieterich"
    law = get_law(law) if isinstance(law, str) else law
    if not isinstance(law, FrictionLaw):
        raise InputError(f"spring-block: the law must be a rate-and-state FrictionLaw or a built-in law's name, got "
                         f"{type(law).__name__}")
    return law


def simulate(setup: Setup, *, t_end: float | None = None, y0=None, history=None, t_eval=None,
             max_steps: int | None = None, sections: bool = False):
    """The spring–block's run (module docstring).

    Parameters
    ----------
    setup : Setup
        ``law`` a :class:`~landau.laws.FrictionLaw` or a built-in law's name (None: dieterich);
        ``params`` the driving velocity ``V`` [m/s] (default 1e-4), the stiffness ``k`` [N/m]
        (default 0.9 k_c(V)), the law's and the block's parameters (M, g, sigma, eta, gamma_ld, alpha_ld).
    t_end : float, optional
        End of the run [s] (default 20; for a history its own default, :func:`simulate_history`).
    y0 : sequence or str, optional
        Initial state in the order and units of the series (X, v, states; at M = 0: X, states).
    history : str or sequence of (V_i, t_i), optional
        A load-point velocity history (``"V0@t0,V1@t1"``, or pairs): velocity V_i [m/s] from t_i [s] on.
    t_eval : array_like or callable, optional
        Output times (or a function of the end time giving them); default the integrator's steps.
    max_steps : int, optional
        Step budget (default 5e6); at it the run ends with status ``max-steps``.
    sections : bool, optional
        Log the upward crossings of v = V (the minima of X) as section events.

    Returns
    -------
    Simulation
    """
    from landau.systems.system import SpringBlock

    law = _law(setup)
    params = dict(setup.params)
    V, k = params.pop("V", None), params.pop("k", None)
    block = SpringBlock.for_params(law, params)   # with the optional terms given (eta, gamma_ld, alpha_ld)
    from landau.verify.hybrid.run_inputs import unknown_parameters

    unknown_parameters(params, list(block.defaults), "spring-block")
    params = block.resolve(params)
    if history is not None:
        return _load_history(law, block, params, history, k, V, y0, t_end, t_eval)
    t_end = end_time(t_end, T_END)
    V = positive(V, "V") if V is not None else 1e-4
    notes = []
    if k is None:
        kc = _critical_stiffness(block, V, params)
        if not (math.isfinite(kc) and kc > 0):
            raise InputError(f"spring-block: law {law.name!r} has no Hopf point at V = {V:g} m/s "
                             "(steady sliding is stable for every k): give k (--k)")
        k = 0.9 * kc
        notes.append(f"k = 0.9 k_c(V) = {k:.6g} N/m (k_c = {kc:.6g} N/m; steady sliding is unstable below k_c)")
    else:
        k = positive(k, "k")
    steps = step_budget(max_steps, MAX_STEPS)
    if params["M"] == 0:
        return _quasidynamic(law, V, k, params, t_end, y0, t_eval, steps, sections, notes)
    return _dynamic(law, V, k, params, t_end, y0, t_eval, steps, sections, notes)


def _critical_stiffness(block, V: float, params) -> float:
    from landau.derivation.linear import critical_stiffness

    if "alpha_ld" in block.terms:
        from landau.derivation.springblock_routes import hopf_point

        return hopf_point(block, V, params).p_c
    return float(np.ravel(critical_stiffness(block, V, params))[0])


def _finish(sim, law, used: dict, units: dict, notes: list, hints: dict):
    return replace(sim, law=law.name, units={"t": "s", **units}, parameters=used, notes=tuple(notes),
                   plot_hints=hints)


def _dynamic(law, V, k, params, t_end, y0, t_eval, steps, sections, notes):
    """M > 0: eq. (4) by the compiled Radau IIA, converted to physical units."""
    from landau.systems.springblock_terms import states as term_states
    from landau.verify.hybrid import EventLog
    from landau.verify.hybrid.plotting import regimes_from_mask
    from landau.verify.springblock.model import SpringBlockModel
    from landau.verify.springblock.simulate import W_INDEX, record_run

    model = SpringBlockModel.build(law, V, k, params)
    # the terms' states (pore pressure, temperature: their excesses over steady sliding) after the law's
    extra = tuple(st.symbol.name for st in term_states(model.terms))
    ns = len(law.states)
    names = ("X", "v") + tuple(s.name for s in law.states) + extra
    if y0 is not None:
        vals = initial_state(y0, names)
        try:
            start_y = model.from_physical(vals[0], vals[1], vals[2:2 + ns], dict(zip(extra, vals[2 + ns:],
                                                                                   strict=True)))
        except InputError as exc:
            raise InputError(f"y0: {exc}") from None
        start = "starts at the given y0 (--y0)"
    else:
        start_y = model.perturbed(0.01 * model.ell)
        start = "starts X = 0.01 L (the law's memory length) off steady sliding along the critical mode"
    # section events: the crossings of v = V (the extrema of X); the Poincaré section keeps the upward ones
    sim = record_run(model, start_y, (0.0, t_end), rtol=1e-9, max_steps=steps, max_points=MAX_POINTS,
                     event_index=W_INDEX if sections else -1)
    ts = output_times(t_eval, t_end)
    how = ""
    if ts is not None:   # cubic Hermite in the scaled variables, with the field at each accepted step
        tu = model.time_unit
        field = np.column_stack([model.f(col) for col in sim.y.T]) / tu
        scaled = interpolated(replace(sim, f=field), ts, t_end, "the integrator's accepted steps, with the field "
                                                                "at each, in the scaled variables")
        how = scaled.notes[-1]
        rec_t, rec_y = scaled.t, scaled.y
    else:
        rec_t, rec_y = sim.t, sim.y
    phys = model.to_physical(rec_y.T)

    def physical(y):
        ph = model.to_physical(y)
        return np.array([float(ph[n]) for n in names])

    events = EventLog()
    for e in sim.events:  # the located minima of X (v = V, rising), in physical units like the series
        if e.note == "up":
            events.append(replace(e, y=physical(e.y), y_after=physical(e.y)))
    v = np.asarray(phys["v"])
    up = sim.event_dir > 0   # the record's crossing arrays follow its events (physical, rising)
    sim = replace(sim, t=rec_t, y=np.vstack([np.asarray(phys[n]) for n in names]).reshape(len(names), -1), f=None,
                  events=events, y_final=physical(sim.y_final), state_names=names,
                  regimes=regimes_from_mask(rec_t, v < STICK_FRACTION * V, "stick (v < V/100)", "slip"),
                  event_t=sim.event_t[up], event_y=np.array([e.y for e in events]).reshape(-1, len(names)),
                  event_dir=sim.event_dir[up])
    used = {"law": law.name, "V": V, "k": k, **params}
    notes.append("X = x - x0(t) is the displacement from steady sliding; " + start)
    if how:
        notes.append(how)
    units = {"X": "m", "v": "m/s", **law_state_units(law),
             **{st.symbol.name: st.unit for st in term_states(model.terms)}}
    return _finish(sim, law, used, units, notes, {"phase": (0, 1), "section_phase": (0, 2),
                                                  "section_label": SECTION_LABEL})


def _quasidynamic(law, V, k, params, t_end, y0, t_eval, steps, sections, notes):
    """M = 0 (with eta > 0): the quasi-dynamic cell, the force balance solved for v."""
    from landau.systems.springblock_terms import states as term_states
    from landau.verify.hybrid.plotting import regimes_from_mask
    from landau.verify.springblock.quasidynamic import QuasiDynamicCell, simulate_quasidynamic

    cell = QuasiDynamicCell.build(law, V, k, params)
    extra = tuple(cell.state_scales)      # the terms' states (their excesses over steady sliding)
    if y0 is not None:
        ns = len(law.states)
        names = ("X",) + tuple(s.name for s in law.states) + extra
        vals = initial_state(y0, names)
        try:
            start_y = cell.from_physical(vals[0], vals[1:1 + ns], dict(zip(extra, vals[1 + ns:], strict=True)))
        except InputError as exc:
            raise InputError(f"y0: {exc}") from None
        start = "starts at the given y0 (--y0) (X and the states; v follows from the force balance)"
    else:
        start_y = None
        start = "starts X = 0.01 L (the law's memory length) off steady sliding along the critical mode"
    sim = simulate_quasidynamic(law, V, k, cell, t_end, start_y, rtol=1e-9, max_steps=steps,
                                max_points=MAX_POINTS, sections=sections)
    sim = interpolated(sim, t_eval, t_end, "the integrator's accepted steps")
    v = sim.y[1]
    sim = replace(sim, regimes=regimes_from_mask(sim.t, v < STICK_FRACTION * V, "stick (v < V/100)", "slip"))
    used = {"law": law.name, "V": V, "k": k, **params}
    notes.append("quasi-dynamic (M = 0): the slip rate v solves k(Vt - x) = sigma mu(v, phi) + eta v at every "
                 "instant; X = x - x0(t) is the displacement from steady sliding; " + start)
    notes += list(sim.notes)
    units = {"X": "m", "v": "m/s", "mu": "1", **law_state_units(law),
             **{st.symbol.name: st.unit for st in term_states(cell.terms)}}
    return _finish(sim, law, used, units, notes,
                   {"phase": (0, 1), "section_phase": (0, 3), "section_label": SECTION_LABEL})


def history_text(history) -> str:
    """A history as the command line's ``"V0@t0,V1@t1"`` (a string, or pairs (V_i, t_i))."""
    if isinstance(history, str):
        return history
    try:
        return ",".join(f"{float(V)!r}@{float(t)!r}" for V, t in history)
    except (TypeError, ValueError):
        raise InputError(f"history: give pairs (V_i, t_i) or the text 'V0@t0,V1@t1', got {history!r}") from None


def _load_history(law, block, params, history, k, V, y0, t_end, t_eval):
    """The load point driven by a velocity history."""
    from landau.verify.springblock.history import parse_history, simulate_history

    if V is not None:
        raise InputError("spring-block: a velocity history gives the load-point velocities; leave out V (--V)")
    if y0 is not None:
        raise InputError("spring-block: a velocity history starts from steady sliding at its first velocity; "
                         "leave out y0 (--y0)")
    hist = parse_history(history_text(history))
    notes = [f"load point: {hist} (m/s @ s); starts from steady sliding at V = {hist.velocities[0]:g} m/s"]
    if k is None:
        k = _history_stiffness(law, block, params, hist, notes)
    else:
        k = positive(k, "k")
    if t_end is not None:
        t_end = end_time(t_end, T_END)
    grid = t_eval
    if callable(t_eval):   # a uniform grid over the run: its end is the history's default when none is given
        from landau.verify.springblock.history import default_end

        grid = t_eval(t_end if t_end is not None else default_end(hist, params))
    sim = simulate_history(law, hist, k, params, t_end, t_eval=grid)
    if grid is not None:
        notes.append(f"{len(sim.t)} output times, each the end of a compiled Radau IIA run")
    units = {"V": "m/s", "v": "m/s", "mu": "1", **law_state_units(law)}
    units.update({nm: "N" for nm in ("F", "sigma") if nm in sim.state_names})
    units.update({"x_lp": "m", "slip": "m"})
    notes.append("x_lp = the load-point displacement, slip = x - x(t0), both from the start of the run")
    used = {"law": law.name, "V_history": str(hist), "k": k, **params}
    if "F" in sim.state_names:
        notes.append("F = k (x_lp - x), the spring force" + (", and sigma the normal load that follows it"
                                                            if "sigma" in sim.state_names else ""))
    notes.append("mu = mu(v, phi), the law's friction coefficient; V the load-point velocity")
    return _finish(sim, law, used, units, notes, {"phase": (1, 2)})


def _history_stiffness(law, block, params, hist, notes: list) -> float:
    """k = 2 max k_c(V_i) (stable at every velocity of the history), else sigma/L."""
    from landau.errors import NoHopfError

    def kc_at(V):
        try:
            return _critical_stiffness(block, V, params)
        except NoHopfError:
            return float("nan")

    kcs = [kc_at(V) for V in set(hist.velocities) if V > 0]
    kcs = [kc for kc in kcs if math.isfinite(kc) and kc > 0]
    if kcs:
        k = 2.0 * max(kcs)
        notes.append(f"k = 2 max k_c(V_i) = {k:.6g} N/m: steady sliding is stable at every velocity of "
                     "the history (give k, --k, for another machine stiffness)")
        return k
    if "L" in params:
        k = params["sigma"] / params["L"]
        notes.append(f"k = sigma/L = {k:.6g} N/m (the law has no Hopf point at these velocities)")
        return k
    raise InputError("spring-block with a velocity history: give k (the law has no Hopf point and no L)")


__all__ = ["MAX_STEPS", "SECTION_LABEL", "STICK_FRACTION", "history_text", "law_state_units", "simulate"]
