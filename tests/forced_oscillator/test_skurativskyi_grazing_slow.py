"""The grazing cascade of Skurativskyi et al. (2019), Nonlinear Dyn. 98:1795, Sec. 4 / Fig. 3b,
located on grazing margins (verify/skurativskyi/grazing.py; opt-in: pytest -m slow, ~3 min).

Paper: grazing bifurcations at f = (20.59, 20.8586, 21.5085, 23.0702) rad/s, spacings
D = (0.2686, 0.6499, 1.5617), ratios D2/D1 = 2.419, D3/D2 = 2.403.

Ours, along the up sweep (the paper's red diagram), every point an edge of a periodic window
at which the orbit grazes a non-smooth surface (margin → 0 linearly, bisection and the
straight-line zero agree to < 1e-4 rad/s, identical at rtol 1e-8 and 1e-9):
  f1 = 20.5989  the up-sweep attractor leaves the chaotic band: lower edge of the period-7
                window (14 impacts), a free maximum touches x = x_I
  f2 = 20.8577  lower edge of the period-3 window with 5 impacts (obstacle grazing)
  f3 = 21.5143  lower edge of the period-2 window with 3 impacts (obstacle grazing)
  f4 = 23.0637  upper end of the period-3 window with 4 impacts: a near-stop of the cart
                touches ẋ = 0 (grazing of the dry-friction switching surface)
"""

import numpy as np
import pytest

from landau.scenes import run_scene
from landau.verify.skurativskyi.analysis import continuation, section_period
from landau.verify.skurativskyi.grazing import locate_friction_grazing, locate_grazing_margin

pytestmark = pytest.mark.slow

PAPER_F = np.array([20.59, 20.8586, 21.5085, 23.0702])
# Tolerance per point: 0.015 rad/s — the paper's 20.59 is printed to ±0.005, and a point
# located at the paper's (unknown) integration tolerance moves by ~0.01 rad/s (located
# at rtol 1e-6; the period-7 edge moves by 5e-4 between rtol 1e-7 and 1e-8); our other three
# points sit 0.0009–0.0065 from the paper's.
TOL = 0.015


def _orbit(path):
    return continuation(path, None, 300, 60, 7)[-1].y_end


@pytest.fixture(scope="module")
def cascade():
    pts = []
    for path, gone in (([20.603, 20.6], 20.595), ([20.9, 20.87, 20.862], 20.85), ([21.6, 21.55, 21.53], 21.50)):
        pts.append(locate_grazing_margin(path[-1], gone, _orbit(path), tol=1e-4))
    up = list(np.round(np.arange(22.9, 23.06 + 1e-9, 0.02), 4))
    fric = locate_friction_grazing([23.062, 23.063, 23.0633, 23.0635, 23.0636], _orbit(up))
    return pts, fric


def test_obstacle_grazings_are_grazings(cascade):
    pts, _ = cascade
    for G, (period, impacts) in zip(pts, ((7, 14), (3, 5), (2, 3)), strict=True):
        assert (G.period, G.impacts, G.kind, G.orbit_side) == (period, impacts, "impact added", "above")
        # the free margin vanishes linearly at the bracket: grazing, not a fold or a crisis
        assert G.lo - 2e-4 <= G.extrapolated <= G.hi + 2e-4


def test_friction_grazing_ends_the_four_thirds_window(cascade):
    _, F = cascade
    assert F.impacts_per_period == pytest.approx(4 / 3)
    # the orbit still exists at the last sample (0.005 mm/s from stopping) and the zero of the
    # near-stop margin lies just beyond it: within 5e-4 rad/s (it is gone by 23.0640)
    assert F.samples[-1][0] < F.omega < F.samples[-1][0] + 5e-4
    ms = np.array(F.samples)[:, 1]
    assert np.all(np.diff(ms) < 0)


def test_grazing_cascade_against_the_paper_and_spacing_ratios(cascade):
    pts, F = cascade
    f = np.array([G.value for G in pts] + [F.omega])
    assert np.all(np.abs(f - PAPER_F) < TOL), f
    D = np.diff(f)
    ratios = D[1:] / D[:-1]
    # the ratios a ±TOL error per point allows around the paper's points (box corners):
    # D2/D1 ∈ [2.08, 2.85], D3/D2 ∈ [2.22, 2.60]; ours 2.54 and 2.36 (paper 2.419, 2.403)
    Dp = np.diff(PAPER_F)
    lo = [(Dp[i + 1] - 2 * TOL) / (Dp[i] + 2 * TOL) for i in range(2)]
    hi = [(Dp[i + 1] + 2 * TOL) / (Dp[i] - 2 * TOL) for i in range(2)]
    assert np.all((np.array(lo) < ratios) & (ratios < np.array(hi))), ratios


def test_both_sweeps_leave_the_chaotic_band_at_the_first_grazing(cascade):
    pts, _ = cascade
    f1 = pts[0].value
    # sweeps in steps of 5e-4 (the paper's Fig. 3 protocol: 100 / 50 transient periods)
    om = np.round(np.arange(20.5950, 20.6001, 0.0005), 5)
    up = continuation(om, None, 100, 50, 84)
    per = np.array([section_period(a, 1e-6, 24) for a in up])
    assert np.all(per[om > f1 + 1e-4] == 7)   # periodic at once above the grazing
    assert np.all(per[om < f1 - 1e-4] == 0)   # chaotic band below it
    # down: the period-3 window (6 impacts) ends at its own grazing near 20.608 (an impact is
    # added, then the sweep falls onto the coexisting period-7 orbit), period 7 down to f1,
    # chaos below — the same boundary in both directions (no hysteresis at 5e-4)
    om = np.round(np.arange(20.615, 20.5949, -0.0005), 5)
    dn = continuation(om, _orbit([20.65, 20.63]), 100, 50, 84)
    per = np.array([section_period(a, 1e-6, 24) for a in dn])
    assert per[0] == 3 and 7 in per
    assert np.all(per[om > f1 + 1e-4][-10:] == 7) and np.all(per[om < f1 - 1e-4] == 0)


def test_scene_first_cascade_grazing(cascade):
    # the scene derives its bracket (no window fitted to 20.59): an up-sweep from the first
    # detachment enters the period-7 window from the chaotic band; the grazing it locates there is
    # the one located from the hand-placed bracket [20.595, 20.6] of the fixture (same root: both
    # brackets are narrower than tol = 1e-4 and hold it; measured: the same dyadic bisection points,
    # the same value 20.5989453125)
    doc = run_scene("skurativskyi2019/first-cascade-grazing")
    assert doc["agrees"] and doc["period"] == 7 and doc["kind"] == "impact added", doc
    win = doc["window"]
    assert win["gone_omega"] <= doc["lo"] < doc["hi"] <= win["orbit_omega"] and win["entered_from_period"] == 0
    assert win["passed_over"] == []
    assert abs(doc["value"] - cascade[0][0].value) < 1e-4
    assert doc["lo"] - 2e-4 <= doc["linear_root"] <= doc["hi"] + 2e-4
