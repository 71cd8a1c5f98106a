"""Check the engine's amplitude-equation predictions by direct simulation of the spring–block.

``landau verify LAW --V v1,v2 [--eps2 e1,e2] [--param K=V ...] [--mu EXPR --state NAME=EXPR ...]``
integrates eq. (4) of Putelat et al. (2010) near each Hopf point: supercritical points at
k = k_c(1 − ε²) (limit cycle by shooting, amplitude vs C·sqrt(k_c − k), frequency vs the
predicted shift); subcritical points at k = k_c(1 + ε²) (unstable cycle by shooting; with
bistability testing on, bisection between decay and growth to stick–slip) — the procedure is
chosen from the prediction (:func:`landau.check`).  Each ε² is measured together with ε²/4 and
agrees when the amplitude error falls like ε² (fitted exponent in 0.75–2.5) and extrapolates to
within 1 % at ε² → 0 (docs/guarantees.md, "The check's contract").  A point where the predicted
cycle would reverse the slip is reported as outside the range of validity, with the largest valid
ε²; one whose cycle the simulation cannot resolve as failed, with the resolvable range.  Exit
code 1 when a point does not agree.  ``--work-precision`` writes the Fig. 3
work–precision table and PNG to ``--out``.
"""

from __future__ import annotations

from pathlib import Path

from landau.analyses import contract
from landau.analyses.checking import check
from landau.cli.common import add_law_arguments, parse_floats, parse_velocities, resolve_law
from landau.errors import InputError
from landau.support.progress import progress, set_quiet
from landau.systems.system import SpringBlock
from landau.verify.springblock.checks import fitted_exponent

AMPLITUDE_DEFINITION = ("amplitude_simulated = half peak-to-peak slip (max X - min X)/2 of the cycle, X = x - x0; "
                        "max|x - x0| (max_abs_slip) carries an extra O(eps) mean shift")


def configure(p) -> None:
    add_law_arguments(p)
    p.add_argument("--V", default=None, help="driving velocities in m/s, comma-separated")
    p.add_argument("--eps2", default="1e-3", help="distances eps^2 = |k - k_c|/k_c, comma-separated (default 1e-3)")
    p.add_argument("--tol", type=float, default=None,
                   help="an extra bound on |relative amplitude error| at each eps2 (default: none — a point agrees "
                        f"when its error falls like eps2, fitted exponent in {contract.EXPONENT_BAND[0]:g} to "
                        f"{contract.EXPONENT_BAND[1]:g}, and extrapolates to within "
                        # "%%": argparse %-formats help texts (a lone "%" would print its own state)
                        f"{100 * contract.EXTRAPOLATION_BOUND:g}%% at eps2 -> 0)")
    p.add_argument("--no-bistability", action="store_true",
                   help="subcritical points: only shoot the unstable cycle, skip the (slow) bisection")
    p.add_argument("--work-precision", action="store_true", help="write the Fig. 3 work-precision table and PNG")
    p.add_argument("--out", default="verify-out", help="output directory for --work-precision (default verify-out)")
    p.add_argument("--contact", choices=("linear", "cubic", "hertz"), default=None,
                   help="mode-coupling: the contact law (default linear; cubic with --param kNL=...)")


def run(args) -> dict:
    from landau import models

    if args.law in models.names():      # a registered model with its own check (mode-coupling)
        return _model_check(models.get(args.law), args)
    if args.contact is not None:
        raise InputError("--contact applies to a model's check (landau verify mode-coupling) only")
    doc: dict = {"amplitude_definition": AMPLITUDE_DEFINITION, "units": {"V": "m/s", "kc": "N/m", "k_c": "N/m",
                 "amplitude": "m", "frequency": "rad/s"},
                 "contract": {"exponent_band": list(contract.EXPONENT_BAND),
                              "extrapolation_bound": contract.EXTRAPOLATION_BOUND,
                              "companion_ratio": contract.RATIO,
                              "multiplier_resolution": contract.MULTIPLIER_RESOLUTION}}
    exit_code = 0
    if args.tol is not None and not (0 < args.tol < 1):
        raise InputError(f"--tol must be in (0, 1), got {args.tol!r}")
    if args.V is None and not args.work_precision:
        raise InputError("give --V (driving velocities in m/s) or --work-precision")
    if args.V is not None:
        law, overrides = resolve_law(args)
        params = SpringBlock.for_params(law, overrides).resolve(overrides)
        if not (params["M"] > 0 or (params["M"] == 0 and params.get("eta", 0.0) > 0)):
            raise InputError(f"--param M={params['M']:g}: the simulation needs a block mass M > 0, or M = 0 with "
                             "radiation damping eta > 0 (the quasi-dynamic cell); M = 0 with eta = 0 is the "
                             "quasi-static limit, which `landau derive` handles")
        eps2s = parse_floats(args.eps2, "--eps2")
        for e in eps2s:
            if not (0 < e < 0.5):
                raise InputError(f"--eps2: values must be in (0, 0.5), got {e!r}")
        points = []
        grid = [(V, e) for V in parse_velocities(args.V) for e in eps2s]
        set_quiet(getattr(args, "json", False))
        with progress(total=len(grid), desc=f"verify {law.name}", unit="point") as bar:
            for V, e in grid:
                bar.set_postfix_str(f"V={V:g}, eps2={e:g}")
                r = check(law, V, e, params, tolerance=args.tol, bistability=not args.no_bistability)
                rec = r.as_dict()
                rec.update(V=V, k=r.p, kc=r.prediction.p_c, k_c=r.prediction.p_c)   # kc: deprecated alias
                points.append(rec)
                if not r.agrees:
                    exit_code = 1
                bar.update()
        doc.update(law=law.name, source=law.source, params=params, points=points)
        if len(eps2s) >= 3:
            fits = {}
            for V in sorted({p["V"] for p in points}):
                pts = [p for p in points if p["V"] == V and p.get("rel_error")]
                if len(pts) >= 3:
                    fits[f"{V:g}"] = fitted_exponent([p["eps2"] for p in pts], [p["rel_error"] for p in pts])
            doc["fitted_exponent"] = fits
    if args.work_precision:
        from landau.support.io import atomic_write_json, atomic_write_text
        from landau.verify.springblock.workprecision import plot, run_work_precision

        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        wp = run_work_precision()
        files = [atomic_write_text(out / "work_precision.md", "```\n" + wp.table() + "```\n"),
                 atomic_write_json(out / "work_precision.json", wp.as_dict()),
                 plot(wp, out / "work_precision.png")]
        doc["work_precision"] = {"files": [str(f) for f in files], "table": wp.table()}
    doc["exit_code"] = exit_code
    return doc


