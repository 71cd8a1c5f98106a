"""Plot a law's amplitude-equation coefficients against V, or its regime diagram, to a file.

Example: landau plot dieterich --V 1e-7:1e-2 --out dieterich.png
         landau plot ruina --V 1e-6:1e-2 --quantities kc,omega_c,Lambda --out ruina.pdf
         landau plot dieterich --V 1e-7:1e-2 --kind regime --out regimes.png
         landau plot --sweep map.nc --out map.png   (a `landau sweep regime` map with k_c(V) on top,
                                                     or a `landau sweep simulate` diagram in omega)
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from landau.cli.common import add_law_arguments, block_and_params, parse_range
from landau.derivation.multiscale import QUANTITIES, UNITS, Derivation
from landau.errors import InputError
from landau.support.io import atomic_savefig

#: file types the figure can be written as
FORMATS = ("png", "pdf", "svg")


def configure(p) -> None:
    add_law_arguments(p)
    p.add_argument("--V", default=None, metavar="LO:HI", help="driving-velocity range in m/s, e.g. 1e-7:1e-2")
    p.add_argument("--out", default=None, metavar="FILE", help=f"output figure ({', '.join(FORMATS)})")
    p.add_argument("--kind", choices=["coefficients", "regime"], default="coefficients",
                   help="coefficients against V (default) or the regime diagram in the (V, k) plane")
    p.add_argument("--quantities", default="kc,Lambda,C",
                   help=f"comma-separated subset of {','.join(QUANTITIES)} (coefficients plot; default kc,Lambda,C)")
    p.add_argument("--points", type=int, default=200, help="log-spaced velocities in the range (default 200)")
    p.add_argument("--sweep", default=None, metavar="FILE.nc",
                   help="draw a sweep: a regime map (landau sweep regime, over V and k) with k_c(V) on top, or "
                        "the forced oscillator's bifurcation diagram (landau sweep simulate)")


def run(args) -> dict:
    if args.sweep is not None:
        from landau.cli.sweep import plot_file

        return plot_file(args.sweep, args.out, FORMATS)
    if args.V is None:
        raise InputError("--V LO:HI is required (driving-velocity range in m/s)")
    if args.out is None:
        raise InputError("--out FILE is required (.png, .pdf or .svg)")
    fmt = Path(args.out).suffix.lstrip(".").lower()
    if fmt not in FORMATS:
        raise InputError(f"--out {args.out!r}: unknown figure type (use .{', .'.join(FORMATS)})")
    if not (2 <= args.points <= 100_000):
        raise InputError(f"--points must be between 2 and 100000, got {args.points}")
    lo, hi = parse_range(args.V, "--V")
    names = [q.strip() for q in args.quantities.split(",") if q.strip()]
    unknown = [q for q in names if q not in QUANTITIES]
    if unknown or not names:
        raise InputError(f"unknown quantity {unknown[0] if unknown else ''!r} (known: {', '.join(QUANTITIES)})")
    block, params = block_and_params(args)
    d = Derivation(block)
    Vs = np.logspace(np.log10(lo), np.log10(hi), args.points)

    from matplotlib.figure import Figure

    from landau.report.plotting import criticality_bands, plot_coefficients, plot_regime_diagram

    fig = Figure(figsize=(6.4, 2.2 * len(names) + 0.8) if args.kind == "coefficients" else (6.4, 4.4))
    doc: dict = {"law": block.law.name, "kind": args.kind, "V_range": [lo, hi], "points": args.points,
                 "params": params}
    if args.kind == "coefficients":
        table = d.evaluate(Vs, params, ["kc", "omega_c", "Lambda", *[n for n in names if n not in ("kc", "omega_c")]])
        plot_coefficients(table, names, fig=fig)
        doc["quantities"] = names
        doc["units"] = {n: UNITS[n] for n in ("V", *names)}
        bands = criticality_bands(table["V"], table["kc"], table["Lambda"])
    else:
        from landau.analyses.regimes import regime_diagram

        diagram = regime_diagram(d, Vs, params)
        plot_regime_diagram(diagram, fig.subplots())
        doc["codim2"] = [c.as_dict() for c in diagram.codim2]
        bands = criticality_bands(diagram.V, diagram.kc, diagram.Lambda)
    doc["bands"] = [{"V_lo": a, "V_hi": b, "criticality": k} for a, b, k in bands]
    doc["out"] = str(atomic_savefig(fig, args.out, dpi=120))
    return doc


def render(doc: dict) -> str:
    if doc.get("kind") == "regime-map":
        return f"regime map of {doc['law']} ({doc['points']} points: {doc['regimes']}) written to {doc['out']}"
    if doc.get("kind") == "bifurcation-diagram":
        return f"bifurcation diagram of the {doc['model']} ({doc['points']} points) written to {doc['out']}"
    if doc.get("kind") == "sweep-lines":
        return (f"{', '.join(doc['variables'])} of the {doc['model']} sweep against {doc['x']} ({doc['points']} "
                f"points) written to {doc['out']}")
    out = [f"{doc['kind']} plot of law {doc['law']} over V = {doc['V_range'][0]:g} .. {doc['V_range'][1]:g} m/s "
           f"({doc['points']} points) written to {doc['out']}"]
    for b in doc["bands"]:
        out.append(f"  {b['V_lo']:12.6g} .. {b['V_hi']:<12.6g} m/s  {b['criticality']}")
    for c in doc.get("codim2", []):
        out.append(f"  codimension-two point V = {c['V']:.8g} m/s, k_c = {c['kc']:.8g} N/m")
    return "\n".join(out)
