"""Display contract: every result object shows in a notebook in well under a second, and no
display (repr, _repr_html_, _repr_latex_) starts symbolic simplification or a derivation."""

import math
import time

import numpy as np
import pytest
import sympy as sp

from landau import SpringBlock, derive
from landau.derivation.hopf import HopfResult
from landau.derivation.multiscale import CoefficientTable, Derivation
from landau.laws import get_law
from landau.report.display import ResultList, html_table, text_table

#: the display contract (not a benchmark): a result shows in under a second
DISPLAY_BOUND_S = 1.0


@pytest.fixture(scope="module")
def dieterich():
    d = derive(SpringBlock(get_law("dieterich")), ["kc", "omega_c", "Lambda", "C"])
    table = d.evaluate(np.logspace(-7, -2, 40), None, ["kc", "omega_c", "Lambda", "C"])
    return d, table


def _no_symbolic_work(monkeypatch):
    def forbidden(*args, **kwargs):
        raise AssertionError("display started a symbolic simplification")

    for name in ("simplify", "factor", "cancel", "together", "nsimplify"):
        monkeypatch.setattr(sp, name, forbidden)
    for name in ("simplify", "factor", "cancel", "together"):
        monkeypatch.setattr(sp.Expr, name, forbidden)
    import landau.derivation.rational

    monkeypatch.setattr(landau.derivation.rational, "closed_form", forbidden)
    monkeypatch.setattr(Derivation, "coefficient", forbidden)      # no derivation either


def _display(obj) -> dict[str, str]:
    """What a notebook asks of an object: its text repr and every rich repr it defines."""
    out = {"text/plain": repr(obj)}
    for mime, meth in (("text/html", "_repr_html_"), ("text/latex", "_repr_latex_")):
        if hasattr(obj, meth):
            out[mime] = getattr(obj, meth)()
    return out


def _results(d, table):
    from landau.analyses.regimes import regime_diagram
    from landau.derivation.general import hopf_normal_form
    from landau.scenes import get_scene, run_scene
    from landau.systems.system import DynamicalSystem

    x, y, mu, beta = *sp.symbols("x y mu", real=True), sp.Symbol("beta", positive=True)
    vdp = DynamicalSystem("van-der-Pol", (x, y), (y, (mu - beta * x ** 2) * y - x), (sp.Integer(1), sp.Integer(1)),
                          mu, (sp.Integer(0), sp.Integer(0)), {"beta": 1.0}, 0)
    from landau.analyses.checking import CheckResult, Verdict

    mixed = Derivation(SpringBlock(get_law("spinodal"))).points([1e-4, 1e-2])     # a Hopf point and none
    hopf = HopfResult("toy", "p", 1.0, 2.0, (0.0, 0.0), complex(1.0, 0.5), -3.0, 0.25)
    checked = CheckResult(system="toy", parameter="p", p=1.1, eps2=0.1, prediction=hopf, amplitude_predicted=0.5,
                          amplitude_simulated=0.49, rel_error=-0.02, frequency_predicted=2.0,
                          frequency_simulated=2.01, frequency_rel_error=0.005, tolerance=0.05, verdict=Verdict.AGREES)
    return {
        "derivation (built)": d,
        "derivation (fresh)": Derivation(SpringBlock(get_law("ruina"))),
        "coefficient table": table,
        "points": d.points([1e-5, 1e-3]),
        "landau point": d.points([1e-3])[0],
        "mixed points": mixed,
        "hopf point": d.hopf.point(1e-4),
        "hopf normal form": hopf_normal_form(vdp, {"beta": 1.0}, (-0.5, 0.5)),
        "hopf result": hopf,
        "check result": checked,
        "list of checks": ResultList([checked, checked]),
        "regime diagram": regime_diagram(d, np.logspace(-6, -3, 20)),
        "scene": get_scene("skurativskyi2019/static-equilibrium"),
        "scene result": run_scene("skurativskyi2019/static-equilibrium"),
    }


