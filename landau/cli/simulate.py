"""Simulate one of the toolkit's models and write its time series (CSV, NPZ) or a plot (PNG).

``landau simulate MODEL [LAW | --law NAME | --mu EXPR --state NAME=RATE ...] [--V V] [--k K]
--param NAME=VALUE ... --t-end T --out run.csv --out run.png [--json]``

Models (defaults: the published parameters):

* ``spring-block`` — the block on a driven spring with a rate-and-state law, eq. (4) of
  Putelat, Dawes & Willis (2010); ``--V`` driving velocity [m/s] (default 1e-4), ``--k``
  stiffness [N/m] (default 0.9 k_c(V), where steady sliding is unstable); starts from steady
  sliding displaced along the critical mode; ``--param M=0 --param eta=...`` is the
  quasi-dynamic cell (the force balance solved for the slip rate; CSV X, v, mu and the states);
* ``galvanetto-one-block``, ``galvanetto-two-blocks`` — the dimensionless stick–slip models of
  Galvanetto (2004), started stuck at the origin; kinetic friction eq. (7) or the user's law
  ``--kinetic EXPR`` (branch r < 0 in the relative velocity r = Ẋ − V and the parameters
  gamma, delta; ``--kinetic-pos EXPR`` the r > 0 branch, default the odd reflection);
  ``--hopf`` (one block) adds the Hopf point c₁ of the damped block, ω and the criticality;
* ``impact-oscillator`` — the frictional impact oscillator (a bar on a moving belt) of
  Lancioni, Lenci & Galvanetto, parameter set 1, belt speed ``v_belt`` −1 m/s, Coulomb friction coefficient ``mu``
  (default 0.42, above the Hopf point) or your law ``--friction EXPR`` with its ``--param`` values,
  started near the slip equilibrium;
* ``forced-oscillator`` — the forced cart with Hertz contact of Skurativskyi, Kudra,
  Witkowski & Awrejcewicz (2019), identified parameters, started at rest; its friction is the
  paper's regularised Coulomb law (c, T, eps by ``--param``) or yours, ``--friction EXPR`` in
  the sliding velocity ``v`` [N] with its parameters by ``--param`` (the notes give the
  linearised grazing estimate of their Sec. 5 for that law).

``spring-block LAW --V-history "V0@t0,V1@t1,..."`` drives the load point at a piecewise-constant
velocity instead (velocity steps, slide-hold-slide; starts from steady sliding at V0); its CSV
holds t, the load-point velocity V, the slip rate v, the friction coefficient mu and the states
(with ``eta`` or ``gamma_ld`` also the spring force F and, with ``gamma_ld``, the normal load sigma).

The output format follows each ``--out`` suffix: ``.csv`` (header ``t [s], name [unit]...``),
``.npz`` or ``.png`` (time series with the regimes shaded and the phase portrait, or the
Poincaré section; ``--discard T`` leaves out t < T).  Every run is bounded: at ``--max-steps``
(or the event and memory bounds) it ends with a named status, exit 1, and the files hold the
run up to there.  Exit 1 when the integrator fails.
"""

from __future__ import annotations

import difflib
import math
from dataclasses import replace
from pathlib import Path

import numpy as np

from landau.cli.common import add_friction_arguments, add_law_arguments, parse_params
from landau.errors import InputError

MODELS = ("spring-block", "galvanetto-one-block", "galvanetto-two-blocks", "impact-oscillator",
          "forced-oscillator")
FORMATS = (".csv", ".npz", ".png")
#: default final time per model (seconds; Galvanetto: dimensionless time)
DEFAULT_T_END = {"spring-block": 20.0, "galvanetto-one-block": 60.0, "galvanetto-two-blocks": 60.0,
                 "impact-oscillator": 10.0, "forced-oscillator": 10.0}
#: state components drawn in the phase portrait (position against its velocity); default (0, 1)
PHASE_PLANE = {"galvanetto-two-blocks": (0, 2), "impact-oscillator": (0, 2)}
#: default step budget per model (``--max-steps``): a run that reaches it ends with status max-steps,
#: exit 1 and the series up to there written (about 1–3 minutes of CPU time each)
MAX_STEPS = {"spring-block": 5_000_000, "galvanetto-one-block": 300_000, "galvanetto-two-blocks": 300_000,
             "impact-oscillator": 300_000, "forced-oscillator": 5_000_000}
