"""``landau cycles``: bad input exits 2 with one line naming it (one JSON document with ``--json``),
never a traceback; the sweep task ``cycles`` is offered by the models that declare cycles."""

from __future__ import annotations

import json

import numpy as np
import pytest

from landau.cli.app import main


def run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.mark.parametrize("argv, needle", [
    (["cycles", "no-such-model"], "unknown model 'no-such-model'"),
    (["cycles", "forced-oscillator"], "declares no cycles (models that do: "),
    (["cycles", "spring-block", "--steps", "x"], "--steps: expected an integer, got 'x'"),
    (["cycles", "spring-block", "--steps", "0"], "--steps must be a positive integer"),
    (["cycles", "spring-block", "--plot", "diagram.jpg"], "unknown figure type"),
    (["cycles", "spring-block", "--ds", "nan"], "--ds"),
    (["cycles", "spring-block", "--direction", "2"], "direction must be +1 or -1"),
    (["cycles", "spring-block", "dieterich", "--param", "M=0", "--param", "eta=1000"], "invertible mass matrix"),
    (["cycles", "spring-block", "dieterich", "--param", "k=1e5"], "k is the bifurcation parameter"),
])
def test_refusals(capsys, argv, needle):
    code, out, err = run(capsys, *argv)
    assert code == 2 and needle in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    code, out, err = run(capsys, *argv, "--json")
    doc = json.loads(out)
    assert code == 2 and doc["exit_code"] == 2 and doc["kind"] == "InputError" and needle in doc["error"]


def test_the_models_that_declare_cycles_offer_the_sweep_task():
    from landau.models import get, offering

    assert {"spring-block", "spring-block-chain", "system", "mode-coupling"} <= set(offering("cycles"))
    assert "cycles" not in get("forced-oscillator").offered()
    assert "cycles" in get("spring-block").offered()


def test_a_branch_of_the_hopf_normal_form_to_json_csv_and_figure(capsys, tmp_path):
    """ẋ = μx − y − a x r², ẏ = x + μy − a y r²: the cycle r = sqrt(μ/a) with period 2π for every μ > 0,
    stable (Kuznetsov 2004, §3.5): the command's JSON, CSV and figure carry it."""
    csv, png = tmp_path / "b.csv", tmp_path / "b.png"
    code, out, err = run(capsys, "cycles", "system", "--rhs", "x=mu*x - y - a*x*(x**2 + y**2)",
                         "--rhs", "y=x + mu*y - a*y*(x**2 + y**2)", "--equilibrium", "x=0", "--equilibrium", "y=0",
                         "--parameter", "mu", "--bracket=-1:1", "--param", "a=4", "--steps", "12",
                         "--csv", str(csv), "--plot", str(png), "--json")
    assert code == 0, err
    doc = json.loads(out)
    br = doc["branch"]
    mu, amp = np.array(br["p"]), np.array(br["amplitude"])
    assert doc["points"] == 13 and mu.max() > 1e-2
    assert np.allclose(amp, np.sqrt(mu / 4), rtol=1e-6)
    assert np.allclose(br["period"], 2 * np.pi, rtol=1e-8) and all(br["stable"])
    assert doc["hopf"]["p_c"] == pytest.approx(0.0, abs=1e-12) and doc["hopf"]["equilibrium_stable_below"]
    assert doc["special_points"] == [] and doc["plot"]["lines"] == 1
    assert len(csv.read_text().splitlines()) == 14 and png.stat().st_size > 1000
