"""The toolkit against its fair peers, every speed goal with its ratio, in one run.

    pip install -e '.[bench]'
    python benchmarks/run.py                  # every section (tens of minutes on a loaded machine)
    python benchmarks/run.py --only lambda,derive --quick

Each section measures the toolkit and its baseline side by side in the same process (or in
fresh interpreters started back to back, where the cost of a cold process is the point) and
prints one line per goal: the ratio, the goal and pass/fail.  Tables (Markdown), the raw
numbers (JSON) and work-precision plots (PNG) go to ``benchmarks/results/`` with a
description of the machine and its load average during the run.

Sections (``--only``):

* ``springblock`` — one period of the Fig. 3 stick-slip cycle of Putelat et al. (2010)
  (Dieterich law, V/V_* = 100, κ = 1e-3): the toolkit (``integrate(method="auto")``, which
  picks the order-5 Radau IIA solved in the eigenbasis of A⁻¹ or the order-9 Radau IIA by
  tolerance; each of its methods also on its own,
  and the order-5 Radau IIA called the way it was before kernels were passed by address)
  against ``solve_ivp`` Radau/BDF/LSODA with the generated right-hand side and Jacobian as plain
  Python and as numba-compiled functions, SUNDIALS CVODE (BDF, compiled f and J, scikit-sundae)
  and, where installed, LSODA with a compiled right-hand side (numbalsoda).
* ``forced`` — Skurativskyi et al. (2019) eq. (1) at ω = 16 (20 periods) and ω = 15 (2 periods):
  the toolkit with its impact log against CVODE and LSODA (compiled, without events) and
  ``solve_ivp`` DOP853 with the contact event.
* ``galvanetto`` — Galvanetto (2004) one block, slip→stick event: the hybrid engine against a
  ``solve_ivp`` loop with a terminal event (DOP853 and RK45), at equal event-time error; two
  blocks, one step of the event map (eight switching events): the engine against the same model
  driven by a ``solve_ivp`` loop with the guards as terminal events.
* ``lambda`` — Λ(V) of every built-in one-state law: throughput of ``Derivation.evaluate``
  on one thread against ``sympy.lambdify(cse=True)`` of the same expression, the first call,
  and the error of 1000 points against 50-digit mpmath.
* ``derive`` — derivation + compile CPU time of Dieterich-type laws with 1…6 state
  variables (fresh interpreter each), with the growth exponent; ``--baseline-derive`` adds the
  direct routes (numeric conversion of symbolic pivots, Berkowitz determinant) for comparison.
* ``verify`` — a cold ``landau verify ruina --V 1e-4`` with a warm kernel cache against one
  with an empty cache, and the CPU time of importing the command alone.
* ``figures`` — ``landau figures putelat2010`` with an empty cache (what a first run costs:
  no derivations, no generated code), with the generated code of that run but no derivations,
  and with everything that run cached.

``LANDAU_BENCH_BASELINE_PYTHON=/path/to/other/checkout/.venv/bin/python`` times that
interpreter side by side with this one in ``verify`` and ``figures`` (ratios in the notes).

Goals are those of the project's performance plan; CPU time (process time) is used wherever
possible because the wall clock of a shared machine is not the toolkit's cost.
"""

from __future__ import annotations

import argparse
import itertools
import os
import platform
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

RESULTS = Path(__file__).resolve().parent / "results"
SECTIONS = ("springblock", "forced", "galvanetto", "lambda", "derive", "verify", "figures")


# --------------------------------------------------------------------------------------------
# bookkeeping
@dataclass(frozen=True)
class Goal:
    """One speed goal: ``value`` compared with ``target`` (``>=`` or ``<=``)."""

    goal: str
    measure: str
    value: float
    target: float
    sense: str = ">="
    note: str = ""

    @property
    def passed(self) -> bool:
        if not np.isfinite(self.value):
            return False
        return self.value >= self.target if self.sense == ">=" else self.value <= self.target

    def line(self) -> str:
        return (f"{self.goal:9s} {self.measure:64s} {self.value:10.3g} {self.sense} {self.target:<8g} "
                f"{'PASS' if self.passed else 'FAIL'}{'  ' + self.note if self.note else ''}")


GOALS: list[Goal] = []
TABLES: dict[str, str] = {}
RAW: dict[str, object] = {}


def report(g: Goal) -> None:
    GOALS.append(g)
    print("  " + g.line(), flush=True)


def machine() -> dict:
    info = {"python": platform.python_version(), "platform": platform.platform(), "cpus": os.cpu_count()}
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                info["cpu"] = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    import numba
    import scipy
    import sympy

    info.update(numpy=np.__version__, scipy=scipy.__version__, sympy=sympy.__version__, numba=numba.__version__)
    for mod in ("sksundae", "numbalsoda"):
        try:
            m = __import__(mod)
            info[mod] = getattr(m, "__version__", "installed")
        except ImportError:
            info[mod] = "not installed"
    return info


def load() -> tuple[float, float, float]:
    return os.getloadavg()