#: events kept by the hybrid models' runs (the run ends with status max-events past it)
MAX_EVENTS = 200_000
#: recorded points kept (decimated past it) by the spring-block and the hybrid models
MAX_POINTS = 200_000
#: state names and units of the hybrid and compiled models
STATE_UNITS = {"impact-oscillator": {"phi": "rad", "y": "m", "phidot": "rad/s", "ydot": "m/s"},
               "forced-oscillator": {"x": "m", "xdot": "m/s"}}


def configure(p) -> None:
    p.add_argument("model", help=f"one of {', '.join(MODELS)}")
    add_law_arguments(p)  # positional LAW after MODEL (spring-block only), --mu, --state, --param
    add_friction_arguments(p)  # --friction EXPR, --friction-neg, --friction-name (impact and forced oscillators)
    p.add_argument("--law", dest="law_option", default=None, metavar="NAME",
                   help="spring-block: built-in law (same as the positional LAW; default dieterich)")
    p.add_argument("--V", default=None, help="spring-block: driving velocity in m/s (default 1e-4); "
                                              "galvanetto models: belt velocity (dimensionless, default 0.25)")
    p.add_argument("--k", default=None, help="spring-block: spring stiffness in N/m (default 0.9 k_c(V))")
    p.add_argument("--t-end", default=None,
                   help="final time (s; dimensionless for the Galvanetto models); default per model: "
                        + ", ".join(f"{m} {t:g}" for m, t in DEFAULT_T_END.items()))
    p.add_argument("--out", action="append", default=[], metavar="FILE",
                   help="output file, format from the suffix (.csv, .npz, .png); repeatable")
    p.add_argument("--kinetic", default=None, metavar="EXPR",
                   help="galvanetto models: kinetic friction for r = Xdot - V < 0 in r, gamma, delta, "
                        "e.g. '(1 - delta)*exp(gamma*r) + delta' (default Galvanetto 2004 eq. 7)")
    p.add_argument("--kinetic-pos", default=None, metavar="EXPR",
                   help="galvanetto models: the r > 0 branch (default the odd reflection of --kinetic)")
    p.add_argument("--hopf", action="store_true",
                   help="galvanetto-one-block: also give the damped block's Hopf point c1, omega and criticality")
    p.add_argument("--max-steps", default=None, metavar="N",
                   help="step budget of the run; at it the run ends with status max-steps (exit 1) and the "
                        "series up to there is written (default per model: "
                        + ", ".join(f"{m} {n:g}" for m, n in MAX_STEPS.items()) + ")")
    p.add_argument("--y0", default=None, metavar="VALUES",
                   help="initial state, comma-separated in the order and units of the CSV columns "
                        "(spring-block: X [m], v [m/s], the law's states; galvanetto: positions then velocities; "
                        "impact-oscillator: phi, y, phidot, ydot; forced-oscillator: x, xdot)")
    p.add_argument("--discard", default=None, metavar="T",
                   help="leave out the transient t < T from what is written (CSV, NPZ and plots: the Poincaré "
                        "section keeps the attractor)")
    p.add_argument("--V-history", dest="V_history", default=None, metavar="V0@t0,V1@t1,...",
                   help="spring-block: drive the load point at velocity V_i [m/s] from time t_i [s] on (0: a hold), "
                        "starting from steady sliding at V0: velocity steps, slide-hold-slide; the CSV has "
                        "t, V, v, mu and the states (with eta or gamma_ld also F and sigma)")
    p.add_argument("--plot", choices=("overview", "poincare"), default="overview",
                   help="what a .png shows: time series and phase portrait (default) or the Poincaré section "
                        "(the logged sections; the forced oscillator: stroboscopic at the forcing period)")


def _positive(text, what: str) -> float:
    try:
        x = float(text)
    except (TypeError, ValueError):
        raise InputError(f"{what}: {text!r} is not a number") from None
    if not (math.isfinite(x) and x > 0):
        raise InputError(f"{what} must be a finite number > 0, got {text!r}")
    return x


