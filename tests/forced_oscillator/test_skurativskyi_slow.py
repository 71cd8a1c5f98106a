"""Long verification runs for Skurativskyi et al. (2019), Nonlinear Dyn. 98:1795 (opt-in: pytest -m slow).

Numbers asserted are the paper's (Sec. 4–5, Figs 3–5, 7, 8); tolerances are explained at
each assertion.  The continuation protocol is the paper's (100 periods of transient at the
first ω, 50 after each step), at rtol 1e-8 (locations converged to 1e-4 rad/s between
rtol 1e-7 and 1e-9, see the report).
"""

import numpy as np
import pytest

from landau.verify.skurativskyi.analysis import (
    attractor,
    continuation,
    first_detachment,
    locate_grazing,
    locate_period_doubling,
    section_period,
    tsallis_q,
)
from landau.verify.skurativskyi.sweep import SweepSpec, run_sweep

pytestmark = pytest.mark.slow


def test_first_detachment_between_14_0_and_14_1_to_1e_3():
    # Sec. 5 / Fig. 8: permanent contact at ω = 14, one impact per period at 14.1
    loc = first_detachment(14.0, 14.1, 1e-3)
    assert 14.0 < loc.lo < loc.hi < 14.1 and loc.hi - loc.lo <= 1e-3


def test_impact_adding_one_by_one_to_five_at_17_5():
    # Fig. 8 / Sec. 5: impacts per period grow one by one up to five by ω = 17.5 (period-1 orbits)
    om = np.round(np.arange(14.1, 17.51, 0.1), 4)
    atts = continuation(om, None, 60, 30, 10, rtol=1e-7)
    ipp = np.array([a.impacts_per_period for a in atts])
    assert ipp[0] == 1 and ipp[-1] == 5
    assert np.all(np.diff(ipp) >= 0) and np.all(np.diff(ipp) <= 1)  # one by one
    assert set(ipp) == {1, 2, 3, 4, 5}


@pytest.fixture(scope="module")
def sweeps(tmp_path_factory):
    om = np.round(np.arange(19.9, 23.2 + 1e-9, 0.05), 6)
    spec = SweepSpec(n_first=100, n_step=50, n_keep=60, rtol=1e-8)
    out = tmp_path_factory.mktemp("sk")
    # chunks of 17 ω (4 chunks): the cut these numbers were established with.  The second
    # period doubling below is found from the warm start at 20.3, and 20.38 lies so close to it
    # (multiplier near -1) that a change of that start at the 1e-8 level (another cut) can move
    # the verdict after 150 transient periods
    return {d: run_sweep(om, d, out=out / d, spec=spec, workers=2, chunk_size=17, progress=False)
            for d in ("up", "down")}


def _at(res, w):
    return next(a for a in res.values if abs(a.omega - w) < 1e-9)


def _n_section(a, tol=1e-8):
    xs = np.sort(a.x_section)
    return 1 + int(np.count_nonzero(np.diff(xs) > tol))


def test_period_doubling_cascade_inside_20_20_5(sweeps):
    up = sweeps["up"]
    # Fig. 4: period 1 at 20.0, period 2 after the first doubling, chaos before 20.5 (TLE > 0)
    assert _n_section(_at(up, 20.0)) == 1
    assert _n_section(_at(up, 20.3)) == 2
    assert _n_section(_at(up, 20.45)) > 8
    # the second doubling: continued from the period-2 attractor at 20.3 the section has period 4
    # at 20.38 (ours: period 2 on 20.28-20.36, period 4 on 20.37-20.39, aperiodic from 20.40)
    a = attractor(20.34, _at(up, 20.3).y_end, 150, 64)
    a = attractor(20.38, a.y_end, 150, 64)
    assert section_period(a, tol=1e-8, max_period=32) == 4


