"""Compiled Radau IIA collocation of any number of stages s (order 2s − 1) for small stiff systems.

The s-stage Radau IIA method (Hairer & Wanner, *Solving ODEs II*, Sec. IV.5 and IV.8) — for
s = 3 the method of :mod:`landau.verify.hybrid.radau`; the 5-stage, order-9 member is the one
of the variable-order code RADAU of Hairer & Wanner (1999).  Its coefficients are computed
here from their definition, not tabulated: the nodes cᵢ are the zeros of
dˢ⁻¹/dxˢ⁻¹ [xˢ⁻¹(x − 1)ˢ] (c_s = 1), the Butcher matrix is aᵢⱼ = ∫₀^{cᵢ} ℓⱼ(τ) dτ
(ℓⱼ the Lagrange basis on the nodes).

The stage equations are solved by simplified Newton on the full sn×sn system I − h(A⊗J) —
one dense LU per step (for s = 3 the eigenbasis of A⁻¹ — one real and one complex n×n system —
is the cheaper route: :func:`split_coefficients`).  The error estimate
is the radau5 construction generalised to s stages: an embedded solution
ŷ₁ = y₀ + h(γ₀ f(y₀) + Σ b̂ᵢ f(Yᵢ)) of order s, with γ₀ the real eigenvalue of A
and b̂ from the order conditions Σ b̂ᵢ cᵢ^{k−1} = 1/k − γ₀ δ_{k1} (k = 1…s), filtered by
(I − hγ₀J)⁻¹ (Hairer & Wanner 1996, IV.8, eq. (8.19)–(8.20)); for s = 3 this reproduces the
radau5 weights (a test checks it).  The step is controlled by the predictive (Gustafsson)
controller with exponent 1/(s + 1).

At tolerances where the 3-stage method needs hundreds of steps per period, the order-9
method takes a fraction of them; it has no event location (the order-5 method keeps that).

:func:`radau_iia_core` is the integrator of any s, with event location and recording;
:func:`landau.verify.hybrid.radau.radau_core` is it for s = 3 with the closed-form coefficients,
and :func:`collocation_core` for any s without events.  Its set-up, step-size control, event
location and recording are the pieces shared by the compiled stiff integrators
(:mod:`landau.verify.hybrid.stiffdriver`).

Speed (not the arithmetic): the loop works on views of its buffers without numba's atomic
reference counts (:func:`landau.verify.hybrid.nrt.borrowed`), and the order-5 core
(:func:`landau.verify.hybrid.radau.radau_core`) compiles it a second time with constant sizes
for three states (the spring–block), so that the compiler unrolls the small loops and the
9 × 9 LU and solves.  Measured on one period of the Fig. 3 cycle of Putelat et al. (2010):
0.79 → 0.51 µs per step (rtol 1e-10), every step and result unchanged to the bit.  (A third
copy for s = 5 gained 15 % per step of the order-9 method but made its first compilation
take a minute; it is not made.)

References
----------
Hairer, E., Wanner, G. (1996). Solving Ordinary Differential Equations II, 2nd ed.,
Springer, Sec. IV.5 (collocation, Radau IIA), IV.8 (implementation: simplified Newton,
error estimate, step-size control).
Hairer, E., Wanner, G. (1999). Stiff differential equations solved by Radau methods.
J. Comput. Appl. Math. 111, 93–111.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numba as nb
import numpy as np
from numpy.polynomial import polynomial as P

from landau.errors import InputError
from landau.verify.hybrid.nrt import borrowed, keep_alive
from landau.verify.hybrid.stiffdriver import (EPS, _crossings, _finish, _guard, _lu, _lu_n, _may_cross, _next_size,
                                              _poly, _record, _retry_size, _rms, _solve_n, _solve_recip, _start)

__all__ = ["RadauTableau", "radau_tableau", "radau_iia_core", "collocation_core", "NEWTON_MAXITER"]


@dataclass(frozen=True)
class RadauTableau:
    """Coefficients of the s-stage Radau IIA method and of its error estimate.

    ``A`` (s × s), ``c`` (s), ``b`` = last row of A; ``mu`` = 1/γ₀ (γ₀ the real eigenvalue of
    A); ``e`` such that the estimate is (μ/h·I − J)⁻¹(f₀ + Σ eᵢZᵢ/h); ``vinv`` maps the stage
    increments Zᵢ to the collocation polynomial y₀ + Σⱼ Qⱼ x^{j+1} (Q = vinv·Z).
    """

    s: int
    A: np.ndarray
    c: np.ndarray
    mu: float
    e: np.ndarray
    vinv: np.ndarray

    @property
    def order(self) -> int:
        return 2 * self.s - 1

    def __repr__(self) -> str:
        return f"RadauTableau(s={self.s}, order={self.order}, mu={self.mu:.6g})"


@lru_cache(maxsize=None)
def radau_tableau(s: int) -> RadauTableau:
    """The s-stage Radau IIA tableau computed from its definition (module docstring).

    Parameters
    ----------
    s : int
        Number of stages (1 … 7).

    Returns
    -------
    RadauTableau
    """
    if not 1 <= s <= 7:
        raise ValueError(f"stages must be in 1..7, got {s}")
    # nodes: zeros of the (s−1)th derivative of x^(s−1) (x−1)^s
    poly = P.polymul(P.polypow([0.0, 1.0], s - 1), P.polypow([-1.0, 1.0], s))
    c = np.sort(np.real(P.polyroots(P.polyder(poly, s - 1)))) if s > 1 else np.array([1.0])
    c[-1] = 1.0
    # a_ij = ∫_0^{c_i} ℓ_j: solve Σ_j a_ij c_j^{k-1} = c_i^k / k  (k = 1..s)
    V = np.vander(c, s, increasing=True)          # V[j, k] = c_j^k
    rhs = np.array([[ci ** (k + 1) / (k + 1) for k in range(s)] for ci in c])
    A = np.linalg.solve(V.T, rhs.T).T
    ev = np.linalg.eigvals(A)
    gamma0 = float(np.real(ev[np.argmin(np.abs(np.imag(ev)))]))
    # embedded order-s weights: γ0·[k = 1] + Σ b̂_i c_i^{k-1} = 1/k
    bhat = np.linalg.solve(V.T, np.array([1.0 / (k + 1) - (gamma0 if k == 0 else 0.0) for k in range(s)]))
    e = (bhat - A[-1]) @ np.linalg.inv(A) / gamma0
    vinv = np.linalg.inv(np.array([[ci ** (j + 1) for j in range(s)] for ci in c]))
    return RadauTableau(s, A, c, 1.0 / gamma0, e, vinv)


#: Newton sweeps of the simplified iteration before a step is declared failed
NEWTON_MAXITER = 7


@nb.njit(cache=True)
def _stage_jacobians(jac, t, h, y, Z, p, AR, CN, JB, ytmp, Mf, pivF, cnt):
    """The full-Newton matrix I − h(A ⊗ I)·diag(J(Y_b)) with the stage Jacobians at the current
    iterate, factorised in place; False when it is singular (off the hot path of the simplified
    iteration, so kept out of its loop)."""
    s, n = Z.shape
    for b in range(s):
        for i in range(n):
            ytmp[i] = y[i] + Z[b, i]
        jac(t + CN[b] * h, ytmp, p, JB[b])
        cnt[3] += 1
    for a in range(s):
        for b in range(s):
            hab = -h * AR[a, b]
            for i in range(n):
                for j in range(n):
                    Mf[a * n + i, b * n + j] = hab * JB[b, i, j]
    for i in range(s * n):
        Mf[i, i] += 1.0
    if not _lu(Mf, pivF):
        return False
    cnt[4] += 1
    return True


@nb.njit(cache=True)
def radau_iia_core(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir, ev_stop,
                   rec_cap, AR, CN, EE, mu, VI, full_retry, f0_first, EVBUF, EVDIR):
    """Integrate from t0 to t_end with the s-stage Radau IIA given by ``AR`` (s × s), nodes ``CN``,
    error weights ``EE``, ``mu`` = 1/γ₀ and ``VI`` (:class:`RadauTableau`).

    The stage increments Z solve Z = h(A ⊗ I)F(y + Z) by simplified Newton on I − h(A⊗J),
    started from the previous step's collocation polynomial.  With ``full_retry``, a failed
    iteration is retried at the same h with the stage Jacobians J(Y_b) in
    I − h(A ⊗ I)·diag(J(Y_b)) (needed when the Jacobian changes by orders of magnitude within
    a step: ẇ ∝ e^{−w} as v → 0); without it, h is halved.  Error estimate:
    (μ/h·I − J)⁻¹(f₀ + Σ eᵢZᵢ/h), filtered once more through f after a rejection (Hairer &
    Wanner 1996, IV.8); ``f0_first`` sums the terms onto f₀ (the order of the first order-5
    code, kept so that its results do not change in the last bit).  The step loop is made of
    the pieces of :mod:`landau.verify.hybrid.stiffdriver`.

    Returns (status, t, y, counters, ev_t, ev_y, rec_t, rec_y, h, Q) as
    :func:`landau.verify.hybrid.radau.radau_core` does.

    Raises
    ------
    InputError
        When crossings are asked for (``ev_idx >= 0``) with s ≠ 3: they are located on a cubic.
    """
    return _radau_iia_any(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir,
                          ev_stop, rec_cap, AR, CN, EE, mu, VI, full_retry, f0_first, EVBUF, EVDIR, y0.shape[0],
                          AR.shape[0])


def _radau_iia_body(fun, jac, t0, y0, t_end, p_in, rtol, atol_in, h0, max_step, max_steps, ev_idx, ev_val, ev_dir,
               ev_stop, rec_cap, AR_in, CN_in, EE_in, mu, VI_in, full_retry, f0_first, EVBUF_in, EVDIR_in, n, s):
    """The body of :func:`radau_iia_core` for n states and s stages, inlined where it is called:
    with constant n and s (:func:`landau.verify.hybrid.radau.radau_core` for three states) the
    compiler unrolls the small loops — the same operations in the same order."""
    N = s * n
    if ev_idx >= 0 and s != 3:
        raise InputError("radau_iia_core: event location needs the cubic dense output of three stages")
    y_own, f0_own, cnt_own, rec_t_own, rec_y_own, h, status, t_end = _start(fun, t0, y0, t_end, p_in, h0, max_step,
                                                                              rec_cap)
    # work arrays, owned here and used in the loop through borrowed views (no reference counts,
    # landau.verify.hybrid.nrt); the owners are kept alive to the end (keep_alive, _finish)
    J_own = np.empty((n, n))
    Mf_own = np.empty((N, N))
    Mr_own = np.empty((n, n))
    pivF_own = np.empty(N, dtype=np.int64)
    pivR_own = np.empty(n, dtype=np.int64)
    Z_own = np.zeros((s, n))
    F_own = np.empty((s, n))
    JB_own = np.empty((s, n, n))
    R_own = np.empty(N)
    vec_own = np.empty((7, n))
    Q_own = np.zeros((s, n))
    Qprev_own = np.zeros((s, n))
    y, f0, cnt, rec_t, rec_y = borrowed(y_own), borrowed(f0_own), borrowed(cnt_own), borrowed(rec_t_own), borrowed(
        rec_y_own)
    p, atol, AR, CN, EE, VI = borrowed(p_in), borrowed(atol_in), borrowed(AR_in), borrowed(CN_in), borrowed(
        EE_in), borrowed(VI_in)
    EVBUF, EVDIR = borrowed(EVBUF_in), borrowed(EVDIR_in)
    J, Mf, Mr, pivF, pivR = borrowed(J_own), borrowed(Mf_own), borrowed(Mr_own), borrowed(pivF_own), borrowed(pivR_own)
    Z, F, JB, R, Q, Qprev = borrowed(Z_own), borrowed(F_own), borrowed(JB_own), borrowed(R_own), borrowed(
        Q_own), borrowed(Qprev_own)
    vec = borrowed(vec_own)
    ytmp, ynew, scale, err, ZE, yprev = vec[0], vec[1], vec[2], vec[3], vec[4], vec[5]
    t = t0
    have_prev = False
    tprev = 0.0
    hprev = 1.0
    newton_tol = max(10 * EPS / rtol, min(0.03, rtol ** 0.5))
    expo = 1.0 / (s + 1)
    use_full = False
    err_old = -1.0
    h_old = -1.0
    rejected = False
    nev_dir = 0
    while t < t_end:
        status, h = _guard(cnt[0] + cnt[1], max_steps, t, t_end, h)
        if status != 0:
            break
        jac(t, y, p, J)
        cnt[3] += 1
        for a in range(s):
            for b in range(s):
                hab = -h * AR[a, b]
                for i in range(n):
                    for j in range(n):
                        Mf[a * n + i, b * n + j] = hab * J[i, j]
        for i in range(N):
            Mf[i, i] += 1.0
        ok = _lu_n(Mf, pivF, N)
        cnt[4] += 1
        # Newton start: extrapolate the previous collocation polynomial
        for a in range(s):
            for i in range(n):
                if have_prev:
                    x = (t + CN[a] * h - tprev) / hprev
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
                for a in range(s):
                    for i in range(n):
                        ytmp[i] = y[i] + Z[a, i]
                    fa = F[a]
                    fun(t + CN[a] * h, ytmp, p, fa)
                    cnt[2] += 1
                    for i in range(n):
                        if not math.isfinite(fa[i]):
                            finite = False
                if not finite:
                    break
                if use_full and not _stage_jacobians(jac, t, h, y, Z, p, AR, CN, JB, ytmp, Mf, pivF, cnt):
                    break
                for a in range(s):
                    for i in range(n):
                        acc = -Z[a, i]
                        for b in range(s):
                            acc += h * AR[a, b] * F[b, i]
                        R[a * n + i] = acc
                _solve_n(Mf, pivF, R, N)
                dW = 0.0
                for a in range(s):
                    for i in range(n):
                        sc = atol[i] + abs(y[i] + Z[a, i]) * rtol
                        r = R[a * n + i] / sc
                        dW += r * r
                        Z[a, i] += R[a * n + i]
                dW = math.sqrt(dW / N)
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
            if use_full or not full_retry:
                h *= 0.5
            use_full = full_retry
            rejected = True
            continue
        for i in range(n):
            ynew[i] = y[i] + Z[s - 1, i]
        # embedded error estimate: (μ/h I − J)⁻¹ (f0 + Σ e_a Z_a / h)
        for i in range(n):
            for j in range(n):
                Mr[i, j] = -J[i, j]
            Mr[i, i] += mu / h
        _lu_n(Mr, pivR, n)
        cnt[4] += 1
        for i in range(n):
            if f0_first:
                acc = f0[i]
                for a in range(s):
                    acc += EE[a] * Z[a, i] / h
                err[i] = acc
                ZE[i] = acc - f0[i]
            else:
                acc = 0.0
                for a in range(s):
                    acc += EE[a] * Z[a, i] / h
                ZE[i] = acc
                err[i] = f0[i] + acc
            scale[i] = atol[i] + max(abs(y[i]), abs(ynew[i])) * rtol
        _solve_n(Mr, pivR, err, n)
        err_norm = _rms(err, scale)
        if rejected and err_norm > 1.0:
            for i in range(n):
                ytmp[i] = y[i] + err[i]
            fun(t, ytmp, p, err)
            cnt[2] += 1
            for i in range(n):
                err[i] += ZE[i]
            _solve_n(Mr, pivR, err, n)
            err_norm = _rms(err, scale)
        safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)
        h_retry = _retry_size(h, err_norm, safety, expo)
        if h_retry > 0.0:
            cnt[1] += 1
            h = h_retry
            rejected = True
            continue
        # accepted: the collocation polynomial Q = V⁻¹Z is the dense output
        cnt[0] += 1
        use_full = False
        for j in range(s):
            for i in range(n):
                acc = 0.0
                for a in range(s):
                    acc += VI[j, a] * Z[a, i]
                Q[j, i] = acc
        t_new = t + h
        stop = False
        if ev_idx >= 0 and _may_cross(y[ev_idx] - ev_val, Q[0, ev_idx], Q[1, ev_idx], Q[2, ev_idx]):
            stop, nev_dir = _crossings(y, Q, t, h, ev_idx, ev_val, ev_dir, ev_stop, nev_dir, cnt, EVBUF, EVDIR)
        # keep this step's polynomial for the next Newton start
        for i in range(n):
            yprev[i] = y[i]
        for j in range(s):
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
        if rec_cap > 0:
            _record(cnt, rec_t, rec_y, t, y)
        if stop:
            status = 1
            break
        h, h_old, err_old = _next_size(h, h_old, err_norm, err_old, rejected, safety, expo, 10.0, max_step)
        rejected = False
    keep_alive((f0_own, J_own, Mf_own, Mr_own, pivF_own, pivR_own, Z_own, F_own, JB_own, R_own, vec_own, Q_own))
    return _finish(status, t, y_own, cnt_own, EVBUF_in, rec_t_own, rec_y_own, h, Qprev_own)


#: the loop inlined at its call (for constant sizes; its callers are cached) and compiled on its
#: own for any sizes (inlining the whole loop where the sizes are not constant only costs compile
#: time: measured 27 s instead of 6 s for the first order-9 run)
_radau_iia = nb.njit(inline="always")(_radau_iia_body)
_radau_iia_any = nb.njit(cache=True)(_radau_iia_body)


@nb.njit(cache=True)
def collocation_core(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, AR, CN, EE, mu, VI):
    """Integrate from t0 to t_end with the s-stage Radau IIA given by ``AR`` (s × s), nodes ``CN``,
    error weights ``EE``, ``mu`` = 1/γ₀ and ``VI`` (:class:`RadauTableau`).

    Returns (status, t, y, counters) with the status codes of
    :data:`landau.verify.hybrid.radau.STATUS` and counters = [accepted, rejected,
    f evaluations, Jacobians, LU decompositions, Newton failures] (:func:`radau_iia_core`
    without event location or recording; a failed Newton iteration halves the step).
    """
    n = y0.shape[0]
    out = radau_iia_core(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, -1, 0.0, 0, 0, 0, AR, CN,
                         EE, mu, VI, False, False, np.empty((1, n + 1)), np.empty(1))
    return out[0], out[1], out[2], out[3]


def split_coefficients(A):
    """The transformation of the 3-stage Newton system to one real and one complex n × n system.

    A⁻¹ = T·Λ·T⁻¹ with Λ = diag(γ, [[α, −β], [β, α]]): γ the real eigenvalue of A⁻¹ and
    α ± iβ (β > 0) its complex pair (Hairer & Wanner 1996, IV.8, eq. (8.15)–(8.18)).  With
    W = T⁻¹Z the stage equations Z = h(A ⊗ I)F decouple, for a constant Jacobian, into
    (γ/h·I − J)·ΔW₁ = … and ((α + iβ)/h·I − J)·(ΔW₂ + iΔW₃) = ….

    Parameters
    ----------
    A : ndarray, shape (3, 3)
        Butcher matrix of a 3-stage method whose A⁻¹ has one real eigenvalue and a complex pair.

    Returns
    -------
    (T, TI, gamma, alpha, beta) : (ndarray, ndarray, float, float, float)
    """
    A = np.asarray(A, dtype=float)
    if A.shape != (3, 3):
        raise InputError(f"split_coefficients: a 3 x 3 Butcher matrix is needed, got shape {A.shape}")
    AI = np.linalg.inv(A)
    lam, vec = np.linalg.eig(AI)
    ir = int(np.argmin(np.abs(np.imag(lam))))
    ic = int(np.argmin(np.imag(lam)))          # the eigenvalue α − iβ of the pair
    if ic == ir or abs(np.imag(lam[ic])) == 0.0:
        raise InputError("split_coefficients: A⁻¹ has no complex eigenvalue pair")
    gamma = float(np.real(lam[ir]))
    alpha, beta = float(np.real(lam[ic])), float(-np.imag(lam[ic]))
    u = vec[:, ic]
    T = np.column_stack([np.real(vec[:, ir]), np.real(u), np.imag(u)])
    TI = np.linalg.inv(T)
    Lam = np.array([[gamma, 0.0, 0.0], [0.0, alpha, -beta], [0.0, beta, alpha]])
    if not np.allclose(T @ Lam @ TI, AI, rtol=1e-12, atol=1e-12 * np.abs(AI).max()):
        raise InputError("split_coefficients: the eigen-decomposition of A⁻¹ does not reproduce it")
    return T, TI, gamma, alpha, beta


def _radau_split_body(fun, jac, t0, y0, t_end, p_in, rtol, atol_in, h0, max_step, max_steps, ev_idx, ev_val, ev_dir,
                      ev_stop, rec_cap, AR_in, CN_in, EE_in, VI_in, T_in, TI_in, gam, alp, bet, EVBUF_in, EVDIR_in, n):
    """The 3-stage Radau IIA of :func:`_radau_iia_body` (``full_retry`` and ``f0_first`` on) with
    the simplified Newton system solved in the eigenbasis of A⁻¹ (:func:`split_coefficients`):
    per step one real n × n LU of γ/h·I − J (also the matrix of the error estimate) and one
    complex n × n LU of (α + iβ)/h·I − J instead of the 3n × 3n LU.  The increments are mapped
    back to Z (ΔZ = T·ΔW), so that the convergence test, the error estimate, the dense output
    and the events are those of the untransformed iteration.  A retry with the stage Jacobians
    uses the full 3n × 3n system, as :func:`_radau_iia_body` does.  Same results up to rounding
    (not bit-identical: the linear algebra differs)."""
    s = 3
    N = s * n
    y_own, f0_own, cnt_own, rec_t_own, rec_y_own, h, status, t_end = _start(fun, t0, y0, t_end, p_in, h0, max_step,
                                                                              rec_cap)
    J_own = np.empty((n, n))
    Mf_own = np.empty((N, N))
    Mr_own = np.empty((n, n))
    Mc_own = np.empty((n, n), dtype=np.complex128)
    bc_own = np.empty(n, dtype=np.complex128)
    pivF_own = np.empty(N, dtype=np.int64)
    pivR_own = np.empty(n, dtype=np.int64)
    pivC_own = np.empty(n, dtype=np.int64)
    Z_own = np.zeros((s, n))
    F_own = np.empty((s, n))
    JB_own = np.empty((s, n, n))
    R_own = np.empty(N)
    vec_own = np.empty((10, n))
    Q_own = np.zeros((s, n))
    Qprev_own = np.zeros((s, n))
    y, f0, cnt, rec_t, rec_y = borrowed(y_own), borrowed(f0_own), borrowed(cnt_own), borrowed(rec_t_own), borrowed(
        rec_y_own)
    p, atol, AR, CN, EE, VI = borrowed(p_in), borrowed(atol_in), borrowed(AR_in), borrowed(CN_in), borrowed(
        EE_in), borrowed(VI_in)
    T, TI = borrowed(T_in), borrowed(TI_in)
    EVBUF, EVDIR = borrowed(EVBUF_in), borrowed(EVDIR_in)
    J, Mf, Mr, pivF, pivR = borrowed(J_own), borrowed(Mf_own), borrowed(Mr_own), borrowed(pivF_own), borrowed(pivR_own)
    Mc, bc, pivC = borrowed(Mc_own), borrowed(bc_own), borrowed(pivC_own)
    Z, F, JB, R, Q, Qprev = borrowed(Z_own), borrowed(F_own), borrowed(JB_own), borrowed(R_own), borrowed(
        Q_own), borrowed(Qprev_own)
    vec = borrowed(vec_own)
    ytmp, ynew, scale, err, ZE, yprev = vec[0], vec[1], vec[2], vec[3], vec[4], vec[5]
    b0, b1, b2 = vec[6], vec[7], vec[8]
    W_own = np.empty((s, n))
    W = borrowed(W_own)
    dinv_own = np.empty(n, dtype=np.complex128)
    dinv = borrowed(dinv_own)
    t = t0
    have_prev = False
    tprev = 0.0
    hprev = 1.0
    newton_tol = max(10 * EPS / rtol, min(0.03, rtol ** 0.5))
    expo = 1.0 / (s + 1)
    use_full = False
    err_old = -1.0
    h_old = -1.0
    rejected = False
    nev_dir = 0
    while t < t_end:
        status, h = _guard(cnt[0] + cnt[1], max_steps, t, t_end, h)
        if status != 0:
            break
        jac(t, y, p, J)
        cnt[3] += 1
        gh = gam / h
        ah = alp / h
        bh = bet / h
        ch = complex(ah, bh)
        for i in range(n):
            for j in range(n):
                Mr[i, j] = -J[i, j]
                Mc[i, j] = -J[i, j]
            Mr[i, i] += gh
            Mc[i, i] += ch
        ok = _lu_n(Mr, pivR, n)
        cnt[4] += 1
        if not use_full:
            ok = _lu_n(Mc, pivC, n) and ok
            cnt[4] += 1
            if ok:
                for i in range(n):
                    dinv[i] = 1.0 / Mc[i, i]
        for a in range(s):
            for i in range(n):
                if have_prev:
                    x = (t + CN[a] * h - tprev) / hprev
                    Z[a, i] = _poly(yprev, Qprev, x, i) - y[i]
                else:
                    Z[a, i] = 0.0
        if not use_full:
            for i in range(n):
                W[0, i] = TI[0, 0] * Z[0, i] + TI[0, 1] * Z[1, i] + TI[0, 2] * Z[2, i]
                W[1, i] = TI[1, 0] * Z[0, i] + TI[1, 1] * Z[1, i] + TI[1, 2] * Z[2, i]
                W[2, i] = TI[2, 0] * Z[0, i] + TI[2, 1] * Z[1, i] + TI[2, 2] * Z[2, i]
        converged = False
        dW_old = -1.0
        rate = -1.0
        n_iter = 0
        if ok:
            for it in range(3 * NEWTON_MAXITER if use_full else NEWTON_MAXITER):
                n_iter = min(it + 1, NEWTON_MAXITER)
                finite = True
                for a in range(s):
                    for i in range(n):
                        ytmp[i] = y[i] + Z[a, i]
                    fa = F[a]
                    fun(t + CN[a] * h, ytmp, p, fa)
                    cnt[2] += 1
                    for i in range(n):
                        if not math.isfinite(fa[i]):
                            finite = False
                if not finite:
                    break
                if use_full:
                    if not _stage_jacobians(jac, t, h, y, Z, p, AR, CN, JB, ytmp, Mf, pivF, cnt):
                        break
                    for a in range(s):
                        for i in range(n):
                            acc = -Z[a, i]
                            for b in range(s):
                                acc += h * AR[a, b] * F[b, i]
                            R[a * n + i] = acc
                    _solve_n(Mf, pivF, R, N)
                else:
                    # right-hand sides T⁻¹F − (Λ/h)·T⁻¹Z of the decoupled systems
                    for i in range(n):
                        g0 = TI[0, 0] * F[0, i] + TI[0, 1] * F[1, i] + TI[0, 2] * F[2, i]
                        g1 = TI[1, 0] * F[0, i] + TI[1, 1] * F[1, i] + TI[1, 2] * F[2, i]
                        g2 = TI[2, 0] * F[0, i] + TI[2, 1] * F[1, i] + TI[2, 2] * F[2, i]
                        w0, w1, w2 = W[0, i], W[1, i], W[2, i]
                        b0[i] = g0 - gh * w0
                        bc[i] = complex(g1 - (ah * w1 - bh * w2), g2 - (bh * w1 + ah * w2))
                    _solve_n(Mr, pivR, b0, n)
                    _solve_recip(Mc, pivC, dinv, bc, n)
                    for i in range(n):
                        b1[i] = bc[i].real
                        b2[i] = bc[i].imag
                        W[0, i] += b0[i]
                        W[1, i] += b1[i]
                        W[2, i] += b2[i]
                    for a in range(s):
                        for i in range(n):
                            R[a * n + i] = T[a, 0] * b0[i] + T[a, 1] * b1[i] + T[a, 2] * b2[i]
                dW = 0.0
                for a in range(s):
                    for i in range(n):
                        sc = atol[i] + abs(y[i] + Z[a, i]) * rtol
                        r = R[a * n + i] / sc
                        dW += r * r
                        Z[a, i] += R[a * n + i]
                dW = math.sqrt(dW / N)
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
            ynew[i] = y[i] + Z[s - 1, i]
        # embedded error estimate: (γ/h I − J)⁻¹ (f0 + Σ e_a Z_a / h), with the real factors above
        for i in range(n):
            acc = f0[i]
            for a in range(s):
                acc += EE[a] * Z[a, i] / h
            err[i] = acc
            ZE[i] = acc - f0[i]
            scale[i] = atol[i] + max(abs(y[i]), abs(ynew[i])) * rtol
        _solve_n(Mr, pivR, err, n)
        err_norm = _rms(err, scale)
        if rejected and err_norm > 1.0:
            for i in range(n):
                ytmp[i] = y[i] + err[i]
            fun(t, ytmp, p, err)
            cnt[2] += 1
            for i in range(n):
                err[i] += ZE[i]
            _solve_n(Mr, pivR, err, n)
            err_norm = _rms(err, scale)
        safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)
        h_retry = _retry_size(h, err_norm, safety, expo)
        if h_retry > 0.0:
            cnt[1] += 1
            h = h_retry
            rejected = True
            continue
        cnt[0] += 1
        use_full = False
        for j in range(s):
            for i in range(n):
                acc = 0.0
                for a in range(s):
                    acc += VI[j, a] * Z[a, i]
                Q[j, i] = acc
        t_new = t + h
        stop = False
        if ev_idx >= 0 and _may_cross(y[ev_idx] - ev_val, Q[0, ev_idx], Q[1, ev_idx], Q[2, ev_idx]):
            stop, nev_dir = _crossings(y, Q, t, h, ev_idx, ev_val, ev_dir, ev_stop, nev_dir, cnt, EVBUF, EVDIR)
        for i in range(n):
            yprev[i] = y[i]
        for j in range(s):
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
        if rec_cap > 0:
            _record(cnt, rec_t, rec_y, t, y)
        if stop:
            status = 1
            break
        h, h_old, err_old = _next_size(h, h_old, err_norm, err_old, rejected, safety, expo, 10.0, max_step)
        rejected = False
    keep_alive((f0_own, J_own, Mf_own, Mr_own, pivF_own, pivR_own, Z_own, F_own, JB_own, R_own, vec_own, Q_own))
    keep_alive((Mc_own, bc_own, pivC_own, W_own, dinv_own))
    return _finish(status, t, y_own, cnt_own, EVBUF_in, rec_t_own, rec_y_own, h, Qprev_own)


#: the split loop inlined where it is called with a constant n (radau.radau_split_core) and on its own for any n
_radau_split = nb.njit(inline="always")(_radau_split_body)
_radau_split_any = nb.njit(cache=True)(_radau_split_body)
