"""The working-precision Hopf point of a user system against its closed form, and what it costs.

The Lorenz system with σ = 10, b = 2 has its Hopf point on the branch C± where the characteristic
polynomial λ³ + (σ + b + 1)λ² + b(σ + r)λ + 2bσ(r − 1) has a pair ±iω: the Routh–Hurwitz condition
a₂a₁ = a₀ gives Lorenz's (1963) critical r_H = σ(σ + b + 3)/(σ − b − 1) = 150/7, and ω² = a₁ = b(σ + r_H)
= 440/7 — exact rationals, since σ and b are exact in float64.
"""

from __future__ import annotations

import mpmath

import landau.derivation.general as general
from landau import DynamicalSystem

LORENZ = DynamicalSystem.from_strings({"x": "s*(y - x)", "y": "x*(r - z) - y", "z": "x*y - b*z"}, "r",
                                      {"s": 10.0, "b": 2.0},
                                      equilibrium={"x": "sqrt(b*(r - 1))", "y": "sqrt(b*(r - 1))", "z": "r - 1"},
                                      name="lorenz")


def test_the_hopf_point_at_50_digits_in_seven_evaluations(monkeypatch):
    num = general.NumericSystem(LORENZ, LORENZ.defaults)
    (p0, y0, lam), = general.scan_hopf(num, 15.0, 30.0)
    equilibria = 0
    solve = general.NumericSystem.equilibrium_mp

    def counted(self, p, guess):
        nonlocal equilibria
        equilibria += 1
        return solve(self, p, guess)

    monkeypatch.setattr(general.NumericSystem, "equilibrium_mp", counted)
    with mpmath.workdps(50):
        pc, wc, y = general.refine_hopf(num, p0, abs(lam.imag), y0)
        rH, omega = mpmath.mpf(150) / 7, mpmath.sqrt(mpmath.mpf(440) / 7)
        assert abs(pc - rH) < mpmath.mpf(10) ** -45 * rH
        assert abs(wc - omega) < mpmath.mpf(10) ** -45 * omega
        assert abs(y[2] - (rH - 1)) < mpmath.mpf(10) ** -45 * rH
    # two equilibria an iteration (the step in ω moves none), three iterations from the float64
    # point, one for the returned state: mpmath.findroot, stopping on the residual |det|, took 12
    assert equilibria <= 7
