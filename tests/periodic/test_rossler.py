"""The Rössler system (a = b = 0.2): published cycles at c = 5.7, the period doublings, the cascade.

Published values: the period-1 and period-2 cycles of the Rössler attractor at a = b = 0.2,
c = 5.7 (their periods and leading multipliers), from the ChaosBook.org page "Roessler's model"
(http://cns.physics.gatech.edu/ChaosBook/extras/simon/Roessler.html), as printed there:
period-1 T = 5.88108845586, eigenvalues 1.000000003, −2.403953527, …;
period-2 T = 11.7586260717, eigenvalues 1.000000000, −3.512006980, ….
The page's own trivial multiplier (1.000000003) bounds its accuracy at a few 1e-9: the converged
collocation values (ntst 120, trivial multiplier 1 ± 1e-13) are T = 5.881088455554 and
μ = −2.4039535318525, 5e-11 and 2e-9 relative from the printed ones; the tolerances below are
the printed digits less the last (period) and less the last two (multiplier) for that reason.
"""

from __future__ import annotations

import numpy as np
import pytest
from cycle_systems import monodromy_by_shooting, rossler, simulated_cycle

from landau.periodic import continue_cycles, follow_cascade

PERIOD1 = (5.88108845586, -2.403953527)
PERIOD2 = (11.7586260717, -3.512006980)


@pytest.fixture(scope="module")
def period1_branch():
    pr = rossler()
    start = simulated_cycle(pr, 2.5, [1.0, 1.0, 0.0])
    return pr, continue_cycles(pr, start, steps=100, ds=0.1, ntst=60)


def _leading(mu):
    return mu[np.argmax(np.abs(mu))]


def test_period_one_cycle_at_c_5_7_matches_the_published_period_and_multiplier(period1_branch):
    _, br = period1_branch
    assert br.end.name == "PARAMETER_RANGE" and br.parameter[-1] == 5.7
    assert abs(br.period[-1] - PERIOD1[0]) < 2e-10 * PERIOD1[0]
    assert abs(_leading(br.floquet[-1]).real - PERIOD1[1]) < 1e-8
    assert abs(br.trivial[-1] - 1) < 1e-9


def test_first_period_doubling_switching_and_period_two_cycle(period1_branch):
    pr, br = period1_branch
    pds = br.points("PD")
    assert len(pds) == 1
    pd = pds[0]
    assert 2.83 < pd.parameter < 2.835 and pd.coefficient < 0          # supercritical: a stable doubled cycle
    # independent check of the location: DOP853 shooting of the located cycle has the multiplier −1
    mesh, Y = pd.cycle
    M = monodromy_by_shooting(pr, Y[:, 0], pd.period, pd.parameter)
    assert np.min(np.abs(np.linalg.eigvals(M) + 1)) < 1e-7
    # switched onto the doubled branch and continued to c = 5.7: the published period-2 cycle
    br2 = continue_cycles(pr, pd, steps=100, ds=0.1)
    assert br2.route == "period-doubling" and br2.parameter[-1] == 5.7
    assert abs(br2.period[-1] - PERIOD2[0]) < 2e-10 * PERIOD2[0]
    assert abs(_leading(br2.floquet[-1]).real - PERIOD2[1]) < 1e-8
    # the doubled branch doubles again (the second doubling of the cascade) near c = 3.84
    assert [round(s.parameter, 2) for s in br2.points("PD")] == [3.84]


@pytest.mark.slow
def test_cascade_three_doublings_and_feigenbaum_ratio():
    # converged PD values, refined by doubling the mesh: the ratio must agree to the digits quoted
    pr = rossler()
    start = simulated_cycle(pr, 2.5, [1.0, 1.0, 0.0])
    cas = {ntst: follow_cascade(pr, start, doublings=4, ds=0.1, ntst=ntst) for ntst in (40, 80)}
    p40, p80 = cas[40].parameters, cas[80].parameters
    assert p80.size == 4
    np.testing.assert_allclose(p40, p80, rtol=1e-7)
    d = cas[80].feigenbaum
    # δ_n approaches Feigenbaum's 4.669 from below along this cascade
    assert d.size == 2 and 3.0 < d[0] < d[1] < 4.9