def _only_known(params: dict, known, model: str) -> None:
    unknown = sorted(set(params) - set(known))
    if unknown:
        raise InputError(f"{model}: unknown parameter(s) {', '.join(unknown)} (known: {', '.join(known)})")


def _no_law(args, model: str) -> None:
    if args.law is not None or args.mu is not None or args.state or args.V is not None or args.k is not None:
        raise InputError(f"{model}: LAW, --mu, --state, --V and --k apply to spring-block only")


# --- the models -----------------------------------------------------------------------
def _spring_block(args, t_end: float):
    from landau.cli.common import resolve_law
    from landau.derivation.linear import critical_stiffness
    from landau.systems.system import SpringBlock
    from landau.verify.hybrid import EventLog
    from landau.verify.hybrid.plotting import regimes_from_mask
    from landau.verify.springblock.model import SpringBlockModel
    from landau.verify.springblock.simulate import W_INDEX, record_run

    if args.law is None and args.mu is None and not args.state:
        args.law = "dieterich"
    if any(it.split("=", 1)[0].strip() in ("V", "k") for it in args.param):
        raise InputError("spring-block: give the driving velocity as --V and the stiffness as --k "
                         "(k is the bifurcation parameter, not a law parameter)")
    law, overrides = resolve_law(args)
    block = SpringBlock.for_params(law, overrides)   # with the optional terms given (eta, gamma_ld, alpha_ld)
    _only_known(overrides, list(block.defaults), "spring-block")
    params = block.resolve(overrides)
    if args.V_history is not None:
        return _load_history(args, law, params, t_end)
    V = _positive(args.V, "--V") if args.V is not None else 1e-4
    notes = []
    if args.k is None:
        if "alpha_ld" in block.terms:
            from landau.derivation.springblock_routes import hopf_point

            kc = hopf_point(block, V, params).p_c
        else:
            kc = float(np.ravel(critical_stiffness(block, V, params))[0])
        if not (math.isfinite(kc) and kc > 0):
            raise InputError(f"spring-block: law {law.name!r} has no Hopf point at V = {V:g} m/s "
                             "(steady sliding is stable for every k): give --k")
        k = 0.9 * kc
        notes.append(f"k = 0.9 k_c(V) = {k:.6g} N/m (k_c = {kc:.6g} N/m; steady sliding is unstable below k_c)")
    else:
        k = _positive(args.k, "--k")
    if params["M"] == 0:
        return _quasidynamic(args, law, V, k, params, t_end, notes)
    model = SpringBlockModel.build(law, V, k, params)
    names = ("X", "v") + tuple(s.name for s in law.states)
    if args.y0 is not None:
        vals = _y0(args.y0, names)
        try:
            y0 = model.from_physical(vals[0], vals[1], vals[2:])
        except InputError as exc:
            raise InputError(f"--y0: {exc}") from None
        start = "starts at --y0"
    else:
        y0 = model.perturbed(0.01 * model.ell)
        start = "starts X = 0.01 L (the law's memory length) off steady sliding along the critical mode"
    # section events: the crossings of v = V (the extrema of X); the Poincaré section keeps the upward ones
    sim = record_run(model, y0, (0.0, t_end), rtol=1e-9, max_steps=_max_steps(args), max_points=MAX_POINTS,
                     event_index=W_INDEX if args.plot == "poincare" else -1)
    phys = model.to_physical(sim.y.T)

    def physical(y):
        ph = model.to_physical(y)
        return np.array([float(ph[n]) for n in names])

    events = EventLog()
    for e in sim.events:  # the located minima of X (v = V, rising), in physical units like the series
        if e.note == "up":
            events.append(replace(e, y=physical(e.y), y_after=physical(e.y)))
    v = np.asarray(phys["v"])
    up = sim.event_dir > 0   # the record's crossing arrays follow its events (physical, rising)
    sim = replace(sim, y=np.vstack([np.asarray(phys[n]) for n in names]), f=None, events=events,
                  y_final=physical(sim.y_final), state_names=names,
                  regimes=regimes_from_mask(sim.t, v < STICK_FRACTION * V, "stick (v < V/100)", "slip"),
                  event_t=sim.event_t[up], event_y=np.array([e.y for e in events]).reshape(-1, len(names)),
                  event_dir=sim.event_dir[up])
    units = {"X": "m", "v": "m/s", **law_state_units(law)}
    used = {"law": law.name, "V": V, "k": k, **params}
    notes.append("X = x - x0(t) is the displacement from steady sliding; " + start)
    return sim, used, units, notes