def cpu_time(fn, min_time: float = 0.05, repeat: int = 3):
    """Best CPU seconds per call over ``repeat`` rounds; fast calls are looped within a round."""
    best, out = np.inf, None
    for _ in range(repeat):
        n, t0 = 0, time.process_time()
        while True:
            out = fn()
            n += 1
            el = time.process_time() - t0
            if el >= min_time or n >= 50:
                break
        best = min(best, el / n)
    return out, best


def pareto(points):
    """(cpu, error) pairs not beaten by a faster run that is at least as accurate, by cpu."""
    pts = sorted((c, e) for c, e in points if np.isfinite(e) and np.isfinite(c))
    front, best = [], np.inf
    for c, e in pts:
        if e < best:
            front.append((c, e))
            best = e
    return front


def cpu_at_error(front, err):
    """CPU time at error ``err`` interpolated log-log along a Pareto front; the cheapest run
    if it is already more accurate; None if ``err`` is below every error of the front."""
    if not front or err < front[-1][1]:
        return None
    if err >= front[0][1]:
        return front[0][0]
    for (c0, e0), (c1, e1) in itertools.pairwise(front):
        if e1 <= err <= e0:
            w = (np.log(err) - np.log(e0)) / (np.log(e1) - np.log(e0)) if e1 < e0 else 0.0
            return float(np.exp(np.log(c0) + w * (np.log(c1) - np.log(c0))))
    return None


def plot_work_precision(rows, title: str, path: Path, xlabel: str = "error") -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from landau.support.io import atomic_savefig

    fig, ax = plt.subplots(figsize=(7, 5))
    for method in dict.fromkeys(r["method"] for r in rows):
        rr = [r for r in rows if r["method"] == method and np.isfinite(r["error"])]
        if rr:
            ax.loglog([max(r["error"], 1e-16) for r in rr], [r["cpu"] for r in rr], "o-", ms=4, label=method)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("CPU time [s]")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    atomic_savefig(fig, path, dpi=110, bbox_inches="tight")
    plt.close(fig)


def table(rows, cols) -> str:
    out = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    for r in rows:
        out.append("| " + " | ".join(f"{r[c]:.3g}" if isinstance(r[c], float) else str(r[c]) for c in cols) + " |")
    return "\n".join(out)


def ratios_at_equal_error(rows, ours: str, theirs: list[str], targets):
    """{target: (their best CPU, our CPU)} at each target error both reach."""
    front_us = pareto([(r["cpu"], r["error"]) for r in rows if r["method"] == ours])
    out = {}
    for tgt in targets:
        mine = cpu_at_error(front_us, tgt)
        best = None
        for m in theirs:
            c = cpu_at_error(pareto([(r["cpu"], r["error"]) for r in rows if r["method"] == m]), tgt)
            if c is not None and (best is None or c < best[0]):
                best = (c, m)
        if mine is not None and best is not None:
            out[tgt] = (best[0], mine, best[1])
    return out


