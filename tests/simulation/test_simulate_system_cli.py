"""``landau simulate system --rhs ...``: a user system from strings, run by the compiled Radau IIA,
against scipy's DOP853 at rtol 1e-12 on the same equations (an independent integration)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from landau.cli import main

BRUSSELATOR = ["--rhs", "x=a - (b + 1)*x + x^2*y", "--rhs", "y=b*x - x^2*y", "--parameter", "b",
               "--param", "a=1.5", "--param", "b=3.3"]


def _brusselator(t, y, a=1.5, b=3.3):
    x, w = y
    return [a - (b + 1) * x + x * x * w, b * x - x * x * w]


def test_a_run_from_strings_matches_an_independent_integration(tmp_path, capsys):
    y0 = [1.2, 2.0]
    assert main(["simulate", "system", *BRUSSELATOR, "--guess", "x=1.5", "--y0", "1.2,2.0", "--t-end", "30",
                 "--out", str(tmp_path / "b.csv"), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    ref = solve_ivp(_brusselator, (0, 30), y0, method="DOP853", rtol=1e-12, atol=1e-12)
    got = [doc["final_state"]["x"], doc["final_state"]["y"]]
    # rtol 1e-8 of the compiled run, over ~5 periods of a growing oscillation: 1e-5 is generous and tight
    # enough to catch a wrong equation (a 1 % change of b moves the end by 1e-2)
    np.testing.assert_allclose(got, ref.y[:, -1], rtol=1e-5)
    assert doc["model"] == "system" and doc["status"] == "finished"
    assert (tmp_path / "b.csv").read_text().splitlines()[0].startswith("t")


@pytest.mark.parametrize("argv, needle", [
    (["--rhs", "x=a*x", "--param", "a=1"], "--t-end"),   # fine, just short: see below
    (["--rhs", "x=a*x", "--parameter", "b", "--param", "a=1"], "'b'"),
    (["--rhs", "x=-x + zz"], "zz"),
    (["dieterich", "--rhs", "x=a*x", "--param", "a=1"], "LAW"),
])
def test_bad_input_exits_2_with_one_line(argv, needle, capsys):
    if needle == "--t-end":
        assert main(["simulate", "system", *argv, "--t-end", "1", "--json"]) == 0
        capsys.readouterr()
        return
    code = main(["simulate", "system", *argv, "--t-end", "1", "--json"])
    out, err = capsys.readouterr()
    assert code == 2, (out, err)
    doc = json.loads(out) if out.strip() else {"error": err}
    assert needle in json.dumps(doc) + err
