"""Engine sections: Λ(V) throughput and accuracy, derivation cost against the number of states.

* ``lambda`` — Λ(V) of every built-in one-state law: throughput of ``Derivation.evaluate`` on
  one thread against ``sympy.lambdify(cse=True)`` of the same expression, the first call, and
  the error of 1000 points against 50-digit mpmath.
* ``derive`` — derivation + compile CPU time of Dieterich-type laws with 1…6 state variables
  (fresh interpreter each), with the growth exponent; ``--baseline-derive`` adds the direct
  routes (numeric conversion of symbolic pivots, Berkowitz determinant) for comparison.
"""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from benchlib import RAW, TABLES, Goal, cpu_time, report, table


# --------------------------------------------------------------------------------------------
# Λ(V) (goal 5)
def lambda_row(name: str, n_points: int, accuracy: bool = True) -> dict:
    """Λ(V) of the built-in law ``name`` on ``n_points`` log-spaced points of its velocity-weakening
    range, one thread: the engine's throughput (best repeated call, and its first call) and that of
    ``sympy.lambdify(cse=True)`` of the same expression in the same run; with ``accuracy``, the
    relative error of 1000 points against the 50-digit evaluation.  Used by :func:`section_lambda`
    and by the drift test (``tests/codegen/test_benchmark_drift.py``)."""
    import mpmath
    import sympy as sp

    import landau.derivation.multiscale as ms
    import landau.derivation.precision as precision
    from landau.laws import get_law
    from landau.systems.system import SpringBlock

    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
    from vw_ranges import vw_range

    workers = precision.WORKERS
    precision.WORKERS = 1               # single-threaded, like the lambdify baseline
    try:
        lo, hi, ends = vw_range(name)
        lo, hi = (lo * (1 + 1e-3) if lo in ends else lo), (hi * (1 - 1e-3) if hi in ends else hi)
        Vs = np.logspace(np.log10(lo), np.log10(hi), n_points)
        d = ms.derive(SpringBlock(get_law(name)), ["Lambda"])
        t0 = time.process_time()
        d.evaluate(Vs[:10], {}, ["Lambda"])
        compile_s = time.process_time() - t0
        t0 = time.process_time()
        d.evaluate(Vs, {}, ["Lambda"])
        first = n_points / (time.process_time() - t0)
        _, t_eng = cpu_time(lambda: d.evaluate(Vs, {}, ["Lambda"]), repeat=2)
        block = d.block
        p = block.resolve()
        expr = d.coefficient("Lambda").expr
        args = list(block.args)
        fn = sp.lambdify(args, expr, modules="numpy", cse=True)
        vals = block.argvals(Vs, p)
        with np.errstate(all="ignore"):
            _, t_lam = cpu_time(lambda: fn(*vals), repeat=2)
        row = {"law": name, "points": n_points, "engine pts/s": n_points / t_eng,
               "lambdify(cse) pts/s": n_points / t_lam,
               "first call pts/s": first, "compile s": compile_s}
        if accuracy:
            # accuracy: 1000 log-spaced points against the 50-digit evaluation
            Vc = np.logspace(np.log10(lo), np.log10(hi), 1000)
            got = d.evaluate(Vc, {}, ["Lambda"])["Lambda"]
            errs = []
            for V0, g in zip(Vc, got, strict=True):
                with mpmath.workdps(50):
                    want = d.evaluate_mp(float(V0), {}, ["Lambda"], dps=50)["Lambda"]
                errs.append(float(abs(g - want) / abs(want)) if want != 0 else abs(g))
            errs = np.array(errs)
            row.update({"max rel err": float(errs.max()), "points > 1e-10": int((errs > 1e-10).sum())})
        return row
    finally:
        precision.WORKERS = workers


def section_lambda(quick: bool) -> None:
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
    from vw_ranges import LAWS

    n_points = 200_000 if quick else 1_000_000
    rows = []
    for name in LAWS:
        rows.append(lambda_row(name, n_points))
        r = rows[-1]
        print(f"  {name:20s} engine {r['engine pts/s']:.3g}/s  "
              f"lambdify {r['lambdify(cse) pts/s']:.3g}/s  first "
              f"{r['first call pts/s']:.3g}/s  max err {r['max rel err']:.2g} ({r['points > 1e-10']} > 1e-10)",
              flush=True)
        report(Goal("lambda", "5", f"Λ(V) {name}: engine / lambdify(cse=True) throughput (1 thread)",
                    r["engine pts/s"] / r["lambdify(cse) pts/s"], 1.0))
        report(Goal("lambda", "5", f"Λ(V) {name}: engine points/s (1 thread)", r["engine pts/s"], 1e6))
        report(Goal("lambda", "5", f"Λ(V) {name}: points off 50-digit mpmath by > 1e-10 (of 1000)",
                    float(r["points > 1e-10"]), 0.0, "<="))
    RAW["lambda"] = rows
    TABLES["lambda"] = (f"Λ(V) over {n_points:.0e} log-spaced V in the velocity-weakening range, one thread, CPU "
                        "time (best of 2); first call includes no compilation (compile s is separate).\n\n"
                        + table(rows, list(rows[0]) if rows else []))