# --------------------------------------------------------------------------------------------
# spring-block (goal 2)
def section_springblock(quick: bool) -> None:
    from scipy.integrate import solve_ivp

    from landau.verify.springblock.simulate import W_INDEX, integrate
    from landau.verify.springblock.workprecision import error, fig3_cycle, fig3_model, scipy_run

    model = fig3_model()
    orbit = fig3_cycle(model)
    y0 = np.insert(orbit.z, W_INDEX, 0.0)
    T = orbit.period
    c, p, n = model.compiled, model.p, model.n
    Ts = T / model.time_unit
    ref = integrate(model, y0, (0.0, T), rtol=1e-13).y
    tols = [10.0 ** -e for e in range(4, 12 if quick else 13)]
    # the multistep peers need tighter tolerances for the same error (their error per rtol is
    # ~1e4 times the toolkit's on this cycle)
    peer_tols = [10.0 ** -e for e in range(6, 15)]
    rows = []

    def add(method, rtol, fn, repeat=3):
        try:
            y, cpu = cpu_time(fn, repeat=repeat)
            rows.append({"method": method, "rtol": rtol, "error": error(y, ref), "cpu": cpu})
        except Exception as exc:  # a peer that fails at this tolerance is reported, not fatal
            rows.append({"method": method, "rtol": rtol, "error": float("nan"), "cpu": float("nan"),
                         "note": type(exc).__name__})

    def f_c(t, y):
        out = np.empty(n)
        c.rhs(t, y, p, out)
        return out

    def j_c(t, y):
        out = np.empty((n, n))
        c.jac(t, y, p, out)
        return out

    def scipy_compiled(method, rtol):
        s = solve_ivp(f_c, (0.0, Ts), y0, method=method, rtol=rtol, atol=rtol, jac=j_c)
        return s.y[:, -1]

    from landau.verify.hybrid.radau import A_RADAU, VINV, pointers, radau_core

    def radau_dispatched(rtol):
        # the order-5 Radau IIA called as integrate() did before the kernels were passed by
        # address: the (f, J) pair as first-class function objects, looked up by numba per call
        fun, jac = pointers(c.rhs, c.jac)
        out = radau_core(fun, jac, 0.0, y0, Ts, p, rtol, np.full(n, rtol), min(1e-3 * Ts, 1e-4), np.inf, 5_000_000,
                         -1, 0.0, 0, 0, 0, A_RADAU, VINV, np.empty((1, n + 1)), np.empty(1))
        return out[2].copy()

    ours = "landau auto (toolkit's choice by tolerance)"
    for rtol in tols:
        add(ours, rtol, lambda: integrate(model, y0, (0.0, T), rtol=rtol, method="auto").y)
        add("landau Radau IIA order 5", rtol, lambda: integrate(model, y0, (0.0, T), rtol=rtol).y)
        add("landau Radau IIA order 5, eigenbasis of A⁻¹", rtol,
            lambda: integrate(model, y0, (0.0, T), rtol=rtol, method="radau5t").y)
        add("landau Radau IIA order 5, per-call dispatch (before)", rtol, lambda: radau_dispatched(rtol))
        add("landau Radau IIA order 9", rtol, lambda: integrate(model, y0, (0.0, T), rtol=rtol, method="radau9").y)
        add("landau RODAS4", rtol, lambda: integrate(model, y0, (0.0, T), rtol=rtol, method="rodas4").y)
        for m in ("Radau", "BDF", "LSODA"):
            add(f"solve_ivp {m} (compiled f+J)", rtol, lambda: scipy_compiled(m, rtol), repeat=1)
        if rtol >= 1e-9 or not quick:
            add("solve_ivp Radau (Python f+J)", rtol, lambda: scipy_run(model, y0, T, "Radau", rtol, True)[0], repeat=1)
    peers = []
    try:
        from sksundae.cvode import CVODE

        def rhs_s(t, y, yp):
            c.rhs(t, np.array(y), p, yp)

        def jac_s(t, y, yp, JJ):
            out = np.empty((n, n))
            c.jac(t, np.array(y), p, out)
            JJ[:, :] = out

        def cvode(rtol):
            s = CVODE(rhs_s, jacfn=jac_s, rtol=rtol, atol=rtol, max_num_steps=10 ** 7).solve([0.0, Ts], y0)
            if not s.success:
                raise RuntimeError(s.message)
            return s.y[-1]

        for rtol in peer_tols:
            add("CVODE BDF (compiled f+J)", rtol, lambda: cvode(rtol))
        peers.append("CVODE BDF (compiled f+J)")
    except ImportError:
        print("  (scikit-sundae not installed: pip install -e '.[bench]')")
    try:
        import numba as nb
        from numbalsoda import lsoda, lsoda_sig

        rhs_nb = c.rhs

        @nb.cfunc(lsoda_sig)
        def rhs_l(t, u, du, pp):
            rhs_nb(t, nb.carray(u, (n,)), nb.carray(pp, (p.size,)), nb.carray(du, (n,)))

        addr = rhs_l.address

        def lsoda_run(rtol):
            usol, ok = lsoda(addr, y0.copy(), np.array([0.0, Ts]), data=p.copy(), rtol=rtol, atol=rtol,
                             mxstep=10 ** 7)
            if not ok:
                raise RuntimeError("lsoda failed")
            return usol[-1]

        for rtol in peer_tols:
            add("numbalsoda LSODA (compiled f)", rtol, lambda: lsoda_run(rtol))
        peers.append("numbalsoda LSODA (compiled f)")
    except ImportError:
        print("  (numbalsoda not installed: it builds from source with a Fortran compiler)")
    compiled = peers + [f"solve_ivp {m} (compiled f+J)" for m in ("Radau", "BDF", "LSODA")]
    RAW["springblock"] = rows
    TABLES["springblock"] = (f"One period T = {T:.6g} s of the Fig. 3 cycle (Putelat et al. 2010), error at the end "
                             f"against the toolkit at rtol 1e-13 (max scaled state error).\n\n"
                             + table(rows, ["method", "rtol", "error", "cpu"]))
    plot_work_precision(rows, "Spring-block, one period of the Fig. 3 stick-slip cycle (Dieterich)",
                        RESULTS / "springblock.png", "error at the end of one period")
    targets = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
    eq = ratios_at_equal_error(rows, ours, compiled, targets)
    for tgt, (theirs, mine, who) in eq.items():
        report(Goal("2", f"spring-block: best compiled peer / toolkit CPU at error {tgt:.0e}", theirs / mine, 3.0,
                    note=f"best peer: {who}"))
    eq = ratios_at_equal_error(rows, ours, ["solve_ivp Radau (compiled f+J)"], [1e-8])
    for tgt, (theirs, mine, _) in eq.items():
        report(Goal("2", f"spring-block: scipy Radau (compiled f+J) / toolkit at error {tgt:.0e}", theirs / mine, 50.0))
    # the same ratios for each of the toolkit's methods alone (information, not goals)
    for label in ("landau Radau IIA order 5, per-call dispatch (before)", "landau Radau IIA order 5",
                  "landau Radau IIA order 9", "landau RODAS4"):
        eq = ratios_at_equal_error(rows, label, compiled, targets)
        print(f"  {label:54s} best compiled peer / it: "
              + ", ".join(f"{tgt:.0e}: {theirs / mine:.3g}" for tgt, (theirs, mine, _) in eq.items()), flush=True)


