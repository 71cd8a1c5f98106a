"""Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019), Nonlinear Dyn. 98:1795 (verify/skurativskyi).

Fast, decisive checks: the Sec. 5 closed forms to the printed digits, the compiled
integrator against a closed-form forced linear oscillator and against the hybrid engine,
the Lyapunov machinery against the exact exponent of the linear case, and the first
detachment bracket of Fig. 8.  Long sweeps: tests/forced_oscillator/test_skurativskyi_slow.py (-m slow).
"""

import math

import numpy as np
import pytest
from scipy.linalg import expm

from landau.errors import InputError
from landau.laws.velocity import regularised_coulomb
from landau.scenes import run_scene
from landau.verify.skurativskyi import approx
from landau.verify.skurativskyi.analysis import attractor, redundancy, tsallis_q
from landau.verify.skurativskyi.model import PAPER, Params, saltation_matrix
from landau.verify.skurativskyi.simulate import run


# ------------------------------------------------------------------ friction law
def test_regularised_friction_and_coulomb_limit():
    # F_R of eq. (1) with the identified c, T, eps of Sec. 2 (the model's default law)
    F = regularised_coulomb()
    assert PAPER.friction.defaults() == F.defaults() == {"c": 6.6511, "T": 0.63133, "eps": 1e-6}
    v = 1e-3
    assert F(v) == pytest.approx(6.6511 * v + 0.63133 * v / math.sqrt(v * v + 1e-12), rel=1e-15)
    # ε → 0: far from v = 0 the regularised force tends to c v + T sgn v with error ~ T ε²/(2v²)
    coulomb_limit = F.with_defaults(eps=0.0)
    assert F(-1e-2) == pytest.approx(coulomb_limit(-1e-2), abs=0.63133 * 1e-8)
    assert coulomb_limit(-1e-2) == pytest.approx(-6.6511e-2 - 0.63133, rel=1e-15)
    assert np.isnan(coulomb_limit(0.0))  # set-valued at v = 0
    assert F.slope(0.0) == pytest.approx(6.6511 + 0.63133 / 1e-6, rel=1e-12)
    with pytest.raises(InputError):
        Params(T=-1.0)


# ------------------------------------------------------------------ Sec. 5 closed forms
def test_static_equilibrium_printed_digits():
    # Sec. 5: X0 = -2.0807e-3 m (5 significant digits printed)
    assert round(approx.static_equilibrium(PAPER) * 1e3, 4) == -2.0807


def test_linearised_solution_eq4_and_grazing_15657():
    s = approx.linear_solution(PAPER, 14.0)
    # eq. (4): x = -2.0807e-3 - 4.7779e-10 cos ωt + 4.2606e-6 sin ωt (at ω = 14, Fig. 9)
    assert s.A2 == pytest.approx(-4.7779e-10, abs=0.00005e-10)
    assert s.A1 == pytest.approx(4.2606e-6, abs=0.00005e-6)
    assert round(approx.grazing_linear(PAPER), 3) == 15.657


def test_harmonic_balance_eq6_and_grazing_12789():
    A, alpha = approx.harmonic_amplitude(PAPER, 14.0)
    # eq. (6): x = X0 - 3.5707e-10 cos ωt + 3.6833e-6 sin ωt
    assert A * math.cos(alpha) == pytest.approx(3.6833e-6, abs=0.00005e-6)
    assert A * math.sin(alpha) == pytest.approx(3.5707e-10, abs=0.00005e-10)
    br = approx.grazing_harmonic_branches(PAPER)
    assert round(br["cos_alpha_negative"], 3) == 12.789  # the sign choice that reproduces the paper
    assert br["cos_alpha_positive"] is None


def test_scenes_agree_with_paper():
    for name in ("static-equilibrium", "grazing-linear", "grazing-harmonic"):
        doc = run_scene(f"skurativskyi2019/{name}")
        assert doc["agrees"], doc
    with pytest.raises(InputError):
        run_scene("skurativskyi2019/static-equilibrium", {"omega": 3.0})  # not a parameter of this scene


# ------------------------------------------------------------------ integrator
def _linear_exact(p: Params, t: float, y0):
    """m ẍ + c ẋ + k x = m0e ω² sin ωt (no contact, T = 0): particular + homogeneous."""
    m, c, k, w, F = p.m, p.c, p.k, p.omega, p.m0e * p.omega ** 2
    # x_p = a sin ωt + b cos ωt
    M = np.array([[k - m * w * w, -c * w], [c * w, k - m * w * w]])
    a, b = np.linalg.solve(M, [F, 0.0])
    yp = lambda s: np.array([a * np.sin(w * s) + b * np.cos(w * s), a * w * np.cos(w * s) - b * w * np.sin(w * s)])
    Asys = np.array([[0.0, 1.0], [-k / m, -c / m]])
    return yp(t) + expm(Asys * t) @ (np.asarray(y0) - yp(0.0))


def test_compiled_integrator_against_closed_form_linear_oscillator():
    # obstacle moved out of reach (x_I = 1 m) and T = 0: eq. (1) is linear
    p = PAPER.with_(xI=1.0, T=0.0, omega=16.0)
    y0 = [1e-3, 0.0]
    r = run(p, 10, y0, rtol=1e-10, atol=(1e-15, 1e-13))
    exact = _linear_exact(p, r.t_final, y0)
    # 5th-order method at rtol 1e-10 over ~4 s: global error a few 1e-13 m
    assert np.abs(r.y_final - exact).max() < 1e-11
    assert len(r.impacts) == 0 and len(r.strobe_t) == 11  # section points at t = 2πi/ω, i = 0..10
    assert r.strobe_t[-1] == pytest.approx(10 * p.period, rel=1e-14)


