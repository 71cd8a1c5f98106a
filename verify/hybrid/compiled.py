"""Compiled steppers: DOPRI5, Radau IIA 5 and SDIRK4 over any compiled kernel.

Each method is a *factory over a kernel*: nothing here knows a model.  The field comes in
as a :class:`~landau.verify.hybrid.kernel.Kernel` (numba ``fun(t, y, p, out)`` and, for the
implicit methods, ``jac(t, y, p, out)``), generated from a model's symbolic declaration by
:mod:`landau.codegen.kernels` or written by hand in numba.

* :func:`dopri5_method` builds, once per kernel function, the jitted Dormand–Prince 5(4)
  step (7 stages, FSAL, embedded 4th-order estimate; Dormand & Prince 1980; Hairer,
  Nørsett & Wanner, *Solving ODEs I*, II.5) with the kernel inlined — the building block of
  the fast event-driven loops (e.g. :mod:`landau.verify.skurativskyi.rk`) and of
  :class:`CompiledDOPRI5`.
* :class:`CompiledRadau5` steps the compiled Radau IIA of :mod:`landau.verify.hybrid.radau`
  (kernels passed as first-class functions).
* :func:`sdirk4_method` / :class:`CompiledSDIRK4`: the 5-stage, order-4, stiffly accurate,
  L-stable SDIRK of Hairer & Wanner (*Solving ODEs II*, IV.6, eq. (6.16), γ = 1/4) with its
  embedded order-3 solution, stages by simplified Newton with one LU of I − hγJ per step and
  the error estimate filtered by (I − hγJ)⁻¹ (Shampine).

The three stepper factories (:class:`CompiledDOPRI5`, :class:`CompiledRadau5`,
:class:`CompiledSDIRK4`) have the contract of :mod:`landau.verify.hybrid.steppers`
(``factory(fun, t0, y0, t_bound, jac) -> stepper`` with scipy ``OdeSolver``'s members), so
the hybrid engine drives them like any scipy solver; ``fun`` must be a ``Kernel``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
from numba import njit

from landau.errors import InputError
from landau.verify.hybrid.kernel import Kernel
from landau.verify.hybrid.radau import A_RADAU, VINV, pointers, radau_core
from landau.verify.hybrid.specialise import specialise

_TEMPLATES = Path(__file__).parent / "templates"

# Dormand–Prince 5(4) tableau
C2, C3, C4, C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
B1, B3, B4, B5, B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
E1, E3, E4, E5, E6, E7 = 71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40
#: its continuous extension of order 4 (Hairer, Nørsett & Wanner, Solving ODEs I, II.6; CONTD5)
D1, D3, D4 = -12715105075 / 11282082432, 87487479700 / 32700410799, -10690763975 / 1880347072
D5, D6, D7 = 701980252875 / 199316789632, -1453857185 / 822651844, 69997945 / 29380423

#: Hairer–Wanner SDIRK4 (6.16): lower-triangular A (diagonal γ), c, embedded weights b̂
SDIRK_GAMMA = 0.25
SDIRK_A = ((0.25, 0.0, 0.0, 0.0, 0.0),
           (0.5, 0.25, 0.0, 0.0, 0.0),
           (17 / 50, -1 / 25, 0.25, 0.0, 0.0),
           (371 / 1360, -137 / 2720, 15 / 544, 0.25, 0.0),
           (25 / 24, -49 / 48, 125 / 16, -85 / 12, 0.25))
SDIRK_C = (0.25, 0.75, 11 / 20, 0.5, 1.0)
SDIRK_BHAT = (59 / 48, -17 / 96, 225 / 32, -85 / 12, 0.0)
#: b − b̂ (b = last row of A: the method is stiffly accurate)
SDIRK_E = tuple(SDIRK_A[4][i] - SDIRK_BHAT[i] for i in range(5))


@njit(cache=True)
def err_norm(err, y, ynew, rtol, atol):
    """RMS of err / (atol + rtol·max(|y|, |ynew|)) (Hairer's norm)."""
    s = 0.0
    n = err.shape[0]
    for a in range(n):
        sc = atol[a] + rtol * max(abs(y[a]), abs(ynew[a]))
        q = err[a] / sc
        s += q * q
    return math.sqrt(s / n)


@lru_cache(maxsize=None)
def dopri5_module(fun):
    """The DOPRI5 template (``templates/dopri5.py``) specialised to the kernel function ``fun``:
    ``step``, ``advance``, ``advance_into``, ``dense_coefficients`` and ``run_quiet``."""
    return specialise(_TEMPLATES / "dopri5.py", {"fun": fun}, "dopri5")


@lru_cache(maxsize=None)
def dopri5_method(fun):
    """The jitted DOPRI5 step for the kernel function ``fun(t, y, p, out)``.

    Returns
    -------
    (step, advance)
        ``step(p, t, y, k1, h, ynew, k7, err)``: one step from (t, y) with k1 = f(t, y);
        fills ynew, k7 = f(t + h, ynew) and the error estimate err.
        ``advance(p, t, y, k1, h, hmax, t_bound, rtol, atol)``: one *accepted* step with
        error control; returns (ok, t_new, y_new, k7, h_used, h_next, nfev).
    """

    mod = dopri5_module(fun)
    return mod.step, mod.advance


@lru_cache(maxsize=None)
def sdirk4_method(fun, jac):
    """The jitted SDIRK4 step for the kernel ``fun``/``jac`` (module docstring).

    Returns
    -------
    attempt
        ``attempt(p, t, y, f0, h, rtol, atol, ynew, fnew, err) -> (status, nfev)``: one step
        of length h; status 0 = stages converged (``err`` holds the filtered estimate),
        1 = Newton failed (retry with a smaller h), 2 = singular iteration matrix.
    """
    return specialise(_TEMPLATES / "sdirk4.py", {"fun": fun, "jac": jac}, "sdirk4").attempt


class _Hermite:
    """Cubic Hermite interpolant on one step (values and slopes at both ends)."""

    def __init__(self, t0, t1, y0, y1, f0, f1):
        self.t0, self.h = t0, t1 - t0
        self.y0, self.y1, self.f0, self.f1 = y0, y1, f0, f1

    def __call__(self, t):
        s = (np.asarray(t, float) - self.t0) / self.h
        h00 = (1 + 2 * s) * (1 - s) ** 2
        h10 = s * (1 - s) ** 2
        h01 = s * s * (3 - 2 * s)
        h11 = s * s * (s - 1)
        if s.ndim == 0:
            return h00 * self.y0 + h10 * self.h * self.f0 + h01 * self.y1 + h11 * self.h * self.f1
        c = lambda v: v[:, None]
        return (h00 * c(self.y0) + h10 * self.h * c(self.f0) + h01 * c(self.y1) + h11 * self.h * c(self.f1))


class _Contd5:
    """DOPRI5's order-4 continuous extension on one step, from the coefficient rows rc (5, n)
    of ``dense_coefficients``: y(t₀ + θh) = rc₀ + θ(rc₁ + (1−θ)(rc₂ + θ(rc₃ + (1−θ)rc₄)))."""

    __slots__ = ("t0", "h", "rc")

    def __init__(self, t0, h, rc):
        self.t0, self.h, self.rc = float(t0), float(h), rc

    def __call__(self, t):
        if isinstance(t, float):
            return _contd5_point(self.rc, (t - self.t0) / self.h)
        x = (np.asarray(t, float) - self.t0) / self.h
        if x.ndim == 0:
            return _contd5_point(self.rc, float(x))
        return _contd5_points(self.rc, np.ascontiguousarray(x))


@njit(cache=True)
def _contd5_point(rc, x):
    n = rc.shape[1]
    out = np.empty(n)
    x1 = 1.0 - x
    for a in range(n):
        out[a] = rc[0, a] + x * (rc[1, a] + x1 * (rc[2, a] + x * (rc[3, a] + x1 * rc[4, a])))
    return out


@njit(cache=True)
def _contd5_points(rc, xs):
    n, m = rc.shape[1], xs.shape[0]
    out = np.empty((n, m))
    for k in range(m):
        x = xs[k]
        x1 = 1.0 - x
        for a in range(n):
            out[a, k] = rc[0, a] + x * (rc[1, a] + x1 * (rc[2, a] + x * (rc[3, a] + x1 * rc[4, a])))
    return out


class _Collocation:
    """Radau IIA dense output y(t₀ + x h) = y₀ + Σ_j Q_j x^j (x ∈ [0, 1])."""

    def __init__(self, t0, h, y0, Q):
        self.t0, self.h, self.y0, self.Q = t0, h, y0, Q

    def __call__(self, t):
        x = (np.asarray(t, float) - self.t0) / self.h
        Q = self.Q
        if x.ndim == 0:
            return self.y0 + x * (Q[0] + x * (Q[1] + x * Q[2]))
        xx = x[None, :]
        return self.y0[:, None] + xx * (Q[0][:, None] + xx * (Q[1][:, None] + xx * Q[2][:, None]))


def _as_kernel(fun, method: str, need_jac: bool) -> Kernel:
    if not isinstance(fun, Kernel):
        raise InputError(f"the compiled {method} stepper integrates a compiled Kernel (numba fun(t, y, p, out)); "
                         f"got {type(fun).__name__} — generate one with landau.codegen.kernels.generate_kernel")
    if need_jac and fun.jac is None:
        raise InputError(f"the compiled {method} stepper needs the kernel's Jacobian (kernel {fun.name!r} has none)")
    return fun


class _CompiledStepper:
    """scipy ``OdeSolver`` members over a compiled single-step routine (subclasses: ``_advance``)."""

    method = "?"

    def __init__(self, kernel: Kernel, t0, y0, t_bound, rtol, atol, first_step, max_step):
        self.kernel = kernel
        self.t = self.t_old = float(t0)
        self.y = np.array(y0, dtype=float)
        self.t_bound = float(t_bound)
        if not t_bound > t0:
            self.status = "finished"
        else:
            self.status = "running"
        self.rtol = float(rtol)
        self.atol = np.array(np.broadcast_to(np.asarray(atol, float), self.y.shape), dtype=float)
        self.max_step = float(max_step)
        span = abs(self.t_bound - self.t)
        self.h = float(first_step) if first_step else min(1e-3 * span, 1e-2) if span > 0 else 1.0
        self.f = kernel(self.t, self.y)
        self.nfev = 1
        self.njev = 0
        self.nlu = 0
        self.nrejected = 0
        self.nsteps = 0
        self._dense = None

    def step(self):
        """Advance one accepted step; ``None`` or an error message (scipy's contract)."""
        if self.status != "running":
            raise RuntimeError("attempt to step on a finished or failed solver")
        msg = self._advance()
        if msg is not None:
            self.status = "failed"
            return msg
        self.nsteps += 1
        if self.t >= self.t_bound:
            self.status = "finished"
        return None

    def dense_output(self):
        """Interpolant on [t_old, t] (scalar t → (n,), array → (n, m))."""
        return self._dense

    def __repr__(self) -> str:
        return (f"{type(self).__name__}(t={self.t:.6g}, {self.status}, steps={self.nsteps}, "
                f"nfev={self.nfev}, kernel={self.kernel!r})")


class DOPRI5Solver(_CompiledStepper):
    method = "DOPRI5"

    def _advance(self):
        _, advance = dopri5_method(self.kernel.fun)
        ok, tn, yn, k7, h, hn, nf = advance(self.kernel.p, self.t, self.y, self.f, self.h, self.max_step,
                                            self.t_bound, self.rtol, self.atol)
        self.nfev += nf
        if not ok:
            return f"compiled DOPRI5: step size underflow at t = {self.t:.12g}"
        self._dense = _Hermite(self.t, tn, self.y.copy(), np.array(yn), self.f.copy(), np.array(k7))
        self.t_old, self.t, self.y, self.f = self.t, tn, np.array(yn), np.array(k7)
        self.h = hn
        return None


class DOPRI5Order4Solver(DOPRI5Solver):
    """DOPRI5 with its order-4 continuous extension as dense output (no extra stages), and
    :meth:`run_quiet`: many steps in one compiled call while affine guards stay clear."""

    method = "DOPRI5"

    def __init__(self, *args):
        super().__init__(*args)
        n = len(self.y)
        self._buf = (np.empty(n), np.empty(n), np.empty(n), np.empty((5, n)))
        self._mod = dopri5_module(self.kernel.fun)

    def _advance(self):
        ynew, k7, err, K = self._buf
        ok, tn, h, hn, nf = self._mod.advance_into(self.kernel.p, self.t, self.y, self.f, self.h, self.max_step,
                                                    self.t_bound, self.rtol, self.atol, ynew, k7, err, K)
        self.nfev += nf
        if not ok:
            return f"compiled DOPRI5: step size underflow at t = {self.t:.12g}"
        rc = np.empty((5, len(self.y)))
        self._mod.dense_coefficients(self.y, ynew, self.f, k7, K, h, rc)
        self._dense = _Contd5(self.t, h, rc)
        self.t_old, self.t, self.y, self.f = self.t, tn, ynew.copy(), k7.copy()
        self.h = hn
        return None

    def run_quiet(self, W, b, s, g_last, dec_before, state, guard_atol, dip_factor, max_steps=100_000):
        """Steps until one whose affine guards g = W·y + b need the engine's dense-output scan.

        Each step's guards are tested on the dense output at the step fractions ``s`` and at
        the step end with the engine's scan test
        (:func:`landau.verify.hybrid.locate._quiet_guards`, which advances ``g_last``,
        ``dec_before`` and ``state`` in place past every quiet step).

        Returns
        -------
        (str or None, bool, int)
            The error message (None on success), whether the run reached ``t_bound`` with
            every step quiet, and the number of steps taken.  Otherwise the last step taken
            (``t_old`` → ``t``, its ``dense_output()``) is the one to scan.
        """
        if self.status != "running":
            raise RuntimeError("attempt to step on a finished or failed solver")
        rc = np.empty((5, len(self.y)))
        code, k = 3, 0
        while code == 3:  # max_steps quiet steps: carry on
            code, t_old, t, hu, hn, nf, kk = self._mod.run_quiet(
                self.kernel.p, self.t, self.y, self.f, self.h, self.max_step, self.t_bound, self.rtol, self.atol,
                max_steps, W, b, s, g_last, dec_before, state, guard_atol, dip_factor, rc)
            self.nfev += nf
            self.nsteps += kk
            k += kk
            self.t, self.h = t, hn
            if kk:
                self._dense = _Contd5(t_old, hu, rc)
                self.t_old = t_old
        if code == 0:
            self.status = "failed"
            return f"compiled DOPRI5: step size underflow at t = {self.t:.12g}", False, k
        if self.t >= self.t_bound:
            self.status = "finished"
        return None, code == 2, k


class SDIRK4Solver(_CompiledStepper):
    method = "SDIRK4"

    def _advance(self):
        attempt = sdirk4_method(self.kernel.fun, self.kernel.jac)
        n = len(self.y)
        ynew, fnew, err = np.empty(n), np.empty(n), np.empty(n)
        for _ in range(500):
            h = min(self.h, self.max_step, self.t_bound - self.t)
            if h <= 1e-15 * max(1.0, abs(self.t)):
                break
            st, nf = attempt(self.kernel.p, self.t, self.y, self.f, h, self.rtol, self.atol, ynew, fnew, err)
            self.nfev += nf
            self.njev += 1
            self.nlu += 1
            if st != 0:
                self.nrejected += 1
                self.h = 0.5 * h
                continue
            en = err_norm(err, self.y, ynew, self.rtol, self.atol)
            if not en <= 1.0:
                self.nrejected += 1
                self.h = h * (0.2 if en != en else max(0.2, 0.9 * en ** -0.25))
                continue
            tn = self.t + h if self.t + h < self.t_bound else self.t_bound
            self._dense = _Hermite(self.t, tn, self.y.copy(), ynew.copy(), self.f.copy(), fnew.copy())
            self.t_old, self.t, self.y, self.f = self.t, tn, ynew.copy(), fnew.copy()
            self.h = h * (10.0 if en == 0 else min(10.0, 0.9 * en ** -0.25))
            return None
        return f"compiled SDIRK4: step size underflow at t = {self.t:.12g}"


class Radau5Solver(_CompiledStepper):
    method = "Radau5"

    def _advance(self):
        n = len(self.y)
        evbuf = np.empty((1, n + 1))
        evdir = np.empty(1)
        k = self.kernel
        fun, jac = pointers(k.fun, k.jac)
        for _ in range(500):
            h0 = min(self.h, self.max_step, self.t_bound - self.t)
            st, t, y, cnt, *_, h_next, Q = radau_core(
                fun, jac, self.t, np.ascontiguousarray(self.y), self.t_bound, k.p, self.rtol, self.atol,
                h0, self.max_step, 1, -1, 0.0, 0, 0, 0, A_RADAU, VINV, evbuf, evdir)
            self.nfev += int(cnt[2]) - 1  # radau_core evaluates f at its start: already counted
            self.njev += int(cnt[3])
            self.nlu += int(cnt[4])
            self.nrejected += int(cnt[1])
            self.h = float(h_next)
            if cnt[0] == 0 and cnt[5] > 0:
                # the Newton iteration failed: the one-step call cannot carry radau_core's retry
                # with stage Jacobians over to the next call, so halve the step here
                self.h = 0.5 * h0
            if st == -3 or (st == -1 and cnt[0] == 0):
                return f"compiled Radau IIA: {'non-finite state' if st == -3 else 'step size too small'} " \
                       f"at t = {self.t:.12g}"
            if cnt[0] == 1:
                self._dense = _Collocation(self.t, t - self.t, self.y.copy(), Q.copy())
                self.t_old, self.t, self.y = self.t, float(t), y.copy()
                return None
        return f"compiled Radau IIA: no accepted step in 500 attempts at t = {self.t:.12g}"


@dataclass(frozen=True)
class _CompiledFactory:
    rtol: float = 1e-8
    atol: float | tuple = 1e-10
    first_step: float | None = None
    max_step: float = np.inf

    _solver = None
    _needs_jac = False

    def __call__(self, fun, t0, y0, t_bound, jac=None):
        k = _as_kernel(fun, self._solver.method, self._needs_jac)
        if not (0 < self.rtol < 1):
            raise InputError(f"rtol must be in (0, 1), got {self.rtol!r}")
        return self._solver_class()(k, t0, y0, t_bound, self.rtol, self.atol, self.first_step, self.max_step)

    def _solver_class(self):
        return self._solver


@dataclass(frozen=True)
class CompiledDOPRI5(_CompiledFactory):
    """Stepper factory: compiled DOPRI5 (explicit, order 5) with a cubic Hermite dense output
    (``dense="hermite"``) or its order-4 continuous extension (``dense="order4"``: free, and
    accurate to the step's own error, so located event times are too; the hybrid engine then
    runs quiet steps of modes with affine guards in one compiled call)."""

    dense: str = "hermite"

    _solver = DOPRI5Solver

    def _solver_class(self):
        if self.dense not in ("hermite", "order4"):
            raise InputError(f"CompiledDOPRI5: dense must be 'hermite' or 'order4', not {self.dense!r}")
        return DOPRI5Order4Solver if self.dense == "order4" else DOPRI5Solver


@dataclass(frozen=True)
class CompiledRadau5(_CompiledFactory):
    """Stepper factory: compiled Radau IIA (implicit, order 5, L-stable) with its collocation
    polynomial as dense output; needs the kernel's Jacobian."""

    _solver = Radau5Solver
    _needs_jac = True


@dataclass(frozen=True)
class CompiledSDIRK4(_CompiledFactory):
    """Stepper factory: compiled SDIRK4 (implicit, order 4, L-stable) with a cubic Hermite
    dense output; needs the kernel's Jacobian."""

    _solver = SDIRK4Solver
    _needs_jac = True
