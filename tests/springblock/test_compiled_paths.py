"""The compiled Radau IIA runs of the quasi-dynamic cell and of the load histories
(:mod:`landau.verify.springblock.compiled_runs`).

* the index-reduced force balance, w' = −(R_y·f + λR)/R_w, in closed form on a residual whose
  manifold is explicit (y = sinh w): along it d(sinh w)/dt = y' exactly;
* the compiled cell (the force balance differentiated and fed back, w a state) against an
  independent route, scipy's Radau IIA of the implicit slip rate (the force balance solved by
  Newton's method at every evaluation), on a stick–slip run with the nonlinear normal-load terms
  γ_LD, α_LD; the force balance holds along the compiled run;
* the sections v = V (rising) are the minima of the slip;
* chunked compiled runs continue where the last chunk ended: the same end state and the same
  stopping crossing as one call;
* a slide-hold-slide at M = 0 against the compiled history with a tiny mass (the momentum equation,
  another kernel and formulation), mid-reload after a hold in which v falls by three decades;
* the step budget of the quasi-dynamic run is a status, a bad budget a named error.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from landau.errors import InputError
from landau.laws import get_law
from landau.verify.springblock.checks import predict
from landau.verify.springblock.compiled_runs import drive, index_reduced
from landau.verify.springblock.history import simulate_history
from landau.verify.springblock.quasidynamic import QuasiDynamicCell, simulate_quasidynamic

LAW = get_law("dieterich")
#: the BP1-like cell of test_quasidynamic.py with a normal load that follows the spring
BP1_LD = dict(a=0.010, b=0.015, L=8e-3, sigma=50e6, eta=4.624e6, V_s=1e-6, a_v=0.6, M=0.0, gamma_ld=0.2,
              alpha_ld=0.3)


def test_index_reduced_force_balance_in_closed_form():
    w, y, lam = sp.symbols("w y lam", real=True)
    R = y - sp.sinh(w)                    # the manifold y = sinh(w), R_w = -cosh(w) < 0
    f = [-y]
    wdot = index_reduced(R, f, w, [y], lam)
    assert sp.simplify(wdot - (-y + lam * R) / sp.cosh(w)) == 0
    # on the manifold the lambda term vanishes and d(sinh w)/dt = cosh(w) w' = y' = -y
    assert sp.simplify((sp.cosh(w) * wdot).subs(y, sp.sinh(w)) + sp.sinh(w)) == 0
    # off it R' = R_w w' + R_y y' = -lam R
    assert sp.simplify(sp.diff(R, w) * wdot + sp.diff(R, y) * f[0] + lam * R) == 0


def _stick_slip_cell():
    V = 1e-6
    pr = predict(LAW, V, BP1_LD)
    k = 0.5 * pr.kc
    cell = QuasiDynamicCell.build(LAW, V, k, BP1_LD)
    return cell, 3 * 2 * math.pi / pr.omega_c, cell.perturbed(0.5 * cell.ell)


def test_compiled_cell_against_the_implicit_slip_rate_route():
    """Three linear periods at k = 0.5 k_c (the orbit grows to stick–slip, v from 2e-3 V to 4e5 V), both
    routes at rtol 1e-9: the final state agrees to 1e-9 (measured 8e-11; each route is within 5e-11 of
    scipy's run at rtol 1e-12); the force balance (the lambdified residual at the recorded points) holds
    to 1e-11 (measured 5e-13)."""
    from scipy.integrate import solve_ivp

    cell, T, y0 = _stick_slip_cell()
    last = [cell.slip_rate(y0)]

    def f(_t, yy):
        out, last[0] = cell.rhs(yy, last[0])
        return out

    def jac(_t, yy):
        return cell.jacobian(yy, cell.slip_rate(yy, last[0]))

    ref = solve_ivp(f, (0.0, T / cell.time_unit), y0, method="Radau", rtol=1e-9, atol=1e-9, jac=jac)
    assert ref.success
    sim = simulate_quasidynamic(LAW, cell.V, cell.k, cell, T, y0, rtol=1e-9)
    assert sim.status.value == "finished" and sim.t[-1] == pytest.approx(T, rel=1e-12)
    v = sim.y[1]
    assert v.min() < 1e-2 * cell.V and v.max() > 1e5 * cell.V          # stick–slip
    end = np.r_[sim.y[0, -1] / cell.ell, math.log(sim.y[3, -1] / cell.phi0[0])]
    assert np.max(np.abs(end - ref.y[:, -1])) < 1e-9
    W = np.log(v / cell.V)
    Y = np.vstack([sim.y[0] / cell.ell, np.log(sim.y[3] / cell.phi0[0])])
    R = np.array([cell._fn(w, *y)[0] for w, y in zip(W, Y.T, strict=True)])
    assert np.max(np.abs(R)) < 1e-11


def test_sections_are_the_minima_of_the_slip():
    """sections=True logs the upward crossings of v = V located by the compiled loop: there v = V (to
    1e-9) and X is at its minimum (each event's X at most the smallest recorded X around it, within the
    tolerance 1e-9 L), one per cycle."""
    cell, T, y0 = _stick_slip_cell()
    sim = simulate_quasidynamic(LAW, cell.V, cell.k, cell, T, y0, rtol=1e-10, sections=True)
    ev = list(sim.events)
    assert len(ev) >= 2 and all(e.note == "up" and e.kind == "section" for e in ev)
    times = [e.t for e in ev]
    assert np.all(np.diff(times) > 0)
    for e in ev:
        assert e.y[1] == pytest.approx(cell.V, rel=1e-9)
        near = np.abs(sim.t - e.t) < 0.05 * T
        assert e.y[0] <= sim.y[0, near].min() + 1e-9 * cell.ell


def test_chunked_runs_continue_where_the_last_chunk_ended():
    """The compiled run in chunks of 40 step attempts against one call at rtol 1e-10: the same end state
    to 1e-9 (each chunk restarts the step-size controller, so to the tolerance; measured 7e-14), and,
    stopping at the third downward crossing of v = V, the same crossing time (to 1e-10, measured 5e-15)."""
    cell, T, y0 = _stick_slip_cell()
    z0 = np.r_[y0[0], cell.slip_rate(y0), y0[1:]]
    at = np.full(3, 1e-10)
    t1 = T / cell.time_unit
    one = drive(cell.kernel, cell.kernel_p, z0, 0.0, t1, rtol=1e-10, atol=at)
    many = drive(cell.kernel, cell.kernel_p, z0, 0.0, t1, rtol=1e-10, atol=at, chunk_steps=40)
    assert one.status == many.status == 0
    assert len(many.rec_t) == many.counts[0] + 1 and np.all(np.diff(many.rec_t) > 0)
    assert np.max(np.abs(one.y - many.y)) < 1e-9
    stops = [drive(cell.kernel, cell.kernel_p, z0, 0.0, t1, rtol=1e-10, atol=at, ev_idx=1, ev_dir=-1, ev_stop=3,
                   chunk_steps=c) for c in (40, 10 ** 6)]
    for run in stops:
        assert run.status == 1 and int(np.sum(run.ev_dir < 0)) == 3
        assert abs(run.ev_y[-1, 1]) < 1e-12 and run.ev_dir[-1] == -1    # on the section, w decreasing
    assert stops[0].ev_t[-1] == pytest.approx(stops[1].ev_t[-1], rel=1e-10)


def test_slide_hold_slide_at_m0_against_a_tiny_mass_history():
    """1e-5 m/s, a 10 s hold, reload: 0.3 s into the reload (v still 7e-8 m/s, rising) the quasi-dynamic
    history (index-reduced force balance) and the history with M = 1e-10 kg (the momentum equation;
    MV/(ηL) = 1e-11) agree to 1e-9 in v, mu, phi and F (measured 2e-11)."""
    sigma = 1.2 * 9.81
    qd = {"M": 0.0, "eta": 100.0, "sigma": sigma}
    hist = "1e-5@0,0@5,1e-5@15"
    a = simulate_history(LAW, hist, 4e5, qd, t_end=15.3, rtol=1e-11)
    b = simulate_history(LAW, hist, 4e5, {**qd, "M": 1e-10}, t_end=15.3, rtol=1e-11)
    assert a.state_names == b.state_names == ("V", "v", "mu", "phi", "F", "x_lp", "slip")
    assert a.y[1].min() < 1e-3 * 1e-5 and a.y_final[1] < 1e-2 * 1e-5      # a real hold, mid-reload
    assert a.y_final[1:] == pytest.approx(b.y_final[1:], rel=1e-9)
    # the jumps of V are restarts: the recorded times increase, and each piece ends at its jump
    assert np.all(np.diff(a.t) > 0) and {5.0, 15.0} <= set(a.t.tolist())


def test_quasidynamic_step_budget_is_a_status_and_a_bad_budget_a_named_error():
    cell, T, y0 = _stick_slip_cell()
    sim = simulate_quasidynamic(LAW, cell.V, cell.k, cell, T, y0, rtol=1e-9, max_steps=30)
    assert sim.status.value == "max-steps" and sim.t[-1] < T and "step limit" in sim.message
    assert sim.nsteps <= 30 and len(sim.t) == sim.nsteps + 1
    with pytest.raises(InputError, match="max_steps"):
        simulate_quasidynamic(LAW, cell.V, cell.k, cell, T, y0, max_steps=0)
    z0 = np.r_[y0[0], cell.slip_rate(y0), y0[1:]]
    with pytest.raises(InputError, match="chunk_steps"):
        drive(cell.kernel, cell.kernel_p, z0, 0.0, 1.0, rtol=1e-9, atol=np.full(3, 1e-9), chunk_steps=0)
    with pytest.raises(InputError, match="max_events"):
        drive(cell.kernel, cell.kernel_p, z0, 0.0, 1.0, rtol=1e-9, atol=np.full(3, 1e-9), ev_idx=1, ev_stop=5,
              max_events=2)