#: the spring–block's "stick" phases shaded in its plots: slip rate below this fraction of V
STICK_FRACTION = 0.01


def _quasidynamic(args, law, V, k, params, t_end, notes):
    """``spring-block --param M=0 --param eta=...``: the quasi-dynamic cell (force balance solved for v)."""
    from landau.verify.hybrid.plotting import regimes_from_mask
    from landau.verify.springblock.quasidynamic import QuasiDynamicCell, simulate_quasidynamic

    cell = QuasiDynamicCell.build(law, V, k, params)
    if args.y0 is not None:
        names = ("X",) + tuple(s.name for s in law.states)
        vals = _y0(args.y0, names)
        try:
            y0 = cell.from_physical(vals[0], vals[1:])
        except InputError as exc:
            raise InputError(f"--y0: {exc}") from None
        start = "starts at --y0 (X and the states; v follows from the force balance)"
    else:
        y0 = None
        start = "starts X = 0.01 L (the law's memory length) off steady sliding along the critical mode"
    sim = simulate_quasidynamic(law, V, k, cell, t_end, y0, rtol=1e-9, max_steps=_max_steps(args),
                                max_points=MAX_POINTS, sections=args.plot == "poincare")
    v = sim.y[1]
    sim = replace(sim, regimes=regimes_from_mask(sim.t, v < STICK_FRACTION * V, "stick (v < V/100)", "slip"))
    units = {"X": "m", "v": "m/s", "mu": "1", **law_state_units(law)}
    used = {"law": law.name, "V": V, "k": k, **params}
    notes.append("quasi-dynamic (M = 0): the slip rate v solves k(Vt - x) = sigma mu(v, phi) + eta v at every "
                 "instant; X = x - x0(t) is the displacement from steady sliding; " + start)
    return sim, used, units, notes


def _load_history(args, law, params, t_end_given):
    """``spring-block LAW --V-history ...``: the load point driven by a velocity history."""
    from landau.derivation.linear import critical_stiffness
    from landau.systems.system import SpringBlock
    from landau.verify.springblock.history import parse_history, simulate_history

    if args.V is not None:
        raise InputError("spring-block: --V-history gives the load-point velocities; leave out --V")
    if args.y0 is not None:
        raise InputError("spring-block: --V-history starts from steady sliding at its first velocity; "
                         "leave out --y0")
    hist = parse_history(args.V_history)
    notes = [f"load point: {hist} (m/s @ s); starts from steady sliding at V = {hist.velocities[0]:g} m/s"]
    if args.k is None:
        block = SpringBlock.for_params(law, params)   # with the optional terms given (eta, gamma_ld, alpha_ld)

        def kc_at(V):
            if "alpha_ld" not in block.terms:
                return float(np.ravel(critical_stiffness(block, V, params))[0])
            from landau.derivation.springblock_routes import hopf_point
            from landau.errors import NoHopfError

            try:
                return hopf_point(block, V, params).p_c
            except NoHopfError:
                return float("nan")

        kcs = [kc_at(V) for V in set(hist.velocities) if V > 0]
        kcs = [kc for kc in kcs if math.isfinite(kc) and kc > 0]
        if kcs:
            k = 2.0 * max(kcs)
            notes.append(f"k = 2 max k_c(V_i) = {k:.6g} N/m: steady sliding is stable at every velocity of "
                         "the history (give --k for another machine stiffness)")
        elif "L" in params:
            k = params["sigma"] / params["L"]
            notes.append(f"k = sigma/L = {k:.6g} N/m (the law has no Hopf point at these velocities)")
        else:
            raise InputError("spring-block --V-history: give --k (the law has no Hopf point and no L)")
    else:
        k = _positive(args.k, "--k")
    t_end = t_end_given if args.t_end is not None else None
    sim = simulate_history(law, hist, k, params, t_end)
    units = {"V": "m/s", "v": "m/s", "mu": "1", **law_state_units(law)}
    units.update({nm: "N" for nm in ("F", "sigma") if nm in sim.state_names})
    used = {"law": law.name, "V_history": str(hist), "k": k, **params}
    if "F" in sim.state_names:
        notes.append("F = k (x_lp - x), the spring force" + (", and sigma the normal load that follows it"
                                                            if "sigma" in sim.state_names else ""))
    notes.append("mu = mu(v, phi), the law's friction coefficient; V the load-point velocity")
    return sim, used, units, notes


