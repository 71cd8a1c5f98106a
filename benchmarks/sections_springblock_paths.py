"""The ``springblock-paths`` section: the spring–block's quasi-dynamic cell and load histories on
the compiled Radau IIA against the scipy routes they replaced, at equal error.

Cases (what users run: :func:`simulate_quasidynamic` and :func:`simulate_history` with their
defaults, the series recorded):

* ``M = 0 cell`` — the BP1-like cell of ``tests/springblock/test_quasidynamic.py`` (Dieterich
  law, σ = 50 MPa, L = 8 mm, η = 4.624e6 Pa s/m, V = 1e-6 m/s) at k = 0.5 k_c from the linear
  mode at X = 0.5 L, three linear periods: the orbit grows to stick–slip (v from 2e-3 V to
  3e5 V); error of the final (ξ, ψ);
* ``velocity steps, M = 0`` — 1e-5 → 1e-4 → 1e-5 → 1e-4 m/s every 10 s (Dieterich defaults,
  σ = 11.77 N, η = 100 N s/m, k = 4e5 N/m), ending 0.05 s after the last step, mid-transient;
* ``slide-hold-slide, M > 0`` and ``M = 0`` — 1e-5 m/s, a 100 s hold, reload, ending 0.5 s into
  the reload (M > 0: the default block at k = 2 k_c; M = 0: as the velocity steps).

The error of a history is the largest difference of the final ln v, ln φ (and F/(kL) where the
run records F) from the reference, scipy's route at rtol 1e-12 (:mod:`scipy_springblock_paths`;
at M = 0 the implicit slip rate, an independent formulation).  Both routes run down the same
tolerance ladder; CPU time is process time, best of three rounds for the compiled route, one for
scipy's (runs of 0.05–3 s); the ratio is read along both Pareto fronts at errors both reach
(:func:`benchlib.ratios_at_equal_error`).  Every compiled kernel is built before the timing; the
first-build cost is measured separately in a fresh process with new landau and numba caches.
"""

from __future__ import annotations

import json
import math
import sys
import tempfile
from pathlib import Path

import numpy as np
from benchlib import RAW, TABLES, Goal, cpu_time, fresh_env, ratios_at_equal_error, report, table, timed_process

OURS = "compiled Radau IIA (landau)"
THEIRS = "scipy route (before)"
#: the speed goal of the compiled paths at equal error
GOAL = 20.0


def _bp1_cell():
    from landau.laws import get_law
    from landau.verify.springblock.checks import predict
    from landau.verify.springblock.quasidynamic import QuasiDynamicCell

    prm = dict(a=0.010, b=0.015, L=8e-3, sigma=50e6, eta=4.624e6, V_s=1e-6, a_v=0.6, M=0.0)
    law = get_law("dieterich")
    V = 1e-6
    pr = predict(law, V, prm)
    cell = QuasiDynamicCell.build(law, V, 0.5 * pr.kc, prm)
    return cell, cell.perturbed(0.5 * cell.ell), 3 * 2 * math.pi / pr.omega_c


def _cases():
    """name -> (ours(rtol) -> final vector, theirs(rtol) -> final vector)."""
    import scipy_springblock_paths as base

    from landau.laws import get_law
    from landau.systems.system import SpringBlock
    from landau.verify.springblock.quasidynamic import simulate_quasidynamic

    law = get_law("dieterich")
    cell, y0, T = _bp1_cell()

    def cell_ours(rtol):
        s = simulate_quasidynamic(cell.law, cell.V, cell.k, cell, T, y0, rtol=rtol)
        return np.r_[s.y[0, -1] / cell.ell, math.log(s.y[3, -1] / cell.phi0[0])]

    out = {"M = 0 cell": (cell_ours, lambda rtol: base.cell_run(cell, y0, T, rtol))}
    p = SpringBlock(law).resolve(None)
    k_m = 2 * p["sigma"] * (p["b"] - p["a"]) / p["L"]
    qd = {"M": 0.0, "eta": 100.0, "sigma": 1.2 * 9.81}
    hists = {"velocity steps, M = 0": ("1e-5@0,1e-4@10,1e-5@20,1e-4@30", 4e5, qd, 30.05),
             "slide-hold-slide, M > 0": ("1e-5@0,0@5,1e-5@105", k_m, None, 105.5),
             "slide-hold-slide, M = 0": ("1e-5@0,0@5,1e-5@105", 4e5, qd, 105.5)}
    for name, (h, k, prm, t_end) in hists.items():
        out[name] = _history_pair(law, h, k, prm, t_end, p["L"], base)
    return out


def _history_pair(law, h, k, prm, t_end, L, base):
    from landau.verify.springblock.history import simulate_history

    def ours(rtol):
        s = simulate_history(law, h, k, prm, t_end, rtol=rtol)
        col = {n: i for i, n in enumerate(s.state_names)}
        v = [math.log(s.y_final[col["v"]]), math.log(s.y_final[col["phi"]])]
        return np.array(v + ([s.y_final[col["F"]] / (k * L)] if "F" in col else []))

    def theirs(rtol):
        y = base.history_run(law, h, k, prm, t_end, rtol)
        return np.array([y[1], y[2]] + ([y[0] / L] if prm else []))

    return ours, theirs


