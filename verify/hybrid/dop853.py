"""Compiled DOP853 over a first-class kernel, with the engine's guard screen inside the loop.

The Dormand–Prince 8(5,3) method of Hairer, Nørsett & Wanner (*Solving ODEs I*, 2nd ed., Sec.
II.5 and II.6; the code DOP853): 12 stages, FSAL, the error estimate that blends the 5th- and
3rd-order embedded solutions, and the 7th-order continuous extension (3 more stages).  The
tableau is Hairer's (:mod:`landau.verify.hybrid.dop853_tableau`, the same numbers as scipy's)
and the step-size control and initial step are scipy's ``DOP853`` rules (safety 0.9, factors in [0.2, 10], exponent
−1/8,
:func:`initial_step`), so a run takes the same steps as scipy's Python stepper and its values
agree with it to rounding.

Why DOP853 and not DOPRI5: the stick–slip maps and their bifurcation locators integrate at
rtol 1e-11 (figures at 1e-9).  A work–precision run on one application of the two-block map of
Galvanetto (2004) (V = 0.25, α = 1.2, β = 1.3, from d = 0.1 to the next global stick phase at
t ≈ 4.36, atol = rtol/100, steps ≤ 1; errors of d and of the stick time against scipy's DOP853
at rtol 1e-13) measured

=====  ==============================================  ==============================================
rtol   compiled DOPRI5 (Hermite dense output)           compiled DOP853
=====  ==============================================  ==============================================
1e-9   113 steps, 726 f-evals, err d 2e-8, t 4e-7       27 steps, 555 f-evals, err d 2e-8, t 3e-8
1e-11  283 steps, 1716 f-evals, err d 1e-10, t 4e-9     43 steps, 843 f-evals, err d 2e-11, t 4e-11
=====  ==============================================  ==============================================

so at the locators' tolerance DOP853 is ~6× more accurate for half the evaluations and a
sixth of the steps (each step is one guard screen and, in Python, one call), and its
7th-order dense output locates events to the integration tolerance.

The right-hand side reaches the compiled loop as a documented numba first-class function:
:func:`kernel_function` wraps the kernel's ``fun(t, y, p, out)`` as a ``cfunc`` and hands it
over through :class:`numba.core.types.WrapperAddressProtocol` typed
``pointer_type(FUN_SIG)`` (:mod:`landau.verify.hybrid.callbacks`: numba's
``FunctionType``, unboxed from the address the pointer holds), so :func:`run_screened`,
:func:`advance` and :func:`dense` compile once per machine for every kernel
(``njit(cache=True)``, built on first use through :func:`landau.verify.compiling.compile_once`).
The step's helpers (:func:`advance`, :func:`dense`, :func:`dense_at`) are part of the loops that
call them (``inline="always"``: numba inlines them before typing), so a first build types and
optimises one function per loop rather than a tree of functions whose machine code every caller
optimises again; called from Python they compile on their own.

:func:`run_screened` takes steps while the mode's guards pass the engine's scan test
(:func:`landau.verify.hybrid.locate._quiet_guards`) on the dense output, and returns to Python
only with the step where a guard may cross (or at ``t_bound``).  One loop serves both kinds of
compiled guards: guards affine in the state and the vector field, g = w·y + u·f(t, y) + b
(``Guard.affine``, the Galvanetto models), and guards given as one compiled vector function
``gfun(t, y, p, out)`` (``Mode.guard_kernel``: the gap, contact forces and stick-cone margins of
the Lancioni model, :mod:`landau.verify.hybrid.guarded`).  The engine then locates the root on
that step's dense output to its ``xtol`` in compiled code as well (:func:`event_root`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import ClassVar

import numpy as np
from numba import cfunc, njit, types

from landau.errors import InputError
from landau.verify.compiling import compile_once
from landau.verify.hybrid import dop853_tableau as _dc
from landau.verify.hybrid.callbacks import FunctionPointer, call_pointer, jit_enabled, pointer_type, warn_once
from landau.verify.hybrid.kernel import Kernel
from landau.verify.hybrid.locate import _quiet_guards

__all__ = ["CompiledDOP853", "DOP853Solver", "FUN_SIG", "FUN_T", "kernel_function", "initial_step"]

_ARR = types.float64[::1]
FUN_SIG = types.void(types.float64, _ARR, _ARR, _ARR)
FUN_T = pointer_type(FUN_SIG)

N_STAGES = _dc.N_STAGES
A = np.ascontiguousarray(_dc.A[:N_STAGES, :N_STAGES])
B = np.ascontiguousarray(_dc.B)
C = np.ascontiguousarray(_dc.C[:N_STAGES])
E3 = np.ascontiguousarray(_dc.E3)
E5 = np.ascontiguousarray(_dc.E5)
D = np.ascontiguousarray(_dc.D)
A_EXTRA = np.ascontiguousarray(_dc.A[N_STAGES + 1:])
C_EXTRA = np.ascontiguousarray(_dc.C[N_STAGES + 1:])
N_EXT = _dc.N_STAGES_EXTENDED
N_DENSE = _dc.INTERPOLATOR_POWER
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
ERR_EXP = -1.0 / 8.0


@lru_cache(maxsize=None)
def kernel_function(fun) -> FunctionPointer:
    """The kernel function ``fun(t, y, p, out)`` (a numba dispatcher or Python function) as a
    first-class function of type :data:`FUN_T`: a ``cfunc`` (cached on disk when its source is
    in a file) handed over as a :class:`~landau.verify.hybrid.callbacks.FunctionPointer`, whose
    numba type is made once, so calling a loop with it from Python is cheap.  Called from Python
    (the loops run as plain Python under ``NUMBA_DISABLE_JIT=1``) it runs the Python kernel."""
    py = getattr(fun, "py_func", fun)
    if not jit_enabled():
        warn_once("dop853-nojit", "landau: NUMBA_DISABLE_JIT is set: the DOP853 stepper runs as plain Python "
                  "(some hundred times slower)")
    try:
        cf = cfunc(FUN_SIG, cache=True)(py)
    except RuntimeError:  # no place for numba's cache (e.g. a function defined in memory)
        cf = cfunc(FUN_SIG)(py)
    return FunctionPointer(cf, FUN_SIG, py)


@njit(cache=True)
def initial_step(fun, p, t0, y0, f0, t_bound, max_step, rtol, atol):
    """scipy's ``select_initial_step`` for an order-7 error estimate (Hairer, Nørsett & Wanner,
    Sec. II.4): the first step of scipy's DOP853 (to rounding: the norms are summed in order)."""
    n = y0.shape[0]
    span = abs(t_bound - t0)
    if span == 0.0:
        return 0.0
    d0, d1 = 0.0, 0.0
    for a in range(n):
        sc = atol[a] + abs(y0[a]) * rtol
        d0 += (y0[a] / sc) ** 2
        d1 += (f0[a] / sc) ** 2
    d0, d1 = math.sqrt(d0 / n), math.sqrt(d1 / n)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, span)
    y1, f1 = np.empty(n), np.empty(n)
    for a in range(n):
        y1[a] = y0[a] + h0 * f0[a]
    fun(t0 + h0, y1, p, f1)
    d2 = 0.0
    for a in range(n):
        sc = atol[a] + abs(y0[a]) * rtol
        d2 += ((f1[a] - f0[a]) / sc) ** 2
    d2 = math.sqrt(d2 / n) / h0
    h1 = max(1e-6, h0 * 1e-3) if d1 <= 1e-15 and d2 <= 1e-15 else (0.01 / max(d1, d2)) ** (1 / 8)
    return min(100 * h0, h1, span, max_step)


