"""Work–precision study on the stick–slip cycle of Putelat et al. (2010), Fig. 3.

Problem: Dieterich law (26)+(28), V/V_* = 100, κ = kL/(Mg) = 1e-3, m = V_*²/(gL) ≈ 1.13e-7
(Table 1 parameters).  The stable stick–slip cycle is found by shooting; each method then
integrates exactly one period from the cycle's section point, and the error is measured
at the end of the period against a reference solution:

    error = max_i |y_i − y_ref,i| / max(1, |y_ref,i|)   (scaled variables ξ, w = ln(v/V), ψ),

i.e. relative for the O(100) slip ξ and absolute in ln v and ln φ (= relative in v, φ).

Reference: the default integrator at rtol = 1e-13 (its convergence from 1e-11 to 1e-13 is
reported), checked against scipy's Radau at rtol = 1e-13 with the analytic Jacobian (a
second, independent implementation of a different code path) — the agreement is part of
the result.  Methods: the toolkit's compiled Radau IIA, and ``scipy.integrate.solve_ivp``
Radau, BDF, LSODA with a plain Python right-hand side, with and without the analytic
Jacobian (also plain Python), over rtol = atol = 1e-4 … 1e-12.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

from landau.laws import get_law
from landau.verify.springblock.model import SpringBlockModel
from landau.verify.springblock.orbits import PeriodicOrbit, section_point, shoot
from landau.verify.springblock.simulate import W_INDEX, integrate

TOLERANCES = tuple(10.0 ** -e for e in range(4, 13))
SCIPY_METHODS = ("Radau", "BDF", "LSODA")


def fig3_model() -> SpringBlockModel:
    """Dieterich law, V/V_* = 100, κ = 1e-3, m = V_*²/(gL) with g = 9.81 (Fig. 3)."""
    law = get_law("dieterich")
    p = law.defaults()
    return SpringBlockModel.from_dimensionless(law, p["V_s"] ** 2 / (9.81 * p["L"]), 1e-3, 100.0)


def fig3_cycle(model: SpringBlockModel | None = None) -> PeriodicOrbit:
    """The stable stick–slip cycle of Fig. 3 (settle 30 cycles from a small perturbation, then shoot)."""
    model = model or fig3_model()
    y0 = np.insert(section_point(model, 5e-6), W_INDEX, 0.0)
    run = integrate(model, y0, (0.0, 1e5), rtol=1e-8, event_index=W_INDEX, event_direction=-1, stop_after=30)
    return shoot(model, np.delete(run.event_y[-1], W_INDEX), rtol=1e-11, tol=1e-11)


def error(y, yref) -> float:
    y, yref = np.asarray(y), np.asarray(yref)
    return float(np.max(np.abs(y - yref) / np.maximum(1.0, np.abs(yref))))


@dataclass(frozen=True)
class WorkPoint:
    method: str
    rtol: float
    error: float
    cpu_seconds: float
    steps: int
    nfev: int


@dataclass(frozen=True)
class WorkPrecision:
    period: float
    reference_rtol: float
    reference_check: dict
    points: tuple[WorkPoint, ...] = field(repr=False)

    def table(self) -> str:
        lines = [f"Fig. 3 stick-slip cycle (Dieterich, V/V* = 100, kappa = 1e-3), one period T = {self.period:.6g} s",
                 f"reference: default integrator at rtol {self.reference_rtol:g}; "
                 + ", ".join(f"{k} = {v:.3g}" for k, v in self.reference_check.items()),
                 f"{'method':34s} {'rtol':>8s} {'error':>10s} {'cpu [s]':>10s} {'steps':>8s} {'nfev':>9s}"]
        for p in self.points:
            lines.append(f"{p.method:34s} {p.rtol:8.0e} {p.error:10.3e} {p.cpu_seconds:10.4g} {p.steps:8d} {p.nfev:9d}")
        return "\n".join(lines) + "\n"

    def as_dict(self) -> dict:
        return {"period": self.period, "reference_rtol": self.reference_rtol, "reference_check": self.reference_check,
                "points": [p.__dict__ for p in self.points]}


def _timed(fn, min_time: float = 0.05):
    """CPU seconds per call (repeats fast calls so the clock resolution does not matter)."""
    reps, total, out = 0, 0.0, None
    while reps == 0 or (total < min_time and reps < 50):
        t0 = time.process_time()
        out = fn()
        total += time.process_time() - t0
        reps += 1
    return out, total / reps


def scipy_run(model: SpringBlockModel, y0, T: float, method: str, rtol: float, with_jac: bool):
    """solve_ivp with the plain Python right-hand side (and Jacobian) generated for the model."""
    c = model.compiled
    p = model.p
    n = model.n

    def f(t, y):
        out = np.empty(n)
        c.rhs_py(t, y, p, out)
        return out

    def jac(t, y):
        out = np.empty((n, n))
        c.jac_py(t, y, p, out)
        return out

    kw = {"jac": jac} if with_jac else {}
    sol = solve_ivp(f, (0.0, T / model.time_unit), np.asarray(y0, dtype=float), method=method, rtol=rtol,
                    atol=rtol, **kw)
    if sol.status != 0:
        from landau.errors import IntegratorError
        raise IntegratorError(f"solve_ivp({method}) failed: {sol.message}", t=float(sol.t[-1] * model.time_unit),
                              state=sol.y[:, -1])
    return sol.y[:, -1], int(sol.t.size - 1), int(sol.nfev)


def run_work_precision(tolerances=TOLERANCES, methods=SCIPY_METHODS, reference_rtol: float = 1e-13,
                       progress=None) -> WorkPrecision:
    model = fig3_model()
    orbit = fig3_cycle(model)
    y0 = np.insert(orbit.z, W_INDEX, 0.0)
    T = orbit.period
    ref = integrate(model, y0, (0.0, T), rtol=reference_rtol).y_final
    check = {
        "default rtol 1e-11 vs ref": error(integrate(model, y0, (0.0, T), rtol=1e-11).y_final, ref),
        "default rtol 1e-12 vs ref": error(integrate(model, y0, (0.0, T), rtol=1e-12).y_final, ref),
        "scipy Radau+J rtol 1e-13 vs ref": error(scipy_run(model, y0, T, "Radau", 1e-13, True)[0], ref),
    }
    pts = []
    for rtol in tolerances:
        run, cpu = _timed(lambda rtol=rtol: integrate(model, y0, (0.0, T), rtol=rtol))
        pts.append(WorkPoint("landau Radau IIA (numba, analytic J)", rtol, error(run.y_final, ref), cpu, run.nsteps,
                             run.nfev))
        if progress:
            progress(pts[-1])
    for method in methods:
        for with_jac in (True, False):
            for rtol in tolerances:
                (y, steps, nfev), cpu = _timed(
                    lambda method=method, rtol=rtol, with_jac=with_jac: scipy_run(model, y0, T, method, rtol, with_jac),
                    min_time=0.0)
                pts.append(WorkPoint(f"solve_ivp {method} {'+ analytic J' if with_jac else '(FD J)'}", rtol,
                                     error(y, ref), cpu, steps, nfev))
                if progress:
                    progress(pts[-1])
    return WorkPrecision(T, reference_rtol, check, tuple(pts))


def plot(wp: WorkPrecision, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from landau.support.io import atomic_savefig

    fig, ax = plt.subplots(figsize=(7, 5))
    for method in dict.fromkeys(p.method for p in wp.points):
        pts = [p for p in wp.points if p.method == method]
        ax.loglog([max(p.error, 1e-16) for p in pts], [p.cpu_seconds for p in pts], "o-", label=method, ms=4)
    ax.set_xlabel("error at the end of one period")
    ax.set_ylabel("CPU time [s]")
    ax.set_title("Work-precision, Fig. 3 stick-slip cycle (Dieterich, V/V* = 100, kappa = 1e-3)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    out = atomic_savefig(fig, path)
    plt.close(fig)
    return out
