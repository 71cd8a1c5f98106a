"""Amplitude equation of the stick–slip Hopf bifurcation: Γ̄, Ω̄, Λ, χ, C (Putelat et al. 2010, eqs 15–23).

Example: landau derive ruina --V 1e-5,1e-4 --quantities k_c,omega_c,Lambda,C --latex ruina.tex
         landau derive dieterich --V 1e-4 --codim2 1e-7:1e-2
         landau derive dieterich --V 1e-4 --sensitivity k_c:a,Lambda:*
"""

from __future__ import annotations

from functools import partial

from landau.cli.common import add_law_arguments, block_and_params, fmt, parse_range, parse_velocities
from landau.derivation.coefficients import internal_name, with_canonical_names
from landau.derivation.multiscale import CONVENTION, QUANTITIES, UNITS, Derivation, criticality
from landau.errors import InputError
from landau.support.io import atomic_write_text, check_output

#: the quantity names as a user writes them (k_c canonical; kc, its deprecated alias, also accepted)
_PUBLIC = tuple("k_c" if q == "kc" else q for q in QUANTITIES)

#: time budget of the symbolic work behind --latex (s)
LATEX_SECONDS = 600.0


def configure(p) -> None:
    add_law_arguments(p)
    p.add_argument("--V", default=None, help="driving velocities in m/s, comma-separated")
    p.add_argument("--quantities", default=",".join(QUANTITIES),
                   help=f"comma-separated subset of {','.join(_PUBLIC)} (default: all; kc is the "
                        "deprecated alias of k_c)")
    p.add_argument("--latex", default=None, metavar="FILE",
                   help="write the coefficients as a .tex file that compiles with pdflatex (closed forms in V and "
                        "the parameters where they exist, else in the law's derivatives at steady sliding)")
    p.add_argument("--fragment", action="store_true",
                   help="with --latex: write only the equations (for \\input into a paper that loads amsmath)")
    p.add_argument("--codim2", default=None, metavar="LO:HI",
                   help="find every velocity in [LO, HI] m/s where Lambda changes sign on the Hopf line")
    p.add_argument("--sensitivity", default=None, metavar="Q:P,...",
                   help="exact sensitivities dQ/dP at each --V (comma-separated QUANTITY:PARAMETER pairs; Q:* every "
                        "parameter, *:P every quantity of --quantities, all: every pair); with --latex also their "
                        "closed forms")


def run(args) -> dict:
    block, params = block_and_params(args)
    names = [q.strip() for q in args.quantities.split(",") if q.strip()]
    if not names:
        raise InputError(f"--quantities: no quantity given (choose from {', '.join(_PUBLIC)})")
    unknown = [q for q in names if internal_name(q) not in QUANTITIES]
    if unknown:
        raise InputError(f"unknown quantity {unknown[0]!r} (known: {', '.join(_PUBLIC)})")
    names = list(dict.fromkeys(internal_name(n) for n in names))   # k_c (canonical) or kc (deprecated)
    if args.V is None and args.codim2 is None and args.latex is None:
        raise InputError("give --V (velocities), --codim2 LO:HI or --latex FILE")
    d = Derivation(block)
    pairs = _sensitivity_pairs(d, args.sensitivity, names)
    if args.latex is not None:
        check_output(args.latex)
    doc: dict = {"law": block.law.name, "source": block.law.source, "convention": CONVENTION,
                 "units": with_canonical_names({k: UNITS[k] for k in ("V", *names)}),
                 "params": params}
    if args.V is not None:
        Vs = parse_velocities(args.V)
        res = d.evaluate(Vs, params, ["kc", "omega_c", *names])
        pts = []
        for i, Vi in enumerate(Vs):
            if res["kc"][i] != res["kc"][i]:  # NaN: no Hopf point here
                pt = d.hopf.point(Vi, params)
                pts.append({"V": Vi, "status": "no-hopf", "reason": pt.reason, "velocity_weakening": pt.weakening})
                continue
            row = with_canonical_names({"V": Vi, "status": "ok", **{n: float(res[n][i]) for n in names}})
            if "Lambda" in res:
                row["criticality"] = "degenerate" if res["degenerate"][i] else criticality(float(res["Lambda"][i]))
            pts.append(row)
        doc["points"] = pts
        if pairs:
            _add_sensitivities(d, doc, Vs, params, pairs)
    if args.codim2 is not None:
        lo, hi = parse_range(args.codim2, "--codim2")
        from landau.analyses.bautin import bautin_point
        from landau.analyses.transition import codim2_points

        doc["codim2"] = []
        for c in codim2_points(d, lo, hi, params):
            # generalised-Hopf (Bautin) point: the quintic coefficient, l2 and the fold of cycles from it
            b = bautin_point(d, c.V, params, sign_below=c.sign_below, sign_above=c.sign_above)
            extra = {k: v for k, v in b.as_dict().items()
                     if k not in ("V", "kc", "omega_c", "sign_below", "sign_above")}
            doc["codim2"].append(with_canonical_names({**c.as_dict(), **extra}))
        doc["units"].update({"Lambda5": UNITS["Lambda5"], "l2": "Re c2 of dz/dt = i omega z + c1 z|z|^2 + c2 z|z|^4, "
                                                                "<q,q> = 1 (MatCont/BifurcationKit)"})
    if args.fragment and args.latex is None:
        raise InputError("--fragment needs --latex FILE")
    if args.latex is not None:
        from landau.support.budget import run_bounded
        from landau.support.progress import set_quiet

        set_quiet(getattr(args, "json", False))
        text = run_bounded(partial(_latex, fragment=args.fragment, pairs=pairs), (d, names), seconds=LATEX_SECONDS,
                           what=f"the closed forms of {', '.join(names)} for --latex",
                           hint="ask for fewer quantities (e.g. --quantities k_c,omega_c,Gamma_bar) or evaluate "
                                "numerically with --V instead")
        doc["latex"] = str(atomic_write_text(args.latex, text))
    return doc


