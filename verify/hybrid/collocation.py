"""Compiled Radau IIA collocation of any number of stages s (order 2s − 1) for small stiff systems.

The s-stage Radau IIA method (Hairer & Wanner, *Solving ODEs II*, Sec. IV.5 and IV.8) — for
s = 3 the method of :mod:`landau.verify.hybrid.radau`; the 5-stage, order-9 member is the one
of the variable-order code RADAU of Hairer & Wanner (1999).  Its coefficients are computed
here from their definition, not tabulated: the nodes cᵢ are the zeros of
dˢ⁻¹/dxˢ⁻¹ [xˢ⁻¹(x − 1)ˢ] (c_s = 1), the Butcher matrix is aᵢⱼ = ∫₀^{cᵢ} ℓⱼ(τ) dτ
(ℓⱼ the Lagrange basis on the nodes).

The stage equations are solved by simplified Newton on the full sn×sn system I − h(A⊗J) —
for the 3-state spring–block (sn = 15 at s = 5) one dense LU per step.  The error estimate
is the radau5 construction generalised to s stages: an embedded solution
ŷ₁ = y₀ + h(γ₀ f(y₀) + Σ b̂ᵢ f(Yᵢ)) of order s, with γ₀ the real eigenvalue of A
and b̂ from the order conditions Σ b̂ᵢ cᵢ^{k−1} = 1/k − γ₀ δ_{k1} (k = 1…s), filtered by
(I − hγ₀J)⁻¹ (Hairer & Wanner 1996, IV.8, eq. (8.19)–(8.20)); for s = 3 this reproduces the
radau5 weights (a test checks it).  The step is controlled by the predictive (Gustafsson)
controller with exponent 1/(s + 1).

At tolerances where the 3-stage method needs hundreds of steps per period, the order-9
method takes a fraction of them; it has no event location (the order-5 method keeps that).

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

from landau.verify.hybrid.radau import NEWTON_MAXITER, _lu, _rms, _solve

__all__ = ["RadauTableau", "radau_tableau", "collocation_core"]


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


@nb.njit(cache=True)
def _poly_s(y0, Q, x, i):
    s = Q.shape[0]
    acc = 0.0
    for j in range(s - 1, -1, -1):
        acc = x * (acc + Q[j, i])
    return y0[i] + acc


@nb.njit(cache=True)
def collocation_core(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, AR, CN, EE, mu, VI):
    """Integrate from t0 to t_end with the s-stage Radau IIA given by ``AR`` (s × s), nodes ``CN``,
    error weights ``EE``, ``mu`` = 1/γ₀ and ``VI`` (:class:`RadauTableau`).

    Returns (status, t, y, counters) with the status codes of
    :data:`landau.verify.hybrid.radau.STATUS` and counters = [accepted, rejected,
    f evaluations, Jacobians, LU decompositions, Newton failures].
    """
    n = y0.shape[0]
    s = AR.shape[0]
    N = s * n
    cnt = np.zeros(8, dtype=np.int64)
    y = y0.copy()
    t = t0
    f0 = np.empty(n)
    fun(t, y, p, f0)
    cnt[2] += 1
    J = np.empty((n, n))
    Mf = np.empty((N, N))
    Mr = np.empty((n, n))
    pivF = np.empty(N, dtype=np.int64)
    pivR = np.empty(n, dtype=np.int64)
    Z = np.zeros((s, n))
    F = np.empty((s, n))
    R = np.empty(N)
    ytmp = np.empty(n)
    ynew = np.empty(n)
    scale = np.empty(n)
    err = np.empty(n)
    ZE = np.empty(n)
    Q = np.zeros((s, n))
    Qprev = np.zeros((s, n))
    yprev = np.empty(n)
    have_prev = False
    tprev = 0.0
    hprev = 1.0
    EPS = 2.220446049250313e-16
    newton_tol = max(10 * EPS / rtol, min(0.03, rtol ** 0.5))
    expo = 1.0 / (s + 1)
    h = min(h0, max_step, t_end - t0)
    err_old = -1.0
    h_old = -1.0
    rejected = False
    status = 0
    for i in range(n):
        if not math.isfinite(y[i]) or not math.isfinite(f0[i]):
            status = -3
            t_end = t
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
        for a in range(s):
            for b in range(s):
                hab = -h * AR[a, b]
                for i in range(n):
                    for j in range(n):
                        Mf[a * n + i, b * n + j] = hab * J[i, j]
        for i in range(N):
            Mf[i, i] += 1.0
        ok = _lu(Mf, pivF)
        cnt[4] += 1
        for a in range(s):
            for i in range(n):
                if have_prev:
                    x = (t + CN[a] * h - tprev) / hprev
                    Z[a, i] = _poly_s(yprev, Qprev, x, i) - y[i]
                else:
                    Z[a, i] = 0.0
        converged = False
        dW_old = -1.0
        rate = -1.0
        n_iter = 0
        if ok:
            for it in range(NEWTON_MAXITER):
                n_iter = it + 1
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
                for a in range(s):
                    for i in range(n):
                        acc = -Z[a, i]
                        for b in range(s):
                            acc += h * AR[a, b] * F[b, i]
                        R[a * n + i] = acc
                _solve(Mf, pivF, R)
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
                if rate >= 1.0 or (rate > 0 and rate ** (NEWTON_MAXITER - it) / (1 - rate) * dW > newton_tol):
                    break
                if dW == 0.0 or (rate > 0 and rate / (1 - rate) * dW < newton_tol):
                    converged = True
                    break
                dW_old = dW
        if not converged:
            cnt[5] += 1
            cnt[1] += 1
            h *= 0.5
            rejected = True
            continue
        for i in range(n):
            ynew[i] = y[i] + Z[s - 1, i]
        for i in range(n):
            for j in range(n):
                Mr[i, j] = -J[i, j]
            Mr[i, i] += mu / h
        _lu(Mr, pivR)
        cnt[4] += 1
        for i in range(n):
            acc = 0.0
            for a in range(s):
                acc += EE[a] * Z[a, i] / h
            ZE[i] = acc
            err[i] = f0[i] + acc
            scale[i] = atol[i] + max(abs(y[i]), abs(ynew[i])) * rtol
        _solve(Mr, pivR, err)
        err_norm = _rms(err, scale)
        if rejected and err_norm > 1.0:
            for i in range(n):
                ytmp[i] = y[i] + err[i]
            fun(t, ytmp, p, err)
            cnt[2] += 1
            for i in range(n):
                err[i] += ZE[i]
            _solve(Mr, pivR, err)
            err_norm = _rms(err, scale)
        if not math.isfinite(err_norm):
            cnt[1] += 1
            h *= 0.25
            rejected = True
            continue
        safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)
        if err_norm > 1.0:
            h *= max(0.2, safety * err_norm ** -expo)
            cnt[1] += 1
            rejected = True
            continue
        cnt[0] += 1
        for j in range(s):
            for i in range(n):
                acc = 0.0
                for a in range(s):
                    acc += VI[j, a] * Z[a, i]
                Q[j, i] = acc
        for i in range(n):
            yprev[i] = y[i]
        for j in range(s):
            for i in range(n):
                Qprev[j, i] = Q[j, i]
        tprev = t
        hprev = h
        have_prev = True
        t = t + h
        for i in range(n):
            y[i] = ynew[i]
        fun(t, y, p, f0)
        cnt[2] += 1
        if err_old > 0 and err_norm > 0:
            mult = h / h_old * (err_old / err_norm) ** expo
        else:
            mult = 1.0
        fac = min(1.0, mult) * (err_norm ** -expo if err_norm > 0 else 10.0)
        fac = min(10.0, safety * fac)
        if rejected:
            fac = min(1.0, fac)
        h_old = h
        err_old = max(err_norm, 1e-10)
        h = min(h * fac, max_step)
        rejected = False
    return status, t, y, cnt