def _first_build() -> dict:
    """CPU seconds of the first runs in a fresh process with new landau and numba caches: the
    Radau IIA loop with the first history kernel, then each other kernel on its own."""
    code = (
        "import json, math, time\n"
        "t0 = time.process_time()\n"
        "from landau.laws import get_law\n"
        "from landau.verify.springblock.history import simulate_history\n"
        "import sys; sys.path.insert(0, %r)\n"
        "from sections_springblock_paths import _bp1_cell\n"
        "from landau.verify.springblock.quasidynamic import simulate_quasidynamic\n"
        "law = get_law('dieterich'); t1 = time.process_time()\n"
        "simulate_history(law, '1e-5@0,0@5,1e-5@15', 2e4, None, t_end=15.5); t2 = time.process_time()\n"
        "simulate_history(law, '1e-5@0,1e-4@10', 4e5, {'M': 0.0, 'eta': 100.0, 'sigma': 11.772}, t_end=10.05)\n"
        "t3 = time.process_time()\n"
        "cell, y0, T = _bp1_cell(); t4 = time.process_time()\n"
        "simulate_quasidynamic(cell.law, cell.V, cell.k, cell, T, y0, rtol=1e-9); t5 = time.process_time()\n"
        "simulate_quasidynamic(cell.law, cell.V, cell.k, cell, T, y0, rtol=1e-9); t6 = time.process_time()\n"
        "print(json.dumps({'import': t1 - t0, 'loop + M > 0 history kernel (first M > 0 history)': t2 - t1,\n"
        "                  'M = 0 history kernel (first M = 0 history)': t3 - t2,\n"
        "                  'cell (lambdified residual, QuasiDynamicCell.build)': t4 - t3,\n"
        "                  'cell kernel (first cell run)': t5 - t4, 'second cell run (warm)': t6 - t5}))\n"
    ) % str(Path(__file__).resolve().parent)
    with tempfile.TemporaryDirectory() as tmp:
        script = Path(tmp) / "first_build.py"
        script.write_text(code)
        out = Path(tmp) / "out.json"
        env = fresh_env(Path(tmp) / "cache")
        wall, cpu, rc, tail = timed_process([sys.executable, "-c",
                                             f"import runpy, sys; sys.stdout = open({str(out)!r}, 'w'); "
                                             f"runpy.run_path({str(script)!r})"], env=env, cwd=tmp, timeout=600)
        if rc != 0 or not out.exists():
            return {"failed": tail}
        res = json.loads(out.read_text().strip().splitlines()[-1])
    res["child CPU s"] = cpu
    res["child wall s"] = wall
    return res


def section_springblock_paths(quick: bool) -> None:
    rtols = [10.0 ** -e for e in ((5, 7, 9) if quick else (5, 6, 7, 8, 9, 10))]
    rows = []
    lines = []
    for name, (ours, theirs) in _cases().items():
        ref = theirs(1e-12)
        ours(1e-6)                      # every kernel built and loaded before the timing
        for rtol in rtols:
            y, cpu = cpu_time(lambda rtol=rtol: ours(rtol), repeat=3)
            rows.append({"case": name, "method": OURS, "rtol": rtol, "error": float(np.max(np.abs(y - ref))),
                         "cpu": cpu})
            y, cpu = cpu_time(lambda rtol=rtol: theirs(rtol), min_time=0.0, repeat=1)
            rows.append({"case": name, "method": THEIRS, "rtol": rtol, "error": float(np.max(np.abs(y - ref))),
                         "cpu": cpu})
        mine = [r for r in rows if r["case"] == name]
        errs = [r["error"] for r in mine]
        targets = [10.0 ** -e for e in range(4, 12) if max(errs) >= 10.0 ** -e >= min(errs)]
        ratios = ratios_at_equal_error(mine, OURS, [THEIRS], targets)
        for tgt, (t_their, t_mine, _) in ratios.items():
            lines.append({"case": name, "error": tgt, "scipy cpu": t_their, "compiled cpu": t_mine,
                          "ratio": t_their / t_mine})
        if ratios:
            worst = min(t / m for t, m, _ in ratios.values())
            report(Goal("springblock-paths", "paths", f"{name}: scipy route / compiled CPU, worst at equal error",
                        worst, GOAL, note=f"errors {min(ratios):.0e}..{max(ratios):.0e}"))
    build = _first_build()
    RAW["springblock-paths"] = {"rows": rows, "ratios": lines, "first build": build}
    TABLES["springblock-paths"] = (
        "Compiled Radau IIA against the scipy routes it replaced (module docstring of "
        "`benchmarks/sections_springblock_paths.py`); error against scipy's route at rtol 1e-12, CPU s "
        "(process time), kernels built before the timing.\n\n"
        + table(rows, ["case", "method", "rtol", "error", "cpu"])
        + "\n\nRatios at equal error (along both Pareto fronts):\n\n"
        + table(lines, ["case", "error", "scipy cpu", "compiled cpu", "ratio"])
        + "\n\nFirst build in a fresh process (new landau and numba caches), CPU s: "
        + ", ".join(f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}" for k, v in build.items()))
    print("  first build (fresh caches, CPU s): "
          + ", ".join(f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}" for k, v in build.items()), flush=True)
