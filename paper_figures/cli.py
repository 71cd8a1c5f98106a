"""Regenerate a paper's figures: landau figures PAPER [--only figN,...] [--out DIR]."""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from landau.errors import InputError
from landau.paper_figures import using_workers

#: the entry-point group of the papers' figure tables (paper name -> its FIGURES)
GROUP = "landau.figures"


def papers() -> dict:
    """Paper name -> its entry point (loaded by :func:`load`)."""
    from importlib.metadata import entry_points

    return {ep.name: ep for ep in entry_points(group=GROUP)}


#: the papers with figures, in the order of the entry points
PAPERS = tuple(papers())


def configure(p: argparse.ArgumentParser) -> None:
    p.add_argument("paper", help="one of: " + ", ".join(PAPERS))
    p.add_argument("--only", default=None, help="comma-separated figure names (e.g. fig8,fig10)")
    p.add_argument("--out", default="figures", help="output folder (default: ./figures)")
    p.add_argument("--no-progress", action="store_true", help="hide the progress bar")
    p.add_argument("--workers", type=int, default=None,
                   help="local processes for the figures' parameter loops (default: the number of cores; "
                        "the numbers do not depend on it)")


def load(paper: str):
    eps = papers()
    if paper not in eps:
        raise InputError(f"unknown paper {paper!r} (known: {', '.join(eps)})")
    try:
        return eps[paper].load()
    except ModuleNotFoundError as exc:
        raise InputError(f"figures for {paper!r} are not available: {exc}") from None


def run(args) -> dict:
    figures = load(args.paper)
    names = list(figures)
    if args.only is not None:
        wanted = [s.strip() for s in args.only.split(",") if s.strip()]
        if not wanted:
            raise InputError(f"--only names no figure (got {args.only!r}; known: {', '.join(names)})")
        unknown = [w for w in wanted if w not in figures]
        if unknown:
            raise InputError(f"unknown figure(s) {', '.join(unknown)} for {args.paper} (known: {', '.join(names)})")
        names = wanted
    if not args.out.strip():
        raise InputError("--out: the output folder is empty (give a folder, e.g. --out figures; '.' for the "
                         "current one)")
    out = Path(args.out)
    n_workers = getattr(args, "workers", None)
    if n_workers is not None and n_workers < 1:
        raise InputError(f"--workers must be >= 1, got {n_workers}")
    rows = []
    bar = None
    if not (args.no_progress or args.json):
        from tqdm import tqdm

        bar = tqdm(names, desc=args.paper, unit="fig")
    for name in names if bar is None else bar:
        if bar is not None:
            bar.set_postfix_str(name)
        t0 = time.perf_counter()
        with using_workers(n_workers):
            paths = figures[name](out)
        rows.append({"figure": name, "files": [str(p) for p in paths], "seconds": time.perf_counter() - t0})
    return {"paper": args.paper, "out": str(out), "figures": rows,
            "seconds": sum(r["seconds"] for r in rows)}


def render(doc: dict) -> str:
    lines = [f"{doc['paper']}: {len(doc['figures'])} figure(s) in {doc['out']} ({doc['seconds']:.1f} s)"]
    for r in doc["figures"]:
        lines.append(f"  {r['figure']:<10} {r['seconds']:6.2f} s  " + ", ".join(r["files"]))
    return "\n".join(lines)
