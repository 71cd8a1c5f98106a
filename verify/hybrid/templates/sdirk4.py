"""Template: one SDIRK4 step over a kernel with Jacobian (see landau.verify.hybrid.specialise).

Free names: ``fun(t, y, p, out)``, ``jac(t, y, p, out)`` (the kernel), ``jit`` (the numba decorator).
"""

import math

import numpy as np

from landau.verify.hybrid.compiled import SDIRK_A, SDIRK_C, SDIRK_E, SDIRK_GAMMA
from landau.verify.hybrid.radau import _lu, _solve

A = SDIRK_A
C = SDIRK_C
E = SDIRK_E
G = SDIRK_GAMMA

@jit
def attempt(p, t, y, f0, h, rtol, atol, ynew, fnew, err):
    n = y.shape[0]
    J = np.empty((n, n))
    jac(t, y, p, J)
    M = np.empty((n, n))
    hg = h * G
    for i in range(n):
        for j in range(n):
            M[i, j] = -hg * J[i, j]
        M[i, i] += 1.0
    piv = np.empty(n, np.int64)
    if not _lu(M, piv):
        return 2, 0
    K = np.empty((5, n))
    s = np.empty(n)
    Y = y.copy()
    fY = np.empty(n)
    r = np.empty(n)
    sc = np.empty(n)
    for i in range(n):
        sc[i] = atol[i] + rtol * abs(y[i])
    nfev = 0
    for st in range(5):
        for c in range(n):
            acc = 0.0
            for j in range(st):
                acc += A[st][j] * K[j, c]
            s[c] = y[c] + h * acc
        tc = t + C[st] * h
        # predictor: the previous stage value (Y), then simplified Newton on Y = s + hγ f(Y)
        ok = False
        dn_old = -1.0
        for it in range(10):
            fun(tc, Y, p, fY)
            nfev += 1
            for c in range(n):
                r[c] = s[c] + hg * fY[c] - Y[c]
            _solve(M, piv, r)
            dn = 0.0
            for c in range(n):
                Y[c] += r[c]
                q = r[c] / sc[c]
                dn += q * q
            dn = math.sqrt(dn / n)
            if not math.isfinite(dn):
                break
            if dn_old > 0.0:
                rate = dn / dn_old
                if rate >= 1.0:
                    break
                if rate / (1.0 - rate) * dn < 1e-2:
                    ok = True
                    break
            if dn < 1e-10:
                ok = True
                break
            dn_old = dn
        if not ok:
            return 1, nfev
        for c in range(n):
            K[st, c] = (Y[c] - s[c]) / hg
    for c in range(n):
        ynew[c] = Y[c]
        fnew[c] = K[4, c]
        e = 0.0
        for j in range(5):
            e += E[j] * K[j, c]
        err[c] = h * e
    _solve(M, piv, err)
    return 0, nfev

