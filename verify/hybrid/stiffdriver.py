"""The step loop shared by the compiled stiff integrators, and the pieces it is made of.

The order-5 Radau IIA (:mod:`landau.verify.hybrid.radau`), the s-stage Radau IIA
(:mod:`landau.verify.hybrid.collocation`) and RODAS4 (:mod:`landau.verify.hybrid.rosenbrock`)
differ only in how one step is attempted — the stage solve and the embedded error estimate —
and in their dense output.  Everything else is here, written once:

* the set-up (first evaluation of f, the check that the initial state is finite, the counters,
  the buffers of recorded steps), the step-size guards (end of the interval, step-size
  underflow, the step budget) and the returned tuple;
* the rejection of a step (stage failure: the factor the method asks for; a non-finite error:
  h/4; an error above the tolerance: h·max(0.2, safety·err^(−1/(q+1))));
* the predictive (Gustafsson 1994) step-size controller after an accepted step, with the
  exponent 1/(q + 1) of the estimate's order q and the method's largest growth factor;
* crossings of ``y[ev_idx] = ev_val`` located on the accepted step's dense output when that is
  a cubic (the compiled event locator of :mod:`landau.verify.hybrid.crossing`), with a stop
  after a number of crossings in a chosen direction (Poincaré returns), and the recording of
  accepted steps;
* the small dense linear algebra (LU with partial pivoting and its solve) and the scaled RMS
  error norm.

:func:`make_driver` binds the loop to one method's two compiled functions (``attempt`` and
``accept``, contracts in its docstring).  numba inlines them as it does any called function;
the bound loop is compiled as part of the method's core (``radau_core``, …), which numba caches
on disk with it.  numba's cache of a core is invalidated only by changes to the core's own
source file: after editing this module, delete the cache files of the cores and of
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

__all__ = ["EPS", "STATUS", "make_driver"]

#: double-precision machine epsilon
EPS = 2.220446049250313e-16
#: the status codes every core returns
STATUS = {0: "finished", 1: "terminal event", -1: "step size too small", -2: "maximum number of steps",
          -3: "non-finite state"}


@nb.njit(cache=True)
def _lu(a, piv):
    """In-place LU decomposition of ``a`` with partial pivoting (row swaps in ``piv``);
    False when a pivot is exactly zero."""
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
    """Solve with the factors of :func:`_lu`, in place in ``b``."""
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


def make_driver(attempt, accept):
    """The compiled step loop bound to one method.

    Parameters
    ----------
    attempt : numba function
        ``attempt(fun, jac, t, y, f0, h, p, rtol, atol, rejected, t_old, y_old, h_old, Q, ynew,
        cnt, W) -> (fail, err_norm, safety)``: try one step of size h from (t, y) (f0 = f(t, y));
        write the new state into ``ynew`` and return the scaled error norm and the safety factor
        of the step-size controller, or ``fail > 0`` (the step is retried with h·fail) when
        the stages could not be computed.  ``rejected`` says whether the previous attempt from
        this point was rejected; (t_old, y_old, h_old, Q) describe the last accepted step
        (``cnt[0] > 0``).  It counts its evaluations, Jacobians, LU decompositions and
        Newton failures in ``cnt[2:6]``; ``W`` is the method's coefficients and workspace.
    accept : numba function
        ``accept(y, ynew, f0, fnew, h, Q, W)``, called once a step is accepted (fnew =
        f(t + h, ynew)): write the step's dense output y(t + xh) = y + Σ_j Q_j x^{j+1} into
        ``Q`` and reset the method's per-step state.

    Returns
    -------
    numba dispatcher
        ``drive(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val,
        ev_dir, ev_stop, rec_cap, one_step, expo, facmax, stop_nonfinite, Q, W, EVBUF, EVDIR)``
        integrating from t0 to t_end.  It returns (status, t, y, counters, ev_t, ev_y, rec_t,
        rec_y, h, Q) with the codes of :data:`STATUS`; counters = [accepted steps, rejected
        steps, f evaluations, Jacobians, LU decompositions, Newton failures, events, recorded
        steps]; ``h`` is the next step size and ``Q`` the last accepted step's dense output,
        so that a caller can drive the method one step at a time (``max_steps = 1``, or
        ``one_step = 1``: return after the first accepted step).  ``EVBUF`` (m × (n + 1)) /
        ``EVDIR`` (m) receive crossings of ``y[ev_idx] = ev_val`` (``ev_idx < 0``: none; the
        dense output must then be a cubic, ``Q`` of three rows); ``ev_stop > 0`` stops after
        that many crossings in direction ``ev_dir`` (±1, 0 = either); ``rec_cap`` accepted
        steps are recorded.  ``expo`` = 1/(q + 1) for an error estimate of order q, ``facmax``
        the largest step-size growth; ``stop_nonfinite`` ends the run (status −3) at an
        accepted state where f is not finite.
    """

    @nb.njit
    def drive(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir, ev_stop,
              rec_cap, one_step, expo, facmax, stop_nonfinite, Q, W, EVBUF, EVDIR):
        n = y0.shape[0]
        cnt = np.zeros(8, dtype=np.int64)
        rec_t = np.empty(rec_cap)
        rec_y = np.empty((rec_cap, n))
        y = y0.copy()
        t = t0
        f0 = np.empty(n)
        fun(t, y, p, f0)
        cnt[2] += 1
        ynew = np.empty(n)
        fnew = np.empty(n)
        y_old = np.empty(n)
        t_old = t0
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
            fail, err_norm, safety = attempt(fun, jac, t, y, f0, h, p, rtol, atol, rejected, t_old, y_old, h_old,
                                             Q, ynew, cnt, W)
            if fail > 0.0 or not math.isfinite(err_norm) or err_norm > 1.0:
                cnt[1] += 1
                rejected = True
                if fail > 0.0:
                    h *= fail
                elif not math.isfinite(err_norm):
                    h *= 0.25
                else:
                    h *= max(0.2, safety * err_norm ** -expo)
                continue
            # accepted: f at the new point is the next step's f0
            cnt[0] += 1
            t_new = t + h
            fun(t_new, ynew, p, fnew)
            cnt[2] += 1
            accept(y, ynew, f0, fnew, h, Q, W)
            stop = False
            if ev_idx >= 0:
                stop, nev_dir = _crossings(y, Q, t, h, ev_idx, ev_val, ev_dir, ev_stop, nev_dir, cnt, EVBUF, EVDIR)
            finite = True
            for i in range(n):
                y_old[i] = y[i]
                y[i] = ynew[i]
                f0[i] = fnew[i]
                if not math.isfinite(fnew[i]):
                    finite = False
            t_old = t
            t = t_new
            if stop_nonfinite and not finite:
                status = -3
                break
            if rec_cap > 0 and cnt[7] < rec_cap:
                rec_t[cnt[7]] = t
                for i in range(n):
                    rec_y[cnt[7], i] = y[i]
                cnt[7] += 1
            if stop:
                status = 1
                break
            # predictive step-size control (Gustafsson 1994)
            if err_old > 0 and err_norm > 0:
                mult = h / h_old * (err_old / err_norm) ** expo
            else:
                mult = 1.0
            fac = min(1.0, mult) * (err_norm ** -expo if err_norm > 0 else facmax)
            fac = min(facmax, safety * fac)
            if rejected:
                fac = min(1.0, fac)
            h_old = h
            err_old = max(err_norm, 1e-10)
            h = min(h * fac, max_step)
            rejected = False
            if one_step == 1:
                break
        ne = min(cnt[6], EVBUF.shape[0])
        return (status, t, y, cnt, EVBUF[:ne, 0].copy(), EVBUF[:ne, 1:].copy(), rec_t[:cnt[7]].copy(),
                rec_y[:cnt[7]].copy(), h, Q)

    return drive
