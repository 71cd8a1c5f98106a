"""Command-line sections: what a user waits for, in fresh processes, CPU time of the child.

* ``coldstart`` — the first ``landau verify ruina --V 1e-4`` and the first ``landau simulate
  forced-oscillator`` with a friction law of the user's, truly cold: a new ``LANDAU_CACHE_DIR``
  *and* a new ``NUMBA_CACHE_DIR`` (numba then writes and reads every cache file of the package
  there, so nothing compiled by an earlier run is found), in a fresh process; then the same
  command again with the caches that first run left (warm).
  Then the commands a user repeats (``hopf``, ``derive``, ``linear`` with ``--json``; not ``verify``,
  which simulates every time): a first run in
  fresh caches and the same command again, which prints the stored answer
  (:mod:`landau.support.answers`): its CPU time, whether its bytes equal the first run's, and whether
  it imported sympy (a probe run of the same command line that lists ``sys.modules``).
  "Truly cold" here also means a new ``HOME``, ``XDG_CACHE_HOME`` and ``XDG_CONFIG_HOME`` (matplotlib's
  font cache, the cache key) and no compiled bytecode of the timed package (its ``*.pyc`` files under
  ``__pycache__`` are removed before each cold run).
* ``help`` — ``landau --help`` and ``landau --version`` (the installed script beside the
  interpreter), best of 5: what a user pays to be told what the commands are; neither imports
  the engine (no sympy, numba or scipy; a unit test checks that in ``sys.modules``).
* ``figures`` — ``landau figures`` for galvanetto2004, skurativskyi2019 and putelat2010 warm
  (the caches of a first run of the same command), and cold (new caches, as above) for
  skurativskyi2019 and putelat2010 each repeat; the first, cold run of galvanetto2004 is kept
  as one sample.

CPU time is user + sys of the child (``resource.getrusage(RUSAGE_CHILDREN)``).  With
``LANDAU_BENCH_BASELINE_PYTHON`` set to another checkout's interpreter, each repeat runs both
interpreters back to back, and the ratio baseline / this of each repeat is reported as
min / median / max over the repeats.
"""

from __future__ import annotations

import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np
from benchlib import NEUTRAL, RAW, TABLES, Goal, fresh_env, interpreters, load, report, spread, table, timed_process

#: the first run of a user's own friction law in the forced oscillator (README's example law)
FORCED_NEW_LAW = ["simulate", "forced-oscillator", "--friction", "c*v + T*tanh(v/e)", "--param", "c=6.6511",
                  "--param", "T=0.63133", "--param", "e=1e-5", "--t-end", "2"]

#: (name, argv after ``python -m landau``, goal number, target CPU s for the cold run)
COLD_COMMANDS = (
    ("verify ruina --V 1e-4", ["verify", "ruina", "--V", "1e-4"], "7", 7.0),
    ("simulate forced-oscillator, new law, --t-end 2", FORCED_NEW_LAW, "9", 15.0),
)

#: (paper, cold in every repeat, goal number or None, target CPU s of its first (cold) run)
FIGURES = (
    ("galvanetto2004", False, "figures-galvanetto", 25.0),
    ("skurativskyi2019", True, None, None),
    ("putelat2010", True, "8", 8.0),
)

#: (name, argv after ``python -m landau``, goal or None, target CPU s of the repeated run): commands
#: whose repeat is answered from the store of finished answers
REPEATED = (
    ("hopf spring-block dieterich --V 1e-4 --json", ["hopf", "spring-block", "dieterich", "--V", "1e-4", "--json"],
     "answers-1", 1.0),
    ("derive dieterich --V 1e-4 --json", ["derive", "dieterich", "--V", "1e-4", "--json"], None, None),
    ("linear dieterich --V 1e-4 --json", ["linear", "dieterich", "--V", "1e-4", "--json"], None, None),
)

#: a command line run in-process, then the heavy libraries it imported on stderr
PROBE = ("import sys\nfrom landau.cli.app import main\nrc = main(sys.argv[1:])\n"
         "sys.stderr.write('\\nLOADED ' + ' '.join(m for m in ('sympy', 'numba', 'scipy') if m in sys.modules))\n"
         "sys.exit(rc)\n")


def _package_folders(py: str) -> list[str]:
    """The folders of the package ``py`` runs (``landau`` and the folders mapped into it)."""
    code = ("import importlib.util as u\nfor n in ('landau', 'landau.laws', 'landau.verify', 'landau.paper_figures'):\n"
            "    s = u.find_spec(n)\n    print(*(s.submodule_search_locations or []) if s else (), sep='\\n')\n")
    out = subprocess.run([py, "-c", code], capture_output=True, text=True, cwd=NEUTRAL, timeout=120).stdout
    return [line for line in out.splitlines() if line.strip()]


