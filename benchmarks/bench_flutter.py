"""Cost of the flutter analysis: the stability diagram (200 values of μ) and the nonlinear coefficients.

For the 2-DOF model of Hoffmann et al. (2002) (its illustrative defaults, cubic contact, damped) and a
4-DOF structure given by its matrices: the complex eigenvalues at 200 values of μ
(:func:`landau.analyses.flutter_diagram.stability_diagram`), then the flutter onset with its amplitude
equation (:func:`landau.analyses.flutter.flutter_hopf`: the threshold scan, the Hopf point at 50
digits, Λ and C of every coordinate).  Warm: each is run once first (imports, sympy caches), then the
best of ``--repeat`` runs is reported.  Goals: the 2-DOF under 1 s, the 4-DOF under 3 s (CPU time).

Run:  python benchmarks/bench_flutter.py [--repeat 3] [--json]
Timings are wall-clock on a shared machine.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

#: the 4-DOF structure of tests/flutter/test_flutter_cli.py
M4 = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0.5, 0], [0, 0, 0, 0.8]]
K4 = [[3e4, 1e4, -1e4, 0], [1e4, 2e4, 0, -5e3], [-1e4, 0, 2e4, 0], [0, -5e3, 0, 1.5e4]]
C4 = [[1, 0, 0, 0], [0, 0.5, 0, 0], [0, 0, 0.2, 0], [0, 0, 0, 0.3]]


def systems():
    from landau.systems.mode_coupling import ContactLaw, ModeCoupling

    return {"2-DOF": ModeCoupling.hoffmann2002(),
            "4-DOF": ModeCoupling(M4, C4, K4, 1, 0, 50.0, 0.1, ContactLaw("cubic", 2e4, 5e8), 0.3)}


def run_once(mc) -> tuple[float, float, float, object]:
    from landau.analyses.flutter import flutter_hopf
    from landau.analyses.flutter_diagram import stability_diagram

    t0, c0 = time.perf_counter(), time.process_time()
    stability_diagram(mc, np.linspace(0.0, 1.5, 200))
    t1 = time.perf_counter()
    res = flutter_hopf(mc)
    t2, c2 = time.perf_counter(), time.process_time()
    return t1 - t0, t2 - t1, c2 - c0, res


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    out = {}
    for name, mc in systems().items():
        run_once(mc)   # warm-up
        runs = [run_once(mc) for _ in range(max(1, args.repeat))]
        diagram = min(r[0] for r in runs)
        hopf = min(r[1] for r in runs)
        total = min(r[0] + r[1] for r in runs)
        cpu = min(r[2] for r in runs)
        res = runs[-1][3]
        out[name] = {"diagram_s": diagram, "hopf_s": hopf, "total_s": total, "cpu_s": cpu, "p_c": res.p_c,
                     "Lambda": res.Lambda}
    if args.json:
        print(json.dumps(out, indent=1))
        return
    print(f"{'system':8} {'diagram (200 mu)':>18} {'onset + Lambda':>16} {'total':>8} {'CPU':>8}   mu_c, Lambda")
    for name, r in out.items():
        print(f"{name:8} {r['diagram_s']:17.3f}s {r['hopf_s']:15.3f}s {r['total_s']:7.3f}s {r['cpu_s']:7.3f}s   "
              f"{r['p_c']:.10g}, {r['Lambda']:.6g}")


if __name__ == "__main__":
    main()
