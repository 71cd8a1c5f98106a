"""The forced oscillator of Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019) with a friction
law object: the compiled friction term generated from the law, a user's law simulated against an
independent scipy integration, the Sec. 5 estimates damped with the law's viscous coefficient,
and the ``landau simulate forced-oscillator --friction`` command."""

from __future__ import annotations

import csv
import json
import math
import os
import pickle

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from landau.cli import main
from landau.errors import InputError
from landau.laws.velocity import VelocityFriction, coulomb, regularised_coulomb
from landau.verify.skurativskyi import approx
from landau.verify.skurativskyi.model import PAPER, Params, compiled_field
from landau.verify.skurativskyi.simulate import rest_state, run

#: the user's law of the README and the CLI test: viscous plus tanh-regularised dry friction [N]
TANH = "c*v + T*tanh(v/e)"


def tanh_law(c=6.6511, T=0.63133, e=1e-5) -> VelocityFriction:
    return VelocityFriction.from_strings("tanh-dry", TANH, params={"c": c, "T": T, "e": e}, quantity="force")


def test_default_field_is_eq1_of_the_paper():
    # the generated field with the default law against eq. (1) typed out here, with the
    # identified parameters of Sec. 2: the same floating-point operations, so equal to rounding
    p = PAPER.packed()
    acc = compiled_field().accel
    for t, x, v in [(0.1, -2.0e-3, 1e-3), (0.37, -2.09e-3, -2e-6), (1.3, -2.07e-3, 0.0), (0.2, -2.2e-3, 4e-7)]:
        fr = 6.6511 * v + 0.63133 * v / math.sqrt(v * v + 1e-12)
        d = x + 2.086e-3
        fi = 0.0
        if d > 0:
            f = d ** 1.5 + 0.8485 * d ** 1.5 * math.copysign(abs(v) ** 0.18667, v) * (v != 0)
            fi = 2.3983e8 * max(f, 0.0)
        exact = (0.01805 * 256 * math.sin(16 * t) - 1418.9 * x - fr - fi) / 8.735
        assert acc(t, x, v, p) == pytest.approx(exact, rel=1e-14, abs=1e-15)


@pytest.mark.parametrize("law", [regularised_coulomb(), tanh_law(e=1e-4)], ids=["paper", "tanh"])
def test_compiled_friction_and_slope_match_the_law(law):
    # the numba kernels are printed from the law's expressions: they agree with the law's own
    # numpy evaluation (sympy-lambdified) to rounding, also at v = 0 exactly
    prm = Params(friction=law)
    k = compiled_field(prm).friction
    p = prm.packed()
    for v in (-0.3, -2e-6, 0.0, 1e-7, 5e-6, 0.1):
        assert k.friction(v, p) == pytest.approx(law.value(v), rel=1e-13, abs=1e-300)
        F, dF = k.friction_slope(v, p)
        assert F == pytest.approx(law.value(v), rel=1e-13, abs=1e-300)
        assert dF == pytest.approx(law.slope(v), rel=1e-9)


@pytest.mark.skipif(os.environ.get("NUMBA_DISABLE_JIT") == "1", reason="no compiler: no machine code to count")
def test_one_compiled_loop_serves_every_law():
    # the loop is compiled for one signature; a law reaches it as C callbacks, so runs with the
    # paper's law and two user laws leave that one machine-code version (nothing recompiled)
    from landau.verify.skurativskyi import rk

    for law in (regularised_coulomb(), tanh_law(), tanh_law(e=1e-4)):
        run(Params(friction=law), 0.5, rtol=1e-6)
    assert rk.integrate_mixed.signatures == [rk.loop_signature()]
    fr = [compiled_field(Params(friction=law)).pointers for law in (regularised_coulomb(), tanh_law())]
    assert fr[0][3] and not fr[1][3]            # the paper's law is the compiled-in one, tanh is not


def test_user_law_against_scipy_radau():
    """Off-paper: the forced oscillator with c v + T tanh(v/e) (e = 1e-4 m/s) and no Hertz
    damping (b = 0; scipy's Newton-based Radau stalls on the |ẋ|^{n₃} cusp of the damping, see
    verify/benchmarks/skurativskyi_work_precision.py), ω = 16, from rest at X₀, 0.6 s with 4
    impacts, against solve_ivp Radau at rtol 1e-10 on eq. (1) written out here with the law in
    closed form — the contact force is continuous (δ^{3/2}), integrated as a smooth force.
    Measured differences: 2e-13 m, 1e-11 m/s, 3e-11 s on the impact times; the tolerances are
    100x that (both runs carry rtol 1e-10 errors) and far below the effect of the law (the
    paper's law gives a state 1e-5 m/s away)."""
    c, T, e = 6.6511, 0.63133, 1e-4
    p = Params(friction=tanh_law(c, T, e), omega=16.0, b=0.0)
    y0 = rest_state(p)
    r = run(p, 0.6 / p.period, y0, rtol=1e-11, atol=(1e-16, 1e-14))

    def f(t, y):
        x, v = y
        d = x - p.xI
        fi = p.kI * d ** 1.5 if d > 0 else 0.0
        return [v, (p.m0e * 256.0 * math.sin(16.0 * t) - p.k * x - c * v - T * math.tanh(v / e) - fi) / p.m]

    s = solve_ivp(f, (0.0, r.t_final), y0, method="Radau", rtol=1e-10, atol=[1e-15, 1e-13],
                  events=lambda t, y: y[0] - p.xI)
    assert s.status == 0
    up = np.array([ye[1] > 0 for ye in s.y_events[0]], bool)
    impacts = s.t_events[0][up]
    assert len(r.impacts) == len(impacts) >= 3
    np.testing.assert_allclose(r.impacts, impacts, rtol=0, atol=1e-8)
    assert abs(r.y_final[0] - s.y[0, -1]) < 1e-10 and abs(r.y_final[1] - s.y[1, -1]) < 1e-8
    paper = run(PAPER.with_(omega=16.0, b=0.0), 0.6 / p.period, y0, rtol=1e-11, atol=(1e-16, 1e-14))
    assert abs(paper.y_final[1] - r.y_final[1]) > 1e-6


