"""The command line takes the new terms: ``landau hopf`` prints the analysis (the same numbers as the
library), bad values of their parameters exit 2 with one line naming the parameter, and
``landau simulate`` writes the term states as columns with their units."""

from __future__ import annotations

import json

import pytest

from landau.cli import main
from landau.laws import get_law
from landau.verify.springblock.checks import predict

PORE = {"sigma": 20.0, "p_inf": 5.0, "eps_dil": 3e-4, "beta": 1e-3, "t_drain": 1.0}


def _params(d):
    return [a for k, v in d.items() for a in ("--param", f"{k}={v}")]


def test_hopf_with_pore_pressure(capsys):
    assert main(["hopf", "spring-block", "dieterich", "--V", "1e-6", *_params(PORE), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    r = predict(get_law("dieterich"), 1e-6, PORE)
    assert out["p_c"] == pytest.approx(r.p_c, rel=1e-12)
    assert out["Lambda"] == pytest.approx(r.Lambda, rel=1e-10)
    assert out["criticality"] == "supercritical"


@pytest.mark.parametrize("bad,message", [
    ({"t_drain": 0.0}, "parameter 't_drain' (drainage (hydraulic diffusion) time) must be > 0"),
    ({"beta": -1e-3}, "parameter 'beta' (storage coefficient of the pore fluid) must be > 0"),
    ({"eps_dil": -1e-4}, "parameter 'eps_dil'"),
    ({"lambda_tp": 1e5, "w_sz": 0.0}, "parameter 'w_sz' (half-width of the slip zone) must be > 0"),
    ({"p_inf": 25.0}, "the effective normal stress sigma - p_inf = -5 must be > 0"),
])
def test_bad_values_exit_2_with_one_line(capsys, bad, message):
    assert main(["hopf", "spring-block", "dieterich", "--V", "1e-6", *_params({**PORE, **bad})]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and message in err and "Traceback" not in err


def test_simulate_writes_the_pore_pressure(tmp_path, capsys):
    out = tmp_path / "run.csv"
    assert main(["simulate", "spring-block", "dieterich", "--V", "1e-6", "--k", "2.1e5", *_params(PORE),
                 "--t-end", "20", "--samples", "11", "--out", str(out), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["units"]["p"] == "Pa"
    header = out.read_text().splitlines()[0]
    assert header == "t [s],X [m],v [m/s],phi [s],p [Pa]"
    rows = [list(map(float, r.split(","))) for r in out.read_text().splitlines()[1:]]
    assert len(rows) == 11 and any(abs(r[4]) > 0 for r in rows)    # the pore pressure moves off p_inf


def test_load_histories_refuse_the_states_by_name(tmp_path, capsys):
    code = main(["simulate", "spring-block", "dieterich", "--k", "2.1e5", *_params(PORE),
                 "--V-history", "1e-6@0,2e-6@5", "--t-end", "10", "--out", str(tmp_path / "h.csv")])
    assert code == 2
    err = capsys.readouterr().err
    assert "the load histories" in err and "eps_dil" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "h.csv").exists()
