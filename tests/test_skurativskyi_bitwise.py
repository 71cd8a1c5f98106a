"""The forced oscillator of Skurativskyi et al. (2019) with its friction generated from the
paper's law: bit for bit the field of eq. (1) typed by hand.

The field below is eq. (1) of Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019) with
F_R = c ẋ + T ẋ/sqrt(ẋ² + ε²), written out term by term with its own parameter vector (the
layout m, m0e, eps, n1, n2, n3, k, c, T, kI, b, xI, omega) — the floating-point operations of the
hand-typed kernels this model was first verified with.  The published values of the model (its
grazing and period-doubling points) are reproduced with those operations, and the
period-doubling cascade near ω = 20.4 is sensitive to the last bit of the stiff stepper's
acceleration, so the field generated from the law object must round exactly as they do: compared
here with ``==``, on random states and over whole runs (same steps, same final state).
"""

from __future__ import annotations

import numpy as np
import pytest
from numba import njit

from landau.laws.velocity import regularised_coulomb
from landau.verify.skurativskyi import rk as R
from landau.verify.skurativskyi.model import IN3, PAPER, Params, compiled_field
from landau.verify.skurativskyi.sdirk import cusp_sdirk_method
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
    for t, x, v in zip(*_states(3000, 7)):
        assert k.accel(t, x, v, p) == hand_accel(t, x, v, q)
        assert k.accel_grad(t, x, v, p) == hand_accel_grad(t, x, v, q)
        assert k.accel_partials(t, x, v, p) == hand_accel_partials(t, x, v, q)
        y = np.array([x, v, 0.3, -0.7])
        k.rhs(t, y, p, out)
        hand_rhs(t, y, q, ref)
        assert np.array_equal(out, ref)


@pytest.fixture(scope="module")
def both_integrators():
    k = compiled_field(PAPER)
    _, generated_step = cusp_sdirk_method(k.accel_partials, k.accel_grad, IN3)
    _, hand_step = cusp_sdirk_method(hand_accel_partials, hand_accel_grad, HN3)
    return (R.switching_integrator(k.rhs, generated_step)[1], R.switching_integrator(hand_rhs, hand_step)[1])


@pytest.mark.parametrize("omega, lyapunov", [(15.0, False), (20.38, True)])
def test_whole_runs_equal_the_hand_typed_field_bitwise(both_integrators, omega, lyapunov):
    # the mixed DOPRI5/SDIRK4 loop over the generated and the hand-typed field, 3 forcing periods
    # from rest (ω = 15: long stick phases on the obstacle, taken by the stiff stepper; ω = 20.38:
    # the period-doubling window, with the variational equation): every output equal
    generated, hand = both_integrators
    prm = PAPER.with_(omega=omega)
    P, rtol = prm.period, 1e-8
    y0 = rest_state(prm)
    at = np.array([rtol * 1e-4, rtol * 1e-2] + ([1e-9, 1e-9] if lyapunov else []))
    y = np.concatenate([y0, [1.0, 0.0]]) if lyapunov else y0.copy()
    outs = []
    for fn, p in ((generated, prm.packed()), (hand, hand_packed(prm))):
        outs.append(fn(p, 0.0, y.copy(), 3 * P, rtol, at, 1e-5, P / 20, prm.xI, True, 0.0, P, 5, lyapunov,
                       100_000, 10_000_000, *METHODS["mixed"], 0))
    g, h = outs
    assert g[2] == h[2] == R.OK
    assert g[14] > 0  # the stiff stepper took steps
    for a, b in zip(g, h):
        if isinstance(a, np.ndarray):
            assert a.shape == b.shape and np.array_equal(a, b)
        else:
            assert a == b