@njit(cache=True, inline="always")
def _attempt(fun, p, t, y, f, h, K, ynew, fnew, yt, rtol, atol):
    """One DOP853 step of length h from (t, y), f = f(t, y): fills K (stages, row 12 = f_new),
    ynew, fnew; returns the scaled error norm (scipy's ``_estimate_error_norm``)."""
    n = y.shape[0]
    for a in range(n):
        K[0, a] = f[a]
    for s in range(1, N_STAGES):
        for a in range(n):
            acc = 0.0
            for j in range(s):
                acc += K[j, a] * A[s, j]
            yt[a] = y[a] + acc * h
        fun(t + C[s] * h, yt, p, K[s])
    for a in range(n):
        acc = 0.0
        for j in range(N_STAGES):
            acc += K[j, a] * B[j]
        ynew[a] = y[a] + h * acc
    fun(t + h, ynew, p, fnew)
    for a in range(n):
        K[N_STAGES, a] = fnew[a]
    e5, e3 = 0.0, 0.0
    for a in range(n):
        sc = atol[a] + max(abs(y[a]), abs(ynew[a])) * rtol
        x5, x3 = 0.0, 0.0
        for j in range(N_STAGES + 1):
            x5 += K[j, a] * E5[j]
            x3 += K[j, a] * E3[j]
        x5 /= sc
        x3 /= sc
        e5 += x5 * x5
        e3 += x3 * x3
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * n)


