"""``landau simulate``: bounded runs, talk-ready plots and load-point velocity histories.

* every model stops at its step budget with the named status ``max-steps``, exit 1, and still
  writes its files (tested with a small ``--max-steps``; the default budgets are per model);
* the spring–block's streamed, decimated record keeps at most its point bound over the whole run;
* the plots: units on every axis, the slip rate on a log axis, shaded regimes with a legend,
  ``--discard`` and ``--y0``;
* ``--V-history``: a velocity step settles at μ_ss(V₂) with μ_ss(V₂) − μ_ss(V₁) = (a − b) ln(V₂/V₁)
  (Dieterich's law, steady state φ = L/v); a slide-hold-slide's peak on reloading grows with the
  hold time (the aging law heals during a hold: φ grows ≈ t_h).
"""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

from landau.cli import main

MODELS = ("spring-block", "galvanetto-one-block", "galvanetto-two-blocks", "impact-oscillator", "forced-oscillator")


def _csv(path):
    with open(path) as fh:
        rows = list(csv.reader(fh))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


@pytest.mark.parametrize("model", MODELS)
def test_step_budget_ends_with_a_named_status_and_writes_files(model, tmp_path, capsys):
    """A run that would last for ever (t_end = 1e12) ends at the step budget: status max-steps,
    exit 1, the message names the limit, and the CSV holds the run up to where it stopped."""
    out = tmp_path / "run.csv"
    code = main(["simulate", model, "--t-end", "1e12", "--max-steps", "400", "--out", str(out), "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 1 and doc["exit_code"] == 1
    assert doc["status"] == "max-steps"
    assert doc["steps"] <= 400 + 1
    assert 0 < doc["t_final"] < 1e12
    assert any("--max-steps" in n for n in doc["notes"])
    assert doc["files"] == [str(out)]
    header, rows = _csv(out)
    assert rows.shape[0] >= 2 and rows.shape[1] == len(header)
    assert all("[" in h for h in header)   # a unit on every column
    np.testing.assert_allclose(rows[-1, 0], doc["t_final"], rtol=1e-12)


def test_bad_max_steps_and_discard(capsys):
    for argv in (["--max-steps", "0"], ["--max-steps", "1.5"], ["--discard", "-1"], ["--y0", "1,2,3,4,5"],
                 ["--y0", "a,b"]):
        assert main(["simulate", "galvanetto-one-block", *argv]) == 2
        err = capsys.readouterr().err
        assert argv[0] in err and len(err.strip().splitlines()) == 1


def test_spring_block_streamed_record_is_bounded_and_spans_the_run():
    """record_run in compiled pieces of 3000 steps with a 1000-point bound: the record covers the
    whole run (first point at t0, last at the end), never holds more than about the bound, and
    its points are points of the single uninterrupted run's record to the integration tolerance."""
    from landau.laws import get_law
    from landau.verify.springblock.model import SpringBlockModel
    from landau.verify.springblock.simulate import integrate, record_run

    law = get_law("dieterich")
    model = SpringBlockModel.build(law, 1e-4, 1.7e5)
    y0 = model.perturbed(0.01 * model.ell)
    sim = record_run(model, y0, (0.0, 5.0), max_points=1000, chunk_steps=3000)
    assert sim.success and sim.t[0] == 0.0 and sim.t[-1] == pytest.approx(5.0, rel=1e-12)
    assert len(sim.t) <= 1000 + 1 and sim.nsteps > 3 * 3000
    assert np.all(np.diff(sim.t) > 0)
    ref = integrate(model, y0, (0.0, 5.0), record=10 ** 6)
    # the restarts at each piece change the steps: the end states agree to the tolerance's growth
    np.testing.assert_allclose(sim.y_final[:2], ref.y_final[:2], rtol=0, atol=1e-5)
    # a budget below the run's steps: status max-steps, no exception, the record up to there
    short = record_run(model, y0, (0.0, 5.0), max_steps=2500, max_points=1000, chunk_steps=1000)
    assert short.status.value == "max-steps" and short.t_final < 5.0 and short.t[-1] == short.t_final


def test_spring_block_streamed_record_keeps_every_step_of_each_chunk():
    """record_run in chunks of 10 step attempts without a point bound keeps one point per accepted step
    and the start: the last step of a chunk whose attempts were all accepted is recorded too (the next
    chunk's record starts at it)."""
    from landau.laws import get_law
    from landau.verify.springblock.model import SpringBlockModel
    from landau.verify.springblock.simulate import record_run

    model = SpringBlockModel.build(get_law("dieterich"), 1e-4, 1.7e5)
    y0 = model.perturbed(0.01 * model.ell)
    sim = record_run(model, y0, (0.0, 0.5), rtol=1e-8, chunk_steps=10)
    assert sim.nsteps > 100 and len(sim.t) == sim.nsteps + 1 and np.all(np.diff(sim.t) > 0)


def test_hybrid_engine_step_budget_is_a_status():
    """The hybrid engine at its step budget returns status max_steps (not an exception) with the
    recorded trajectory up to there."""
    from landau.verify.galvanetto.analysis import FIG_STEPPER
    from landau.verify.galvanetto.maps import model_for
    from landau.verify.galvanetto.model import StickSlipParams
    from landau.verify.hybrid import EngineOptions, simulate

    p = StickSlipParams(n=1)
    sol = simulate(model_for(p), "s", np.array([0.0, p.V]), (0.0, 1e12), FIG_STEPPER,
                   EngineOptions(record=True, max_steps=200, max_samples=64))
    sim = sol
    assert sim.status.value == "max-steps" and sim.nsteps <= 201
    assert len(sim.t) <= 64 + 16 and sim.t[-1] == pytest.approx(sol.t_final)
    # the regimes follow the mode changes: stuck at the start, for t < 1/V (closed form, X = Vt = 1)
    assert sim.regimes[0][2] == "stick" and sim.regimes[0][1] == pytest.approx(1 / p.V, rel=1e-9)


def test_state_units_by_dimensional_analysis():
    from landau.laws import get_law
    from landau.verify.springblock.units import infer_state_units, parse_units

    assert parse_units("m/s") == (1, -1) and parse_units("") == (0, 0) and parse_units("Pa") is None
    assert parse_units("m^2/s") == (2, -1)
    assert infer_state_units(get_law("dieterich")) == {"phi": "s"}     # dφ/dt = 1 − vφ/L
    assert infer_state_units(get_law("ruina")) == {"phi": "s"}         # dφ/dt = −(vφ/L) ln(vφ/L)


def test_overview_plot_axes(tmp_path):
    """The spring–block's overview: v on a log axis (its stick phases span decades), a unit on
    every axis, the stick regime shaded and named in a figure legend, no status in the title."""
    from matplotlib.figure import Figure

    from landau.cli.app import build_parser
    from landau.cli.simulate import simulate_model

    parser, _ = build_parser("simulate")
    args = parser.parse_args(["simulate", "spring-block", "--k", "1.2e5", "--t-end", "4"])
    sim, _, units, _ = simulate_model(args)
    assert any(r[2].startswith("stick") for r in sim.regimes)
    fig = sim.plot(units=units, fig=Figure())
    ts_axes = fig.axes[:3]
    assert [a.get_ylabel() for a in ts_axes] == ["X [m]", "v [m/s]", "phi [s]"]
    assert ts_axes[1].get_yscale() == "log" and ts_axes[0].get_yscale() == "linear"
    assert ts_axes[-1].get_xlabel() == "t [s]"
    assert "finished" not in fig._suptitle.get_text()
    texts = [t.get_text() for leg in fig.legends for t in leg.get_texts()]
    assert any(t.startswith("stick") for t in texts)
    labels = [t.get_text() for t in fig.axes[3].get_legend().get_texts()]
    assert any(lab.startswith("start") for lab in labels) and any(lab.startswith("end") for lab in labels)
    # --discard drops the transient from the drawn series, the events and the regimes
    late = sim.after(2.0)
    assert late.t[0] >= 2.0 and all(r[0] >= 2.0 for r in late.regimes)
    with pytest.raises(ValueError, match="no recorded point"):
        sim.after(10.0)


def test_poincare_with_discard_and_y0(tmp_path, capsys):
    """The forced oscillator's stroboscopic section without its transient; --y0 sets the start."""
    out = tmp_path / "run.csv"
    assert main(["simulate", "forced-oscillator", "--t-end", "3", "--discard", "1", "--y0", "-0.0021,0.001",
                 "--out", str(out), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    _, rows = _csv(out)
    assert rows[0, 0] >= 1.0
    assert any("--y0" in n for n in doc["notes"])
    png = tmp_path / "s.png"
    assert main(["simulate", "forced-oscillator", "--t-end", "3", "--discard", "1", "--plot", "poincare",
                 "--out", str(png)]) == 0


def test_galvanetto_y0_starts_slipping(tmp_path, capsys):
    """--y0 with a velocity below the belt's starts the block slipping (mode n), not stuck."""
    out = tmp_path / "run.csv"
    assert main(["simulate", "galvanetto-one-block", "--t-end", "0.5", "--y0", "0.5,0", "--out", str(out)]) == 0
    _, rows = _csv(out)
    np.testing.assert_allclose(rows[0, 1:], [0.5, 0.0])
    assert rows[-1, 2] != pytest.approx(0.25)   # not riding the belt


# --- load-point histories -------------------------------------------------------------------
def _dieterich():
    from landau.laws import get_law
    from landau.systems.system import SpringBlock

    law = get_law("dieterich")
    return law, SpringBlock(law).resolve({})


def _mu_ss(p, V):
    """Dieterich's steady state φ = L/V: μ_ss = a_v + (a − b) ln(V/V_*)."""
    return p["a_v"] + (p["a"] - p["b"]) * math.log(V / p["V_s"])


def test_velocity_step_cli(tmp_path, capsys):
    """A velocity step 1e-6 → 1e-5 m/s at t = 20 s: μ settles at μ_ss(V₂), and μ_ss(V₂) − μ_ss(V₁)
    = (a − b) ln(V₂/V₁) (closed form).  The run is 20 evolution distances L/V₂ long after the
    step on a stiff machine (k = 2 k_c): the transient has decayed below 1e-7 there (measured
    1e-15); the CSV holds t, V, v, mu and φ with units."""
    out = tmp_path / "step.csv"
    assert main(["simulate", "spring-block", "dieterich", "--V-history", "1e-6@0,1e-5@20", "--t-end", "40",
                 "--out", str(out), "--json"]) == 0
    header, rows = _csv(out)
    assert header == ["t [s]", "V [m/s]", "v [m/s]", "mu [1]", "phi [s]", "x_lp [m]", "slip [m]"]
    _, p = _dieterich()
    before = rows[rows[:, 0] < 20, 3][-1]
    after = rows[-1, 3]
    assert rows[-1, 1] == 1e-5 and rows[0, 1] == 1e-6
    assert before == pytest.approx(_mu_ss(p, 1e-6), abs=1e-7)
    assert after == pytest.approx(_mu_ss(p, 1e-5), abs=1e-7)
    assert after - before == pytest.approx((p["a"] - p["b"]) * math.log(10.0), abs=2e-7)
    assert rows[-1, 2] == pytest.approx(1e-5, rel=1e-6)


def test_slide_hold_slide_peak_grows_with_hold_time():
    """Slide-hold-slide at 1e-5 m/s with holds of 1, 10, 100 s (aging law, Python API): the peak
    friction on reloading grows with the hold time.  During a hold v ≪ L/φ, so dφ/dt ≈ 1 and φ
    grows ≈ t_h: the peak grows by about b ln 10 per decade of hold (Dieterich 1972; Marone 1998);
    measured 0.94 and 0.99 b ln 10 — asserted within [0.8, 1.1] b ln 10."""
    from landau.verify.springblock.history import peak_after, simulate_history

    law, p = _dieterich()
    k = 2 * p["sigma"] * (p["b"] - p["a"]) / p["L"]
    peaks = []
    for th in (1.0, 10.0, 100.0):
        sim = simulate_history(law, f"1e-5@0,0@5,1e-5@{5 + th}", k, t_end=5 + th + 5)
        assert sim.success and sim.state_names == ("V", "v", "mu", "phi", "x_lp", "slip")
        hold = (sim.t > 5) & (sim.t < 5 + th)
        assert np.all(sim.y[0, hold] == 0.0)                 # the load point holds
        peaks.append(peak_after(sim, 5 + th) - _mu_ss(p, 1e-5))
    growth = np.diff(peaks) / (p["b"] * math.log(10.0))
    assert np.all(growth > 0.8) and np.all(growth < 1.1), growth


@pytest.mark.parametrize("text, words", [
    ("0@0,1e-5@1", ["first"]),
    ("1e-5@0,1e-6@0", ["increasing"]),
    ("1e-5@0,-1@3", [">= 0"]),
    ("1e-5", ["V@t"]),
    ("x@0", ["numbers"]),
])
def test_bad_histories_exit_2(text, words, capsys):
    assert main(["simulate", "spring-block", "--V-history", text]) == 2
    err = capsys.readouterr().err
    for w in words:
        assert w in err
    assert main(["simulate", "galvanetto-one-block", "--V-history", "1e-5@0"]) == 2


def test_plot_makes_a_pyplot_managed_figure_or_draws_into_the_one_given():
    """The toolkit's plotting convention (landau.report.plotting): without ``fig=`` the figure is
    pyplot's (a notebook shows it as an image, never ``<Figure …>`` text); with ``fig=`` the plot
    is drawn there and that figure is returned."""
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    from landau.verify.hybrid import EventLog
    from landau.verify.hybrid.plotting import regimes_from_mask
    from landau.verify.hybrid.result import Simulation, Status

    t = np.linspace(0.0, 10.0, 201)
    y = np.vstack([np.sin(t), 1e-3 + np.exp(-t) * (1 + np.cos(3 * t))])
    sim = Simulation("demo", t, y, EventLog(), Status.FINISHED, "", t[-1], y[:, -1], 200, 0, None, ("x", "v"),
                     regimes_from_mask(t, y[1] < 1e-2, "stick", "slip"))
    fig = sim.plot(units={"x": "m", "v": "m/s"})
    try:
        assert fig.canvas.manager is not None and plt.fignum_exists(fig.number)
        assert fig.axes[1].get_yscale() == "log"   # v spans more than two decades
    finally:
        plt.close(fig)
    given = Figure()
    assert sim.plot(fig=given) is given


def test_forced_oscillator_streamed_record():
    """The forced oscillator's record_run: one call is the same computation as ``run`` (identical
    series); in compiled pieces of 2000 steps with a 500-point bound the record spans the whole
    run, stays bounded, logs the same impacts, and ends where the uninterrupted run ends to the
    tolerance (rtol 1e-8, atol 1e-12 m, 1e-10 m/s: measured 1e-14 m, 1e-11 m/s)."""
    from landau.verify.skurativskyi.model import PAPER
    from landau.verify.skurativskyi.simulate import record_run, run

    one = record_run(PAPER, 3.0)
    ref = run(PAPER, 3.0 / PAPER.period, record=10 ** 6)
    np.testing.assert_array_equal(one.y, ref.y)
    pieces = record_run(PAPER, 30.0, max_points=500, chunk_steps=2000)
    whole = run(PAPER, 30.0 / PAPER.period, record=10 ** 6)
    assert pieces.success and len(pieces.t) <= 501 and pieces.t[0] == 0.0 and pieces.t[-1] == 30.0
    assert len(pieces.events) == len(whole.events)
    np.testing.assert_allclose(pieces.y_final, whole.y_final, rtol=0, atol=1e-9)
    short = record_run(PAPER, 1e12, max_steps=3000, chunk_steps=1000, max_points=100)
    assert short.status.value == "max-steps" and short.t[-1] == short.t_final and len(short.t) <= 101
