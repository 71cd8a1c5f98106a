"""The toolkit against its fair peers, every speed goal with its ratio, in one run.

    pip install -e '.[bench]'
    python benchmarks/run.py                  # every section (an hour or more on a loaded 2-core machine)
    python benchmarks/run.py --only coldstart,figures --quick
    python benchmarks/report.py               # docs/performance.md from benchmarks/results/*.json

Each section measures the toolkit and its baseline side by side in the same process (or in
fresh interpreters started back to back, where the cost of a cold process is the point) and
prints one line per goal: the value, the goal and pass/fail.  Tables (Markdown), the raw
numbers (JSON) and work-precision plots (PNG) go to ``benchmarks/results/`` with a
description of the machine, the date and the load average during the run.

Benchmarks measure what users run: the default method of each command and function (read at
run time, so the suite follows the code), CPU time of the child for commands, and "cold"
means a new landau cache *and* a new numba cache in a fresh process.

Sections (``--only``), each described in its module:

* ``springblock``, ``forced``, ``galvanetto`` — work-precision against compiled peers at equal
  error (``sections_solvers.py``);
* ``springblock-paths`` — the quasi-dynamic cell and the load histories on the compiled Radau IIA
  against the scipy routes they replaced, at equal error, and their first build
  (``sections_springblock_paths.py``, about a minute);
* ``lambda``, ``derive`` — Λ(V) throughput and accuracy, derivation cost (``sections_engine.py``);
* ``coldstart``, ``help``, ``figures`` — commands in fresh processes, cold and warm (``sections_cli.py``);
* ``sweep`` — landau.sweep: 1 → 2 workers, hopf points per second, executor overhead (``sections_sweep.py``);
* ``usersystem`` — a DynamicalSystem from strings: compiled simulation and check against the scipy
  route (``sections_usersystem.py``);
* ``chain`` — the spring–block chain's Hopf point and Λ against the number of blocks, both routes
  (``bench_chain.py``).

``LANDAU_BENCH_BASELINE_PYTHON=/path/to/other/checkout/.venv/bin/python`` times that
interpreter side by side with this one in ``coldstart`` and ``figures`` (per-repeat ratios,
min / median / max).

Goals are those of the project's performance plan; CPU time (process time) is used wherever
possible because the wall clock of a shared machine is not the toolkit's cost.
"""

from __future__ import annotations

import argparse
import datetime
import sys
import time
from dataclasses import asdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import benchlib  # noqa: E402
from bench_chain import section_chain  # noqa: E402
from benchlib import GOALS, RAW, TABLES, load, machine  # noqa: E402
from sections_cli import section_coldstart, section_figures, section_help  # noqa: E402
from sections_engine import section_derive, section_lambda  # noqa: E402
from sections_solvers import section_forced, section_galvanetto, section_springblock  # noqa: E402
from sections_springblock_paths import section_springblock_paths  # noqa: E402
from sections_sweep import section_sweep  # noqa: E402
from sections_usersystem import section_usersystem  # noqa: E402

SECTIONS = ("springblock", "springblock-paths", "forced", "galvanetto", "lambda", "derive", "coldstart", "help",
            "figures", "sweep", "usersystem", "chain")
RUNNERS = {"springblock": section_springblock, "springblock-paths": section_springblock_paths,
           "forced": section_forced, "galvanetto": section_galvanetto,
           "lambda": section_lambda, "coldstart": section_coldstart, "help": section_help,
           "figures": section_figures, "sweep": section_sweep, "usersystem": section_usersystem,
           "chain": section_chain}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default=",".join(SECTIONS), help=f"comma-separated sections ({', '.join(SECTIONS)})")
    ap.add_argument("--quick", action="store_true", help="fewer tolerances and points")
    ap.add_argument("--baseline-derive", action="store_true",
                    help="also time the derivation with the direct routes (slow: minutes at 5-6 states)")
    ap.add_argument("--out", default=str(Path(__file__).resolve().parent / "results"),
                    help="folder for tables, JSON and PNGs")
    args = ap.parse_args(argv)
    benchlib.set_results(Path(args.out))
    results = benchlib.RESULTS
    results.mkdir(parents=True, exist_ok=True)
    only = [s.strip() for s in args.only.split(",") if s.strip()]
    bad = [s for s in only if s not in SECTIONS]
    if bad:
        print(f"unknown section(s) {', '.join(bad)} (known: {', '.join(SECTIONS)})", file=sys.stderr)
        return 2
    info = machine()
    info["commit"] = benchlib.commit()
    info["date"] = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    loads = [load()]
    t_start = time.time()
    print(f"machine: {info.get('cpu', '?')}, {info['cpus']} CPUs, load average {loads[0][0]:.1f}")
    for s in only:
        print(f"\n[{s}]", flush=True)
        try:
            if s == "derive":
                section_derive(args.quick, args.baseline_derive)
            else:
                RUNNERS[s](args.quick)
        except Exception as exc:     # one broken section must not hide the others' results
            print(f"  section {s} failed: {type(exc).__name__}: {exc}")
            TABLES[s] = f"failed: {type(exc).__name__}: {exc}"
        loads.append(load())
    info["load average (1 min) during the run"] = [round(x[0], 2) for x in loads]
    info["run seconds"] = round(time.time() - t_start, 1)
    print("\nsummary (goal, measure, value, target, result)")
    for g in GOALS:
        print("  " + g.line())
    from landau.support.io import atomic_write_json, atomic_write_text

    md = ["# Benchmarks", "", "Machine: " + ", ".join(f"{k} {v}" for k, v in info.items()), "",
          "## Goals", "", "| goal | measure | value | target | result | note |", "|---|---|---|---|---|---|"]
    md += [f"| {g.goal} | {g.measure} | {g.value:.3g} | {g.sense} {g.target:g} | {'PASS' if g.passed else 'FAIL'} | "
           f"{g.note} |" for g in GOALS]
    for s in only:
        md += ["", f"## {s}", "", TABLES.get(s, "")]
    tag = ("quick" if args.quick else "full") + ("" if set(only) == set(SECTIONS) else "-" + "-".join(only))
    atomic_write_text(results / f"results-{tag}.md", "\n".join(md) + "\n")
    atomic_write_json(results / f"results-{tag}.json", {"machine": info, "sections": only,
                                                        "goals": [asdict(g) | {"passed": g.passed} for g in GOALS],
                                                        "tables": {s: TABLES.get(s, "") for s in only}, "raw": RAW})
    print(f"\nwrote {results / f'results-{tag}.md'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