# --------------------------------------------------------------------------------------------
# forced oscillator (goal 3)
def section_forced(quick: bool) -> None:
    from landau.verify.benchmarks.skurativskyi_work_precision import errors, scipy_run, toolkit_run
    from landau.verify.skurativskyi.model import Params, accel
    from landau.verify.skurativskyi.simulate import rest_state, run

    run(Params(), 1)  # compile
    cases = [(16.0, 20), (15.0, 2)]
    rows = []
    for omega, nper in cases:
        prm = Params(omega=omega)
        pk = prm.packed()
        tend = nper * prm.period
        ref, _, _ = toolkit_run(prm, nper, 1e-12, repeat=1, min_cpu=0)
        yref = ref[0]

        def state_error(y):
            return float(np.max(np.abs((np.asarray(y) - yref) / np.array([1e-3, 1e-2]))))

        for rt in (1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10):
            res, cpu, _ = toolkit_run(prm, nper, rt, repeat=3)
            rows.append({"omega": omega, "method": "landau (with impact log)", "rtol": rt,
                         "error": errors(res, ref)[0], "cpu": cpu})
        for rt in ((1e-5, 1e-6) if quick else (1e-5, 1e-6, 1e-7)):
            res, cpu, _ = scipy_run(prm, nper, "DOP853", rt)
            rows.append({"omega": omega, "method": "solve_ivp DOP853 + event", "rtol": rt,
                         "error": errors(res, ref)[0] if res is not None else float("nan"), "cpu": cpu})
        try:
            from sksundae.cvode import CVODE

            def rhs_s(t, y, yp):
                yp[0] = y[1]
                yp[1] = accel(t, y[0], y[1], pk)

            for rt in (1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10):
                def cv(meth=None, rt=rt):
                    # max_step: started from rest, the forcing is invisible to CVODE's first error
                    # tests, and without a cap it steps over all 20 periods in four steps
                    s = CVODE(rhs_s, method=meth, rtol=rt, atol=[rt * 1e-4, rt * 1e-2],
                              max_step=prm.period / 20, max_num_steps=500_000).solve([0.0, tend], rest_state(prm))
                    if not s.success:
                        raise RuntimeError(s.message)
                    return s.y[-1]
                for meth in ("Adams", "BDF"):
                    try:
                        y, cpu = cpu_time(lambda: cv(meth), repeat=1)
                        rows.append({"omega": omega, "method": f"CVODE {meth} (no events)", "rtol": rt,
                                     "error": state_error(y), "cpu": cpu})
                    except Exception:
                        pass
        except ImportError:
            pass
        try:
            import numba as nb
            from numbalsoda import lsoda, lsoda_sig

            npk = pk.size

            # numbalsoda takes one scalar atol: integrate (x/1e-4 m, ẋ/1e-2 m/s), which is the
            # same as the per-component atol (rtol·1e-4 m, rtol·1e-2 m/s) of the other runs
            s0, s1 = 1e-4, 1e-2

            @nb.cfunc(lsoda_sig)
            def rhs_l(t, u, du, pp):
                uu = nb.carray(u, (2,))
                dd = nb.carray(du, (2,))
                dd[0] = uu[1] * s1 / s0
                dd[1] = accel(t, uu[0] * s0, uu[1] * s1, nb.carray(pp, (npk,))) / s1

            for rt in (1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10):
                def ls(rt=rt):
                    u0 = rest_state(prm) / np.array([s0, s1])
                    usol, ok = lsoda(rhs_l.address, u0, np.array([0.0, tend]), data=pk.copy(),
                                     rtol=rt, atol=rt, mxstep=10 ** 8)
                    if not ok:
                        raise RuntimeError("lsoda failed")
                    return usol[-1] * np.array([s0, s1])
                try:
                    y, cpu = cpu_time(ls)
                except Exception:
                    continue
                rows.append({"omega": omega, "method": "numbalsoda LSODA (no events)", "rtol": rt,
                             "error": state_error(y), "cpu": cpu})
        except ImportError:
            pass
        sub = [r for r in rows if r["omega"] == omega]
        plot_work_precision(sub, f"Skurativskyi et al. (2019) eq. (1), ω = {omega:g}, {nper} periods",
                            RESULTS / f"forced_omega{omega:g}.png", "scaled final-state error")
        peers = sorted({r["method"] for r in sub if "no events" in r["method"]})
        eq = ratios_at_equal_error(sub, "landau (with impact log)", peers, [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9])
        for tgt, (theirs, mine, who) in eq.items():
            report(Goal("3", f"forced ω={omega:g}: compiled peer (no events) / toolkit at error {tgt:.0e}",
                        theirs / mine, 1.0, note=f"best peer: {who}"))
        eq = ratios_at_equal_error(sub, "landau (with impact log)", ["solve_ivp DOP853 + event"], [1e-4, 1e-5, 1e-6])
        for tgt, (theirs, mine, _) in eq.items():
            report(Goal("3", f"forced ω={omega:g}: solve_ivp + event / toolkit at error {tgt:.0e}", theirs / mine, 100.0))
    RAW["forced"] = rows
    TABLES["forced"] = ("Skurativskyi et al. (2019) eq. (1) from rest; error = max |Δ(x, ẋ)|/(1 mm, 10 mm/s) at the "
                        "end against the toolkit at rtol 1e-12.\n\n" + table(rows, ["omega", "method", "rtol", "error", "cpu"]))