@njit(cache=True, inline="always")
def advance(fun, p, t, y, f, h_abs, hmax, t_bound, rtol, atol, K, ynew, fnew):
    """One accepted step with scipy's DOP853 step-size control.

    Returns (ok, t_new, h_used, h_abs_next, nfev); ok False: step size too small."""
    n = y.shape[0]
    yt = np.empty(n)
    min_step = 10.0 * abs(np.nextafter(t, np.inf) - t)
    if h_abs > hmax:
        h_abs = hmax
    elif h_abs < min_step:
        h_abs = min_step
    rejected = False
    nfev = 0
    while True:
        if h_abs < min_step:
            return False, t, 0.0, h_abs, nfev
        t_new = t + h_abs
        if t_new > t_bound:
            t_new = t_bound
        h = t_new - t
        h_abs = abs(h)
        en = _attempt(fun, p, t, y, f, h, K, ynew, fnew, yt, rtol, atol)
        nfev += N_STAGES
        if en < 1.0:
            factor = MAX_FACTOR if en == 0.0 else min(MAX_FACTOR, SAFETY * en ** ERR_EXP)
            if rejected:
                factor = min(1.0, factor)
            return True, t_new, h, h_abs * factor, nfev
        h_abs *= max(MIN_FACTOR, SAFETY * en ** ERR_EXP) if en == en else MIN_FACTOR
        rejected = True


@njit(cache=True, inline="always")
def dense(fun, p, t_old, y_old, y, f_new, K, h, F):
    """The 7th-order continuous extension of the step (t_old, y_old) → (t_old + h, y): the three
    extra stages (K rows 13–15; rows 0–12 from the step) and the rows of F (7, n), as scipy's
    ``Dop853DenseOutput``.  Returns the number of evaluations (3)."""
    n = y.shape[0]
    yt = np.empty(n)
    for q in range(A_EXTRA.shape[0]):
        s = N_STAGES + 1 + q
        for a in range(n):
            acc = 0.0
            for j in range(s):
                acc += K[j, a] * A_EXTRA[q, j]
            yt[a] = y_old[a] + acc * h
        fun(t_old + C_EXTRA[q] * h, yt, p, K[s])
    for a in range(n):
        dy = y[a] - y_old[a]
        F[0, a] = dy
        F[1, a] = h * K[0, a] - dy
        F[2, a] = 2.0 * dy - h * (f_new[a] + K[0, a])
        for r in range(N_DENSE - 3):
            acc = 0.0
            for j in range(N_EXT):
                acc += D[r, j] * K[j, a]
            F[3 + r, a] = h * acc
    return 3


@njit(cache=True, inline="always")
def dense_at(F, y_old, x, out):
    """y(t_old + x h) from the rows F of :func:`dense` into out (scipy's evaluation order)."""
    n = y_old.shape[0]
    for a in range(n):
        v = 0.0
        for i in range(N_DENSE):
            v += F[N_DENSE - 1 - i, a]
            if i % 2 == 0:
                v *= x
            else:
                v *= 1.0 - x
        out[a] = v + y_old[a]


@njit(cache=True)
def dense_many(F, y_old, xs):
    n, m = y_old.shape[0], xs.shape[0]
    out = np.empty((n, m))
    col = np.empty(n)
    for k in range(m):
        dense_at(F, y_old, xs[k], col)
        for a in range(n):
            out[a, k] = col[a]
    return out


