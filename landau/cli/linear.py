"""Linear stability of steady sliding: critical stiffness k_c (eq. 7) and frequency ω_c (eq. 8).

Example: landau linear dieterich --V 1e-5,1e-4 --param M=2
"""

from __future__ import annotations

from landau.cli.common import add_law_arguments, block_and_params, fmt, parse_velocities
from landau.derivation.linear import HopfLine
from landau.support.io import atomic_write_text, check_output


def configure(p) -> None:
    add_law_arguments(p)
    p.add_argument("--V", default=None, help="driving velocities in m/s, comma-separated")
    p.add_argument("--latex", default=None, metavar="FILE", help="write k_c and omega_c^2 closed forms as LaTeX")


def run(args) -> dict:
    block, params = block_and_params(args)
    Vs = parse_velocities(args.V)
    if args.latex is not None:
        check_output(args.latex)
    hl = HopfLine(block)
    pts = hl.points(Vs, params)
    doc = {"law": block.law.name, "source": block.law.source,
           "units": {"V": "m/s", "kc": "N/m", "k_c": "N/m", "omega_c": "rad/s", "phi_ss": "s (state units)",
                     "mu_ss": "1", "dmu_ss_dV": "s/m"},
           "params": params, "points": [pt.as_dict() for pt in pts]}
    if args.latex is not None:
        doc["latex"] = str(atomic_write_text(args.latex, linear_latex(hl)))
    return doc


def linear_latex(hl: HopfLine) -> str:
    from landau.report.latex import hopf_line_latex

    return hopf_line_latex(hl)


def render(doc: dict) -> str:
    out = [f"Linear stability of steady sliding — law {doc['law']} ({doc['source']})",
           f"{'V [m/s]':>12} {'k_c [N/m]':>12} {'w_c [rad/s]':>12} {'mu_ss':>12} {'dmu_ss/dV':>12}  phi_ss"]
    for p in doc["points"]:
        phi = ", ".join(f"{x:.4g}" for x in p["phi_ss"])
        if p["status"] == "ok":
            out.append(f"{fmt(p['V'])} {fmt(p['k_c'])} {fmt(p['omega_c'])} {fmt(p['mu_ss'])} "
                       f"{fmt(p['dmu_ss_dV'])}  {phi}")
        else:
            out.append(f"{fmt(p['V'])}  {p['reason']}  (mu_ss = {p['mu_ss']:.6g}, slope {p['dmu_ss_dV']:.4g}); "
                       f"{p['velocity_weakening']}")
    if "latex" in doc:
        out.append(f"LaTeX written to {doc['latex']}")
    return "\n".join(out)
