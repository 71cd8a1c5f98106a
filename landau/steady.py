"""Steady sliding: μ_ss(V), its slope, and the extrema that bound velocity weakening.

The extrema of μ_ss (V_M, a local maximum, and V_m, a local minimum, Putelat et al.
Sec. 4.1) are where k_c = 0: they close the stick–slip domain.  They are found as the
sign changes of dμ_ss/dV on a log-spaced grid, refined with brentq in log V.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Mapping

import numpy as np
import scipy.optimize
import sympy as sp

from landau.codegen import compile_expr
from landau.errors import InputError
from landau.system import V, SpringBlock


@dataclass(frozen=True)
class Extremum:
    """A velocity where dμ_ss/dV = 0: ``kind`` is "max" (V_M) or "min" (V_m)."""

    V: float
    kind: str
    mu_ss: float

    def __repr__(self) -> str:
        return f"Extremum(V={self.V:.6g} m/s, {self.kind}, mu_ss={self.mu_ss:.6g})"


@lru_cache(maxsize=64)
def _compiled(block: SpringBlock):
    mu = block.mu_ss()
    return compile_expr(mu, block.args), compile_expr(sp.diff(mu, V), block.args)


def mu_ss(block: SpringBlock, Vs, params: Mapping[str, float] | None = None) -> np.ndarray:
    """μ_ss(V) (vectorised)."""
    f, _ = _compiled(block)
    return f(*block.argvals(np.asarray(Vs, dtype=float), block.resolve(params)))


def dmu_ss(block: SpringBlock, Vs, params: Mapping[str, float] | None = None) -> np.ndarray:
    """dμ_ss/dV (vectorised) [s/m]."""
    _, f = _compiled(block)
    return f(*block.argvals(np.asarray(Vs, dtype=float), block.resolve(params)))


def extrema(block: SpringBlock, params: Mapping[str, float] | None = None,
            lo: float = 1e-12, hi: float = 1e2, n: int = 2000) -> list[Extremum]:
    """Every extremum of μ_ss in [lo, hi] m/s, refined to ~1e-14 relative in V."""
    p = block.resolve(params)
    _, fd = _compiled(block)
    fmu, _ = _compiled(block)
    grid = np.logspace(np.log10(lo), np.log10(hi), n)
    d = fd(*block.argvals(grid, p))
    out = []
    for i in np.nonzero(np.sign(d[:-1]) * np.sign(d[1:]) < 0)[0]:
        g = lambda s: float(fd(*block.argvals(np.exp(s), p)))
        s = scipy.optimize.brentq(g, np.log(grid[i]), np.log(grid[i + 1]), xtol=1e-15, rtol=1e-15)
        Ve = float(np.exp(s))
        out.append(Extremum(Ve, "max" if d[i] > 0 else "min", float(fmu(*block.argvals(Ve, p)))))
    return out


def velocity_weakening_range(block: SpringBlock, params: Mapping[str, float] | None = None,
                             lo: float = 1e-12, hi: float = 1e2) -> tuple[float, float]:
    """The (first) interval of [lo, hi] where dμ_ss/dV < 0; its ends are extrema or the search bounds.

    Raises :class:`InputError` when the law has no velocity-weakening branch there.
    """
    p = block.resolve(params)
    ex = extrema(block, p, lo, hi)
    d_lo = float(dmu_ss(block, lo, p))
    edges = [lo] + [e.V for e in ex] + [hi]
    signs = [d_lo] + [(-1.0 if e.kind == "max" else 1.0) for e in ex]
    for (a, b), s in zip(zip(edges[:-1], edges[1:]), signs):
        if s < 0:
            return a, b
    raise InputError(f"law {block.law.name!r} has no velocity-weakening branch in [{lo:g}, {hi:g}] m/s "
                     "(no Hopf bifurcation of steady sliding there)")