# --------------------------------------------------------------------------------------------
# Galvanetto blocks (goal 4)
#: the engine's fastest configuration for the Galvanetto models: the compiled DOPRI5 over the
#: model's generated kernels, order-4 dense output, quiet steps screened in one compiled call
COMPILED_ENGINE = "hybrid engine, compiled DOPRI5 (generated kernels)"


def section_galvanetto(quick: bool) -> None:
    from landau.verify.benchmarks.event_location_galvanetto import (UNSCREENED, baseline, compiled_engine, engine,
                                                                    two_block_compiled_engine)

    t_ref, _, _ = engine("DOP853", 1e-13)
    compiled_engine(1e-6), two_block_compiled_engine(1e-6)  # the generated kernels compiled (or loaded) once
    rows = []
    compiled = lambda method, rtol, *extra: compiled_engine(rtol, *extra)
    methods = (("hybrid engine DOP853", engine, "DOP853", ()),
               ("hybrid engine DOP853, dense scan every step", engine, "DOP853", (UNSCREENED,)),
               ("hybrid engine RK45", engine, "RK45", ()),
               (COMPILED_ENGINE, compiled, "DOPRI5", ()),
               ("solve_ivp DOP853 + terminal event", baseline, "DOP853", ()),
               ("solve_ivp RK45 + terminal event", baseline, "RK45", ()))
    for rtol in [10.0 ** -e for e in range(4, 15, 2 if quick else 1)]:
        for label, fn, method, extra in methods:
            if method == "RK45" and rtol < 1e-10:
                continue  # thousands of fifth-order steps: off the front the goal reads
            if rtol < 1e-12 and method != "DOPRI5":
                continue  # the fifth-order method needs rtol 1e-14 for an event-time error 1e-13
            (t_ev, _, nfev), cpu = cpu_time(lambda: fn(method, rtol, *extra), min_time=0.1, repeat=5)
            rows.append({"method": label, "rtol": rtol, "error": abs(t_ev - t_ref), "nfev": int(nfev), "cpu": cpu})
    RAW["galvanetto"] = rows
    TABLES["galvanetto"] = ("Galvanetto (2004) one block (γ = 3, δ = 0.2, V = 1): slip→stick event time against the "
                            "engine at rtol 1e-13 (atol = rtol/100 throughout; the engine's default guard scan, "
                            "4 samples per step screened on the cubic Hermite interpolant, and the same scan on "
                            "the dense output of every step; the compiled DOPRI5 over the model's generated "
                            "kernels with its order-4 dense output, quiet steps screened in one compiled call; "
                            "only it runs below rtol 1e-12).\n\n"
                            + table(rows, ["method", "rtol", "error", "nfev", "cpu"]))
    plot_work_precision(rows, "Galvanetto (2004) one block: slip→stick event time", RESULTS / "galvanetto.png",
                        "event-time error")
    theirs = ["solve_ivp DOP853 + terminal event", "solve_ivp RK45 + terminal event"]
    eq = ratios_at_equal_error(rows, COMPILED_ENGINE, theirs, [1e-5, 1e-7, 1e-9, 1e-11, 1e-13])
    for tgt, (their, mine, who) in eq.items():
        report(Goal("4", f"Galvanetto: best solve_ivp loop / engine CPU at event-time error {tgt:.0e}", their / mine,
                    1.0, note=f"{who}; engine with the compiled DOPRI5"))
    eq = ratios_at_equal_error(rows, "hybrid engine DOP853", theirs, [1e-5, 1e-7, 1e-9, 1e-11, 1e-13])
    for tgt, (their, mine, who) in eq.items():
        print(f"  (information) best solve_ivp loop / engine on scipy's DOP853 at event-time error {tgt:.0e}: "
              f"{their / mine:.2f} ({who})")

    # two blocks: one map step (eight switching events), the same model driven by solve_ivp
    from landau.verify.benchmarks.event_location_galvanetto import two_block_baseline, two_block_engine

    t_ref2, d_ref2, _ = two_block_engine("DOP853", 1e-13)
    rows2 = []
    for rtol in [10.0 ** -e for e in range(5, 14, 2 if quick else 1)]:
        for label, fn in (("hybrid engine DOP853", two_block_engine),
                          (COMPILED_ENGINE, lambda method, rtol: two_block_compiled_engine(rtol)),
                          ("solve_ivp DOP853 loop, terminal events", two_block_baseline)):
            if rtol < 1e-12 and fn is not two_block_baseline and label != COMPILED_ENGINE:
                continue
            (t_ev, d1, nfev), cpu = cpu_time(lambda: fn("DOP853", rtol), min_time=0.1, repeat=5)
            rows2.append({"method": label, "rtol": rtol, "error": abs(t_ev - t_ref2), "d_error": abs(d1 - d_ref2),
                          "nfev": int(nfev), "cpu": cpu})
    RAW["galvanetto_two_blocks"] = rows2
    TABLES["galvanetto"] += (
        "\n\nGalvanetto (2004) two blocks (α = 1.2, β = 1.722, γ = 3, V = 0.25): one step of the event map from the "
        "global stick phase d = -0.3 (eight switching events); error = time of the next global stick phase against "
        "the engine at rtol 1e-13, d_error = its d.\n\n"
        + table(rows2, ["method", "rtol", "error", "d_error", "nfev", "cpu"]))
    plot_work_precision(rows2, "Galvanetto (2004) two blocks: one event-map step", RESULTS / "galvanetto_two_blocks.png",
                        "error of the time of the next global stick phase")
    eq = ratios_at_equal_error(rows2, COMPILED_ENGINE, ["solve_ivp DOP853 loop, terminal events"],
                               [1e-6, 1e-8, 1e-10, 1e-12])
    for tgt, (their, mine, _) in eq.items():
        report(Goal("4", f"Galvanetto two blocks: solve_ivp loop / engine CPU at error {tgt:.0e}", their / mine, 1.0,
                    note="engine with the compiled DOPRI5"))
    eq = ratios_at_equal_error(rows2, "hybrid engine DOP853", ["solve_ivp DOP853 loop, terminal events"],
                               [1e-6, 1e-8, 1e-10, 1e-12])
    for tgt, (their, mine, _) in eq.items():
        print(f"  (information) solve_ivp loop / engine on scipy's DOP853 at error {tgt:.0e}: {their / mine:.2f}")


