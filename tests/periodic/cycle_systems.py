"""The cycle engine's test systems (:mod:`landau.periodic.examples`) and the tests' independent routes:
simulated starting cycles and the monodromy by shooting with a separate integrator."""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from landau.periodic import CycleProblem, CycleStart
from landau.periodic.examples import (  # noqa: F401  (the tests take the systems from here)
    ROSSLER_AB,
    STEINMETZ_LARTER,
    adaptive_control,
    lorenz,
    rossler,
    steinmetz_larter,
    stuart_landau,
)


def simulated_cycle(problem: CycleProblem, p: float, y0, t_end: float = 300.0) -> CycleStart:
    """The last full period of a DOP853 simulation (between two upward zero crossings of state 1)."""
    sol = solve_ivp(lambda t, y: problem.rhs(y, p), (0.0, t_end), y0, method="DOP853", rtol=1e-10,
                    atol=1e-12, dense_output=True)
    ts = np.linspace(t_end / 2, t_end, 20001)
    y1 = sol.sol(ts)[1]
    i = np.where((y1[:-1] < 0) & (y1[1:] >= 0))[0]
    t0, t1 = ts[i[-2]], ts[i[-1]]
    tt = np.linspace(t0, t1, 200)
    return CycleStart(tt, sol.sol(tt), t1 - t0, p)


def monodromy_by_shooting(problem: CycleProblem, y0: np.ndarray, T: float, p: float) -> np.ndarray:
    """The monodromy from the variational equations Φ′ = A Φ integrated with DOP853 (rtol 1e-12)."""
    n = problem.n

    def f(t, z):
        y, Phi = z[:n], z[n:].reshape(n, n)
        return np.concatenate([problem.rhs(y, p), (problem.jac(y, p) @ Phi).ravel()])

    z0 = np.concatenate([y0, np.eye(n).ravel()])
    sol = solve_ivp(f, (0.0, T), z0, method="DOP853", rtol=1e-12, atol=1e-14)
    return sol.y[n:, -1].reshape(n, n)


def simulated_cycle_lsoda(problem: CycleProblem, p: float, y0, t_end: float, state: int = 0) -> CycleStart:
    """The last full period of an LSODA simulation (rtol 1e-11, the analytic Jacobian) between two
    upward crossings of state ``state`` through its mean over the second half."""
    sol = solve_ivp(lambda t, y: problem.rhs(y, p), (0.0, t_end), y0, method="LSODA", rtol=1e-11, atol=1e-13,
                    jac=lambda t, y: problem.jac(y, p), dense_output=True)
    ts = np.linspace(t_end / 2, t_end, 1000 * int(t_end) + 1)
    a = sol.sol(ts)[state]
    m = a.mean()
    i = np.where((a[:-1] < m) & (a[1:] >= m))[0]
    t0, t1 = ts[i[-2]], ts[i[-1]]
    tt = np.linspace(t0, t1, 400)
    return CycleStart(tt, sol.sol(tt), t1 - t0, p)


def simulated_cycle_by_section(problem: CycleProblem, p: float, y0, t_end: float, section, state: int = 0,
                               max_crossings: int = 16) -> CycleStart:
    """One full period of a DOP853 simulation (rtol 1e-11) on its attractor: the section ``section(y)``
    crossed upward; the period closes at the first later crossing where ``state`` repeats to 1e-6."""
    sol = solve_ivp(lambda t, y: problem.rhs(y, p), (0.0, t_end), y0, method="DOP853", rtol=1e-11, atol=1e-11)

    def event(t, y):
        return section(y)
    event.direction = 1
    tail = solve_ivp(lambda t, y: problem.rhs(y, p), (0.0, t_end / 2), sol.y[:, -1], method="DOP853",
                     rtol=1e-11, atol=1e-11, events=event, dense_output=True)
    te, ye = tail.t_events[0], tail.y_events[0]
    i0 = len(te) - max_crossings - 1
    k = next(k for k in range(1, max_crossings + 1) if abs(ye[i0 + k, state] - ye[i0, state]) < 1e-6)
    tt = np.linspace(te[i0], te[i0 + k], 600)
    return CycleStart(tt, tail.sol(tt), te[i0 + k] - te[i0], p)
