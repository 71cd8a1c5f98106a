"""Compiled Radau IIA (order 5) integrator for small stiff systems with an analytic Jacobian.

The three-stage Radau IIA collocation method (Hairer & Wanner, *Solving ODEs II*, Sec. IV.8)
solved by simplified Newton on the full 3n×3n stage system I − h(A⊗J) — for the
spring–block n = 3…4, so one dense LU per step is cheaper than the complex
eigen-decomposition of the classical code.  Error estimate and step-size control follow
the standard radau5 recipe (embedded estimate (μ/h·I − J)⁻¹(f₀ + Σ eᵢZᵢ/h), predictive
Gustafsson controller), dense output is the collocation polynomial.

Everything runs inside one ``numba`` function compiled once (cached on disk) that calls
the right-hand side and Jacobian through first-class function pointers of signature
``f(t, y, p, out)`` / ``jac(t, y, p, out)`` — a new friction law compiles only its own
two small functions.

Crossings of ``y[ev_idx] = ev_val`` are located on the dense output (the collocation cubic,
by the compiled event locator of :mod:`landau.verify.hybrid.crossing`) and recorded; the run can stop after a number of crossings in a
chosen direction (Poincaré returns).  Accepted steps may be recorded for plots.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np
from numba import types

from landau.verify.hybrid.crossing import cubic, cubic_crossing

SQ6 = math.sqrt(6.0)
#: collocation nodes c_i and Butcher matrix A of Radau IIA (order 5)
C_NODES = np.array([(4 - SQ6) / 10, (4 + SQ6) / 10, 1.0])
A_RADAU = np.array([
    [(88 - 7 * SQ6) / 360, (296 - 169 * SQ6) / 1800, (-2 + 3 * SQ6) / 225],
    [(296 + 169 * SQ6) / 1800, (88 + 7 * SQ6) / 360, (-2 - 3 * SQ6) / 225],
    [(16 - SQ6) / 36, (16 + SQ6) / 36, 1.0 / 9],
])
#: the real eigenvalue of A⁻¹ (γ₀⁻¹) and the embedded-error weights e_i (radau5)
MU_REAL = 3 + 3 ** (2 / 3) - 3 ** (1 / 3)
E_ERR = np.array([-13 - 7 * SQ6, -13 + 7 * SQ6, -1.0]) / 3
#: Z_i = Σ_j Q_j c_i^j  →  Q = VINV·Z (dense output y(t+xh) = y + Σ Q_j x^j)
VINV = np.linalg.inv(np.array([[c ** j for j in (1, 2, 3)] for c in C_NODES]))

NEWTON_MAXITER = 7
STATUS = {0: "finished", 1: "terminal event", -1: "step size too small", -2: "maximum number of steps",
          -3: "non-finite state"}

SIG = types.void(types.float64, types.float64[::1], types.float64[::1], types.float64[::1])
SIG_JAC = types.void(types.float64, types.float64[::1], types.float64[::1], types.float64[:, ::1])
FUN_T = types.FunctionType(SIG)
JAC_T = types.FunctionType(SIG_JAC)


class FunctionPointer(types.WrapperAddressProtocol):
    """A compiled function handed to :func:`radau_core` by its machine address.

    Passing a numba dispatcher where a first-class function type is expected makes numba look
    up (and possibly compile) its wrapper at *every* call — about 0.2 ms, more than a whole
    loose-tolerance run of a small system.  This object resolves the address once; numba then
    only reads it (:meth:`__wrapper_address__`).  It keeps the dispatcher alive, so the
    address stays valid.
    """

    def __init__(self, dispatcher, signature):
        from numba.experimental.function_type import _get_wrapper_address

        self._dispatcher = dispatcher
        self._signature = signature
        self._address = _get_wrapper_address(dispatcher, signature)

    def __wrapper_address__(self) -> int:
        return self._address

    def signature(self):
        return self._signature

    def __call__(self, *args):
        return self._dispatcher(*args)


_POINTERS: dict[tuple[int, str], FunctionPointer] = {}


def pointers(fun, jac) -> tuple[FunctionPointer, FunctionPointer]:
    """(fun, jac) as :class:`FunctionPointer` objects for :func:`radau_core` (made once per function).

    Parameters
    ----------
    fun, jac : numba dispatchers
        ``fun(t, y, p, out)`` and ``jac(t, y, p, out)`` (signatures :data:`SIG`, :data:`SIG_JAC`).

    Returns
    -------
    tuple of FunctionPointer
    """
    out = []
    for f, sig, tag in ((fun, SIG, "f"), (jac, SIG_JAC, "J")):
        if isinstance(f, FunctionPointer):
            out.append(f)
            continue
        key = (id(f), tag)
        ptr = _POINTERS.get(key)
        if ptr is None or ptr._dispatcher is not f:
            ptr = _POINTERS[key] = FunctionPointer(f, sig)
        out.append(ptr)
    return out[0], out[1]
F64 = types.float64
A1 = types.float64[::1]
A2 = types.float64[:, ::1]
I64 = types.int64


@nb.njit(cache=True)
def _lu(a, piv):
    n = a.shape[0]
    for k in range(n):
        m = k
        big = abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                m = i
        piv[k] = m
        if big == 0.0:
            return False
        if m != k:
            for j in range(n):
                tmp = a[k, j]
                a[k, j] = a[m, j]
                a[m, j] = tmp
        inv = 1.0 / a[k, k]
        for i in range(k + 1, n):
            a[i, k] *= inv
            f = a[i, k]
            if f != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= f * a[k, j]
    return True


@nb.njit(cache=True)
def _solve(lu, piv, b):
    n = lu.shape[0]
    for k in range(n):
        m = piv[k]
        if m != k:
            tmp = b[k]
            b[k] = b[m]
            b[m] = tmp
    for i in range(n):
        s = b[i]
        for j in range(i):
            s -= lu[i, j] * b[j]
        b[i] = s
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= lu[i, j] * b[j]
        b[i] = s / lu[i, i]


@nb.njit(cache=True)
def _rms(x, scale):
    s = 0.0
    for i in range(x.shape[0]):
        r = x[i] / scale[i]
        s += r * r
    return math.sqrt(s / x.shape[0])


@nb.njit(cache=True)
def _poly(y0, Q, x, i):
    return y0[i] + x * (Q[0, i] + x * (Q[1, i] + x * Q[2, i]))


@nb.njit(types.Tuple((I64, F64, A1, I64[::1], A1, A2, A1, A2, F64, A2))(
    FUN_T, JAC_T, F64, A1, F64, A1, F64, A1, F64, F64, I64, I64, F64, I64, I64, I64, A2, A2, A2, A1), cache=True)
def radau_core(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps,
               ev_idx, ev_val, ev_dir, ev_stop, rec_cap, AR, VI, EVBUF, EVDIR):
    """Integrate from t0 to t_end.  Returns (status, t, y, counters, ev_t, ev_y, rec_t, rec_y, h, Q).

    counters = [accepted steps, rejected steps, f evaluations, Jacobians, LU decompositions,
    Newton failures, events, recorded steps].  ``EVBUF`` (m × n) / ``EVDIR`` (m) receive
    crossings; ``ev_idx < 0`` disables events; ``ev_stop > 0`` stops after that many
    crossings in direction ``ev_dir`` (±1, 0 = either).  ``h`` is the next step size and ``Q``
    the last accepted step's collocation polynomial (y(t_old + x h_old) = y_old + Σ_j Q_j x^{j+1}),
    so that a caller can drive the method one step at a time (``max_steps = 1``).
    """
    n = y0.shape[0]
    N3 = 3 * n
    cnt = np.zeros(8, dtype=np.int64)
    rec_t = np.empty(rec_cap)
    rec_y = np.empty((rec_cap, n))
    y = y0.copy()
    t = t0
    f0 = np.empty(n)
    fun(t, y, p, f0)
    cnt[2] += 1
    J = np.empty((n, n))
    Mfull = np.empty((N3, N3))
    Mreal = np.empty((n, n))
    pivF = np.empty(N3, dtype=np.int64)
    pivR = np.empty(n, dtype=np.int64)
    Z = np.zeros((3, n))
    F = np.empty((3, n))
    JB = np.empty((3, n, n))
    use_full = False
    R = np.empty(N3)
    ytmp = np.empty(n)
    ynew = np.empty(n)
    scale = np.empty(n)
    err = np.empty(n)
    Q = np.zeros((3, n))
    Qprev = np.zeros((3, n))
    have_prev = False
    yprev = np.empty(n)
    tprev = 0.0
    hprev = 1.0
    EPS = 2.220446049250313e-16
    newton_tol = max(10 * EPS / rtol, min(0.03, rtol ** 0.5))
    h = min(h0, max_step, t_end - t0)
    err_old = -1.0
    h_old = -1.0
    rejected = False
    status = 0
    nev_dir = 0
    for i in range(n):
        if not math.isfinite(y[i]) or not math.isfinite(f0[i]):
            status = -3
            t_end = t
    if rec_cap > 0:
        rec_t[0] = t
        rec_y[0] = y
        cnt[7] = 1
    while t < t_end:
        if cnt[0] + cnt[1] >= max_steps:
            status = -2
            break
        if h > t_end - t:
            h = t_end - t
        if h < 10 * EPS * max(abs(t), 1e-300) or h <= 0.0:
            status = -1
            break
        jac(t, y, p, J)
        cnt[3] += 1
        for a in range(3):
            for b in range(3):
                for i in range(n):
                    for j in range(n):
                        Mfull[a * n + i, b * n + j] = -h * AR[a, b] * J[i, j]
        for i in range(N3):
            Mfull[i, i] += 1.0
        ok = _lu(Mfull, pivF)
        cnt[4] += 1
        # Newton start: extrapolate the previous collocation polynomial
        for a in range(3):
            ca = (0.1550510257216822 if a == 0 else (0.6449489742783178 if a == 1 else 1.0))
            for i in range(n):
                if have_prev:
                    x = (t + ca * h - tprev) / hprev
                    Z[a, i] = _poly(yprev, Qprev, x, i) - y[i]
                else:
                    Z[a, i] = 0.0
        converged = False
        dW_old = -1.0
        rate = -1.0
        n_iter = 0
        if ok:
            for it in range(3 * NEWTON_MAXITER if use_full else NEWTON_MAXITER):
                n_iter = min(it + 1, NEWTON_MAXITER)
                finite = True
                for a in range(3):
                    ca = (0.1550510257216822 if a == 0 else (0.6449489742783178 if a == 1 else 1.0))
                    for i in range(n):
                        ytmp[i] = y[i] + Z[a, i]
                    fa = F[a]
                    fun(t + ca * h, ytmp, p, fa)
                    cnt[2] += 1
                    for i in range(n):
                        if not math.isfinite(fa[i]):
                            finite = False
                if not finite:
                    break
                if use_full:
                    # full Newton: the stage Jacobians J(Y_b) in I − h(A ⊗ I)·diag(J(Y_b)); needed when the
                    # Jacobian changes by orders of magnitude within a step (ẇ ∝ e^{−w} as v → 0)
                    for b in range(3):
                        cb = (0.1550510257216822 if b == 0 else (0.6449489742783178 if b == 1 else 1.0))
                        for i in range(n):
                            ytmp[i] = y[i] + Z[b, i]
                        jac(t + cb * h, ytmp, p, JB[b])
                        cnt[3] += 1
                    for a in range(3):
                        for b in range(3):
                            for i in range(n):
                                for j in range(n):
                                    Mfull[a * n + i, b * n + j] = -h * AR[a, b] * JB[b, i, j]
                    for i in range(N3):
                        Mfull[i, i] += 1.0
                    if not _lu(Mfull, pivF):
                        break
                    cnt[4] += 1
                for a in range(3):
                    for i in range(n):
                        s = -Z[a, i]
                        for b in range(3):
                            s += h * AR[a, b] * F[b, i]
                        R[a * n + i] = s
                _solve(Mfull, pivF, R)
                dW = 0.0
                for a in range(3):
                    for i in range(n):
                        sc = atol[i] + abs(y[i] + Z[a, i]) * rtol
                        r = R[a * n + i] / sc
                        dW += r * r
                        Z[a, i] += R[a * n + i]
                dW = math.sqrt(dW / N3)
                if dW_old > 0:
                    rate = dW / dW_old
                if use_full:
                    if (rate >= 1.0 and it >= 4) or it >= 3 * NEWTON_MAXITER - 1:
                        break
                    if dW < newton_tol and rate < 1.0:
                        converged = True
                        break
                    dW_old = dW
                    continue
                if rate >= 1.0 or (rate > 0 and rate ** (NEWTON_MAXITER - it) / (1 - rate) * dW > newton_tol):
                    break
                if dW == 0.0 or (rate > 0 and rate / (1 - rate) * dW < newton_tol):
                    converged = True
                    break
                dW_old = dW
        if not converged:
            cnt[5] += 1
            cnt[1] += 1
            if use_full:
                h *= 0.5
            use_full = True
            rejected = True
            continue
        for i in range(n):
            ynew[i] = y[i] + Z[2, i]
        # embedded error estimate (radau5): (μ/h I − J)⁻¹ (f0 + Σ e_a Z_a / h)
        for i in range(n):
            for j in range(n):
                Mreal[i, j] = -J[i, j]
            Mreal[i, i] += MU_REAL / h
        _lu(Mreal, pivR)
        cnt[4] += 1
        for i in range(n):
            s = f0[i]
            for a in range(3):
                s += E_ERR[a] * Z[a, i] / h
            err[i] = s
            scale[i] = atol[i] + max(abs(y[i]), abs(ynew[i])) * rtol
        ZE = err.copy()
        for i in range(n):
            ZE[i] -= f0[i]
        _solve(Mreal, pivR, err)
        err_norm = _rms(err, scale)
        if rejected and err_norm > 1.0:
            for i in range(n):
                ytmp[i] = y[i] + err[i]
            fun(t, ytmp, p, err)
            cnt[2] += 1
            for i in range(n):
                err[i] += ZE[i]
            _solve(Mreal, pivR, err)
            err_norm = _rms(err, scale)
        if not math.isfinite(err_norm):
            cnt[1] += 1
            h *= 0.25
            rejected = True
            continue
        safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)
        if err_norm > 1.0:
            fac = max(0.2, safety * err_norm ** -0.25)
            h *= fac
            cnt[1] += 1
            rejected = True
            continue
        # accepted
        cnt[0] += 1
        use_full = False
        for j in range(3):
            for i in range(n):
                s = 0.0
                for a in range(3):
                    s += VI[j, a] * Z[a, i]
                Q[j, i] = s
        t_new = t + h
        # crossings of y[ev_idx] = ev_val on the dense output
        stop = False
        if ev_idx >= 0:
            # every sign change of the collocation cubic in the step (the compiled event locator:
            # exact for double crossings, root on the new side)
            g0 = y[ev_idx] - ev_val
            c1 = Q[0, ev_idx]
            c2 = Q[1, ev_idx]
            c3 = Q[2, ev_idx]
            xa = 0.0
            ga = g0
            for _ in range(4):  # a cubic changes sign at most three times
                if ga == 0.0:
                    break
                sgn = -1.0 if ga > 0.0 else 1.0
                xr = cubic_crossing(g0, c1, c2, c3, xa, sgn, True)
                if xr < 0.0:
                    break
                d = 1 if sgn > 0.0 else -1
                k = cnt[6]
                if k < EVBUF.shape[0]:
                    EVDIR[k] = d
                    EVBUF[k, 0] = t + xr * h
                    for i in range(n):
                        EVBUF[k, 1 + i] = _poly(y, Q, xr, i)
                    cnt[6] += 1
                if ev_stop > 0 and (ev_dir == 0 or d == ev_dir):
                    nev_dir += 1
                    if nev_dir >= ev_stop:
                        stop = True
                        break
                xa = xr
                ga = g0 + cubic(c1, c2, c3, xr)
                if xr >= 1.0:
                    break
        # keep this step's polynomial for the next Newton start
        for i in range(n):
            yprev[i] = y[i]
        for j in range(3):
            for i in range(n):
                Qprev[j, i] = Q[j, i]
        tprev = t
        hprev = h
        have_prev = True
        t = t_new
        for i in range(n):
            y[i] = ynew[i]
        fun(t, y, p, f0)
        cnt[2] += 1
        if rec_cap > 0 and cnt[7] < rec_cap:
            rec_t[cnt[7]] = t
            for i in range(n):
                rec_y[cnt[7], i] = y[i]
            cnt[7] += 1
        if stop:
            status = 1
            break
        # predictive step-size control (Gustafsson)
        if err_old > 0 and err_norm > 0:
            mult = h / h_old * (err_old / err_norm) ** 0.25
        else:
            mult = 1.0
        fac = min(1.0, mult) * (err_norm ** -0.25 if err_norm > 0 else 10.0)
        fac = min(10.0, safety * fac)
        if rejected:
            fac = min(1.0, fac)
        h_old = h
        err_old = max(err_norm, 1e-10)
        h = min(h * fac, max_step)
        rejected = False
    ne = min(cnt[6], EVBUF.shape[0])
    return (status, t, y, cnt, EVBUF[:ne, 0].copy(), EVBUF[:ne, 1:].copy(), rec_t[:cnt[7]].copy(),
            rec_y[:cnt[7]].copy(), h, Qprev)
