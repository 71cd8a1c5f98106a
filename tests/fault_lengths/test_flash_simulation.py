"""A direct simulation of the spring–block with flash heating confirms the predicted criticality and
amplitude at two ε² (the contract of :func:`landau.check`: the relative amplitude error falls like ε²
and extrapolates to within 1 % at ε² → 0).

The ε² are inside the range the check can resolve at each point (the amplitude's Floquet multiplier
must differ from 1 by more than float64 resolves: at V = 0.3 m/s from ε² ≈ 0.036, measured by the
check itself, which says so when asked below it).  Measured: V = 0.3 m/s, ε² = 0.05, 0.1: +0.99 %
at 0.1, exponent 1.10, extrapolated −0.07 %; V = 0.05 m/s, ε² = 4e-3, 1.6e-2: +0.16 % at 1.6e-2,
exponent 1.01, extrapolated −0.000 %.
"""

from __future__ import annotations

import pytest

from landau import Verdict, check
from landau.laws import get_law
from landau.verify.springblock.checks import predict

P = dict(a_v=0.55, a=0.011, b=0.016, L=2e-6, V_s=1e-6, f_w=0.15, V_w=0.03, sigma=20.0, M=0.5)


def _confirm(V, eps2):
    r = check("dieterich+flash", V=V, eps2=eps2, params=P)
    pr = predict(get_law("dieterich+flash").with_defaults(**{k: P[k] for k in P if k not in ("sigma", "M")}), V,
                 {"sigma": P["sigma"], "M": P["M"]})
    assert r.prediction.p_c == pytest.approx(pr.p_c, rel=1e-12, abs=0)     # the flash law's Hopf point
    assert r.criticality == pr.criticality == "supercritical"
    assert len(r.detail["points"]) == 2
    for pt in r.detail["points"]:
        assert pt["cycle_stable"] is True and abs(pt["rel_error"]) < 0.02
    assert r.verdict is Verdict.AGREES and r.agrees
    return r


def test_flash_heating_high_rate_branch_confirmed_at_two_eps2():
    """V = 0.3 m/s = 10 V_w (Rice's V_w/V branch)."""
    _confirm(0.3, [0.05, 0.1])


@pytest.mark.slow
def test_flash_heating_onset_of_weakening_confirmed_at_two_eps2():
    """V = 0.05 m/s ~ V_w, where the weakening sets in (about 6 s)."""
    _confirm(0.05, [4e-3, 1.6e-2])
