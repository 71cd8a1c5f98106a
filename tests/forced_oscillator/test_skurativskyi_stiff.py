"""The stiff (SDIRK4) stick-phase stepper of the Skurativskyi (2019) integrator
(verify/skurativskyi/sdirk.py, used by run(method="mixed"), the default).

Checks: the Hairer–Wanner SDIRK4 tableau (order conditions, L-stability); the scalar stage
solve on the non-Lipschitz Hertz-damping cusp; the quasi-static creep of the regularised
friction law (closed form) out of contact; and the stick-dominated regime ω = 15 of
eq. (1) against the explicit path and a tight-tolerance explicit reference.  Speed is
measured in verify/benchmarks/skurativskyi_work_precision.py, not here.
"""

import math

import numpy as np
import pytest

from landau.errors import InputError
from landau.verify.skurativskyi import sdirk
from landau.verify.skurativskyi.model import PAPER, Params, accel_partials, compiled_field
from landau.verify.skurativskyi.simulate import run

SCALE = np.array([1e-3, 1e-2])  # m, m/s: the error scale of the work-precision benchmark


def test_sdirk4_tableau_order_4_embedded_3_and_L_stable():
    A = np.array(sdirk.SA)
    b = A[-1]
    bh = np.array(sdirk.SBHAT)
    c = np.array(sdirk.SC)
    assert np.allclose(A.sum(1), c, atol=1e-15)
    # Butcher order conditions (Hairer, Nørsett & Wanner I, Table II.2.1)
    for w, order in ((b, 4), (bh, 3)):
        conds = [w.sum() - 1, w @ c - 1 / 2, w @ c**2 - 1 / 3, w @ A @ c - 1 / 6]
        if order == 4:
            conds += [w @ c**3 - 1 / 4, (w * c) @ A @ c - 1 / 8, w @ A @ c**2 - 1 / 12, w @ A @ A @ c - 1 / 24]
        assert np.abs(conds).max() < 1e-13
    # the embedded solution is genuinely of order 3 (else the error estimate would vanish)
    assert abs(bh @ c**3 - 1 / 4) > 1e-3
    # L-stability: R(z) = 1 + z bᵀ(I − zA)⁻¹1 → 0 as z → −∞ (stiffly accurate), |R| ≤ 1 on iR
    R = lambda z: 1 + z * b @ np.linalg.solve(np.eye(5) - z * A, np.ones(5))
    assert abs(R(-1e12)) < 1e-9
    assert max(abs(R(1j * y)) for y in np.logspace(-2, 6, 200)) <= 1 + 1e-12


def test_stage_solve_converges_on_the_hertz_damping_cusp():
    # in contact (x − x_I = 9 µm, the stick of ω = 15) with stage velocities around 0: the
    # scalar stage equation G(V) = V − s_v − hγ a(t, s_x + hγV, V) has one root (G' ≥ 1) —
    # check the returned V is it (|G| ≤ tol and G changes sign across V ± 2 tol)
    p = PAPER.packed()
    fr = compiled_field(PAPER).pointers
    rng = np.random.default_rng(1)
    for _ in range(300):
        sx = PAPER.xI + 9e-6 * rng.uniform(0.5, 1.5)
        sv = rng.choice([-1, 1]) * 10 ** rng.uniform(-12, -3)
        h = 10 ** rng.uniform(-7, -2)
        tol = 1e-16
        V, _, nev, ok = sdirk.stage_velocity(p, 0.1, sx, sv, 0.25 * h, sv, tol, fr)
        assert ok and nev <= 40

        def G(v, sx=sx, sv=sv, hg=0.25 * h):
            return v - sv - hg * accel_partials(0.1, sx + hg * v, v, p)[0]

        assert abs(G(V)) <= tol or G(V - 2 * tol) < 0 < G(V + 2 * tol)


def test_free_stick_follows_the_quasistatic_creep_of_the_regularised_law():
    # obstacle out of reach (x_I = 1 m) and T = 5 N > m0e ω² = 4.06 N: the cart sticks for
    # ever; with the regularised law it creeps at the quasi-static balance
    # T v/sqrt(v² + ε²) = F(t) ⇒ v = ε F/sqrt(T² − F²) (c v, k x and m v̇ are ~1e-4 N, i.e.
    # ~1e-4 relative against F ≈ 4 N).  At t = 5P/4, F = m0e ω² (maximum).
    p = PAPER.with_(xI=1.0, T=5.0, omega=15.0)
    F = p.m0e * p.omega**2
    v_qs = p.eps * F / math.sqrt(p.T**2 - F**2)
    mixed = run(p, 1.25, [0.0, 0.0], rtol=1e-8, method="mixed")
    explicit = run(p, 1.25, [0.0, 0.0], rtol=1e-8, method="dopri5")
    assert mixed.y_final[1] == pytest.approx(v_qs, rel=1e-3)
    assert explicit.y_final[1] == pytest.approx(v_qs, rel=1e-3)
    # every step is a stick step (|ẋ| < 1e-5 m/s, |ẍ| ≈ 0); the explicit path is stability-bound
    # (h ≲ 3.3 εm/T ≈ 6e-6 s): deterministic counts, measured 46 vs 51977;
    # measured relative deviations from v_qs: 9e-5 (mixed), 3e-6 (explicit)
    assert mixed.nstiff == mixed.nsteps
    assert explicit.nsteps > 100 * mixed.nsteps


