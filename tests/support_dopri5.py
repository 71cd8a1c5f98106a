"""The test oracle DOPRI5: a compiled Dormand–Prince 5(4) stepper over any compiled kernel.

Dormand & Prince (1980); Hairer, Nørsett & Wanner, *Solving ODEs I*, II.5: 7 stages, FSAL,
embedded 4th-order error estimate, Hairer's RMS error norm.  It is on no user path of the
toolkit (the stick–slip models run on the compiled DOP853 of
:mod:`landau.verify.hybrid.dop853`) and lives here as an independent reference:

* :func:`dopri5_method` — the jitted step with the kernel inlined.  The published bifurcation
  values of Skurativskyi et al. (2019) were computed with this step; the forced oscillator's
  switching loop (:mod:`landau.verify.skurativskyi.rk`) must reproduce it to the bit, so its
  arithmetic is kept exactly as it was in the package;
* :class:`CompiledDOPRI5` — a stepper factory with the contract of
  :mod:`landau.verify.hybrid.steppers` (cubic Hermite dense output), checked against scipy's
  ``RK45`` and driven by the hybrid engine in the tests;
* :func:`specialise` — binds a compiled-method template's free names (``fun``, …) to one kernel
  and runs it through the code cache of :mod:`landau.verify.jitcache`, so numba inlines the
  kernel and keeps the machine code on disk (a closure over a dispatcher would be recompiled
  in every process: numba keys its cache on the captured values).
"""

from __future__ import annotations

import hashlib
import importlib
import math
import sys
from dataclasses import dataclass
from functools import lru_cache
from types import ModuleType
from typing import ClassVar, Mapping

import numba
import numpy as np
from numba import njit

from landau.errors import InputError
from landau.verify.hybrid.kernel import Kernel
from landau.verify.jitcache import exec_cached

# Dormand–Prince 5(4) tableau
C2, C3, C4, C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
B1, B3, B4, B5, B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
E1, E3, E4, E5, E6, E7 = 71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40


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


#: the DOPRI5 step as a template: free names ``fun(t, y, p, out)`` (the kernel) and ``jit``
DOPRI5_TEMPLATE = '''
import numpy as np

from support_dopri5 import (A21, A31, A32, A41, A42, A43, A51, A52, A53, A54, A61, A62, A63, A64,
                            A65, B1, B3, B4, B5, B6, C2, C3, C4, C5, E1, E3, E4, E5, E6, E7,
                            err_norm)


@jit
def step(p, t, y, k1, h, ynew, k7, err):
    stages(p, t, y, k1, h, ynew, k7, err, np.empty((5, y.shape[0])))


@jit
def stages(p, t, y, k1, h, ynew, k7, err, K):
    """``step`` keeping the stages k2..k6 in the rows of K (for the dense output)."""
    n = y.shape[0]
    yt = np.empty(n)
    k2, k3, k4, k5, k6 = K[0], K[1], K[2], K[3], K[4]
    for a in range(n):
        yt[a] = y[a] + h * A21 * k1[a]
    fun(t + C2 * h, yt, p, k2)
    for a in range(n):
        yt[a] = y[a] + h * (A31 * k1[a] + A32 * k2[a])
    fun(t + C3 * h, yt, p, k3)
    for a in range(n):
        yt[a] = y[a] + h * (A41 * k1[a] + A42 * k2[a] + A43 * k3[a])
    fun(t + C4 * h, yt, p, k4)
    for a in range(n):
        yt[a] = y[a] + h * (A51 * k1[a] + A52 * k2[a] + A53 * k3[a] + A54 * k4[a])
    fun(t + C5 * h, yt, p, k5)
    for a in range(n):
        yt[a] = y[a] + h * (A61 * k1[a] + A62 * k2[a] + A63 * k3[a] + A64 * k4[a] + A65 * k5[a])
    fun(t + h, yt, p, k6)
    for a in range(n):
        ynew[a] = y[a] + h * (B1 * k1[a] + B3 * k3[a] + B4 * k4[a] + B5 * k5[a] + B6 * k6[a])
    fun(t + h, ynew, p, k7)
    for a in range(n):
        err[a] = h * (E1 * k1[a] + E3 * k3[a] + E4 * k4[a] + E5 * k5[a] + E6 * k6[a] + E7 * k7[a])


@jit
def advance(p, t, y, k1, h, hmax, t_bound, rtol, atol):
    n = y.shape[0]
    ynew = np.empty(n)
    k7 = np.empty(n)
    ok, tn, h, hn, nfev = advance_into(p, t, y, k1, h, hmax, t_bound, rtol, atol, ynew, k7, np.empty(n),
                                       np.empty((5, n)))
    if ok:
        return True, tn, ynew, k7, h, hn, nfev
    return False, t, y.copy(), k1.copy(), h, h, nfev


@jit
def advance_into(p, t, y, k1, h, hmax, t_bound, rtol, atol, ynew, k7, err, K):
    """One accepted step with error control into the buffers ynew, k7 (f there) and K (the
    stages k2..k6); returns (ok, t_new, h_used, h_next, nfev)."""
    nfev = 0
    for _ in range(500):
        h = min(h, hmax, t_bound - t)
        if h <= 1e-15 * max(1.0, abs(t)):
            break
        stages(p, t, y, k1, h, ynew, k7, err, K)
        nfev += 6
        en = err_norm(err, y, ynew, rtol, atol)
        if en <= 1.0:
            fac = 10.0 if en == 0 else min(10.0, 0.9 * en ** -0.2)
            tn = t + h if t + h < t_bound else t_bound
            return True, tn, h, h * fac, nfev
        h *= 0.2 if en != en else max(0.2, 0.9 * en ** -0.2)
    return False, t, h, h, nfev
'''

