"""Compiled Radau IIA (order 5) integrator for small stiff systems with an analytic Jacobian.

The three-stage Radau IIA collocation method (Hairer & Wanner 1996, *Solving ODEs II*,
Sec. IV.8) with its simplified Newton iteration solved in the eigenbasis of A⁻¹, as in the
classical code radau5: one real n × n LU of γ/h·I − J (also the matrix of the error estimate)
and one complex n × n LU of (α + iβ)/h·I − J, computed in real arithmetic on its real and
imaginary parts (compiling real arithmetic only halves the first build of the loop).  The
Jacobian and the factors are reused as radau5 reuses them (:data:`THETA_KEEP_JAC`,
:data:`HOLD_LO`, :data:`HOLD_HI`): J is kept while the Newton iteration contracts fast, the
step size is held when the controller proposes a growth below 20 %, and the factors are made
again only when J or h changed; a sweep whose increment is already below the tolerance ends the
iteration with the contraction factor of the last step (radau5's FACCON).  A Newton iteration
that fails with a kept J is retried with a fresh one; with a fresh J it is retried at the same
step with the stage Jacobians J(Yᵢ) on the full 3n × 3n system (needed when the Jacobian changes
by orders of magnitude within a step: ẇ ∝ e^{−w} as v → 0) before the step is halved.  Error
estimate and step-size control follow the radau5 recipe (embedded estimate
(γ/h·I − J)⁻¹(f₀ + Σ eᵢZᵢ/h), predictive controller of Gustafsson 1994); the dense output is
the collocation cubic.

Crossings of ``y[ev_idx] = ev_val`` are located on the collocation cubic (the exact cubic scan
of :func:`cubic_crossing`) and recorded; the run can stop after a number of crossings in a
chosen direction (Poincaré returns).  Accepted steps may be recorded for plots.

Compilation: the loop (:func:`radau_core`) is one ``numba.njit(cache=True)`` function, compiled
on its first use for the one signature it is called with (:func:`landau.verify.compiling.compile_once`)
and loaded from numba's disk cache afterwards; nothing compiles at import.  The right-hand side
and the Jacobian, ``f(t, y, p, out)`` and ``jac(t, y, p, out)`` (signatures :data:`SIG`,
:data:`SIG_JAC`), reach it as first-class functions: :func:`pointers` compiles each as a
``numba.cfunc`` (cached on disk) and wraps its address in a
:class:`numba.types.WrapperAddressProtocol` object (:mod:`landau.verify.hybrid.callbacks`), so a
new friction law compiles only its own two small functions.  The method's coefficients are in
:mod:`landau.verify.hybrid.radau_tableau`, the Newton matrices, their LU factors and solves in
:mod:`landau.verify.hybrid.radau_linalg` (inlined into the loop), the exact scan of a cubic for
crossings in :mod:`landau.verify.hybrid.crossing`; :func:`~landau.verify.compiling.compile_once`
keys the loop's disk cache on the sources of all of them, so an edit of any one builds the loop
again (numba's own cache would notice edits of this file only).

With ``NUMBA_DISABLE_JIT=1`` the same code runs as plain Python (slowly; a warning says so once).

References
----------
Hairer, E., Wanner, G. (1996). Solving Ordinary Differential Equations II, 2nd ed., Springer,
Sec. IV.5 (collocation, Radau IIA) and IV.8 (implementation: simplified Newton in the
eigenbasis of A⁻¹, eq. (8.15)–(8.20), error estimate, step-size control).
Gustafsson, K. (1994). Control-theoretic techniques for stepsize selection in implicit
Runge–Kutta methods. ACM Trans. Math. Softw. 20, 496–517.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np
from numba import types

from landau.errors import InputError
from landau.verify.compiling import compile_once
from landau.verify.hybrid.borrowed import borrowed as _borrowed
from landau.verify.hybrid.borrowed import keep_alive as _keep_alive
from landau.verify.hybrid.callbacks import FunctionPointer, jit_enabled, make_pointers, pointer_type, warn_once
from landau.verify.hybrid.crossing import cubic, cubic_crossing
from landau.verify.hybrid.radau_linalg import (
    factor_complex,
    factor_real,
    inlined,
    solve,
    solve_complex,
    stage_jacobians,
)
from landau.verify.hybrid.radau_tableau import (
    A_RADAU,
    ALPHA_SPLIT,
    BETA_SPLIT,
    C_NODES,
    E_ERR,
    GAMMA_SPLIT,
    MU_REAL,
    NODES,
    T_ROWS,
    TI_ROWS,
    VINV,
    split_coefficients,
)

__all__ = ["A_RADAU", "C_NODES", "E_ERR", "MU_REAL", "VINV", "SIG", "SIG_JAC", "FUN_T", "JAC_T", "STATUS",
           "THETA_KEEP_JAC", "HOLD_LO", "HOLD_HI",
           "FunctionPointer", "pointers", "radau_core", "split_coefficients", "cubic", "cubic_crossing"]

#: double-precision machine epsilon
EPS = 2.220446049250313e-16
#: Newton sweeps of the simplified iteration before a step is declared failed
NEWTON_MAXITER = 7
#: the largest growth of the step size after an accepted step
FACMAX = 10.0
#: the status codes :func:`radau_core` returns
STATUS = {0: "finished", 1: "terminal event", -1: "step size too small", -2: "maximum number of steps",
          -3: "non-finite state"}

SIG = types.void(types.float64, types.float64[::1], types.float64[::1], types.float64[::1])
SIG_JAC = types.void(types.float64, types.float64[::1], types.float64[::1], types.float64[:, ::1])
FUN_T = pointer_type(SIG)
JAC_T = pointer_type(SIG_JAC)


#: the decorator of the loop's private helpers: they are compiled as part of the loop and only
#: called from compiled code, so they get no disk-cache entry of their own (the loop's entry holds
#: their machine code)
_inner = nb.njit


# ---------------------------------------------------------------------------------------------
# dense output
@inlined
def _poly(y0, Q, x, i):
    """Component i of the dense output y0 + Σ_j Q_j x^{j+1} (Horner)."""
    acc = Q[Q.shape[0] - 1, i]
    for j in range(Q.shape[0] - 2, -1, -1):
        acc = Q[j, i] + x * acc
    return y0[i] + x * acc


# ---------------------------------------------------------------------------------------------
# event location on the collocation cubic (the scan itself: landau.verify.hybrid.crossing)
#: the loop's own build of :func:`cubic_crossing` (the same Python function): compiled inside the
#: loop's build without a disk-cache entry of its own, which the public function keeps for its
#: other callers
_cubic_crossing = _inner(getattr(cubic_crossing, "py_func", cubic_crossing))


@_inner
def _crossings(y, Q, t, h, ev_idx, ev_val, ev_dir, ev_stop, nev_dir, cnt, EVBUF, EVDIR):
    """Record every sign change of y[ev_idx] − ev_val on the step's cubic dense output.

    Returns (stop, nev_dir): whether the ``ev_stop``-th crossing in direction ``ev_dir`` was
    reached, and the updated count of such crossings.
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
        xr = _cubic_crossing(g0, c1, c2, c3, xa, sgn, True)
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


