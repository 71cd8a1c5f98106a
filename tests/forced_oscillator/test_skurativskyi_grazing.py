"""Grazing margins of Skurativskyi et al. (2019), Nonlinear Dyn. 98:1795, Sec. 4 / Fig. 3b
(verify/skurativskyi/grazing.py).  Fast checks; the located cascade against the paper's
(20.59, 20.8586, 21.5085, 23.0702) is in tests/forced_oscillator/test_skurativskyi_grazing_slow.py (-m slow).
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from landau.errors import InputError
from landau.verify.skurativskyi.analysis import continuation
from landau.verify.skurativskyi.grazing import locate_grazing_margin, maxima, velocity_stops
from landau.verify.skurativskyi.model import PAPER, field


@pytest.fixture(scope="module")
def period3():
    """The period-3 orbit with 6 impacts of the window above ω ≈ 20.61 (continued downward
    from 20.65, where every start settles on it)."""
    return continuation([20.65, 20.63, 20.62], None, 300, 60, 3)[-1]


def test_maxima_agree_with_scipy_dop853_events(period3):
    # independent computation: scipy DOP853 on the Python field with an event ẋ = 0 (↓),
    # rtol 1e-12, no contact switching handling at all (the field is C¹ across x = x_I)
    p = PAPER.with_(omega=period3.omega)
    m = maxima(p.omega, period3.y_end, 3, 200)
    ev = lambda t, y: y[1]
    ev.direction = -1
    sol = solve_ivp(lambda t, y: field(p, t, y), (0.0, 3 * p.period), period3.y_end, method="DOP853",
                    rtol=1e-12, atol=[1e-15, 1e-13], events=ev)
    ref = np.sort(sol.y_events[0][:, 0])
    assert len(ref) == len(m.x) == 7          # 6 impacts and one free-flight maximum per 3 periods
    # measured difference 0.2 nm (our run is at rtol 1e-8); 5 nm is 1/3000 of the 15 µm
    # margin, i.e. 4e-6 rad/s of ω at dg/dω ≈ 1.3 mm/(rad/s)
    assert np.max(np.abs(np.sort(m.x) - ref)) < 5e-9
    assert int(np.count_nonzero(~m.impacting)) == 1
    assert m.margin == pytest.approx(p.xI - ref[ref < p.xI].max(), abs=5e-9)


def test_grazing_margin_vanishes_where_the_impact_count_changes(period3):
    # two independent criteria for the lower edge of the period-3 window: bisection on the
    # impact count of the continued orbit, and the straight-line zero of its free margin g(ω)
    # sampled on the orbit side; at a grazing both coincide (at a saddle-node or a crisis the
    # orbit would end with g > 0).  tol 1e-3 keeps this fast; the fit is local (1e-4 spacing).
    G = locate_grazing_margin(period3.omega, 20.60, period3.y_end, tol=1e-3, n_keep=42, n_transient=120)
    assert (G.period, G.impacts, G.kind) == (3, 6, "impact added")
    assert G.lo - 1e-4 <= G.extrapolated <= G.hi + 1e-4
    ws, ss = np.array(G.samples).T
    resid = ss - np.polyval(np.polyfit(ws, ss, 1), ws)
    assert np.max(np.abs(resid)) < 0.01 * np.ptp(ss)  # linear: a smooth family through the grazing


def test_near_stops_agree_with_scipy_dop853_events():
    # the period-3 orbit with 4 impacts at ω = 23.06 (continued up from 22.9 as in the up sweep
    # of Fig. 3) nearly stops once per 3 periods (ẋ ≈ −0.17 mm/s): it ends at ω ≈ 23.064 where
    # that near-stop touches ẋ = 0 (friction grazing, see the slow test).  Independent check of
    # the extremal velocities: scipy DOP853 (rtol 1e-12) with an event on ẍ = 0.
    a = continuation(np.round(np.arange(22.9, 23.06 + 1e-9, 0.02), 4), None, 100, 50, 3)[-1]
    assert a.impacts_per_period == pytest.approx(4 / 3)
    p = PAPER.with_(omega=a.omega)
    s = velocity_stops(p.omega, a.y_end, 3, 2000)
    ev = lambda t, y: field(p, t, y)[1]
    sol = solve_ivp(lambda t, y: field(p, t, y), (0.0, 3 * p.period), a.y_end, method="DOP853",
                    rtol=1e-12, atol=[1e-15, 1e-13], events=ev)
    ref = np.sort(np.abs(sol.y_events[0][:, 1]))
    ours = np.sort(np.abs(s.v))
    assert len(ours) == len(ref)
    # the near-stop: measured 2.6e-8 m/s apart (0.169 mm/s; parabolic refinement of samples
    # 0.15 ms apart); 1e-7 m/s is 0.06 % of it, i.e. 2e-6 rad/s at the slope 47 mm/s per rad/s
    assert abs(s.margin - ref[0]) < 1e-7
    # all extrema (the large ones lie in the fast contact phases: parabola error ~1e-5 m/s)
    assert np.allclose(ours, ref, rtol=1e-3, atol=1e-7)
    assert 1e-4 < s.margin < 3e-4   # a near-stop, well above the friction regularisation ε = 1e-6 m/s


def test_bad_input():
    with pytest.raises(InputError):
        maxima(20.6, [PAPER.xI - 1e-3, 0.0], 0)
    a = continuation([20.45], None, 100, 1, 1)[-1]        # chaotic (Fig. 5: λ1 > 0)
    with pytest.raises(InputError, match="not periodic"):
        locate_grazing_margin(20.45, 20.44, a.y_end, n_keep=42)


def test_sweep_enters_the_period_7_window_from_the_chaotic_band():
    # the up-sweep from inside the chaotic band (Fig. 4/5: λ1 > 0 on 20.44–20.59) meets the period-7
    # window (14 impacts) on the grid of multiples of the step, entered from an aperiodic attractor
    # one step below; the bracket holds the published first grazing 20.59 ± 0.015 (Fig. 3b).
    # Independent of the sweep's protocol: the returned state, continued at rtol 1e-10 (not 1e-8)
    # over 100 + 84 periods, is the period-7 orbit with 14 impacts.
    from landau.verify.skurativskyi.analysis import attractor, section_period, sweep_to_window
    E = sweep_to_window(20.58, 7, 14)
    assert (E.gone_period, E.period, E.impacts) == (0, 7, 14)
    assert E.orbit_omega - E.gone_omega == pytest.approx(E.step, rel=1e-9)
    assert E.orbit_omega / E.step == pytest.approx(round(E.orbit_omega / E.step), abs=1e-9)
    assert 20.59 - 0.015 < E.gone_omega < E.orbit_omega < 20.59 + 0.015
    a = attractor(E.orbit_omega, E.y_orbit, 100, 84, rtol=1e-10)
    assert section_period(a, 1e-6, 24) == 7 and a.impacts_per_period * 7 == pytest.approx(14)


def test_sweep_strides_along_a_settled_orbit_and_resolves_the_change_to_one_step():
    # along the period-1 orbit with 2 impacts (19.34–20.25, Fig. 4) the stride grows to 32 steps;
    # the first period doubling is still met across a single step of 0.0025, at the doubling
    # located independently by bisection on a persistent period-2 alternation (is_doubled,
    # 300 transient periods).  Tolerance 5e-3 rad/s: the sweep keeps 50 + 8 periods per point, so
    # just below the doubling (multiplier → −1) the slowly decaying alternation can exceed the
    # section tolerance 1e-6 m a little early.
    from landau.verify.skurativskyi.analysis import attractor, locate_period_doubling, sweep_to_window
    E = sweep_to_window(19.9, 2, 4)
    assert E.orbit_omega - E.gone_omega == pytest.approx(E.step, rel=1e-9) and E.gone_period == 1
    n_grid = round((E.orbit_omega - E.start) / E.step)
    assert E.points < n_grid / 4                  # 143 grid steps, 26 attractors
    y = attractor(20.1, None, 200, 1).y_end
    pd = locate_period_doubling(20.1, 20.3, y, tol=2e-3)
    assert abs(E.orbit_omega - pd.value) < 5e-3


def test_sweep_to_window_bad_input_and_no_window():
    from landau.verify.skurativskyi.analysis import sweep_to_window
    with pytest.raises(InputError):
        sweep_to_window(20.58, step=0.0)
    with pytest.raises(InputError, match="multiple"):
        sweep_to_window(20.58, 7, 14, n_keep=30)
    with pytest.raises(InputError, match="no period-7"):   # the band has no period-7 orbit below 20.59
        sweep_to_window(20.58, 7, 14, stop=20.59)


def test_cascade_scene_bracket_is_both_or_neither():
    from landau.scenes import run_scene
    with pytest.raises(InputError, match="both"):
        run_scene("skurativskyi2019/first-cascade-grazing", {"orbit_omega": 20.6})
    with pytest.raises(InputError, match="step"):
        run_scene("skurativskyi2019/first-cascade-grazing", {"step": 0.0})
