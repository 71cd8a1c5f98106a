"""Continue the branch of cycles of a model from its Hopf point, with Floquet multipliers and LPC/PD/NS points.

``landau cycles MODEL [LAW] [--param NAME=VALUE ...] [model options] [--steps N] [--ds DS]
[--direction +1|-1] [--start hopf] [--json] [--csv FILE] [--plot FILE]``

MODEL is any registered model with a ``cycles`` declaration (``landau cycles --help`` lists them):
the command builds its setup as ``landau hopf`` does (:func:`landau.cli.model_args.setup_from_args`),
asks the model for its smooth vector field with the Hopf parameter as the continuation parameter
(:class:`~landau.periodic.problem.CycleProblem`), and follows the branch of cycles born at the Hopf
point (:func:`landau.analyses.cycles.follow`: orthogonal collocation, the Floquet multipliers at
every point, the folds of cycles LPC, period doublings PD and Neimark–Sacker points NS located).
The text is a table of the branch (parameter, period, amplitude of the measured state, stability)
and the special points; ``--json`` one JSON document (the branch's columns and the special points);
``--csv FILE`` the branch's columns; ``--plot FILE`` the bifurcation diagram (amplitude and period
against the parameter, stable solid, unstable dashed, the special points marked, the equilibrium
branch and the Hopf point).

Example: ``landau cycles spring-block dieterich --V 1e-4 --steps 60``.
"""

from __future__ import annotations

from pathlib import Path

from landau.cli.common import add_friction_arguments, add_law_arguments
from landau.cli.model_args import add_model_options, setup_from_args
from landau.errors import InputError

#: the figure types of --plot
FORMATS = ("png", "pdf", "svg")


def configure(p) -> None:
    from landau.models import all_models

    p.add_argument("model", help="the model (" + ", ".join(m.name for m in all_models() if m.cycles is not None)
                   + ")")
    add_law_arguments(p)
    add_friction_arguments(p)
    p.add_argument("--V", default=None, help="spring-block: driving velocity in m/s (default 1e-4)")
    add_model_options(p)
    p.add_argument("--steps", default="100", metavar="N", help="continuation steps (default 100)")
    p.add_argument("--ds", default=None, metavar="DS", help="the first arclength step (default the engine's)")
    p.add_argument("--direction", default=None, metavar="+1|-1",
                   help="+1 (default): away from the Hopf point, the cycle growing; -1 the other way")
    p.add_argument("--start", default="hopf", choices=("hopf",),
                   help="where the branch starts: hopf, the amplitude equation's cycle (default)")
    p.add_argument("--csv", default=None, metavar="FILE", help="write the branch's columns to FILE (CSV)")
    p.add_argument("--plot", default=None, metavar="FILE", help="write the bifurcation diagram to FILE (.png, .pdf, "
                                                                ".svg)")


def _int(text, what: str) -> int:
    try:
        n = int(str(text))
    except ValueError:
        raise InputError(f"{what}: expected an integer, got {text!r}") from None
    return n


def run(args) -> dict:
    from landau.analyses.cycles import branch_csv, branch_document, branch_table, follow
    from landau.models import all_models, get

    model = get(args.model)
    if model.cycles is None:
        have = [m.name for m in all_models() if m.cycles is not None]
        raise InputError(f"landau cycles: the model {model.name!r} declares no cycles (models that do: "
                         f"{', '.join(have)})")
    steps = _int(args.steps, "--steps")
    direction = None if args.direction is None else _int(args.direction, "--direction")
    if direction not in (None, 1, -1):
        raise InputError(f"--direction must be +1 or -1, got {args.direction!r}")
    ds = None
    if args.ds is not None:
        from landau.cli.model_args import one_number

        ds = one_number(args.ds, "--ds")
    if args.plot is not None and Path(args.plot).suffix.lstrip(".").lower() not in FORMATS:
        raise InputError(f"--plot {args.plot!r}: unknown figure type (use .{', .'.join(FORMATS)})")
    if steps < 1:
        raise InputError(f"--steps must be a positive integer, got {steps}")
    problem = model.cycles(setup_from_args(model, args, "landau cycles"))
    table = branch_table(follow(problem, args.start, steps=steps, ds=ds, direction=direction), problem)
    doc = {"model": model.name, **branch_document(table)}
    if args.csv is not None:
        from landau.support.io import atomic_write_text

        atomic_write_text(args.csv, branch_csv(table))
        doc["csv"] = args.csv
    if args.plot is not None:
        from matplotlib.figure import Figure

        from landau.report.cycles_figure import plot_cycle_branch
        from landau.support.io import atomic_savefig

        fig = Figure(figsize=(9.0, 3.8))
        drawn = plot_cycle_branch(table, fig=fig)
        atomic_savefig(fig, args.plot, dpi=120, bbox_inches="tight")
        doc["plot"] = {"file": args.plot, "lines": drawn["lines"], "special": drawn["special"]}
    return doc


def render(doc: dict) -> str:
    return doc.get("text") or repr(doc)