# ---------------------------------------------------------------------------------------------
# the reuse of the Jacobian and of the factors (the policy of radau5: Hairer & Wanner 1996,
# IV.8, and the code's parameters THET, QUOT1, QUOT2)
#: the Jacobian is kept for the next step when the accepted step's simplified Newton iteration
#: contracted at a rate θ ≤ THETA_KEEP_JAC (a step that converged at its first sweep counts as
#: θ = THETA_KEEP_JAC, as in radau5).  Reason: a J that still gives θ this small costs no extra
#: sweep on the next step, and keeping it is what lets the factors survive.  radau5's default
#: THET = 0.001; on the spring–block cycle of ``benchmarks/sections_solvers.py`` 0.01, 0.1 and
#: 0.3 cost 10–40 % more CPU at equal tolerance (more sweeps and rejected steps with a stale J
#: through the slip), so the default stays
THETA_KEEP_JAC = 0.001
#: the step size is held, and with it both LU factors, when the controller proposes a ratio
#: h_new/h in [HOLD_LO, HOLD_HI] and the Jacobian is kept (radau5's QUOT1 = 1, QUOT2 = 1.2).
#: Reason: a growth below 20 % saves less work than the two factorisations it would cost,
#: while a shrink is never held (the error estimate asked for it)
HOLD_LO = 1.0
HOLD_HI = 1.2