_LOADED: dict[tuple, ModuleType] = {}


def _import_line(name: str, value) -> str | None:
    """``from M import A as name`` if ``value`` is importable as M.A, ``name = repr`` for a number."""
    if isinstance(value, (bool, int, float)) and not isinstance(value, bool):
        return f"{name} = {value!r}"
    py = getattr(value, "py_func", value)
    mod, attr = getattr(py, "__module__", None), getattr(py, "__name__", None)
    if not mod or not attr or "<" in attr:
        return None
    module = sys.modules.get(mod)
    if module is None:
        try:
            module = importlib.import_module(mod)
        except ImportError:
            return None
    if getattr(module, attr, None) is not value:
        return None
    return f"from {mod} import {attr} as {name}"


def specialise(template: str, bindings: Mapping[str, object], tag: str) -> ModuleType:
    """A template (Python source whose jitted functions call free names and are decorated with
    ``@jit``) with its free names bound to ``bindings`` (name → numba function or number).

    When every binding is importable (a module-level kernel, hand-written or generated), the
    source with an import header goes through :func:`landau.verify.jitcache.exec_cached`
    (``@jit`` = ``njit(cache=True)``: machine code kept on disk); otherwise it is bound in memory
    (``@jit`` = ``njit``, compiled once per process).  One module per distinct template and
    bindings in a process.
    """
    key = (hashlib.sha256(template.encode()).hexdigest(),
           tuple((k, id(v) if not isinstance(v, (int, float)) else v) for k, v in sorted(bindings.items())))
    if key in _LOADED:
        return _LOADED[key]
    lines = {k: _import_line(k, v) for k, v in bindings.items()}
    module = None
    present = [v for v in lines.values() if v is not None]
    if len(present) == len(lines):
        header = [f"# generated by the tests' support_dopri5.specialise ({tag})",
                  "import numba as _numba", "jit = _numba.njit(cache=True)", *present, ""]
        try:
            module = exec_cached("\n".join(header) + "\n" + template, f"jit_{tag}")
        except RuntimeError:  # numba found no place for its cache (the source runs from memory)
            module = None
    if module is None:  # in memory: bind the objects directly, compile once per process
        modname = f"landau_jit_{tag}_{len(_LOADED)}"
        module = ModuleType(modname)
        module.__dict__.update(bindings)
        module.__dict__["jit"] = numba.njit
        sys.modules[modname] = module
        exec(compile(template, f"<template {tag}>", "exec"), module.__dict__)
    _LOADED[key] = module
    return module


@lru_cache(maxsize=None)
def dopri5_module(fun):
    """:data:`DOPRI5_TEMPLATE` specialised to the kernel function ``fun``: ``step``, ``stages``,
    ``advance`` and ``advance_into``."""
    return specialise(DOPRI5_TEMPLATE, {"fun": fun}, "dopri5")


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


class DOPRI5Solver:
    """scipy ``OdeSolver`` members over :func:`dopri5_method` (the engine's stepper contract);
    ``f`` is the field at ``(t, y)`` after every step (FSAL)."""

    method = "DOPRI5"
    #: the hybrid engine may screen each step on its Hermite interpolant (f is kept current)
    keeps_f = True

    def __init__(self, kernel: Kernel, t0, y0, t_bound, rtol, atol, first_step, max_step):
        self.kernel = kernel
        self.t = self.t_old = float(t0)
        self.y = np.array(y0, dtype=float)
        self.t_bound = float(t_bound)
        self.status = "running" if t_bound > t0 else "finished"
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

    def dense_output(self):
        """Interpolant on [t_old, t] (scalar t → (n,), array → (n, m))."""
        return self._dense


@dataclass(frozen=True)
class CompiledDOPRI5:
    """Stepper factory: the compiled DOPRI5 (explicit, order 5) over a compiled
    :class:`~landau.verify.hybrid.kernel.Kernel`, with a cubic Hermite dense output."""

    rtol: float = 1e-8
    atol: float | tuple = 1e-10
    first_step: float | None = None
    max_step: float = np.inf

    #: the hybrid engine hands this factory a mode's compiled kernel
    takes_kernel: ClassVar[bool] = True

    def __call__(self, fun, t0, y0, t_bound, jac=None):
        if not isinstance(fun, Kernel):
            raise InputError("the compiled DOPRI5 stepper integrates a compiled Kernel (numba fun(t, y, p, out)); "
                             f"got {type(fun).__name__} — generate one with landau.codegen.kernels.generate_kernel")
        if not (0 < self.rtol < 1):
            raise InputError(f"rtol must be in (0, 1), got {self.rtol!r}")
        return DOPRI5Solver(fun, t0, y0, t_bound, self.rtol, self.atol, self.first_step, self.max_step)
