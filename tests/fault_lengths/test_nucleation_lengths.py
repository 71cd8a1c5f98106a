"""``landau nucleation`` and ``landau hopf spring-block --patch``: the continuum fault's length scales.

Each length against its formula computed here: the SEAS BP1 parameters (Erickson et al. 2020:
ρ = 2670 kg/m³, c_s = 3.464 km/s, σ = 50 MPa, a = 0.010, b = 0.015, L = 8 mm, V = V_p = 1e-9 m/s,
antiplane) give G = ρ c_s², k_c = σ(b − a)/L (Ruina 1983), h* = π G L/((b − a)σ) (Rice & Ruina 1983,
k = π μ′/λ), L_b = G L/(bσ) and L_∞ = (b/(b − a))² L_b/π (Rubin & Ampuero 2005); the circular
patch's stiffness against Kanamori & Anderson's 7πG/(16 r) at ν = 1/4.
"""

from __future__ import annotations

import contextlib
import io
import json
import math

import numpy as np
import pytest

from landau.analyses.nucleation import local_a_b, nucleation, patch_stiffness
from landau.cli.app import main
from landau.errors import InputError
from landau.laws import get_law

RHO, CS, SIGMA = 2670.0, 3464.0, 50e6
BP1 = dict(a=0.010, b=0.015, L=0.008, a_v=0.6, V_s=1e-6)
G = RHO * CS ** 2


def _cli(argv, rc=0):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main([*argv, "--json"]) == rc
    return json.loads(out.getvalue())


def _params(p):
    return [x for k, v in p.items() for x in ("--param", f"{k}={v!r}")]


BP1_ARGS = ["nucleation", "dieterich", "--V", "1e-9", "--sigma", "50e6", "--density", "2670", "--shear-speed", "3464",
            *_params(BP1)]


def test_bp1_lengths_from_the_command_line():
    doc = _cli(BP1_ARGS)
    a, b, L = BP1["a"], BP1["b"], BP1["L"]
    assert doc["shear_modulus"] == pytest.approx(G, rel=1e-15, abs=0)
    assert doc["k_c"] == pytest.approx(SIGMA * (b - a) / L, rel=1e-12, abs=0)
    assert doc["h_star"] == pytest.approx(math.pi * G * L / ((b - a) * SIGMA), rel=1e-12, abs=0)
    L_b = G * L / (b * SIGMA)
    assert doc["L_b"] == pytest.approx(L_b, rel=1e-12, abs=0)
    assert doc["L_inf"] == pytest.approx((b / (b - a)) ** 2 * L_b / math.pi, rel=1e-12, abs=0)
    # the numbers: L_b = 341.74 m, h* = 3220.8 m, L_inf = 979.0 m (a/b = 2/3, above 0.3781)
    assert (round(doc["L_b"], 2), round(doc["h_star"], 1), round(doc["L_inf"], 1)) == (341.74, 3220.8, 979.0)
    assert doc["L_nu"] is None and "0.3781 < a/b" in doc["regime"]
    assert doc["a_over_b"] == pytest.approx(2 / 3, rel=1e-12, abs=0)
    for name in ("h_star", "L_b", "L_inf", "k_patch"):
        assert doc["formulas"][name]["source"] and doc["formulas"][name]["validity"]


def test_localised_regime_and_in_plane():
    """a/b = 0.3 ≤ 0.3781: L_ν = 1.3774 L_b and no L_∞; in-plane: μ′ = G/(1 − ν) in h* and L_b."""
    p = dict(BP1, a=0.0045)
    nu = 0.3
    r = nucleation("dieterich", 1e-9, SIGMA, shear_modulus=G, poisson=nu, geometry="inplane", params=p)
    mu_p = G / (1 - nu)
    L_b = mu_p * p["L"] / (p["b"] * SIGMA)
    assert r.L_b == pytest.approx(L_b, rel=1e-12, abs=0)
    assert r.L_nu == pytest.approx(1.3774 * L_b, rel=1e-12, abs=0) and r.L_inf is None
    assert r.h_star == pytest.approx(math.pi * mu_p * p["L"] / ((p["b"] - p["a"]) * SIGMA), rel=1e-12, abs=0)


def test_ruina_law_has_the_same_quasi_static_kc():
    """The slip law's quasi-static k_c is σ(b − a)/L too (Ruina 1983): the same h*."""
    r = nucleation("ruina", 1e-9, SIGMA, shear_modulus=G, params=BP1)
    assert r.h_star == pytest.approx(math.pi * G * BP1["L"] / ((BP1["b"] - BP1["a"]) * SIGMA), rel=1e-10, abs=0)