@inlined
def _root4(x):
    """x^(1/4) as two square roots (the controller's exponent 1/(s + 1) for s = 3 stages; a square
    root costs a fraction of a general power)."""
    return math.sqrt(math.sqrt(x))


# ---------------------------------------------------------------------------------------------
# the step loop
@nb.njit(cache=True)
def _radau_loop(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir, ev_stop,
                rec_cap, EVBUF, EVDIR):
    """The integrator (:func:`radau_core` documents the arguments and the returned tuple).

    Every work array is used through a borrowed view
    (:func:`~landau.verify.hybrid.borrowed.borrowed`) of an array the loop owns until it returns:
    numba counts the references of an owned array, and of every view made of it, with an atomic
    instruction at each copy, pass and call, which cost this loop a third of its time when a
    stage's f was written into a row view of F (measured on the spring–block cycle of
    ``benchmarks/sections_solvers.py``); views of a borrowed array (``F[a]``) cost nothing.

    Why the step's phases (Newton start, iteration, error estimate, dense output, controller) are
    written in this one function rather than apart: numba's inliner copies an inlined callee's IR
    block by block (twice), and each block's copy copies the callee's whole scope, so the cost
    grows with blocks × variables of the callee, which for the Newton iteration (with its solves
    inlined into it first) is large.  Measured on the first build of this loop (a fresh
    ``NUMBA_CACHE_DIR``, CPU-s, AMD EPYC, 2 cores, the other core busy), the same bits from the
    same operations in every variant: one function 11.6, 12.5, 13.6, 13.9; the five phases as
    ``inline="always"`` helpers 13.2, 13.0, 14.9, 16.3 (cProfile: 5.2 s of 26 s in the
    inliner's ``copy_ir``); the iteration and the error estimate as separately compiled functions
    16.5, against 11.5.  The first build is a cost every new machine pays (the cold ``landau
    verify``), so the loop stays one function; each phase is marked by a comment.
    """
    s = 3
    n = y0.shape[0]
    N = s * n
    T = T_ROWS
    TI = TI_ROWS
    gam = GAMMA_SPLIT
    alp = ALPHA_SPLIT
    bet = BETA_SPLIT
    # set-up: f at the start (counted), the first step, counters and recording buffers
    cnt_own = np.empty(8, dtype=np.int64)
    cnt = _borrowed(cnt_own)
    for i in range(8):
        cnt[i] = 0
    rec_t = np.empty(rec_cap)
    rec_y = np.empty((rec_cap, n))
    y_own = y0.copy()
    y = _borrowed(y_own)
    p = _borrowed(p)
    atol = _borrowed(atol)
    EVBUF = _borrowed(EVBUF)
    EVDIR = _borrowed(EVDIR)
    f0_own = np.empty(n)
    f0 = _borrowed(f0_own)
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
        for i in range(n):
            rec_y[0, i] = y[i]
        cnt[7] = 1
    J_own = np.empty((n, n))
    J = _borrowed(J_own)
    Mf_own = np.empty((N, N))
    Mf = _borrowed(Mf_own)
    Mr_own = np.empty((n, n))
    Mr = _borrowed(Mr_own)
    Mcr_own = np.empty((n, n))
    Mcr = _borrowed(Mcr_own)
    Mci_own = np.empty((n, n))
    Mci = _borrowed(Mci_own)
    bre_own = np.empty(n)
    bre = _borrowed(bre_own)
    bim_own = np.empty(n)
    bim = _borrowed(bim_own)
    dinv_own = np.empty((4, N))
    dinv = _borrowed(dinv_own)
    pivF_own = np.empty(N, dtype=np.int64)
    pivF = _borrowed(pivF_own)
    pivR_own = np.empty(n, dtype=np.int64)
    pivR = _borrowed(pivR_own)
    pivC_own = np.empty(n, dtype=np.int64)
    pivC = _borrowed(pivC_own)
    Z_own = np.empty((s, n))
    Z = _borrowed(Z_own)
    W_own = np.empty((s, n))
    W = _borrowed(W_own)
    F_own = np.empty((s, n))
    F = _borrowed(F_own)
    JB_own = np.empty((s, n, n))
    JB = _borrowed(JB_own)
    R_own = np.empty(N)
    R = _borrowed(R_own)
    Q_own = np.empty((s, n))
    Q = _borrowed(Q_own)
    Qprev_own = np.empty((s, n))
    Qprev = _borrowed(Qprev_own)
    for a in range(s):
        for i in range(n):
            Qprev[a, i] = 0.0
    ytmp_own = np.empty(n)
    ytmp = _borrowed(ytmp_own)
    wsc_own = np.empty(n)
    wsc = _borrowed(wsc_own)
    ynew_own = np.empty(n)
    ynew = _borrowed(ynew_own)
    scale_own = np.empty(n)
    scale = _borrowed(scale_own)
    err_own = np.empty(n)
    err = _borrowed(err_own)
    ZE_own = np.empty(n)
    ZE = _borrowed(ZE_own)
    yprev_own = np.empty(n)
    yprev = _borrowed(yprev_own)
    b0_own = np.empty(n)
    b0 = _borrowed(b0_own)
    dinvR = dinv[0]
    dcr = dinv[1]
    dci = dinv[2]
    dinvF = dinv[3]
    t = t0
    have_prev = False
    tprev = 0.0
    hprev = 1.0
    newton_tol = max(10 * EPS / rtol, min(0.03, rtol ** 0.5))
    use_full = False
    err_old = -1.0
    h_old = -1.0
    rejected = False
    # the reuse state: J is evaluated when need_jac; jac_fresh says it was evaluated at the current
    # (t, y); the factors belong to J and h_lu (real_ok, cplx_ok); faccon = θ/(1 − θ) of the last
    # iteration, carried to the next step's convergence test (radau5's FACCON)
    need_jac = True
    jac_fresh = False
    h_lu = -1.0
    real_ok = False
    cplx_ok = False
    faccon = 1.0
    nev_dir = 0 * ev_stop      # (an int64 variable: a literal 0 would compile _crossings twice)
    while t < t_end:
        # before a step: the budget of step attempts (-2), h cut to the end of the interval,
        # step-size underflow (-1)
        if cnt[0] + cnt[1] >= max_steps:
            status = -2
            break
        if h > t_end - t:
            h = t_end - t
        if h < 10 * EPS * max(abs(t), 1e-300) or h <= 0.0:
            status = -1
            break
        # the iteration matrices: J when asked for, the factors when J or h changed since they
        # were made (the complex one is not needed by the full Newton retry)
        if need_jac:
            jac(t, y, p, J)
            cnt[3] += 1
            need_jac = False
            jac_fresh = True
            h_lu = -1.0
        if h != h_lu:
            real_ok = False
            cplx_ok = False
            h_lu = h
        if not real_ok:
            real_ok = factor_real(J, h, Mr, pivR, dinvR)
            cnt[4] += 1
        if not use_full and not cplx_ok:
            cplx_ok = factor_complex(J, h, Mcr, Mci, pivC, dcr, dci)
            cnt[4] += 1
        ok = real_ok and (use_full or cplx_ok)
        gh = gam / h
        ah = alp / h
        bh = bet / h
        # Newton start: the previous step's collocation polynomial, extrapolated
        # (and W = T⁻¹Z for the split iteration), one loop over the components
        x0 = (t + NODES[0] * h - tprev) / hprev
        x1 = (t + NODES[1] * h - tprev) / hprev
        x2 = (t + NODES[2] * h - tprev) / hprev
        for i in range(n):
            if have_prev:
                Z[0, i] = _poly(yprev, Qprev, x0, i) - y[i]
                Z[1, i] = _poly(yprev, Qprev, x1, i) - y[i]
                Z[2, i] = _poly(yprev, Qprev, x2, i) - y[i]
            else:
                Z[0, i] = 0.0
                Z[1, i] = 0.0
                Z[2, i] = 0.0
            if not use_full:
                W[0, i] = TI[0][0] * Z[0, i] + TI[0][1] * Z[1, i] + TI[0][2] * Z[2, i]
                W[1, i] = TI[1][0] * Z[0, i] + TI[1][1] * Z[1, i] + TI[1][2] * Z[2, i]
                W[2, i] = TI[2][0] * Z[0, i] + TI[2][1] * Z[1, i] + TI[2][2] * Z[2, i]
        converged = False
        dW_old = -1.0
        rate = -1.0
        thq_old = 1.0
        # radau5: the contraction factor of the last step, raised to 0.8 (so that a run of fast
        # steps cannot lock it at a tiny value), lets a sweep whose increment is already below the
        # tolerance end the iteration; θ starts at THETA_KEEP_JAC (one sweep counts as fast)
        faccon = max(faccon, EPS) ** 0.8
        theta = THETA_KEEP_JAC
        n_iter = 0
        # the weights of the increments' norm, 1/(atol + rtol·|y|) at the start of the step (radau5's SCAL)
        for i in range(n):
            wsc[i] = 1.0 / (atol[i] + abs(y[i]) * rtol)
        if ok:
            for it in range(3 * NEWTON_MAXITER if use_full else NEWTON_MAXITER):
                n_iter = min(it + 1, NEWTON_MAXITER)
                # the stage values f(t + c_a h, y + Z_a) straight into the rows of F (views of a
                # borrowed array: no reference counts); a non-finite one shows in the increment's norm
                for a in range(s):
                    for i in range(n):
                        ytmp[i] = y[i] + Z[a, i]
                    fun(t + NODES[a] * h, ytmp, p, F[a])
                    cnt[2] += 1
                if use_full:
                    # the retry: full Newton matrix with the stage Jacobians
                    if not stage_jacobians(jac, t, h, y, Z, p, JB, ytmp, Mf, pivF, dinvF, cnt):
                        break
                    for a in range(s):
                        for i in range(n):
                            acc = -Z[a, i]
                            for b in range(s):
                                acc += h * A_RADAU[a, b] * F[b, i]
                            R[a * n + i] = acc
                    solve(Mf, pivF, dinvF, R)
                else:
                    # right-hand sides T⁻¹F − (Λ/h)·T⁻¹Z of the decoupled systems
                    for i in range(n):
                        g0 = TI[0][0] * F[0, i] + TI[0][1] * F[1, i] + TI[0][2] * F[2, i]
                        g1 = TI[1][0] * F[0, i] + TI[1][1] * F[1, i] + TI[1][2] * F[2, i]
                        g2 = TI[2][0] * F[0, i] + TI[2][1] * F[1, i] + TI[2][2] * F[2, i]
                        w0, w1, w2 = W[0, i], W[1, i], W[2, i]
                        b0[i] = g0 - gh * w0
                        bre[i] = g1 - (ah * w1 - bh * w2)
                        bim[i] = g2 - (bh * w1 + ah * w2)
                    # (γ/h·I − J)·ΔW₁ = b0 and ((α + iβ)/h·I − J)·(ΔW₂ + iΔW₃) = bre + i·bim (eq. (8.18)),
                    # with the factors made above
                    solve(Mr, pivR, dinvR, b0)
                    solve_complex(Mcr, Mci, pivC, dcr, dci, bre, bim)
                    # ΔW = (b0, Re, Im of the complex solution) and ΔZ = T·ΔW, one loop (constant
                    # indices into T: a variable index into a tuple compiles to a switch)
                    for i in range(n):
                        d0 = b0[i]
                        d1 = bre[i]
                        d2 = bim[i]
                        W[0, i] += d0
                        W[1, i] += d1
                        W[2, i] += d2
                        R[i] = T[0][0] * d0 + T[0][1] * d1 + T[0][2] * d2
                        R[n + i] = T[1][0] * d0 + T[1][1] * d1 + T[1][2] * d2
                        R[2 * n + i] = T[2][0] * d0 + T[2][1] * d1 + T[2][2] * d2
                dW = 0.0
                for a in range(s):
                    for i in range(n):
                        r = R[a * n + i] * wsc[i]
                        dW += r * r
                        Z[a, i] += R[a * n + i]
                dW = math.sqrt(dW / N)
                if not math.isfinite(dW):
                    break
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
                if rate > 0:
                    # θ: the last ratio of increments, from the third sweep on the geometric mean of
                    # the last two (radau5); divergence, or a rate too slow to reach the tolerance
                    # within the sweeps left, fails the iteration
                    theta = rate if it == 1 else math.sqrt(rate * thq_old)
                    thq_old = rate
                    if theta >= 0.99:
                        break
                    faccon = theta / (1.0 - theta)
                    if n_iter < NEWTON_MAXITER and faccon * dW * theta ** (NEWTON_MAXITER - 1 - n_iter) > newton_tol:
                        break
                if dW == 0.0 or faccon * dW <= newton_tol:
                    converged = True
                    break
                dW_old = max(dW, EPS)
        if not converged:
            # a failed iteration (radau5's unexpected rejection): with a kept J, retry with a fresh one
            # at the same h; with a fresh one, the full Newton retry with the stage Jacobians (needed
            # when J changes by orders of magnitude within the step: ẇ ∝ e^{−w} as v → 0), then h/2
            cnt[5] += 1
            cnt[1] += 1
            rejected = True
            faccon = 1.0
            if not jac_fresh:
                need_jac = True
            elif not use_full:
                use_full = True
            else:
                h *= 0.5
            continue
        # embedded error estimate: (γ/h I − J)⁻¹ (f0 + Σ e_a Z_a / h), with the real factors above
        hinv = 1.0 / h
        for i in range(n):
            ynew[i] = y[i] + Z[s - 1, i]
            acc = f0[i]
            for a in range(s):
                acc += E_ERR[a] * Z[a, i] * hinv
            err[i] = acc
            ZE[i] = acc - f0[i]
            scale[i] = atol[i] + max(abs(y[i]), abs(ynew[i])) * rtol
        # after a rejection an estimate above the tolerance is refined once with f(y + err)
        # (radau5): the solve and the norm are written once, for both passes
        err_norm = 0.0
        for sweep in range(2):
            solve(Mr, pivR, dinvR, err)
            acc = 0.0
            for i in range(n):
                r = err[i] / scale[i]
                acc += r * r
            err_norm = math.sqrt(acc / n)      # the root mean square of err / scale
            if sweep == 1 or not (rejected and err_norm > 1.0):
                break
            for i in range(n):
                ytmp[i] = y[i] + err[i]
            fun(t, ytmp, p, err)
            cnt[2] += 1
            for i in range(n):
                err[i] += ZE[i]
        safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)
        # the error test: retry with h/4 after a non-finite error, h·max(0.2, safety·err^(−1/4))
        # above the tolerance; a rejected step keeps J only when it was evaluated for this step (radau5)
        if not math.isfinite(err_norm):
            h_retry = h * 0.25
        elif err_norm > 1.0:
            h_retry = h * max(0.2, safety / _root4(err_norm))
        else:
            h_retry = -1.0
        if h_retry > 0.0:
            cnt[1] += 1
            h = h_retry
            rejected = True
            need_jac = not jac_fresh
            continue
        # accepted: the collocation polynomial Q = V⁻¹Z is the dense output
        cnt[0] += 1
        keep_jac = theta <= THETA_KEEP_JAC and not use_full
        use_full = False
        for i in range(n):
            for j in range(s):
                acc = 0.0
                for a in range(s):
                    acc += VINV[j, a] * Z[a, i]
                Q[j, i] = acc
        t_new = t + h
        if t_end - t_new <= 10 * EPS * abs(t_end):
            # the last step, cut to the end: t + (t_end − t) may round a few ulps short of t_end (t < t_end/2),
            # and the step left would be below the underflow bound (-1); the end is reached
            t_new = t_end
        stop = False
        if ev_idx >= 0:
            # g(x) = g0 + c1 x + c2 x² + c3 x³ may change sign on [0, 1] only when g0 ≠ 0 (a crossing
            # starting on the surface is not one) and |g0| does not exceed the cubic's largest change
            # |c1| + |c2| + |c3| by a margin (10⁻¹²) far above the rounding of its evaluation: most
            # steps are decided here, with scalars only
            ge = y[ev_idx] - ev_val
            if ge != 0.0 and (abs(Q[0, ev_idx]) + abs(Q[1, ev_idx]) + abs(Q[2, ev_idx])) * (1.0 + 1e-12) >= abs(ge):
                stop, nev_dir = _crossings(y, Q, t, h, ev_idx, ev_val, ev_dir, ev_stop, nev_dir, cnt, EVBUF, EVDIR)
        for i in range(n):
            yprev[i] = y[i]
            Qprev[0, i] = Q[0, i]
            Qprev[1, i] = Q[1, i]
            Qprev[2, i] = Q[2, i]
            y[i] = ynew[i]
        tprev = t
        hprev = h
        have_prev = True
        t = t_new
        fun(t, y, p, f0)
        cnt[2] += 1
        if rec_cap > 0:
            k = cnt[7]
            if k < rec_t.shape[0]:
                rec_t[k] = t
                for i in range(n):
                    rec_y[k, i] = y[i]
                cnt[7] += 1
        if stop:
            status = 1
            break
        # the predictive controller (Gustafsson 1994): exponent 1/4 for the order-3 estimate, growth by
        # at most FACMAX, and none right after a rejection
        if err_old > 0 and err_norm > 0:
            mult = h / h_old * _root4(err_old / err_norm)
        else:
            mult = 1.0
        fac = min(1.0, mult) * (1.0 / _root4(err_norm) if err_norm > 0 else FACMAX)
        fac = min(FACMAX, safety * fac)
        if rejected:
            fac = min(1.0, fac)
        h_old = h
        err_old = max(err_norm, 1e-10)
        rejected = False
        # the reuse policy (THETA_KEEP_JAC, HOLD_LO, HOLD_HI): the step size and both factors are held
        # when J is kept and the proposal grows h by less than 20 %; otherwise J is evaluated again at
        # the new point unless the iteration contracted fast
        jac_fresh = False
        need_jac = not keep_jac
        h_new = min(h * fac, max_step)
        if not (keep_jac and HOLD_LO <= h_new / h <= HOLD_HI):
            h = h_new
    # the crossings are in EVBUF[:cnt[6]] and the recorded steps in rec_t, rec_y[:cnt[7]]: radau_core
    # cuts them to size (in Python, which spares the first build the slicing and copying)
    _keep_alive(f0_own, J_own, Mf_own, Mr_own, pivF_own, pivR_own, pivC_own, Z_own, W_own, F_own, JB_own, R_own, Q_own,
                ytmp_own, wsc_own, ynew_own, scale_own, err_own, ZE_own, yprev_own, b0_own, Mcr_own, Mci_own, bre_own,
                bim_own, dinv_own)
    return status, t, y_own, cnt_own, rec_t, rec_y, h, Qprev_own