def cold_env(cache: Path, py: str) -> dict:
    """:func:`benchlib.fresh_env` and a new ``HOME``, ``XDG_CACHE_HOME``, ``XDG_CONFIG_HOME`` in ``cache``, with
    the compiled bytecode (``*.pyc``) of ``py``'s landau removed: a truly cold process."""
    env = fresh_env(cache)
    for name, sub in (("HOME", "home"), ("XDG_CACHE_HOME", "xdg-cache"), ("XDG_CONFIG_HOME", "xdg-config")):
        (cache / sub).mkdir(parents=True, exist_ok=True)
        env[name] = str(cache / sub)
    for folder in _package_folders(py):
        for pyc in Path(folder).rglob("__pycache__/*.pyc"):
            try:
                pyc.unlink()
            except OSError:
                pass
    return env


def _timed_output(argv, env) -> tuple[float, float, int, str, str]:
    """(wall s, CPU s of the child, return code, stdout, stderr) of one run."""
    import resource

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run(argv, env=env, cwd=NEUTRAL, capture_output=True, text=True, timeout=1800)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, proc.returncode, proc.stdout, proc.stderr


def _repeated_rows(repeats: int) -> list[dict]:
    """Each command of :data:`REPEATED`: first run (cold caches), then ``repeats`` repeats and one probe."""
    rows = []
    for what, argv, _, _ in REPEATED:
        for label, py in interpreters():
            with tempfile.TemporaryDirectory() as cache:
                env = cold_env(Path(cache), py)
                wall, cpu, rc, first, err = _timed_output([py, "-m", "landau", *argv], env)
                rows.append({"python": label, "command": what, "state": "first", "repeat": 0, "wall s": wall,
                             "CPU s": cpu if rc == 0 else float("nan"), "exit": rc, "load": round(load()[0], 1),
                             "same bytes": True, "imports": "", "note": "" if rc == 0 else err[-120:]})
                for rep in range(repeats):
                    wall, cpu, rc, out, err = _timed_output([py, "-m", "landau", *argv], env)
                    rows.append({"python": label, "command": what, "state": "repeat", "repeat": rep, "wall s": wall,
                                 "CPU s": cpu if rc == 0 else float("nan"), "exit": rc, "load": round(load()[0], 1),
                                 "same bytes": out == first, "imports": "", "note": "" if rc == 0 else err[-120:]})
                _, _, rc, out, err = _timed_output([py, "-c", PROBE, *argv], env)
                rows[-1]["imports"] = err.rsplit("LOADED", 1)[-1].strip() or "none of sympy, numba, scipy"
            print(f"  {label} {what}: first {rows[-1 - repeats]['CPU s']:.2f} CPU s, repeat "
                  f"{rows[-1]['CPU s']:.2f} CPU s, same bytes {rows[-1]['same bytes']}, imports: {rows[-1]['imports']}",
                  flush=True)
    return rows


def _row(label: str, what: str, state: str, run: tuple, repeat: int) -> dict:
    wall, cpu, rc, tail = run
    return {"python": label, "command": what, "state": state, "repeat": repeat, "wall s": wall,
            "CPU s": cpu if rc == 0 else float("nan"), "exit": rc, "load": round(load()[0], 1),
            "note": "" if rc == 0 else tail[:120]}


def _summary(rows: list[dict]) -> list[dict]:
    """One line per (command, state): this interpreter's min/median/max CPU s and, with a
    baseline, the per-repeat ratio baseline / this as min/median/max."""
    out = []
    for what, state in dict.fromkeys((r["command"], r["state"]) for r in rows):
        sel = [r for r in rows if r["command"] == what and r["state"] == state]
        mine = {r["repeat"]: r["CPU s"] for r in sel if r["python"] == "this"}
        base = {r["repeat"]: r["CPU s"] for r in sel if r["python"] == "baseline"}
        s = spread(mine.values())
        line = {"command": what, "state": state, "repeats": s["n"], "CPU s min": s["min"],
                "CPU s median": s["median"], "CPU s max": s["max"],
                "wall s median": spread(r["wall s"] for r in sel if r["python"] == "this")["median"]}
        if base:
            ratios = spread(base[k] / mine[k] for k in mine if k in base and mine[k] > 0)
            line.update({"baseline CPU s median": spread(base.values())["median"],
                         "baseline/this min": ratios["min"], "baseline/this median": ratios["median"],
                         "baseline/this max": ratios["max"]})
        out.append(line)
    return out