def test_circular_patch():
    """The circular patch of diameter h = 2r: k = 3π(2 − ν)G/(16(1 − ν) r), 7πG/(16 r) at ν = 1/4
    (Kanamori & Anderson 1975), and h* its diameter at k = k_c."""
    r_ = 700.0
    assert patch_stiffness(2 * r_, G, 0.25, "circular") == pytest.approx(7 * math.pi * G / (16 * r_), rel=1e-14,
                                                                         abs=0)
    res = nucleation("dieterich", 1e-9, SIGMA, shear_modulus=G, poisson=0.25, geometry="circular", params=BP1)
    kc = SIGMA * (BP1["b"] - BP1["a"]) / BP1["L"]
    assert res.h_star == pytest.approx(2 * 7 * math.pi * G / (16 * kc), rel=1e-12, abs=0)
    assert res.L_b is None and res.notes


def test_flash_law_local_a_b_and_h_star():
    """dieterich+flash at V = 0.1 m/s (above V_w = 0.03): a unchanged; b = a − dμ_ss/d ln V of eq. (1),
    differentiated here by hand; h* = π G/k_c with the quasi-static k_c = σ(μ_φ/V − a/L), μ_φ = b/φ − W′."""
    p = dict(BP1, f_w=0.2, V_w=0.03)
    V = 0.1
    a, b, L, fw, Vw = p["a"], p["b"], p["L"], p["f_w"], p["V_w"]
    mu_lv = p["a_v"] + (a - b) * math.log(V / p["V_s"])
    slope = (a - b) * Vw / (V + Vw) - (mu_lv - fw) * V * Vw / (V + Vw) ** 2
    law = get_law("dieterich+flash")
    full = {**law.defaults(), **p}
    a_loc, b_loc = local_a_b(law, V, full)
    assert a_loc == pytest.approx(a, rel=1e-12, abs=0)
    assert b_loc == pytest.approx(a - slope, rel=1e-10, abs=0)
    phi = L / V
    s, ds = L / (L + Vw * phi), -L * Vw / (L + Vw * phi) ** 2
    dW = -(a - b) / phi * s + (mu_lv - fw) * ds
    kc = SIGMA * ((b / phi - dW) / V - a / L)
    r = nucleation(law, V, SIGMA, shear_modulus=G, params=p)
    assert r.k_c == pytest.approx(kc, rel=1e-10, abs=0)
    assert r.h_star == pytest.approx(math.pi * G / kc, rel=1e-10, abs=0)
    assert r.L_b == pytest.approx(G * L / (b_loc * SIGMA), rel=1e-12, abs=0)
    # at the plate rate flash heating is negligible: it raises k_c, so lowers h*, by a relative
    # ~(f_LV - f_w)(V/V_w)/(b - a) = 4e-6 below the BP1 h*
    V0 = 1e-9
    r0 = nucleation(law, V0, SIGMA, shear_modulus=G, params=p)
    bound = 2 * (p["a_v"] - fw) * (V0 / Vw) / (b - a)
    assert 0 < 1 - r0.h_star / (math.pi * G * L / ((b - a) * SIGMA)) < bound


@pytest.mark.parametrize("extra,words", [
    ([], None),
    (["--shear-modulus", "3e10"], "not both"),
    (["--sigma", "-5"], "sigma"),
    (["--geometry", "inplane"], "needs Poisson's ratio"),
    (["--geometry", "inplane", "--poisson", "0.6"], "(-1, 0.5)"),
    (["--geometry", "sphere"], "unknown geometry 'sphere'"),
    (["--patch", "-3"], "patch size"),
    (["--param", "sigma=5"], "not a law parameter"),
])
def test_bad_input_is_exit_2_with_one_line(extra, words):
    if words is None:        # the BP1 call itself succeeds (the cases below change one thing each)
        _cli(BP1_ARGS)
        return
    argv = list(BP1_ARGS)
    if extra[0] == "--sigma":
        argv[argv.index("--sigma") + 1] = extra[1]
        extra = []
    err = _cli([*argv, *extra], rc=2)["error"]
    assert words in err and "\n" not in err


@pytest.mark.parametrize("argv,words", [
    (["nucleation", "dieterich", "--sigma", "5e7", "--shear-modulus", "3e10"], "--V"),
    (["nucleation", "dieterich", "--V", "1e-9", "--shear-modulus", "3e10"], "--sigma"),
    (["nucleation", "dieterich", "--V", "1e-9", "--sigma", "5e7"], "--shear-modulus"),
    (["nucleation", "dieterich+foo", "--V", "1e-9", "--sigma", "5e7", "--shear-modulus", "3e10"], "modifier"),
])
def test_missing_inputs_are_named(argv, words):
    err = _cli(argv, rc=2)["error"]
    assert words in err and "\n" not in err


