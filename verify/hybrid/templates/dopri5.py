"""Template: the Dormand–Prince 5(4) step over a kernel (see landau.verify.hybrid.specialise).

Free names: ``fun(t, y, p, out)`` (the kernel), ``jit`` (the numba decorator).
"""

import numpy as np

from landau.verify.hybrid.compiled import (A21, A31, A32, A41, A42, A43, A51, A52, A53, A54, A61, A62, A63, A64,
                                           A65, B1, B3, B4, B5, B6, C2, C3, C4, C5, D1, D3, D4, D5, D6, D7, E1,
                                           E3, E4, E5, E6, E7, err_norm)
from landau.verify.hybrid.locate import _quiet_guards


@jit
def step(p, t, y, k1, h, ynew, k7, err):
    stages(p, t, y, k1, h, ynew, k7, err, np.empty((5, y.shape[0])))


@jit
def stages(p, t, y, k1, h, ynew, k7, err, K):
    """``step`` keeping the stages k2..k6 in the rows of K (for the dense output)."""
    n = y.shape[0]
    yt = np.empty(n)
    k2, k3, k4, k5, k6 = K[0], K[1], K[2], K[3], K[4]
    for a in range(n):
        yt[a] = y[a] + h * A21 * k1[a]
    fun(t + C2 * h, yt, p, k2)
    for a in range(n):
        yt[a] = y[a] + h * (A31 * k1[a] + A32 * k2[a])
    fun(t + C3 * h, yt, p, k3)
    for a in range(n):
        yt[a] = y[a] + h * (A41 * k1[a] + A42 * k2[a] + A43 * k3[a])
    fun(t + C4 * h, yt, p, k4)
    for a in range(n):
        yt[a] = y[a] + h * (A51 * k1[a] + A52 * k2[a] + A53 * k3[a] + A54 * k4[a])
    fun(t + C5 * h, yt, p, k5)
    for a in range(n):
        yt[a] = y[a] + h * (A61 * k1[a] + A62 * k2[a] + A63 * k3[a] + A64 * k4[a] + A65 * k5[a])
    fun(t + h, yt, p, k6)
    for a in range(n):
        ynew[a] = y[a] + h * (B1 * k1[a] + B3 * k3[a] + B4 * k4[a] + B5 * k5[a] + B6 * k6[a])
    fun(t + h, ynew, p, k7)
    for a in range(n):
        err[a] = h * (E1 * k1[a] + E3 * k3[a] + E4 * k4[a] + E5 * k5[a] + E6 * k6[a] + E7 * k7[a])


@jit
def advance(p, t, y, k1, h, hmax, t_bound, rtol, atol):
    n = y.shape[0]
    ynew = np.empty(n)
    k7 = np.empty(n)
    ok, tn, h, hn, nfev = advance_into(p, t, y, k1, h, hmax, t_bound, rtol, atol, ynew, k7, np.empty(n),
                                       np.empty((5, n)))
    if ok:
        return True, tn, ynew, k7, h, hn, nfev
    return False, t, y.copy(), k1.copy(), h, h, nfev


@jit
def advance_into(p, t, y, k1, h, hmax, t_bound, rtol, atol, ynew, k7, err, K):
    """One accepted step with error control into the buffers ynew, k7 (f there) and K (the
    stages k2..k6); returns (ok, t_new, h_used, h_next, nfev)."""
    nfev = 0
    for _ in range(500):
        h = min(h, hmax, t_bound - t)
        if h <= 1e-15 * max(1.0, abs(t)):
            break
        stages(p, t, y, k1, h, ynew, k7, err, K)
        nfev += 6
        en = err_norm(err, y, ynew, rtol, atol)
        if en <= 1.0:
            fac = 10.0 if en == 0 else min(10.0, 0.9 * en ** -0.2)
            tn = t + h if t + h < t_bound else t_bound
            return True, tn, h, h * fac, nfev
        h *= 0.2 if en != en else max(0.2, 0.9 * en ** -0.2)
    return False, t, h, h, nfev


@jit
def dense_coefficients(y, ynew, k1, k7, K, h, rc):
    """The rows of rc (5, n) of the order-4 continuous extension of the step (Hairer's CONTD5):
    y(t₀ + θh) = rc₀ + θ(rc₁ + (1−θ)(rc₂ + θ(rc₃ + (1−θ)rc₄)))."""
    for a in range(y.shape[0]):
        ydiff = ynew[a] - y[a]
        bspl = h * k1[a] - ydiff
        rc[0, a] = y[a]
        rc[1, a] = ydiff
        rc[2, a] = bspl
        rc[3, a] = ydiff - h * k7[a] - bspl
        rc[4, a] = h * (D1 * k1[a] + D3 * K[1, a] + D4 * K[2, a] + D5 * K[3, a] + D6 * K[4, a] + D7 * k7[a])


@jit
def run_quiet(p, t, y, k1, h, hmax, t_bound, rtol, atol, max_steps, W, b, s, g_last, dec_before, state, gatol,
              dip_factor, rc):
    """Steps from (t, y) with k1 = f(t, y) while every affine guard g = W·y + b passes the
    engine's scan test (:func:`landau.verify.hybrid.locate._quiet_guards`) on the step's dense
    output at the fractions s and at the step end, up to ``max_steps`` steps or ``t_bound``.

    y and k1 are advanced in place to the end of the last step taken, rc holds its dense
    coefficients; ``g_last``, ``dec_before`` and ``state`` are advanced past every quiet step.
    Returns (code, t_old, t, h_used, h_next, nfev, nsteps), h_used the length of the last step:
    code 1 = the last step is not quiet (the engine scans it), 2 = t_bound reached with every
    step quiet, 3 = ``max_steps`` quiet steps, 0 = step-size underflow (y, k1 unchanged since
    the last accepted step)."""
    n, m, k = y.shape[0], s.shape[0], W.shape[0]
    ynew, k7, err, K = np.empty(n), np.empty(n), np.empty(n), np.empty((5, n))
    vals = np.empty((k, 3 * m + 1))
    yk = np.empty(n)
    nfev, nsteps, t_old, h_used = 0, 0, t, 0.0
    while nsteps < max_steps:
        ok, tn, hu, h, nf = advance_into(p, t, y, k1, h, hmax, t_bound, rtol, atol, ynew, k7, err, K)
        nfev += nf
        if not ok:
            return 0, t_old, t, h_used, h, nfev, nsteps
        nsteps += 1
        h_used = hu
        dense_coefficients(y, ynew, k1, k7, K, hu, rc)
        finite = True
        for a in range(n):
            finite = finite and np.isfinite(ynew[a])
        for q in range(m):
            th = s[q]
            for a in range(n):
                yk[a] = rc[0, a] + th * (rc[1, a] + (1 - th) * (rc[2, a] + th * (rc[3, a] + (1 - th) * rc[4, a])))
            for j in range(k):
                g = b[j]
                for a in range(n):
                    g += W[j, a] * yk[a]
                vals[j, q] = g
                vals[j, m + 1 + q] = g
                vals[j, 2 * m + 1 + q] = g
        for j in range(k):
            g = b[j]
            for a in range(n):
                g += W[j, a] * ynew[a]
            vals[j, m] = g
        t_old = t
        t = tn
        for a in range(n):
            y[a] = ynew[a]
            k1[a] = k7[a]
        if not finite or not _quiet_guards(vals, m, g_last, dec_before, state, gatol, dip_factor):
            return 1, t_old, t, h_used, h, nfev, nsteps
        if t >= t_bound:
            return 2, t_old, t, h_used, h, nfev, nsteps
    return 3, t_old, t, h_used, h, nfev, nsteps
