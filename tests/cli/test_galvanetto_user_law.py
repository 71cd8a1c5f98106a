"""Galvanetto's "your own kinetic law": parameters of its own, and the domain of every parameter.

The damped one block ẍ + cẋ + x = F_k(ẋ − V) (Galvanetto 2004, eq. 4a) loses stability at
c₁ = F_k'(−V); for the user law F_k(r) = (1 − δ)/(1 − γr)² + δ − ηr the hand derivative is
F_k'(r) = 2γ(1 − δ)/(1 − γr)³ − η.
"""

from __future__ import annotations

import json

import pytest

from landau.cli import main
from landau.errors import DomainError, InputError
from landau.laws.kinetic import KineticFriction

LAW = "(1 - delta)/(1 - gamma*r)**2 + delta - eta*r"


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def slope(r, gamma=3.0, delta=0.0, eta=0.05):
    return 2 * gamma * (1 - delta) / (1 - gamma * r) ** 3 - eta


def test_hopf_with_a_parameter_of_the_users_law(capsys):
    code, out, err = run(capsys, "hopf", "galvanetto-one-block", "--kinetic", LAW, "--param", "eta=0.05",
                         "--V", "0.3", "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["p_c"] == pytest.approx(slope(-0.3), rel=1e-10)
    # η enters linearly: it moves c₁ only, the cubic coefficient is that of the law without it
    code, out0, _ = run(capsys, "hopf", "galvanetto-one-block", "--kinetic", LAW.replace(" - eta*r", ""),
                        "--V", "0.3", "--json")
    ref = json.loads(out0)
    assert ref["p_c"] == pytest.approx(slope(-0.3, eta=0.0), rel=1e-10)
    assert doc["Lambda"] == pytest.approx(ref["Lambda"], rel=1e-9)


def test_from_expression_takes_extra_parameters():
    law = KineticFriction.from_expression(LAW, eta=0.05, delta=0.2)
    assert law.dneg(-0.3) == pytest.approx(slope(-0.3, delta=0.2), rel=1e-13)
    assert law.defaults()["eta"] == 0.05 and not law.is_paper_law
    assert law.with_defaults(eta=0.1).dneg(-0.3) == pytest.approx(slope(-0.3, delta=0.2, eta=0.1), rel=1e-13)
    import pickle

    assert pickle.loads(pickle.dumps(law)) == law
    from landau.verify.galvanetto.model import one_block

    p = one_block(0.3, law=law).with_(eta=0.0, c=0.5)
    assert p.law.dneg(-0.3) == pytest.approx(slope(-0.3, delta=0.2, eta=0.0), rel=1e-13) and p.c == 0.5


@pytest.mark.parametrize("argv, needle", [
    (["--kinetic", LAW], "uses eta without a value: give eta=VALUE"),
    (["--kinetic", LAW, "--param", "eta=0.05", "--param", "zeta=1"], "unknown parameter(s) zeta"),
    (["--kinetic", LAW.replace("eta", "c"), "--param", "c=0.05"], "'c' is reserved: it is the damping"),
    (["--param", "gamma=-1"], "gamma >= 0"),
    (["--param", "delta=2"], "0 <= delta <= 1"),
    (["--param", "delta=-0.1"], "0 <= delta <= 1"),
    (["--kinetic", "sqrt(r)"], "branch is not real at r = -1e-06"),
    (["--kinetic", "log(r)"], "branch is not real"),
    (["--kinetic", "sign(r + 0.5)", "--V", "0.5"], "not differentiable at steady sliding"),
    (["--V", "1e300"], "leaves the float64 range"),
    (["--param", "gamma=1e300"], "leaves the float64 range"),
])
def test_bad_kinetic_law_or_parameter_is_named(capsys, argv, needle):
    code, out, err = run(capsys, "hopf", "galvanetto-one-block", *argv)
    assert code == 2 and out == "" and err.count("\n") == 1
    assert needle in err


def test_a_jump_away_from_steady_sliding_has_zero_slope(capsys):
    # sign(r + 0.5) is constant near r = −0.3: F_k' = 0 there, no Hopf point (no "DiracDelta" in the code)
    code, _, err = run(capsys, "hopf", "galvanetto-one-block", "--kinetic", "sign(r + 0.5)", "--V", "0.3")
    assert "stable for every damping" in err and "internal error" not in err


@pytest.mark.parametrize("kw, needle", [
    (dict(c=-0.1), "c must be >= 0"),
    (dict(V=0.0), "V must be > 0"),
    (dict(V=float("nan")), "V must be finite"),
    (dict(beta=0.0, n=2), "beta must be > 0"),
    (dict(alpha=-1.0, n=2), "alpha must be >= 0"),
    (dict(n=3), "one or two blocks"),
    (dict(gamma=-0.5), "gamma >= 0"),
])
def test_model_parameters_are_checked(kw, needle):
    from landau.verify.galvanetto.model import StickSlipParams

    with pytest.raises(InputError, match=needle.replace("(", r"\(")):
        StickSlipParams(**kw)


def test_non_real_law_is_refused_from_python():
    with pytest.raises(DomainError, match="not real"):
        KineticFriction.from_expression("sqrt(r) + gamma")


def test_simulate_takes_the_parameters_of_the_users_law(capsys, tmp_path):
    # was: "unknown parameter(s) eta" — the simulation knew only gamma and delta
    code, out, err = run(capsys, "simulate", "galvanetto-one-block", "--kinetic", LAW, "--param", "eta=0.05",
                         "--t-end", "5", "--out", str(tmp_path / "run.csv"), "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["parameters"]["eta"] == 0.05
    # the value reaches the law: the r < 0 branch at r = -0.1 is F(-0.1) = 1/1.3**2 + 0.05*0.1
    law = KineticFriction.from_expression(doc["parameters"]["kinetic"])
    assert float(law.neg(-0.1)) == pytest.approx(1 / 1.3 ** 2 + 0.005, rel=1e-12)
    code, _, err = run(capsys, "simulate", "galvanetto-one-block", "--kinetic", LAW, "--t-end", "5",
                       "--out", str(tmp_path / "run2.csv"))
    assert code == 2 and "eta without a value" in err
