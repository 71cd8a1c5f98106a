"""Velocity-weakening ranges of the built-in laws (helper for the engine tests and benchmark).

The Hopf line of a one-state spring–block exists where μ_ss'(V) < 0 (Putelat et al.
2010, eq. 8: ω_c² = −G_φ² F'_ss/F_V).  The ends V_M < V_m of the range are the zeros of
μ_ss'(V), found here with mpmath (50 digits) from brackets on a log grid.  Laws that are
velocity weakening for every V (Dieterich, Ruina, two-state) get a fixed window.
"""

from __future__ import annotations

from functools import lru_cache

import mpmath
import numpy as np
import sympy as sp

from landau.laws import get_law
from landau.systems.system import SpringBlock, V

#: window used when the law is velocity weakening on all of (0, ∞) [m/s]
OPEN_WINDOW = (1e-8, 1e-1)
LAWS = ("dieterich", "ruina", "spinodal", "modified-dieterich", "nanoscale", "micron-scale")


@lru_cache(maxsize=None)
def vw_range(name: str) -> tuple[float, float, tuple[float, ...]]:
    """(V_lo, V_hi, exact ends) of the velocity-weakening range of law ``name`` (defaults).

    The third item lists the ends that are true zeros of μ_ss' (where k_c, Γ, Λ → 0).
    """
    block = SpringBlock(get_law(name))
    p = block.resolve()
    dmu = sp.diff(block.mu_ss(), V)
    syms = sorted(dmu.free_symbols - {V}, key=lambda s: s.name)
    f = sp.lambdify([V, *syms], dmu, modules="mpmath")
    vals = [p[s.name] for s in syms]
    grid = np.logspace(-12, 2, 1401)
    with mpmath.workdps(50):
        sgn = [mpmath.sign(f(mpmath.mpf(x), *vals)) for x in grid]
        ends = []
        for i in range(len(grid) - 1):
            if sgn[i] != sgn[i + 1]:
                root = mpmath.findroot(lambda x: f(x, *vals), (mpmath.mpf(grid[i]), mpmath.mpf(grid[i + 1])),
                                       solver="anderson")
                ends.append(float(root))
        weak = [s < 0 for s in sgn]
    lo = OPEN_WINDOW[0] if weak[0] else None
    hi = OPEN_WINDOW[1] if weak[-1] else None
    if lo is None:
        lo = ends[0]
    if hi is None:
        hi = ends[-1]
    return lo, hi, tuple(ends)
