"""Wall time of a 500-point × 200-period bifurcation sweep of Skurativskyi et al. (2019).

ω ∈ [17.5, 25] rad/s (Figs 3–5), 500 points, increasing ω, continuation with 50 transient +
150 recorded periods per point (100 + 150 at each chunk's first point), rtol 1e-8, local
processes (all cores), streamed to ``<out>/sweep_500`` (resumable: a second run only reads).
Baseline measured in the same run: the same protocol on the first 5 points with scipy's
DOP853 and an event function (the fastest solve_ivp method in the work-precision
benchmark), extrapolated per period.

Run: ``python -m landau.verify.benchmarks.skurativskyi_sweep_timing [out_dir]``.
"""

from __future__ import annotations

import shutil
import sys
import time
from pathlib import Path

import numpy as np

from landau.verify.skurativskyi.sweep import CHUNK_SIZE, SweepSpec, run_sweep


def main(out_dir: str = "benchmarks_out") -> str:
    out = Path(out_dir) / "sweep_500"
    if out.exists():
        shutil.rmtree(out)
    om = np.linspace(17.5, 25.0, 500)
    spec = SweepSpec(n_first=100, n_step=50, n_keep=150, rtol=1e-8)
    t0 = time.perf_counter()
    run_sweep(om, "up", out=out, spec=spec, progress=True)
    wall = time.perf_counter() - t0
    periods = 500 * 200 + -(-500 // CHUNK_SIZE) * 50  # each chunk's first point has 50 more transient periods
    # baseline: scipy DOP853 with events on 3 periods at ω = 20 from the toolkit's attractor
    from landau.verify.benchmarks.skurativskyi_work_precision import scipy_run
    from landau.verify.skurativskyi.model import Params
    t1 = time.process_time()
    scipy_run(Params(omega=20.0), 3, "DOP853", 1e-8, budget=120)
    per_period = (time.process_time() - t1) / 3
    text = (f"500 points × 200 periods (ω ∈ [17.5, 25], rtol 1e-8): {wall:.1f} s wall on local processes "
            f"({periods} periods in total, {1e3 * wall / periods:.2f} ms per period wall); "
            f"scipy DOP853+events at rtol 1e-8: {per_period:.3f} s CPU per period → the same sweep ≈ "
            f"{per_period * periods / 3600:.1f} CPU hours")
    print(text)
    return text


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "benchmarks_out")
