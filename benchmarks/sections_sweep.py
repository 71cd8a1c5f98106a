"""Sweep section: what the sweep mechanism (landau.sweep) costs and how it scales.

* ``workers`` — wall-clock speed-up from 1 to 2 local worker processes on an ω-sweep of the
  forced oscillator (Skurativskyi et al. 2019): 128 simulation points × 200 recorded periods (16
  chunks of 8 ω, so that the per-point work dominates and the two workers stay busy to the end),
  caches warm, as users run it (the calling process compiles or loads the integrator once, the
  forked workers inherit it).  A/B pairs alternated — 1 worker, 2 workers, 1, 2, … (3 pairs) —
  each pair with its own control: equal pure-Python loops on 1 and 2 processes, what the machine
  gave a second process at that moment (on a shared machine, possibly much less than 2×).  The
  ratio's min / median / max over the pairs is reported, the goal read on the median (≥ 1.8× on
  a 2-core machine).  The cost of starting the two workers (a pool forked and a round trip to
  each) is measured separately and is included in the 2-worker wall time, as users pay it.
  Two figures the load of a shared machine does not move: the CPU seconds of each run (this
  process and its workers; equal for 1 and 2 workers when no work is repeated and no worker
  compiles), and the speed-up on two free cores projected from each chunk's CPU time, dealt to
  two workers in the engine's order (the load balance of the chunks is in it).
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
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from benchlib import RAW, TABLES, Goal, report, table  # noqa: E402

#: the ω-sweep of the speed-up measurement: a window of the paper's Fig. 3 (period-1 to chaos)
OMEGA = (19.9, 23.2)


def _cpu() -> float:
    """CPU seconds (user + sys) of this process and of its children that have ended."""
    import resource

    me, kids = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return me.ru_utime + me.ru_stime + kids.ru_utime + kids.ru_stime


def _omega_sweep(n: int, workers: int, periods: int, quick: bool, cpu: list | None = None) -> float:
    """Wall seconds of an ω-sweep of ``n`` points on ``workers`` local processes (the CPU seconds of
    this process and its workers appended to ``cpu``)."""
    import landau

    opts = {"n_first": 40 if quick else 100, "n_step": 20 if quick else 50, "n_keep": periods, "rtol": 1e-8}
    c0 = _cpu()
    t0 = time.perf_counter()
    ds = landau.sweep("simulate", {"omega": np.linspace(*OMEGA, n)}, model="forced-oscillator", workers=workers,
                      progress=False, options=opts)
    wall = time.perf_counter() - t0
    if cpu is not None:
        cpu.append(_cpu() - c0)   # the pool's workers have been joined: their CPU time is counted
    if not (ds.status == "ok").all():
        raise RuntimeError("a point of the benchmark sweep failed")
    got = np.asarray(ds.impacts_per_period).tolist()
    seen = RAW.setdefault("sweep_omega", {}).setdefault(f"{n}", got)
    if seen != got:
        raise RuntimeError(f"the ω-sweep differs between runs ({workers} worker(s))")
    return wall


def _burn(n: int) -> int:
    s = 0
    for i in range(n):
        s += i * i
    return s


def _noop(_: int) -> int:
    return os.getpid()


def _control(workers: int, n: int = 4_000_000, tasks: int = 8) -> float:
    """Wall seconds of ``tasks`` equal pure-Python loops on a pool of ``workers`` processes: what the
    machine gives a second process at this moment (the control of the speed-up)."""
    from concurrent.futures import ProcessPoolExecutor

    t0 = time.perf_counter()
    with ProcessPoolExecutor(workers) as ex:
        list(ex.map(_burn, [n] * tasks))
    return time.perf_counter() - t0


def _startup(workers: int = 2, repeat: int = 5) -> float:
    """Median wall seconds to start ``workers`` local processes as a sweep does (forked from this
    process, with everything it loaded), reach each once and shut them down."""
    from concurrent.futures import ProcessPoolExecutor

    walls = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        with ProcessPoolExecutor(workers) as ex:
            pids = set(ex.map(_noop, range(4 * workers)))
        walls.append(time.perf_counter() - t0)
        if len(pids) < 1:
            raise RuntimeError("no worker answered")
    return float(np.median(walls))


def _pairs(n: int, periods: int, pairs: int, quick: bool) -> list[dict]:
    """``pairs`` A/B pairs, alternated: 1 worker then 2 workers, each pair with its control.

    Besides the wall times, the CPU seconds of each run (this process and its workers): their
    ratio is what the 2-worker run costs in total against one worker (1.0: no overhead), and
    2 × CPU(1) / CPU(2) is the speed-up the run would reach on two free cores with perfectly
    balanced workers — a figure the load of a shared machine does not move."""
    rows = []
    for i in range(pairs):
        cpu: list[float] = []
        w1 = _omega_sweep(n, 1, periods, quick, cpu)
        w2 = _omega_sweep(n, 2, periods, quick, cpu)
        c1, c2 = _control(1), _control(2)
        rows.append({"pair": i + 1, "1 worker (s)": w1, "2 workers (s)": w2, "speed-up": w1 / w2,
                     "control speed-up": c1 / c2, "CPU 1 worker (s)": cpu[0], "CPU 2 workers (s)": cpu[1],
                     "CPU ratio": cpu[1] / cpu[0]})
        print(f"  pair {i + 1}: {w1:.1f} s / {w2:.1f} s = {w1 / w2:.2f}x (control {c1 / c2:.2f}x); "
              f"CPU {cpu[0]:.1f} s / {cpu[1]:.1f} s", flush=True)
    return rows


def _projection(n: int, periods: int, quick: bool, workers: int = 2) -> dict:
    """The speed-up the ω-sweep would reach on ``workers`` free cores: each chunk's CPU seconds, run
    in this process, dealt to the workers as the engine deals them (in grid order, each chunk to the
    first worker free), against the sum.  CPU time, so the load of a shared machine barely moves it;
    the load balance of the chunks is in it, the start-up of the workers (measured apart) is not."""
    import heapq

    from landau.analyses.sweep_engine import make_grid, run_chunk
    from landau.analyses.sweep_tasks import make_task

    opts = {"n_first": 40 if quick else 100, "n_step": 20 if quick else 50, "n_keep": periods, "rtol": 1e-8}
    task = make_task("simulate", "forced-oscillator", None, {}, opts)
    grid = make_grid({"omega": np.linspace(*OMEGA, n)}, task.units())
    task = task.for_grid(grid)
    cost = []
    for ch in task.chunks(grid):
        t0 = time.process_time()
        run_chunk(task, ch)
        cost.append(time.process_time() - t0)
    free = [0.0] * workers
    for c in cost:
        heapq.heapreplace(free, free[0] + c)
    return {"chunks": len(cost), "cpu": sum(cost), "makespan": max(free), "speed-up": sum(cost) / max(free)}


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
    # --- 1 -> 2 workers, >= 64 simulation points, alternated A/B pairs
    n = 64 if quick else 128
    periods = 50 if quick else 200
    _omega_sweep(8, 1, 5, True)  # loads every compiled piece in this process
    start = _startup(2)
    pairs = _pairs(n, periods, 3, quick)
    RAW["sweep_pairs"] = pairs
    sp = np.array([r["speed-up"] for r in pairs])
    ctl = np.array([r["control speed-up"] for r in pairs])
    rows.append({"measure": f"omega-sweep {n} points x {periods} periods, 1 worker, median of {len(pairs)}",
                 "value": float(np.median([r["1 worker (s)"] for r in pairs])), "unit": "s"})
    rows.append({"measure": f"omega-sweep {n} points x {periods} periods, 2 workers, median of {len(pairs)}",
                 "value": float(np.median([r["2 workers (s)"] for r in pairs])), "unit": "s"})
    rows.append({"measure": "speed-up 1 -> 2 workers, min / median / max over the pairs",
                 "value": f"{sp.min():.2f} / {np.median(sp):.2f} / {sp.max():.2f}", "unit": "x"})
    rows.append({"measure": "control: 8 equal pure-Python loops, speed-up 1 -> 2 processes, min / median / max",
                 "value": f"{ctl.min():.2f} / {np.median(ctl):.2f} / {ctl.max():.2f}", "unit": "x"})
    cr = np.array([r["CPU ratio"] for r in pairs])
    rows.append({"measure": "CPU seconds of the 2-worker run / of the 1-worker run (this process and its "
                            "workers), min / median / max", "value": f"{cr.min():.3f} / {np.median(cr):.3f} / "
                                                                    f"{cr.max():.3f}", "unit": "x"})
    rows.append({"measure": "speed-up on two free cores, perfectly balanced: 2 x CPU(1) / CPU(2), median",
                 "value": float(2 / np.median(cr)), "unit": "x"})
    proj = _projection(n, periods, quick)
    RAW["sweep_projection"] = proj
    rows.append({"measure": f"speed-up on two free cores, from each of the {proj['chunks']} chunks' CPU time dealt "
                            "to 2 workers as the engine deals them (load balance included, start-up not)",
                 "value": proj["speed-up"], "unit": "x"})
    rows.append({"measure": "the same with the worker start-up below added to the 2-worker time",
                 "value": proj["cpu"] / (proj["makespan"] + start), "unit": "x"})
    rows.append({"measure": "worker start-up: 2 processes forked, reached and shut down (median of 5; "
                            "inside the 2-worker times)", "value": start * 1e3, "unit": "ms"})
    report(Goal("sweep", "sweep-1", f"speed-up 1 -> 2 local workers, {n} simulation points (wall, median of "
                f"{len(pairs)} alternated pairs)", float(np.median(sp)), 1.8,
                note=f"pairs {sp.min():.2f}-{sp.max():.2f}x; control on this machine then: "
                     f"{ctl.min():.2f}-{ctl.max():.2f}x (median {np.median(ctl):.2f}x)"))
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
    TABLES["sweep"] = (table(rows, ["measure", "value", "unit"]) + "\n\nThe alternated pairs (1 worker, then 2 "
                       "workers, then the control of that moment):\n\n"
                       + table(pairs, ["pair", "1 worker (s)", "2 workers (s)", "speed-up", "control speed-up",
                                       "CPU 1 worker (s)", "CPU 2 workers (s)", "CPU ratio"]))
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