@njit(cache=True)
def run_screened(fun, p, t, y, f, h_abs, hmax, t_bound, rtol, atol, max_steps, W, b, U, gfun, gp, s,
                 g_last, dec_before, state, gatol, dip_factor, K, F, y_old, vals, rec_t, rec_y, rec):
    """Steps from (t, y), f = f(t, y), while the mode's guards pass the engine's scan test
    (:func:`landau.verify.hybrid.locate._quiet_guards`) on the step's dense output at the
    fractions s and at the step end, up to ``max_steps`` steps or ``t_bound``: one loop for both
    kinds of compiled guards.

    The guards are either the affine forms g = W·y + U·f(t, y) + b (``Guard.affine``; ``gfun``
    and ``gp`` None; the field at a sample is evaluated only when U ≠ 0, at the step end it is
    the step's f_new) or the compiled vector function ``gfun(t, y, gp, out)``
    (``Mode.guard_kernel``; W, b and U None) at the engine's sample times
    t_old + (t − t_old) s_q — the dense output at the fraction of that time, as the engine's
    scan evaluates it.  The kind is the argument left None, so each kind compiles only its own
    branch (numba prunes a branch on an argument typed None): the two entries
    (:meth:`DOP853Solver.run_quiet`, :meth:`DOP853Solver.run_guarded`) are two specialisations
    of this one loop.  The step, its dense output and the record are written inline (one
    compiled function, not a tree of them: a cold build costs per function).

    y and f are advanced in place to the end of the last step taken; F and y_old hold its dense
    output; ``vals`` (guards × 3m + 1) its guard values (``vals[:, :m]`` the samples,
    ``vals[:, m]`` the step end); ``g_last``, ``dec_before`` and ``state`` are advanced past
    every quiet step.  With ``rec_t`` not None and ``rec_t.shape[0] > 0`` each quiet step's
    samples and end (stride 1), or the end of every stride-th step, go to ``rec_t``/``rec_y`` as
    the engine's recorder keeps them; ``rec`` = [samples written, samples recorded in all, bound
    on them, stride, steps seen at stride > 1] is advanced.

    Returns (code, t_old, t, h_used, h_abs_next, nfev, nsteps): code 1 = the last step is not
    quiet (the engine scans it), 2 = ``t_bound`` reached with every step quiet, 3 =
    ``max_steps`` quiet steps, 4 = the record buffer cannot take another step or the record has
    passed its bound (the engine thins it), 0 = step size too small (y, f at the last accepted
    step)."""
    n, m, k = y.shape[0], s.shape[0], vals.shape[0]
    ynew, fnew = np.empty(n), np.empty(n)
    yk, fk, gk = np.empty(n), np.empty(n), np.empty(k)
    cap = 0
    if rec_t is not None:
        cap = rec_t.shape[0]
    Y = np.empty((n, m))
    ts = np.empty(m)
    uses_f = False
    if W is not None:
        for j in range(k):
            for a in range(n):
                uses_f = uses_f or U[j, a] != 0.0
    nfev, nsteps, t_old, h_used = 0, 0, t, 0.0
    while nsteps < max_steps:
        ok, tn, hu, h_abs, nf = advance(fun, p, t, y, f, h_abs, hmax, t_bound, rtol, atol, K, ynew, fnew)
        nfev += nf
        if not ok:
            return 0, t_old, t, h_used, h_abs, nfev, nsteps
        nsteps += 1
        h_used = hu
        nfev += dense(fun, p, t, y, ynew, fnew, K, hu, F)
        finite = True
        for a in range(n):
            finite = finite and np.isfinite(ynew[a])
            y_old[a] = y[a]
        for q in range(m):
            tq = t + s[q] * hu
            if W is not None:
                dense_at(F, y_old, s[q], yk)
                if uses_f:
                    fun(tq, yk, p, fk)
                    nfev += 1
                for j in range(k):
                    g = b[j]
                    for a in range(n):
                        g += W[j, a] * yk[a]
                        if uses_f:
                            g += U[j, a] * fk[a]
                    gk[j] = g
            if gfun is not None:
                dense_at(F, y_old, (tq - t) / hu, yk)
                if k > 0:
                    gfun(tq, yk, gp, gk)
            for j in range(k):
                vals[j, q] = gk[j]
                vals[j, m + 1 + q] = gk[j]
                vals[j, 2 * m + 1 + q] = gk[j]
            if cap > 0:
                ts[q] = tq
                for a in range(n):
                    Y[a, q] = yk[a]
        if W is not None:
            for j in range(k):
                g = b[j]
                for a in range(n):
                    g += W[j, a] * ynew[a] + U[j, a] * fnew[a]
                vals[j, m] = g
        if gfun is not None:
            if k > 0:
                gfun(tn, ynew, gp, gk)
                for j in range(k):
                    vals[j, m] = gk[j]
        t_old = t
        t = tn
        for a in range(n):
            y[a] = ynew[a]
            f[a] = fnew[a]
        if not finite or not _quiet_guards(vals, m, g_last, dec_before, state, gatol, dip_factor):
            return 1, t_old, t, h_used, h_abs, nfev, nsteps
        if rec_t is not None:
            if cap > 0:
                # the quiet step into the record: its samples and end at stride 1, else the end of
                # every stride-th step
                w = rec[0]
                if rec[3] == 1:
                    for q in range(m):
                        rec_t[w + q] = ts[q]
                        for a in range(n):
                            rec_y[a, w + q] = Y[a, q]
                    w += m
                    rec_t[w] = t
                    for a in range(n):
                        rec_y[a, w] = y[a]
                    rec[0] = w + 1
                    rec[1] += m + 1
                else:
                    rec[4] += 1
                    if rec[4] % rec[3] == 0:
                        rec_t[w] = t
                        for a in range(n):
                            rec_y[a, w] = y[a]
                        rec[0] = w + 1
                        rec[1] += 1
        if t >= t_bound:
            return 2, t_old, t, h_used, h_abs, nfev, nsteps
        if rec_t is not None:
            if cap > 0 and (rec[1] > rec[2] or rec[0] + m + 1 > cap):
                return 4, t_old, t, h_used, h_abs, nfev, nsteps
    return 3, t_old, t, h_used, h_abs, nfev, nsteps


