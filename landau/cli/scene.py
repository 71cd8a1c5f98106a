"""Named, reproducible computations: landau scene list | landau scene run NAME|GLOB... [--all] [--param K=V ...].

Example: landau scene run putelat2010/V-hat
         landau scene run 'skurativskyi2019/grazing-*'      # one summary table
         landau scene run --all --json
"""

from __future__ import annotations

from landau.cli.common import parse_params
from landau.errors import InputError
from landau.report.display import text_table
from landau.scenes import SceneResult, all_scenes, failed, run_scene, run_scenes, verdict


def configure(p) -> None:
    p.add_argument("action", choices=["list", "run"], help="list the scenes or run them")
    p.add_argument("names", nargs="*", default=[], metavar="NAME",
                   help="scene names or shell-style patterns, e.g. 'putelat2010/*' (for run)")
    p.add_argument("--all", action="store_true", help="run every scene and print one summary table")
    p.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                   help="override a scene parameter (with several scenes: those that have it)")


def _is_pattern(name: str) -> bool:
    return any(ch in name for ch in "*?[")


def run(args) -> dict:
    if args.action == "list":
        if args.names or args.all:
            raise InputError("'scene list' takes no name")
        return {"scenes": [s.as_dict() for s in all_scenes()]}
    if args.all and args.names:
        raise InputError("'scene run --all' takes no name")
    if not args.all and not args.names:
        raise InputError("'scene run' needs a scene name, a pattern or --all (see 'landau scene list')")
    overrides = parse_params(args.param, reserved={})  # a scene's own names (k, v, ...) are checked by the scene
    if not args.all and len(args.names) == 1 and not _is_pattern(args.names[0]):
        doc = run_scene(args.names[0], overrides)
        if failed(doc):
            doc["exit_code"] = 1
        return doc
    results = run_scenes(None if args.all else args.names, overrides)
    counts: dict[str, int] = {}
    for r in results:
        counts[verdict(r)] = counts.get(verdict(r), 0) + 1
    return {"results": [dict(r) for r in results], "summary": counts,
            "exit_code": 1 if any(failed(r) for r in results) else 0}


def render(doc: dict) -> str:
    if "scenes" in doc:
        lines = [f"{len(doc['scenes'])} scenes:"]
        for s in doc["scenes"]:
            pub = "" if s["published"] is None else f"  published {s['published']:.6g}"
            lines.append(f"  {s['scene']:<42} {s['parameter']} [{s['units']}]{pub}  — {s['source']}")
        return "\n".join(lines)
    if "results" in doc:
        lines = [text_table([SceneResult(r)._display_row() for r in doc["results"]], max_rows=10_000)]
        for r in doc["results"]:
            if r.get("error"):
                lines.append(f"{r['scene']}: {r['error']}")
            elif r.get("note"):
                lines.append(f"{r['scene']}: {r['note']}")
        lines.append(", ".join(f"{n} {k}" for k, n in sorted(doc["summary"].items())))
        return "\n".join(lines)
    lines = [f"{doc['scene']}: {doc['parameter']} = {doc['value']:.10g} {doc['units']}"]
    if doc.get("published") is not None:
        tag = verdict(doc)
        lines.append(f"  published {doc['published']:.10g} ({doc['source']}); relative difference {doc['rel_diff']:.2e}"
                     + (f"  [{tag}]" if tag in ("agrees", "explained", "DISAGREES", "not comparable") else ""))
    else:
        lines.append(f"  source: {doc['source']}")
    for k, v in doc.items():
        if k not in {"scene", "parameter", "value", "units", "published", "source", "rel_diff", "agrees",
                     "tolerance", "params", "seconds", "exit_code", "at_defaults", "comparable", "explained"}:
            lines.append(f"  {k}: {v}")
    lines.append(f"  ({doc['seconds']:.2f} s)")
    return "\n".join(lines)
