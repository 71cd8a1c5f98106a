"""Template: the Dormand–Prince 5(4) step over a kernel (see landau.verify.hybrid.specialise).

Free names: ``fun(t, y, p, out)`` (the kernel), ``jit`` (the numba decorator).
"""

import numpy as np

from landau.verify.hybrid.compiled import (A21, A31, A32, A41, A42, A43, A51, A52, A53, A54, A61, A62, A63, A64,
                                           A65, B1, B3, B4, B5, B6, C2, C3, C4, C5, E1, E3, E4, E5, E6, E7,
                                           err_norm)


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