@njit(cache=True)
def event_root(fun, p, w, bj, u, gfun, gp, j, k, F, y_old, t_old, h, a, b, xtol):
    """Root in [a, b] of one guard on the step's dense output (rows F of :func:`dense`), g(a) > 0
    >= g(b): the affine guard g = w·y + u·f(t, y) + bj (``gfun``, ``gp`` None), or component j
    of the compiled guard vector ``gfun(t, y, gp, out)`` of k guards (w, bj, u None; each kind
    compiles only its own branch, as in :func:`run_screened`).  Bisection to ``xtol`` (or to
    adjacent floating-point numbers), returned on the new side (g <= 0), as
    :func:`landau.verify.hybrid.locate.root_new_side` does with Brent's method: the root lies in
    [returned − xtol, returned].  Should the signs at the ends disagree (the bracket was found
    with other formulas for the same guard), the end on the new side is returned.  The guard is
    evaluated at one place in the loop (at b, then at a, then at the midpoints)."""
    n = y_old.shape[0]
    yk, fk, gk = np.empty(n), np.empty(n), np.empty(k)
    uses_f = False
    if w is not None:
        for c in range(n):
            uses_f = uses_f or u[c] != 0.0
    lo, hi = a, b
    tt = b
    stage = 0
    while True:
        dense_at(F, y_old, (tt - t_old) / h, yk)
        g = 0.0
        if w is not None:
            if uses_f:
                fun(tt, yk, p, fk)
            g = bj
            for c in range(n):
                g += w[c] * yk[c]
                if uses_f:
                    g += u[c] * fk[c]
        if gfun is not None:
            gfun(tt, yk, gp, gk)
            g = gk[j]
        if stage == 0:
            if g > 0.0:
                return b
            stage = 1
            tt = a
            continue
        if stage == 1:
            if g <= 0.0:
                return a
            stage = 2
        elif g > 0.0:
            lo = tt
        else:
            hi = tt
        if not hi - lo > xtol:
            return hi
        tt = 0.5 * (lo + hi)
        if tt <= lo or tt >= hi:
            return hi


