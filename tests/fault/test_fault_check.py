"""A direct simulation of each new spring–block system confirms the predicted criticality and amplitude
at two ε² (the check's contract, :func:`landau.check`: the amplitude error falls like ε² and extrapolates
to within 1 % at ε² → 0).

The default suite checks the block with thermal pressurisation, which carries both new states (the pore
pressure of the dilatancy term, built in with it, and the slip-zone temperature); the dilatant block alone
is the ``slow`` sibling.  Both parameter sets are supercritical at V = 1e-6 m/s, where the plain block
(σ = 20) is subcritical (Λ > 0): the amplitude is a stable cycle the simulation converges to.
"""

from __future__ import annotations

import pytest

import landau
from landau.laws import get_law

LAW = get_law("dieterich")
V = 1e-6
PORE = dict(sigma=20.0, p_inf=5.0, eps_dil=3e-4, beta=1e-3, t_drain=1.0)
THERMAL = dict(sigma=20.0, p_inf=5.0, eps_dil=1e-4, beta=1e-3, t_drain=0.5, lambda_tp=1e5, rho_c=30.0,
               w_sz=1e-3, t_th=0.2)


def _confirm(params):
    r = landau.check(LAW, V, 1e-3, params).as_dict()
    assert r["criticality_predicted"] == "supercritical"
    assert r["verdict"] == "agrees", r
    assert r["eps2_measured"] == [1e-3, 2.5e-4]
    # the amplitude at ε² = 1e-3 within 1 % of the prediction (the contract's extrapolation bound)
    assert abs(r["rel_error"]) < 1e-2
    assert r["cycle_stable"]
    return r


def test_thermal_pressurisation_confirmed_by_simulation():
    r = _confirm(THERMAL)
    assert len(r["detail"]["floquet_multipliers"]) == 4          # X, u, θ, p, T: the nontrivial multipliers


@pytest.mark.slow
def test_dilatancy_confirmed_by_simulation():
    r = _confirm(PORE)
    assert len(r["detail"]["floquet_multipliers"]) == 3          # X, u, θ, p


def test_the_plain_block_is_subcritical_here():
    """The new terms change the criticality: the tests above measure a cycle the plain block does not have."""
    from landau.verify.springblock.checks import predict

    assert predict(LAW, V, {"sigma": 20.0}).criticality == "subcritical"
