"""Λ and C at the flutter onset against Kuznetsov's l₁ formula written in the test.

The reference (:func:`flutter_reference.kuznetsov_l1`) assembles the first-order matrix of the
2-DOF model of Hoffmann et al. (2002) by hand, takes the contact's second and third derivatives
N'', N''' by hand (the only nonlinearity of the sliding motion with Coulomb friction), evaluates
Kuznetsov's invariant c₁ (2004, eq. 3.20) with ⟨p, q⟩ = 1, and dλ/dμ by a five-point stencil.
Landau's engine uses neither: it derives the amplitude equation by the Fredholm route on the
DynamicalSystem with Taylor-arithmetic jets at 50 digits.  Tolerance 1e-8 relative: the reference
is a float64 computation (the stencil's error, ~h⁴ and eps/h with h = 1e-4 μ_c, measured below 1e-9 in dλ/dμ).
Cubic (hardening, softening) and Hertz contacts; the default hardening contact is supercritical, a
stiffer cubic term or a Hertz contact subcritical.
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


@pytest.mark.parametrize("contact,params", [("cubic", dict(kNL=5.0e9)), ("hertz", dict(kH=4.0e5))],
                         ids=["stiff-cubic", "hertz"])
def test_subcritical_onsets(contact, params):
    # a stiff cubic term, or a Hertz contact, turns the onset subcritical (Λ > 0); the reference agrees
    res = flutter_hopf(ModeCoupling.hoffmann2002(contact=contact, **params))
    Lambda, *_ = kuznetsov_l1({**HOFFMANN_DEFAULTS, **params}, res.p_c, contact)
    assert res.Lambda == pytest.approx(Lambda, rel=1e-8)
    assert Lambda > 0 and res.criticality == "subcritical"


def test_linear_contact_is_degenerate_at_every_order():
    # with a linear contact and Coulomb friction the sliding motion is a linear system: every nonlinear
    # coefficient is exactly 0, so Λ = 0 and the engine's next order l₂ = 0 too (degenerate)
    res = flutter_hopf(ModeCoupling.hoffmann2002(contact="linear"))
    assert res.Lambda == 0.0 and res.l2 == 0.0
    assert res.criticality == "degenerate"