_NO_RECORD = (np.empty(0), np.empty((0, 0)), np.zeros(5, dtype=np.int64))


class _Dense:
    """The step's 7th-order interpolant (scalar t → (n,), array → (n, m))."""

    __slots__ = ("t0", "h", "F", "y0")

    def __init__(self, t0, h, F, y0):
        self.t0, self.h, self.F, self.y0 = float(t0), float(h), F, y0

    def __call__(self, t):
        x = (np.asarray(t, float) - self.t0) / self.h
        if x.ndim == 0:
            out = np.empty(len(self.y0))
            dense_at(self.F, self.y0, float(x), out)
            return out
        return dense_many(self.F, self.y0, np.ascontiguousarray(x))


_LOOPS: dict = {}


def _signatures() -> dict:
    """name → (dispatcher, argument types, what it is) of the compiled entries used here."""
    f64, arr, i64, i64arr = types.float64, types.float64[::1], types.int64, types.int64[::1]
    mat, barr, none = types.float64[:, ::1], types.boolean[::1], types.none
    return {
        "advance": (advance, (FUN_T, arr, f64, arr, arr, f64, f64, f64, f64, arr, mat, arr, arr),
                    "the compiled DOP853 step"),
        "dense": (dense, (FUN_T, arr, f64, arr, arr, arr, mat, f64, mat), "the DOP853 dense output"),
        "initial_step": (initial_step, (FUN_T, arr, f64, arr, arr, f64, f64, f64, arr), "the DOP853 first step"),
        "affine_root": (event_root, (FUN_T, arr, arr, f64, arr, none, none, i64, i64, mat, arr, f64, f64, f64, f64,
                                     f64), "the DOP853 event root"),
        "kernel_root": (event_root, (none, none, none, none, none, FUN_T, arr, i64, i64, mat, arr, f64, f64, f64, f64,
                                     f64), "the DOP853 event root of compiled guards"),
        "run_quiet": (run_screened, (FUN_T, arr, f64, arr, arr, f64, f64, f64, f64, arr, i64, mat, arr, mat, none, none,
                                     arr, arr, barr, i64arr, f64, f64, mat, mat, arr, mat, none, none, none),
                      "the compiled DOP853 event loop"),
        "run_guarded": (run_screened, (FUN_T, arr, f64, arr, arr, f64, f64, f64, f64, arr, i64, none, none, none, FUN_T,
                                       arr, arr, arr, barr, i64arr, f64, f64, mat, mat, arr, mat, arr, mat, i64arr),
                        "the compiled DOP853 loop with compiled guards"),
    }


def _compiled(name: str):
    """The compiled entry ``name``, built (or loaded from numba's disk cache) for the argument types
    used here on its first use (:func:`~landau.verify.compiling.compile_once`: a run of affine
    guards does not build the entries of compiled guard vectors, nor the other way round); the
    dispatcher itself, called as usual (the kernel's
    :class:`~landau.verify.hybrid.callbacks.FunctionPointer` is typed once, not at every call)."""
    fn = _LOOPS.get(name)
    if fn is None:
        fn, sig, what = _signatures()[name]
        compile_once(fn, sig, what)
        _LOOPS[name] = fn
    return fn


