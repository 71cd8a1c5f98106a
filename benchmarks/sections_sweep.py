"""Sweep section: what the sweep mechanism (landau.sweep) costs and how it scales.

* ``workers`` — wall-clock speed-up from 1 to 2 local worker processes on an ω-sweep of the
  forced oscillator (Skurativskyi et al. 2019) of at least 64 simulation points, both runs in this
  process one after the other (same-run ratio), caches warm.  Goal ≥ 1.8× on a 2-core machine.
  A control in the same run — equal pure-Python loops on 1 and 2 processes — shows what the
  machine gives a second process at that moment (on a shared machine, possibly nothing).
* ``hopf`` — grid points per CPU second of the spring–block's ``hopf`` task in one process (the
  vectorised compiled kernels, a chunk of 4096 points per task), on a velocity grid (the exactly
  cancelled route; goal ≥ 1e5 points/s) and, for information, on a (V, a) grid (the screened
  float route), Dataset assembly included.
* ``overhead`` — per-point cost of the executor path: the ``hopf`` task one point per chunk, in
  this process and on 2 local processes, less the vectorised cost per point.

On a machine with many cores (not this one), ``python benchmarks/sections_sweep.py --scaling
1,2,4,8,16 --points 1000 --periods 200`` measures the speed-up of the ω-sweep of the forced
oscillator (1000 ω × 200 recorded periods) at each number of workers against one worker; the goal
there is ≥ 12× at 16 workers (the previous implementation reached 1.73 / 3.14 / 6.46 / 9.34× at
2 / 4 / 8 / 16: its continuation chunks were few and unequal, and every worker compiled on its
own; chunks are now 8 ω values each, equal in work, and the compiled loop is loaded from numba's
disk cache, compiled once by the calling process).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from benchlib import RAW, TABLES, Goal, report, table  # noqa: E402

#: the ω-sweep of the speed-up measurement: a window of the paper's Fig. 3 (period-1 to chaos)
OMEGA = (19.9, 23.2)


def _omega_sweep(n: int, workers: int, periods: int, quick: bool) -> float:
    """Wall seconds of an ω-sweep of ``n`` points on ``workers`` local processes."""
    import landau

    opts = {"n_first": 40 if quick else 100, "n_step": 20 if quick else 50, "n_keep": periods, "rtol": 1e-8}
    t0 = time.perf_counter()
    ds = landau.sweep("simulate", {"omega": np.linspace(*OMEGA, n)}, model="forced-oscillator", workers=workers,
                      progress=False, options=opts)
    wall = time.perf_counter() - t0
    if not (ds.status == "ok").all():
        raise RuntimeError("a point of the benchmark sweep failed")
    RAW.setdefault("sweep_omega", {})[f"{n}x{workers}"] = np.asarray(ds.impacts_per_period).tolist()
    return wall


def _burn(n: int) -> int:
    s = 0
    for i in range(n):
        s += i * i
    return s


def _control(workers: int, n: int = 4_000_000, tasks: int = 8) -> float:
    """Wall seconds of ``tasks`` equal pure-Python loops on a pool of ``workers`` processes: what the
    machine gives a second process at this moment (the control of the speed-up)."""
    from concurrent.futures import ProcessPoolExecutor

    t0 = time.perf_counter()
    with ProcessPoolExecutor(workers) as ex:
        list(ex.map(_burn, [n] * tasks))
    return time.perf_counter() - t0


def _hopf_rate(grid: dict, repeat: int = 3) -> float:
    import landau

    best = np.inf
    n = int(np.prod([len(v) for v in grid.values()]))
    for _ in range(repeat):
        t0 = time.process_time()
        landau.sweep("hopf", grid, law="dieterich", workers=1, progress=False)
        best = min(best, time.process_time() - t0)
    return n / best


def section_sweep(quick: bool = False) -> None:
    import landau
    from landau.verify.skurativskyi.sweep import warm_up

    warm_up()
    rows = []
    # --- 1 -> 2 workers, >= 64 simulation points
    n = 64
    periods = 50 if quick else 200
    _omega_sweep(8, 1, 5, True)  # loads every compiled piece in this process
    walls = {w: _omega_sweep(n, w, periods, quick) for w in (1, 2)}
    speedup = walls[1] / walls[2]
    control = _control(1) / _control(2)
    rows.append({"measure": "control: 8 equal pure-Python loops, speed-up 1 -> 2 processes (wall)", "value": control,
                 "unit": "x"})
    rows.append({"measure": f"omega-sweep {n} points x {periods} periods, 1 worker", "value": walls[1], "unit": "s"})
    rows.append({"measure": f"omega-sweep {n} points x {periods} periods, 2 workers", "value": walls[2], "unit": "s"})
    report(Goal("sweep", "sweep-1", f"speed-up 1 -> 2 local workers, {n} simulation points (wall)", speedup, 1.8,
                note=f"control on this machine now: {control:.2f}x"))
    if RAW["sweep_omega"][f"{n}x1"] != RAW["sweep_omega"][f"{n}x2"]:
        raise RuntimeError("the ω-sweep differs between 1 and 2 workers")
    # --- hopf points per CPU second in one process
    nV = 20_000 if quick else 100_000
    r1 = _hopf_rate({"V": np.logspace(-7, -2, nV)})
    # the screened float route: V up to 1e-3 m/s (above, near the inertia-free limit, some points are
    # re-evaluated with mpmath at about 1 ms each; the cancelled route has no such points)
    r2 = _hopf_rate({"V": np.logspace(-6, -3, nV // 10), "a": np.linspace(0.02, 0.04, 10)})
    rows.append({"measure": f"hopf, V grid of {nV} (exactly cancelled route)", "value": r1, "unit": "points/CPU s"})
    rows.append({"measure": f"hopf, V x a grid of {nV} (screened float route, V <= 1e-3)", "value": r2,
                 "unit": "points/CPU s"})
    report(Goal("sweep", "sweep-2", "hopf task, spring-block, points per CPU s in one process (V grid)", r1, 1e5))
    # --- per-point overhead of the executor path
    m = 200 if quick else 1000
    grid = {"V": np.logspace(-7, -2, m)}
    t0 = time.perf_counter()
    landau.sweep("hopf", grid, law="dieterich", workers=1, progress=False)
    vec = (time.perf_counter() - t0) / m
    t0 = time.perf_counter()
    landau.sweep("hopf", grid, law="dieterich", workers=1, progress=False, options={"chunk_size": 1})
    inproc = (time.perf_counter() - t0) / m - vec
    t0 = time.perf_counter()
    landau.sweep("hopf", grid, law="dieterich", workers=2, progress=False, options={"chunk_size": 1})
    procs = (time.perf_counter() - t0) / m - vec / 2
    rows.append({"measure": "per-point overhead, one point per chunk, in this process", "value": inproc * 1e3,
                 "unit": "ms"})
    rows.append({"measure": "per-point overhead, one point per chunk, 2 local processes (wall)", "value": procs * 1e3,
                 "unit": "ms"})
    report(Goal("sweep", "sweep-4", "executor path, per-point overhead on 2 local processes, ms (wall)", procs * 1e3,
                10.0, "<=", "one point per chunk; chunks of many points amortise it"))
    TABLES["sweep"] = table(rows, ["measure", "value", "unit"])
    print(TABLES["sweep"])


def scaling(workers: list[int], points: int, periods: int) -> None:
    """Speed-up of the ω-sweep at each number of workers against one (a many-core machine)."""
    from landau.verify.skurativskyi.sweep import warm_up

    warm_up()
    _omega_sweep(8, 1, 5, True)
    base = _omega_sweep(points, 1, periods, False)
    print(f"1 worker: {base:.1f} s")
    for w in workers:
        if w == 1:
            continue
        wall = _omega_sweep(points, w, periods, False)
        print(f"{w} workers: {wall:.1f} s, speed-up {base / wall:.2f}x"
              + ("  (goal >= 12x)" if w == 16 else ""), flush=True)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--scaling", default=None, metavar="N1,N2,...", help="numbers of workers (many-core machine)")
    ap.add_argument("--points", type=int, default=1000)
    ap.add_argument("--periods", type=int, default=200)
    a = ap.parse_args()
    if a.scaling:
        scaling([int(x) for x in a.scaling.split(",")], a.points, a.periods)
    else:
        section_sweep(a.quick)
