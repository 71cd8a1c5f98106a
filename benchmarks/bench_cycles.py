"""Cost of a branch of 200 cycles with Floquet multipliers (landau.periodic) against scipy's solve_bvp.

The system: Rössler (1976), a = b = 0.2, continued in c from its stable period-1 cycle at c = 2.5
(3 states). Ours: :func:`landau.periodic.continue_cycles` — 200 pseudo-arclength steps, orthogonal
collocation (ntst 40, m 4), the multipliers at every point, detection and location of the special
points on (the two period doublings the branch crosses). Warm: one run first (imports, caches), then
the best CPU time of ``--repeat`` runs.

The peer, in the same run: :func:`scipy.integrate.solve_bvp` — a Python-stepped collocation BVP
solver (4th-order Lobatto IIIA with residual-controlled mesh refinement) — solving the same 200
cycles by natural-parameter continuation, each from the previous solution, for y′ = T f(y; c),
y(0) = y(1), the phase fixed by ẏ₂(0) = 0, at ``tol`` 1e-8, at the c values of our branch. It
computes no multipliers (scipy has none), so the ratio understates our advantage by their cost.

Run:  python benchmarks/bench_cycles.py [--repeat 3] [--json]
Writes benchmarks/results/results-cycles.json (commit, machine, load, CPU seconds, the ratio).
Goal: our branch under 10 CPU-s warm.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402

from landau.periodic.examples import ROSSLER_AB  # noqa: E402

GOAL_S = 10.0


def problem():
    from landau.periodic.examples import rossler

    return rossler(parameter_range=(0.0, 100.0))


def start(pr):
    from scipy.integrate import solve_ivp

    from landau.periodic import CycleStart

    sol = solve_ivp(lambda t, y: pr.rhs(y, 2.5), (0, 300), [1.0, 1.0, 0.0], method="DOP853", rtol=1e-10,
                    atol=1e-12, dense_output=True)
    ts = np.linspace(150, 300, 20001)
    y1 = sol.sol(ts)[1]
    i = np.where((y1[:-1] < 0) & (y1[1:] >= 0))[0]
    t0, t1 = ts[i[-2]], ts[i[-1]]
    tt = np.linspace(t0, t1, 200)
    return CycleStart(tt, sol.sol(tt), t1 - t0, 2.5)


def ours(pr, st):
    from landau.periodic import continue_cycles

    return continue_cycles(pr, st, steps=199, ds=0.05, ds_max=0.05, ntst=40)


def peer(pr, br):
    """solve_bvp along the c values of ``br``, warm-started from the previous solution."""
    from scipy.integrate import solve_bvp

    t, Y = br.cycle(0)
    s = t / br.period[0]
    # shift the phase so that ẏ₂(0) = x + a y = 0 with ẏ₂ going down (y at its maximum) at s = 0
    k = int(np.argmax(Y[1]))
    Y = np.concatenate([Y[:, k:-1], Y[:, :k + 1]], axis=1)
    T = br.period[0]
    out = []
    for c in br.parameter:
        def f(x, y, p, c=c):
            return p[0] * pr.rhs(y, c)

        def bc(ya, yb, p):
            return np.array([ya[0] - yb[0], ya[1] - yb[1], ya[2] - yb[2], ya[0] + ROSSLER_AB * ya[1]])

        res = solve_bvp(f, bc, s, Y, p=[T], tol=1e-8, max_nodes=20000)
        if not res.success:
            raise RuntimeError(f"solve_bvp failed at c = {c}: {res.message}")
        s, Y, T = res.x, res.y, float(res.p[0])
        out.append(T)
    return np.array(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    pr = problem()
    st = start(pr)
    br = ours(pr, st)                                   # warm-up
    peer(pr, br)
    cpu_ours, cpu_peer = [], []
    for _ in range(max(1, args.repeat)):
        c0 = time.process_time()
        br = ours(pr, st)
        c1 = time.process_time()
        T_peer = peer(pr, br)
        c2 = time.process_time()
        cpu_ours.append(c1 - c0)
        cpu_peer.append(c2 - c1)
    ours_s, peer_s = min(cpu_ours), min(cpu_peer)
    dT = float(np.max(np.abs(T_peer - np.array(br.period)) / np.array(br.period)))
    res = {
        "benchmark": "cycles", "commit": benchlib.commit(), "machine": benchlib.machine(),
        "load": list(benchlib.load()), "cycles": len(br), "c_range": [br.parameter[0], br.parameter[-1]],
        "special_points": [f"{s.kind}@{s.parameter:.8g}" for s in br.special],
        "ours_cpu_s": ours_s, "peer_solve_bvp_cpu_s": peer_s, "ratio_peer_over_ours": peer_s / ours_s,
        "goal_cpu_s": GOAL_S, "goal_met": ours_s < GOAL_S, "max_relative_period_difference": dT,
        "note": "ours includes the multipliers and the location of the special points; solve_bvp "
                "(a Python-stepped collocation BVP solver, tol 1e-8) solves the same cycles without multipliers",
    }
    out = Path(__file__).resolve().parent / "results" / "results-cycles.json"
    out.write_text(json.dumps(res, indent=2) + "\n")
    if args.json:
        print(json.dumps(res, indent=2))
    else:
        print(f"{len(br)} cycles, c {br.parameter[0]:.4g}…{br.parameter[-1]:.4g}, {res['special_points']}")
        print(f"ours (with multipliers): {ours_s:.2f} CPU-s (goal < {GOAL_S} s: {res['goal_met']})")
        print(f"scipy solve_bvp (no multipliers): {peer_s:.2f} CPU-s; ratio {peer_s / ours_s:.1f}x; "
              f"periods agree to {dT:.1e}")
        print(f"written {out}")


if __name__ == "__main__":
    main()