# --------------------------------------------------------------------------------------------
# Λ(V) (goal 5)
def section_lambda(quick: bool) -> None:
    import mpmath
    import sympy as sp

    import landau.derivation.multiscale as ms
    import landau.derivation.precision as precision
    from landau.laws import get_law
    from landau.systems.system import SpringBlock

    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
    from vw_ranges import LAWS, vw_range

    workers = precision.WORKERS
    precision.WORKERS = 1                    # single-threaded, like the lambdify baseline
    n_points = 200_000 if quick else 1_000_000
    rows = []
    try:
        for name in LAWS:
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
            # accuracy: 1000 log-spaced points against the 50-digit evaluation
            Vc = np.logspace(np.log10(lo), np.log10(hi), 1000)
            got = d.evaluate(Vc, {}, ["Lambda"])["Lambda"]
            errs = []
            for V0, g in zip(Vc, got):
                with mpmath.workdps(50):
                    want = d.evaluate_mp(float(V0), {}, ["Lambda"], dps=50)["Lambda"]
                errs.append(float(abs(g - want) / abs(want)) if want != 0 else abs(g))
            errs = np.array(errs)
            rows.append({"law": name, "engine pts/s": n_points / t_eng,
                         "lambdify(cse) pts/s": n_points / t_lam,
                         "first call pts/s": first, "compile s": compile_s, "max rel err": float(errs.max()),
                         "points > 1e-10": int((errs > 1e-10).sum())})
            r = rows[-1]
            print(f"  {name:20s} engine {r['engine pts/s']:.3g}/s  "
                  f"lambdify {r['lambdify(cse) pts/s']:.3g}/s  first "
                  f"{first:.3g}/s  max err {r['max rel err']:.2g} ({r['points > 1e-10']} > 1e-10)", flush=True)
            report(Goal("5", f"Λ(V) {name}: engine / lambdify(cse=True) throughput (1 thread)",
                        r["engine pts/s"] / r["lambdify(cse) pts/s"], 1.0))
            report(Goal("5", f"Λ(V) {name}: engine points/s (1 thread)", r["engine pts/s"], 1e6))
            report(Goal("5", f"Λ(V) {name}: points off 50-digit mpmath by > 1e-10 (of 1000)",
                        float(r["points > 1e-10"]), 0.0, "<="))
    finally:
        precision.WORKERS = workers
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
law = FrictionLaw.from_strings(f"dieterich-{{n}}", mu, {{p: f"1 - v*{{p}}/L{{i}}" for i, p in enumerate(names, 1)}}, params)
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
    ok = [(n, t) for n, t in zip(ns, ts) if np.isfinite(t)]
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
    TABLES["derive"] += f"\n\nGrowth exponent (t ∝ n^p, fit over 1…{ns[-1]}): p = {exp_now:.2f}; over the last three: {exp_pw:.2f}"
    if baseline:
        eb = _exponent(ns, [r["direct routes CPU s"] for r in rows])
        TABLES["derive"] += f"; direct routes: p = {eb:.2f}"
    for r in rows:
        if r["states"] <= 5:
            report(Goal("6", f"derivation + compile, {r['states']} state(s) [CPU s]", r["CPU s"], 2.0, "<="))
    print(f"  growth exponent over 1..{ns[-1]} states: {exp_now:.2f}")


