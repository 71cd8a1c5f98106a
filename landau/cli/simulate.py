"""Simulate one of the toolkit's models and write its time series (CSV, NPZ) or a plot (PNG).

``landau simulate MODEL [LAW | --law NAME | --mu EXPR --state NAME=RATE ...] [--V V] [--k K]
--param NAME=VALUE ... --t-end T [--dt DT | --samples N] --out run.csv --out run.png [--json]``

The command is a shell around :func:`landau.simulate`: it reads the arguments, asks the model (found
by name in :mod:`landau.models`) for its run, and writes the files and the JSON document.

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
  linearised grazing estimate of their Sec. 5 for that law);
* ``mode-coupling`` — the mass on a belt of Hoffmann, Fischer, Allgaier & Gaul (2002) (friction-induced
  flutter), Coulomb ``mu`` 0.9 (above the flutter onset) or ``--friction EXPR`` in v_rel, the contact law
  ``--contact linear|cubic|hertz``, started near steady sliding: the contact opens (flight) and the mass
  sticks as the flutter grows (angles ``alpha1``, ``alpha2`` in degrees).

``spring-block LAW --V-history "V0@t0,V1@t1,..."`` drives the load point at a piecewise-constant
velocity instead (velocity steps, slide-hold-slide; starts from steady sliding at V0); its CSV
holds t, the load-point velocity V, the slip rate v, the friction coefficient mu and the states
(with ``eta`` or ``gamma_ld`` also the spring force F and, with ``gamma_ld``, the normal load sigma),
the load-point displacement x_lp and the slip; its figure is friction against load-point
displacement.  ``--param M=0`` without ``eta`` is the quasi-static run of the laboratory models;
``--preset lab`` is that run per unit normal stress in the lab's units (``--k`` k' in 1/um, velocities
in um/s, lengths in um), and under either preset values may carry units (``--k 1e-3/um``,
``--V-history "1um/s@0,10um/s@10"``, ``--param L=10um``).

The output format follows each ``--out`` suffix: ``.csv`` (header ``t [s], name [unit]...``),
``.npz`` or ``.png`` (time series with the regimes shaded and the phase portrait, or the
Poincaré section; ``--discard T`` leaves out t < T).  ``--dt DT`` or ``--samples N`` give the series
on a uniform grid of times (from the integrator's dense output where the model has one, else
interpolated from the run; the notes say which).  Every run is bounded: at ``--max-steps``
(or the event and memory bounds) it ends with a named status, exit 1, and the files hold the
run up to there.  Exit 1 when the integrator fails.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from landau.cli.common import NOT_PARAMS, add_friction_arguments, add_law_arguments, parse_params
from landau.errors import InputError
from landau.verify.hybrid.run_inputs import positive

FORMATS = (".csv", ".npz", ".png")
#: the front door's argument names as the command line spells them (in the words of an error)
FLAGS = {"y0": "--y0", "t_end": "--t-end", "max_steps": "--max-steps", "dt": "--dt", "samples": "--samples",
         "history": "--V-history", "V": "--V", "k": "--k"}
#: the law options of the velocity and kinetic laws: attribute of the arguments -> flag
LAW_OPTIONS = {"friction": "--friction", "friction_neg": "--friction-neg", "kinetic": "--kinetic",
               "kinetic_pos": "--kinetic-pos"}
#: the options of a system written on the command line
SYSTEM_OPTIONS = ("rhs", "equilibrium", "guess", "mass", "parameter", "contact")


def configure(p) -> None:
    p.add_argument("model", help="a registered model with a simulation: spring-block, galvanetto-one-block, "
                                 "galvanetto-two-blocks, impact-oscillator, forced-oscillator (or a plug-in's)")
    add_law_arguments(p)  # positional LAW after MODEL (rate-and-state models), --mu, --state, --param
    add_friction_arguments(p)  # --friction EXPR, --friction-neg, --friction-name (impact and forced oscillators)
    p.add_argument("--law", dest="law_option", default=None, metavar="NAME",
                   help="spring-block: built-in law (same as the positional LAW; default dieterich)")
    p.add_argument("--V", default=None, help="spring-block: driving velocity in m/s (default 1e-4); "
                                              "galvanetto models: belt velocity (dimensionless, default 0.25)")
    p.add_argument("--k", default=None, help="spring-block: spring stiffness in N/m (default 0.9 k_c(V))")
    p.add_argument("--t-end", default=None,
                   help="final time (s; dimensionless for the Galvanetto models); default the model's: "
                        "spring-block 20, galvanetto models 60, impact and forced oscillators 10")
    p.add_argument("--dt", default=None, metavar="DT",
                   help="give the series on the uniform grid 0, DT, 2 DT, ... <= t_end (default: the integrator's "
                        "points)")
    p.add_argument("--samples", default=None, metavar="N",
                   help="give the series at N uniform times spanning [0, t_end]")
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
                        "series up to there is written (default the model's: spring-block and forced-oscillator "
                        "5e6, the others 3e5)")
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
    p.add_argument("--rhs", action="append", default=[], metavar="NAME=EXPR",
                   help="system: a state and its right-hand side dNAME/dt (repeatable, in order)")
    p.add_argument("--equilibrium", action="append", default=[], metavar="NAME=EXPR",
                   help="system: the equilibrium of a state (the default start, displaced)")
    p.add_argument("--guess", action="append", default=[], metavar="NAME=VALUE",
                   help="system: instead of --equilibrium, a guess of it for Newton's method")
    p.add_argument("--mass", action="append", default=[], metavar="NAME=EXPR",
                   help="system: the mass entry E_ii of a state (default 1)")
    p.add_argument("--parameter", default=None, metavar="NAME",
                   help="system: the Hopf parameter (its value by --param; default the first --param)")
    p.add_argument("--contact", choices=("linear", "cubic", "hertz"), default=None,
                   help="mode-coupling: the contact law N(y) of the penetration y: linear kH*y, cubic kH*y + kNL*y^3 "
                        "(default) or hertz kH*y^(3/2)")
    p.add_argument("--plot", choices=("overview", "poincare", "friction"), default=None,
                   help="what a .png shows: time series and phase portrait (the default), the Poincaré section "
                        "(the logged sections; the forced oscillator: stroboscopic at the forcing period) or, "
                        "for a --V-history run (its default), friction against load-point displacement")
    p.add_argument("--preset", choices=("si", "lab"), default="si",
                   help="conventions: si (default; the block M = 1.2 kg, sigma = Mg, k in N/m, m/s, m) or lab "
                        "(spring-block --V-history: quasi-static M = 0, eta = 0, per unit normal stress sigma = 1; "
                        "bare numbers of --k in 1/um (k' = k/sigma), of velocities in um/s, of lengths in um; "
                        "files in um, um/s). Under either, values may carry units: --k 1e-3/um, --V-history "
                        "'1um/s@0,10um/s@10', --param L=10um")


def _max_steps(args) -> int | None:
    if args.max_steps is None:
        return None
    try:
        n = float(args.max_steps)
    except ValueError:
        n = float("nan")
    if not (math.isfinite(n) and n >= 1 and n == int(n)):
        raise InputError(f"--max-steps must be a whole number >= 1, got {args.max_steps!r}")
    return int(n)


def _takers(test) -> str:
    """The names of the models with a simulation for which ``test(model)`` holds."""
    from landau import models

    return ", ".join(m.name for m in models.all_models() if m.simulate is not None and test(m))


def _law_and_params(args, model) -> tuple:
    """The law (rate-and-state models: a FrictionLaw; the others: None, their law is an option) and the
    --param values with --V and --k."""
    from landau.models import LawKind

    if args.law_option is not None:
        if args.law is not None and args.law != args.law_option:
            raise InputError(f"two laws given: {args.law!r} and --law {args.law_option!r}")
        args.law = args.law_option
    declared = {p.name for p in model.parameters()}
    if model.law_kind is LawKind.RATE_AND_STATE:
        from landau.cli.common import resolve_law

        if any(it.split("=", 1)[0].strip() in ("V", "k") for it in args.param):
            raise InputError(f"{model.name}: give the driving velocity as --V and the stiffness as --k "
                             "(k is the bifurcation parameter, not a law parameter)")
        if args.law is None and args.mu is None and not args.state:
            args.law = model.default_law
        from landau.cli import lab_args
        from landau.lab.preset import get_preset

        preset = get_preset(getattr(args, "preset", "si"))
        kinds = lab_args.convert_params(args, preset)     # values with units in SI
        law, params = resolve_law(args)
        lab_args.finish_params(law, params, kinds, preset)
        params = {**preset.block, **params}
        if args.V is not None:
            params["V"] = positive(preset.velocity_value(args.V, "--V"), "--V")
        if args.k is not None:
            params["k"] = lab_args.stiffness(args.k, law, params, preset)
        return law, params
    if args.law is not None or args.mu is not None or args.state or args.k is not None or (
            args.V is not None and "V" not in declared):
        raise InputError(f"{model.name}: LAW, --mu, --state, --V and --k apply to "
                         f"{_takers(lambda m: m.law_kind is LawKind.RATE_AND_STATE)} only")
    V = args.V
    reserved = dict(NOT_PARAMS)
    given_V = []
    if "V" in declared:   # --V (or --param V=...) is the model's own V (the galvanetto belt velocity)
        reserved.pop("V")
        given_V = [it for it in args.param if it.split("=", 1)[0].strip() == "V"]
        if given_V and (V is not None or len(given_V) > 1):
            raise InputError(f"{model.name}: the belt velocity V is given twice")
    params = parse_params([it for it in args.param if it not in given_V], reserved)
    if given_V:
        V = given_V[0].split("=", 1)[1]
    if V is not None:
        params["V"] = positive(V, "--V")
    return None, params


def _options(args, model) -> dict:
    """The model's options given on the command line (a flag the model does not take: InputError)."""
    from landau.cli.model_args import convert_option

    takes = _taken(model)
    given = {name: getattr(args, name) for name in LAW_OPTIONS if getattr(args, name) is not None}
    given.update({name: convert_option(name, getattr(args, name)) for name in SYSTEM_OPTIONS
                  if getattr(args, name) not in (None, [])})
    if "friction" in given:
        given["friction_name"] = args.friction_name
    if args.hopf:
        given["hopf"] = True
    for name in given:
        if name not in takes:
            flag = LAW_OPTIONS.get(name, "--" + name.replace("_", "-"))
            raise InputError(f"{model.name}: {flag} applies to {_takers(lambda m, n=name: n in _taken(m))} only")
    return given