def _sensitivity_pairs(d: Derivation, spec: str | None, names: list[str]) -> list[tuple[str, str]]:
    """The (quantity, parameter) pairs of --sensitivity ([] without it)."""
    if spec is None:
        return []
    from landau.derivation.sensitivity import parse_pairs

    public = ["k_c" if n == "kc" else n for n in names if n != "Lambda5"]
    return parse_pairs(d, spec, public)


def _add_sensitivities(d: Derivation, doc: dict, Vs, params: dict, pairs: list[tuple[str, str]]) -> None:
    """Each point's ∂Q/∂P under ``sensitivities`` ("d(Q)/d(P)" keys), their units in ``sensitivity_units``."""
    quantities = list(dict.fromkeys(q for q, _ in pairs))
    wanted = list(dict.fromkeys(p for _, p in pairs))
    res = d.sensitivities(Vs, params, quantities, wanted)
    units: dict[str, str] = {}
    for q, p in pairs:
        sens = d.sensitivity(q, p)
        units[sens.name] = sens.units
    for i, row in enumerate(doc["points"]):
        if row["status"] != "ok":
            continue
        row["sensitivities"] = {d.sensitivity(q, p).name: float(res[q][p][i]) for q, p in pairs}
    doc["sensitivity_units"] = units


def _latex(d: Derivation, names: list[str], fragment: bool, pairs: list[tuple[str, str]]) -> str:
    """The derivation's LaTeX, with the closed forms of the sensitivities asked for after the coefficients."""
    from landau.derivation.latex import derivation_latex

    text = derivation_latex(d, names, fragment=fragment)
    if not pairs:
        return text
    body = "\\section*{Sensitivities}\n" + "\n".join(d.sensitivity(q, p).latex() for q, p in pairs) + "\n"
    end = "\\end{document}"
    return text.replace(end, body + end) if not fragment and end in text else text + body


def _side(sign: int) -> str:
    """The criticality on one side of a codimension-two point, from the sign of Λ there."""
    return {-1: "supercritical", 1: "subcritical"}.get(sign, "degenerate")


def render(doc: dict) -> str:
    out = [f"Amplitude equation — law {doc['law']} ({doc['source']})", f"Convention: {doc['convention']}"]
    if "points" in doc:
        # the table's columns: the quantities of the rows (units also names --codim2's Lambda5 and l2)
        ok = [p for p in doc["points"] if p["status"] == "ok"]
        # one column for the critical stiffness, under its name k_c (kc is its deprecated JSON alias)
        names = [n for n in doc["units"] if n not in ("V", "kc") and (any(n in p for p in ok) if ok else
                                                          not ("codim2" in doc and n in ("Lambda5", "l2")))]
        out.append(f"{'V [m/s]':>12} " + " ".join(f"{n:>12}" for n in names) + "  criticality")
        for p in doc["points"]:
            if p["status"] != "ok":
                out.append(f"{fmt(p['V'])}  {p['reason']}; {p.get('velocity_weakening', '')}")
                continue
            out.append(f"{fmt(p['V'])} " + " ".join(fmt(p[n]) for n in names) + f"  {p.get('criticality', '')}")
        out.append("units: " + ", ".join(f"{k} [{v}]" for k, v in doc["units"].items() if k != "kc"))
    if doc.get("codim2"):
        out.append("codimension-two (generalised-Hopf) points, Lambda = 0 on the Hopf line; "
                   "l2 = Re c2 with <q,q> = 1 (MatCont/BifurcationKit):")
        out.append(f"{'V* [m/s]':>16} {'k_c [N/m]':>12} {'omega_c':>12} {'Lambda5':>12} {'l2':>12}  criticality")
        out.append(f"{'':>16} {'':>12} {'[rad/s]':>12} {'[1/(m^4 s)]':>12} {'':>12}  below / above V*")
        for c in doc["codim2"]:
            out.append(f"{c['V']:16.10g} {fmt(c['k_c'])} {fmt(c['omega_c'])} {fmt(c.get('Lambda5'))} {fmt(c.get('l2'))}"
                       f"  {_side(c['sign_below'])} / {_side(c['sign_above'])}")
        for c in doc["codim2"]:
            fc = c.get("fold_of_cycles")
            if fc:
                out.append(f"fold of cycles from V* = {c['V']:.6g} m/s, for {fc['side']}: k - k_c = "
                           f"{fc['k_minus_kc_per_dV2']:.4g} (V - V*)^2 N/m, slip amplitude "
                           f"{fc['amplitude_per_sqrt_dV']:.4g} |V - V*|^(1/2) m")
    if "codim2" in doc and not doc["codim2"]:
        out.append("no change of sign of Lambda on the Hopf line in the requested range")
    sens = [p for p in doc.get("points", ()) if "sensitivities" in p]
    if sens:
        out.append("exact sensitivities:")
        keys = list(doc["sensitivity_units"])
        out.append(f"{'V [m/s]':>12} " + " ".join(f"{k:>22}" for k in keys))
        for p in sens:
            out.append(f"{fmt(p['V'])} " + " ".join(fmt(p["sensitivities"][k], 22) for k in keys))
        out.append("units: " + ", ".join(f"{k} [{u}]" for k, u in doc["sensitivity_units"].items()))
    if "latex" in doc:
        out.append(f"LaTeX written to {doc['latex']}")
    return "\n".join(out)
