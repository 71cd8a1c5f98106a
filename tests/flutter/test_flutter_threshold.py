"""The flutter threshold of the 2-DOF model of Hoffmann et al. (2002): closed form, bisection, named result.

* Undamped: μ_c and ω_c against the closed form (the discriminant of the 2×2 eigenproblem,
  derived in :mod:`landau.analyses.flutter`) at parameter sets away from the defaults, to 1e-10
  relative (both sides are float64 evaluations of well-conditioned expressions: measured ~1e-15).
* Damped: the Hopf point of the engine against a plain bisection of max Re λ of the matrices
  assembled by hand in the test (:mod:`flutter_reference`), to 1e-9 relative (the bisection is run to
  1e-14; the eigenvalues at a simple crossing are well conditioned).
* At c = 0 the result is the named mode-coupling result, never NoHopfError.
* The destabilisation paradox (Hoffmann & Gaul 2003): with non-proportional damping the threshold
  as the damping vanishes lies below the undamped one; with proportional damping (C ∝ M) it is the
  undamped one.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from flutter_reference import damped_threshold

from landau.analyses.flutter import (
    ModeCouplingResult,
    destabilisation_paradox,
    flutter_hopf,
    flutter_threshold,
    hoffmann_threshold,
)
from landau.systems.mode_coupling import HOFFMANN_DEFAULTS, ModeCoupling

#: parameter sets away from the defaults (undamped, linear contact)
UNDAMPED = [
    dict(m=0.7, k1=1.3e4, k2=1.0e4, alpha1=25.0, alpha2=140.0, kH=3.0e4),
    dict(m=2.5, k1=5.0e3, k2=8.0e3, alpha1=40.0, alpha2=160.0, kH=1.2e4, P=20.0),
    dict(m=0.2, k1=2.0e5, k2=1.5e5, alpha1=15.0, alpha2=120.0, kH=4.0e5, P=300.0),
]


@pytest.mark.parametrize("params", UNDAMPED, ids=["a", "b", "c"])
def test_undamped_threshold_is_the_closed_form(params):
    mc = ModeCoupling.hoffmann2002(contact="linear", c1=0.0, c2=0.0, **params)
    full = {**HOFFMANN_DEFAULTS, **params}
    mu_c, omega_c = hoffmann_threshold(full["m"], full["k1"], full["k2"], full["alpha1"], full["alpha2"], full["kH"])
    assert 0 < mu_c < 2
    th = flutter_threshold(mc, "mu", (0.0, 2.0))
    assert th.kind == "mode-coupling"
    assert th.p_c == pytest.approx(mu_c, rel=1e-10)
    assert th.omega_c == pytest.approx(omega_c, rel=1e-10)


def test_undamped_result_is_named_mode_coupling_not_no_hopf():
    params = UNDAMPED[0]
    mc = ModeCoupling.hoffmann2002(contact="linear", c1=0.0, c2=0.0, **params)
    res = flutter_hopf(mc)
    assert isinstance(res, ModeCouplingResult)
    full = {**HOFFMANN_DEFAULTS, **params}
    mu_c, omega_c = hoffmann_threshold(full["m"], full["k1"], full["k2"], full["alpha1"], full["alpha2"], full["kH"])
    doc = res.as_dict()
    assert doc["kind"] == "mode-coupling" and doc["Lambda"] is None
    assert doc["p_c"] == pytest.approx(mu_c, rel=1e-10)
    assert doc["omega_c"] == pytest.approx(omega_c, rel=1e-10)
    # the two merging modes: the two undamped modes at mu = 0, frequencies of K0 = K + kH e_y e_yᵀ
    k11, k12, k22 = mc.K[0, 0], mc.K[0, 1], mc.K[1, 1]
    w2 = np.sort(np.linalg.eigvalsh(np.array([[k11, k12], [k12, k22 + full["kH"]]]))) / full["m"]
    assert [m["index"] for m in doc["modes"]] == [1, 2]
    assert [m["omega"] for m in doc["modes"]] == pytest.approx(np.sqrt(w2), rel=1e-12)
    # the merged shape is the null vector of K_eff − ω_c² M: its y/x ratio solves the first row
    ratio = doc["shape_re"][1]
    assert (k11 - omega_c**2 * full["m"]) + (k12 - mu_c * full["kH"]) * ratio == pytest.approx(0, abs=1e-6 * k11)


DAMPED = [
    ("cubic", dict(c1=2.0, c2=0.5)),
    ("cubic", dict(c1=0.3, c2=3.0, kNL=-2.0e8, alpha1=35.0)),
    ("hertz", dict(c1=1.0, c2=1.5, kH=4.0e5)),
    ("linear", dict(c1=5.0, c2=0.1, m=0.5, k2=1.4e4)),
]


@pytest.mark.parametrize("contact,params", DAMPED, ids=["cubic", "softening", "hertz", "linear"])
def test_damped_threshold_against_bisection(contact, params):
    mc = ModeCoupling.hoffmann2002(contact=contact, **params)
    full = {**HOFFMANN_DEFAULTS, **params}
    ref = damped_threshold(full, contact)
    res = flutter_hopf(mc)
    assert res.extra["kind"] == "hopf"
    assert res.p_c == pytest.approx(ref, rel=1e-9)
    th = flutter_threshold(mc)
    assert th.p_c == pytest.approx(ref, rel=1e-9)
    assert th.omega_c == pytest.approx(res.omega_c, rel=1e-9)


def test_destabilisation_paradox():
    # non-proportional damping (c1 != c2 with M = m I): mu_c(c -> 0) < mu_c(c = 0)
    mc = ModeCoupling.hoffmann2002(contact="linear", c1=2.0, c2=0.2)
    out = destabilisation_paradox(mc, scales=[1.0, 1e-2, 1e-3])
    full = HOFFMANN_DEFAULTS
    mu0, _ = hoffmann_threshold(full["m"], full["k1"], full["k2"], full["alpha1"], full["alpha2"], full["kH"])
    assert out.p_c_undamped == pytest.approx(mu0, rel=1e-10)
    assert out.limit < 0.95 * mu0
    # the limit is reached (the last two scales agree) and is not the undamped value
    assert out.p_c[-1] == pytest.approx(out.p_c[-2], rel=1e-4)
    # proportional damping C = c M: the limit is the undamped threshold
    prop = destabilisation_paradox(ModeCoupling.hoffmann2002(contact="linear", c1=1.0, c2=1.0), scales=[1e-3])
    assert prop.limit == pytest.approx(mu0, rel=1e-5)
    assert not math.isclose(out.limit, prop.limit, rel_tol=1e-2)


@pytest.mark.parametrize("params", UNDAMPED[:2], ids=["a", "b"])
def test_damping_ratio_sweep_against_the_routh_hurwitz_limit(params):
    # μ_c(ε → 0) against the damping ratio c2/c1, against the closed form of the Routh–Hurwitz condition
    # at leading order in ε (derived in hoffmann_vanishing_damping_threshold).  The numerical threshold at
    # ε = 1e-4 differs from the limit by O(ε²) and by the eigenvalues' conditioning near the collision
    # (~eps/ε): measured below 1e-9 relative; tolerance 1e-8.
    from landau.analyses.flutter import hoffmann_vanishing_damping_threshold, vanishing_damping_thresholds

    mc = ModeCoupling.hoffmann2002(contact="linear", c1=1.0, c2=1.0, **params)
    full = {**HOFFMANN_DEFAULTS, **params}
    ratios = [0.05, 0.3, 1.0, 4.0]
    got = vanishing_damping_thresholds(mc, ratios, scale=1e-4)
    ref = [hoffmann_vanishing_damping_threshold(full["k1"], full["k2"], full["alpha1"], full["alpha2"], full["kH"],
                                                1.0, r) for r in ratios]
    assert got == pytest.approx(ref, rel=1e-8)
    mu0, _ = hoffmann_threshold(full["m"], full["k1"], full["k2"], full["alpha1"], full["alpha2"], full["kH"])
    assert ref[2] == pytest.approx(mu0, rel=1e-14)          # proportional: the undamped threshold
    assert all(r < mu0 * (1 - 1e-3) for i, r in enumerate(ref) if i != 2)
