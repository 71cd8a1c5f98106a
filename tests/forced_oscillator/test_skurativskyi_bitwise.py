"""The forced oscillator of Skurativskyi et al. (2019) with its friction generated from the
paper's law: bit for bit the field of eq. (1) typed by hand.

The field below is eq. (1) of Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019) with
F_R = c ẋ + T ẋ/sqrt(ẋ² + ε²), written out term by term with its own parameter vector (the
layout m, m0e, eps, n1, n2, n3, k, c, T, kI, b, xI, omega) — the floating-point operations of the
hand-typed kernels this model was first verified with.  The published values of the model (its
grazing and period-doubling points) are reproduced with those operations, and the
period-doubling cascade near ω = 20.4 is sensitive to the last bit of the stiff stepper's
acceleration, so the field must round exactly as they do, whether the friction is the compiled-in
paper's law or reached through the C callbacks generated from the law object: compared here with
``==``, on random states and over whole runs (same steps, same final state).
"""

from __future__ import annotations

import numpy as np
import pytest
from numba import cfunc, njit, types

from landau.verify.skurativskyi import field as F
from landau.verify.skurativskyi import rk as R
from landau.verify.skurativskyi.field import BUILT_IN
from landau.verify.skurativskyi.friction import Callbacks, quiet_first_class
from landau.verify.skurativskyi.model import ILAW, PAPER, Params, compiled_field
from landau.verify.skurativskyi.simulate import METHODS, rest_state

# the hand-typed layout of the parameter vector
HM, HM0E, HEPS, HN1, HN2, HN3, HK, HC, HT, HKI, HB, HXI, HOM = range(13)


def hand_packed(p: Params) -> np.ndarray:
    return np.array([p.m, p.m0e, p.eps, p.n1, p.n2, p.n3, p.k, p.c, p.T, p.kI, p.b, p.xI, p.omega], float)


@njit(cache=True)
def hand_contact_force(x, v, p):
    d = x - p[HXI]
    if d <= 0.0:
        return 0.0
    sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
    f = d ** p[HN1] + p[HB] * d ** p[HN2] * sv * abs(v) ** p[HN3]
    return p[HKI] * f if f > 0.0 else 0.0


@njit(cache=True)
def hand_accel(t, x, v, p):
    eps = p[HEPS]
    fr = p[HC] * v + p[HT] * v / np.sqrt(v * v + eps * eps)
    om = p[HOM]
    return (p[HM0E] * om * om * np.sin(om * t) - p[HK] * x - fr - hand_contact_force(x, v, p)) / p[HM]


@njit(cache=True)
def hand_accel_grad(t, x, v, p):
    eps = p[HEPS]
    s = v * v + eps * eps
    dfr = p[HC] + p[HT] * eps * eps / (s * np.sqrt(s))
    dx = -p[HK]
    dv = -dfr
    d = x - p[HXI]
    if d > 0.0:
        av = abs(v)
        sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
        pw = av ** p[HN3]
        f = d ** p[HN1] + p[HB] * d ** p[HN2] * sv * pw
        if f > 0.0:
            dx -= p[HKI] * (p[HN1] * d ** (p[HN1] - 1.0) + p[HB] * p[HN2] * d ** (p[HN2] - 1.0) * sv * pw)
            avf = max(av, eps)
            dv -= p[HKI] * p[HB] * d ** p[HN2] * p[HN3] * avf ** (p[HN3] - 1.0)
    return dx / p[HM], dv / p[HM]


@njit(cache=True)
def hand_rhs(t, y, p, out):
    out[0] = y[1]
    out[1] = hand_accel(t, y[0], y[1], p)
    if y.shape[0] == 4:
        ax, av = hand_accel_grad(t, y[0], y[1], p)
        out[2] = y[3]
        out[3] = ax * y[2] + av * y[3]


@njit(cache=True)
def hand_accel_partials(t, x, v, p):
    eps = p[HEPS]
    s = v * v + eps * eps
    rs = np.sqrt(s)
    om = p[HOM]
    m = p[HM]
    a = p[HM0E] * om * om * np.sin(om * t) - p[HK] * x - p[HC] * v - p[HT] * v / rs
    av = -(p[HC] + p[HT] * eps * eps / (s * rs)) / m
    ax = -p[HK]
    kap = 0.0
    d = x - p[HXI]
    if d > 0.0:
        sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
        pw = abs(v) ** p[HN3]
        dn2 = d ** p[HN2]
        f = d ** p[HN1] + p[HB] * dn2 * sv * pw
        if f > 0.0:
            a -= p[HKI] * f
            ax -= p[HKI] * (p[HN1] * d ** (p[HN1] - 1.0) + p[HB] * p[HN2] * d ** (p[HN2] - 1.0) * sv * pw)
            kap = p[HKI] * p[HB] * dn2 / m
    return a / m, ax / m, av, kap


def _states(n, seed):
    """Random (t, x, ẋ) over the attractors' range: in and out of contact, |ẋ| from 1e-12 m/s
    (the stick on the obstacle) to 0.1 m/s, both signs, and ẋ = 0 exactly."""
    rng = np.random.default_rng(seed)
    t = rng.uniform(0.0, 10.0, n)
    x = PAPER.xI + rng.uniform(-2e-3, 5e-5, n)
    v = rng.choice([-1.0, 1.0], n) * 10.0 ** rng.uniform(-12, -1, n)
    v[::17] = 0.0
    return t, x, v


