"""``landau simulate galvanetto-*`` with a user's kinetic law (``--kinetic``/``--kinetic-pos``) and the
damped one block's Hopf analysis (``--hopf``), checked against closed forms and solve_ivp."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from landau.cli import main

EXP_LAW = "(1 - delta)*exp(gamma*r) + delta"


def _json(capsys, *argv):
    code = main(["simulate", *argv, "--json"])
    out = capsys.readouterr().out
    return code, json.loads(out)


def test_one_block_user_law_hopf_point_and_criticality(capsys):
    # c1 = F_k'(−V) = γ(1 − δ)e^{−γV} for the user's branch (closed form); ω = 1; subcritical:
    # F_k''' > 0 gives a3 = F_k'''(−V)/6 > 0 in ẅ + w = −(c − c1)ẇ + a3ẇ³ (+ even terms), so
    # Λ > 0 and the unstable cycle's amplitude factor C = 1/sqrt(2ℓ1), ℓ1 = 3a3/8 (Guckenheimer &
    # Holmes 1983, eq. 3.4.11).  Engine tolerance 1e-8 (root finder on the Hopf point).
    V, g, d = 0.5, 3.0, 0.2
    code, doc = _json(capsys, "galvanetto-one-block", "--kinetic", EXP_LAW, "--param", f"gamma={g}",
                      "--param", f"delta={d}", "--V", str(V), "--t-end", "5", "--hopf")
    assert code == 0
    h = doc["hopf"]
    c1 = g * (1 - d) * math.exp(-g * V)
    assert h["c1"] == pytest.approx(c1, rel=1e-8)
    assert h["omega"] == pytest.approx(1.0, rel=1e-10)
    assert h["criticality"] == "subcritical" and h["Lambda"] > 0
    a3 = g ** 3 * (1 - d) * math.exp(-g * V) / 6
    assert h["C"] == pytest.approx(1 / math.sqrt(2 * 3 * a3 / 8), rel=1e-8)
    assert doc["parameters"]["kinetic"] == "delta + (1 - delta)*exp(gamma*r)"


def test_one_block_user_law_simulation_against_solve_ivp(tmp_path, capsys):
    # Started stuck at X = 0 the block rides the belt until X = F_s = 1 at t = 1/V (closed form),
    # then slips on the user's branch: that slip phase integrated independently with solve_ivp
    # (closed-form law) must match the CSV to the integrators' accuracy (rtol 1e-9 in the CLI).
    V, c = 0.5, 0.1
    out = tmp_path / "run.csv"
    code = main(["simulate", "galvanetto-one-block", "--kinetic", EXP_LAW, "--param", "delta=0.2",
                 "--param", f"c={c}", "--V", str(V), "--t-end", "8", "--out", str(out), "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 0 and doc["status"] == "finished"
    with open(out) as fh:
        rows = np.array([[float(x) for x in r] for r in list(csv.reader(fh))[1:]])
    t0 = (1.0 - c * V) / V                      # the stick phase ends at K = X + cV = 1
    F = lambda r: 0.8 * math.exp(3.0 * r) + 0.2
    up = lambda t, y: y[1] - V
    up.terminal, up.direction = True, 1
    sol = solve_ivp(lambda t, y: [y[1], -(y[0] + c * y[1]) + F(y[1] - V)], (t0, 8.0), [1.0 - c * V, V],
                    events=up, dense_output=True, method="DOP853", rtol=1e-12, atol=1e-13)
    t_end = sol.t_events[0][0] if sol.t_events[0].size else 8.0
    slip = (rows[:, 0] > t0 + 1e-6) & (rows[:, 0] < t_end - 1e-6)
    assert slip.sum() > 10
    np.testing.assert_allclose(rows[slip, 1], sol.sol(rows[slip, 0])[0], atol=1e-7)
    np.testing.assert_allclose(rows[slip, 2], sol.sol(rows[slip, 0])[1], atol=1e-7)


def test_two_blocks_take_a_user_law_with_its_own_positive_branch(capsys):
    code, doc = _json(capsys, "galvanetto-two-blocks", "--kinetic", "1/(1 - gamma*r)",
                      "--kinetic-pos", "-1/(1 + gamma*r)", "--param", "beta=1.5", "--t-end", "20")
    assert code == 0 and doc["status"] == "finished"
    assert doc["parameters"]["kinetic_pos"] == "-1/(gamma*r + 1)"


@pytest.mark.parametrize("argv,needle", [
    (["galvanetto-one-block", "--kinetic", "__import__('os').getcwd()"], "kinetic"),
    (["galvanetto-one-block", "--kinetic-pos", "-1"], "--kinetic-pos needs --kinetic"),
    (["galvanetto-one-block", "--kinetic", "exp(q*r)"], "q"),
    (["galvanetto-one-block", "--kinetic", "1/(1 + r)", "--V", "1"], "not finite"),
    (["galvanetto-two-blocks", "--hopf"], "--hopf applies to galvanetto-one-block"),
    (["impact-oscillator", "--kinetic", "1"], "--kinetic applies to galvanetto-one-block, galvanetto-two-blocks only"),
])
def test_bad_kinetic_input_exits_2_with_one_line(capsys, argv, needle):
    code = main(["simulate", *argv, "--t-end", "1"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1 and needle in err


def test_belt_velocity_from_param_or_option(capsys):
    # --param V=... (as in the README) and --V give the same belt velocity; the first stick phase
    # then lasts until X = F_s = 1, i.e. t = 1/V (closed form), so the first event is at 1/V
    for argv in (["--param", "V=0.4"], ["--V", "0.4"]):
        code, doc = _json(capsys, "galvanetto-one-block", *argv, "--t-end", "3")
        assert code == 0 and doc["parameters"]["V"] == 0.4
        assert doc["status"] == "finished"


def test_landau_hopf_damped_one_block_with_user_law(capsys):
    # `landau hopf galvanetto-one-block`: the same closed forms as above (c1 = γ(1 − δ)e^{−γV},
    # subcritical, C = 1/sqrt(2ℓ1) with ℓ1 = 3a3/8), from the Hopf command
    V, g, d = 0.5, 3.0, 0.2
    code = main(["hopf", "galvanetto-one-block", "--kinetic", EXP_LAW, "--param", f"delta={d}", "--V", str(V),
                 "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 0
    assert doc["p_c"] == pytest.approx(g * (1 - d) * math.exp(-g * V), rel=1e-8)
    assert doc["omega_c"] == pytest.approx(1.0, rel=1e-10) and doc["criticality"] == "subcritical"
    a3 = g ** 3 * (1 - d) * math.exp(-g * V) / 6
    assert doc["C"] == pytest.approx(1 / math.sqrt(2 * 3 * a3 / 8), rel=1e-8)
    # a law that strengthens with the slip speed (F_k'(−V) = −1 < 0) has no Hopf point: NoHopfError,
    # exit 1 with one line
    code = main(["hopf", "galvanetto-one-block", "--kinetic", "1 - r", "--json"])
    err = capsys.readouterr().err.strip()
    assert code == 1 and "NoHopfError" in err and len(err.splitlines()) == 1