def law_state_units(law) -> dict:
    """The units of the law's states, inferred by dimensional analysis (:func:`infer_state_units`)."""
    from landau.verify.springblock.units import infer_state_units

    return infer_state_units(law)


def _y0(text: str, names) -> np.ndarray:
    """``--y0 a,b,...``: one finite number per state, in the order of ``names``."""
    try:
        vals = np.array([float(x) for x in str(text).split(",")])
    except ValueError:
        raise InputError(f"--y0 {text!r}: give {len(names)} comma-separated numbers ({', '.join(names)})") from None
    if vals.shape != (len(names),) or not np.all(np.isfinite(vals)):
        raise InputError(f"--y0 {text!r}: give {len(names)} finite numbers ({', '.join(names)})")
    return vals


def _max_steps(args) -> int:
    if args.max_steps is None:
        return MAX_STEPS[args.model]
    try:
        n = float(args.max_steps)
    except ValueError:
        n = float("nan")
    if not (math.isfinite(n) and n >= 1 and n == int(n)):
        raise InputError(f"--max-steps must be a whole number >= 1, got {args.max_steps!r}")
    return int(n)


def _galvanetto(args, t_end: float, n: int):
    from landau.laws.kinetic import KineticFriction
    from landau.verify.galvanetto.analysis import FIG_STEPPER
    from landau.verify.galvanetto.maps import model_for
    from landau.verify.galvanetto.model import StickSlipParams
    from landau.verify.hybrid import EngineOptions, simulate

    name = MODELS[n]
    V, args.V = args.V, None   # --V (or --param V=...) is the (dimensionless) belt velocity here
    _no_law(args, name)
    known = ["V", "gamma", "delta", "c"] + (["alpha", "beta"] if n == 2 else [])
    own: set[str] = set()   # a user's law may have parameters of its own (--param eta=0.05)
    if args.kinetic is not None:
        from landau.laws.parse import referenced_names

        own = referenced_names(args.kinetic, what="--kinetic") | (
            referenced_names(args.kinetic_pos, what="--kinetic-pos") if args.kinetic_pos is not None else set())
    given_V = [it for it in args.param if it.split("=", 1)[0].strip() == "V"]
    if given_V:
        if V is not None or len(given_V) > 1:
            raise InputError(f"{name}: the belt velocity V is given twice")
        V = given_V[0].split("=", 1)[1]
    over = parse_params([it for it in args.param if it not in given_V])
    _only_known(over, known + sorted(own - set(known) - {"r"}), name)
    if V is not None:
        over["V"] = _positive(V, "--V")
    if args.kinetic_pos is not None and args.kinetic is None:
        raise InputError(f"{name}: --kinetic-pos needs --kinetic (the r < 0 branch)")
    extra = {k: over.pop(k) for k in list(over) if k in own and k not in ("V", "gamma", "delta", "c", "alpha", "beta")}
    law = (KineticFriction() if args.kinetic is None
           else KineticFriction.from_expression(args.kinetic, args.kinetic_pos,   # parsed, never evaluated
                                                names=("--kinetic", "--kinetic-pos"), **extra))
    p = StickSlipParams(n=n, law=law).with_(**over)
    if not p.V > 0:
        raise InputError(f"{name}: belt velocity V must be > 0, got {p.V!r}")
    for side, r in (("--kinetic", -p.V), ("--kinetic-pos", p.V)):
        with np.errstate(all="ignore"):
            vals = p.law.neg(r * _R_PROBE) if side == "--kinetic" else p.law.pos(r * _R_PROBE)
        if not np.all(np.isfinite(vals)):
            raise InputError(f"{name}: the kinetic law's {side} branch is not finite on the slip velocities "
                             f"0 < |r| <= {p.V:g} ({p.law!r})")
    names = ("X", "Xdot") if n == 1 else ("X1", "X2", "X1dot", "X2dot")
    if args.y0 is not None:
        y0 = _y0(args.y0, names)
        # each block sticks where it moves with the belt, else slips on the side of its relative velocity
        mode = "".join("s" if y0[n + i] == p.V else ("n" if y0[n + i] < p.V else "p") for i in range(n))
        start = f"starts at --y0 in mode {mode!r} (s: stuck, n/p: slipping with r = Xdot - V < 0 / > 0)"
    else:
        mode = "s" * n
        y0 = np.array([0.0] * n + [p.V] * n)
        start = "starts stuck at X = 0"
    sol = simulate(model_for(p), mode, y0, (0.0, t_end), FIG_STEPPER,
                   EngineOptions(record=True, samples=8, max_steps=_max_steps(args), max_events=MAX_EVENTS,
                                 max_samples=MAX_POINTS))
    sim = replace(sol, model=name, state_names=names)
    used = {k: getattr(p, k) for k in known}
    used.update(extra)
    notes = ["dimensionless time and displacements; " + start]
    if not p.law.is_paper_law:
        used["kinetic"] = str(p.law.neg_expr)
        used["kinetic_pos"] = str(p.law.pos_expr)
        notes.append(f"kinetic friction: {p.law!r}")
    if args.hopf:
        if n != 1:
            raise InputError(f"{name}: --hopf applies to galvanetto-one-block (the damped one block)")
        used["hopf"] = _galvanetto_hopf(p)
        h = used["hopf"]
        notes.append(f"damped one block at V = {p.V:g}: Hopf point c1 = {h['c1']:.10g} (omega = {h['omega']:.6g}), "
                     f"{h['criticality']}" if h["c1"] is not None else h["note"])
    return sim, used, {"t": "1", **{nm: "1" for nm in names}}, notes   # dimensionless (Galvanetto 2004, eq. 1)


