"""The compiled DOPRI5 stepper over any compiled kernel, and the tableaux the compiled loops share.

A method here is a *factory over a kernel*: nothing here knows a model.  The field comes in
as a :class:`~landau.verify.hybrid.kernel.Kernel` (numba ``fun(t, y, p, out)``), generated from
a model's symbolic declaration by :mod:`landau.codegen.kernels` or written by hand in numba.

* :func:`dopri5_method` builds, once per kernel function, the jitted Dormand–Prince 5(4)
  step (7 stages, FSAL, embedded 4th-order estimate; Dormand & Prince 1980; Hairer,
  Nørsett & Wanner, *Solving ODEs I*, II.5) with the kernel inlined — the building block of
  the fast event-driven loops (e.g. :mod:`landau.verify.skurativskyi.rk`) and of
  :class:`CompiledDOPRI5`, a stepper factory with the contract of
  :mod:`landau.verify.hybrid.steppers` (cubic Hermite dense output).
* The SDIRK4 tableau of Hairer & Wanner (*Solving ODEs II*, IV.6, eq. (6.16), γ = 1/4), used by
  the forced oscillator's stiff loop.

The stepper on the user path of the stick–slip models is the compiled DOP853 of
:mod:`landau.verify.hybrid.dop853`.  ``_CompiledStepper``/``_CompiledFactory`` are the
members shared with the compiled Rosenbrock stepper.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
from numba import njit

from landau.errors import InputError
from landau.verify.hybrid.kernel import Kernel
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
    ``step``, ``stages``, ``advance`` and ``advance_into``."""
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


@dataclass(frozen=True)
class _CompiledFactory:
    rtol: float = 1e-8
    atol: float | tuple = 1e-10
    first_step: float | None = None
    max_step: float = np.inf

    _solver: ClassVar[Any] = None   # the compiled solver class of a concrete factory
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
    """Stepper factory: compiled DOPRI5 (explicit, order 5) with a cubic Hermite dense output."""

    _solver = DOPRI5Solver