def test_python_errors_are_named():
    with pytest.raises(InputError, match="shear modulus"):
        nucleation("dieterich", 1e-9, SIGMA)
    with pytest.raises(InputError, match="rate-and-state"):
        nucleation(3.0, 1e-9, SIGMA, shear_modulus=G)


# ---------------------------------------------------------------------------------------------
# the patch as a spring-block
# ---------------------------------------------------------------------------------------------
#: the quasi-dynamic patch: M = 0 with radiation damping eta = G/(2 c_s) (Rice 1993; the quasi-static ageing
#: law's Hopf point is degenerate, Lambda = 0); its k_c = (sigma (b - a) - eta V)/L
ETA = G / (2 * CS)
HOPF = ["hopf", "spring-block", "dieterich", "--V", "1e-9",
        *_params({**BP1, "sigma": SIGMA, "M": 0.0, "eta": ETA}), "--shear-modulus", repr(G)]


def test_patch_stiffness_and_the_hopf_analysis_of_a_patch():
    """k_patch = π G/h (antiplane); the quasi-dynamic patch of size h_c = π G/k_c is at onset (ε² = 0), of
    size 2h_c unstable with ε² = 1/2 and the predicted amplitude C sqrt(k_c − k_patch), of size h_c/2 stable."""
    doc = _cli([*BP1_ARGS, "--patch", "2000"])
    assert doc["k_patch"] == pytest.approx(math.pi * G / 2000, rel=1e-14, abs=0)
    assert doc["patch_steady_sliding"] == "stable"
    kc = (SIGMA * (BP1["b"] - BP1["a"]) - ETA * 1e-9) / BP1["L"]
    h_star = math.pi * G / kc
    at = _cli([*HOPF, "--patch", repr(h_star)])
    assert at["p_c"] == pytest.approx(kc, rel=1e-9, abs=0)
    assert at["patch_critical_size"] == pytest.approx(h_star, rel=1e-9, abs=0)
    assert abs(at["patch_eps2"]) < 1e-9
    big = _cli([*HOPF, "--patch", repr(2 * h_star)])
    assert big["patch_eps2"] == pytest.approx(0.5, rel=1e-9, abs=0) and big["patch_steady_sliding"] == "unstable"
    assert big["criticality"] == "supercritical"
    assert big["patch_amplitude"] == pytest.approx(big["C"] * math.sqrt(kc - math.pi * G / (2 * h_star)),
                                                   rel=1e-9, abs=0)
    small = _cli([*HOPF, "--patch", repr(h_star / 2)])
    assert small["patch_steady_sliding"] == "stable" and small["patch_amplitude"] is None
    circ = _cli([*HOPF, "--patch", "1000", "--geometry", "circular", "--poisson", "0.25"])
    assert circ["k_patch"] == pytest.approx(7 * math.pi * G / (16 * 500), rel=1e-14, abs=0)
    assert np.isfinite(circ["Lambda"])


@pytest.mark.parametrize("argv,words", [
    (["hopf", "spring-block", "dieterich", "--shear-modulus", "3e10"], "give its size with --patch"),
    (["hopf", "spring-block", "dieterich", "--patch", "100", "--shear-modulus", "3e10"], "--param sigma"),
    (["hopf", "spring-block", "dieterich", "--patch", "100", "--param", "sigma=5e7"], "shear modulus"),
    (["hopf", "spring-block", "dieterich", "--patch", "x", "--param", "sigma=5e7"], "--patch"),
    (["hopf", "impact-oscillator", "--patch", "100"], "belongs to another model"),
])
def test_patch_errors_are_exit_2(argv, words):
    err = _cli(argv, rc=2)["error"]
    assert words in err and "\n" not in err


def test_velocity_strengthening_has_no_h_star():
    """a > b: no critical stiffness, so no h* (said in the notes), the regime named, any patch stable."""
    doc = _cli(["nucleation", "dieterich", "--V", "1e-9", "--sigma", "5e7", "--shear-modulus", "3e10",
                "--param", "a=0.02", "--param", "b=0.015", "--patch", "1e4"])
    assert doc["k_c"] is None and doc["h_star"] is None and doc["L_inf"] is None
    assert "velocity strengthening" in doc["regime"] and any("no h*" in n for n in doc["notes"])
    assert doc["L_b"] == pytest.approx(3e10 * 0.9e-6 / (0.015 * 5e7), rel=1e-12, abs=0)   # L of Table 1
    assert doc["patch_steady_sliding"] == "stable"