#: fractions of the belt velocity where a user's kinetic branch is checked to be finite
_R_PROBE = np.array([1e-9, 1e-3, 0.25, 0.5, 0.75, 1.0])


def _galvanetto_hopf(p) -> dict:
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


def _impact_oscillator(args, t_end: float):
    from landau.cli.common import velocity_law_from_args
    from landau.laws.velocity import coulomb
    from landau.verify.hybrid import simulate
    from landau.verify.hybrid.dop853 import CompiledDOP853
    from landau.verify.lancioni import slip as S
    from landau.verify.lancioni.contact import default_options
    from landau.verify.lancioni.model import ConstantBelt, build, slip_state

    name = "impact-oscillator"
    _no_law(args, name)
    over = parse_params(args.param)
    law = velocity_law_from_args(args, coulomb(over.get("mu", 0.42)), over)
    known = ["eN", "v_belt"] + list(S.PARAM_NAMES)
    _only_known(over, known, name)
    eN, v = over.pop("eN", 0.0), over.pop("v_belt", -1.0)
    if not (math.isfinite(v) and v != 0):
        raise InputError(f"{name}: v_belt must be a nonzero belt velocity (m/s), got {v!r}")
    p = S.resolve(over)
    cm = build(None, eN, p, ConstantBelt(v), friction=law)
    s = 1 if v < 0 else -1
    names = ("phi", "y", "phidot", "ydot")
    if args.y0 is not None:
        y0 = _y0(args.y0, names)
        start = "starts at --y0"
    else:
        y0 = slip_state(cm.mech, S.equilibrium_phi(p, None, s, law, None, v) + 1e-3)
        start = "starts on the belt 1e-3 rad off the slip equilibrium"
    sol = simulate(cm.model, cm.initial_mode(0.0, y0), y0, (0.0, t_end), CompiledDOP853(1e-10, 1e-12),
                   default_options(record=True, max_steps=_max_steps(args), max_events=MAX_EVENTS,
                                   max_samples=MAX_POINTS))
    sim = replace(sol, model=name, state_names=names)
    units = dict(STATE_UNITS[name])
    used = {**law.defaults(), "eN": eN, "v_belt": v, **p}
    if args.friction is not None:
        used["friction"] = f"{law.positive} (v > 0), {law.branch(-1)} (v < 0)"
    return sim, used, units, [start]


