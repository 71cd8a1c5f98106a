"""Error against run time of event location on the one-block stick–slip cycle.

Problem: Galvanetto (2004) one block, γ = 3, δ = 0.2, c = 0, V = 1 (Fig. 7a).  From the
end of the stick interval (X = 1, Ẋ = V) the block slips with r < 0 until r = 0 again
(slip→stick).  Measured: the time of that event and the landing position X (the value the
event maps and the type-II locator use).

Methods, each over rtol = 1e-4 … 1e-12 (atol = rtol/100):
* the hybrid engine (``landau.verify.hybrid.simulate``) with DOP853 (default guard scan: 4
  samples per step, which is what catches double crossings, screened on the step's cubic
  Hermite interpolant so that the dense output is built only where a guard may cross; with the
  screen off, i.e. every step scanned on the dense output; and ``samples=0``: step ends
  only, the same information solve_ivp uses) and with RK45;
* ``scipy.integrate.solve_ivp`` with a terminal event (direction +1), DOP853 and RK45.
Reference: the engine at rtol 1e-13, cross-checked against solve_ivp/DOP853 at 1e-13.

Run: ``python -m landau.verify.benchmarks.event_location_galvanetto [out_dir]`` → writes
``event_location_galvanetto.md`` (table) and ``.png`` (error vs time) into out_dir
(default ./benchmarks_out).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

from landau.verify.galvanetto.maps import model_for
from landau.verify.galvanetto.model import one_block
from landau.verify.hybrid import EngineOptions, ScipyStepper, simulate

P = one_block(1.0, gamma=3.0, delta=0.2, c=0.0)
Y0 = np.array([1.0, P.V])
OPTS = EngineOptions(record=False)
UNSCREENED = EngineOptions(record=False, screen=False)


def engine(method: str, rtol: float, opts: EngineOptions = OPTS):
    sol = simulate(model_for(P), "n", Y0, (0.0, 50.0), ScipyStepper(method, rtol, rtol * 1e-2), opts,
                   stop=lambda ev: ev.to_mode == "s")
    return sol.t, sol.y[0], sol.nfev


def baseline(method: str, rtol: float):
    law, V = P.law, P.V
    rhs = lambda t, y: [y[1], -y[0] + law.neg(y[1] - V)]
    ev = lambda t, y: y[1] - V
    ev.terminal, ev.direction = True, 1
    s = solve_ivp(rhs, (0.0, 50.0), Y0, method=method, rtol=rtol, atol=rtol * 1e-2, events=ev)
    return s.t_events[0][0], s.y_events[0][0][0], s.nfev


def timed(fn, *args, repeat: int = 5):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn(*args)
        best = min(best, time.perf_counter() - t0)
    return out, best


def run(out_dir: Path = Path("benchmarks_out")) -> list[dict]:
    t_ref, x_ref, _ = engine("DOP853", 1e-13)
    t_chk, x_chk, _ = baseline("DOP853", 1e-13)
    rows = []
    ends_only = EngineOptions(record=False, samples=0)
    for label, fn, method, extra in (("engine DOP853", engine, "DOP853", ()),
                                     ("engine DOP853 screen off", engine, "DOP853", (UNSCREENED,)),
                                     ("engine DOP853 samples=0", engine, "DOP853", (ends_only,)),
                                     ("engine RK45", engine, "RK45", ()),
                                     ("solve_ivp DOP853", baseline, "DOP853", ()),
                                     ("solve_ivp RK45", baseline, "RK45", ())):
        for rtol in (1e-4, 1e-6, 1e-8, 1e-10, 1e-12):
            (t_ev, x_ev, nfev), sec = timed(fn, method, rtol, *extra)
            rows.append({"method": label, "rtol": rtol, "t_error": abs(t_ev - t_ref), "x_error": abs(x_ev - x_ref),
                         "nfev": int(nfev), "seconds": sec})
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    lines = ["# Event location on the one-block stick–slip cycle (Galvanetto 2004, V=1, γ=3, δ=0.2)", "",
             f"Reference slip→stick time {t_ref:.15g} (engine rtol 1e-13); solve_ivp DOP853 rtol 1e-13 "
             f"differs by {abs(t_chk - t_ref):.2g} in t and {abs(x_chk - x_ref):.2g} in X.", "",
             "| method | rtol | event-time error | landing-X error | nfev | time [ms] |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['method']} | {r['rtol']:.0e} | {r['t_error']:.2e} | {r['x_error']:.2e} | "
                     f"{r['nfev']} | {1e3 * r['seconds']:.2f} |")
    from landau.io import atomic_savefig, atomic_write_text
    atomic_write_text(out_dir / "event_location_galvanetto.md", "\n".join(lines) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for label, mk in (("engine DOP853", "o-"), ("engine DOP853 screen off", "v-"),
                      ("engine DOP853 samples=0", "^-"), ("engine RK45", "s-"),
                      ("solve_ivp DOP853", "o--"),
                      ("solve_ivp RK45", "s--")):
        rr = [r for r in rows if r["method"] == label]
        ax.loglog([r["seconds"] * 1e3 for r in rr], [max(r["t_error"], 1e-17) for r in rr], mk, label=label)
    ax.set_xlabel("run time [ms] (best of 5)")
    ax.set_ylabel("|event time − reference|")
    ax.set_title("Slip→stick event, one block (Galvanetto 2004 Fig. 7a)")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    atomic_savefig(fig, out_dir / "event_location_galvanetto.png", dpi=110, bbox_inches="tight")
    plt.close(fig)
    return rows


if __name__ == "__main__":
    rows = run(Path(sys.argv[1]) if len(sys.argv) > 1 else Path("benchmarks_out"))
    for r in rows:
        print(f"{r['method']:24s} rtol={r['rtol']:.0e}  dt={r['t_error']:.2e}  dX={r['x_error']:.2e}  "
              f"nfev={r['nfev']:5d}  {1e3 * r['seconds']:.2f} ms")
