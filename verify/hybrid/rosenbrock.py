"""Compiled Rosenbrock–Wanner method RODAS4 for small stiff systems with an analytic Jacobian.

RODAS4 (Hairer & Wanner, *Solving ODEs II*, Sec. VI.4; coefficients of their code RODAS,
``METH = 1``) is a 6-stage, order-4, L-stable, stiffly accurate Rosenbrock method with an
embedded order-3 solution.  One step costs one Jacobian, one LU of the n×n matrix
(1/(hγ))·I − J and six right-hand sides — no Newton iteration — about half the cost of a
step of the Radau IIA of :mod:`landau.verify.hybrid.radau` (a 3n×3n LU and two or more
Newton sweeps of three stages each) on the 3-state spring–block.  Being of order 4 and
linearly implicit, it is less accurate per step: on the stick–slip cycle of Putelat et al.
(2010), Fig. 3, it takes as many steps as the Radau IIA at the same tolerance for a 20–40
times larger error at the end of a period, so there the Radau IIA is cheaper at equal error
(``benchmarks/run.py --only springblock``).

The method is written in the "transformed" variables of Hairer & Wanner (Sec. IV.7,
"implementation of Rosenbrock-type methods"): with uᵢ = Σⱼ γᵢⱼ kⱼ,

    ((1/(hγ)) I − J) uᵢ = f(t + cᵢh, y₀ + Σⱼ<ᵢ aᵢⱼ uⱼ) + Σⱼ<ᵢ (Cᵢⱼ/h) uⱼ + h dᵢ ∂f/∂t,
    y₁ = y₀ + Σ mⱼ uⱼ,      error estimate  Σ eⱼ uⱼ  (for RODAS4: the last stage u₆).

:func:`tableau_classical` maps the coefficients back to the classical (α, γ, b) form in which
the order conditions are stated (a test checks them up to order 4).

Step-size control is the predictive (Gustafsson) controller with exponent 1/4 (the
embedded estimate is of order 3), as in the Radau IIA.  The dense output is the cubic
Hermite interpolant of the step (the derivative at the end is the next step's first
stage, so it costs nothing); crossings of one component are located on it with the compiled
event locator of :mod:`landau.verify.hybrid.crossing`, exactly as the Radau IIA does on its
collocation polynomial.

The set-up, step-size control, event location and recording are the pieces shared by the
compiled stiff integrators (:mod:`landau.verify.hybrid.stiffdriver`); this module holds the
coefficients, the step and the Hermite interpolant.

:func:`rosenbrock_core` has the calling convention and the return value of
:func:`landau.verify.hybrid.radau.radau_core` (with ``Q`` the Hermite cubic's coefficients),
so a caller switches method by switching function; :class:`CompiledRODAS4` is the
stepper factory of :mod:`landau.verify.hybrid.steppers` over a compiled kernel.

References
----------
Hairer, E., Wanner, G. (1996). Solving Ordinary Differential Equations II, 2nd ed.,
Springer, Sec. IV.7 (Rosenbrock methods, order conditions Table 7.1, embedded
methods and implementation) and Sec. VI.4 (RODAS).
Gustafsson, K. (1994). Control-theoretic techniques for stepsize selection in implicit
Runge–Kutta methods. ACM Trans. Math. Softw. 20, 496–517.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba as nb
import numpy as np

from landau.verify.hybrid.compiled import _Collocation, _CompiledFactory, _CompiledStepper
from landau.verify.hybrid.stiffdriver import (EPS, STATUS, _crossings, _finish, _guard, _lu, _may_cross, _next_size,
                                              _record, _retry_size, _rms, _solve, _start)

__all__ = ["RODAS4_GAMMA", "RODAS4_A", "RODAS4_C", "RODAS4_CNODES", "RODAS4_D", "RODAS4_M", "RODAS4_E",
           "STATUS", "rosenbrock_core", "tableau_classical", "CompiledRODAS4", "RODAS4Solver"]

#: RODAS4 (Hairer & Wanner 1996, Sec. VI.4), transformed coefficients: γ, a_ij, C_ij, c_i, d_i
RODAS4_GAMMA = 0.25
_A_LOWER = (
    (1.544,),
    (0.9466785280815826, 0.2557011698983284),
    (3.314825187068521, 2.896124015972201, 0.9986419139977817),
    (1.221224509226641, 6.019134481288629, 12.53708332932087, -0.6878860361058950),
)
_C_LOWER = (
    (-5.6688,),
    (-2.430093356833875, -0.2063599157091915),
    (-0.1073529058151375, -9.594562251023355, -20.47028614809616),
    (7.496443313967647, -10.24680431464352, -33.99990352819905, 11.70890893206160),
    (8.083246795921522, -7.981132988064893, -31.52159432874371, 16.31930543123136, -6.058818238834054),
)


def _lower(rows, s):
    out = np.zeros((s, s))
    for i, r in enumerate(rows):
        out[i + 1, :len(r)] = r
    return out


#: a_ij: stage i evaluates f at y₀ + Σⱼ a_ij u_j (stage 6 = the embedded solution y₀ + Σ a₅ⱼuⱼ + u₅)
RODAS4_A = _lower(_A_LOWER + ((*_A_LOWER[3], 1.0),), 6)
#: C_ij: stage i's right-hand side gets + Σⱼ C_ij u_j / h
RODAS4_C = _lower(_C_LOWER, 6)
#: nodes c_i (stiffly accurate: the last two stages sit at t + h)
RODAS4_CNODES = np.array([0.0, 0.386, 0.21, 0.63, 1.0, 1.0])
#: d_i = Σⱼ γ_ij (coefficient of h ∂f/∂t)
RODAS4_D = np.array([0.25, -0.1043, 0.1035, -0.0362, 0.0, 0.0])
#: weights m_j of y₁ = y₀ + Σ m_j u_j (y₁ = the stage-6 point + u₆)
RODAS4_M = np.array([*_A_LOWER[3], 1.0, 1.0])
#: error-estimate weights: y₁ − ŷ₁ = u₆
RODAS4_E = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 1.0])


@dataclass(frozen=True)
class ClassicalTableau:
    """A Rosenbrock method in the classical form (Hairer & Wanner 1996, IV.7 eq. (7.4)):
    (I − hγ_iiJ) k_i = h f(y₀ + Σ α_ij k_j) + hJ Σ γ_ij k_j, y₁ = y₀ + Σ b_i k_i."""

    alpha: np.ndarray
    gamma: np.ndarray
    b: np.ndarray
    b_hat: np.ndarray

    def __repr__(self) -> str:
        return f"ClassicalTableau(stages={len(self.b)}, gamma={self.gamma[0, 0]:g})"


def tableau_classical(gamma: float = RODAS4_GAMMA, A=RODAS4_A, C=RODAS4_C, m=RODAS4_M, e=RODAS4_E) -> ClassicalTableau:
    """The classical coefficients of a Rosenbrock method given in transformed form.

    With Γ = (γ_ij) (diagonal γ), the transformation u = Γk gives Γ⁻¹ = diag(1/γ) − C,
    α = AΓ, b = mΓ and b̂ = (m − e)Γ (Hairer & Wanner 1996, IV.7, "transformed" method).

    Parameters
    ----------
    gamma : float
        The diagonal γ.
    A, C : ndarray
        Transformed stage coefficients (strictly lower triangular).
    m, e : ndarray
        Weights of the solution and of the error estimate.

    Returns
    -------
    ClassicalTableau
    """
    s = len(m)
    G = np.linalg.inv(np.eye(s) / gamma - np.asarray(C))
    return ClassicalTableau(np.asarray(A) @ G, G, np.asarray(m) @ G, (np.asarray(m) - np.asarray(e)) @ G)


@nb.njit(cache=True)
def rosenbrock_core(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps,
                    ev_idx, ev_val, ev_dir, ev_stop, rec_cap, autonomous, one_step, RA, RC, RCN, RD, RM, RE, EVBUF,
                    EVDIR):
    """Integrate from t0 to t_end with a Rosenbrock method (RODAS4 by default).

    Returns (status, t, y, counters, ev_t, ev_y, rec_t, rec_y, h, Q) as
    :func:`landau.verify.hybrid.radau.radau_core` does: counters = [accepted, rejected,
    f evaluations, Jacobians, LU decompositions, 0, events, recorded steps]; ``h`` is the
    next step size and ``Q`` (3 × n) the last accepted step's Hermite cubic
    y(t_old + x h_old) = y_old + Σ_j Q_j x^{j+1}.  ``autonomous = 0`` adds the h dᵢ ∂f/∂t
    term (∂f/∂t by a forward difference, one more evaluation per step); ``one_step = 1`` returns
    after the first accepted step (status 0).  ``RA``/``RC``
    (s × s), ``RCN``, ``RD``, ``RM``, ``RE`` (s) are the transformed coefficients.
    """
    n = y0.shape[0]
    s = RM.shape[0]
    gam = RD[0]
    y, f0, cnt, rec_t, rec_y, h, status, t_end = _start(fun, t0, y0, t_end, p, h0, max_step, rec_cap)
    t = t0
    J = np.empty((n, n))
    M = np.empty((n, n))
    piv = np.empty(n, dtype=np.int64)
    U = np.empty((s, n))
    ft = np.zeros(n)
    ytmp = np.empty(n)
    fs = np.empty(n)
    ynew = np.empty(n)
    fnew = np.empty(n)
    err = np.empty(n)
    scale = np.empty(n)
    Q = np.zeros((3, n))
    err_old = -1.0
    h_old = -1.0
    rejected = False
    nev_dir = 0
    need_jac = True
    while t < t_end:
        status, h = _guard(cnt[0] + cnt[1], max_steps, t, t_end, h)
        if status != 0:
            break
        if need_jac:
            jac(t, y, p, J)
            cnt[3] += 1
            if autonomous == 0:
                dt = math.sqrt(EPS) * max(1e-5, abs(t))
                fun(t + dt, y, p, ft)
                cnt[2] += 1
                for i in range(n):
                    ft[i] = (ft[i] - f0[i]) / dt
            need_jac = False
        fac = 1.0 / (h * gam)
        for i in range(n):
            for j in range(n):
                M[i, j] = -J[i, j]
            M[i, i] += fac
        ok = _lu(M, piv)
        cnt[4] += 1
        if not ok:
            cnt[1] += 1
            h *= 0.5
            rejected = True
            continue
        finite = True
        for st in range(s):
            if st == 0:
                for i in range(n):
                    fs[i] = f0[i]
            else:
                for i in range(n):
                    acc = y[i]
                    for j in range(st):
                        acc += RA[st, j] * U[j, i]
                    ytmp[i] = acc
                fun(t + RCN[st] * h, ytmp, p, fs)
                cnt[2] += 1
            for i in range(n):
                acc = fs[i] + h * RD[st] * ft[i]
                for j in range(st):
                    acc += RC[st, j] * U[j, i] / h
                if not math.isfinite(acc):
                    finite = False
                U[st, i] = acc
            if not finite:
                break
            _solve(M, piv, U[st])
        if not finite:
            cnt[1] += 1
            h *= 0.25
            rejected = True
            continue
        for i in range(n):
            a = y[i]
            e = 0.0
            for j in range(s):
                a += RM[j] * U[j, i]
                e += RE[j] * U[j, i]
            ynew[i] = a
            err[i] = e
            scale[i] = atol[i] + max(abs(y[i]), abs(a)) * rtol
        err_norm = _rms(err, scale)
        # the embedded estimate is of order 3: exponent 1/4
        h_retry = _retry_size(h, err_norm, 0.9, 0.25)
        if h_retry > 0.0:
            cnt[1] += 1
            h = h_retry
            rejected = True
            continue
        # accepted: f at the new point is the next step's first stage and the Hermite slope
        t_new = t + h
        fun(t_new, ynew, p, fnew)
        cnt[2] += 1
        cnt[0] += 1
        fin = True
        for i in range(n):
            if not math.isfinite(fnew[i]):
                fin = False
            d = ynew[i] - y[i]
            Q[0, i] = h * f0[i]
            Q[1, i] = 3.0 * d - h * (2.0 * f0[i] + fnew[i])
            Q[2, i] = h * (f0[i] + fnew[i]) - 2.0 * d
        stop = False
        if ev_idx >= 0 and _may_cross(y[ev_idx] - ev_val, Q[0, ev_idx], Q[1, ev_idx], Q[2, ev_idx]):
            stop, nev_dir = _crossings(y, Q, t, h, ev_idx, ev_val, ev_dir, ev_stop, nev_dir, cnt, EVBUF, EVDIR)
        t = t_new
        for i in range(n):
            y[i] = ynew[i]
            f0[i] = fnew[i]
        need_jac = True
        if not fin:
            status = -3
            break
        if rec_cap > 0:
            _record(cnt, rec_t, rec_y, t, y)
        if stop:
            status = 1
            break
        h, h_old, err_old = _next_size(h, h_old, err_norm, err_old, rejected, 0.9, 0.25, 6.0, max_step)
        rejected = False
        if one_step == 1:
            break
    return _finish(status, t, y, cnt, EVBUF, rec_t, rec_y, h, Q)


# --------------------------------------------------------------------------------------------
# the stepper contract of landau.verify.hybrid.steppers over a compiled kernel
class RODAS4Solver(_CompiledStepper):
    """scipy ``OdeSolver`` members over :func:`rosenbrock_core` (one accepted step per call;
    dense output: the step's cubic Hermite interpolant)."""

    method = "RODAS4"

    def _advance(self):
        from landau.verify.hybrid.fastcall import addresses, rosenbrock_at

        n = len(self.y)
        k = self.kernel
        af, aj = addresses(k.fun, k.jac)
        evbuf, evdir = np.empty((1, n + 1)), np.empty(1)
        h0 = min(self.h, self.max_step, self.t_bound - self.t)
        st, t, y, cnt, *_, h_next, Q = rosenbrock_at(
            af, aj, self.t, np.ascontiguousarray(self.y), self.t_bound, k.p, self.rtol, self.atol, h0,
            self.max_step, 500, -1, 0.0, 0, 0, 0, 0, 1, RODAS4_A, RODAS4_C, RODAS4_CNODES, RODAS4_D, RODAS4_M,
            RODAS4_E, evbuf, evdir)
        self.nfev += int(cnt[2]) - 1  # the core evaluates f at its start: already counted
        self.njev += int(cnt[3])
        self.nlu += int(cnt[4])
        self.nrejected += int(cnt[1])
        self.h = float(h_next)
        if cnt[0] == 0:
            why = STATUS[int(st)] if st < 0 else "no accepted step"
            return f"compiled RODAS4: {why} at t = {self.t:.12g}"
        self._dense = _Collocation(self.t, t - self.t, self.y.copy(), Q.copy())
        self.t_old, self.t, self.y = self.t, float(t), y.copy()
        return None


@dataclass(frozen=True)
class CompiledRODAS4(_CompiledFactory):
    """Stepper factory: compiled RODAS4 (Rosenbrock, order 4, L-stable, stiffly accurate) with
    a cubic Hermite dense output; needs the kernel's Jacobian."""

    _solver = RODAS4Solver
    _needs_jac = True
