"""Standard systems with known cycles, as :class:`~landau.periodic.problem.CycleProblem` data: the
systems the cycle engine is checked on against closed forms and published values (its tests and
``benchmarks/bench_cycles.py`` take them from here), and small examples to try the engine on.

* :func:`stuart_landau` — the Hopf normal form, cycle r = √μ in closed form;
* :func:`rossler` — Rössler (1976), a = b = 0.2, continued in c (the period-doubling cascade);
* :func:`lorenz` — Lorenz (1963), σ = 10, b = 8/3, continued in r (the window near r = 100);
* :func:`adaptive_control` — MatCont's adaptive-control (Lur'e) example, continued in α;
* :func:`steinmetz_larter` — the Steinmetz–Larter peroxidase–oxidase model of MatCont and
  BifurcationKit, continued in k₈ (a Neimark–Sacker point and a fold of cycles).

References
----------
Rössler, O. E. (1976), An equation for continuous chaos, Phys. Lett. A 57, 397–398.
Lorenz, E. N. (1963), Deterministic nonperiodic flow, J. Atmos. Sci. 20, 130–141.
Steinmetz, C. G. & Larter, R. (1991), The quasiperiodic route to chaos in a model of the
peroxidase–oxidase reaction, J. Chem. Phys. 94, 1388–1396.
"""

from __future__ import annotations

import numpy as np

from landau.periodic.problem import CycleProblem, HopfStart

ROSSLER_AB = 0.2
#: BifurcationKit's Steinmetz–Larter tutorial parameters (k₈ is the continuation parameter)
STEINMETZ_LARTER = dict(k1=0.1631021, k2=1250.0, k3=0.046875, k4=20.0, k5=1.104, k6=0.001, km7=0.1175, k7=1.5)


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


def rossler(parameter_range: tuple[float, float] = (0.0, 5.7)) -> CycleProblem:
    """Rössler (1976): ẋ = −y − z, ẏ = x + a y, ż = b + z(x − c), a = b = 0.2, parameter c."""
    a = b = ROSSLER_AB

    def rhs(y, c):
        return np.array([-y[1] - y[2], y[0] + a * y[1], b + y[2] * (y[0] - c)])

    def jac(y, c):
        x, _, z = np.broadcast_arrays(y[0], y[1], y[2])
        o, one = np.zeros_like(x), np.ones_like(x)
        return np.array([[o, -one, -one], [one, a * one, o], [z, o, x - c]])

    return CycleProblem("rossler", ("x", "y", "z"), "c", rhs, jac, parameter_range=parameter_range)


def lorenz(sigma: float = 10.0, b: float = 8.0 / 3.0,
           parameter_range: tuple[float, float] = (99.0, 101.0)) -> CycleProblem:
    """Lorenz (1963): ẋ = σ(y − x), ẏ = rx − y − xz, ż = xy − bz, continued in r (σ = 10, b = 8/3);
    the default range is the period-doubling window near r = 100."""

    def rhs(y, r):
        return np.array([sigma * (y[1] - y[0]), r * y[0] - y[1] - y[0] * y[2], y[0] * y[1] - b * y[2]])

    def jac(y, r):
        x, v, z = np.broadcast_arrays(y[0], y[1], y[2])
        o, one = np.zeros_like(x), np.ones_like(x)
        return np.array([[-sigma * one, sigma * one, o], [r - z, -one, -x], [v, x, -b * one]])

    return CycleProblem("lorenz", ("x", "y", "z"), "r", rhs, jac, scales=np.array([20.0, 30.0, 100.0]),
                        parameter_range=parameter_range)


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


def steinmetz_larter(parameter_range: tuple[float, float] = (0.7, 0.9)) -> CycleProblem:
    """The Steinmetz–Larter peroxidase–oxidase model (MatCont's and BifurcationKit's example),
    Ȧ = −k₁ABX − k₃ABY + k₇ − k₋₇A, Ḃ = −k₁ABX − k₃ABY + k₈, Ẋ = k₁ABX − 2k₂X² + 2k₃ABY − k₄X + k₆,
    Ẏ = −k₃ABY + 2k₂X² − k₅Y, with BifurcationKit's parameters (``STEINMETZ_LARTER``), continued in k₈."""
    k = STEINMETZ_LARTER

    def rhs(y, k8):
        A, B, X, Y = y[0], y[1], y[2], y[3]
        r1, r3 = k["k1"] * A * B * X, k["k3"] * A * B * Y
        return np.array([-r1 - r3 + k["k7"] - k["km7"] * A, -r1 - r3 + k8,
                         r1 - 2 * k["k2"] * X ** 2 + 2 * r3 - k["k4"] * X + k["k6"],
                         -r3 + 2 * k["k2"] * X ** 2 - k["k5"] * Y])

    def jac(y, k8):
        A, B, X, Y = np.broadcast_arrays(y[0], y[1], y[2], y[3])
        k1, k3 = k["k1"], k["k3"]
        dA = -k1 * B * X - k3 * B * Y      # ∂(−k₁ABX − k₃ABY)/∂A
        dB = -k1 * A * X - k3 * A * Y
        dX, dY = -k1 * A * B, -k3 * A * B
        return np.array([[dA - k["km7"], dB, dX, dY],
                         [dA, dB, dX, dY],
                         [k1 * B * X + 2 * k3 * B * Y, k1 * A * X + 2 * k3 * A * Y,
                          k1 * A * B - 4 * k["k2"] * X - k["k4"], 2 * k3 * A * B],
                         [-k3 * B * Y, -k3 * A * Y, 4 * k["k2"] * X, -k3 * A * B - k["k5"]]])

    return CycleProblem("steinmetz-larter", ("A", "B", "X", "Y"), "k8", rhs, jac, parameter_range=parameter_range)


__all__ = ["ROSSLER_AB", "STEINMETZ_LARTER", "adaptive_control", "lorenz", "rossler", "steinmetz_larter",
           "stuart_landau"]