def test_grazing_cascade_and_ratio(sweeps):
    up = sweeps["up"]
    # Sec. 4: grazing bifurcations at 20.8586, 21.5085, 23.0702 (Fig. 3b): impacts/period change
    # (ours: 20.851-20.858 — the attractor below the first is chaotic, so the bracket depends on the
    # warm start —, 21.513, 23.063; converged to 1e-4 over rtol 1e-7..1e-9)
    # 2 → 5/3 → 3/2 → 4/3 → 1 along the up sweep; located by bisection to 1e-4 from the attractor
    # at the lower end.  Tolerance 0.015 rad/s: the paper's own integration moves such points by
    # ~0.01 at rtol 1e-6; ours are converged to 1e-4 between rtol 1e-7 and 1e-9.
    found = []
    for lo, hi, paper in ((20.85, 20.9, 20.8586), (21.5, 21.55, 21.5085), (23.05, 23.1, 23.0702)):
        L = locate_grazing(lo, hi, _at(up, lo).y_end, tol=1e-4)
        assert abs(L.value - paper) < 0.015
        found.append(L.value)
    D = np.diff(found)
    # paper: D3/D2 = 1.5617/0.6499 = 2.403; ours 2.34-2.37 (geometric ratio ≈ 2.4 within 5 %)
    assert D[1] / D[0] == pytest.approx(2.403, rel=0.05)


def test_coexistence_near_22_71(sweeps):
    # Sec. 4, Fig. 3: forward and backward sweeps end on different attractors near 22.71-22.75
    up, dn = sweeps["up"], sweeps["down"]
    diff = [w for w in (22.7, 22.75) if abs(_at(up, w).impacts_per_period - _at(dn, w).impacts_per_period) > 1e-9]
    assert diff


def test_lyapunov_positive_in_chaos_and_near_zero_at_period_doubling(sweeps):
    up = sweeps["up"]
    chaos = attractor(20.45, _at(up, 20.45).y_end, 50, 600, lyapunov=True)
    assert chaos.lyapunov > 0.1  # Fig. 5: λ1 > 0 in the chaotic window (20.4, 20.5) (ours: +1.06)
    y = _at(up, 20.1).y_end
    per1 = attractor(20.1, y, 100, 400, lyapunov=True)
    assert per1.lyapunov < -1.0  # a stable period-1 orbit away from the bifurcation (ours: -3.63)
    # the first doubling (section period 1 → 2), located by bisection, lies in (20, 20.5) (Fig. 4);
    # there the multiplier crosses -1, so λ1 = log|μ|/T → 0 (Fig. 5): measured |λ1| ≲ 0.1 within
    # 0.01 rad/s of the doubling against 3.6 at 20.1 (finite-time and slow-transient bias)
    pd = locate_period_doubling(20.1, 20.3, y, tol=2e-3)
    assert 20.0 < pd.lo < pd.hi < 20.5
    lam = attractor(pd.value, y, 300, 400, lyapunov=True).lyapunov
    assert abs(lam) < 0.1 * abs(per1.lyapunov)


def test_tsallis_q_below_one_at_20_465(sweeps):
    up = sweeps["up"]
    a = attractor(20.465, _at(up, 20.45).y_end, 100, 1000)
    fit = tsallis_q(a.intervals)
    assert fit.q < 1.0  # Sec. 4, Fig. 6: q = 0.62 (rare events dominate)


def test_sweep_resumes_after_interruption(tmp_path):
    om = np.round(np.arange(21.6, 21.8 + 1e-9, 0.05), 6)
    spec = SweepSpec(n_first=40, n_step=20, n_keep=10, rtol=1e-7, overlap=1)
    full = run_sweep(om, "up", out=tmp_path / "a", spec=spec, workers=1, progress=False)
    # interrupt: keep the first two points of the single chunk, the rest pending again
    import xarray as xr

    f = tmp_path / "a" / "sweep.nc"
    with xr.open_dataset(f) as stored:
        ds = stored.load()
    ds["status"] = ds.status.astype(object)
    ds["status"][2:] = "pending"
    ds.to_netcdf(f)
    again = run_sweep(om, "up", out=tmp_path / "a", spec=spec, workers=1, progress=False)
    for a, b in zip(full.values, again.values, strict=True):
        assert np.allclose(a.x_section, b.x_section, rtol=0, atol=1e-12)
