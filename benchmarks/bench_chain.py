"""Cost of the spring–block chain's first Hopf point and Λ against the number of blocks N.

* ``chain`` — :func:`landau.analyses.chain.chain_hopf` for the Dieterich law at its defaults
  (identical blocks, k_coupling = 1e5 N/m, V = 1e-4 m/s) by its default route: the numeric route
  (one block's law jets, sparse LU solves, :mod:`landau.derivation.sparse_hopf`) at N = 10, 20, 50,
  100, and — in the same run — both routes for N = 1…6 (the symbolic route: the general engine at 50
  digits; ``--quick``: N = 1…4), with their ratio and the largest relative difference of p_c, ω_c, Λ,
  χ, C and l₁ between them, and N = 100 once more with OpenBLAS's default threads in the eigenvalue
  scan (the cost that :mod:`landau.support.blas_threads` removes).  Each call is timed warm (a
  first call compiles the law's jets and the engine's kernels) as the best CPU time of three.
  Goals: the exponent of a log–log least-squares fit of CPU-s against N over 10…100 at most 3,
  and N = 50 within 10 CPU-s.

Run:  python benchmarks/bench_chain.py [--quick]    (the ``chain`` section of benchmarks/run.py;
      it writes benchmarks/results/results-full-chain.json, then python benchmarks/report.py)
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from benchlib import RAW, TABLES, Goal, cpu_time, report, table  # noqa: E402

#: the chain sizes of the scaling fit
SIZES = (10, 20, 50, 100)
FIELDS = ("p_c", "omega_c", "Lambda", "chi", "C", "l1")


def _call(n: int, route: str = "auto"):
    from landau.analyses.chain import chain_hopf
    from landau.systems.chain import SpringBlockChain

    return chain_hopf(SpringBlockChain("dieterich", n), {}, route=route)


def section_chain(quick: bool) -> None:
    _call(1, "numeric")
    _call(1, "symbolic")                   # warm: the law jets and the engine's kernels compiled
    rows = []
    for n in SIZES:
        res, cpu = cpu_time(lambda n=n: _call(n), min_time=0.0, repeat=3)
        rows.append({"N": n, "states": 3 * n, "route": res.extra["route"], "CPU-s": cpu, "k_c": res.p_c,
                     "Lambda": res.Lambda, "mode": res.extra["mode"]})
        print(f"  N = {n:3d}: {cpu:.3f} CPU-s ({res.extra['route']})", flush=True)
    ns = np.array([r["N"] for r in rows], dtype=float)
    ts = np.array([r["CPU-s"] for r in rows])
    slope = float(np.polyfit(np.log(ns), np.log(ts), 1)[0])
    report(Goal("chain", "chain-1", "chain_hopf CPU-s ~ N^x over N = 10…100 (log-log least squares): x",
                slope, 3.0, "<="))
    report(Goal("chain", "chain-2", "chain_hopf at N = 50 blocks, CPU-s", float(ts[list(ns).index(50)]), 10.0, "<="))
    # the eigenvalue scan with OpenBLAS's default threads (landau.support.blas_threads off), same run
    import contextlib

    import landau.derivation.sparse_hopf as sh

    guard = sh.one_blas_thread
    sh.one_blas_thread = contextlib.nullcontext        # type: ignore[assignment]
    try:
        _, threaded = cpu_time(lambda: _call(100), min_time=0.0, repeat=3)
    finally:
        sh.one_blas_thread = guard
    one = float(ts[list(ns).index(100)])
    print(f"  N = 100 with the default BLAS threads: {threaded:.3f} CPU-s ({threaded / one:.1f}x one thread)")
    both = []
    for n in range(1, (4 if quick else 6) + 1):
        num, c_num = cpu_time(lambda n=n: _call(n, "numeric"), min_time=0.0, repeat=3)
        sym, c_sym = cpu_time(lambda n=n: _call(n, "symbolic"), min_time=0.0, repeat=1 if n > 4 else 3)
        diff = max(abs(getattr(num, f) / getattr(sym, f) - 1) for f in FIELDS)
        both.append({"N": n, "numeric CPU-s": c_num, "symbolic CPU-s": c_sym, "symbolic / numeric": c_sym / c_num,
                     "max rel. difference": diff})
        print(f"  N = {n}: numeric {c_num:.3f}, symbolic {c_sym:.3f} CPU-s, difference {diff:.1e}", flush=True)
    rows.append({"N": 100, "states": 300, "route": "numeric, default BLAS threads", "CPU-s": threaded,
                 "k_c": rows[-1]["k_c"], "Lambda": rows[-1]["Lambda"], "mode": rows[-1]["mode"]})
    RAW["chain"] = rows
    RAW["chain_routes"] = both
    TABLES["chain"] = (
        "`chain_hopf(SpringBlockChain('dieterich', N))` at the defaults, its default route (best CPU of 3, warm); "
        f"fitted exponent over N = 10…100: **{slope:.2f}**; the last row is N = 100 with OpenBLAS's default "
        f"threads in the eigenvalue scan ({threaded / one:.1f}× the CPU of one thread, "
        "`landau.support.blas_threads`).\n\n" + table(rows, list(rows[0]))
        + "\n\nBoth routes in the same run (the default chooses the symbolic route up to 3 blocks, for its 50 "
        "digits, Λ's round-off bound and the verdict at a degenerate point; the numeric one beyond):\n\n"
        + table(both, list(both[0])))


def main(argv=None) -> int:
    import run

    return run.main(["--only", "chain", *(argv if argv is not None else sys.argv[1:])])


if __name__ == "__main__":
    raise SystemExit(main())
