"""``landau cycles``: bad input exits 2 with one line naming it (one JSON document with ``--json``),
never a traceback; the sweep task ``cycles`` is offered by the models that declare cycles."""

from __future__ import annotations

import json

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
