"""Benchmark: default integrator vs ``solve_ivp(Radau)`` with a plain Python right-hand side.

Problem: one period of the Fig. 3 stick–slip cycle (Dieterich, V/V_* = 100, κ = 1e-3,
m ≈ 1.13e-7; :mod:`landau.verify.springblock.workprecision`).  Both integrators run over a
tolerance ladder in the same process; the CPU time at equal error 1e-8 (error at the end of
the period vs the rtol = 1e-13 reference) is interpolated log–log from the two bracketing
runs, and the ratio is printed.  Goal: ≥ 20×.

    python -m landau.verify.springblock.benchmark
"""

from __future__ import annotations

import sys
import time

import numpy as np

from landau.verify.springblock.simulate import W_INDEX, integrate
from landau.verify.springblock.workprecision import _timed, error, fig3_cycle, fig3_model, scipy_run

TARGET_ERROR = 1e-8


def cpu_at_error(points: list[tuple[float, float]], target: float = TARGET_ERROR) -> float:
    """log–log interpolation of CPU time at ``target`` error from (error, cpu) pairs."""
    pts = sorted(points)
    for (e0, c0), (e1, c1) in zip(pts, pts[1:], strict=False):  # consecutive pairs
        if e0 <= target <= e1:
            w = (np.log(target) - np.log(e0)) / (np.log(e1) - np.log(e0))
            return float(np.exp(np.log(c0) + w * (np.log(c1) - np.log(c0))))
    raise RuntimeError(f"target error {target:g} not bracketed by {pts}")


def main(argv=None) -> int:
    t_start = time.time()
    model = fig3_model()
    orbit = fig3_cycle(model)
    y0 = np.insert(orbit.z, W_INDEX, 0.0)
    T = orbit.period
    ref = integrate(model, y0, (0.0, T), rtol=1e-13).y_final
    print(f"Fig. 3 cycle: T = {T:.6g} s, v in [{orbit.v_min:.3g}, {orbit.v_max:.3g}] m/s; m = {model.m:.4g}, "
          f"kappa = {model.kappa:.3g}")
    ours, theirs = [], []
    for rtol in (1e-7, 1e-8, 1e-9, 1e-10, 1e-11):
        run, cpu = _timed(lambda rtol=rtol: integrate(model, y0, (0.0, T), rtol=rtol), min_time=0.2)
        ours.append((error(run.y_final, ref), cpu))
        print(f"  default    rtol {rtol:6.0e}: error {ours[-1][0]:.3e}, cpu {cpu * 1e3:9.3f} ms, steps {run.nsteps}")
    for rtol in (1e-7, 1e-8, 1e-9, 1e-10):
        (y, steps, _), cpu = _timed(lambda rtol=rtol: scipy_run(model, y0, T, "Radau", rtol, False), min_time=0.0)
        theirs.append((error(y, ref), cpu))
        print(f"  scipy Radau rtol {rtol:6.0e}: error {theirs[-1][0]:.3e}, cpu {cpu * 1e3:9.3f} ms, steps {steps}")
    a, b = cpu_at_error(ours), cpu_at_error(theirs)
    print(f"CPU at error {TARGET_ERROR:g}: default {a * 1e3:.3f} ms, solve_ivp(Radau, plain Python RHS) "
          f"{b * 1e3:.1f} ms  ->  speed-up {b / a:.0f}x (goal >= 20x)   [{time.time() - t_start:.0f} s total]")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