# --------------------------------------------------------------------------------------------
# derivation cost against the number of state variables (goal 6)
_DERIVE_SNIPPET = r"""
import sys, time
n, direct = int(sys.argv[1]), sys.argv[2] == "direct"
from landau.laws import FrictionLaw
from landau.systems.system import SpringBlock
from landau.derivation.multiscale import QUANTITIES, derive
if direct:
    sys.path.insert(0, {bench!r})
    from direct_routes import install
    install()
names = [f"phi{{i}}" for i in range(1, n + 1)]
mu = "a_v + a*log(v/V_s) + " + " + ".join(f"b{{i}}*log(V_s*phi{{i}}/L{{i}})" for i in range(1, n + 1))
params = {{}}
for i in range(1, n + 1):
    params[f"b{{i}}"] = 0.06 / n * (1 + 0.1 * i)
    params[f"L{{i}}"] = 1e-6 * 3.0 ** (i - 1)
rates = {{p: f"1 - v*{{p}}/L{{i}}" for i, p in enumerate(names, 1)}}
law = FrictionLaw.from_strings(f"dieterich-{{n}}", mu, rates, params)
t0 = time.process_time()
d = derive(SpringBlock(law), list(QUANTITIES))
r = d.evaluate([1e-5], {{}}, list(QUANTITIES))
print(time.process_time() - t0, repr(float(r["Lambda"][0])))
"""


def _derive_cpu(n: int, route: str, timeout: float) -> tuple[float, float]:
    code = _DERIVE_SNIPPET.format(bench=str(Path(__file__).resolve().parent))
    try:
        out = subprocess.run([sys.executable, "-c", code, str(n), route], capture_output=True, text=True,
                             check=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return float("inf"), float("nan")
    a, b = out.stdout.split()[-2:]
    return float(a), float(b)


def _exponent(ns, ts) -> float:
    ok = [(n, t) for n, t in zip(ns, ts, strict=True) if np.isfinite(t)]
    if len(ok) < 2:
        return float("nan")
    x, y = np.log([n for n, _ in ok]), np.log([t for _, t in ok])
    return float(np.polyfit(x, y, 1)[0])


def section_derive(quick: bool, baseline: bool) -> None:
    ns = list(range(1, 6 if quick else 7))
    rows = []
    for n in ns:
        t, lam = _derive_cpu(n, "current", 600)
        row = {"states": n, "CPU s": t, "Lambda(1e-5)": lam}
        if baseline:
            tb, lamb = _derive_cpu(n, "direct", 900)
            row.update({"direct routes CPU s": tb, "same Lambda": bool(lamb == lam) if np.isfinite(lamb) else "n/a"})
        rows.append(row)
        print(f"  {n} states: {t:.2f} s" + (f" (direct routes {row['direct routes CPU s']:.2f} s)" if baseline else ""),
              flush=True)
    RAW["derive"] = rows
    cols = list(rows[0])
    TABLES["derive"] = ("Derivation + compile of all seven quantities, Dieterich law with n states "
                        "(μ = a_v + a ln(v/V_*) + Σ bᵢ ln(V_*φᵢ/Lᵢ), dφᵢ/dt = 1 − vφᵢ/Lᵢ), CPU seconds in a fresh "
                        "interpreter (imports excluded).\n\n" + table(rows, cols))
    exp_now = _exponent(ns, [r["CPU s"] for r in rows])
    exp_pw = _exponent(ns[-3:], [r["CPU s"] for r in rows][-3:])
    TABLES["derive"] += (f"\n\nGrowth exponent (t ∝ n^p, fit over 1…{ns[-1]}): p = {exp_now:.2f}; "
                         f"over the last three: {exp_pw:.2f}")
    if baseline:
        eb = _exponent(ns, [r["direct routes CPU s"] for r in rows])
        TABLES["derive"] += f"; direct routes: p = {eb:.2f}"
    for r in rows:
        if r["states"] <= 5:
            report(Goal("derive", "6", f"derivation + compile, {r['states']} state(s) [CPU s]", r["CPU s"], 2.0, "<="))
    print(f"  growth exponent over 1..{ns[-1]} states: {exp_now:.2f}")