def test_every_result_displays_fast_without_symbolic_work(dieterich, monkeypatch):
    d, table = dieterich
    results = _results(d, table)
    _no_symbolic_work(monkeypatch)
    for name, obj in results.items():
        t0 = time.perf_counter()
        shown = _display(obj)
        elapsed = time.perf_counter() - t0
        assert elapsed < DISPLAY_BOUND_S, (name, elapsed)
        assert "0x" not in shown["text/plain"], (name, shown["text/plain"])   # no <object at 0x...>
        if name != "hopf normal form":      # shows as text and LaTeX
            assert "text/html" in shown, name


def test_large_tables_display_fast():
    n = 1_000_000
    big = CoefficientTable({"V": np.logspace(-7, -2, n), "kc": np.full(n, 2e5), "Lambda": np.linspace(-1, 1, n),
                            "degenerate": np.zeros(n, dtype=bool)}, law="synthetic")
    many = ResultList([{"i": i} for i in range(100_000)])
    for obj in (big, many):
        t0 = time.perf_counter()
        shown = _display(obj)
        assert time.perf_counter() - t0 < DISPLAY_BOUND_S
        assert "more" in shown["text/plain"] and "shown" in shown["text/html"]


def test_derivation_repr_reports_without_deriving():
    d = Derivation(SpringBlock(get_law("ruina")))
    text, page = repr(d), d._repr_html_()
    assert "ruina" in text and "built: nothing yet" in text and "not derived yet" in text
    assert d._coefs == {} and "closed_form" not in vars(d.hopf)           # nothing was derived
    assert "<table>" in page and "Landau coefficient" in page
    d.coefficient("Lambda")
    assert "Lambda" in repr(d) and "derived" in d._repr_html_()


def test_coefficient_table_is_a_dict_with_units_and_a_dataframe(dieterich):
    d, table = dieterich
    assert isinstance(table, dict) and isinstance(table, CoefficientTable)
    assert table.units["kc"] == "N/m" and table.units["Lambda"] == "1/(m^2 s)"
    pd = pytest.importorskip("pandas")
    df = table.to_dataframe()
    assert isinstance(df, pd.DataFrame) and len(df) == 40
    np.testing.assert_array_equal(df["kc [N/m]"].to_numpy(), table["kc"])
    assert df.attrs["units"]["V"] == "m/s" and df.attrs["law"] == "dieterich"
    # criticality column from the sign of Λ (Λ < 0: supercritical)
    assert list(df["criticality"]) == ["supercritical" if lam < 0 else "subcritical" for lam in table["Lambda"]]


def test_to_dataframe_without_pandas_names_the_extra(dieterich, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "pandas", None)          # import pandas -> ImportError
    with pytest.raises(ImportError, match=r"landau-friction\[notebook\]"):
        dieterich[1].to_dataframe()
    with pytest.raises(ImportError, match="notebook"):
        ResultList([dieterich[0].points([1e-3])[0]]).to_dataframe()


def test_a_list_of_results_is_one_table(dieterich):
    d, _ = dieterich
    pts = d.points([1e-5, 1e-4, 1e-3])
    page = pts._repr_html_()
    assert page.count("<table>") == 1 and page.count("<tr>") == 1 + 3      # header + one row per point
    assert "k_c [N/m]" in page and "V [m/s]" in page and "supercritical" in page and "subcritical" in page
    assert len(repr(pts).splitlines()) == 2 + 3


def test_tables_escape_and_cut():
    rows = [{"name": "<b>x</b>", "value": i * 0.5, "n": i} for i in range(100)]
    page = html_table(rows, units={"value": "m"}, max_rows=10)
    assert "&lt;b&gt;" in page and "<b>x</b>" not in page and "value [m]" in page and "90 more rows" in page
    text = text_table(rows[:2])
    assert text.splitlines()[2].split() == ["<b>x</b>", "0.5", "1"]       # integers stay integers
    assert math.isclose(float(text.splitlines()[2].split()[1]), 0.5)
