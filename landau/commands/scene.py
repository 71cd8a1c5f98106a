"""Named, reproducible computations: landau scene list | landau scene run NAME [--param K=V ...]."""

from __future__ import annotations

from landau.commands.common import parse_params
from landau.errors import InputError
from landau.scenes import all_scenes, run_scene


def configure(p) -> None:
    p.add_argument("action", choices=["list", "run"], help="list the scenes or run one")
    p.add_argument("name", nargs="?", default=None, help="scene name (for run)")
    p.add_argument("--param", action="append", default=[], metavar="NAME=VALUE", help="override a scene parameter")


def run(args) -> dict:
    if args.action == "list":
        if args.name:
            raise InputError("'scene list' takes no name")
        return {"scenes": [{"scene": s.name, "parameter": s.parameter, "units": s.units,
                            "published": s.published, "source": s.source, "params": dict(s.defaults),
                            "description": s.description} for s in all_scenes()]}
    if not args.name:
        raise InputError("'scene run' needs a scene name (see 'landau scene list')")
    doc = run_scene(args.name, parse_params(args.param))
    if doc.get("agrees") is False and doc.get("at_defaults"):
        doc["exit_code"] = 1
    return doc


def render(doc: dict) -> str:
    if "scenes" in doc:
        lines = [f"{len(doc['scenes'])} scenes:"]
        for s in doc["scenes"]:
            pub = "" if s["published"] is None else f"  published {s['published']:.6g}"
            lines.append(f"  {s['scene']:<42} {s['parameter']} [{s['units']}]{pub}  — {s['source']}")
        return "\n".join(lines)
    lines = [f"{doc['scene']}: {doc['parameter']} = {doc['value']:.10g} {doc['units']}"]
    if doc.get("published") is not None:
        lines.append(f"  published {doc['published']:.10g} ({doc['source']}); relative difference {doc['rel_diff']:.2e}"
                     + ("" if "agrees" not in doc else ("  [agrees]" if doc["agrees"] else "  [DISAGREES]")))
    else:
        lines.append(f"  source: {doc['source']}")
    for k, v in doc.items():
        if k not in {"scene", "parameter", "value", "units", "published", "source", "rel_diff", "agrees",
                     "tolerance", "params", "seconds", "exit_code", "at_defaults"}:
            lines.append(f"  {k}: {v}")
    lines.append(f"  ({doc['seconds']:.2f} s)")
    return "\n".join(lines)
