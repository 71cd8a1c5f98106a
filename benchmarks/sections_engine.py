"""Engine sections: Λ(V) throughput and accuracy, derivation cost against the number of states.

* ``lambda`` — Λ(V) of every built-in law: throughput of ``Derivation.evaluate`` on one thread
  against the previous route and ``sympy.lambdify(cse=True)`` compiled by ``numba.vectorize``,
  the first call, the points the float64 bound sends to double-double, and the error of 1000
  points (plus the floats around each zero of Λ) against 40-digit mpmath.
* ``derive`` — derivation + compile CPU time of Dieterich-type laws with 1…8 state variables
  (fresh interpreter each, landau cache off), the ratio per added state and the growth exponent;
  with ``LANDAU_BENCH_BASELINE_PYTHON`` the same for that interpreter's checkout in the same run
  ("before"); ``--baseline-derive`` adds the direct routes (numeric conversion of symbolic
  pivots, Berkowitz determinant) up to 6 states for comparison.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
from benchlib import NEUTRAL, RAW, TABLES, Goal, cpu_time, interpreters, report, table

# --------------------------------------------------------------------------------------------
# Λ(V) (goal 5)


def _numba_lambdify(d):
    """The peer: ``sympy.lambdify(args, Λ(V), "math", cse=True)`` compiled by ``numba.vectorize``
    (one fused compiled loop over the points); None for a law without a closed-form Λ(V)."""
    import numba
    import sympy as sp

    if d.hopf.closed_form is None:
        return None
    fn = sp.lambdify(list(d.block.args), d.coefficient("Lambda").expr, modules="math", cse=True)
    sig = numba.float64(*([numba.float64] * len(d.block.args)))
    return numba.vectorize([sig])(fn)


def _zeros_of(d, Vs, lam) -> list[float]:
    """Float velocities at each sign change of Λ on the grid (bisected to adjacent floats), with
    their neighbours 1, 10, 10³, 10⁶ ulps away: where relative error is hardest."""
    out = []
    s = np.sign(lam)
    for i in np.flatnonzero((s[:-1] * s[1:] < 0) & np.isfinite(lam[:-1]) & np.isfinite(lam[1:]))[:4]:
        a, b = Vs[i], Vs[i + 1]
        sa = s[i]
        for _ in range(200):
            m = 0.5 * (a + b)
            if m in (a, b):
                break
            sm = np.sign(d.evaluate_mp(float(m), {}, ["Lambda"], dps=40)["Lambda"])
            a, b = (m, b) if sm == sa else (a, m)
        for k in (0, 1, 10, 1_000, 1_000_000):
            out += [a - k * np.spacing(a), b + k * np.spacing(b)]
    return out


def _accuracy(d, Vc, peer=None) -> tuple[float, int, int, float]:
    """(largest relative error of Λ against 40-digit mpmath, points off by > 1e-10, points, the
    peer's largest relative error on the same points)."""
    got = d.evaluate(Vc, {}, ["Lambda"])["Lambda"]
    theirs = np.full(Vc.shape, np.nan)
    if peer is not None:
        with np.errstate(all="ignore"):
            theirs = np.asarray(peer(*d.block.argvals(Vc, d.block.resolve())), dtype=float)
    errs, errs_peer = [], []
    for V0, g, t in zip(Vc, got, theirs, strict=True):
        want = d.evaluate_mp(float(V0), {}, ["Lambda"], dps=40)["Lambda"]
        if not np.isfinite(g) and want != want:
            continue
        errs.append(float(abs(g - want) / abs(want)) if want != 0 else abs(g))
        errs_peer.append(float(abs(t - want) / abs(want)) if want != 0 else abs(t))
    e = np.array(errs)
    return float(e.max()), int((e > 1e-10).sum()), len(e), float(np.max(errs_peer))


def _law_range(name: str) -> tuple[float, float]:
    """The velocity range the benchmark samples for the built-in law ``name``: its velocity-weakening
    range (ends pulled in by 1e-3 where Λ's domain ends there), or the open window."""
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
    from vw_ranges import LAWS, OPEN_WINDOW, vw_range

    if name not in LAWS:
        return OPEN_WINDOW
    lo, hi, ends = vw_range(name)
    return (lo * (1 + 1e-3) if lo in ends else lo), (hi * (1 - 1e-3) if hi in ends else hi)


def lambda_row(name: str, n_points: int, accuracy: bool = True) -> dict:
    """Λ(V) of the built-in law ``name`` on ``n_points`` log-spaced points, one thread: the
    engine's throughput (best repeated call and first call), the previous route's and that of
    ``sympy.lambdify(cse=True)`` compiled by ``numba.vectorize`` in the same run; with
    ``accuracy``, the error of 1000 points (and the floats around each zero of Λ) against
    40-digit mpmath.  Used by :func:`section_lambda` and by the drift test
    (``tests/codegen/test_benchmark_drift.py``)."""
    import landau.derivation.multiscale as ms
    import landau.derivation.precision as pr
    from landau.laws import get_law
    from landau.systems.system import SpringBlock

    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
    from vw_ranges import LAWS

    workers = pr.WORKERS
    pr.WORKERS = 1                      # single-threaded, like the peers
    try:
        lo, hi = _law_range(name)
        d = ms.derive(SpringBlock(get_law(name)), ["Lambda"])
        n = n_points
        Vs = np.logspace(np.log10(lo), np.log10(hi), n)
        t0 = time.process_time()
        d.evaluate(Vs[:10], {}, ["Lambda"])
        compile_s = time.process_time() - t0
        for k in pr.BOUNDED_STATS:
            pr.BOUNDED_STATS[k] = 0
        t0 = time.process_time()
        lam = d.evaluate(Vs, {}, ["Lambda"])["Lambda"]
        first = n / (time.process_time() - t0)
        stats = dict(pr.BOUNDED_STATS)
        _, t_eng = cpu_time(lambda: d.evaluate(Vs, {}, ["Lambda"]), repeat=2, min_time=0.0)
        row = {"law": name, "points": n, "engine pts/s": n / t_eng, "first call pts/s": first,
               "compile s": compile_s,
               "double-double points": stats["dd"] if stats["f64"] else "— (exact rational route)",
               "left to mpmath": stats["left"] if stats["f64"] else 0}
        if d.hopf.closed_form is not None and d.block.law.name in LAWS:
            _, t_gen = cpu_time(lambda: d.evaluate(Vs, {}, ["Lambda"], method="general"), repeat=1, min_time=0.0)
            row["float32-screen + long double route pts/s"] = n / t_gen
        peer = _numba_lambdify(d)
        if peer is not None:
            vals = d.block.argvals(Vs, d.block.resolve())
            peer(*[np.ravel(v)[:10] if np.ndim(v) else v for v in vals])       # compiled before timing
            with np.errstate(all="ignore"):
                _, t_lam = cpu_time(lambda: peer(*vals), repeat=2, min_time=0.0)
            row["numba-lambdify pts/s"] = n / t_lam
        if accuracy:
            # 1000 log-spaced points plus the floats at and around each zero of Λ
            Vc = np.concatenate([np.logspace(np.log10(lo), np.log10(hi), 1000), _zeros_of(d, Vs, lam)])
            (row["max rel err (40 digits)"], row["points > 1e-10"], row["points checked"],
             peer_err) = _accuracy(d, Vc, peer)
            if peer is not None:
                row["numba-lambdify max rel err"] = peer_err
        return row
    finally:
        pr.WORKERS = workers


def section_lambda(quick: bool) -> None:
    from landau.laws import BUILTIN

    n_points = 200_000 if quick else 1_000_000
    rows = []
    for name in BUILTIN:
        row = lambda_row(name, n_points)
        rows.append(row)
        print("  " + ", ".join(f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}" for k, v in row.items()),
              flush=True)
        if "numba-lambdify pts/s" in row:
            report(Goal("lambda", "5", f"Λ(V) {name}: engine / numba-lambdify throughput (1 thread)",
                        row["engine pts/s"] / row["numba-lambdify pts/s"], 1.0))
        report(Goal("lambda", "5", f"Λ(V) {name}: engine points/s (1 thread)", row["engine pts/s"], 2e6))
        report(Goal("lambda", "5", f"Λ(V) {name}: points off 40-digit mpmath by > 1e-10 "
                    f"(of {row['points checked']})", float(row["points > 1e-10"]), 0.0, "<="))
    RAW["lambda"] = rows
    TABLES["lambda"] = (
        f"Λ(V) over {n_points:.0e} log-spaced V in the velocity-weakening range, one thread, CPU time "
        "(best of 2; the first call and the compilation separately).  Route: the exactly cancelled form "
        "for the laws rational in V and a closed-form Hopf line; else float64 with a first-order error "
        "bound, the points it does not certify to 5e-11 again in double-double (`landau.codegen.bounded`), "
        "the rest with mpmath; for the two-state law the Hopf line is the stiffest root of the Hopf "
        "polynomial at every point, with its bound (`landau.codegen.bounded_hopf`), and the coefficients' "
        "bound includes that of (ω_c, k_c).  Peers in the same run: the previous route (float32 screen, "
        "numpy long double, mpmath) and `sympy.lambdify(cse=True)` compiled by `numba.vectorize` (no "
        "accuracy guarantee).  Accuracy: 1000 log-spaced points plus the floats at each zero of Λ and "
        "1, 10, 10³, 10⁶ ulps either side (a true zero, Λ = 0 exactly at a float V, would count its "
        "absolute value).\n\n"
        + table(rows, list(dict.fromkeys(k for r in rows for k in r)) if rows else []))


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
import os
def children():     # the finished children (the steady-state solve runs in a forked child)
    t = os.times()
    return t.children_user + t.children_system
t0, c0 = time.process_time(), children()
d = derive(SpringBlock(law), list(QUANTITIES))
r = d.evaluate([1e-5], {{}}, list(QUANTITIES))
child = children() - c0
print(time.process_time() - t0 + child, child, repr(float(r["Lambda"][0])))
"""


def _derive_cpu(n: int, route: str, timeout: float, python: str = sys.executable) -> tuple[float, float, float]:
    """CPU seconds of the derivation and first evaluation in a fresh interpreter ``python`` — its own and
    that of the children it waited for (``landau.support.budget.run_bounded`` solves a law's steady
    state in a forked child: ~0.2 CPU-s that ``time.process_time`` alone does not see) — with the
    landau cache off (a cold derivation: nothing read from an earlier run), and Λ(1e-5) and the
    children's share: (CPU s, Λ(1e-5), children's CPU s)."""
    code = _DERIVE_SNIPPET.format(bench=str(Path(__file__).resolve().parent))
    env = dict(os.environ, LANDAU_CACHE="off")
    try:
        out = subprocess.run([python, "-c", code, str(n), route], capture_output=True, text=True,
                             check=True, timeout=timeout, env=env, cwd=NEUTRAL)
    except subprocess.TimeoutExpired:
        return float("inf"), float("nan"), float("nan")
    a, c, b = out.stdout.split()[-3:]
    return float(a), float(b), float(c)


def _exponent(ns, ts) -> float:
    ok = [(n, t) for n, t in zip(ns, ts, strict=True) if np.isfinite(t)]
    if len(ok) < 2:
        return float("nan")
    x, y = np.log([n for n, _ in ok]), np.log([t for _, t in ok])
    return float(np.polyfit(x, y, 1)[0])


#: the most states timed, and the most the direct routes are timed for (minutes beyond)
DERIVE_STATES, DIRECT_STATES = 8, 6
#: goal: the cost of one more state variable, t(n + 1)/t(n), from 1 → 2 to 7 → 8 states
DERIVE_RATIO = 1.5


#: repetitions of each derivation (best of), in rounds over every n so that a change of machine load
#: between rounds reaches every n alike: at 0.2–1.5 CPU-s a derivation's spread on a shared 2-core
#: machine is ±30 % (measured: 0.33–0.51 s for 3 states), which a best of 3 in a row left in the ratios
DERIVE_REPS = 5


def section_derive(quick: bool, baseline: bool) -> None:
    """Derivation + first evaluation of the n-state Dieterich family, n = 1…8, CPU time (best of
    ``DERIVE_REPS`` in interleaved rounds over n, each peer interpreter of
    ``LANDAU_BENCH_BASELINE_PYTHON`` in the same rounds: the same machine load), and the ratios
    t(n + 1)/t(n)."""
    ns = list(range(1, DERIVE_STATES + 1))
    peers = interpreters()
    reps = 1 if quick else DERIVE_REPS
    runs: dict[tuple[int, str], list[tuple[float, float]]] = {}
    for rnd in range(reps):
        for n in ns:
            for label, py in peers:
                if label != "this" and rnd > 0:
                    continue
                runs.setdefault((n, label), []).append(_derive_cpu(n, "current", 900, py))
        print(f"  round {rnd + 1}/{reps}: " + ", ".join(f"{n}: {runs[(n, 'this')][-1][0]:.2f} s" for n in ns),
              flush=True)
    rows = []
    for n in ns:
        row: dict = {"states": n}
        for label, _ in peers:
            t, lam, child = min(runs[(n, label)])
            row["CPU s" if label == "this" else "before CPU s"] = t
            row["Lambda(1e-5)" if label == "this" else "before Lambda(1e-5)"] = lam
            if label == "this":
                row["of which children"] = child
        row["spread"] = max(r[0] for r in runs[(n, "this")]) / row["CPU s"]
        if baseline and n <= DIRECT_STATES:
            tb, lamb, _ = _derive_cpu(n, "direct", 900)
            row.update({"direct routes CPU s": tb, "same Lambda": bool(lamb == row["Lambda(1e-5)"])
                        if np.isfinite(lamb) else "n/a"})
        rows.append(row)
    for prev, row in zip(rows[:-1], rows[1:], strict=True):
        row["ratio"] = row["CPU s"] / prev["CPU s"]
        row["ratio without children"] = ((row["CPU s"] - row["of which children"])
                                         / (prev["CPU s"] - prev["of which children"]))
        if "before CPU s" in row:
            row["before ratio"] = row["before CPU s"] / prev["before CPU s"]
    rows[0]["ratio"] = rows[0]["ratio without children"] = float("nan")
    if "before CPU s" in rows[0]:
        rows[0]["before ratio"] = float("nan")
    RAW["derive"] = rows
    cols = [c for c in ("states", "CPU s", "ratio", "of which children", "ratio without children", "spread",
                        "before CPU s", "before ratio", "Lambda(1e-5)",
                        "before Lambda(1e-5)", "direct routes CPU s", "same Lambda") if c in rows[0]]
    TABLES["derive"] = ("Derivation + first evaluation of all seven quantities, Dieterich law with n states "
                        "(μ = a_v + a ln(v/V_*) + Σ bᵢ ln(V_*φᵢ/Lᵢ), dφᵢ/dt = 1 − vφᵢ/Lᵢ), CPU seconds in a fresh "
                        "interpreter, with those of the forked child that solves the steady state, with "
                        f"the landau cache off (imports excluded; best of {reps}, in "
                        "rounds over every n); ratio = t(n)/t(n − 1) (the goal's), and the same without the "
                        "children's CPU; spread = slowest/fastest run"
                        + ("; before = the baseline interpreter's checkout, timed in the same run, "
                           "interleaved" if len(peers) > 1 else "") + ".\n\n" + table(rows, cols))
    exp_now = _exponent(ns, [r["CPU s"] for r in rows])
    exp_pw = _exponent(ns[-3:], [r["CPU s"] for r in rows][-3:])
    TABLES["derive"] += (f"\n\nGrowth exponent (t ∝ n^p, fit over 1…{ns[-1]}): p = {exp_now:.2f}; "
                         f"over the last three: {exp_pw:.2f}")
    if len(peers) > 1:
        eb = _exponent(ns, [r["before CPU s"] for r in rows])
        TABLES["derive"] += f"; before: p = {eb:.2f}"
    if baseline:
        nd = [r["states"] for r in rows if "direct routes CPU s" in r]
        eb = _exponent(nd, [r["direct routes CPU s"] for r in rows if "direct routes CPU s" in r])
        TABLES["derive"] += f"; direct routes (1…{nd[-1]}): p = {eb:.2f}"
    for r in rows:
        if r["states"] <= 5:
            report(Goal("derive", "6", f"derivation + compile, {r['states']} state(s) [CPU s]", r["CPU s"], 2.0, "<="))
    for r in rows[1:]:
        report(Goal("derive", "6", f"derivation cost ratio t({r['states']})/t({r['states'] - 1} states)",
                    r["ratio"], DERIVE_RATIO, "<="))
    print(f"  growth exponent over 1..{ns[-1]} states: {exp_now:.2f}")
