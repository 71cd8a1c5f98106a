"""The Linker–Dieterich state response α_LD through ``landau derive``, ``--latex`` and ``--codim2``.

With α_LD the stiffness k enters the state row as well as the force row (dσ/dt = −γ_LD k u).
Independent routes: the general Fredholm engine on the same equations
(:func:`landau.derivation.springblock_routes.hopf_point`, behind ``landau hopf spring-block``: a
numeric Hopf point located by its own root finder, numeric jets), the closed form for the aging law
(derived by hand, :mod:`landau.systems.springblock_terms`), the block without α_LD at 50 digits,
and the quintic coefficient of the general engine (:func:`landau.analyses.bautin.quintic_normal_form`).
"""

from __future__ import annotations

import contextlib
import io
import json

import numpy as np
import pytest

from landau.cli.app import main
from landau.derivation.multiscale import derive
from landau.derivation.springblock_routes import hopf_point
from landau.systems.system import SpringBlock

LAW = "dieterich"
V = 1e-4
#: away from the defaults: both signs of γ_LD, two α_LD, radiation damping and another mass
CASES = [{"gamma_ld": -1.0, "alpha_ld": 0.3},
         {"gamma_ld": 0.3, "alpha_ld": 0.56},
         {"gamma_ld": 0.3, "alpha_ld": 0.56, "eta": 3.0, "M": 2.5}]


def _cli(argv):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        rc = main(argv)
    assert rc == 0
    return out.getvalue()


def _params(extra):
    return [x for k, v in extra.items() for x in ("--param", f"{k}={v!r}")]


def _mu_ss(p, V):
    return p["a_v"] + (p["a"] - p["b"]) * np.log(V / p["V_s"])


def aging_closed_form(p, V):
    """(k_c, ω_c) of the aging-law spring–block with η, γ_LD, α_LD and M (springblock_terms docstring)."""
    a, b, L, s0, M = p["a"], p["b"], p["L"], p["sigma"], p["M"]
    eta, g, al = p.get("eta", 0.0), p.get("gamma_ld", 0.0), p.get("alpha_ld", 0.0)
    mu = _mu_ss(p, V)
    s = (s0 + g * eta * V) / (1 - g * mu)
    A = s * a + eta * V
    kc = (s * (b - a) - eta * V) / L * (A + M * V ** 2 / L) / ((1 - g * (mu - al)) * A + al * g * M * V ** 2 / L)
    return kc, np.sqrt(kc * (1 - g * mu) * V ** 2 / (L * A + M * V ** 2))


@pytest.mark.parametrize("extra", CASES)
def test_derive_equals_the_general_engine(extra):
    """``landau derive --json`` and ``landau hopf spring-block --json`` (the general engine) agree."""
    d = json.loads(_cli(["derive", LAW, "--V", repr(V), *_params(extra), "--json"]))
    (pt,) = d["points"]
    h = json.loads(_cli(["hopf", "spring-block", LAW, "--V", repr(V), *_params(extra), "--json"]))
    assert pt["k_c"] == pytest.approx(h["p_c"], rel=1e-8)
    assert pt["omega_c"] == pytest.approx(h["omega_c"], rel=1e-8)
    assert pt["Lambda"] == pytest.approx(h["Lambda"], rel=1e-8)
    for name in ("Gamma_bar", "Omega_bar", "chi"):
        assert pt[name] == pytest.approx(h[name], rel=1e-8)
    assert pt["criticality"] == h["criticality"]


def test_two_state_law_equals_the_general_engine():
    """A law with two states: the Hopf line from the roots of the Hopf polynomial, α_LD on the first state."""
    extra = {"gamma_ld": 0.3, "alpha_ld": 0.56}
    block = SpringBlock.for_params("two-state-dieterich", extra)
    r = derive(block).evaluate([V], extra, ["kc", "omega_c", "Lambda"])
    g = hopf_point(block, V, block.resolve(extra))
    assert r["kc"][0] == pytest.approx(g.p_c, rel=1e-8)
    assert r["omega_c"][0] == pytest.approx(g.omega_c, rel=1e-8)
    assert r["Lambda"][0] == pytest.approx(g.Lambda, rel=1e-8)


@pytest.mark.parametrize("extra", [*CASES, {"gamma_ld": 0.3, "alpha_ld": 0.56, "eta": 3.0, "M": 0.0},
                                   {"gamma_ld": -0.7, "alpha_ld": 0.2, "eta": 0.5, "M": 0.01, "sigma": 20.0}])
