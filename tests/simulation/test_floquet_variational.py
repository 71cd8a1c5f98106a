"""The Floquet multipliers of a shot cycle come from the variational equations, not from central
differences of the flow with a 1e-6 step: that step exceeded a small cycle (a 2-block chain's 3.4e-7 m)
and called a stable cycle unstable ("Floquet multiplier gap 0.0731" while its amplitudes agreed)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from landau.analyses.shooting import shoot


@pytest.mark.parametrize("scale", [1.0, 1e-7])
def test_multiplier_of_the_stuart_landau_cycle_against_its_closed_form(scale):
    # ż = (m + iω) z − |z|² z / s² in x, y: the cycle |z| = s√m, period 2π/(ω − 0), and its one nontrivial
    # multiplier exp(−2 m T) (the radial rate −2m); s = 1e-7 is a cycle far below the old 1e-6 step
    m, w, s = 0.05, 2.0, scale

    def rhs(t, y):
        r2 = (y[0] ** 2 + y[1] ** 2) / s**2
        return np.array([m * y[0] - w * y[1] - r2 * y[0], w * y[0] + m * y[1] - r2 * y[1]])

    def jac(t, y):
        x, v = y
        r2 = (x * x + v * v) / s**2
        return np.array([[m - r2 - 2 * x * x / s**2, -w - 2 * x * v / s**2],
                         [w - 2 * x * v / s**2, m - r2 - 2 * v * v / s**2]])

    y0 = np.array([s * math.sqrt(m) * 1.01, 0.0])
    T = 2 * math.pi / w
    z, period, _, mult = shoot(rhs, jac, y0, T * 1.001, rhs(0.0, y0), 1e-11)
    assert period == pytest.approx(T, rel=1e-9)
    assert np.hypot(*z) == pytest.approx(s * math.sqrt(m), rel=1e-8)
    assert mult.shape == (1,)
    assert mult[0].real == pytest.approx(math.exp(-2 * m * T), rel=1e-8) and abs(mult[0].imag) < 1e-12


def test_the_chain_cycle_that_was_called_unstable_is_stable():
    # the 2-block chain (slip law, masses 1.2 and 0.7 kg, coupling 3e4 N/m) of the report: supercritical,
    # its cycle at eps2 = 1e-3 stable by an independent return map (multipliers 0.99626, 0.187)
    import landau
    from landau.analyses.chain import chain_hopf
    from landau.laws import get_law
    from landau.systems.chain import SpringBlockChain

    chain = SpringBlockChain(get_law("ruina"), 2)
    given = {"V": 1e-4, "M_1": 1.2, "M_2": 0.7, "k_coupling": 3e4}
    hopf = chain_hopf(chain, given)
    res = landau.check(chain.system, eps2=1e-3, params=chain.resolve(given),
                       bracket=(0.9 * hopf.p_c, 1.1 * hopf.p_c))
    doc = res.as_dict()
    assert doc["criticality_predicted"] == "supercritical"
    assert res.cycle_stable is True and doc["verdict"] == "agrees", res.reason   # before: "disagrees", unstable
