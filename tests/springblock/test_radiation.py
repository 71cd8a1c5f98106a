"""Radiation damping η (Rice 1993) on the spring–block: closed form, criticality, quasi-dynamic limit.

Independent routes: the closed form k_c = [σ(b − a) − ηV]/L · [1 + MV²/(L(σa + ηV))] (the aging
law's eq. (30) of Putelat et al. 2010 with a → a + ηV/σ), and the general Fredholm engine on the
equations written by hand here (not through :class:`SpringBlock`).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import sympy as sp

from landau.derivation.general import hopf_normal_form
from landau.laws import get_law
from landau.systems.system import DynamicalSystem, SpringBlock
from landau.verify.springblock.checks import predict

LAW = get_law("dieterich")
OFF = dict(a=0.02, b=0.031, L=2e-5, sigma=30.0, V_s=1e-6, a_v=0.5)   # away from the defaults


def kc_closed(p, V):
    a, b, L, s, M, eta = p["a"], p["b"], p["L"], p["sigma"], p["M"], p["eta"]
    return (s * (b - a) - eta * V) / L * (1 + M * V ** 2 / (L * (s * a + eta * V)))


def hand_made(p, V):
    """M u̇ = −kX − σ[a ln(1 + u/V) + b ln(Vθ/L)] − ηu, θ̇ = 1 − (V + u)θ/L, written here."""
    X, u, th, k = sp.symbols("X u theta k", real=True)
    a, b, L, s, M, eta = (sp.Float(p[n]) for n in ("a", "b", "L", "sigma", "M", "eta"))
    rhs = (u, -k * X - s * (a * sp.log(1 + u / V) + b * sp.log(V * th / L)) - eta * u, 1 - (V + u) * th / L)
    return DynamicalSystem("hand-made", (X, u, th), rhs, (1, M, 1), k, (0, 0, sp.Float(p["L"] / V)))


@pytest.mark.parametrize("M,eta,V", [(3.0, 40.0, 3e-4), (0.0, 40.0, 3e-4), (0.5, 0.0, 1e-3)])
def test_kc_closed_form_and_general_engine(M, eta, V):
    prm = {**OFF, "M": M, "eta": eta}
    res = predict(LAW, V, prm)
    kc = kc_closed(prm, V)
    assert res.kc == pytest.approx(kc, rel=1e-12)
    ref = hopf_normal_form(hand_made(prm, V), {}, (0.5 * kc, 2 * kc))
    assert res.omega_c == pytest.approx(ref.omega_c, rel=1e-9)
    assert res.dlambda_dp == pytest.approx(ref.dlambda_dp, rel=1e-8)
    assert res.Lambda == pytest.approx(ref.Lambda, rel=1e-7)
    assert res["eta"] == eta                          # η named in the result


def test_eta_zero_reproduces_plain_block():
    plain = predict(LAW, 1e-4, {})
    damped = predict(LAW, 1e-4, {"eta": 0.0})
    for name in ("kc", "omega_c", "Lambda", "chi"):
        assert damped[name] == pytest.approx(plain[name], rel=1e-13)


def _Lambda(eta):
    return predict(LAW, 1e-4, {"eta": eta}).Lambda


def test_damping_turns_aging_law_hopf_supercritical():
    """Table 1 of Putelat et al. (2010), V = 1e-4 m/s: subcritical without damping, supercritical
    with η of order 100 N·s/m (the mechanism of Mizushima & Hatano 2021)."""
    from scipy.optimize import brentq

    assert _Lambda(0.0) > 0
    assert _Lambda(100.0) < 0 and _Lambda(1000.0) < 0
    eta_star = brentq(_Lambda, 0.0, 100.0, xtol=1e-10)
    assert 10 < eta_star < 100
    # the turning point against the general engine on the hand-made equations
    prm = {**SpringBlock("dieterich", ("eta",)).resolve({"eta": eta_star})}
    kc = kc_closed(prm, 1e-4)
    ref = hopf_normal_form(hand_made(prm, 1e-4), {}, (0.5 * kc, 2 * kc))
    assert abs(ref.Lambda) < 1e-6 * abs(_Lambda(0.0))


@pytest.mark.slow
def test_simulated_cycle_with_damping():
    """η = 100 N·s/m, k = k_c(1 − ε²): a small perturbation grows into the stable cycle of amplitude
    C sqrt(k_c − k) (half peak-to-peak slip), integrated here with scipy on the hand-made equations."""
    from scipy.integrate import solve_ivp

    prm = SpringBlock("dieterich", ("eta",)).resolve({"eta": 100.0})
    V = 1e-4
    res = predict(LAW, V, prm)
    eps2 = 2e-3
    k = res.kc * (1 - eps2)
    a, b, L, s, M, eta = (prm[n] for n in ("a", "b", "L", "sigma", "M", "eta"))

    def f(t, y):
        X, w, psi = y            # w = ln(v/V), psi = ln(θ V/L)
        v = V * np.exp(w)
        force = -k * X - s * (a * w + b * psi) - eta * (v - V)
        return [v - V, force / (M * v), (1 - v * L / V * np.exp(psi) / L) * V / L * np.exp(-psi)]

    amp = res.amplitude(k)
    T = 2 * np.pi / res.omega_c
    for start in (0.3 * amp, 2.0 * amp):
        sol = solve_ivp(f, (0, 1500 * T), [start, 0.0, 0.0], method="LSODA", rtol=1e-10, atol=1e-14,
                        max_step=T / 20)
        tail = sol.y[0][sol.t > 1400 * T]
        half = (tail.max() - tail.min()) / 2
        assert half == pytest.approx(amp, rel=0.1)


def test_cli_json_and_latex(tmp_path):
    import contextlib
    import io

    from landau.cli.app import main

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        rc = main(["hopf", "spring-block", "dieterich", "--V", "1e-4", "--param", "eta=100", "--json"])
    assert rc == 0
    doc = json.loads(buf.getvalue())
    assert doc["eta"] == 100.0 and doc["criticality"] == "supercritical"
    assert doc["p_c"] == pytest.approx(kc_closed({**SpringBlock("dieterich", ("eta",)).resolve({"eta": 100})},
                                                 1e-4), rel=1e-12)
    tex = tmp_path / "kc.tex"
    with contextlib.redirect_stdout(io.StringIO()):
        rc = main(["derive", "dieterich", "--V", "1e-4", "--param", "eta=100", "--quantities", "kc,omega_c",
                   "--latex", str(tex)])
    assert rc == 0
    assert r"V \eta" in tex.read_text()          # k_c in closed form with η (not only \theta)


def test_check_confirms_the_damped_cycle():
    """landau.check simulates the block with η = 100 N·s/m (the compiled field carries the term): the
    supercritical cycle at k = k_c(1 − 1e-3) has the predicted amplitude (within the O(ε²) tolerance)."""
    import landau

    r = landau.check("dieterich", 1e-4, 1e-3, {"eta": 100.0})
    assert r.agrees and r.prediction.criticality == "supercritical"
