"""The period-doubling cascade of the Lorenz system in its window near r = 100, against published values.

Boyce, W. E. & DiPrima, R. C., *Elementary Differential Equations and Boundary Value Problems*,
7th ed. (Wiley, 2001), Sect. 9.8 (the Lorenz equations, σ = 10, b = 8/3), Problem 9: "One
period-doubling window contains the value r = 100 … When r ≅ 99.98, you may be able to observe that
the period of the solution doubles … As r decreases further, the period of the solution doubles
repeatedly. The next period doubling occurs at about r = 99.629." (read as reproduced at
https://vaia.com/en-us/textbooks/math/elementary-differential-equations-and-boundary-value-problem-7-edition/chapter-9/problem-9-for-certain-r-intervals-or-windows-the-lorenz-equa).

The branch starts from the attracting cycle simulated at r = 100.5 (three upward crossings of
z = r − 1 per period; one of the two mirror-image cycles) and is continued down in r; each period
doubling is located, the doubled branch switched onto and continued to its own doubling
(:func:`landau.periodic.follow_cascade`). Measured (ntst 80): r = 99.9796511, 99.6285454,
99.5471072, 99.5293475, Feigenbaum ratios δ = 4.3113, 4.5855 on the way to 4.669202 (Feigenbaum 1978).
"""

from __future__ import annotations

import numpy as np
import pytest
from cycle_systems import lorenz, monodromy_by_shooting, simulated_cycle_by_section

from landau.periodic import follow_cascade

BOYCE_DIPRIMA_PD = (99.98, 99.629)      # Sect. 9.8, Problem 9(b) "r ≅ 99.98", 9(c) "about r = 99.629"


def _start(pr):
    return simulated_cycle_by_section(pr, 100.5, [1.0, 1.0, 20.0], 200.0, lambda y: y[2] - (100.5 - 1.0))


def test_the_first_two_period_doublings_match_the_printed_digits():
    pr = lorenz()
    cascade = follow_cascade(pr, _start(pr), doublings=2, ds=0.01, ds_max=0.1, ntst=80, direction=-1)
    p1, p2 = cascade.parameters
    assert round(p1, 2) == BOYCE_DIPRIMA_PD[0] and round(p2, 3) == BOYCE_DIPRIMA_PD[1]
    # each doubling of period: the second doubled branch's cycle at its PD has about twice the period
    t1, t2 = (s.period for s in cascade.points)
    assert 1.95 < t2 / t1 < 2.05
    # the multiplier −1 of each located cycle, by DOP853 shooting of the variational equations
    for pd in cascade.points:
        mesh, Y = pd.cycle
        M = monodromy_by_shooting(pr, Y[:, 0], pd.period, pd.parameter)
        assert np.min(np.abs(np.linalg.eigvals(M) + 1)) < 1e-6


@pytest.mark.slow
def test_four_doublings_and_the_feigenbaum_ratio():
    pr = lorenz()
    cascade = follow_cascade(pr, _start(pr), doublings=4, ds=0.01, ds_max=0.1, ntst=80, direction=-1)
    assert cascade.parameters.size == 4
    d = cascade.feigenbaum
    # δ_n rising toward 4.669202 (measured 4.3113, 4.5855)
    assert d.size == 2 and 4.0 < d[0] < d[1] < 4.6692 and abs(d[1] - 4.669202) < 0.15
