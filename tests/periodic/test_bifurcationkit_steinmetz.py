"""The Neimark–Sacker point and the fold of cycles of BifurcationKit's Steinmetz–Larter tutorial.

BifurcationKit.jl documentation, tutorial "Steinmetz-Larter model" (version v0.3.2,
https://bifurcationkit.github.io/BifurcationKitDocs.jl/v0.3.2/tutorials/ode/steinmetz/): the cycle
branch continued in k₈ from k₈ = 0.75 (k₁ = 0.1631021, k₂ = 1250, k₃ = 0.046875, k₄ = 20,
k₅ = 1.104, k₆ = 0.001, k₋₇ = 0.1175, k₇ = 1.5) prints

    ns at k8 ≈ +0.82521357 ∈ (+0.82521357, +0.82521357), |δp|=5e-09, [converged]
    bp at k8 ≈ +0.84391360 ∈ (+0.84391360, +0.84391360), |δp|=1e-09, [converged]

and continues the curve of folds of cycles from the second point, so it is the fold (LPC).
The tutorial sets ``tol_stability = 1e-3``; BifurcationKit counts a Floquet exponent σ = log μ as
unstable when Re σ > tol_stability (``is_stable`` in src/Bifurcations.jl, the exponents from
src/periodicorbit/Floquet.jl) and bisects where that count changes. Its printed points are
therefore where Re log μ = 10⁻³, not |μ| = 1: the NS multipliers there have |μ| = e^0.001,
1.1e-5 in k₈ past the true NS point (a DOP853 shooting at rtol 1e-12 gives |μ| = 1.0010005 at
k₈ = 0.82521357 and 1 − 2e-9 at landau's NS, 0.8252022368); at the fold,
where k₈ is extremal along the branch, the offset is quadratic and only 1.2e-8.

What is asserted:
* the published digits: on landau's branch, the k₈ where Re log μ = 10⁻³ (the NS pair; the
  critical real multiplier before the fold) rounds to BifurcationKit's printed 8 decimals;
* the true points: the located NS has |μ| = 1 by DOP853 shooting of a separate monodromy (to
  1e-7: the collocation error of the located cycle, ntst = 60, is far below), and the located LPC
  lies above BifurcationKit's printed k₈ by the fold's quadratic offset (0 < offset < 5e-8).
"""

from __future__ import annotations

import numpy as np
import pytest
from cycle_systems import monodromy_by_shooting, simulated_cycle_lsoda, steinmetz_larter
from scipy.optimize import brentq

from landau.errors import InputError
from landau.periodic import continue_cycles, cycle_at

BK_NS = 0.82521357          # BifurcationKit tutorial, "ns at k8 ≈ +0.82521357"
BK_FOLD = 0.84391360        # BifurcationKit tutorial, "bp at k8 ≈ +0.84391360"
BK_TOL_STABILITY = 1e-3     # the tutorial's ContinuationPar(tol_stability = 1e-3)


@pytest.fixture(scope="module")
def branch():
    pr = steinmetz_larter()
    # the starting state of Kuznetsov's MatCont tutorial on this model (BifurcationKit starts from a random one),
    # integrated onto the attracting cycle
    start = simulated_cycle_lsoda(pr, 0.75, [31.78997, 1.45468, 0.01524586, 0.1776113], t_end=600.0)
    return pr, continue_cycles(pr, start, steps=200, ds=0.01, ds_max=0.05, ntst=60)


def _exponent_root(br, near, lo, hi, pick):
    """k₈ in (lo, hi) where Re log μ of the multiplier ``pick`` picks equals tol_stability, on the
    cycles corrected at fixed k₈ from branch point ``near`` (landau.periodic.cycle_at)."""
    def g(p):
        mu = cycle_at(br, p, near=near).multipliers.nontrivial
        return np.log(np.abs(pick(mu))) - BK_TOL_STABILITY
    return brentq(g, lo, hi, xtol=1e-13)


def test_the_branch_has_one_ns_and_one_fold_where_bifurcationkit_finds_them(branch):
    _, br = branch
    assert [s.kind for s in br.special] == ["NS", "LPC"]
    ns, lpc = br.special
    assert abs(ns.parameter - BK_NS) < 2e-5 and abs(lpc.parameter - BK_FOLD) < 1e-7


def test_bifurcationkits_printed_ns_is_where_the_floquet_exponent_reaches_its_tol_stability(branch):
    _, br = branch
    ns = br.points("NS")[0]
    p = _exponent_root(br, ns.index + 1, ns.parameter, ns.parameter + 5e-5, lambda mu: mu[0])
    assert round(p, 8) == BK_NS


def test_bifurcationkits_printed_fold_is_where_the_critical_exponent_reaches_its_tol_stability(branch):
    _, br = branch
    lpc = br.points("LPC")[0]

    def critical(mu):        # the real multiplier that passes through 1 at the fold
        return mu[np.argmin(np.abs(np.abs(mu) - 1.0))]
    # bracket: 1e-7 below the fold the critical exponent is ≈ 3e-3, 1e-9 below it ≈ 3e-4
    p = _exponent_root(br, lpc.index, lpc.parameter - 1e-7, lpc.parameter - 1e-9, critical)
    assert round(p, 8) == BK_FOLD
    # the located fold itself: above the printed value by the quadratic offset of the threshold
    assert 0 < lpc.parameter - BK_FOLD < 5e-8


def test_the_located_ns_is_on_the_unit_circle_by_independent_shooting(branch):
    pr, br = branch
    ns = br.points("NS")[0]
    mesh, Y = ns.cycle
    mu = np.linalg.eigvals(monodromy_by_shooting(pr, Y[:, 0], ns.period, ns.parameter))
    pair = mu[np.abs(mu.imag) > 1e-3]
    assert pair.size == 2 and np.max(np.abs(np.abs(pair) - 1.0)) < 1e-7


def test_cycle_at_names_a_bad_parameter_or_branch_point(branch):
    _, br = branch
    with pytest.raises(InputError, match="p must be finite"):
        cycle_at(br, float("nan"))
    with pytest.raises(InputError, match="near = 10000"):
        cycle_at(br, 0.8, near=10_000)