def _f(x, spec="10.4g"):
    return "-".rjust(int(spec.split(".")[0])) if x is None else format(x, spec)


def _model_check(model, args) -> dict:
    """``landau verify MODEL``: the model's own check (:attr:`landau.models.Model.check`)."""
    from landau import models
    from landau.cli.common import parse_params
    from landau.models import Setup

    if model.check is None:
        have = ", ".join(m.name for m in models.all_models() if m.check is not None)
        raise InputError(f"verify {model.name}: the model has no check by simulation (models with one: {have}; "
                         "a law name checks the spring-block)")
    if args.V is not None or args.mu is not None or args.state or args.work_precision:
        raise InputError(f"verify {model.name}: --V, --mu, --state and --work-precision belong to the spring-block")
    if args.tol is not None and not (0 < args.tol < 1):
        raise InputError(f"--tol must be in (0, 1), got {args.tol!r}")
    eps2s = parse_floats(args.eps2, "--eps2")
    for e in eps2s:
        if not (0 < e < 0.5):
            raise InputError(f"--eps2: values must be in (0, 0.5), got {e!r}")
    setup = Setup(None, parse_params(args.param, {}), {"contact": args.contact} if args.contact else {})
    return model.check(setup, eps2s[0] if len(eps2s) == 1 else eps2s, args.tol)


def render(doc: dict) -> str:
    if "text" in doc and "model" in doc:   # a model's own check
        return doc["text"]
    lines = []
    if "points" in doc:
        lines.append(f"law {doc['law']}  [{doc['source']}]")
        lines.append(doc["amplitude_definition"])
        lines.append(f"{'V [m/s]':>10} {'eps2':>8} {'k_c [N/m]':>12} {'criticality':>13} {'A_pred [m]':>11} "
                     f"{'A_sim [m]':>11} {'rel.err':>9} {'exponent':>8} {'extrap.':>9} {'freq.err':>9} "
                     f"{'bistable':>8} {'agrees':>6}")
        for p in doc["points"]:
            fe = p.get("frequency_rel_error")
            lines.append(f"{p['V']:10.4g} {p['eps2']:8.2g} {p['k_c']:12.6g} {p['criticality_predicted']:>13} "
                         f"{_f(p['amplitude_predicted'], '11.4g')} {_f(p['amplitude_simulated'], '11.4g')} "
                         f"{_f(p['rel_error'], '+9.2e')} {_f(p.get('exponent'), '8.3f')} "
                         f"{_f(p.get('extrapolated_error'), '+9.2e')} {_f(fe, '+9.1e')} {str(p['bistable']):>8} "
                         f"{'yes' if p['agrees'] else 'NO':>6}")
            if p.get("reason"):
                lines.append(f"    {p['verdict']}: {p['reason']}")
    if "points" in doc:
        c = doc["contract"]
        lines.append(f"contract: each eps2 is measured with eps2/{c['companion_ratio']:g}; it agrees when the error "
                     f"falls like eps2 (exponent in {c['exponent_band'][0]:g} to {c['exponent_band'][1]:g}) and "
                     f"extrapolates to within {c['extrapolation_bound']:.0%} at eps2 -> 0")
    if doc.get("fitted_exponent"):
        lines.append("fitted exponent p in |rel.err| ~ (eps2)^p: "
                     + ", ".join(f"V={v}: {x:.3f}" for v, x in doc["fitted_exponent"].items()))
    if "work_precision" in doc:
        lines.append(doc["work_precision"]["table"])
        lines.append("wrote " + ", ".join(doc["work_precision"]["files"]))
    if "points" in doc:
        verdicts = sorted({p["verdict"] for p in doc["points"]})
        lines.append("all points agree" if verdicts == ["agrees"] else
                     "not all points agree: " + ", ".join(verdicts) + " (exit 1)")
    return "\n".join(lines) + "\n"
