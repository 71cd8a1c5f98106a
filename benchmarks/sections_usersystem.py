"""User systems: the compiled simulation and check of a DynamicalSystem written as strings.

* ``usersystem`` — two systems from :meth:`DynamicalSystem.from_strings`: the Brusselator
  (a = 1.5, b = 3.3, just above b_c = 1 + a² = 3.25: its stable cycle, from (1, 2) over t = 100,
  about 24 periods) and a spring–block with the aging (Dieterich–Ruina) law written as E·ẏ = f with
  states X, u = v − V, θ and E = diag(1, M, 1) (σ = V = L = 1, a = 0.01, b = 0.015, M = 0.5; its
  supercritical Hopf at k_c = 0.255, ω_c = 0.707; run at k = 0.98·k_c from the displaced
  equilibrium over t = 200, about 22 periods).

  *Simulation*: :func:`landau.analyses.system_simulation.simulate_system` (the compiled Radau IIA,
  its default and only method) against today's scipy route for a user system — the field and
  Jacobian lambdified with numpy and E⁻¹ applied in Python (``landau.systems.numeric_field.numeric_field``,
  what the check used), integrated by ``solve_ivp`` Radau with that Jacobian — both down a tolerance
  ladder with the same absolute-tolerance rule (atol = rtol·max|y₀|), the error at t_end against
  ``solve_ivp`` DOP853 at rtol = atol = 1e-13 (relative to max|y|), and the CPU ratio read along both
  Pareto fronts at errors both reach.

  *Check*: ``landau.check(system, eps2=1e-3)`` (two shots, at ε² = 1e-3 and 2.5e-4, each with its
  monodromy) with the compiled shooting against the same check with the former scipy flow
  (``_shoot``'s default), in the same process, both at the check's rtol 1e-10; the whole call is
  timed (Hopf normal form included), and the simulated amplitudes must agree.

Both sides are warm (compiled code loaded, derivation cached) before timing; the first call's
cost is reported beside it, and the Brusselator's check is also timed as a user's first call, in
fresh interpreters (imports and the loading of compiled code included).
"""

from __future__ import annotations

import time

import numpy as np
from benchlib import RAW, TABLES, Goal, cpu_time, ladder, ratios_at_equal_error, report, table

BRUSSELATOR = ({"x": "a - (b + 1)*x + x^2*y", "y": "b*x - x^2*y"}, "b", {"a": 1.5})
RATE_STATE = ({"X": "u", "u": "-k*X - sigma*(a*log((V + u)/V) + b*log(V*theta/L))",
               "theta": "1 - (V + u)*theta/L"}, "k",
              {"V": 1.0, "sigma": 1.0, "a": 0.01, "b": 0.015, "L": 1.0, "M": 0.5})


def _systems():
    from landau import DynamicalSystem

    bru = DynamicalSystem.from_strings(*BRUSSELATOR, equilibrium={"x": "a", "y": "b/a"}, name="brusselator")
    rs = DynamicalSystem.from_strings(*RATE_STATE, equilibrium={"X": "0", "u": "0", "theta": "L/V"},
                                      mass={"u": "M"}, name="rate-state")
    # (system, simulation parameters, y0 (None: displaced equilibrium), t_end, check bracket)
    return [(bru, {"b": 3.3}, [1.0, 2.0], 100.0, (2.5, 4.0)),
            (rs, {"k": 0.98 * 0.255}, None, 200.0, (0.001, 1.0))]


def _scipy_route(system, values):
    """Today's scipy route: numpy-lambdified f, J and E⁻¹ applied in Python (the check's former field)."""
    from landau.systems.numeric_field import numeric_field

    f, J, E_inverse, vals = numeric_field(system, values)
    pp = float(values[system.parameter.name])
    Einv = E_inverse(pp)

    def rhs(t, y):
        return Einv @ np.asarray(f(*y, pp, *vals), dtype=float)

    def jac(t, y):
        return Einv @ np.asarray(J(*y, pp, *vals), dtype=float)

    return rhs, jac


def _simulation_rows(system, sim_params, y0, t_end, quick):
    from scipy.integrate import solve_ivp

    from landau.analyses.system_simulation import compile_system, simulate_system

    cs = compile_system(system)
    values = cs.resolve(sim_params)
    tic = time.process_time()
    first = simulate_system(system, sim_params, t_end, y0, rtol=1e-6)
    first_cpu = time.process_time() - tic
    y0 = first.y[:, 0].copy()
    rhs, jac = _scipy_route(system, {**system.defaults, **values})
    ref = solve_ivp(rhs, (0.0, t_end), y0, method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]
    scale = float(np.max(np.abs(ref)))

    def error(y):
        return float(np.max(np.abs(np.asarray(y) - ref)) / scale)

    atol0 = float(np.max(np.abs(y0)))
    rows = []
    ours = f"{system.name}: landau simulate_system (compiled Radau IIA)"
    for e in range(4, 11 if quick else 12):
        rt = 10.0 ** -e
        run, cpu = cpu_time(lambda rt=rt: simulate_system(system, sim_params, t_end, y0, rtol=rt))
        rows.append({"system": system.name, "method": ours, "rtol": rt, "error": error(run.y_final), "cpu": cpu,
                     "steps": run.nsteps})
    floor = min(r["error"] for r in rows)
    theirs = f"{system.name}: solve_ivp Radau (numpy f+J, the former route)"

    def one(rt):
        def go():
            s = solve_ivp(rhs, (0.0, t_end), y0, method="Radau", jac=jac, rtol=rt, atol=rt * atol0)
            if s.status != 0:
                raise RuntimeError(s.message)
            return s
        s, cpu = cpu_time(go, repeat=1)
        return error(s.y[:, -1]), cpu

    for rt, err, cpu, note in ladder(one, [10.0 ** -e for e in range(4, 13)], floor, budget=10.0 if quick else 20.0):
        rows.append({"system": system.name, "method": theirs, "rtol": rt, "error": err, "cpu": cpu, "note": note})
    return rows, ours, theirs, first_cpu


