"""Transition velocity V*(p) where the Hopf bifurcation changes nature, and the critical p*
(Putelat et al. 2010, Sec. 4.2).

Continues every codimension-two point (Λ = 0 on the Hopf line) in a law parameter and
finds p*, where a branch V*(p) meets the extremum V_m(p) of μ_ss and disappears.

The parameter values are independent points, scanned on the sweep engine with ``--workers``
local processes (default: one per core; the numbers do not depend on it).

Example: landau transition modified-dieterich --vary c=1e-5:2e-3
         landau transition spinodal --vary c=2e-4:2e-3 --json --workers 2
"""

from __future__ import annotations

import math

from landau.analyses.transition import transition_curve
from landau.cli.common import add_law_arguments, block_and_params, fmt, parse_floats, parse_range
from landau.derivation.multiscale import Derivation
from landau.errors import InputError


def configure(p) -> None:
    add_law_arguments(p)
    p.add_argument("--vary", required=False, default=None, metavar="NAME=LO:HI",
                   help="law parameter to continue in, and its range (e.g. c=1e-5:2e-3)")
    p.add_argument("--points", type=int, default=30, help="number of parameter values on the curve (default 30)")
    p.add_argument("--V-range", default="1e-12:1e2", metavar="LO:HI",
                   help="velocity interval searched for codimension-two points and extrema of mu_ss (m/s)")
    p.add_argument("--workers", type=int, default=None,
                   help="local processes for the scan over the parameter values (default: the number of cores; "
                        "the numbers do not depend on it)")


def _parse_vary(text: str | None) -> tuple[str, float, float]:
    if not text:
        raise InputError("--vary NAME=LO:HI is required (e.g. --vary c=1e-5:2e-3)")
    if "=" not in text or ":" not in text.split("=", 1)[1]:
        raise InputError(f"--vary {text!r}: expected NAME=LO:HI")
    name, rng = text.split("=", 1)
    lo_s, hi_s = rng.split(":", 1)
    lo, hi = parse_floats(lo_s, "--vary")[0], parse_floats(hi_s, "--vary")[0]
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise InputError(f"--vary {name}: need finite LO < HI, got {lo!r}:{hi!r}")
    return name.strip(), lo, hi


def run(args) -> dict:
    block, params = block_and_params(args)
    name, lo, hi = _parse_vary(args.vary)
    if name in ("M", "g", "sigma"):
        raise InputError(f"--vary {name}: vary a law parameter ({', '.join(p.name for p in block.law.parameters)})")
    block.law.parameter(name)  # InputError naming the known parameters
    prm = block.law.parameter(name)
    if prm.positive and lo <= 0:
        raise InputError(f"--vary {name}: {name} must be > 0, got LO = {lo!r}")
    if args.points < 3:
        raise InputError("--points must be >= 3")
    workers = getattr(args, "workers", None)
    if workers is not None and workers < 1:
        raise InputError(f"--workers must be >= 1, got {workers}")
    vlo, vhi = parse_range(args.V_range, "--V-range")
    params = {k: v for k, v in params.items() if k != name}
    d = Derivation(block)
    curve = transition_curve(d, name, lo, hi, params, n=args.points, V_range=(vlo, vhi), workers=workers)
    doc = {"law": block.law.name, "source": block.law.source, "vary": name, "range": [lo, hi],
           "units": {"V_star": "m/s", "kc": "N/m", "omega_c": "rad/s", "V_ext": "m/s"},
           "convention": "V_star: Lambda = 0 on the Hopf line (k_c > 0); critical_value: the parameter value "
                         "where a branch V_star meets the extremum V_ext of mu_ss (k_c = 0) and ends",
           **curve.as_dict()}
    return doc


def render(doc: dict) -> str:
    name = doc["vary"]
    cv = doc["critical_value"]
    out = [f"Transition velocity V* (Lambda = 0 on the Hopf line) — law {doc['law']}, {name} in "
           f"[{doc['range'][0]:g}, {doc['range'][1]:g}]",
           f"critical {name}* = " + ("none in range" if cv is None else f"{cv:.8g}")]
    for c in doc["critical_values"]:
        out.append(f"  {name}* = {c['value']:.8g}: V* meets the {c['end']} extremum of mu_ss at {c['V_ext']:.8g} m/s")
    out.append(f"{name:>12} {'V_star [m/s]':>14} {'kc [N/m]':>12} {'V_ext [m/s]':>12}")
    for r in doc["curve"]:
        out.append(f"{fmt(r[name])} {fmt(r['V_star'], 14)} {fmt(r['kc'])} {fmt(r['V_ext'])}")
    if not doc["curve"]:
        out.append("(no codimension-two point in the range)")
    return "\n".join(out)