def _cols(summary: list[dict]) -> list[str]:
    cols = list(dict.fromkeys(k for r in summary for k in r))
    return cols


def section_coldstart(quick: bool) -> None:
    repeats = 1 if quick else 3
    rows = []
    with tempfile.TemporaryDirectory() as out:
        for rep in range(repeats):
            for what, argv, _, _ in COLD_COMMANDS:
                extra = ["--out", str(Path(out) / "run.csv")] if argv[0] == "simulate" else []
                for label, py in interpreters():      # interleaved: the same machine load for both
                    with tempfile.TemporaryDirectory() as cache:
                        env = cold_env(Path(cache), py)
                        cmd = [py, "-m", "landau", *argv, *extra]
                        rows.append(_row(label, what, "cold", timed_process(cmd, env, cwd=NEUTRAL), rep))
                        rows.append(_row(label, what, "warm", timed_process(cmd, env, cwd=NEUTRAL), rep))
                    print(f"  {label} {what}: cold {rows[-2]['CPU s']:.1f} CPU s, warm {rows[-1]['CPU s']:.2f} "
                          f"CPU s", flush=True)
        for label, py in interpreters():
            with tempfile.TemporaryDirectory() as cache:
                env = fresh_env(Path(cache))
                cmd = [py, "-c", "import landau.verify.cli"]   # nothing should compile at import
                rows.append(_row(label, "import landau.verify.cli", "cold", timed_process(cmd, env, cwd=NEUTRAL), 0))
                rows.append(_row(label, "import landau.verify.cli", "warm", timed_process(cmd, env, cwd=NEUTRAL), 0))
    again = _repeated_rows(repeats)
    summary = _summary(rows)
    again_summary = _summary(again)
    for line in again_summary:
        sel = [r for r in again if r["command"] == line["command"] and r["state"] == line["state"]
               and r["python"] == "this"]
        line["same bytes"] = all(r["same bytes"] for r in sel)
        line["imports"] = "; ".join(sorted({r["imports"] for r in sel if r["imports"]}))
    RAW["coldstart"] = rows + again
    RAW["coldstart_summary"] = summary + again_summary
    TABLES["coldstart"] = (
        "A command in a fresh process: `cold` — new `LANDAU_CACHE_DIR`, `NUMBA_CACHE_DIR`, `HOME`, `XDG_CACHE_HOME` "
        "and `XDG_CONFIG_HOME` folders and no `*.pyc` of landau (nothing derived or compiled before); `warm` — the "
        "same command again with the caches the cold run left (`verify` simulates again: it is never answered "
        "from the store of finished answers). CPU s = "
        f"user + sys of the child; {repeats} repeat(s).\n\n" + table(summary, _cols(summary)) +
        "\n\nA command repeated: `first` — its first run in fresh caches; `repeat` — the same command line again, "
        "answered from the store of finished answers (`landau.support.answers`); `same bytes` — its stdout equals "
        "the first run's; `imports` — which of sympy, numba and scipy a probe run of the repeat imported.\n\n"
        + table(again_summary, _cols(again_summary)))
    for name, _, goal, target in REPEATED:
        if goal is None:
            continue
        line = next(s for s in again_summary if s["command"] == name and s["state"] == "repeat")
        report(Goal("coldstart", goal, f"repeated `landau {name}`, answered from the store [CPU s]",
                    line["CPU s median"], target, "<=",
                    note=f"median of {line['repeats']}; same bytes as the first run: {line['same bytes']}; "
                         f"imports: {line['imports']}"))
    for name, _, goal, target in COLD_COMMANDS:
        cold = next(s for s in summary if s["command"] == name and s["state"] == "cold")
        warm = next(s for s in summary if s["command"] == name and s["state"] == "warm")
        note = f"median of {cold['repeats']}; warm {warm['CPU s median']:.2f} CPU s"
        if "baseline/this median" in cold:
            note += (f"; baseline/this cold {cold['baseline/this min']:.2f}/{cold['baseline/this median']:.2f}/"
                     f"{cold['baseline/this max']:.2f} (min/median/max)")
        report(Goal("coldstart", goal, f"first `landau {name}`, truly cold [CPU s]", cold["CPU s median"], target,
                    "<=", note=note))


