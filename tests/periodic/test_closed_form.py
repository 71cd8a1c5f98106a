"""Cycles with closed forms: the Stuart–Landau cycle and the Bautin fold of cycles (LPC)."""

from __future__ import annotations

import numpy as np
from cycle_systems import stuart_landau

from landau.periodic import CycleProblem, HopfStart, continue_cycles
from landau.systems.system import DynamicalSystem


def test_stuart_landau_radius_period_and_multiplier():
    # ẋ = μx − ωy − x r², ẏ = ωx + μy − y r²: r = √μ, T = 2π/ω, nontrivial multiplier exp(−2μT)
    # (the radial linearisation −2μ over one period); started from the Hopf point μ = 0
    omega = 1.3
    br = continue_cycles(stuart_landau(omega), steps=25, ds=0.05, ntst=30)
    assert len(br) == 26 and br.end.name == "STEPS"
    mu, T = np.array(br.parameter), np.array(br.period)
    assert mu.max() > 2.0
    for i in range(len(br)):
        _, Y = br.cycle(i)
        err = np.abs(np.hypot(Y[0], Y[1]) - np.sqrt(mu[i])) / max(1.0, np.sqrt(mu[i]))
        # Gauss collocation: O(h^{2m}) at the mesh points (every m-th node), O(h^{m+1}) between
        assert err[::4].max() < 1e-10 and err.max() < 5e-9
    np.testing.assert_allclose(T, 2 * np.pi / omega, rtol=1e-10)
    np.testing.assert_allclose(br.amplitude, np.sqrt(mu), rtol=1e-8)
    mults = br.floquet
    nontrivial = mults[np.arange(len(br)), np.argmax(np.abs(mults - 1), axis=1)]
    np.testing.assert_allclose(nontrivial.real, np.exp(-2 * mu * T), rtol=1e-8, atol=1e-12)
    assert np.all(np.abs(np.array(br.trivial) - 1) < 1e-10)
    assert br.stable.all() and not br.special


def bautin(beta: float = 1.0) -> CycleProblem:
    """ṙ = r(μ + 2r² − r⁴), θ̇ = 1 + βr², written in x, y from strings (exact multilinear forms)."""
    r2 = "(x^2 + y^2)"
    g, w = f"(mu + 2*{r2} - {r2}^2)", f"(1 + b*{r2})"
    system = DynamicalSystem.from_strings({"x": f"x*{g} - {w}*y", "y": f"y*{g} + {w}*x"}, "mu", {"b": beta},
                                          equilibrium={"x": "0", "y": "0"}, name="bautin")
    # subcritical Hopf at μ = 0: r² ≈ −μ/2 for μ < 0, so the half peak-to-peak of x is √2·√|μ| on side −1
    hopf = HopfStart(0.0, np.zeros(2), 1.0, np.array([1.0, -1j]), amplitude=np.sqrt(2.0), side=-1)
    return CycleProblem.from_system(system, hopf=hopf)


def test_bautin_fold_of_cycles_and_its_coefficient():
    # cycles where μ = r⁴ − 2r²: the fold is at r = 1, μ = −1 (closed form), period 2π/(1 + β).
    # Its normal-form coefficient b (dξ/dt = bξ², dτ/dt = 1 − ξ): along the centre manifold
    # r − 1 = ρξ with ρ = −(1 + β)/(2β) (from dτ/dt = θ̇/(1 + β)), and ṙ = −r(r² − 1)² ≈ −4(r − 1)²,
    # so b = −4ρ = 2(1 + β)/β — 4 for β = 1.
    beta = 1.0
    br = continue_cycles(bautin(beta), steps=30, ds=0.05, ntst=20)
    folds = br.points("LPC")
    assert len(folds) == 1
    lpc = folds[0]
    assert abs(lpc.parameter + 1.0) < 1e-10
    assert abs(lpc.period - 2 * np.pi / (1 + beta)) < 1e-9
    assert abs(lpc.coefficient - 2 * (1 + beta) / beta) < 1e-9      # exact B: the system's multilinear forms
    # the inner branch (r < 1) is unstable, the outer one stable
    k = lpc.index
    assert not br.stable[k - 1] and br.stable[k + 2]