def test_lyapunov_exponent_of_linear_case_is_minus_c_over_2m():
    # underdamped linear oscillator: both exponents are -c/(2m) = -0.3807 1/s; the bounded
    # rotation of the tangent vector contributes ≤ log(ω0 scale ratio)/(N T) ≈ 0.01 over 1000 periods
    p = PAPER.with_(xI=1.0, T=0.0, omega=16.0)
    lam = run(p, 1000, [1e-3, 0.0], rtol=1e-8, lyapunov=True).lyapunov
    assert lam == pytest.approx(-p.c / (2 * p.m), abs=0.02)


def test_contact_switching_exact_and_engine_agrees():
    from support_dopri5 import CompiledDOPRI5

    from landau.verify.hybrid import EngineOptions, simulate
    from landau.verify.skurativskyi.simulate import hybrid_model

    p = PAPER.with_(omega=16.0)
    y0 = run(p, 4, rtol=1e-8).y_final  # on the 3-impact attractor (phase 0)
    r = run(p, 1, y0, rtol=1e-9, atol=(1e-13, 1e-11))
    # the re-taken step lands on x = x_I to rounding before the projection
    assert r.max_mismatch <= 1e-17
    assert len(r.impacts) == 3 and np.all(r.impact_v > 0)  # impacts: x crosses x_I upwards
    sol = simulate(hybrid_model(p), "free" if y0[0] < p.xI else "contact", y0, (0.0, p.period),
                   CompiledDOPRI5(rtol=1e-9, atol=(1e-13, 1e-11), first_step=1e-5, max_step=0.01),
                   EngineOptions(record=False))
    imp = sol.events.times(guard="impact")
    # the engine locates roots on the Hermite interpolant and does not restart the step on the
    # surface; both runs carry the rtol-1e-9 error of the impact times (≈ 1e-8 s, work-precision
    # table), so they agree to a few 1e-8 s (measured 1.1e-8), far below any T_j of Fig. 3b
    assert len(imp) == len(r.impacts)
    assert np.abs(imp - r.impacts).max() < 5e-8
    assert np.abs((sol.y_final - r.y_final) / [1e-3, 1e-2]).max() < 1e-6


def test_saltation_is_identity_at_contact_switching():
    # F_I is continuous at x = x_I (δ^{3/2} → 0): S = I + (f+ - f-) n^T/(n·f-) = I
    S = saltation_matrix(PAPER, 0.3, [PAPER.xI, 4e-3])
    assert np.abs(S - np.eye(2)).max() < 1e-7


def test_bad_input_is_named():
    with pytest.raises(InputError):
        Params(m=-1.0)
    with pytest.raises(InputError):
        Params(eps=0.0)
    with pytest.raises(InputError):
        run(PAPER, 0)
    with pytest.raises(InputError):
        PAPER.with_(mass=3.0)


# ------------------------------------------------------------------ Fig. 8: first detachment
def test_permanent_contact_at_14_and_one_impact_per_period_at_14_1():
    # Fig. 8 / Sec. 5: at ω = 14 the cart stays on the obstacle; at 14.1 one impact per period
    a14 = attractor(14.0, n_transient=40, n_keep=10)
    assert a14.impacts_per_period == 0 and np.all(a14.x_section > PAPER.xI)
    a141 = attractor(14.1, n_transient=40, n_keep=10)
    assert a141.impacts_per_period == 1


# ------------------------------------------------------------------ Tsallis q (Sec. 4)
def test_tsallis_redundancy_limits():
    p = np.array([0.5, 0.25, 0.125, 0.125])
    # q → 1 is the Shannon redundancy 1 - H/log N (continuity of the closed form)
    assert redundancy(1.0 + 1e-6, p) == pytest.approx(redundancy(1.0, p), abs=1e-5)
    assert redundancy(0.7, np.full(8, 1 / 8)) == pytest.approx(0.0, abs=1e-12)  # equiprobable: R_T = 0
    with pytest.raises(InputError):
        tsallis_q(np.full(30, 0.1))  # periodic attractor: one bin


# ------------------------------------------------------------------ sweeps: local vs dask, streamed
def test_sweep_dask_matches_local_and_streams(tmp_path):
    from distributed import Client, LocalCluster

    from landau.verify.skurativskyi.sweep import SweepSpec, run_sweep

    om = [21.7, 21.75, 21.8]
    spec = SweepSpec(n_first=30, n_step=10, n_keep=6, rtol=1e-7, overlap=1)
    local = run_sweep(om, "down", out=tmp_path / "local", spec=spec, workers=1, chunk_size=2, progress=False)
    import xarray as xr

    with xr.open_dataset(tmp_path / "local" / "sweep.nc") as stored:  # written to netCDF, every point ok
        assert list(stored.omega.values) == sorted(om) and (stored.status == "ok").all()
    with LocalCluster(n_workers=1, processes=False, dashboard_address=None) as cluster, Client(cluster) as client:
        remote = run_sweep(om, "down", out=tmp_path / "dask", spec=spec, scheduler=client, chunk_size=2,
                           progress=False)
    assert list(local.params) == [21.8, 21.75, 21.7]
    for a, b in zip(local.values, remote.values, strict=True):
        # same chunks, same warm starts, same deterministic integrator: identical results
        assert np.array_equal(a.x_section, b.x_section)
    with pytest.raises(InputError):  # the folder holds a different sweep
        run_sweep([20.0], "down", out=tmp_path / "local", spec=spec, workers=1, progress=False)