class DOP853Solver:
    """scipy ``OdeSolver`` members over the compiled DOP853 (the engine's stepper contract,
    :mod:`landau.verify.hybrid.steppers`), plus the compiled screened runs (:meth:`run_quiet`,
    :meth:`run_guarded`) and event roots (:meth:`affine_root`, :meth:`kernel_root`)."""

    method = "DOP853"
    #: ``f`` is the field at ``(t, y)`` after every step (the engine's Hermite screen may use it)
    keeps_f = True

    def __init__(self, kernel: Kernel, t0, y0, t_bound, rtol, atol, first_step, max_step):
        self.kernel = kernel
        self._fun = kernel_function(kernel.fun)
        self.t = self.t_old = float(t0)
        self.y = np.array(y0, dtype=float)
        self.t_bound = float(t_bound)
        self.status = "running" if self.t_bound > self.t else "finished"
        self.rtol = float(rtol)
        self.atol = np.array(np.broadcast_to(np.asarray(atol, float), self.y.shape), dtype=float)
        self.max_step = float(max_step)
        # f(t0, y0) by the cfunc the loops call (its values to the last bit): the kernel's own dispatcher,
        # called from Python, would be compiled a second time for this one evaluation
        self.f = np.empty(len(self.y))
        call_pointer(self._fun, self.t, self.y, kernel.p, self.f)
        self.nfev, self.nsteps, self.njev, self.nlu = 1, 0, 0, 0
        if first_step:
            self.h_abs = min(float(first_step), abs(self.t_bound - self.t))
        else:
            self.h_abs = _compiled("initial_step")(self._fun, kernel.p, self.t, self.y, self.f, self.t_bound,
                                                    self.max_step, self.rtol, self.atol)
            self.nfev += 1
        n = len(self.y)
        self._K = np.empty((N_EXT, n))
        self._F = np.empty((N_DENSE, n))
        self._y_old = np.empty(n)
        self._dense = None
        self._h_used = 0.0

    def step(self):
        """Advance one accepted step; ``None`` or an error message (scipy's contract)."""
        if self.status != "running":
            raise RuntimeError("attempt to step on a finished or failed solver")
        n = len(self.y)
        ynew, fnew = np.empty(n), np.empty(n)
        ok, tn, hu, hn, nf = _compiled("advance")(self._fun, self.kernel.p, self.t, self.y, self.f, self.h_abs,
                                                   self.max_step, self.t_bound, self.rtol, self.atol, self._K, ynew,
                                                   fnew)
        self.nfev += nf
        if not ok:
            self.status = "failed"
            return f"compiled DOP853: step size too small at t = {self.t:.12g}"
        self._y_old[:] = self.y
        self._h_used, self._dense = hu, None
        self.t_old, self.t, self.y, self.f, self.h_abs = self.t, tn, ynew, fnew, hn
        self.nsteps += 1
        if self.t >= self.t_bound:
            self.status = "finished"
        return None

    def dense_output(self):
        """Interpolant on [t_old, t] (the 7th-order continuous extension; 3 evaluations, once)."""
        if self._dense is None:
            F = np.empty_like(self._F)
            self.nfev += _compiled("dense")(self._fun, self.kernel.p, self.t_old, self._y_old, self.y, self.f,
                                             self._K, self._h_used, F)
            self._dense = _Dense(self.t_old, self._h_used, F, self._y_old.copy())
        return self._dense

    def _took(self, code, t_old, t, hu, hn, nf, k):
        """Advance the solver past the ``k`` steps of a compiled run (:func:`run_screened`'s return
        value); returns (error message or None, code, k)."""
        self.nfev += nf
        self.nsteps += k
        self.t, self.h_abs = t, hn
        if k:
            self.t_old, self._h_used = t_old, hu
            self._dense = _Dense(t_old, hu, self._F.copy(), self._y_old.copy())
        if code == 0:
            self.status = "failed"
            return f"compiled DOP853: step size too small at t = {self.t:.12g}", 0, k
        if self.t >= self.t_bound:
            self.status = "finished"
        return None, int(code), k

    def run_quiet(self, W, b, U, s, g_last, dec_before, state, guard_atol, dip_factor, max_steps=1_000_000):
        """Steps until one whose affine guards g = W·y + U·f(t, y) + b need the engine's
        dense-output scan (:func:`run_screened`), at most ``max_steps``.
        Returns (error message or None, whether ``t_bound`` was reached with every step quiet —
        None when ``max_steps`` quiet steps were taken —, steps taken); otherwise the last step
        (``t_old`` → ``t``, ``dense_output()``) is the one to scan."""
        if self.status != "running":
            raise RuntimeError("attempt to step on a finished or failed solver")
        vals = np.empty((len(b), 3 * len(s) + 1))
        msg, code, k = self._took(*_compiled("run_quiet")(
            self._fun, self.kernel.p, self.t, self.y, self.f, self.h_abs, self.max_step, self.t_bound,
            self.rtol, self.atol, int(max_steps), W, b, U, None, None, s, g_last, dec_before, state,
            float(guard_atol), float(dip_factor), self._K, self._F, self._y_old, vals, None, None, None))
        if msg is not None:
            return msg, False, k
        return None, (None if code == 3 else code == 2), k

    def run_guarded(self, guard_kernel, s, g_last, dec_before, state, guard_atol, dip_factor, max_steps, values,
                    record=None):
        """Steps until one whose guards, the compiled vector function ``guard_kernel`` (a
        :class:`~landau.verify.hybrid.kernel.Kernel`), need the engine's dense-output scan
        (:func:`run_screened`), at most ``max_steps``; ``values`` receives
        the last step's guard values and ``record`` = (t, y, info) buffers the quiet steps.
        Returns (error message or None, code of :func:`run_screened`, steps taken)."""
        if self.status != "running":
            raise RuntimeError("attempt to step on a finished or failed solver")
        rt, ry, ri = record if record is not None else _NO_RECORD
        return self._took(*_compiled("run_guarded")(
            self._fun, self.kernel.p, self.t, self.y, self.f, self.h_abs, self.max_step, self.t_bound, self.rtol,
            self.atol, int(max_steps), None, None, None, kernel_function(guard_kernel.fun), guard_kernel.p, s, g_last,
            dec_before, state, float(guard_atol), float(dip_factor), self._K, self._F, self._y_old, values, rt, ry,
            ri))

    def affine_root(self, w, b, u, lo, hi, xtol) -> float:
        """Root of the guard w·y + u·f(t, y) + b in [lo, hi] on the last step's dense output
        (:func:`event_root`; the guard is > 0 at lo and <= 0 at hi)."""
        d = self.dense_output()
        return _compiled("affine_root")(self._fun, self.kernel.p, w, float(b), u, None, None, 0, 0, d.F, d.y0, d.t0,
                                         d.h, float(lo), float(hi), float(xtol))

    def kernel_root(self, guard_kernel, j, n_guards, lo, hi, xtol) -> float:
        """Root of guard j of the compiled guard vector ``guard_kernel`` (a
        :class:`~landau.verify.hybrid.kernel.Kernel` of ``n_guards`` components) in [lo, hi] on
        the last step's dense output (:func:`event_root`; > 0 at lo, <= 0 at hi)."""
        d = self.dense_output()
        return _compiled("kernel_root")(None, None, None, None, None, kernel_function(guard_kernel.fun),
                                         guard_kernel.p, int(j), int(n_guards), d.F, d.y0, d.t0, d.h, float(lo),
                                         float(hi), float(xtol))

    def __repr__(self) -> str:
        return (f"DOP853Solver(t={self.t:.6g}, {self.status}, steps={self.nsteps}, nfev={self.nfev}, "
                f"kernel={self.kernel!r})")


