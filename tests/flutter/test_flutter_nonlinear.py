"""Λ and C at the flutter onset against Kuznetsov's l₁ formula written in the test.

The reference (:func:`flutter_reference.kuznetsov_l1`) assembles the first-order matrix of the
2-DOF model of Hoffmann et al. (2002) by hand, takes the contact's second and third derivatives
N'', N''' by hand (the only nonlinearity of the sliding motion with Coulomb friction), evaluates
Kuznetsov's invariant c₁ (2004, eq. 3.20) with ⟨p, q⟩ = 1, and dλ/dμ by a five-point stencil.
Landau's engine uses neither: it derives the amplitude equation by the Fredholm route on the
DynamicalSystem with Taylor-arithmetic jets at 50 digits.  Tolerance 1e-8 relative: the reference
is a float64 computation (the stencil's error, ~h⁴ and eps/h with h = 1e-4 μ_c, measured below 1e-9 in dλ/dμ).
Hardening and softening cubic contacts give the two signs of Λ; a Hertz contact the third law.
"""

from __future__ import annotations

import pytest
from flutter_reference import kuznetsov_l1

from landau.analyses.flutter import flutter_hopf
from landau.systems.mode_coupling import HOFFMANN_DEFAULTS, ModeCoupling

CASES = [
    ("cubic", dict(c1=2.0, c2=0.5), "supercritical"),
    ("cubic", dict(c1=0.3, c2=3.0, kNL=-2.0e8, alpha1=35.0), None),
    ("hertz", dict(c1=1.0, c2=1.5, kH=4.0e5), None),
]


@pytest.mark.parametrize("contact,params,expected", CASES, ids=["hardening", "softening", "hertz"])
def test_lambda_and_amplitudes_against_kuznetsov(contact, params, expected):
    mc = ModeCoupling.hoffmann2002(contact=contact, **params)
    res = flutter_hopf(mc)
    Lambda, C, ratio_y, l1 = kuznetsov_l1({**HOFFMANN_DEFAULTS, **params}, res.p_c, contact)
    assert res.Lambda == pytest.approx(Lambda, rel=1e-8)
    assert res.C == pytest.approx(C, rel=1e-8)
    assert res.extra["C_x"] == pytest.approx(C, rel=1e-8)
    assert res.extra["C_y"] == pytest.approx(C * ratio_y, rel=1e-8)
    assert res.l1 == pytest.approx(l1, rel=1e-8)
    if expected:
        assert res.criticality == expected


def test_softening_contact_can_be_subcritical():
    # a strongly softening contact turns the onset subcritical (Λ > 0), and the reference agrees on the sign
    params = dict(c1=2.0, c2=0.5, kNL=-1.0e9)
    res = flutter_hopf(ModeCoupling.hoffmann2002(contact="cubic", **params))
    Lambda, *_ = kuznetsov_l1({**HOFFMANN_DEFAULTS, **params}, res.p_c, "cubic")
    assert res.Lambda == pytest.approx(Lambda, rel=1e-8)
    assert (res.Lambda > 0) == (res.criticality == "subcritical")
