"""The period-doubling cascade of the quasi-static spring–block with two state variables (Gu, Rice,
Ruina & Tse 1984), by cycle continuation, confirmed by direct simulation in a Poincaré section.

The block is written as a user system (the model ``system``, strings parsed by the whitelist parser):
the slip law with two states in Gu et al.'s dimensionless form — stress in units of Aσ, velocity
v = V/V₀, time in L₁/V₀, stiffness κ = kL₁/(Aσ), no inertia — in the states x = ln v, θ₁, θ₂:

    dθ₁/dt = −v[θ₁ + (1 + β₁) ln v],   dθ₂/dt = −(v/ρ)[θ₂ + β₂ ln v],
    τ = ln v + θ₁ + θ₂,  dτ/dt = κ(1 − v)  ⇒  dx/dt = κ(1 − v) − dθ₁/dt − dθ₂/dt,

with β₁ = 1, β₂ = 0.84, ρ = L₂/L₁ = 0.048 (B₁ = (1 + β₁)A, B₂ = β₂A; the steady state weakens as
−(β₁ + β₂) ln v). Gu et al.'s paper is not among the sources available here: these are the values
quoted for their chaotic example, in this convention. With β₂ = −0.84 instead the steady state still
weakens (slope −0.16, Hopf at κ = 0.1567), but below the Hopf point every simulated motion runs away
(v → ∞: in fast slip the two states form a saddle, friction falling exponentially with slip).

The branch from the supercritical Hopf point κ_c = 2.2210635 is continued down in κ; its period
doublings (measured: κ = 2.0730668, 2.0566736, 2.0534002, 2.0527081; Feigenbaum ratios 5.01, 4.73
→ 4.669) are located and switched onto. The check by simulation is independent of the engine's
doubled branches: DOP853 from a point of the period-1 (resp. period-2) cycle, perturbed, on either
side of the first (second) doubling; after the transient the section x = 0 (v = 1, upward) shows
1 | 2 and 2 | 4 distinct values of θ₁.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import landau
from landau.periodic import cycle_at, follow_cascade

RHS = {"x": "kappa*(1 - exp(x)) + exp(x)*(th1 + (1 + b1)*x) + exp(x)/rho*(th2 + b2*x)",
       "th1": "-exp(x)*(th1 + (1 + b1)*x)",
       "th2": "-exp(x)/rho*(th2 + b2*x)"}
GU1984 = {"b1": 1.0, "b2": 0.84, "rho": 0.048}
OPTIONS = {"rhs": RHS, "parameter": "kappa", "equilibrium": {"x": "0", "th1": "0", "th2": "0"},
           "bracket": (1.5, 3.0)}


@pytest.fixture(scope="module")
def cascade():
    br = landau.cycles("system", params=GU1984, options=OPTIONS, steps=40, ds=0.01, ds_max=0.05,
                       stop_at=("PD",))
    return br, follow_cascade(br.problem, br.points("PD")[0], doublings=2, ds=0.005, ds_max=0.02)


def test_hopf_point_and_the_first_two_doublings(cascade):
    br, cas = cascade
    h = br.problem.hopf
    # the Hopf point of the linearisation: J = [[−κ + 2 + β₂/ρ, 1, 1/ρ], [−2, −1, 0], [−β₂/ρ, 0, −1/ρ]]
    b2, rho = GU1984["b2"], GU1984["rho"]

    def growth(k):
        J = np.array([[-k + 2 + b2 / rho, 1, 1 / rho], [-2, -1, 0], [-b2 / rho, 0, -1 / rho]])
        return np.max(np.linalg.eigvals(J).real)
    from scipy.optimize import brentq
    assert h.p_c == pytest.approx(brentq(growth, 1.5, 3.0, xtol=1e-14), rel=1e-10)
    assert h.Lambda < 0 and bool(br.stable[1])            # supercritical: the stable cycle for κ < κ_c
    pd1 = br.points("PD")[0]
    pd2, pd3 = cas.points
    assert pd1.parameter > pd2.parameter > pd3.parameter
    assert 1.95 < pd2.period / pd1.period < 2.05 and 1.95 < pd3.period / pd2.period < 2.05
    # the windows shrink as a cascade's do (Feigenbaum: δ → 4.669)
    assert 3.5 < (pd1.parameter - pd2.parameter) / (pd2.parameter - pd3.parameter) < 6.5


def _block(t, y, kappa):
    """The block's field written again for the simulation (independent of landau's field builder)."""
    x, th1, th2 = y
    v = np.exp(x)
    d1 = -v * (th1 + (1 + GU1984["b1"]) * x)
    d2 = -(v / GU1984["rho"]) * (th2 + GU1984["b2"] * x)
    return [kappa * (1 - v) - d1 - d2, d1, d2]


def _section(kappa, y0, t_end=400.0):
    """The distinct θ₁ at the upward crossings of x = 0 after the first half of a DOP853 run."""
    def crossing(t, y, kappa):
        return y[0]
    crossing.direction = 1
    sol = solve_ivp(_block, (0.0, t_end), y0, method="DOP853", rtol=1e-11, atol=1e-12, events=crossing,
                    args=(kappa,))
    assert sol.status == 0
    th1 = sol.y_events[0][len(sol.t_events[0]) // 2:, 1]
    assert th1.size > 60
    distinct: list[float] = []
    for v in np.sort(th1):
        if not distinct or v - distinct[-1] > 1e-5:
            distinct.append(v)
    return distinct


@pytest.mark.parametrize("which, offset, count", [(0, +0.007, 1), (0, -0.008, 2), (1, +0.0034, 2), (1, -0.0017, 4)])
def test_poincare_section_on_both_sides_of_each_doubling(cascade, which, offset, count):
    br, cas = cascade
    parent = br if which == 0 else cas.branches[0]      # period 1 for the first PD, period 2 for the second
    pd = (br.points("PD")[0], cas.points[0])[which]
    kappa = pd.parameter + offset
    c = cycle_at(parent, kappa)
    y0 = c.Y[:, 0] + 1e-3 * np.array([1.0, -1.0, 0.5])  # off the parent cycle, stable or not
    values = _section(kappa, y0)
    assert len(values) == count
    if count > 1:    # the doubled orbit's section points are well apart (not a slow transient)
        assert np.min(np.diff(values)) > 1e-3