def _forced_oscillator(args, t_end: float):
    from landau.cli.common import velocity_law_from_args
    from landau.laws.velocity import regularised_coulomb
    from landau.verify.skurativskyi.approx import grazing_linear, static_equilibrium
    from landau.verify.skurativskyi.model import MECHANICAL, Params
    from landau.verify.skurativskyi.simulate import record_run

    name = "forced-oscillator"
    _no_law(args, name)
    over = parse_params(args.param)
    # the friction F_R(v) [N]: the paper's regularised Coulomb law (c, T, eps by --param) or --friction
    law = velocity_law_from_args(args, regularised_coulomb(), over, quantity="force")
    _only_known(over, list(MECHANICAL) + [q.name for q in law.parameters], name)
    p = Params(friction=law).with_(**over)
    if args.y0 is not None:
        y0, note = _y0(args.y0, ("x", "xdot")), "starts at --y0"
    elif p.xI < 0:  # the springs press the cart on the obstacle: rest is the static equilibrium in contact
        y0, note = None, "starts at rest at the static equilibrium (in contact)"
    else:  # the obstacle is not touched at rest
        y0, note = np.zeros(2), "starts at rest at x = 0 (free of the obstacle)"
    sim = replace(record_run(p, t_end, y0, max_steps=_max_steps(args), max_points=MAX_POINTS), model=name)
    used = {"friction": law.name, **p.values()}
    neg = "the odd extension -F(-v)" if law.negative is None else str(law.branch(-1))
    notes = [note, f"friction F_R(v) = {law.branch(1)} [N] for v > 0, {neg} for v < 0"]
    if p.xI < 0:
        # the Sec. 5 estimate of the first grazing, damped with the law's viscous coefficient
        try:
            notes.append(f"linearised grazing estimate (Skurativskyi et al. 2019, Sec. 5, eq. 4) with X0 = "
                         f"{static_equilibrium(p):.6g} m and the law's viscous coefficient "
                         f"{p.linear_damping:.6g} N s/m: omega = {grazing_linear(p):.6g} rad/s")
        except InputError as exc:
            notes.append(f"no linearised grazing estimate: {exc}")
    return sim, used, dict(STATE_UNITS[name]), notes


def simulate_model(args):
    """Run the model named in ``args``; returns (Simulation, parameters, units, notes)."""
    model = args.model
    if args.law_option is not None:
        if args.law is not None and args.law != args.law_option:
            raise InputError(f"two laws given: {args.law!r} and --law {args.law_option!r}")
        args.law = args.law_option
    if model not in MODELS:
        close = difflib.get_close_matches(model, MODELS, n=1)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise InputError(f"unknown model {model!r} (known: {', '.join(MODELS)}){hint}")
    t_end = _positive(args.t_end, "--t-end") if args.t_end is not None else DEFAULT_T_END[model]
    if model == "spring-block":
        return _spring_block(args, t_end)
    if model.startswith("galvanetto"):
        return _galvanetto(args, t_end, 1 if model.endswith("one-block") else 2)
    if args.kinetic is not None or args.kinetic_pos is not None or args.hopf:
        raise InputError(f"{model}: --kinetic, --kinetic-pos and --hopf apply to the galvanetto models only")
    if model == "impact-oscillator":
        return _impact_oscillator(args, t_end)
    return _forced_oscillator(args, t_end)


#: what the Poincaré section of each model is (the legend of ``--plot poincare``)
SECTION_LABEL = {"spring-block": "v = V with v rising (X minimal)"}