def _taken(model) -> set:
    """The option names a model's simulation takes (its options and its ``simulate_options``)."""
    return {o.name for o in model.options} | set(model.defaults.get("simulate_options", ()))


def _flagged(exc: InputError) -> InputError:
    """The front door's error in the command line's words (``y0 ...`` -> ``--y0 ...``)."""
    text = str(exc)
    for name, flag in FLAGS.items():
        if text.startswith((name + " ", name + ":")):
            return InputError(flag + text[len(name):])
    return exc


def simulate_model(args):
    """Run the model named in ``args`` through :func:`landau.simulate`; returns (Simulation, parameters,
    units, notes), the last three as the Simulation carries them."""
    from landau import models
    from landau.simulation import simulate

    model = models.get(args.model)
    t_end = positive(args.t_end, "--t-end") if args.t_end is not None else None
    max_steps = _max_steps(args)
    from landau.cli.lab_args import check_preset, history_pairs
    from landau.lab.preset import get_preset

    check_preset(args, model)
    law, params = _law_and_params(args, model)
    options = _options(args, model)
    history = None if args.V_history is None else history_pairs(args.V_history, get_preset(args.preset))
    try:
        sim = simulate(model, law, params=params, t_end=t_end, y0=args.y0, history=history,
                       dt=getattr(args, "dt", None), samples=getattr(args, "samples", None), options=options,
                       max_steps=max_steps, sections=args.plot == "poincare")
    except InputError as exc:
        raise _flagged(exc) from None
    notes = list(sim.notes)
    if args.preset == "lab":   # the series in the lab's units and column order
        from landau.lab.preset import LAB, LAB_COLUMNS

        sim = LAB.convert(sim, LAB_COLUMNS)
        notes.append("lab preset: quasi-static (M = 0, eta = 0) per unit normal stress (sigma = 1); the series "
                     "in um, um/s and s, the parameters in SI (k' = k/sigma in 1/m)")
    return sim, dict(sim.parameters), dict(sim.units), notes


