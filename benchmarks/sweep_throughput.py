"""Points per second of the ``hopf``, ``check`` and ``regime`` sweeps on 1 and 2 workers, local
processes and a dask local cluster, with the parallel efficiency (rate on 2 / (2 × rate on 1)).

Each run is ``landau.sweep`` of a fixed grid written to a file in a fresh folder (the store as users
run it), the caches warm (a first small run of each task is not timed); the wall time includes the
pool's or cluster's start, as users pay it.  The results file carries the commit, the machine's
cores and its load average before and after each run: on a shared machine the efficiency is that
of the cores the others left free.

Run: ``python benchmarks/sweep_throughput.py --json benchmarks/results/sweep-throughput.json``.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

#: task -> (grid, options): sized so that a run takes seconds on one worker
CASES = {
    "hopf": ({"V": np.logspace(-6, -3, 400).tolist(), "a": np.linspace(0.005, 0.04, 500).tolist()}, {}),
    "check": ({"V": np.logspace(-5, -3, 8).tolist()}, {"eps2": 1e-3}),
    "regime": ({"V": np.logspace(-4, -3, 8).tolist(),
                "k": (777410.5656372706 * np.linspace(0.8, 1.2, 8)).tolist()}, {}),
}


def _run(task: str, where: str, n: int) -> dict:
    import landau

    grid, options = CASES[task]
    points = int(np.prod([len(v) for v in grid.values()]))
    with tempfile.TemporaryDirectory() as tmp:
        load0 = os.getloadavg()[0]
        t0 = time.perf_counter()
        if where == "dask":
            from distributed import Client, LocalCluster

            with LocalCluster(n_workers=n, threads_per_worker=1, dashboard_address=None) as cluster, \
                    Client(cluster) as client:
                ds = landau.sweep(task, grid, law="dieterich", executor=client.get_executor(), workers=n,
                                  out=Path(tmp) / "s.nc", progress=False, options=options)
        else:
            ds = landau.sweep(task, grid, law="dieterich", workers=n, out=Path(tmp) / "s.nc", progress=False,
                              options=options)
        wall = time.perf_counter() - t0
    return {"task": task, "executor": where, "workers": n, "points": points, "wall_s": wall,
            "points_per_s": points / wall, "ok": int((ds.status == "ok").sum()), "load_before": load0,
            "load_after": os.getloadavg()[0]}


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description="points/s of sweeps on 1 and 2 workers")
    ap.add_argument("--tasks", default="hopf,check,regime")
    ap.add_argument("--json", default=None)
    args = ap.parse_args(argv)
    import landau

    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    doc: dict = {"commit": commit, "cpus": os.cpu_count(), "load_at_start": os.getloadavg(), "runs": []}
    for task in args.tasks.split(","):
        grid, options = CASES[task]
        first = {k: v[:1] for k, v in grid.items()}
        landau.sweep(task, first, law="dieterich", workers=1, progress=False, options=options)   # warm caches
        rates = {}
        for where in ("processes", "dask"):
            for n in (1, 2):
                run = _run(task, where, n)
                doc["runs"].append(run)
                rates[(where, n)] = run["points_per_s"]
                print(json.dumps(run), flush=True)
            doc.setdefault("efficiency", {})[f"{task} {where}"] = rates[(where, 2)] / (2 * rates[(where, 1)])
    doc["load_at_end"] = os.getloadavg()
    text = json.dumps(doc, indent=1)
    print(text)
    if args.json:
        Path(args.json).write_text(text + "\n")


if __name__ == "__main__":
    main()
