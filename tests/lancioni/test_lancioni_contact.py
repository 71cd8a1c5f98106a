"""Single frictional contact on the hybrid engine (verify/lancioni/contact.py): hand-built systems
with closed-form answers, the Poisson–Coulomb impact law and Painlevé detection.

Tolerances: free flight and constant-acceleration slip are polynomials in t, reproduced by
DOP853's dense output to rounding; event times are located to 1e-14, so closed forms agree to
~1e-10 after a few tens of impacts.
"""

import math

import numpy as np
import pytest

from landau.verify.hybrid import DOP853Stepper, simulate
from landau.verify.lancioni.contact import (
    ContactModel,
    PainleveError,
    PointMassOnPlane,
    contact_problem,
    default_options,
    poisson_impact,
)
from landau.verify.lancioni.model import build, slip_state

G = 9.81
STEP = DOP853Stepper(1e-12, 1e-14)


@pytest.mark.parametrize("e", [0.5, 0.8])
def test_bouncing_ball_chattering_accumulation_time(e):
    # dropped from h at rest: impacts accumulate at T = sqrt(2h/g) + 2 e v1/(g(1 − e)), v1 = sqrt(2gh);
    # chattering is ended (paper's rule) when the inter-impact time < 1e-6: that must happen within
    # the geometric tail e·1e-6/(1 − e) of T, be logged, and leave the ball resting (stick).
    h = 1.0
    v1 = math.sqrt(2 * G * h)
    T = math.sqrt(2 * h / G) + 2 * e * v1 / (G * (1 - e))
    cm = ContactModel(PointMassOnPlane(g=G, mu=0.3, eN=e))
    sol = simulate(cm.model, "flight", [0.0, h, 0.0, 0.0], (0.0, T + 1.0), STEP, default_options(1e-6))
    z = sol.events.filter(kind="zeno")
    assert len(z) == 1 and "chattering ended" in z[0].note
    tail = 1e-6 * e / (1 - e)
    assert T - 2 * tail <= z[0].t <= T
    assert float(z[0].note.split("t=")[-1]) == pytest.approx(T, abs=1e-9)  # extrapolated accumulation
    assert sol.final_mode == "stick" and sol.y_final[1] == 0.0 and abs(sol.y_final[3]) < 1e-12
    imp = sol.events.times(guard="impact")
    k = np.arange(len(imp))
    assert np.max(np.abs(imp - (math.sqrt(2 * h / G) + 2 * v1 / G * e * (1 - e ** k) / (1 - e)))) < 1e-10


@pytest.mark.parametrize("mu", [0.2, 0.6])
def test_inclined_plane_stick_slip_threshold_tan_theta(mu):
    # a block at rest on a plane inclined by θ sticks iff tan θ ≤ μ; beyond, it slides with
    # acceleration g(sin θ − μ cos θ) (closed form).
    th_c = math.atan(mu)
    for th, expect in ((th_c * (1 - 1e-6), "stick"), (th_c * (1 + 1e-6), "slip+"), (th_c + 0.1, "slip+")):
        cm = ContactModel(PointMassOnPlane(g=G, theta=th, mu=mu))
        y0 = np.zeros(4)
        mode = cm.initial_mode(0.0, y0)
        assert mode == expect
        sol = simulate(cm.model, mode, y0, (0.0, 1.0), STEP, default_options())
        a = G * (math.sin(th) - mu * math.cos(th))
        assert sol.final_mode == expect and len([e for e in sol.events if e.kind != "section"]) == 0
        assert sol.y_final[0] == pytest.approx(0.0 if expect == "stick" else 0.5 * a, abs=1e-12)


def test_sliding_block_stops_and_sticks_below_threshold():
    # thrown up... down the slope at u0 with tan θ < μ: decelerates at g(μ cos θ − sin θ), stops at
    # t* = u0/(g(μ cos θ − sin θ)) and then sticks (slip→stick when g_T reaches 0, stick admissible)
    th, mu, u0 = 0.2, 0.5, 1.0
    cm = ContactModel(PointMassOnPlane(g=G, theta=th, mu=mu))
    sol = simulate(cm.model, "slip+", [0.0, 0.0, u0, 0.0], (0.0, 2.0), STEP, default_options())
    ev = [e for e in sol.events if e.kind != "section"]
    assert len(ev) == 1 and ev[0].to_mode == "stick"
    assert ev[0].t == pytest.approx(u0 / (G * (mu * math.cos(th) - math.sin(th))), rel=1e-12)


@pytest.mark.parametrize("vT", [0.1, 3.0])
def test_poisson_impact_point_mass_closed_form(vT):
    # point mass m, approach velocity (v_N, v_T) = (−2, vT): Λ_N = m(1 + e)|v_N|; the tangential
    # velocity is stopped if |v_T| ≤ μ(1 + e)|v_N| (stick), else reduced by μ(1 + e)|v_N|.
    m, e, mu, vN = 2.0, 0.5, 0.4, -2.0
    Gm = np.eye(2) / m
    r = poisson_impact(Gm, [vN, vT], mu, e)
    assert r.Lambda[0] == pytest.approx(m * (1 + e) * abs(vN), rel=1e-14)
    assert r.gamma_plus[0] == pytest.approx(e * abs(vN), rel=1e-14)
    dv = mu * (1 + e) * abs(vN)
    assert r.gamma_plus[1] == pytest.approx(max(vT - dv, 0.0), abs=1e-14)


def test_painleve_situations_are_reported():
    # eq. (1) at φ = 0.39: D₊ = G_NN − μ G_NT ∝ m₁cos²φ + m₂ sin φ(sin φ − μ cos φ) < 0 for
    # μ > (m₁ cot φ + m₂ tan φ)/m₂ ≈ 0.655 — then the contact problem has 0 or 2 solutions.
    cm = build(mu=1.0)
    y = slip_state(cm.mech, 0.39, 0.0)
    a0, MiW, Gd, b = cm.mech.terms(0.0, y[:2], y[2:])
    assert Gd[0, 0] - 1.0 * Gd[0, 1] < 0
    for bN, kind in ((+1.0, "indeterminate"), (-1.0, "inconsistent")):
        with pytest.raises(PainleveError) as ex:
            contact_problem(Gd, np.array([bN, 0.0]), 1.0, gT=1.0)
        assert ex.value.kind == kind
    # the same state with μ = 0.4 (D₊ > 0) has exactly one solution
    assert contact_problem(Gd, np.array([-1.0, 0.0]), 0.4, gT=1.0).mode == "slip+"