def pointers(fun, jac):
    """(fun, jac) as :func:`radau_core` calls them (:func:`landau.verify.hybrid.callbacks.make_pointers`
    with the signatures :data:`SIG`, :data:`SIG_JAC`), made once per function."""
    return make_pointers(fun, jac, SIG, SIG_JAC)


_F64 = types.float64
_I64 = types.int64
_A1 = types.float64[::1]
_A2 = types.float64[:, ::1]
#: the one signature the loop is compiled for
_LOOP_SIG = (FUN_T, JAC_T, _F64, _A1, _F64, _A1, _F64, _A1, _F64, _F64, _I64, _I64, _F64, _I64, _I64, _I64, _A2, _A1)
_READY: list[object] = []


def _loop():
    """The compiled loop (built or loaded from the disk cache on first use), or the Python one."""
    if not _READY:
        if jit_enabled():
            compile_once(_radau_loop, _LOOP_SIG, "the Radau IIA integrator")
        else:
            warn_once("nojit", "landau: NUMBA_DISABLE_JIT is set: the Radau IIA integrator runs as plain Python "
                                "(some hundred times slower)")
        _READY.append(True)
    return _radau_loop


def _f64(a, ndim, what):
    a = np.ascontiguousarray(a, dtype=np.float64)
    if a.ndim != ndim:
        raise InputError(f"radau_core: {what} must have {ndim} dimension(s), got shape {a.shape}")
    return a