# --------------------------------------------------------------------------------------------
# cold CLI runs (goals 7, 8)
def _timed_process(argv, env=None, cwd=None, timeout=1800) -> tuple[float, float, int]:
    """(wall s, CPU s of the child, return code)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(argv, env=env, cwd=cwd, capture_output=True, text=True, timeout=timeout)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, proc.returncode


#: another checkout's interpreter (its own editable install) timed side by side with this one
#: in the ``verify`` and ``figures`` sections, e.g. the main branch before a change
BASELINE_ENV = "LANDAU_BENCH_BASELINE_PYTHON"


def _interpreters() -> list[tuple[str, str]]:
    """(label, python) pairs to time: this interpreter, and the baseline one when set."""
    out = [("this", sys.executable)]
    base = os.environ.get(BASELINE_ENV)
    if base:
        out.append(("baseline", base))
    return out


def _import_cpu(python: str, module: str, env=None) -> float:
    """CPU seconds of a fresh interpreter that imports ``module`` and exits."""
    return _timed_process([python, "-c", f"import {module}"], env, cwd=_NEUTRAL)[1]


#: the working folder of the timed commands: never a checkout, whose ``landau/`` folder would
#: shadow the interpreter's own installation under ``python -m``
_NEUTRAL = tempfile.gettempdir()


def section_verify(quick: bool) -> None:
    args = ["-m", "landau", "verify", "ruina", "--V", "1e-4"]
    warm_env = dict(os.environ)
    rows = []
    for _, py in _interpreters():
        _timed_process([py, *args], warm_env, cwd=_NEUTRAL)     # fills the kernel cache (and numba's own caches)
    for _ in range(1 if quick else 2):
        for label, py in _interpreters():             # interleaved: the same machine load for both
            w, c, rc = _timed_process([py, *args], warm_env, cwd=_NEUTRAL)
            imp = _import_cpu(py, "landau.verify.cli", warm_env)
            rows.append({"python": label, "kernel cache": "warm", "wall s": w, "CPU s": c,
                         "import CPU s": imp, "exit": rc, "load": round(load()[0], 1)})
            with tempfile.TemporaryDirectory() as tmp:
                env = dict(os.environ, LANDAU_CACHE_DIR=tmp)
                w2, c2, rc2 = _timed_process([py, *args], env, cwd=_NEUTRAL)
            rows.append({"python": label, "kernel cache": "empty", "wall s": w2, "CPU s": c2,
                         "import CPU s": float("nan"), "exit": rc2, "load": round(load()[0], 1)})
    RAW["verify"] = rows
    TABLES["verify"] = ("`landau verify ruina --V 1e-4` in a fresh process: generated kernels from the disk cache "
                        "(warm) against compiled afresh (empty cache); `import CPU s` is a fresh interpreter "
                        "importing the command's module only.\n\n" + table(rows, list(rows[0])))

    def best(label, cache, key="CPU s"):
        return min(r[key] for r in rows if r["python"] == label and r["kernel cache"] == cache)

    warm, empty = best("this", "warm"), best("this", "empty")
    note = (f"wall {best('this', 'warm', 'wall s'):.2f} s; imports {best('this', 'warm', 'import CPU s'):.2f} "
            f"CPU s; empty cache {empty:.2f} CPU s ({empty / warm:.1f}x)")
    if len(_interpreters()) > 1:
        note += f"; baseline {best('baseline', 'warm'):.2f} CPU s ({best('baseline', 'warm') / warm:.2f}x)"
    report(Goal("7", "cold `landau verify ruina --V 1e-4`, warm kernel cache [CPU s]", warm, 2.0, "<=", note=note))


#: sub-folders of a landau cache that hold generated code (sources, numba's and, from earlier versions,
#: kernels' object files), not derivations: what "empty derivation cache, warm code cache" keeps
CODE_FOLDERS = ("jit", "kernels")


def section_figures(quick: bool) -> None:
    """Goal 8 on an empty cache — derivations and generated code alike (a first-time user); the
    same run with an empty derivation cache but the generated code of the first run (a user
    after an upgrade that changed the derivations, or who cleared them), and with everything the
    first run cached, are reported beside it."""
    rows = []
    argv = ["-m", "landau", "figures", "putelat2010", "--no-progress"]
    for _ in range(1 if quick else 2):
        for label, py in _interpreters():             # interleaved: the same machine load for both
            with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as code_only, \
                    tempfile.TemporaryDirectory() as out:
                for state, folder in (("empty", cache), ("code only", code_only), ("warm", cache)):
                    if state == "code only":
                        for sub in CODE_FOLDERS:
                            if (Path(cache) / sub).is_dir():
                                shutil.copytree(Path(cache) / sub, Path(code_only) / sub)
                    env = dict(os.environ, LANDAU_CACHE_DIR=folder)
                    w, c, rc = _timed_process([py, *argv, "--out", out], env, cwd=_NEUTRAL)
                    rows.append({"python": label, "cache": state, "wall s": w, "CPU s": c, "exit": rc,
                                 "load": round(load()[0], 1)})
    RAW["figures"] = rows
    TABLES["figures"] = ("`landau figures putelat2010` in a fresh process: `empty` — `LANDAU_CACHE_DIR` a new "
                         "folder (no derivation, no generated code); `code only` — a new folder holding only the "
                         f"generated code ({', '.join(CODE_FOLDERS)}) of the `empty` run, no derivations; `warm` — "
                         "everything the `empty` run cached.\n\n" + table(rows, list(rows[0])))

    def best(label, state, key="CPU s"):
        return min(r[key] for r in rows if r["python"] == label and r["cache"] == state)

    cold = best("this", "empty")
    note = (f"wall {best('this', 'empty', 'wall s'):.1f} s; code cache only {best('this', 'code only'):.1f} CPU s; "
            f"warm cache {best('this', 'warm'):.1f} CPU s")
    if len(_interpreters()) > 1:
        note += (f"; baseline {best('baseline', 'empty'):.1f} CPU s empty ({best('baseline', 'empty') / cold:.2f}x), "
                 f"{best('baseline', 'code only'):.1f} code only, {best('baseline', 'warm'):.1f} warm")
    report(Goal("8", "`landau figures putelat2010`, empty cache (derivations and code) [CPU s]", cold, 8.0, "<=",
                note=note))


# --------------------------------------------------------------------------------------------
def main(argv=None) -> int:
    global RESULTS
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default=",".join(SECTIONS), help=f"comma-separated sections ({', '.join(SECTIONS)})")
    ap.add_argument("--quick", action="store_true", help="fewer tolerances and points")
    ap.add_argument("--baseline-derive", action="store_true",
                    help="also time the derivation with the direct routes (slow: minutes at 5-6 states)")
    ap.add_argument("--out", default=str(Path(__file__).resolve().parent / "results"), help="folder for tables, JSON and PNGs")
    args = ap.parse_args(argv)
    RESULTS = Path(args.out)
    RESULTS.mkdir(parents=True, exist_ok=True)
    only = [s.strip() for s in args.only.split(",") if s.strip()]
    bad = [s for s in only if s not in SECTIONS]
    if bad:
        print(f"unknown section(s) {', '.join(bad)} (known: {', '.join(SECTIONS)})", file=sys.stderr)
        return 2
    info = machine()
    loads = [load()]
    t_start = time.time()
    print(f"machine: {info.get('cpu', '?')}, {info['cpus']} CPUs, load average {loads[0][0]:.1f}")
    for s in only:
        print(f"\n[{s}]", flush=True)
        try:
            if s == "derive":
                section_derive(args.quick, args.baseline_derive)
            else:
                globals()[f"section_{s}"](args.quick)
        except Exception as exc:     # one broken section must not hide the others' results
            print(f"  section {s} failed: {type(exc).__name__}: {exc}")
            TABLES[s] = f"failed: {type(exc).__name__}: {exc}"
        loads.append(load())
    info["load average (1 min) during the run"] = [round(x[0], 2) for x in loads]
    info["run seconds"] = round(time.time() - t_start, 1)
    print("\nsummary (goal, measure, value, target, result)")
    for g in GOALS:
        print("  " + g.line())
    from landau.support.io import atomic_write_json, atomic_write_text

    md = ["# Benchmarks", "", "Machine: " + ", ".join(f"{k} {v}" for k, v in info.items()), "",
          "## Goals", "", "| goal | measure | value | target | result | note |", "|---|---|---|---|---|---|"]
    md += [f"| {g.goal} | {g.measure} | {g.value:.3g} | {g.sense} {g.target:g} | {'PASS' if g.passed else 'FAIL'} | "
           f"{g.note} |" for g in GOALS]
    for s in only:
        md += ["", f"## {s}", "", TABLES.get(s, "")]
    tag = ("quick" if args.quick else "full") + ("" if set(only) == set(SECTIONS) else "-" + "-".join(only))
    atomic_write_text(RESULTS / f"results-{tag}.md", "\n".join(md) + "\n")
    atomic_write_json(RESULTS / f"results-{tag}.json", {"machine": info, "goals": [asdict(g) | {"passed": g.passed}
                                                                                   for g in GOALS], "raw": RAW})
    print(f"\nwrote {RESULTS / f'results-{tag}.md'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
