"""``landau hopf system`` and ``landau hopf spring-block-chain``: the CLI contract (one JSON document,
exit 2 with one line on bad input) and agreement with the Python API."""

from __future__ import annotations

import json

import pytest

from landau.cli import main
from landau.derivation.general import hopf_normal_form
from landau.systems.system import DynamicalSystem

BRUSSELATOR = ["--rhs", "x=a - (b + 1)*x + x^2*y", "--rhs", "y=b*x - x^2*y", "--parameter", "b",
               "--param", "a=1.5"]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_brusselator_json_matches_python(capsys):
    code, out, err = run(capsys, "hopf", "system", *BRUSSELATOR, "--equilibrium", "x=a", "--equilibrium", "y=b/a",
                         "--bracket", "2:4", "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["model"] == "system"
    assert doc["p_c"] == pytest.approx(1 + 1.5 ** 2, rel=1e-13)       # b_c = 1 + a²
    assert doc["omega_c"] == pytest.approx(1.5, rel=1e-13)            # ω_c = a
    s = DynamicalSystem.from_strings({"x": "a - (b + 1)*x + x^2*y", "y": "b*x - x^2*y"}, "b", {"a": 1.5},
                                     equilibrium={"x": "a", "y": "b/a"})
    r = hopf_normal_form(s, s.defaults, (2, 4))
    for key in ("p_c", "omega_c", "Lambda", "chi", "l1"):
        assert doc[key] == r.as_dict()[key]
    assert doc["criticality"] == "supercritical"


def test_guess_negative_bracket_and_mass(capsys):
    # Rayleigh: p_c = 0, Λ = −3, l₁ = −3/4; with mass 2 on both rows ω_c = 1/2
    code, out, err = run(capsys, "hopf", "system", "--rhs", "x=y", "--rhs", "y=-x + p*y - y^3", "--parameter", "p",
                         "--guess", "x=0.1", "--bracket=-1:1", "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["Lambda"] == pytest.approx(-3.0, rel=1e-13) and doc["l1"] == pytest.approx(-0.75, rel=1e-13)
    code, out, err = run(capsys, "hopf", "system", "--rhs", "x=y", "--rhs", "y=-x + p*y - y^3", "--parameter", "p",
                         "--guess", "x=0", "--mass", "x=2", "--mass", "y=2", "--bracket", "-1:1", "--json")
    assert code == 0, err
    assert json.loads(out)["omega_c"] == pytest.approx(0.5, rel=1e-13)


@pytest.mark.parametrize("argv, needle", [
    (["--rhs", "x=__import__('os')", "--parameter", "p", "--guess", "x=0", "--bracket", "0:1"], "__import__"),
    (["--rhs", "x=y", "--parameter", "p", "--guess", "x=0", "--bracket", "0:1"], "unknown symbol 'y'"),
    (["--rhs", "x=p*x", "--parameter", "p", "--guess", "x=0", "--bracket", "1:0"], "--bracket"),
    (["--rhs", "x=p*x", "--parameter", "p", "--guess", "x=0", "--bracket", "0"], "--bracket"),
    (["--rhs", "x=p*x", "--parameter", "p", "--guess", "x=0"], "--bracket"),
    (["--rhs", "x=p*x", "--parameter", "p", "--bracket", "0:1"], "--equilibrium"),
    (["--rhs", "x=p*x", "--parameter", "p", "--guess", "x=0", "--equilibrium", "x=0", "--bracket", "0:1"], "not both"),
    (["--rhs", "x=p*x", "--guess", "x=0", "--bracket", "0:1"], "--parameter"),
    (["--parameter", "p", "--guess", "x=0", "--bracket", "0:1"], "--rhs"),
    (["--rhs", "x=p*x", "--parameter", "p", "--param", "c=1", "--guess", "x=0", "--bracket", "0:1"], "no expression"),
    (["--rhs", "x=p*x", "--parameter", "p", "--param", "c=abc", "--guess", "x=0", "--bracket", "0:1"], "not a number"),
    (["--rhs", "x=p*x", "--parameter", "p", "--guess", "x=zz", "--bracket", "0:1"], "--guess"),
    (["--rhs", "x=p*x", "--rhs", "x=1", "--parameter", "p", "--guess", "x=0", "--bracket", "0:1"], "twice"),
    (["dieterich", "--rhs", "x=p*x", "--parameter", "p", "--guess", "x=0", "--bracket", "0:1"], "another model"),
    (["--rhs", "x=p*x - y", "--rhs", "y=x + p*y", "--parameter", "p", "--guess", "x=0", "--bracket", "0.5:1"],
     "no Hopf crossing"),
])
def test_bad_input_exits_2_with_one_line(capsys, argv, needle):
    code, out, err = run(capsys, "hopf", "system", *argv, "--json")
    assert code in (1, 2) and json.loads(out)["exit_code"] == code
    assert code == 2 or "NoHopfError" in err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0], err
    assert "Traceback" not in err


def test_chain_json_has_the_mode_shape(capsys):
    code, out, err = run(capsys, "hopf", "spring-block-chain", "dieterich", "--blocks", "2", "--V", "1e-4",
                         "--param", "M_2=0.6", "--param", "k_coupling=3e4", "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["model"] == "spring-block-chain" and doc["blocks"] == 2
    assert len(doc["mode_shape"]) == 2 and doc["mode_shape"][0] == [1.0, 0.0]
    assert doc["p_c"] > 0 and doc["criticality"] in ("supercritical", "subcritical")


@pytest.mark.parametrize("argv, needle", [
    (["dieterich"], "--blocks"),
    (["dieterich", "--blocks", "two"], "--blocks"),
    (["dieterich", "--blocks", "2", "--param", "M=1"], "M_1"),
    (["dieterich", "--blocks", "2", "--param", "k=1"], "k"),
    (["dieterich", "--blocks", "2", "--rhs", "x=1"], "another model"),
])
def test_chain_bad_input(capsys, argv, needle):
    code, out, err = run(capsys, "hopf", "spring-block-chain", *argv)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and needle in err


@pytest.mark.parametrize("command", [["hopf", "spring-block", "dieterich"], ["derive", "dieterich"]])
def test_quasi_static_aging_law_at_kcr_is_degenerate_on_the_command_line(capsys, command):
    # the centre of Ranjith & Rice (1999): degenerate through derive and landau hopf
    code, out, err = run(capsys, *command, "--param", "M=0", "--V", "1e-4", "--json")
    assert code == 0, err
    doc = json.loads(out)
    crit = doc["criticality"] if "criticality" in doc else doc["points"][0]["criticality"]
    assert crit == "degenerate"
    if command[0] == "hopf":     # the next order from the general engine vanishes too
        assert doc["degenerate_at_every_order_computed"] is True and doc["l2"] == 0.0
        assert "degenerate at every order computed" in doc["text"]


def test_general_engine_on_the_command_line_says_degenerate_at_every_order(capsys):
    # the same spring-block written as a system (X, u, phi), M = 0: an algebraic u-row
    mu = "a*log((V + u)/V) + b*log(phi*V/L)"
    code, out, err = run(capsys, "hopf", "system", "--rhs", "X=u", "--rhs", f"u=-k*X - sigma*({mu})",
                         "--rhs", "phi=1 - phi*(V + u)/L", "--mass", "u=0", "--parameter", "k",
                         "--param", "a=0.0349", "--param", "b=0.0489", "--param", "L=9e-7", "--param", "V=1e-4",
                         "--param", "sigma=11.772", "--equilibrium", "X=0", "--equilibrium", "u=0",
                         "--equilibrium", "phi=L/V", "--bracket", "1.5e5:2.2e5", "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["p_c"] == pytest.approx(11.772 * (0.0489 - 0.0349) / 9e-7, rel=1e-12)
    assert doc["criticality"] == "degenerate" and doc["Lambda"] == 0.0
    assert doc["degenerate_at_every_order_computed"] is True


def test_a_chain_of_fifty_blocks_answers_by_the_numeric_route(capsys):
    # identical blocks at the defaults: the in-phase mode at the single block's k_c, Putelat et al.
    # (2010) eq. (30), aging law: k_c = σ(b − a)/L·(1 + MV²/(σaL)) with σ = 1.2·9.81 N, M = 1.2 kg
    code, out, err = run(capsys, "hopf", "spring-block-chain", "dieterich", "--blocks", "50", "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["route"] == "numeric" and doc["blocks"] == 50 and doc["mode"] == "in-phase"
    s, m, v = 1.2 * 9.81, 1.2, 1e-4
    assert doc["p_c"] == pytest.approx(s * (0.0489 - 0.0349) / 9e-7 * (1 + m * v ** 2 / (s * 0.0349 * 9e-7)), rel=1e-12)


@pytest.mark.parametrize("argv, needle", [
    (["--blocks", "101"], "1 to 100 blocks"),
    (["--blocks", "13", "--route", "symbolic"], "at most 12 blocks"),
])
def test_chain_refusals_beyond_the_routes(capsys, argv, needle):
    code, out, err = run(capsys, "hopf", "spring-block-chain", "dieterich", *argv)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and needle in err