@pytest.mark.parametrize("prm", [PAPER, PAPER.with_(omega=20.38), PAPER.with_(omega=24.5, xI=-3e-3),
                                 PAPER.with_(eps=3e-6, T=0.5)],
                         ids=["omega16", "omega20.38", "omega24.5", "eps3e-6"])
def test_generated_field_and_partials_equal_the_hand_typed_ones_bitwise(prm):
    k = compiled_field(prm)
    p, q = prm.packed(), hand_packed(prm)
    out, ref = np.empty(4), np.empty(4)
    for t, x, v in zip(*_states(3000, 7), strict=True):
        assert k.accel(t, x, v, p) == hand_accel(t, x, v, q)
        assert k.accel_grad(t, x, v, p) == hand_accel_grad(t, x, v, q)
        assert k.accel_partials(t, x, v, p) == hand_accel_partials(t, x, v, q)
        y = np.array([x, v, 0.3, -0.7])
        k.rhs(t, y, p, out)
        hand_rhs(t, y, q, ref)
        assert np.array_equal(out, ref)


# eq. (1)'s friction typed by hand as the C callbacks the compiled loop takes (parameters read
# from the packed vector at ILAW: c, T, eps), in the operations of hand_accel / hand_accel_partials
_PTR = types.CPointer(types.float64)


def _hand_friction(v, p):
    eps = p[ILAW + 2]
    return p[ILAW] * v + p[ILAW + 1] * v / np.sqrt(v * v + eps * eps)


def _hand_friction_derivative(v, p):
    eps = p[ILAW + 2]
    s = v * v + eps * eps
    return p[ILAW] + p[ILAW + 1] * eps * eps / (s * np.sqrt(s))


def _hand_subtract_friction(a, v, p):
    eps = p[ILAW + 2]
    return a - p[ILAW] * v - p[ILAW + 1] * v / np.sqrt(v * v + eps * eps)


@pytest.fixture(scope="module")
def callbacks():
    """The loop's ``fr`` three ways: the built-in law, the callbacks generated from the law
    object, the hand-typed callbacks above."""
    fr = compiled_field(PAPER).pointers
    assert fr[BUILT_IN]
    one = types.float64(types.float64, _PTR)
    hand = (cfunc(one)(_hand_friction), cfunc(one)(_hand_friction_derivative),
            cfunc(types.float64(types.float64, types.float64, _PTR))(_hand_subtract_friction))
    return {"built-in": fr, "generated": Callbacks(fr[:3] + (False,) + fr[4:]),
            "hand": Callbacks(hand + (False,) + fr[4:])}


@pytest.mark.parametrize("which", ["generated", "hand"])
def test_field_through_the_callbacks_equals_the_hand_typed_one_bitwise(callbacks, which):
    fr = callbacks[which]
    prm = PAPER.with_(omega=20.38)
    p, q = prm.packed(), hand_packed(prm)
    with quiet_first_class():
        for t, x, v in zip(*_states(500, 11), strict=True):
            assert F.accel(t, x, v, p, fr) == hand_accel(t, x, v, q)
            assert F.accel_grad(t, x, v, p, fr) == hand_accel_grad(t, x, v, q)
            assert F.accel_partials(t, x, v, p, fr) == hand_accel_partials(t, x, v, q)


@pytest.mark.parametrize("omega, lyapunov", [(15.0, False), (20.38, True)])
def test_whole_runs_equal_through_the_built_in_law_and_the_callbacks_bitwise(callbacks, omega, lyapunov):
    # the mixed DOPRI5/SDIRK4 loop with the friction compiled in, reached through the generated
    # callbacks and through the hand-typed ones, 3 forcing periods from rest (ω = 15: long stick
    # phases on the obstacle, taken by the stiff stepper; ω = 20.38: the period-doubling window,
    # with the variational equation): every output equal
    prm = PAPER.with_(omega=omega)
    P, rtol = prm.period, 1e-8
    y0 = rest_state(prm)
    at = np.array([rtol * 1e-4, rtol * 1e-2] + ([1e-9, 1e-9] if lyapunov else []))
    y = np.concatenate([y0, [1.0, 0.0]]) if lyapunov else y0.copy()
    loop = R.mixed_loop()
    outs = []
    for which in ("built-in", "generated", "hand"):
        with quiet_first_class():
            outs.append(loop(prm.packed(), 0.0, y.copy(), 3 * P, rtol, at, 1e-5, P / 20, prm.xI, True, 0.0, P, 5,
                             lyapunov, 100_000, 10_000_000, *METHODS["mixed"], 0, callbacks[which]))
    g = outs[0]
    assert g[2] == R.OK
    assert g[14] > 0  # the stiff stepper took steps
    for h in outs[1:]:
        for a, b in zip(g, h, strict=True):
            if isinstance(a, np.ndarray):
                assert a.shape == b.shape and np.array_equal(a, b)
            else:
                assert a == b
