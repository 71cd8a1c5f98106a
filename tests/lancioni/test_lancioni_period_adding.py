"""Lancioni, Lenci & Galvanetto, Sec. 3 / Fig. 2(c): the e_N = 0 detached orbit near μ = 0.38957.

Paper: free flight–slip–stick–slip down to μ = 0.38965, then a period-adding cascade (S n, S n n,
…) accumulating at 0.38957 where the attractor disappears.  What eq. (1) does instead (stick
orbit ends at μ* = 0.3895691 by a border collision, no cascade, also not with a stick
tolerance) is derived in verify/lancioni/period_adding.py; these tests pin it down.
"""

import numpy as np
import pytest

from landau.errors import InputError
from landau.verify.lancioni import period_adding as PA
from landau.verify.lancioni.model import build
from landau.verify.lancioni.slip import resolve

MU_STAR = 0.3895691098   # end of the stick orbit (bisection, see test_end_of_stick_orbit...)


@pytest.fixture(scope="module")
def end_and_scan():
    return PA.end_of_stick_orbit(xtol=1e-10)


def test_stick_exit_is_the_fold_of_slip():
    # every stick phase ends at the lower end φ_P of the one admissible stick interval; there the
    # slip+ tangential acceleration vanishes (slip and stick forces coincide: λ_T = −μλ_N), so a
    # slip phase can touch γ_T = 0 only tangentially at P — the grazing that ends the stick orbit
    cm = PA._model(0.38957, resolve(None))
    P = PA.stick_exit(cm)
    assert 0.39 < P.interval[0] < P.interval[1] < 0.43
    acc, lamN, lamT, (G, b) = cm.forces("slip+", 0.0, P.state)
    gT_dot = b[1] + G[1, 0] * lamN + G[1, 1] * lamT
    # scale of γ̇_T along the orbit is ~10 m/s²; 1e-9 is root-finding (xtol 1e-15 in φ) round-off
    assert abs(gT_dot) < 1e-9 and lamN > 0
    assert cm.stick_margin(0.0, P.state) == pytest.approx(0.0, abs=1e-12)


def test_end_of_stick_orbit_matches_published_accumulation(end_and_scan):
    # paper Sec. 3: accumulation (attractor lost) at μ = 0.38957, 5 decimals → half-unit 5e-6
    mu_end, seen = end_and_scan
    assert abs(mu_end - 0.38957) < 5e-6
    # independent route: the first miss g_1 of the orbit through P is linear in μ* − μ
    # (g_1 = 6.88(μ* − μ)); extrapolating two points 1e-6 and 2e-6 below must hit the same μ*
    # (1e-9: bisection xtol 1e-10 plus curvature of g_1 over 2e-6, measured < 1e-10)
    f1, f2 = PA.first_miss(mu_end - 1e-6), PA.first_miss(mu_end - 2e-6)
    b = (f2.g1 - f1.g1) / 1e-6
    assert f1.mu + f1.g1 / b == pytest.approx(mu_end, abs=1e-9)
    # no period other than 1 (sticks every cycle) or 0 (never sticks again) anywhere in the bracket
    assert {p for _, p in seen} == {0, 1}


def test_no_period_adding_in_the_papers_window():
    # paper: period ≥ 2 (S n, S n n, …) for 0.38957 < μ < 0.38965.  In eq. (1) every orbit with a
    # stick phase passes through P, and the orbit through P sticks in every cycle there: period 1.
    for mu in (0.38958, 0.38960, 0.38962, 0.38964):
        r = PA.exit_orbit(mu, t_end=3.0)
        assert r.period == 1 and r.pattern[1:].count("S") == len(r.pattern) - 1


def test_below_the_end_the_stick_free_iterates_move_away_from_stick():
    # 1.1e-6 below μ*: cycle k misses γ_T = 0 by g_k, growing geometrically (factor = the unstable
    # multiplier of the stick-free flight–slip orbit, 1.2127, constant to 1e-4 over 8 cycles), so
    # the motion never sticks again and decays onto the slip equilibrium (~80 cycles, t ≈ 16 s)
    f = PA.first_miss(0.389568)
    assert np.all(np.diff(f.gT_minima) > 0)
    assert f.multiplier == pytest.approx(1.2127, rel=2e-3)
    r = PA.exit_orbit(0.389568, t_end=20.0)
    assert "S" not in r.pattern[1:] and r.decayed


def test_stick_time_vanishes_like_sqrt_at_the_end():
    # above μ* the stick orbit grazes γ_T = 0 at the fold P: stick time τ ∝ sqrt(μ − μ*), so τ²
    # is linear with its zero at μ* (1e-9: three points at 1e-7…1.6e-6, curvature ~1e-3 relative)
    mus = MU_STAR + np.array([1e-7, 4e-7, 1.6e-6])
    tau = np.array([PA.exit_orbit(m, t_end=1.0).stick_times[2] for m in mus])
    c = np.polyfit(mus, tau ** 2, 1)
    assert -c[1] / c[0] == pytest.approx(MU_STAR, abs=1e-9)


