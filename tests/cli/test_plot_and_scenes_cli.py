"""landau plot, the plotting functions, scene globs / --all summaries and off-paper --param."""

import json

import numpy as np
import pytest

from landau.cli.app import _jsonable, main
from landau.report.plotting import criticality_bands, plot_check, plot_coefficients

#: the Dieterich codimension-two point (Λ = 0 on the Hopf line), Putelat et al. (2010) eq. (34)
#: evaluated by the toolkit (README: V = 2.0693e-4 m/s)
DIETERICH_V_CODIM2 = 2.0693e-4


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_plot_command_writes_a_png_and_reports_the_bands(capsys, tmp_path):
    out = tmp_path / "dieterich.png"
    code, text, err = run(capsys, "plot", "dieterich", "--V", "1e-7:1e-2", "--points", "60",
                          "--out", str(out), "--json")
    assert code == 0 and err == ""
    doc = json.loads(text)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert doc["points"] == 60 and isinstance(doc["points"], int)          # integers stay integers
    kinds = [b["criticality"] for b in doc["bands"]]
    assert kinds == ["subcritical", "supercritical"]
    # the band edge lies within one grid step (5 decades / 59 intervals) of the codimension-two point
    step = 10 ** (5 / 59)
    edge = doc["bands"][0]["V_hi"]
    assert DIETERICH_V_CODIM2 / step < edge < DIETERICH_V_CODIM2 * step


@pytest.mark.parametrize("argv, needle", [
    (["plot", "dieterich", "--V", "1e-7:1e-2", "--out", "f.txt"], "unknown figure type"),
    (["plot", "dieterich", "--out", "f.png"], "--V LO:HI is required"),
    (["plot", "dieterich", "--V", "1e-2:1e-7", "--out", "f.png"], "LO < HI"),
    (["plot", "dieterich", "--V", "1e-7:1e-2", "--out", "f.png", "--quantities", "kc,nope"], "unknown quantity"),
    (["scene", "run"], "needs a scene name"),
    (["scene", "run", "putelat2010/V-hat", "--all"], "takes no name"),
    (["scene", "run", "--all", "putelat2010/V-hat"], "unrecognized arguments"),
    (["scene", "run", "nothing-like-this/*"], "no scene matches"),
    (["scene", "run", "skurativskyi2019/grazing-*", "--param", "zzz=1"], "none of the selected scenes"),
])
def test_bad_input_exits_2_with_one_line(capsys, argv, needle, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == "" and needle in err and len(err.strip().splitlines()) == 1


def test_scene_glob_prints_one_summary_table(capsys):
    code, out, _ = run(capsys, "scene", "run", "skurativskyi2019/grazing-*", "skurativskyi2019/static-equilibrium")
    lines = out.strip().splitlines()
    assert code == 0
    assert lines[0].split()[:3] == ["scene", "parameter", "value"]
    assert [ln.split()[0] for ln in lines[1:4]] == ["skurativskyi2019/grazing-harmonic",
                                                     "skurativskyi2019/grazing-linear",
                                                     "skurativskyi2019/static-equilibrium"]
    assert lines[-1] == "3 agrees"


def test_off_paper_param_is_not_a_disagreement(capsys):
    # Galvanetto (2004) prints delta = 0 but its type II sliding point 1.241 needs delta = 0.2;
    # with delta = 0 the value (0.642) belongs to other parameters than the published one
    code, out, _ = run(capsys, "scene", "run", "galvanetto2004/one-block-type-II", "--param", "delta=0")
    assert code == 0 and "DISAGREES" not in out and "[not comparable]" in out and "delta = 0.2" in out
    code, out, _ = run(capsys, "scene", "run", "galvanetto2004/one-block-type-II", "--param", "delta=0", "--json")
    doc = json.loads(out)
    assert doc["comparable"] is False and doc["agrees"] is None and round(doc["value"], 3) == 0.642
    # a numerical setting (the search bracket) keeps the comparison
    code, out, _ = run(capsys, "scene", "run", "galvanetto2004/one-block-type-II", "--param", "hi=4", "--json")
    doc = json.loads(out)
    assert doc["comparable"] is True and doc["agrees"] is True


def test_jsonable_keeps_integers():
    doc = _jsonable({"n": 3, "m": np.int64(7), "x": 2.5, "b": True, "bad": float("nan")})
    assert doc == {"n": 3, "m": 7, "x": 2.5, "b": True, "bad": None}
    assert type(doc["n"]) is int and type(doc["m"]) is int


def test_criticality_bands_and_check_plot():
    V = np.array([1e-6, 1e-5, 1e-4, 1e-3])
    bands = criticality_bands(V, [1.0, 1.0, 1.0, np.nan], [2.0, -1.0, -3.0, np.nan])
    # boundaries at the geometric mean of the neighbouring samples
    assert bands == [(1e-6, pytest.approx(10 ** -5.5), "subcritical"),
                     (pytest.approx(10 ** -5.5), pytest.approx(10 ** -3.5), "supercritical"),
                     (pytest.approx(10 ** -3.5), 1e-3, "no Hopf point")]
    e = np.array([1e-4, 4e-4, 1e-3, 4e-3])
    predicted = np.sqrt(e)
    simulated = predicted * (1 + 0.7 * e ** 1.5)          # relative error (ε²)^1.5 by construction
    fig = plot_check(e, predicted, simulated)
    assert len(fig.axes) == 2
    label = [t.get_text() for t in fig.axes[1].get_legend().get_texts()][1]
    assert "1.50" in label                                 # the fitted exponent
    with pytest.raises(Exception, match="same length"):
        plot_check(e, predicted, simulated[:2])
    # the same from check results (anything with eps2 and the two amplitudes)
    from types import SimpleNamespace

    results = [SimpleNamespace(system="toy", eps2=a, amplitude_predicted=b, amplitude_simulated=c)
               for a, b, c in zip(e, predicted, simulated, strict=True)]
    fig = plot_check(results)
    assert "1.50" in [t.get_text() for t in fig.axes[1].get_legend().get_texts()][1]
    np.testing.assert_allclose(fig.axes[0].lines[1].get_ydata(), simulated)


def test_coefficient_plot_has_one_panel_per_quantity():
    from landau import SpringBlock, derive
    from landau.laws import get_law

    d = derive(SpringBlock(get_law("dieterich")), ["kc", "omega_c", "Lambda", "C"])
    fig = d.plot((1e-6, 1e-3), n=30, names=("kc", "omega_c", "Lambda"))
    assert len(fig.axes) == 3 and all(ax.get_xscale() == "log" for ax in fig.axes)
    table = d.evaluate(np.logspace(-6, -3, 30), None, ["kc", "omega_c", "Lambda"])
    fig2 = plot_coefficients(table, ["omega_c"])
    assert len(fig2.axes) == 1
    ax = fig2.axes[0]
    np.testing.assert_allclose(ax.lines[0].get_ydata(), table["omega_c"])