#: (argv after ``landau``, goal number, target CPU s of the best of the repeats)
HELP_COMMANDS = ((["--help"], "10", 0.3), (["--version"], "10", 0.3))


def _script(py: str) -> list[str]:
    """The ``landau`` console script installed beside ``py`` (``py -m landau`` without one)."""
    script = Path(py).parent / "landau"
    return [str(script)] if script.is_file() else [py, "-m", "landau"]


def section_help(quick: bool) -> None:
    repeats = 5
    rows = []
    for rep in range(repeats):
        for argv, _, _ in HELP_COMMANDS:
            for label, py in interpreters():      # interleaved: the same machine load for both
                rows.append(_row(label, "landau " + " ".join(argv), "warm",
                                 timed_process([*_script(py), *argv], cwd=NEUTRAL), rep))
    summary = _summary(rows)
    RAW["help"] = rows
    RAW["help_summary"] = summary
    TABLES["help"] = (
        "`landau --help` and `landau --version` in a fresh process (the installed `landau` script); CPU s = "
        f"user + sys of the child; {repeats} repeats, the goal on the best.\n\n" + table(summary, _cols(summary)))
    for argv, goal, target in HELP_COMMANDS:
        what = "landau " + " ".join(argv)
        line = next(s for s in summary if s["command"] == what)
        note = f"best of {line['repeats']}; median {line['CPU s median']:.3f} CPU s"
        if "baseline CPU s median" in line:
            note += f"; baseline median {line['baseline CPU s median']:.3f} CPU s"
        report(Goal("help", goal, f"`{what}` [CPU s]", line["CPU s min"], target, "<=", note=note))


def section_figures(quick: bool) -> None:
    repeats = 1 if quick else 3
    rows = []
    with tempfile.TemporaryDirectory() as root:
        warm_caches = {}
        for rep in range(repeats):
            for paper, cold_each, _, _ in FIGURES:
                argv = ["-m", "landau", "figures", paper, "--no-progress", "--out", str(Path(root) / "out" / paper)]
                for label, py in interpreters():      # interleaved: the same machine load for both
                    key = (paper, label)
                    if key not in warm_caches:        # the first run fills this pair's caches: cold
                        warm_caches[key] = cold_env(Path(root) / f"{paper}-{label}", py)
                        rows.append(_row(label, paper, "cold", timed_process([py, *argv], warm_caches[key],
                                                                             cwd=NEUTRAL), rep))
                    elif cold_each:
                        with tempfile.TemporaryDirectory() as cache:
                            rows.append(_row(label, paper, "cold", timed_process([py, *argv], cold_env(Path(cache), py),
                                                                                 cwd=NEUTRAL), rep))
                    rows.append(_row(label, paper, "warm", timed_process([py, *argv], warm_caches[key],
                                                                         cwd=NEUTRAL), rep))
                    print(f"  {label} figures {paper}: " + ", ".join(
                        f"{r['state']} {r['CPU s']:.1f} CPU s" for r in rows
                        if r["command"] == paper and r["python"] == label and r["repeat"] == rep), flush=True)
    summary = _summary(rows)
    RAW["figures"] = rows
    RAW["figures_summary"] = summary
    TABLES["figures"] = (
        "`landau figures PAPER` in a fresh process: `warm` — the caches of an earlier run of the same command; "
        "`cold` — new `LANDAU_CACHE_DIR`, `NUMBA_CACHE_DIR`, `HOME`, `XDG_CACHE_HOME` and `XDG_CONFIG_HOME` folders "
        "and no `*.pyc` of landau (galvanetto2004: its first run only). "
        f"CPU s = user + sys of the child; {repeats} repeat(s).\n\n" + table(summary, _cols(summary)))
    for paper, _, goal, target in FIGURES:
        if goal is None:
            continue
        cold = next(s for s in summary if s["command"] == paper and s["state"] == "cold")
        warm = next(s for s in summary if s["command"] == paper and s["state"] == "warm")
        note = f"median of {cold['repeats']}; warm {warm['CPU s median']:.1f} CPU s"
        if "baseline/this median" in cold:
            note += (f"; baseline/this cold {cold['baseline/this min']:.2f}/{cold['baseline/this median']:.2f}/"
                     f"{cold['baseline/this max']:.2f} (min/median/max)")
        report(Goal("figures", goal, f"first `landau figures {paper}`, truly cold [CPU s]", cold["CPU s median"],
                    target, "<=", note=note))
    if not all(np.isfinite(r["CPU s"]) for r in rows):
        print("  some figure runs failed: see the note column", flush=True)