@pytest.mark.parametrize("reset, slope", [("project", -1 / 6.881), ("hold", None)])
def test_stick_tolerance_shifts_the_end_linearly_and_adds_no_cascade(reset, slope):
    # The paper's window might come from a stick tolerance |γ_T| < η (stick_tol).  It does not:
    # only periods 0 and 1 occur, and the end moves linearly in η.  "project" (γ_T := 0) keeps the
    # reset P, so the first miss must exceed η: shift −η/b with b = dg_1/d(μ* − μ) = 6.881 from the
    # exact model (independent; 0.5 % covers the bisection xtol 1e-4 η and b's variation).  "hold"
    # equals the exact model with belt speed |v| − η: shift +0.0309 η; checked for linearity.
    shifts = []
    for eta in (1e-4, 1e-3):
        mu_end, seen = PA.end_of_stick_orbit(bracket=(MU_STAR - 0.3 * eta, MU_STAR + 0.3 * eta), xtol=1e-4 * eta,
                                             stick_tol=eta, stick_tol_reset=reset)
        assert {p for _, p in seen} == {0, 1}
        shifts.append((mu_end - MU_STAR) / eta)
    if slope is not None:
        assert shifts[0] == pytest.approx(slope, rel=5e-3)
    else:
        assert shifts[0] == pytest.approx(0.0309, rel=2e-2)
    assert shifts[1] == pytest.approx(shifts[0], rel=5e-3)


def test_stick_tolerance_is_off_by_default_and_validated():
    cm = build(0.38957)
    assert cm.stick_tol == 0.0
    with pytest.raises(InputError):
        build(0.38957, stick_tol=-1e-4)
    with pytest.raises(InputError):
        build(0.38957, stick_tol=1e-4, stick_tol_reset="clip")


@pytest.mark.slow
def test_stick_free_saddle_border_collision():
    # above μ* an unstable stick-free flight–slip orbit coexists with the stick orbit; its slip
    # phase misses γ_T = 0 by g_F ∝ (μ − μ*) (border collision at μ*: both orbits meet at P).
    # Two points, 2e-5 and 8.09e-5 (the paper's first step 0.38965) above μ*: the same slope
    # (2 %: g_F is read at the closest approach of a basin-boundary trajectory, ~1 % accurate)
    s1 = PA.stick_free_saddle(MU_STAR + 2e-5)
    s2 = PA.stick_free_saddle(MU_STAR + 8.09e-5)
    a1, a2 = s1.gT_min / 2e-5, s2.gT_min / 8.09e-5
    assert a1 > 0 and a2 == pytest.approx(a1, rel=2e-2)
    # the saddle is real beyond P's reset (g_F > 0) exactly where the stick orbit exists: no window
    # 0 < g_1 < g_F below μ* where a cascade could live
    assert 25 < a1 < 40


@pytest.mark.parametrize("reset", ["project", "hold"])
def test_stick_tolerance_on_a_decelerating_block(reset):
    # hand-built closed form (verify.lancioni.contact.PointMassOnPlane): a block sliding along
    # an incline with tan θ < μ decelerates at a = g(sin θ − μ cos θ) < 0; exact stick at v0/|a|.
    # With the band |γ_T| ≤ η it sticks when the speed reaches η: t = (v0 − η)/|a|; "project" then
    # rests (v = 0), "hold" creeps at η (stick forces keep γ̇_T = 0).  Slip is a polynomial in t
    # and the event is located to 1e-14, so 1e-10 is round-off.
    from landau.verify.hybrid import DOP853Stepper, simulate
    from landau.verify.lancioni.contact import ContactModel, PointMassOnPlane, default_options
    g, th, mu, v0, eta = 9.81, 0.2, 0.5, 1.0, 1e-3
    a = g * (np.sin(th) - mu * np.cos(th))
    cm = ContactModel(PointMassOnPlane(g=g, theta=th, mu=mu), stick_tol=eta, stick_tol_reset=reset)
    sol = simulate(cm.model, "slip+", np.array([0.0, 0.0, v0, 0.0]), (0.0, 1.0), DOP853Stepper(1e-12, 1e-14),
                   default_options(record=False))
    stops = [e for e in sol.events if e.guard == "stop"]
    assert len(stops) == 1 and stops[0].to_mode == "stick" and sol.final_mode == "stick"
    assert stops[0].t == pytest.approx((v0 - eta) / -a, abs=1e-10)
    assert sol.y_final[2] == pytest.approx(0.0 if reset == "project" else eta, abs=1e-12)
    exact = ContactModel(PointMassOnPlane(g=g, theta=th, mu=mu))
    sol0 = simulate(exact.model, "slip+", np.array([0.0, 0.0, v0, 0.0]), (0.0, 1.0), DOP853Stepper(1e-12, 1e-14),
                    default_options(record=False))
    assert [e.t for e in sol0.events if e.guard == "stop"][0] == pytest.approx(v0 / -a, abs=1e-10)