def test_linear_grazing_damps_with_the_viscous_coefficient():
    # Sec. 5, eq. (4): x_I = X0 - m0e w^2 / sqrt((w c)^2 + D^2), D = k + 1.5 kI sqrt(X0 - xI) - m w^2,
    # solved here from the closed form; a law c v + T tanh(v/e) has viscous coefficient c
    c = 4.0
    p = Params(friction=tanh_law(c=c, T=0.9, e=1e-5))
    assert p.linear_damping == pytest.approx(c, rel=1e-15)
    X0 = brentq(lambda X: p.k * X + p.kI * (X - p.xI) ** 1.5, p.xI, 0.0, xtol=1e-18)
    klin = p.k + 1.5 * p.kI * math.sqrt(X0 - p.xI)
    g = lambda w: X0 - p.m0e * w * w / math.hypot(w * c, klin - p.m * w * w) - p.xI
    exact = brentq(g, 1.0, math.sqrt(klin / p.m) * 0.999, xtol=1e-13)
    assert approx.grazing_linear(p) == pytest.approx(exact, rel=1e-10)
    # the paper's own law gives the printed 15.657 rad/s (c = 6.6511)
    assert round(approx.grazing_linear(Params(friction=tanh_law())), 3) == 15.657


def test_params_hold_the_law():
    law = tanh_law()
    p = Params(friction=law, omega=20.0)
    assert p.with_(T=0.5).friction.defaults()["T"] == 0.5 and p.T == 0.63133
    assert p.with_(omega=3.0).friction is law
    assert PAPER.with_(eps=2e-6).eps == 2e-6 and PAPER.c == 6.6511
    q = pickle.loads(pickle.dumps(p))          # sweeps send Params to worker processes
    assert q.friction.value(1e-5) == law.value(1e-5) and q.omega == 20.0
    with pytest.raises(InputError, match="set-valued"):
        Params(friction=coulomb(0.4))
    with pytest.raises(InputError, match="set-valued"):
        PAPER.with_(eps=0.0)
    with pytest.raises(InputError, match="no parameter"):
        Params(friction=law, eps=1e-6)
    with pytest.raises(InputError, match="unknown parameter"):
        p.with_(mu=0.3)


def test_cli_forced_oscillator_with_user_friction(tmp_path, capsys):
    out = tmp_path / "run.csv"
    code = main(["simulate", "forced-oscillator", "--friction", TANH, "--param", "c=6.6511", "--param", "T=0.63133",
                 "--param", "e=1e-5", "--t-end", "1", "--out", str(out), "--json"])
    text = capsys.readouterr().out
    assert code == 0, text
    doc = json.loads(text)
    assert doc["status"] == "finished" and doc["files"] == [str(out)]
    assert doc["parameters"]["e"] == 1e-5 and doc["parameters"]["friction"] == "user-friction"
    assert any("omega = 15.65" in n for n in doc["notes"])     # the Sec. 5 estimate for this law
    with open(out) as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["t [s]", "x [m]", "xdot [m/s]"] and len(rows) > 100
    # the CSV's last row is the simulated final state, which the same law run from Python reproduces
    r = run(Params(friction=tanh_law()), 1.0 / PAPER.period)
    assert float(rows[-1][0]) == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_allclose([float(x) for x in rows[-1][1:]], r.y_final, rtol=1e-12)


@pytest.mark.parametrize("argv,words", [
    (["--friction", TANH, "--param", "c=6.6511", "--param", "T=0.63133"], ["unknown symbol", "e"]),
    (["--friction", "mu", "--param", "mu=0.3"], ["set-valued"]),
    (["--friction", "c*v + __import__('os')"], ["__import__"]),
    (["--param", "eps=0"], ["set-valued"]),
])
def test_cli_bad_friction_exits_2_naming_it(capsys, argv, words):
    assert main(["simulate", "forced-oscillator", *argv, "--t-end", "0.1", "--json"]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1
    for w in words:
        assert w in err