def radau_core(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir, ev_stop,
               rec_cap, AR=None, VI=None, EVBUF=None, EVDIR=None):
    """Integrate y' = f(t, y; p) from t0 to t_end with the order-5 Radau IIA (module docstring).

    Parameters
    ----------
    fun, jac : function, numba dispatcher or FunctionPointer
        ``fun(t, y, p, out)``, ``jac(t, y, p, out)`` (:func:`pointers`).
    t0, t_end : float
        Interval.
    y0, p : ndarray
        Initial state (n) and parameter vector.
    rtol : float
        Relative tolerance; ``atol`` (ndarray, n) the absolute one.
    h0, max_step : float
        First step and largest step.
    max_steps : int
        Budget of step attempts (accepted and rejected).
    ev_idx, ev_val, ev_dir, ev_stop : int, float, int, int
        Crossings of ``y[ev_idx] = ev_val`` are recorded (``ev_idx < 0``: none); the run stops
        after ``ev_stop > 0`` crossings in direction ``ev_dir`` (±1, 0 = either).
    rec_cap : int
        Number of accepted steps kept (from the start; 0: none).
    AR, VI : ndarray, optional
        :data:`A_RADAU` and :data:`VINV` (accepted for existing callers; no other values).
    EVBUF, EVDIR : ndarray, optional
        m × (n + 1) and m buffers that receive the crossings (time, state) and their directions.

    Returns
    -------
    tuple
        (status, t, y, counters, ev_t, ev_y, rec_t, rec_y, h, Q): status as in :data:`STATUS`;
        counters = [accepted steps, rejected steps, f evaluations, Jacobians, LU decompositions,
        Newton failures, events, recorded steps]; ``h`` the next step size and ``Q`` the last
        accepted step's collocation polynomial (y(t_old + x h_old) = y_old + Σ_j Q_j x^{j+1}),
        so that a caller can drive the method one step at a time (``max_steps = 1``).
    """
    for given, ours, name in ((AR, A_RADAU, "AR"), (VI, VINV, "VI")):
        if given is not None and given is not ours and not np.array_equal(given, ours):
            raise InputError(f"radau_core: {name} must be the Radau IIA coefficients of this module")
    fun, jac = make_pointers(fun, jac, SIG, SIG_JAC)
    y0 = _f64(y0, 1, "y0")
    n = y0.shape[0]
    if EVBUF is None:
        EVBUF = np.empty((1, n + 1))
    if EVDIR is None:
        EVDIR = np.empty(EVBUF.shape[0])
    EVBUF = _f64(EVBUF, 2, "EVBUF")
    status, t, y, cnt, rec_t, rec_y, h, Q = _loop()(
        fun, jac, float(t0), y0, float(t_end), _f64(p, 1, "p"), float(rtol), _f64(atol, 1, "atol"), float(h0),
        float(max_step), int(max_steps), int(ev_idx), float(ev_val), int(ev_dir), int(ev_stop), int(rec_cap), EVBUF,
        _f64(EVDIR, 1, "EVDIR"))
    ne, nrec = min(int(cnt[6]), EVBUF.shape[0]), int(cnt[7])
    return (status, t, y, cnt, EVBUF[:ne, 0].copy(), EVBUF[:ne, 1:].copy(), rec_t[:nrec].copy(), rec_y[:nrec].copy(),
            h, Q)