def test_aging_law_closed_form(extra):
    block = SpringBlock("dieterich", ("eta", "gamma_ld", "alpha_ld"))
    d = derive(block, ["kc"])
    p = block.resolve(extra)
    Vs = np.array([1e-5, 1e-4, 1e-3])
    r = d.evaluate(Vs, extra, ["kc", "omega_c"])
    with np.errstate(invalid="ignore"):
        kc, om = aging_closed_form(p, Vs)
    hopf = kc > 0                       # k_c ≤ 0: steady sliding stable at every stiffness
    assert hopf[:2].all()
    np.testing.assert_allclose(r["kc"][hopf], kc[hopf], rtol=1e-12)
    np.testing.assert_allclose(r["omega_c"][hopf], om[hopf], rtol=1e-12)
    assert np.isnan(r["kc"][~hopf]).all()


def test_alpha_zero_is_the_block_without_it():
    """α_LD = 0: the same numbers as the block with γ_LD only (and, with γ_LD = 0 too, the plain block),
    compared at 50 digits so that only the arrangement of the formulas differs."""
    names = ["Gamma_bar", "Omega_bar", "Lambda", "chi"]
    with_alpha = derive(SpringBlock(LAW, ("gamma_ld", "alpha_ld")))
    for extra, other in (({"gamma_ld": 0.4}, derive(SpringBlock(LAW, ("gamma_ld",)))),
                         ({"gamma_ld": 0.0}, derive(SpringBlock(LAW)))):
        p0 = other.block.resolve(extra if "gamma_ld" in other.block.terms else {})
        for Vi in (3e-6, 1e-4):
            a = with_alpha.evaluate_mp(Vi, {**p0, **extra, "alpha_ld": 0.0}, names)
            b = other.evaluate_mp(Vi, p0, names)
            for n in ("kc", "omega_c", *names):
                assert abs(a[n] / b[n] - 1) < 1e-40, n


def test_latex_has_alpha(tmp_path):
    tex = tmp_path / "alpha.tex"
    _cli(["derive", LAW, "--V", "1e-4", "--param", "gamma_ld=0.3", "--param", "alpha_ld=0.56",
          "--quantities", "k_c,omega_c,Lambda", "--latex", str(tex)])
    text = tex.read_text()
    assert r"\alpha_{\mathrm{ld}}" in text and r"\gamma_{\mathrm{ld}}" in text
    assert "k_c &=" in text and r"\Lambda" in text


def test_json_keys_as_without_alpha():
    plain = json.loads(_cli(["derive", LAW, "--V", "1e-4,1e-3", "--json"]))
    alpha = json.loads(_cli(["derive", LAW, "--V", "1e-4,1e-3", "--param", "gamma_ld=0.3",
                             "--param", "alpha_ld=0.56", "--json"]))
    assert set(alpha) == set(plain)
    assert [set(p) for p in alpha["points"]] == [set(p) for p in plain["points"]]
    assert alpha["params"]["alpha_ld"] == 0.56 and alpha["units"] == plain["units"]


def test_codim2_equals_a_root_of_the_general_engines_Lambda():
    """``--codim2``: V* where Λ changes sign, against brentq on the general engine's Λ(V); Λ₅ against the
    general engine's fifth-order Fredholm coefficient at that point."""
    from scipy.optimize import brentq

    from landau.analyses.bautin import quintic_normal_form

    extra = {"gamma_ld": 0.3, "alpha_ld": 0.56}
    doc = json.loads(_cli(["derive", LAW, "--codim2", "1e-4:1e-3", *_params(extra), "--json"]))
    (c,) = doc["codim2"]
    assert (c["sign_below"], c["sign_above"]) == (1, -1)
    block = SpringBlock.for_params(LAW, extra)
    p = block.resolve(extra)
    lam = lambda x: hopf_point(block, x, p).Lambda
    ref = brentq(lam, c["V"] * 0.99, c["V"] * 1.01, xtol=1e-12 * c["V"], rtol=1e-12)
    assert c["V"] == pytest.approx(ref, rel=1e-6)
    q = quintic_normal_form(block.system, {**p, "V": c["V"]}, c["k_c"], c["omega_c"])
    assert c["Lambda5"] == pytest.approx(q.Lambda5, rel=1e-6)
    assert np.isfinite(c["l2"]) and np.sign(c["l2"]) == np.sign(c["Lambda5"])


def test_points_carry_the_terms_and_kuznetsovs_l1():
    """``Derivation.points``: the terms' values located in the result, l₁ equal to the general engine's."""
    extra = {"gamma_ld": -1.0, "alpha_ld": 0.3}
    block = SpringBlock.for_params(LAW, extra)
    (pt,) = derive(block).points([V], extra)
    g = hopf_point(block, V, block.resolve(extra))
    assert pt.as_dict()["alpha_ld"] == 0.3 and pt.as_dict()["gamma_ld"] == -1.0
    assert pt.l1 == pytest.approx(g.l1, rel=1e-8)
    assert pt.Lambda == pytest.approx(g.Lambda, rel=1e-8)
