"""Contact loss and stick of the non-smooth mode-coupling model located by the hybrid engine, against an
independent root find (brentq) on scipy's DOP853 dense output of the same phase, integrated from the
state where the phase began with the equations written out here."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from landau.verify.modecoupling.nonsmooth import hoffmann_structure, sliding_equilibrium
from landau.verify.modecoupling.run import bounded_run


def slip_field(mu=0.9, c1=0.02, c2=0.04, v0=1.0):
    a1, a2 = math.radians(30.0), math.radians(60.0)
    k11 = math.cos(a1) ** 2 + 0.5 * math.cos(a2) ** 2
    k12 = math.sin(a1) * math.cos(a1) - 0.5 * math.sin(a2) * math.cos(a2)
    k22 = math.sin(a1) ** 2 + 0.5 * math.sin(a2) ** 2

    def f(t, y):
        x, d, xd, dd = y
        N = d                                  # linear contact, kH = 1
        return [xd, dd, -c1 * xd - k11 * x - k12 * d + mu * N, -c2 * dd - k12 * x - k22 * d + 1.0 - N]
    return f


@pytest.fixture(scope="module")
def run():
    # mu = 0.9 > mu_c: the flutter grows until the mass sticks (t ~ 216) and the contact opens (t ~ 229)
    s = hoffmann_structure(mu=0.9)
    y0 = sliding_equilibrium(s)
    y0[0] += 1e-3
    return s, bounded_run(s, y0, 235.0)


def test_stick_and_contact_loss_located(run):
    s, sol = run
    assert sol.status.value == "finished"
    f = slip_field()
    # the first stick: the phase is the whole slip+ run from t = 0
    ev = next(e for e in sol.events if e.guard == "stop")
    assert (ev.from_mode, ev.to_mode) == ("slip+", "stick")
    y0 = sliding_equilibrium(s)
    y0[0] += 1e-3
    ref = solve_ivp(f, (0.0, ev.t + 1.0), y0, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    lo = ev.t - 0.2
    t_stick = brentq(lambda t: 1.0 - ref.sol(t)[2], lo, ev.t + 0.2, xtol=1e-14)
    # two integrations of a 216 s flutter (growth by e^7) at rtol 1e-10 and 1e-12: the root agrees to
    # the amplified integration error, ~1e-10 x e^7 relative of the period
    assert ev.t == pytest.approx(t_stick, abs=1e-6)
    # the first contact loss: the phase starts where the preceding switch left the mass (slip+ after a stick)
    switches = [e for e in sol.events if e.kind in ("switch", "zero-length")]
    k = next(i for i, e in enumerate(switches) if e.guard == "lift-off")
    prev, ev = switches[k - 1], switches[k]
    assert prev.to_mode == "slip+" and (ev.from_mode, ev.to_mode) == ("slip+", "flight")
    ref = solve_ivp(f, (prev.t, ev.t + 0.5), prev.y_after, method="DOP853", rtol=1e-12, atol=1e-14,
                    dense_output=True)
    t_open = brentq(lambda t: ref.sol(t)[1], prev.t + 1e-9, min(ev.t + 0.3, ref.t[-1]), xtol=1e-14)
    # one short phase from the same state: the event time to the integrators' tolerance
    assert ev.t == pytest.approx(t_open, abs=1e-9)
    assert abs(ev.y[1]) < 1e-12 and ev.y[2] < 1.0        # on the surface, still slipping
    np.testing.assert_allclose(ev.y, ref.sol(ev.t), rtol=0, atol=1e-8)
