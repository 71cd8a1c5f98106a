"""The compiled fields of eq. (1) (verify/lancioni/kernels.py) against independent computations.

* each regime's generated kernel against the Python field of the contact model (numpy, the
  contact algebra of verify/hybrid/contact.py), for Coulomb friction, a user's law and the
  sinusoidal belt — the same formulas evaluated in another order, so they agree to rounding
  (1e-11 relative: the stick forces divide by det G, which loses ~3 digits);
* the contact terms (a₀, M⁻¹W, G, b) against M⁻¹ by numpy's inverse of the mass matrix of eq. (1);
* a hybrid run on the compiled DOP853 against the same run on scipy's DOP853 (the same method
  and step-size rules: equal events, states to the integration tolerance);
* the slip shooting's compiled return map against scipy's ``solve_ivp`` event.
"""

import numpy as np
import pytest

from landau.laws.velocity import VelocityFriction
from landau.verify.hybrid import DOP853Stepper, simulate
from landau.verify.hybrid.dop853 import CompiledDOP853
from landau.verify.lancioni import analysis as A
from landau.verify.lancioni import slip as S
from landau.verify.lancioni.contact import default_options
from landau.verify.lancioni.model import ConstantBelt, SineBelt, build, slip_state

LAW = VelocityFriction.from_strings("mine", "mu*(1 + alpha*exp(-v/v0))", params={"mu": 0.3, "alpha": 0.3, "v0": 0.5})
MODES = ("flight", "slip+", "slip-", "stick")


def _states(n=12, seed=3):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        yield rng.uniform(0, 3), np.array([0.4, 0.92, 0.0, 0.0]) + rng.normal(size=4) * [0.2, 0.05, 2.0, 0.5]


@pytest.mark.parametrize("kw", [dict(mu=0.4), dict(friction=LAW), dict(mu=0.5, belt=SineBelt())],
                         ids=["coulomb", "user-law", "sine-belt"])
def test_mode_kernels_equal_the_python_fields(kw):
    cm = build(**kw)
    for mode in MODES:
        kern = cm.model.mode(mode).kernel()
        f = cm.rhs(mode)
        for t, y in _states():
            assert kern(t, y) == pytest.approx(f(t, y), rel=1e-11, abs=1e-11), (mode, t, y)


def test_another_belt_has_no_kernel_and_runs_on_scipy():
    class Ramp:
        def __call__(self, t):
            return -1.0 + 0.0 * np.asarray(t, float)

        def rate(self, t):
            return 0.0 * np.asarray(t, float)
    cm, ref = build(0.4, belt=Ramp()), build(0.4, belt=ConstantBelt(-1.0))
    assert all(m.kernel is None for m in cm.model.modes.values())
    y0 = slip_state(cm.mech, 0.4)
    a = simulate(cm.model, "slip+", y0, (0.0, 0.5), CompiledDOP853(1e-10, 1e-12), default_options(record=False))
    b = simulate(ref.model, "slip+", y0, (0.0, 0.5), DOP853Stepper(1e-10, 1e-12), default_options(record=False))
    assert np.array_equal(a.y_final, b.y_final)


def test_contact_terms_against_the_mass_matrix():
    mech = build(0.4).mech
    p = mech.params
    m1, m2, l = p["m1"], p["m2"], p["l"]
    for t, y in _states(5):
        phi, w = y[0], y[2]
        M = np.array([[m1 * l * l, m1 * l * np.sin(phi)], [m1 * l * np.sin(phi), m1 + m2]])
        W = np.array([[l * np.sin(phi), l * np.cos(phi)], [1.0, 0.0]])
        h = np.array([p["c_phi"] * w + p["k_phi"] * (phi - p["phi0"]) + m1 * p["g"] * l * np.sin(phi),
                      p["c_y"] * y[3] + p["k_y"] * (y[1] - p["y0"]) + m1 * l * w * w * np.cos(phi)
                      + (m1 + m2) * p["g"]])
        Mi = np.linalg.inv(M)
        a0, MiW, G, b = mech.terms(t, y[:2], y[2:])
        assert a0 == pytest.approx(-Mi @ h, rel=1e-12)
        assert MiW == pytest.approx(Mi @ W, rel=1e-12, abs=1e-14)
        assert G == pytest.approx(W.T @ Mi @ W, rel=1e-12, abs=1e-14)
        # the vectorised call (samples on a trailing axis) gives the same numbers
        Y = np.column_stack([y, y])
        assert np.array_equal(mech.terms(np.array([t, t]), Y[:2], Y[2:])[2][:, :, 1], G)


@pytest.mark.parametrize("eN", [0.0, 0.2])
def test_compiled_run_equals_scipy_run(eN):
    cm = build(0.395, eN)
    y0 = np.array([0.38, 0.929, 0.0, 0.0])
    m = cm.initial_mode(0.0, y0)
    a = simulate(cm.model, m, y0, (0.0, 4.0), CompiledDOP853(1e-10, 1e-12), default_options(record=False))
    b = simulate(cm.model, m, y0, (0.0, 4.0), DOP853Stepper(1e-10, 1e-12), default_options(record=False))
    assert (a.status, a.final_mode, a.nsteps) == (b.status, b.final_mode, b.nsteps)
    assert [e.kind for e in a.events] == [e.kind for e in b.events] and len(a.events) > 10
    assert [e.t for e in a.events] == pytest.approx([e.t for e in b.events], abs=1e-9)
    assert a.y_final == pytest.approx(b.y_final, abs=1e-8)


@pytest.mark.parametrize("law", [(), (LAW, None, -1.0)], ids=["coulomb", "user-law"])
def test_slip_return_map_compiled_equals_solve_ivp(law):
    p = S.resolve(S.SET1)
    mu, w0 = (0.4098, 0.3) if not law else (0.36, 0.05)
    h = S.slip_hopf(p) if not law else S.slip_hopf(p, friction=LAW, v=-1.0)
    phi_e = S.equilibrium_phi(p, mu, 1, *law[:2], *((-1.0,) if law else ()))
    T = 2 * np.pi / h.omega_c
    te, ye = A._return_point(p, mu, 1, w0, phi_e, T, law=law)
    ref = A._one_turn(p, mu, 1, w0, phi_e, T, law=law)
    assert te == pytest.approx(ref.t_events[0][0], abs=1e-12)
    assert ye == pytest.approx(ref.y_events[0][0], abs=1e-12)