@pytest.fixture(scope="module")
def omega15():
    """Stick-dominated regime (ω = 15, the cart rests on the obstacle most of the period):
    2 periods from rest, explicit reference at rtol 1e-10 (its self-check against rtol 1e-9:
    9.5e-9 scaled state, 1.4e-9 s impacts; work-precision table)."""
    p = Params(omega=15.0)
    ref = run(p, 2, rtol=1e-10, method="dopri5")
    return p, ref


def test_stick_dominated_run_agrees_with_explicit_path_and_tight_reference(omega15):
    p, ref = omega15
    mixed = run(p, 2, rtol=1e-8)
    explicit = run(p, 2, rtol=1e-8, method="dopri5")
    assert mixed.method == "mixed" and explicit.method == "dopri5"
    # rtol 1e-8 over two periods: measured scaled state errors 2.7e-9 (mixed) / 2.4e-8
    # (explicit) and impact-time errors 3.1e-9 s / 1.2e-8 s; bounds 1e-7 and 5e-8 s leave
    # a 4× margin and are still 1e3× below the loose-tolerance errors (1e-4 at rtol 1e-5)
    for r in (mixed, explicit):
        assert len(r.impacts) == len(ref.impacts) == 2
        assert np.abs((r.y_final - ref.y_final) / SCALE).max() < 1e-7
        assert np.abs(r.impacts - ref.impacts).max() < 5e-8
        assert np.abs((r.strobe_y - ref.strobe_y) / SCALE).max() < 1e-7
    assert np.abs((mixed.y_final - explicit.y_final) / SCALE).max() < 1e-7
    # the stick is taken by the stiff stepper, and the mixed path needs far fewer steps
    # (deterministic counts, measured 691 steps of which 246 stiff, vs 90635)
    assert mixed.nstiff > 0.2 * mixed.nsteps
    assert explicit.nsteps > 20 * mixed.nsteps


def test_tangent_through_stick_agrees_with_explicit_path(omega15):
    # finite-time top Lyapunov exponent over 2 periods at ω = 15 (stick on the obstacle,
    # variational equation through the SDIRK tangent stages): both paths integrate the same
    # variational ODE (Jacobian floored at |ẋ| = ε), so they agree to the tolerance-level error
    # of the log-growth (measured relative difference 3e-7 over 4 periods; bound 1e-5)
    p, _ = omega15
    lm = run(p, 2, rtol=1e-8, lyapunov=True).lyapunov
    le = run(p, 2, rtol=1e-8, lyapunov=True, method="dopri5").lyapunov
    assert lm < 0 and lm == pytest.approx(le, rel=1e-5)


def test_unknown_method_is_named():
    with pytest.raises(InputError):
        run(PAPER, 1, method="radau")


@pytest.mark.parametrize("rtol", [1e-4, 1e-5])
def test_loose_tolerances_bogacki_shampine_converges(rtol):
    # at rtol >= 1e-5 the explicit steps are Bogacki-Shampine 3(2) (3 f evaluations a step)
    # under PI control: ω = 16 from rest, 5 periods (12 impacts) against the same loop at
    # rtol 1e-11 (DOPRI5).  Measured scaled final-state errors 1.7·rtol (1e-4) and 4.6·rtol
    # (1e-5), impact times to 1.5·rtol and 1.9·rtol s; the bounds (30·rtol, 20·rtol s) leave
    # room for the irregular dependence of the global error on rtol in this non-smooth problem
    # (after 20 periods: 7.5·rtol and 6·rtol)
    p = Params(omega=16.0)
    ref = run(p, 5, rtol=1e-11, atol=(1e-15, 1e-13), strobe=False)
    r = run(p, 5, rtol=rtol, atol=(rtol * 1e-4, rtol * 1e-2), strobe=False)
    assert r.nfev < 4.5 * (r.nsteps + r.nrejected)  # 3 per explicit step (6 with DOPRI5)
    assert len(r.impacts) == len(ref.impacts) == 12
    assert np.max(np.abs((r.y_final - ref.y_final) / np.array([1e-3, 1e-2]))) < 30 * rtol
    assert np.max(np.abs(r.impacts - ref.impacts)) < 20 * rtol
