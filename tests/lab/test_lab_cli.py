"""``landau simulate spring-block --preset lab``: the quasi-static protocol from the command line, its
columns and units, the default figure (friction against load-point displacement), --json, exit 2."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

from landau.cli import main

LAW = ["--param", "a_v=0.6", "--param", "a=0.005", "--param", "b=0.01", "--param", "L=10um", "--param", "V_s=1"]
STEP = ["simulate", "spring-block", "dieterich", "--preset", "lab", "--V-history", "1um/s@0,10um/s@100",
        "--k", "1e-3/um", "--t-end", "200", *LAW]


def test_the_lab_run_writes_displacement_slip_mu_v_and_states_in_lab_units(tmp_path, capsys, monkeypatch):
    import landau.lab.figure as figure

    drawn = []

    def spy(sim, **kw):
        fig = real(sim, **kw)
        drawn.append(fig)
        return fig

    real = figure.plot_friction
    monkeypatch.setattr(figure, "plot_friction", spy)
    out, png = tmp_path / "step.csv", tmp_path / "step.png"
    assert main([*STEP, "--out", str(out), "--out", str(png), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    with open(out) as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["t [s]", "x_lp [um]", "slip [um]", "mu [1]", "v [um/s]", "V [um/s]", "phi [s]", "F [1]"]
    data = np.array(rows[1:], float)
    t, x, slip, mu, v, V, phi, F = data.T
    # the load point: 1 um/s for 100 s then 10 um/s; x_lp = integral of V dt
    assert x == pytest.approx(np.where(t < 100, t, 100 + 10 * (t - 100)), rel=1e-12, abs=1e-9)
    # quasi-static per unit normal stress: mu = k'(x_lp - slip) + mu(0), the spring's force (F) balancing it
    assert mu == pytest.approx(0.6 + 1e-3 * (x - slip), abs=1e-12)
    # F = mu holds at the collocation nodes; the rows are read from the dense output between them, where
    # v and phi carry the integration's local error (rtol 1e-9 of the run, relative): mu then moves by
    # a*dv/v + b*dphi/phi <= (a + b)*rtol = 1.5e-11 (measured 5.3e-13 with radau5's reuse policy,
    # 1e-13 before it changed the steps)
    assert F == pytest.approx(mu, abs=(0.005 + 0.01) * 1e-9)
    # settled: slip - x_lp = -(mu_ss(V2) - mu_ss(V1)) / k' = -(a - b) ln 10 / 1e-3 um
    assert slip[-1] - x[-1] == pytest.approx(5.0 * math.log(10.0), rel=1e-9)
    assert v[-1] == pytest.approx(10.0, rel=1e-9) and phi[-1] == pytest.approx(1.0, rel=1e-9)   # theta = L/V
    assert doc["units"]["x_lp"] == "um" and doc["final_state"]["x_lp"] == pytest.approx(1100.0, rel=1e-12)
    assert doc["parameters"]["M"] == 0.0 and doc["parameters"]["eta"] == 0.0 and doc["parameters"]["k"] == 1e3
    # the default figure of a protocol: mu against load-point displacement (and v below), from the same series
    assert png.stat().st_size > 0 and len(drawn) == 1
    ax_mu, ax_v = drawn[0].axes
    xy = ax_mu.lines[0].get_xydata()
    assert xy[:, 0] == pytest.approx(x, rel=1e-12, abs=1e-12) and xy[:, 1] == pytest.approx(mu, abs=1e-15)
    assert ax_v.lines[0].get_ydata() == pytest.approx(v, rel=1e-12)
    assert "load-point displacement" in ax_v.get_xlabel() and "um" in ax_v.get_xlabel()


def test_units_on_the_si_preset(tmp_path, capsys):
    # --k 1e-3/um on the SI block is k = k' sigma; the history with units is the m/s one
    assert main(["simulate", "spring-block", "dieterich", "--V-history", "1um/s@0,10um/s@20", "--k", "1/um",
                 "--t-end", "25", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["parameters"]["k"] == pytest.approx(1e6 * 1.2 * 9.81, rel=1e-15)
    assert doc["parameters"]["V_history"] == "1e-06@0,1e-05@20"
    assert doc["units"]["x_lp"] == "m"


@pytest.mark.parametrize("extra, words", [
    (["--k", "1e-3/kg"], ["--k", "unknown unit '/kg'"]),
    (["--k", "1um/s"], ["--k", "is a velocity"]),
    (["--param", "L=10um/s"], ["--param L", "is a velocity, but L is a length (m)"]),
    (["--V-history", "1um@0"], ["--V-history", "'1um' is a length"]),
    (["--preset", "lab", "--V", "1um/s"], ["--preset lab", "--V-history"]),
    (["--plot", "friction", "--V", "1e-4"], ["--plot friction", "--V-history"]),
])
def test_bad_input_is_exit_2_with_one_line(extra, words, capsys):
    args = ["simulate", "spring-block", "dieterich", *extra]
    if "--V-history" not in extra and "--V" not in extra:
        args += ["--V-history", "1um/s@0,10um/s@10"]
    if "--k" not in extra:
        args += ["--k", "1e6"]
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    for w in words:
        assert w in err
    # with --json: the error document on stdout, still exit 2
    assert main([*args, "--json"]) == 2
    assert json.loads(capsys.readouterr().out)["exit_code"] == 2
