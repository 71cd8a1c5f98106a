"""Bookkeeping shared by the benchmark sections: goals, timing, Pareto fronts, child processes.

Every section appends its goals to :data:`GOALS`, its Markdown table to :data:`TABLES` and its
raw rows to :data:`RAW`; ``benchmarks/run.py`` writes them to ``benchmarks/results/`` and
``benchmarks/report.py`` turns the results into ``docs/performance.md``.
"""

from __future__ import annotations

import os
import platform
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

# the Pareto front and the CPU time at an error: one definition, beside the forced oscillator's study
from landau.verify.benchmarks.skurativskyi_work_precision import cpu_at_error, pareto  # noqa: F401 (re-exported)

#: where tables, JSON and PNGs go (``run.py --out`` changes it)
RESULTS = Path(__file__).resolve().parent / "results"


def set_results(path: Path) -> None:
    global RESULTS
    RESULTS = Path(path)


@dataclass(frozen=True)
class Goal:
    """One speed goal of ``section``: ``value`` compared with ``target`` (``>=`` or ``<=``)."""

    section: str
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
    info["commit"] = commit()
    for mod in ("sksundae", "numbalsoda"):
        try:
            m = __import__(mod)
            info[mod] = getattr(m, "__version__", "installed")
        except ImportError:
            info[mod] = "not installed"
    return info


def commit() -> str:
    """The checkout's commit (short hash), with ``+dirty`` when tracked files differ from it; "unknown"
    outside a git checkout. The results files themselves (``benchmarks/results/``) do not count: a
    section run after another has rewritten them measures the same code."""
    root = Path(__file__).resolve().parent.parent
    try:
        head = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], cwd=root, capture_output=True,
                              text=True, timeout=30, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "--", ".",
                                ":(exclude)benchmarks/results"], cwd=root,
                               capture_output=True, text=True, timeout=30, check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return head + ("+dirty" if dirty else "")


def load() -> tuple[float, float, float]:
    return os.getloadavg()


def _round(fn, min_time: float):
    """One timed round: ``fn()`` looped until ``min_time`` CPU seconds (at most 50 calls);
    (the last result, CPU seconds per call)."""
    n, t0 = 0, time.process_time()
    while True:
        out = fn()
        n += 1
        el = time.process_time() - t0
        if el >= min_time or n >= 50:
            return out, el / n


def cpu_time(fn, min_time: float = 0.05, repeat: int = 3):
    """Best CPU seconds per call over ``repeat`` rounds; fast calls are looped within a round."""
    best, out = np.inf, None
    for _ in range(repeat):
        out, per_call = _round(fn, min_time)
        best = min(best, per_call)
    return out, best


def interleaved_cpu(calls: dict, min_time: float = 0.01, rounds: int = 15) -> dict:
    """Best CPU seconds per call of every ``calls[key]()`` over ``rounds`` interleaved rounds.

    Each round times every call once (looped within the round up to ``min_time``, as
    :func:`cpu_time` does), starting one place further along the list each round.  Calls whose
    times are compared with each other are thus timed in the same stretches of a shared
    machine's load.  A best of rounds taken one method after the other can catch one of them in
    a quiet stretch and its peer in a busy one: on a 2-core machine, the spring-block ratio at
    error 1e-4 read 1.8 to 3.9 between runs of the same commit."""
    keys = list(calls)
    best = {k: np.inf for k in keys}
    for r in range(rounds):
        for i in range(len(keys)):
            k = keys[(i + r) % len(keys)]
            best[k] = min(best[k], _round(calls[k], min_time)[1])
    return best


def ratios_at_equal_error(rows, ours: str, theirs: list[str], targets):
    """{target: (their best CPU, our CPU, their name)} at each target error that both sides reach
    (a target below the smallest error of either side is left out, never extrapolated)."""
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


def ladder(run_one, rtols, floor: float, budget: float = 30.0):
    """Run ``run_one(rtol)`` -> (error, cpu) down a tolerance ladder until the error reaches
    ``floor`` (the smallest error the other side reaches) or one run costs more than ``budget``
    CPU seconds; a failing tolerance is recorded and the ladder goes on.  Returns the rows
    reached, as (rtol, error, cpu, note)."""
    out = []
    for rt in rtols:
        try:
            err, cpu = run_one(rt)
        except Exception as exc:  # a peer may fail at one tolerance and succeed at a tighter one
            out.append((rt, float("nan"), float("nan"), f"{type(exc).__name__}: {str(exc)[:60]}"))
            continue
        out.append((rt, err, cpu, ""))
        if (np.isfinite(err) and err <= floor) or cpu > budget:
            break
    return out


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
        out.append("| " + " | ".join(f"{r.get(c, ''):.3g}" if isinstance(r.get(c), float) else str(r.get(c, ''))
                                     for c in cols) + " |")
    return "\n".join(out)


def spread(values) -> dict:
    """min / median / max of finite ``values`` (NaN when there are none)."""
    v = [x for x in values if np.isfinite(x)]
    if not v:
        return {"min": float("nan"), "median": float("nan"), "max": float("nan"), "n": 0}
    return {"min": min(v), "median": statistics.median(v), "max": max(v), "n": len(v)}


# --------------------------------------------------------------------------------------------
# child processes
def timed_process(argv, env=None, cwd=None, timeout=1800) -> tuple[float, float, int, str]:
    """(wall s, CPU s user+sys of the child, return code, last line of its stderr)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    try:
        proc = subprocess.run(argv, env=env, cwd=cwd, capture_output=True, text=True, timeout=timeout)
        rc, err = proc.returncode, proc.stderr
    except subprocess.TimeoutExpired:
        rc, err = -9, "timeout"
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    tail = err.strip().splitlines()[-1] if err and err.strip() else ""
    return wall, cpu, rc, tail


#: another checkout's interpreter (its own editable install) timed side by side with this one
#: in the ``coldstart`` and ``figures`` sections, e.g. the main branch before a change
BASELINE_ENV = "LANDAU_BENCH_BASELINE_PYTHON"

#: the working folder of the timed commands: never a checkout, whose ``landau/`` folder would
#: shadow the interpreter's own installation under ``python -m``
NEUTRAL = tempfile.gettempdir()


def interpreters() -> list[tuple[str, str]]:
    """(label, python) pairs to time: this interpreter, and the baseline one when set."""
    out = [("this", sys.executable)]
    base = os.environ.get(BASELINE_ENV)
    if base:
        out.append(("baseline", base))
    return out


def fresh_env(cache: Path) -> dict:
    """The environment of a truly cold process: a new landau cache *and* a new numba cache
    (numba then writes and reads every cache file of the package there, not in ``__pycache__``)."""
    (cache / "landau").mkdir(parents=True, exist_ok=True)
    (cache / "numba").mkdir(parents=True, exist_ok=True)
    return dict(os.environ, LANDAU_CACHE_DIR=str(cache / "landau"), NUMBA_CACHE_DIR=str(cache / "numba"))