@dataclass(frozen=True)
class CompiledDOP853:
    """Stepper factory: the compiled DOP853 over a mode's :class:`~landau.verify.hybrid.kernel.Kernel`
    (module docstring); the hybrid engine runs the quiet steps of modes with affine guards in
    one compiled call.  A mode without a kernel (a plain Python ``rhs``) is integrated by scipy's
    ``DOP853`` with the same tolerances.

    Parameters
    ----------
    rtol, atol : float
        Tolerances (scipy's meaning).
    first_step : float, optional
        Default: scipy's initial-step rule.
    max_step : float, optional
        Largest step.
    """

    rtol: float = 1e-10
    atol: float | tuple = 1e-12
    first_step: float | None = None
    max_step: float = np.inf

    #: the hybrid engine hands this factory a mode's compiled kernel (its ``Mode.kernel``)
    takes_kernel: ClassVar[bool] = True

    def __call__(self, fun, t0, y0, t_bound, jac=None):
        if not (0 < self.rtol < 1):
            raise InputError(f"rtol must be in (0, 1), got {self.rtol!r}")
        if not isinstance(fun, Kernel):
            # a mode without a compiled field (Mode.kernel None): scipy's DOP853, the same method
            from landau.verify.hybrid.steppers import ScipyStepper

            return ScipyStepper("DOP853", self.rtol, self.atol, self.max_step, self.first_step)(fun, t0, y0, t_bound)
        return DOP853Solver(fun, t0, y0, t_bound, self.rtol, self.atol, self.first_step, self.max_step)
