"""A compiled vector field: what every compiled stepper integrates.

A :class:`Kernel` holds numba-compiled functions ``fun(t, y, p, out)`` (out = f(t, y; p))
and optionally ``jac(t, y, p, out)`` (out = ∂f/∂y), with the packed parameter vector ``p``.
Kernels are generated from a model's symbolic declaration by :mod:`landau.codegen.kernels` (or
written by hand in numba); the simulation layer only calls them.  A kernel is also callable
like a Python right-hand side, ``kernel(t, y) -> f`` (the hybrid engine evaluates it at
phase starts and the scipy steppers can use it directly).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np


@dataclass(frozen=True)
class Kernel:
    """A compiled field f(t, y; p) with optional Jacobian.

    Attributes
    ----------
    fun : numba dispatcher
        ``fun(t, y, p, out)``.
    p : ndarray
        The parameter vector passed as ``p``.
    jac : numba dispatcher or None
        ``jac(t, y, p, out)`` with ``out`` of shape (n, n).
    name : str
        A label (repr and error messages).
    n : int or None
        Dimension of the state, when known.
    source : str
        The generated source (empty for hand-written kernels).
    """

    fun: Callable[..., None]
    p: np.ndarray
    jac: Callable[..., None] | None = None
    name: str = ""
    n: int | None = None
    source: str = field(default="", repr=False)

    def __call__(self, t, y) -> np.ndarray:
        y = np.ascontiguousarray(y, dtype=float)
        out = np.empty(len(y))
        self.fun(float(t), y, self.p, out)
        return out

    def jacobian(self, t, y) -> np.ndarray:
        """∂f/∂y at (t, y) (a dense (n, n) array)."""
        if self.jac is None:
            raise TypeError(f"kernel {self.name!r} has no Jacobian")
        y = np.ascontiguousarray(y, dtype=float)
        out = np.empty((len(y), len(y)))
        self.jac(float(t), y, self.p, out)
        return out

    def __repr__(self) -> str:
        j = ", jac" if self.jac is not None else ""
        n = f", n={self.n}" if self.n is not None else ""
        return f"Kernel({self.name or getattr(self.fun, '__name__', '?')}{n}{j})"