def _check_row(system, bracket):
    from landau import check
    from landau.analyses import system_simulation

    params = dict(system.defaults)
    tic = time.process_time()
    check(system, eps2=1e-3, params=params, bracket=bracket)
    first = time.process_time() - tic
    ours, cpu_ours = cpu_time(lambda: check(system, eps2=1e-3, params=params, bracket=bracket), repeat=3)
    real = system_simulation.shooting_flow
    system_simulation.shooting_flow = lambda *a: None       # the check's former flow: _shoot's scipy default
    try:
        theirs, cpu_theirs = cpu_time(lambda: check(system, eps2=1e-3, params=params, bracket=bracket), repeat=2)
    finally:
        system_simulation.shooting_flow = real
    return {"system": system.name, "check compiled cpu": cpu_ours, "check scipy cpu": cpu_theirs,
            "ratio": cpu_theirs / cpu_ours, "first call cpu": first,
            "amplitude compiled": ours.amplitude_simulated, "amplitude scipy": theirs.amplitude_simulated,
            "amplitude rel. difference": abs(ours.amplitude_simulated / theirs.amplitude_simulated - 1),
            "verdicts": f"{ours.verdict.value} / {theirs.verdict.value}"}


#: one check in a fresh interpreter: prints the check's own CPU seconds (argv[1]: "compiled" or "scipy")
_FRESH = """
import sys, time
from landau import DynamicalSystem, check
from landau.analyses import system_simulation
if sys.argv[1] == "scipy":
    system_simulation.shooting_flow = lambda *a: None
s = DynamicalSystem.from_strings({rhs!r}, {par!r}, {params!r}, equilibrium={eq!r})
t = time.process_time()
check(s, eps2=1e-3, params=dict(s.defaults), bracket={bracket!r})
print(time.process_time() - t)
"""


def _fresh_check_rows(repeat: int) -> list[dict]:
    """The Brusselator's check as a user's first call: a fresh interpreter each time (disk caches warm),
    the check's own CPU and the child's whole CPU (imports included), the two routes alternating."""
    import subprocess
    import sys

    from benchlib import NEUTRAL

    rhs, par, params = BRUSSELATOR
    code = _FRESH.format(rhs=rhs, par=par, params=params, eq={"x": "a", "y": "b/a"}, bracket=(2.5, 4.0))
    got: dict[str, list[tuple[float, float]]] = {"compiled": [], "scipy": []}
    for _ in range(repeat):
        for route in got:
            import resource

            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            out = subprocess.run([sys.executable, "-c", code, route], capture_output=True, text=True, cwd=NEUTRAL,
                                 timeout=600, check=True).stdout
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            child = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
            got[route].append((float(out.strip().splitlines()[-1]), child))
    return [{"route": r, "check cpu (min)": min(c for c, _ in v), "process cpu (min)": min(p for _, p in v),
             "runs": len(v)} for r, v in got.items()]


def section_usersystem(quick: bool) -> None:
    sim_rows, checks, firsts = [], [], []
    for system, sim_params, y0, t_end, bracket in _systems():
        rows, ours, theirs, first = _simulation_rows(system, sim_params, y0, t_end, quick)
        sim_rows += rows
        firsts.append(f"{system.name} {first:.3g} s")
        for tgt, (c_theirs, c_ours, _) in ratios_at_equal_error(rows, ours, [theirs], [1e-5, 1e-7, 1e-9]).items():
            report(Goal("usersystem", "usersystem-1", f"{system.name} from strings: scipy Radau / compiled "
                        f"simulate_system CPU at error {tgt:.0e}", c_theirs / c_ours, 20.0))
        row = _check_row(system, bracket)
        checks.append(row)
        report(Goal("usersystem", "usersystem-2", f"{system.name} from strings: check with scipy flow / compiled, CPU",
                    row["ratio"], 5.0, note=f"amplitudes agree to {row['amplitude rel. difference']:.1g}"))
    fresh = _fresh_check_rows(1 if quick else 2)
    RAW["usersystem"] = sim_rows
    RAW["usersystem_check"] = checks
    RAW["usersystem_fresh"] = fresh
    TABLES["usersystem"] = (
        "Simulation (error at t_end against solve_ivp DOP853 at 1e-13, relative to max|y|; CPU per run, warm; "
        f"first call in this process, loading the kernel: {', '.join(firsts)}):\n\n"
        + table(sim_rows, ["method", "rtol", "error", "cpu", "steps", "note"])
        + "\n\nlandau.check(system, eps2=1e-3) (two shots with their monodromy, rtol 1e-10; CPU per call, warm):\n\n"
        + table(checks, ["system", "check compiled cpu", "check scipy cpu", "ratio", "first call cpu",
                         "amplitude rel. difference", "verdicts"])
        + "\n\nThe Brusselator's check as a user's first call, in a fresh interpreter (disk caches warm; "
          "the process CPU includes importing landau, scipy and numba and loading the compiled code):\n\n"
        + table(fresh, ["route", "check cpu (min)", "process cpu (min)", "runs"]))