def run(args) -> dict:
    outs = [Path(o) for o in args.out]
    for o in outs:
        if o.suffix.lower() not in FORMATS:
            raise InputError(f"--out {str(o)!r}: unknown format {o.suffix!r} (use {', '.join(FORMATS)})")
    discard = None if args.discard is None else positive(args.discard, "--discard")
    if args.plot == "friction" and args.V_history is None:
        raise InputError("--plot friction: friction against load-point displacement is the plot of a --V-history run")
    from landau.support.progress import progress, set_quiet

    set_quiet(getattr(args, "json", False))
    with progress(total=1, desc=f"simulate {args.model}", unit="run") as bar:   # a status line on a terminal
        sim, params, units, notes = simulate_model(args)
        bar.update()
    extra = {"hopf": params.pop("hopf")} if "hopf" in params else {}   # galvanetto-one-block --hopf
    files = []
    gridded = getattr(args, "dt", None) is not None or getattr(args, "samples", None) is not None
    if len(sim.t) and sim.t[-1] < sim.t_final and not gridded:
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
    kind = args.plot or ("friction" if args.V_history is not None else "overview")
    if has_data and any(o.suffix.lower() == ".png" for o in outs):
        from matplotlib.figure import Figure  # a figure pyplot never shows: the command only saves it

        try:
            if kind == "friction":   # the lab's plot of a protocol: mu against load-point displacement
                from landau.lab.figure import plot_friction

                fig = plot_friction(written, fig=Figure(figsize=(7.5, 5.5), layout="constrained"),
                                    title=written.plot_hints.get("title"))
            else:
                size = (11, max(4.5, 1.7 * len(sim._names()) + 0.8)) if kind == "overview" else (6.0, 4.8)
                fig = sim.plot(kind, discard=discard or 0.0, fig=Figure(figsize=size, layout="constrained"))
        except ValueError as exc:
            raise InputError(f"--plot {kind}: {args.model}: {str(exc).split(':')[0]}") from None
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