def run(args) -> dict:
    outs = [Path(o) for o in args.out]
    for o in outs:
        if o.suffix.lower() not in FORMATS:
            raise InputError(f"--out {str(o)!r}: unknown format {o.suffix!r} (use {', '.join(FORMATS)})")
    discard = None if args.discard is None else _positive(args.discard, "--discard")
    if args.V_history is not None and args.model != "spring-block":
        raise InputError(f"{args.model}: --V-history applies to spring-block only")
    from landau.support.progress import progress, set_quiet

    set_quiet(getattr(args, "json", False))
    with progress(total=1, desc=f"simulate {args.model}", unit="run") as bar:   # a status line on a terminal
        sim, params, units, notes = simulate_model(args)
        bar.update()
    extra = {"hopf": params.pop("hopf")} if "hopf" in params else {}   # galvanetto-one-block --hopf
    files = []
    if len(sim.t) and sim.t[-1] < sim.t_final:
        notes.append(f"the time series holds the first {len(sim.t)} steps only (up to t = {sim.t[-1]:.6g}): "
                     "shorten --t-end for the whole run")
    if not sim.success:
        notes.append(f"the run ended at its limit ({sim.status.value}) at t = {sim.t_final:.6g}: the files hold "
                     "the run up to there" + (" (raise --max-steps or shorten --t-end for more)"
                                              if sim.status.value == "max-steps" else ""))
    written = sim
    if discard is not None:
        try:
            written = sim.after(discard)
        except ValueError as exc:
            raise InputError(f"--discard {args.discard}: {exc}") from None
        notes.append(f"t < {discard:g} discarded from the files (transient)")
    has_data = len(written.t) > 0
    if has_data and any(o.suffix.lower() == ".png" for o in outs):
        from matplotlib.figure import Figure  # a figure pyplot never shows: the command only saves it

        period = 2 * math.pi / params["omega"] if args.model == "forced-oscillator" else None
        phase = (1, 2) if args.V_history is not None else PHASE_PLANE.get(args.model, (0, 1))
        if args.plot == "poincare" and args.model == "spring-block":
            # v = V on the section: X against the first state (after mu in the quasi-dynamic series)
            phase = (0, 3) if "mu" in sim._names() else (0, 2)
        try:
            size = (11, max(4.5, 1.7 * len(sim._names()) + 0.8)) if args.plot == "overview" else (6.0, 4.8)
            fig = sim.plot(args.plot, discard=discard or 0.0, units=units, phase=phase,
                           period=period if args.plot == "poincare" else None,
                           section_label=SECTION_LABEL.get(args.model), fig=Figure(figsize=size, layout="constrained"))
        except ValueError as exc:
            raise InputError(f"--plot {args.plot}: {args.model}: {str(exc).split(':')[0]}") from None
    if has_data:
        for o in outs:
            suf = o.suffix.lower()
            if suf == ".csv":
                written.to_csv(o, units)
            elif suf == ".npz":
                written.to_npz(o)
            else:
                from landau.support.io import atomic_savefig

                atomic_savefig(fig, o, dpi=110)
            files.append(str(o))
    return {"model": args.model, "parameters": params, "units": {k: v for k, v in units.items() if k != "t"},
            "status": sim.status.value, "message": sim.message, "t_final": sim.t_final,
            "points": len(sim.t), "events": len(sim.events), "steps": sim.nsteps,
            "state_names": list(sim._names()),
            "final_state": dict(zip(sim._names(), (float(v) for v in np.ravel(sim.y_final)), strict=True)),
            "notes": notes, "files": files, **extra, "exit_code": 0 if sim.success else 1}


def render(doc: dict) -> str:
    lines = [f"model {doc['model']}: {doc['status']} at t = {doc['t_final']:.6g} "
             f"({doc['points']} points, {doc['events']} events, {doc['steps']} steps)"]
    if doc["exit_code"]:
        lines.append(f"run stopped ({doc['status']}): {doc['message']}")
    lines.append("parameters: " + ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
                                            for k, v in doc["parameters"].items()))
    units = doc["units"]
    lines.append("final state: " + ", ".join(
        f"{k} = {v:.6g}" + (f" {units[k]}" if units.get(k, "1") != "1" else "") for k, v in doc["final_state"].items()))
    lines += doc["notes"]
    if doc["files"]:
        lines.append("wrote " + ", ".join(doc["files"]))
    return "\n".join(lines) + "\n"