def test_period_doubling_coefficient_against_the_doubled_cycles_amplitude():
    # Independent of normal_forms.py: on the centre manifold dξ/dt = νξ + cξ³, so the doubled cycle
    # has ξ² = −ν/c, with ν = ln(−μ)/T from the multiplier μ of the period-1 cycle at the same c,
    # and ξ = ½∫₀^{2T}⟨x₂ − x₀, v⟩dt (v anti-periodic, ∫₀ᵀ⟨v, v⟩dt = 1; the projection over the
    # doubled period removes the periodic O(ξ²) terms). −ν/ξ² → c as ξ → 0 (error O(ξ²)).
    from dataclasses import replace

    from landau.periodic.collocation import evaluate
    from landau.periodic.floquet import monodromy, propagate
    from landau.periodic.problem import CycleStart

    pr = rossler()
    start = simulated_cycle(pr, 2.5, [1.0, 1.0, 0.0])
    # one uniform mesh throughout (no adaptation): ν ≈ 0.1 (p − p_PD) is tiny here, so the PD point and
    # the period-1 cycles must come from the same discretisation
    kw = {"ntst": 40, "adapt_every": 0}
    pd = continue_cycles(pr, start, steps=100, ds=0.1, stop_at=("PD",), **kw).points("PD")[0]
    doubled = continue_cycles(pr, pd, steps=2, ds=0.005, ds_max=0.005, amplitude0=1e-3, detect=False,
                              adapt_every=0)
    mesh_pd, Y_pd = pd.cycle
    estimates = []
    for i in (1, 2):
        p = doubled.parameter[i]
        assert p > pd.parameter
        one = continue_cycles(replace(pr, parameter_range=(0.0, p)),
                              CycleStart(mesh_pd.nodes * pd.period, Y_pd, pd.period, pd.parameter),
                              steps=20, ds=0.01, detect=False, **kw)
        mesh, Y, T = one.meshes[-1], one.nodes[-1], one.period[-1]
        lam, vec = np.linalg.eig(monodromy(pr, mesh, Y, T, p))
        k = int(np.argmin(np.abs(lam + 1)))
        nu = np.log(-lam[k].real) / T
        v = np.real(propagate(pr, mesh, Y, T, p, np.real(vec[:, k])))
        s = np.linspace(0, 1, 2001)[:-1]
        v = v / np.sqrt(T * np.mean(np.sum(evaluate(mesh, v, s) ** 2, axis=0)))
        x2 = evaluate(doubled.meshes[i], doubled.nodes[i], s)

        def dist(shift, x2=x2, mesh=mesh, Y=Y, s=s):
            return np.mean(np.sum((x2 - evaluate(mesh, Y, 2 * s + shift)) ** 2, axis=0))

        from scipy.optimize import minimize_scalar

        coarse = np.linspace(0, 1, 201)[:-1]
        s0 = coarse[int(np.argmin([dist(c) for c in coarse]))]
        shift = minimize_scalar(dist, bounds=(s0 - 0.005, s0 + 0.005), method="bounded",
                                options={"xatol": 1e-10}).x
        tt = 2 * s + shift
        vv = evaluate(mesh, v, tt) * (-1.0) ** np.floor(tt)          # v(t + T) = −v(t)
        xi = 0.5 * 2 * T * np.mean(np.sum((x2 - evaluate(mesh, Y, tt)) * vv, axis=0))
        estimates.append((xi ** 2, -nu / xi ** 2))
    (a2, ca), (b2, cb) = estimates
    extrapolated = (ca * b2 - cb * a2) / (b2 - a2)                  # Richardson in ξ²
    assert abs(ca / pd.coefficient - 1) < 1e-5
    assert abs(extrapolated / pd.coefficient - 1) < 3e-6


def test_branch_point_on_the_twice_traversed_cycle_is_the_period_doubling():
    # the period-1 cycle traversed twice (period 2T) has the multipliers μ², so its period doubling
    # (μ = −1) is a branch point of the doubled representation (μ² = 1: the doubled branch crosses it)
    pr = rossler()
    st = simulated_cycle(pr, 2.5, [1.0, 1.0, 0.0])
    pd = continue_cycles(pr, st, steps=6, ds=0.1, ntst=40, stop_at=("PD",)).points("PD")[0]
    from landau.periodic import CycleStart

    twice = CycleStart(np.concatenate([st.t, st.t[1:] + st.period]), np.concatenate([st.y, st.y[:, 1:]], axis=1),
                       2 * st.period, 2.5)
    from dataclasses import replace

    br = continue_cycles(replace(pr, parameter_range=(0.0, 2.9)), twice, steps=6, ds=0.15, ntst=60)
    bps = br.points("BP")
    assert len(bps) == 1 and not br.points("PD")
    # bisection on the sign of det [F_u; τᵀ]; Newton converges only linearly near the branch point,
    # which limits the location to about 1e-5 (documented)
    assert abs(bps[0].parameter - pd.parameter) < 1e-5
    assert abs(bps[0].period - 2 * pd.period) < 1e-4
