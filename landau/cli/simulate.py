"""Simulate one of the toolkit's models and write its time series (CSV, NPZ) or a plot (PNG).

``landau simulate MODEL [LAW | --law NAME | --mu EXPR --state NAME=RATE ...] [--V V] [--k K]
--param NAME=VALUE ... --t-end T --out run.csv --out run.png [--json]``

Models (defaults: the published parameters):

* ``spring-block`` — the block on a driven spring with a rate-and-state law, eq. (4) of
  Putelat, Dawes & Willis (2010); ``--V`` driving velocity [m/s] (default 1e-4), ``--k``
  stiffness [N/m] (default 0.9 k_c(V), where steady sliding is unstable); starts from steady
  sliding displaced along the critical mode;
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

The output format follows each ``--out`` suffix: ``.csv`` (header ``t [s], name [unit]...``),
``.npz`` or ``.png`` (time series and phase portrait).  Exit 1 when the integrator fails.
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
#: accepted steps kept by the compiled integrators (spring-block, forced oscillator) as the time series
RECORD = 1_000_000


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
    from landau.verify.springblock.model import SpringBlockModel
    from landau.verify.springblock.simulate import W_INDEX, integrate

    if args.law is None and args.mu is None and not args.state:
        args.law = "dieterich"
    if any(it.split("=", 1)[0].strip() in ("V", "k") for it in args.param):
        raise InputError("spring-block: give the driving velocity as --V and the stiffness as --k "
                         "(k is the bifurcation parameter, not a law parameter)")
    law, overrides = resolve_law(args)
    block = SpringBlock(law)
    _only_known(overrides, list(block.defaults), "spring-block")
    params = block.resolve(overrides)
    V = _positive(args.V, "--V") if args.V is not None else 1e-4
    notes = []
    if args.k is None:
        kc = float(np.ravel(critical_stiffness(block, V, params))[0])
        if not (math.isfinite(kc) and kc > 0):
            raise InputError(f"spring-block: law {law.name!r} has no Hopf point at V = {V:g} m/s "
                             "(steady sliding is stable for every k): give --k")
        k = 0.9 * kc
        notes.append(f"k = 0.9 k_c(V) = {k:.6g} N/m (k_c = {kc:.6g} N/m; steady sliding is unstable below k_c)")
    else:
        k = _positive(args.k, "--k")
    model = SpringBlockModel.build(law, V, k, params)
    y0 = model.perturbed(0.01 * model.ell)
    # section events: the crossings of v = V (the extrema of X), marked in the phase portrait
    run = integrate(model, y0, (0.0, t_end), rtol=1e-9, record=RECORD, event_index=W_INDEX)
    sim = run.simulation("spring-block")
    phys = model.to_physical(sim.y.T)
    names = ("X", "v") + tuple(s.name for s in law.states)

    def physical(y):
        ph = model.to_physical(y)
        return np.array([float(ph[n]) for n in names])

    events = EventLog()
    for e in sim.events:  # the located X extrema, in physical units like the series
        events.append(replace(e, y=physical(e.y), y_after=physical(e.y)))
    sim = replace(sim, y=np.vstack([np.asarray(phys[n]) for n in names]), f=None, events=events,
                  y_final=physical(sim.y_final), state_names=names)
    units = {"X": "m", "v": "m/s"}
    used = {"law": law.name, "V": V, "k": k, **params}
    notes.append("X = x - x0(t) is the displacement from steady sliding; starts X = 0.01 L (the law's memory "
                 "length) off steady sliding along the critical mode")
    return sim, used, units, notes


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
    given_V = [it for it in args.param if it.split("=", 1)[0].strip() == "V"]
    if given_V:
        if V is not None or len(given_V) > 1:
            raise InputError(f"{name}: the belt velocity V is given twice")
        V = given_V[0].split("=", 1)[1]
    over = parse_params([it for it in args.param if it not in given_V])
    _only_known(over, known, name)
    if V is not None:
        over["V"] = _positive(V, "--V")
    if args.kinetic_pos is not None and args.kinetic is None:
        raise InputError(f"{name}: --kinetic-pos needs --kinetic (the r < 0 branch)")
    law = (KineticFriction() if args.kinetic is None
           else KineticFriction.from_expression(args.kinetic, args.kinetic_pos,   # parsed, never evaluated
                                                names=("--kinetic", "--kinetic-pos")))
    p = StickSlipParams(n=n, law=law).with_(**over)
    if not p.V > 0:
        raise InputError(f"{name}: belt velocity V must be > 0, got {p.V!r}")
    for side, r in (("--kinetic", -p.V), ("--kinetic-pos", p.V)):
        with np.errstate(all="ignore"):
            vals = p.law.neg(r * _R_PROBE) if side == "--kinetic" else p.law.pos(r * _R_PROBE)
        if not np.all(np.isfinite(vals)):
            raise InputError(f"{name}: the kinetic law's {side} branch is not finite on the slip velocities "
                             f"0 < |r| <= {p.V:g} ({p.law!r})")
    mode = "s" * n
    y0 = np.array([0.0] * n + [p.V] * n)
    sol = simulate(model_for(p), mode, y0, (0.0, t_end), FIG_STEPPER, EngineOptions(record=True, samples=8))
    names = ("X", "Xdot") if n == 1 else ("X1", "X2", "X1dot", "X2dot")
    sim = replace(sol.simulation(name), state_names=names)
    used = {k: getattr(p, k) for k in known}
    notes = ["dimensionless time and displacements; starts stuck at X = 0"]
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
    return sim, used, {"t": "1"}, notes


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
    y0 = slip_state(cm.mech, S.equilibrium_phi(p, None, s, law, None, v) + 1e-3)
    sol = simulate(cm.model, cm.initial_mode(0.0, y0), y0, (0.0, t_end), CompiledDOP853(1e-10, 1e-12),
                   default_options(record=True))
    sim = replace(sol.simulation(name), state_names=("phi", "y", "phidot", "ydot"))
    units = {"phi": "rad", "y": "m", "phidot": "rad/s", "ydot": "m/s"}
    used = {**law.defaults(), "eN": eN, "v_belt": v, **p}
    if args.friction is not None:
        used["friction"] = f"{law.positive} (v > 0), {law.branch(-1)} (v < 0)"
    return sim, used, units, ["starts on the belt 1e-3 rad off the slip equilibrium"]


def _forced_oscillator(args, t_end: float):
    from landau.cli.common import velocity_law_from_args
    from landau.laws.velocity import regularised_coulomb
    from landau.verify.skurativskyi.approx import grazing_linear, static_equilibrium
    from landau.verify.skurativskyi.model import MECHANICAL, Params
    from landau.verify.skurativskyi.simulate import run

    name = "forced-oscillator"
    _no_law(args, name)
    over = parse_params(args.param)
    # the friction F_R(v) [N]: the paper's regularised Coulomb law (c, T, eps by --param) or --friction
    law = velocity_law_from_args(args, regularised_coulomb(), over, quantity="force")
    _only_known(over, list(MECHANICAL) + [q.name for q in law.parameters], name)
    p = Params(friction=law).with_(**over)
    if p.xI < 0:  # the springs press the cart on the obstacle: rest is the static equilibrium in contact
        y0, note = None, "starts at rest at the static equilibrium (in contact)"
    else:  # the obstacle is not touched at rest
        y0, note = np.zeros(2), "starts at rest at x = 0 (free of the obstacle)"
    r = run(p, t_end / p.period, y0=y0, record=RECORD)
    sim = replace(r.simulation(), model=name)
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
    return sim, used, {"x": "m", "xdot": "m/s"}, notes


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


def run(args) -> dict:
    outs = [Path(o) for o in args.out]
    for o in outs:
        if o.suffix.lower() not in FORMATS:
            raise InputError(f"--out {str(o)!r}: unknown format {o.suffix!r} (use {', '.join(FORMATS)})")
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
    if sim.success and any(o.suffix.lower() == ".png" for o in outs):
        period = 2 * math.pi / params["omega"] if args.model == "forced-oscillator" else None
        try:
            fig = sim.plot(args.plot, units=units, phase=PHASE_PLANE.get(args.model, (0, 1)),
                           period=period if args.plot == "poincare" else None)
        except ValueError as exc:
            raise InputError(f"--plot {args.plot}: {args.model}: {str(exc).split(':')[0]}") from None
    if sim.success:
        for o in outs:
            suf = o.suffix.lower()
            if suf == ".csv":
                sim.to_csv(o, units)
            elif suf == ".npz":
                sim.to_npz(o)
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
        lines.append(f"integrator failed: {doc['message']}")
    lines.append("parameters: " + ", ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}"
                                            for k, v in doc["parameters"].items()))
    units = doc["units"]
    lines.append("final state: " + ", ".join(
        f"{k} = {v:.6g}" + (f" {units[k]}" if k in units else "") for k, v in doc["final_state"].items()))
    lines += doc["notes"]
    if doc["files"]:
        lines.append("wrote " + ", ".join(doc["files"]))
    return "\n".join(lines) + "\n"
