"""``landau simulate``: every model writes a CSV and a PNG; values against independent computations."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from landau.cli import main

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _run(tmp_path, capsys, *argv):
    """Run the command with a CSV and a PNG output; returns (JSON document, header, rows)."""
    csv_path, png_path = tmp_path / "run.csv", tmp_path / "run.png"
    code = main(["simulate", *argv, "--out", str(csv_path), "--out", str(png_path), "--json"])
    out = capsys.readouterr().out
    assert code == 0, out
    doc = json.loads(out)
    assert doc["status"] == "finished"
    assert sorted(doc["files"]) == sorted([str(csv_path), str(png_path)])
    assert png_path.read_bytes()[:8] == PNG_MAGIC
    with open(csv_path) as fh:
        reader = csv.reader(fh)
        header = next(reader)
        rows = np.array([[float(x) for x in r] for r in reader])
    assert rows.shape[0] >= 10 and rows.shape[1] == len(header)
    assert np.all(np.isfinite(rows))
    assert np.all(np.diff(rows[:, 0]) >= 0)
    return doc, header, rows


def test_spring_block_against_physical_ode(tmp_path, capsys):
    """The Dieterich spring–block (Putelat et al. 2010, eq. (4)) integrated independently in
    physical variables (M Ẍ = −kX − σ(μ − μ₀), φ̇ = 1 − vφ/L) by scipy's Radau from the CSV's first
    row: the CSV's last row agrees to 1e-8 of the scale (L, V, L/V).  The command integrates
    log-variables with its own compiled Radau IIA at rtol 1e-9, the reference runs at rtol 1e-11;
    measured difference 3e-11, so 1e-8 leaves room for the error growth of the unstable run
    on other platforms."""
    doc, header, rows = _run(tmp_path, capsys, "spring-block", "--V", "1e-4", "--t-end", "0.3")
    assert header == ["t [s]", "X [m]", "v [m/s]", "phi [s]"]   # φ of the aging law: a time (dφ/dt = 1 − vφ/L)
    p = doc["parameters"]
    assert p["law"] == "dieterich"
    assert any("0.9 k_c" in n for n in doc["notes"])
    M, k, V, sigma = p["M"], p["k"], p["V"], p["sigma"]
    a_v, a, b, L, Vs = p["a_v"], p["a"], p["b"], p["L"], p["V_s"]

    def mu(v, phi):
        return a_v + a * math.log(v / Vs) + b * math.log(Vs * phi / L)

    mu0 = mu(V, L / V)  # steady sliding: φ = L/V

    def rhs(t, y):
        X, v, phi = y
        return [v - V, (-k * X - sigma * (mu(v, phi) - mu0)) / M, 1.0 - v * phi / L]

    t_last = rows[-1, 0]
    ref = solve_ivp(rhs, (0.0, t_last), rows[0, 1:], method="Radau", rtol=1e-11,
                    atol=[1e-11 * L, 1e-11 * V, 1e-11 * L / V])
    assert ref.success
    scale = np.array([L, V, L / V])
    np.testing.assert_allclose(rows[-1, 1:] / scale, ref.y[:, -1] / scale, rtol=0, atol=1e-8 * np.abs(
        ref.y[:, -1] / scale).max())
    # the run is the unstable side of the Hopf point: the oscillation has grown
    third = len(rows) // 3
    assert np.abs(rows[-third:, 1]).max() > np.abs(rows[:third, 1]).max()


def test_forced_oscillator_before_contact_is_linear(tmp_path, capsys):
    """Without dry friction (T = 0) and before the cart reaches the obstacle (x < x_I), eq. (1) of
    Skurativskyi et al. (2019) is the linear damped oscillator m ẍ + c ẋ + k x = m₀e ω² sin ωt,
    solved in closed form from rest at x = 0.  The command's DOPRI5 runs at rtol 1e-8 with
    atol 1e-12 m (measured difference 5e-10 of the forced amplitude): agreement to 1e-7."""
    doc, header, rows = _run(tmp_path, capsys, "forced-oscillator", "--param", "T=0", "--param", "xI=0.003",
                             "--t-end", "3")
    assert header == ["t [s]", "x [m]", "xdot [m/s]"]
    p = doc["parameters"]
    m, c, k, om, F = p["m"], p["c"], p["k"], p["omega"], p["m0e"] * p["omega"] ** 2
    # particular solution A sin ωt + B cos ωt
    det = (k - m * om ** 2) ** 2 + (c * om) ** 2
    A, B = F * (k - m * om ** 2) / det, -F * c * om / det
    # homogeneous part fitting x(0) = 0, ẋ(0) = 0
    zeta, wd = c / (2 * m), math.sqrt(k / m - (c / (2 * m)) ** 2)
    C1 = -B
    C2 = (-A * om + zeta * C1) / wd
    free = np.cumprod(rows[:, 1] < p["xI"]).astype(bool)  # rows before the first contact
    assert 20 < free.sum() < len(rows)                     # contact does happen later in the run
    t = rows[free, 0]
    x = A * np.sin(om * t) + B * np.cos(om * t) + np.exp(-zeta * t) * (C1 * np.cos(wd * t) + C2 * np.sin(wd * t))
    amp = math.hypot(A, B)
    np.testing.assert_allclose(rows[free, 1], x, rtol=0, atol=1e-7 * amp)
    assert doc["events"] > 0


def test_galvanetto_one_block_first_stick_phase(tmp_path, capsys):
    """Galvanetto (2004), one block: started stuck at X = 0 the block rides the belt, X = Vt,
    Ẋ = V, until the spring force reaches the static friction X = F_s = 1 at t = 1/V (closed form)."""
    doc, header, rows = _run(tmp_path, capsys, "galvanetto-one-block", "--t-end", "10")
    assert header == ["t [1]", "X [1]", "Xdot [1]"]   # dimensionless (Galvanetto 2004)
    V = doc["parameters"]["V"]
    stick = rows[:, 0] < 1.0 / V - 1e-9
    assert stick.sum() > 5
    np.testing.assert_allclose(rows[stick, 1], V * rows[stick, 0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(rows[stick, 2], V, rtol=0, atol=1e-12)
    assert rows[~stick, 2].min() < V - 1e-3  # then it slips


def test_galvanetto_two_blocks(tmp_path, capsys):
    """Two blocks (Galvanetto 2004, Sec. 3), started stuck: both ride the belt until block 1's
    spring force K₁ = X₁ + α(X₁ − X₂) = X₁ reaches F_s1 = 1 at t = 1/V (closed form)."""
    doc, header, rows = _run(tmp_path, capsys, "galvanetto-two-blocks", "--t-end", "8")
    assert header == ["t [1]", "X1 [1]", "X2 [1]", "X1dot [1]", "X2dot [1]"]
    V = doc["parameters"]["V"]
    stick = rows[:, 0] < 1.0 / V - 1e-9
    np.testing.assert_allclose(rows[stick, 1:3], np.repeat(V * rows[stick, 0][:, None], 2, axis=1), rtol=0,
                               atol=1e-12)


def test_impact_oscillator(tmp_path, capsys):
    """Lancioni, Lenci & Galvanetto (2009), eq. (1), above the Hopf point: while the bar stays on the
    belt the contact holds, y = l cos φ (the gap g_N = y − l cos φ is zero to integration accuracy)."""
    doc, header, rows = _run(tmp_path, capsys, "impact-oscillator", "--t-end", "1")
    assert header == ["t [s]", "phi [rad]", "y [m]", "phidot [rad/s]", "ydot [m/s]"]
    assert doc["parameters"]["mu"] == 0.42
    gap = rows[:, 2] - doc["parameters"]["l"] * np.cos(rows[:, 1])
    assert np.abs(gap).max() < 1e-8


def test_npz_output(tmp_path, capsys):
    out = tmp_path / "run.npz"
    assert main(["simulate", "galvanetto-one-block", "--t-end", "6", "--out", str(out)]) == 0
    data = np.load(out)
    assert list(data["state_names"]) == ["X", "Xdot"]
    assert data["y"].shape == (2, len(data["t"]))
    np.testing.assert_allclose(data["y"][:, -1], data["y_final"], rtol=1e-12)


@pytest.mark.parametrize("argv, words", [
    (["spring-blok"], ["unknown model", "did you mean 'spring-block'"]),
    (["forced-oscillator", "--t-end", "-1"], ["--t-end"]),
    (["forced-oscillator", "--t-end", "nan"], ["--t-end"]),
    (["forced-oscillator", "--param", "omgea=3"], ["omgea", "omega"]),
    (["galvanetto-one-block", "--param", "beta=2"], ["beta", "gamma"]),
    (["impact-oscillator", "--out", "run.txt"], ["run.txt", ".csv"]),
    (["spring-block", "--param", "V=1e-4"], ["--V"]),
    (["spring-block", "--param", "k=1e5"], ["--k", "bifurcation"]),
    (["galvanetto-one-block", "dieterich"], ["spring-block only"]),
    (["galvanetto-one-block", "--law", "ruina"], ["spring-block only"]),
    (["spring-block", "--law", "nosuchlaw"], ["nosuchlaw"]),
])
def test_bad_input_exit_2(argv, words, capsys):
    assert main(["simulate", *argv]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1
    for w in words:
        assert w in err


# --- the Simulation result: sections, plots, HTML, files -------------------------------------
def _harmonic(n_periods: int = 5, with_sections: bool = True):
    """x = cos t, ẋ = −sin t recorded at 40 points per period, with its field (cubic Hermite)."""
    from landau.verify.hybrid import Event, EventLog
    from landau.verify.hybrid.result import Simulation, Status

    t = np.linspace(0.0, 2 * np.pi * n_periods, 40 * n_periods + 1)
    y = np.vstack([np.cos(t), -np.sin(t)])
    f = np.vstack([-np.sin(t), -np.cos(t)])
    log = EventLog()
    if with_sections:
        for k in range(n_periods):  # ẋ = 0 from above: x maximal
            tk = 2 * np.pi * (k + 1)
            log.append(Event(tk, np.array([1.0, 0.0]), "xdot=0", "m", "m", "section"))
    return Simulation("harmonic", t, y, log, Status.FINISHED, Status.FINISHED.advice, t[-1], y[:, -1],
                      len(t) - 1, 0, f, ("x", "xdot"))


def test_simulation_sections_and_plots(tmp_path):
    from matplotlib.figure import Figure

    sim = _harmonic()
    ts, ys = sim.section_points()
    assert len(ts) == 5 and ys.shape == (2, 5)
    # strobe at a period that is not a recorded time: cubic Hermite from 40 points per period,
    # interpolation error ≲ h⁴/384 · max|x''''| = (2π/40)⁴/384 ≈ 1.6e-6
    ts, ys = sim.section_points(period=2 * np.pi / 3 * 1.01)
    np.testing.assert_allclose(ys[0], np.cos(ts), atol=2e-6)
    np.testing.assert_allclose(ys[1], -np.sin(ts), atol=2e-6)
    fig = sim.plot(units={"x": "m", "xdot": "m/s"})
    assert isinstance(fig, Figure) and len(fig.axes) == 3
    assert fig.axes[0].get_ylabel() == "x [m]"
    fig = sim.plot(kind="poincare")
    line = fig.axes[0].lines[0]
    np.testing.assert_allclose(line.get_xdata(), 1.0)
    with pytest.raises(ValueError, match="no section events"):
        _harmonic(with_sections=False).plot(kind="poincare")
    with pytest.raises(ValueError, match="kind"):
        sim.plot(kind="bode")


def test_simulation_html_and_files(tmp_path):
    sim = _harmonic(2)
    html = sim._repr_html_()
    for word in ("harmonic", "finished", "81", "x = 1", "<table>"):
        assert word in html
    sim.to_csv(tmp_path / "h.csv", {"x": "m"})
    rows = np.loadtxt(tmp_path / "h.csv", delimiter=",", skiprows=1)
    assert open(tmp_path / "h.csv").readline().strip() == "t [s],x [m],xdot"
    np.testing.assert_array_equal(rows[:, 1:].T, sim.y)  # repr() of floats: exact round trip
    sim.to_npz(tmp_path / "h.npz")
    data = np.load(tmp_path / "h.npz")
    np.testing.assert_array_equal(data["event_t"], [e.t for e in sim.events])


def test_failed_run_exits_1(monkeypatch, capsys, tmp_path):
    """A run that ends without reaching t_end: exit 1, the status and its advice, and the files
    hold the run up to where it stopped."""
    from dataclasses import replace

    import landau.verify.galvanetto.run as G
    from landau.verify.hybrid.result import Status

    failed = replace(_harmonic(), status=Status.ZENO, message=Status.ZENO.advice)
    monkeypatch.setattr(G, "simulate_one_block", lambda setup, **kw: failed)
    out = tmp_path / "run.csv"
    assert main(["simulate", "galvanetto-one-block", "--out", str(out)]) == 1
    text = capsys.readouterr().out
    assert "zeno" in text and "accumulate" in text
    rows = np.loadtxt(out, delimiter=",", skiprows=1)
    np.testing.assert_array_equal(rows[:, 1:].T, failed.y)


def test_stroboscopic_section_matches_the_integrators_strobe():
    """The forced oscillator's integrator samples the state at t = 2πi/ω by ending steps there, so
    the section taken from the recorded series lands on recorded points and reproduces those
    samples to rounding (1e-12 of the motion's scale; measured < 1e-15)."""
    from landau.verify.skurativskyi.model import PAPER
    from landau.verify.skurativskyi.simulate import run

    r = run(PAPER, 6, record=100_000)
    ts, ys = r.section_points(period=PAPER.period)
    n = min(len(ts), len(r.strobe_t))
    np.testing.assert_allclose(ts[:n], r.strobe_t[:n], rtol=1e-12)
    scale = np.abs(r.strobe_y[:n, :2]).max(axis=0)
    np.testing.assert_allclose(ys[:, :n].T / scale, r.strobe_y[:n, :2] / scale, rtol=0, atol=1e-12)


def test_poincare_png(tmp_path, capsys):
    out = tmp_path / "section.png"
    assert main(["simulate", "forced-oscillator", "--t-end", "3", "--plot", "poincare", "--out", str(out)]) == 0
    assert out.read_bytes()[:8] == PNG_MAGIC
    assert main(["simulate", "galvanetto-one-block", "--plot", "poincare", "--out", str(out)]) == 2
    assert "no section events" in capsys.readouterr().err
