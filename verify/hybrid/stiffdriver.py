"""The pieces of the step loop shared by the compiled stiff integrators.

The s-stage Radau IIA (:mod:`landau.verify.hybrid.collocation`, whose s = 3 instance is the
default order-5 method of :mod:`landau.verify.hybrid.radau`) and RODAS4
(:mod:`landau.verify.hybrid.rosenbrock`) differ in how one step is attempted — the stage
solve and the embedded error estimate — and in their dense output.  Everything else is
here, written once:

* the set-up (:func:`_start`: first evaluation of f, the check that the initial state is
  finite, the counters, the buffers of recorded steps) and the returned tuple
  (:func:`_finish`);
* the guards before a step (:func:`_guard`: the step budget, the end of the interval,
  step-size underflow);
* the error test (:func:`_retry_size`: a non-finite error retries with h/4, an error above
  the tolerance with h·max(0.2, safety·err^(−1/(q+1)))) and the predictive (Gustafsson 1994)
  controller after an accepted step (:func:`_next_size`), with the exponent 1/(q + 1) of the
  estimate's order q and the method's largest growth factor;
* crossings of ``y[ev_idx] = ev_val`` located on an accepted step's cubic dense output (the
  compiled event locator of :mod:`landau.verify.hybrid.crossing`), with a stop after a number
  of crossings in a chosen direction (Poincaré returns) (:func:`_crossings`, called on the steps
  where :func:`_may_cross` cannot rule a sign change out), and the recording of accepted steps
  (:func:`_record`);
* the small dense linear algebra (LU with partial pivoting, its solve), the scaled RMS error
  norm and the evaluation of a dense output polynomial.

Each method keeps its own ``while`` loop over these pieces, with its stage arrays as local
variables: handing a method's work arrays to a shared loop (as a tuple, or as arguments of a
function called every step) costs numba two reference-count updates per array per step,
measured 20–120 % of a step of the 3-state spring–block.  The pieces take scalars or few arrays
and are called once per run, once per step or only when events or recording are asked for; a
loop that passes them views without reference counts (:mod:`landau.verify.hybrid.nrt`) pays
no atomic update at all.  :func:`_lu_n` and :func:`_solve_n` are the LU and its solve inlined
where they are called, so that with a constant size the compiler unrolls them (the same
operations in the same order as :func:`_lu` and :func:`_solve`).

numba's cache of a compiled function is invalidated only by changes to its own source file:
after editing this module, delete the cache files of the cores and of
:mod:`landau.verify.hybrid.fastcall` (``__pycache__/*.nbi``, ``*.nbc``) in a development
checkout.

References
----------
Hairer, E., Wanner, G. (1996). Solving Ordinary Differential Equations II, 2nd ed.,
Springer, Sec. IV.8 (step-size control of implicit Runge–Kutta methods).
Gustafsson, K. (1994). Control-theoretic techniques for stepsize selection in implicit
Runge–Kutta methods. ACM Trans. Math. Softw. 20, 496–517.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from landau.verify.hybrid.crossing import cubic, cubic_crossing

__all__ = ["EPS", "STATUS"]

#: double-precision machine epsilon
EPS = 2.220446049250313e-16
#: the status codes every core returns
STATUS = {0: "finished", 1: "terminal event", -1: "step size too small", -2: "maximum number of steps",
          -3: "non-finite state"}


@nb.njit(cache=True)
def _lu(a, piv):
    """In-place LU decomposition of ``a`` with partial pivoting (row swaps in ``piv``);
    False when a pivot is exactly zero."""
    return _lu_n(a, piv, a.shape[0])


@nb.njit(cache=True, inline="always")
def _lu_n(a, piv, n):
    """:func:`_lu` of the leading n × n block, inlined where it is called: with a constant
    ``n`` the compiler unrolls the loops (same operations in the same order)."""
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
    """Solve with the factors of :func:`_lu`, in place in ``b``."""
    _solve_n(lu, piv, b, lu.shape[0])


@nb.njit(cache=True, inline="always")
def _permute_forward(lu, piv, b, n):
    """The row interchanges and the unit-lower-triangular forward substitution of a solve with
    the factors of :func:`_lu` (leading n × n block), in place in ``b``."""
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


@nb.njit(cache=True, inline="always")
def _solve_n(lu, piv, b, n):
    """:func:`_solve` with the leading n × n block, inlined where it is called (see :func:`_lu_n`)."""
    _permute_forward(lu, piv, b, n)
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= lu[i, j] * b[j]
        b[i] = s / lu[i, i]


@nb.njit(cache=True, inline="always")
def _solve_recip(lu, piv, dinv, b, n):
    """:func:`_solve_n` with the reciprocals ``dinv`` of the pivots given (for complex factors,
    where a division costs several multiplications)."""
    _permute_forward(lu, piv, b, n)
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= lu[i, j] * b[j]
        b[i] = s * dinv[i]


@nb.njit(cache=True)
def _rms(x, scale):
    """The error norm: the root mean square of x / scale."""
    s = 0.0
    for i in range(x.shape[0]):
        r = x[i] / scale[i]
        s += r * r
    return math.sqrt(s / x.shape[0])


@nb.njit(cache=True)
def _poly(y0, Q, x, i):
    """Component i of the dense output y0 + Σ_j Q_j x^{j+1} (Horner, any number of rows of Q)."""
    acc = Q[Q.shape[0] - 1, i]
    for j in range(Q.shape[0] - 2, -1, -1):
        acc = Q[j, i] + x * acc
    return y0[i] + x * acc


@nb.njit(cache=True)
def _may_cross(g0, c1, c2, c3):
    """Whether g(x) = g0 + c1 x + c2 x² + c3 x³ may change sign on [0, 1] (else :func:`_crossings`
    would find nothing): False for g0 = 0 (a crossing starting on the surface is not one), and
    when |g0| exceeds the cubic's largest change |c1| + |c2| + |c3| by a margin (10⁻¹²) far
    above the rounding of its evaluation — most steps, decided with scalars only."""
    return g0 != 0.0 and (abs(c1) + abs(c2) + abs(c3)) * (1.0 + 1e-12) >= abs(g0)


@nb.njit(cache=True)
def _crossings(y, Q, t, h, ev_idx, ev_val, ev_dir, ev_stop, nev_dir, cnt, EVBUF, EVDIR):
    """Record every sign change of y[ev_idx] − ev_val on the step's cubic dense output.

    The compiled event locator is exact for double crossings and returns the root on the new
    side.  Returns (stop, nev_dir): whether the ``ev_stop``-th crossing in direction
    ``ev_dir`` was reached, and the updated count of such crossings.
    """
    n = y.shape[0]
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
                return True, nev_dir
        xa = xr
        ga = g0 + cubic(c1, c2, c3, xr)
        if xr >= 1.0:
            break
    return False, nev_dir


@nb.njit(cache=True)
def _start(fun, t0, y0, t_end, p, h0, max_step, rec_cap):
    """The set-up of a run: f at the start (counted), the first step size, the counters and the
    buffers of recorded steps (the first holding the start).

    Returns (y, f0, cnt, rec_t, rec_y, h, status, t_end): a non-finite start gives status −3
    and t_end = t0, so that no step is taken.
    """
    n = y0.shape[0]
    cnt = np.zeros(8, dtype=np.int64)
    rec_t = np.empty(rec_cap)
    rec_y = np.empty((rec_cap, n))
    y = y0.copy()
    f0 = np.empty(n)
    fun(t0, y, p, f0)
    cnt[2] += 1
    h = min(h0, max_step, t_end - t0)
    status = 0
    for i in range(n):
        if not math.isfinite(y[i]) or not math.isfinite(f0[i]):
            status = -3
            t_end = t0
    if rec_cap > 0:
        rec_t[0] = t0
        rec_y[0] = y
        cnt[7] = 1
    return y, f0, cnt, rec_t, rec_y, h, status, t_end


@nb.njit(cache=True)
def _guard(steps, max_steps, t, t_end, h):
    """(status, h) before a step: the budget of ``max_steps`` attempts (−2), h cut to the end of
    the interval, step-size underflow (−1); status 0 to go on."""
    if steps >= max_steps:
        return -2, h
    if h > t_end - t:
        h = t_end - t
    if h < 10 * EPS * max(abs(t), 1e-300) or h <= 0.0:
        return -1, h
    return 0, h


@nb.njit(cache=True)
def _retry_size(h, err_norm, safety, expo):
    """The step size to retry with when the error test fails — h/4 for a non-finite error,
    h·max(0.2, safety·err^(−expo)) above the tolerance — or −1 when the step is accepted."""
    if not math.isfinite(err_norm):
        return h * 0.25
    if err_norm > 1.0:
        return h * max(0.2, safety * err_norm ** -expo)
    return -1.0


@nb.njit(cache=True)
def _next_size(h, h_old, err_norm, err_old, rejected, safety, expo, facmax, max_step):
    """The predictive (Gustafsson 1994) controller after an accepted step of size h.

    ``expo`` = 1/(q + 1) for an estimate of order q; the step grows by at most ``facmax``, and
    not at all right after a rejection.  Returns (next h, h_old, err_old) for the next call.
    """
    if err_old > 0 and err_norm > 0:
        mult = h / h_old * (err_old / err_norm) ** expo
    else:
        mult = 1.0
    fac = min(1.0, mult) * (err_norm ** -expo if err_norm > 0 else facmax)
    fac = min(facmax, safety * fac)
    if rejected:
        fac = min(1.0, fac)
    return min(h * fac, max_step), h, max(err_norm, 1e-10)


@nb.njit(cache=True)
def _record(cnt, rec_t, rec_y, t, y):
    """Keep the accepted step's end (t, y) while the buffers have room (count in ``cnt[7]``)."""
    k = cnt[7]
    if k < rec_t.shape[0]:
        rec_t[k] = t
        for i in range(y.shape[0]):
            rec_y[k, i] = y[i]
        cnt[7] += 1


@nb.njit(cache=True)
def _finish(status, t, y, cnt, EVBUF, rec_t, rec_y, h, Q):
    """The tuple every core returns: (status, t, y, counters, ev_t, ev_y, rec_t, rec_y, h, Q)."""
    ne = min(cnt[6], EVBUF.shape[0])
    return (status, t, y, cnt, EVBUF[:ne, 0].copy(), EVBUF[:ne, 1:].copy(), rec_t[:cnt[7]].copy(),
            rec_y[:cnt[7]].copy(), h, Q)
