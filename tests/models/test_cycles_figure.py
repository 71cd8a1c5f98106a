"""The bifurcation diagram of a branch of cycles: what it draws, checked on a branch written here.

The branch is the closed form of the Bautin normal form ṙ = r(μ + r² − r⁴) (Kuznetsov 2004, §8.3):
cycles r² = (1 ± sqrt(1 + 4μ))/2, the unstable (small) one born at the subcritical Hopf point μ = 0
and folding with the stable (large) one at the LPC μ = −1/4, r² = 1/2.
"""

from __future__ import annotations

import numpy as np

from landau.analyses.cycles import BranchTable, HopfMark, SpecialPoint, branch_csv, branch_document
from landau.report.cycles_figure import MARKERS, STYLES, plot_cycle_branch, runs


def _bautin_branch() -> BranchTable:
    # along the branch from the Hopf point: the small (unstable) cycle to the fold, then the large (stable) one
    s = np.linspace(-1.0, 1.0, 41)
    r2 = 0.5 * (1 + s)                       # r² from 0 (Hopf) through 1/2 (fold) to 1
    mu = r2 ** 2 - r2                        # μ = r⁴ − r² on the branch
    stable = r2 > 0.5                        # d(μ + r² − r⁴)/dr² = 1 − 2r² < 0: the large cycle is stable
    period = np.full(s.size, 2 * np.pi)
    fold = SpecialPoint("LPC", -0.25, 2 * np.pi, np.sqrt(0.5), 1.0)
    return BranchTable("bautin normal form", "mu", "x", "", mu, period, np.sqrt(r2), stable, (fold,),
                       HopfMark(0.0, 1.0, True))


def test_runs_split_by_stability_and_share_their_ends():
    assert runs(np.array([False, False, True, True, True, False])) == [(0, 3, False), (2, 6, True), (5, 6, False)]
    assert runs(np.array([True])) == [(0, 1, True)]


def test_diagram_draws_stable_solid_unstable_dashed_and_marks_the_fold_and_hopf_point():
    from matplotlib.figure import Figure

    table = _bautin_branch()
    fig = Figure()
    drawn = plot_cycle_branch(table, fig=fig)
    ax_a, ax_t = drawn["axes"]
    assert drawn["lines"] == 2 and drawn["special"] == {"LPC": 1} and drawn["hopf"]
    lines = ax_a.get_lines()
    cycles = [ln for ln in lines if ln.get_linestyle() in ("-", "--") and len(ln.get_xdata()) > 2]
    styles = {ln.get_linestyle(): ln for ln in cycles}
    # the unstable run is the small cycle (r² ≤ 1/2 up to the shared end point), dashed; the stable run solid
    assert set(styles) == {STYLES[True], STYLES[False]}
    assert np.max(styles["--"].get_ydata()) <= np.sqrt(0.5) + 0.02
    assert np.min(styles["-"].get_ydata()) >= np.sqrt(0.5) - 0.02
    # the fold marker at (μ, r) = (−1/4, sqrt(1/2)), the Hopf point at (0, 0)
    marks = {ln.get_marker(): (ln.get_xdata()[0], ln.get_ydata()[0]) for ln in lines if len(ln.get_xdata()) == 1}
    assert np.allclose(marks[MARKERS["LPC"]], (-0.25, np.sqrt(0.5)))
    assert np.allclose(marks["s"], (0.0, 0.0))
    # the equilibrium: stable (solid) below μ = 0, unstable (dashed) above, at amplitude 0
    eq = [ln for ln in lines if len(ln.get_xdata()) == 2 and np.all(np.asarray(ln.get_ydata()) == 0)]
    below = [ln for ln in eq if max(ln.get_xdata()) <= 0]
    above = [ln for ln in eq if min(ln.get_xdata()) >= 0]
    assert below[0].get_linestyle() == "-" and above[0].get_linestyle() == "--"
    # the period panel: the Hopf point at 2π/ω
    tmarks = [ln for ln in ax_t.get_lines() if ln.get_marker() == "s"]
    assert np.isclose(tmarks[0].get_ydata()[0], 2 * np.pi)


def test_document_and_csv_carry_the_branch():
    table = _bautin_branch()
    doc = branch_document(table)
    assert doc["points"] == 41 and doc["special_points"][0]["kind"] == "LPC"
    assert "LPC  mu = -0.25" in doc["text"]
    rows = branch_csv(table).splitlines()
    assert rows[0] == "mu,period,amplitude_x,stable" and len(rows) == 42
    assert float(rows[1].split(",")[0]) == table.p[0]
