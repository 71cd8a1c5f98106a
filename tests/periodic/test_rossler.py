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
