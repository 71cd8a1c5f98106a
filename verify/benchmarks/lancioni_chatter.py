"""Error against run time of the impact/chatter handling on one periodic orbit (Lancioni et al., set 2).

Orbit: set 2 (m₁ = 0.4, k_φ = 25), μ = 0.47, e_N = 0.2, belt v = −1: a free flight–slip–stick–slip
periodic motion whose landing is a chattering sequence (the paper's Fig. 4/5 regime).  Knob:
the chatter tolerance (inter-impact time below which chattering is ended, the paper's rule)
and the mode integrator's rtol.  Error: |φ̇_max − reference| on the Poincaré section
(φ̈ = 0, φ̇ > 0) after a 12 s transient, reference = tolerance 1e-10 with rtol 1e-12.
Run time: ratio to the cheapest setting in the same run.

    python -m landau.verify.benchmarks.lancioni_chatter
"""

from __future__ import annotations

import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from landau.support.io import atomic_savefig, atomic_write_text  # noqa: E402
from landau.verify.hybrid import DOP853Stepper, simulate  # noqa: E402
from landau.verify.lancioni.contact import default_options  # noqa: E402
from landau.verify.lancioni.model import build, slip_state  # noqa: E402
from landau.verify.lancioni.slip import SET2, equilibrium_phi  # noqa: E402

OUT = Path(__file__).parent / "results"
MU, EN, T_TR, T_END = 0.47, 0.2, 12.0, 15.0


def run(chatter_tol: float, rtol: float):
    cm = build(MU, EN, SET2)
    y0 = slip_state(cm.mech, equilibrium_phi(SET2, MU, 1) + 0.05)
    t0 = time.perf_counter()
    sol = simulate(cm.model, cm.initial_mode(0.0, y0), y0, (0.0, T_END), DOP853Stepper(rtol, rtol * 1e-2),
                   default_options(chatter_tol, record=False))
    dt = time.perf_counter() - t0
    mx = [e.y[2] for e in sol.events.filter(guard="phidot-max") if e.t > T_TR and e.y[2] > 0.5]
    n_imp = len(sol.events.filter(guard="impact"))
    n_z = len(sol.events.filter(kind="zeno"))
    return float(np.max(mx)), dt, n_imp, n_z, sol.nfev


def main() -> None:
    ref = run(1e-10, 1e-12)
    rows = []
    for tol in (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-8):
        for rtol in (1e-6, 1e-9):
            v, dt, ni, nz, nfev = run(tol, rtol)
            rows.append((tol, rtol, abs(v - ref[0]), dt, ni, nz, nfev))
    base = min(r[3] for r in rows)
    lines = ["# Lancioni et al. set 2, μ = 0.47, e_N = 0.2: chatter tolerance sweep", "",
             f"reference φ̇_max = {ref[0]:.12f} (chatter tol 1e-10, rtol 1e-12, {ref[1]:.2f} s, {ref[2]} impacts)", "",
             "| chatter tol | rtol | error φ̇_max | time [s] | time / fastest | impacts | chatter ends | nfev |",
             "|---|---|---|---|---|---|---|---|"]
    for tol, rtol, err, dt, ni, nz, nfev in rows:
        lines.append(f"| {tol:.0e} | {rtol:.0e} | {err:.2e} | {dt:.2f} | {dt / base:.2f} | {ni} | {nz} | {nfev} |")
    OUT.mkdir(exist_ok=True)
    atomic_write_text(OUT / "lancioni_chatter.md", "\n".join(lines) + "\n")
    fig, ax = plt.subplots(figsize=(6, 4))
    for rtol, mk in ((1e-6, "o-"), (1e-9, "s-")):
        rr = [r for r in rows if r[1] == rtol]
        ax.loglog([r[3] for r in rr], [max(r[2], 1e-16) for r in rr], mk, label=f"rtol {rtol:.0e}")
        for r in rr:
            ax.annotate(f"{r[0]:.0e}", (r[3], max(r[2], 1e-16)), fontsize=6)
    ax.set_xlabel("run time [s] (15 s of motion)")
    ax.set_ylabel("|φ̇_max − reference|")
    ax.set_title("chatter tolerance sweep (labels: tolerance)")
    ax.legend()
    atomic_savefig(fig, OUT / "lancioni_chatter.png", dpi=110, bbox_inches="tight")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
