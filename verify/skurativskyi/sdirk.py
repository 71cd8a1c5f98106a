"""A compiled L-stable SDIRK step for the stick phases of eq. (1) (stiff, non-Lipschitz).

Where the explicit DOPRI5 of :mod:`landau.verify.skurativskyi.rk` is slow (measured at ω = 15,
``verify/benchmarks/skurativskyi_work_precision.py``): while the cart rests *on the
obstacle* (contact, x − x_I ≈ 9 µm) its velocity sits at |ẋ| ~ 1e-9…1e-7 m/s.  There the
damping D(ẋ) = cẋ + Tẋ/sqrt(ẋ² + ε²) + k_I b (x − x_I)^{n₂} sgn(ẋ)|ẋ|^{n₃} is stiff (T/(εm)
≈ 7e4 1/s) and non-Lipschitz (slope ∝ |ẋ|^{n₃−1}, n₃ ≈ 0.187, ≈ 5e5 1/s at 1e-8 m/s); an
explicit method chatters around ẋ = 0 with steps ~1e-6 s, >95 % of all its steps.  The true
motion there is slow (ẋ follows the quasi-static balance D(ẋ) = residual force).  Off the
obstacle (e.g. ω = 24.5) the cart also sticks on the track, stiff through T/(εm) only.
Which steps this stepper takes is decided in :func:`landau.verify.skurativskyi.rk.integrate_mixed`.
The friction law reaches the step as the tuple ``fr`` of first-class functions of
:mod:`landau.verify.skurativskyi.field`, so the step is compiled once for every law.

Method: the 5-stage, order-4, stiffly accurate, L-stable SDIRK4 of Hairer & Wanner (*Solving
ODEs II*, IV.6, eq. (6.16), γ = 1/4) with its embedded order-3 solution; the error estimate
is filtered by (I − hγJ)⁻¹ (Shampine) so that stiff components do not cap the step.

Why not the Radau IIA of ``verify/hybrid/radau.py`` (simplified Newton on the coupled
3n stage system): that iteration linearises D at the step start, and on the cusp
sgn(ẋ)|ẋ|^{n₃} Newton diverges (for |ẋ|^{n₃} each Newton step multiplies the distance to a
root by −(1/n₃ − 1) ≈ −4.4).  Measured (work-precision benchmark, last table): on the stick
at ω = 15 it stalls — 1e5 Newton failures in 2e5 step attempts, 3 ms of a 50 ms window
advanced (2.8 µs from rest), where this stepper needs ~70 steps.  With a *diagonally*
implicit method each stage of the second-order system is one scalar equation for the stage
velocity V,

    G(V) = V − s_v − hγ a(t, s_x + hγV, V) = 0,    G'(V) = 1 − hγ(hγ ∂a/∂x + ∂a/∂ẋ) ≥ 1,

(∂a/∂x ≤ 0 and ∂a/∂ẋ ≤ 0 for |ẋ| below b^{−1/n₃} ≈ 2.4 m/s when n₁ = n₂, as in the paper),
so G is strictly increasing with
a unique root and |V − V*| ≤ |G(V)|: a bracket is known from any guess.  In contact the
root is found by Newton in w = sgn(V)|V|^{n₃}, in which the cusp term is *linear* (the
Hertz damping is −κw, κ = k_I b (x − x_I)^{n₂}/m) and G(w) is smooth with a positive slope
at w = 0; out of contact in V itself.  A Newton step that leaves the bracket is replaced
by bisection, so every stage solve converges.

With the 4-D variational system (one tangent vector, top Lyapunov exponent) the tangent
stages solve (I − hγJ(Y_i)) δY_i = δs_i exactly (2×2), J = :func:`model.accel_grad` (the
Hertz-damping slope floored at |ẋ| = ε, as in the explicit path).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from landau.verify.skurativskyi.field import accel_grad, accel_partials
from landau.verify.skurativskyi.model import IN3

#: Hairer & Wanner, Solving ODEs II, IV.6, eq. (6.16): the 5-stage SDIRK4 (γ = 1/4),
#: lower-triangular A (diagonal γ), nodes c and embedded weights b̂; order conditions are
#: checked in the tests
GAMMA = 0.25
SA = ((0.25, 0.0, 0.0, 0.0, 0.0),
      (0.5, 0.25, 0.0, 0.0, 0.0),
      (17 / 50, -1 / 25, 0.25, 0.0, 0.0),
      (371 / 1360, -137 / 2720, 15 / 544, 0.25, 0.0),
      (25 / 24, -49 / 48, 125 / 16, -85 / 12, 0.25))
SC = (0.25, 0.75, 11 / 20, 0.5, 1.0)
SBHAT = (59 / 48, -17 / 96, 225 / 32, -85 / 12, 0.0)
#: b − b̂ (b = the last row of A: the method is stiffly accurate)
SE = tuple(SA[4][i] - SBHAT[i] for i in range(5))
#: Newton/bisection iterations of one stage solve
MAX_ITER = 80


@njit(cache=True)
def _to_w(V, q, in_w):
    if not in_w:
        return V
    return math.copysign(abs(V) ** q, V)


@njit(cache=True)
def _to_v(w, q, in_w):
    if not in_w:
        return w
    return math.copysign(abs(w) ** (1.0 / q), w)


@njit(cache=True)
def _g_and_slope(p, t, sx, sv, hg, V, in_w, fr):
    """G(V) and dG/dw (in_w: w = sgn V |V|^{n₃}) or dG/dV."""
    a, ax, av, kap = accel_partials(t, sx + hg * V, V, p, fr)
    return _g_and_slope_at(p, sv, hg, V, in_w, a, ax, av, kap)


@njit(cache=True)
def _g_and_slope_at(p, sv, hg, V, in_w, a, ax, av, kap):
    """:func:`_g_and_slope` from the partials (a, ax, av, kap) at V."""
    G = V - sv - hg * a
    base = 1.0 - hg * (hg * ax + av)
    q = p[IN3]
    aV = abs(V)
    if in_w:
        # dV/dw = |V|^{1−n₃}/n₃; the Hertz damping −κ w contributes hg κ
        dV = aV ** (1.0 - q) / q
        slope = base * dV + hg * kap
    else:
        slope = base + (hg * kap * q * aV ** (q - 1.0) if (kap > 0.0 and aV > 0.0) else 0.0)
        if kap > 0.0 and aV == 0.0:
            slope = math.inf
    return G, slope, a


@njit(cache=True)
def stage_velocity(p, t, sx, sv, hg, V0, tol, fr):
    """Root V of G(V) = V − s_v − hγ a(t, s_x + hγV, V) (module docstring) from the guess V0:
    safeguarded Newton (bracket from |V − V*| ≤ |G|).  Returns (V, a(V), evaluations, ok)."""
    q = p[IN3]
    # one evaluation at the guess decides the variable (w in contact) and gives G there
    a0, ax0, av0, kap0 = accel_partials(t, sx + hg * V0, V0, p, fr)
    in_w = kap0 > 0.0
    V = V0
    G, slope, a = _g_and_slope_at(p, sv, hg, V, in_w, a0, ax0, av0, kap0)
    nev = 1
    if abs(G) <= tol:
        return V, a, nev, True
    if G > 0.0:
        lo, hi = _to_w(V - G, q, in_w), _to_w(V, q, in_w)
    else:
        lo, hi = _to_w(V, q, in_w), _to_w(V - G, q, in_w)
    w = _to_w(V, q, in_w)
    for _ in range(MAX_ITER):
        wn = w - G / slope if slope > 0.0 and math.isfinite(slope) else 0.5 * (lo + hi)
        if not (lo < wn < hi):
            wn = 0.5 * (lo + hi)
        w = wn
        V = _to_v(w, q, in_w)
        G, slope, a = _g_and_slope(p, t, sx, sv, hg, V, in_w, fr)
        nev += 1
        if not math.isfinite(G):
            return V, a, nev, False
        if abs(G) <= tol:
            return V, a, nev, True
        if G > 0.0:
            hi = w
        else:
            lo = w
        if _to_v(hi, q, in_w) - _to_v(lo, q, in_w) <= tol:
            return V, a, nev, True
    return V, a, nev, False


@njit(cache=True)
def sdirk_step(p, t, y, h, rtol, atol, ynew, fnew, err, fr):
    """One SDIRK4 step of length h from (t, y) (n = 2: (x, ẋ); n = 4: with one tangent vector).
    Fills ynew, fnew = f(t + h, ynew) (stiffly accurate: the last stage derivative) and the
    filtered error estimate err.  Returns (ok, number of acceleration evaluations)."""
    n = y.shape[0]
    K = np.empty((5, n))
    s = np.empty(n)
    hg = h * GAMMA
    nev = 0
    V = y[1]
    X = y[0]
    for i in range(5):
        for c in range(n):
            acc = 0.0
            for j in range(i):
                acc += SA[i][j] * K[j, c]
            s[c] = y[c] + h * acc
        ti = t + SC[i] * h
        tol = 1e-6 * (atol[1] + rtol * abs(V))
        V, a, ne, ok = stage_velocity(p, ti, s[0], s[1], hg, V, tol, fr)
        nev += ne
        if not ok:
            return False, nev
        X = s[0] + hg * V
        K[i, 0] = V
        K[i, 1] = a
        if n == 4:
            ax, av = accel_grad(ti, X, V, p, fr)
            det = (1.0 - hg * av) - hg * hg * ax
            dx = (s[2] * (1.0 - hg * av) + hg * s[3]) / det
            dv = (s[3] + hg * ax * s[2]) / det
            K[i, 2] = dv
            K[i, 3] = ax * dx + av * dv
    ynew[0] = X
    ynew[1] = V
    if n == 4:
        for c in range(2, 4):
            acc = 0.0
            for j in range(5):
                acc += SA[4][j] * K[j, c]
            ynew[c] = y[c] + h * acc
    for c in range(n):
        fnew[c] = K[4, c]
    # embedded estimate h Σ (b − b̂)_i K_i, filtered by (I − hγJ)⁻¹ (J at the new point)
    ax, av = accel_grad(t + h, ynew[0], ynew[1], p, fr)
    det = (1.0 - hg * av) - hg * hg * ax
    for blk in range(n // 2):
        e0 = 0.0
        e1 = 0.0
        for j in range(5):
            e0 += SE[j] * K[j, 2 * blk]
            e1 += SE[j] * K[j, 2 * blk + 1]
        e0 *= h
        e1 *= h
        err[2 * blk] = (e0 * (1.0 - hg * av) + hg * e1) / det
        err[2 * blk + 1] = (e1 + hg * ax * e0) / det
    return True, nev

