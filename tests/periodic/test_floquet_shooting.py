"""Floquet multipliers from the collocation system against shooting with an independent integrator.

The independent route: the monodromy from the variational equations Φ′ = A(y(t))Φ, Φ(0) = I,
integrated with scipy's DOP853 (rtol 1e-12) from the collocation cycle's y(0) over its period.
"""

from __future__ import annotations

import numpy as np
from cycle_systems import monodromy_by_shooting, rossler, simulated_cycle

from landau.periodic import continue_cycles


def _match(a, b):
    a, b = np.sort_complex(np.asarray(a, dtype=complex)), np.sort_complex(np.asarray(b, dtype=complex))
    return np.max(np.abs(a - b))


def test_multipliers_of_stable_and_unstable_rossler_cycles_match_shooting():
    pr = rossler()
    start = simulated_cycle(pr, 2.5, [1.0, 1.0, 0.0])
    br = continue_cycles(pr, start, steps=4, ds=0.15, ntst=60, detect=False)
    assert br.stable[0] and not br.stable[-1]          # the period doubling at c ≈ 2.83 lies between
    for i in (0, len(br) - 1):
        _, Y = br.cycle(i)
        M = monodromy_by_shooting(pr, Y[:, 0], br.period[i], br.parameter[i])
        assert _match(br.floquet[i], np.linalg.eigvals(M)) < 1e-8
