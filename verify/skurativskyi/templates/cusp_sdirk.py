"""Template: the SDIRK4 step of landau.verify.skurativskyi.sdirk for ẍ = a(t, x, ẋ) with a cusp
term (see landau.verify.hybrid.specialise for how templates are bound).

Free names: ``accel_partials``, ``accel_grad`` (numba functions of (t, x, v, p)),
``exponent_index`` (int: the cusp exponent's index in p), ``jit`` (the numba decorator).
"""

import math

import numpy as np

from landau.verify.skurativskyi.sdirk import GAMMA, MAX_ITER, SA, SC, SE, _to_v, _to_w

@jit
def _g_and_slope(p, t, sx, sv, hg, V, in_w):
    """G(V) and dG/dw (in_w: w = sgn V |V|^{n₃}) or dG/dV."""
    a, ax, av, kap = accel_partials(t, sx + hg * V, V, p)
    return _g_and_slope_at(p, sv, hg, V, in_w, a, ax, av, kap)


@jit
def _g_and_slope_at(p, sv, hg, V, in_w, a, ax, av, kap):
    """:func:`_g_and_slope` from the partials (a, ax, av, kap) at V."""
    G = V - sv - hg * a
    base = 1.0 - hg * (hg * ax + av)
    q = p[exponent_index]
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


@jit
def stage_velocity(p, t, sx, sv, hg, V0, tol):
    """Root V of G(V) = V − s_v − hγ a(t, s_x + hγV, V) (module docstring) from the guess V0:
    safeguarded Newton (bracket from |V − V*| ≤ |G|).  Returns (V, a(V), evaluations, ok)."""
    q = p[exponent_index]
    # one evaluation at the guess decides the variable (w in contact) and gives G there
    a0, ax0, av0, kap0 = accel_partials(t, sx + hg * V0, V0, p)
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
        G, slope, a = _g_and_slope(p, t, sx, sv, hg, V, in_w)
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


@jit
def sdirk_step(p, t, y, h, rtol, atol, ynew, fnew, err):
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
        V, a, ne, ok = stage_velocity(p, ti, s[0], s[1], hg, V, tol)
        nev += ne
        if not ok:
            return False, nev
        X = s[0] + hg * V
        K[i, 0] = V
        K[i, 1] = a
        if n == 4:
            ax, av = accel_grad(ti, X, V, p)
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
    ax, av = accel_grad(t + h, ynew[0], ynew[1], p)
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

