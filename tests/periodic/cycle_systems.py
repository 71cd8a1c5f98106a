"""Small systems with known cycles for the tests of the cycle engine (numbers only)."""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from landau.periodic import CycleProblem, CycleStart, HopfStart

ROSSLER_AB = 0.2


def stuart_landau(omega: float = 1.3) -> CycleProblem:
    """ẋ = μx − ωy − x r², ẏ = ωx + μy − y r²: the cycle r = √μ, T = 2π/ω, multiplier exp(−2μT)."""

    def rhs(y, mu):
        x, v = y[0], y[1]
        r2 = x * x + v * v
        return np.array([mu * x - omega * v - x * r2, omega * x + mu * v - v * r2])

    def jac(y, mu):
        x, v = y[0], y[1]
        r2 = x * x + v * v
        return np.array([[mu - r2 - 2 * x * x, -omega - 2 * x * v], [omega - 2 * x * v, mu - r2 - 2 * v * v]])

    hopf = HopfStart(0.0, np.zeros(2), omega, np.array([1.0, -1j]), amplitude=1.0, side=1)
    return CycleProblem("stuart-landau", ("x", "y"), "mu", rhs, jac, hopf=hopf)


def rossler() -> CycleProblem:
    """Rössler (1976): ẋ = −y − z, ẏ = x + a y, ż = b + z(x − c), a = b = 0.2, parameter c."""
    a = b = ROSSLER_AB

    def rhs(y, c):
        return np.array([-y[1] - y[2], y[0] + a * y[1], b + y[2] * (y[0] - c)])

    def jac(y, c):
        x, _, z = np.broadcast_arrays(y[0], y[1], y[2])
        o, one = np.zeros_like(x), np.ones_like(x)
        return np.array([[o, -one, -one], [one, a * one, o], [z, o, x - c]])

    return CycleProblem("rossler", ("x", "y", "z"), "c", rhs, jac, parameter_range=(0.0, 5.7))


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


def adaptive_control(beta: float = 1.0) -> CycleProblem:
    """The adaptive-control (Lur'e) system ẋ = y, ẏ = z, ż = −αz − βy − x + x² (MatCont's ``adaptx``),
    continued in α from its Hopf point at the origin, α = 1 (β = 1, ω = 1, q = (1, i, −1))."""

    def rhs(y, a):
        return np.array([y[1], y[2], -a * y[2] - beta * y[1] - y[0] + y[0] ** 2])

    def jac(y, a):
        x = np.asarray(y[0])
        o, one = np.zeros_like(x), np.ones_like(x)
        return np.array([[o, one, o], [o, o, one], [-1 + 2 * x, -beta * one, -a * one]])

    hopf = HopfStart(1.0, np.zeros(3), 1.0, np.array([1.0, 1j, -1.0]))
    return CycleProblem("adaptive-control", ("x", "y", "z"), "alpha", rhs, jac, hopf=hopf)
