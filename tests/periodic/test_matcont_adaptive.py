"""The period doubling of MatCont's adaptive-control example, against the value its manual prints.

MatCont manual (Dhooge, Govaerts, Kuznetsov et al., "MATCONT and CL_MATCONT: continuation
toolboxes in Matlab", the MatCont7p4 documentation, section "Adaptive control example",
http://www.math.uu.nl/people/kuznet/NBA/MatCont7p4.zip): the limit-cycle continuation from the
Hopf point α = 1 (β = 1) of ẋ = y, ẏ = z, ż = −αz − βy − x + x² prints
"Period Doubling (period = 6.364071e+000, parameter = 6.303020e-001)
Normal form coefficient = -4.267675e-002".
"""

from __future__ import annotations

import numpy as np
from cycle_systems import adaptive_control, monodromy_by_shooting

from landau.periodic import continue_cycles


def test_period_doubling_of_the_adaptive_control_cycle_matches_matcont():
    pr = adaptive_control()
    br = continue_cycles(pr, steps=120, ds=0.02, ds_max=0.1, ntst=40, stop_at=("PD",))
    assert br.route == "hopf" and br.end.name == "SPECIAL_POINT"
    pd = br.points("PD")[0]
    # the printed digits: 7 significant for the parameter and the period
    assert round(pd.parameter, 7) == 0.6303020
    assert round(pd.period, 6) == 6.364071
    # the normal-form coefficient: supercritical (negative) as MatCont's; its magnitude follows the
    # normalisation ∫₀ᵀ⟨v, v⟩dt = 1 of landau.periodic.normal_forms, not MatCont's
    assert pd.coefficient < 0
    # the multiplier −1 confirmed by DOP853 shooting of the located cycle
    mesh, Y = pd.cycle
    M = monodromy_by_shooting(pr, Y[:, 0], pd.period, pd.parameter)
    assert np.min(np.abs(np.linalg.eigvals(M) + 1)) < 1e-7
