"""Event location on a step's dense output.

Per step the engine samples every guard at a few interior points of the dense output
(vectorised).  A guard is *crossed* inside the step when a sample is <= 0; the root is
then found by a bracketing solver (Brent) on ``g(t, dense(t))`` and moved, if needed,
onto the new side (``g <= 0``).  A guard that dips below zero and comes back inside one
step (a double crossing) leaves all samples positive: it is caught by tracking discrete
local minima of the samples.  For a locally quadratic guard the true minimum can lie
below the sampled one by at most the rise to the higher neighbour, so every sampled
minimum closer to zero than (twice) that rise is refined by a bounded minimisation on the
dense output, and a negative minimum gives the bracket [left sample, argmin].
"""

from __future__ import annotations

import numpy as np


def guard_on_dense(fun, dense):
    """Scalar function s -> g(s, dense(s))."""
    return lambda s: float(fun(s, dense(s)))


def root_new_side(gs, a: float, b: float, xtol: float) -> float:
    """Root of ``gs`` in [a, b] (gs(a) > 0 >= gs(b)), returned on the side gs <= 0."""
    if gs(b) > 0:  # defensive: caller guarantees the sign change
        return b
    ga = gs(a)
    if ga <= 0:
        return a
    from scipy.optimize import brentq

    r = brentq(gs, a, b, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=200)
    # Brent returns a point within xtol of the root, on either side; walk to the new side.
    step = max(xtol, 4 * np.finfo(float).eps * abs(r))
    while gs(r) > 0 and r < b:
        r = min(b, r + step)
        step *= 2
    return r


def first_crossing(G: np.ndarray, ts: np.ndarray, start: int, gs, dec_before: bool,
                   dip_factor: float = 2.0):
    """Bracket of the first crossing of one guard in a step, or None.

    ``G[i]`` are guard values at ``ts[i]`` (``ts[0]`` = step start); only indices >=
    ``start`` are armed.  ``dec_before``: the guard was decreasing at the end of the
    previous step (so a minimum may sit just after ``ts[0]``).  Returns ``(a, b)`` with
    g(a) > 0 >= g(b).
    """
    m = len(G)
    neg = np.nonzero(G[start + 1:] <= 0)[0]
    kneg = start + 1 + neg[0] if len(neg) else m
    # Check for a dip (double crossing) before the first negative sample.
    for i in range(start, min(kneg, m - 1)):
        gi = G[i]
        if i == start:
            if not (i == 0 and dec_before and G[1] >= gi):
                continue
            lo, hi, rise = ts[0], ts[1], G[1] - gi
        else:
            if not (gi <= G[i - 1] and gi <= G[i + 1]):
                continue
            lo, hi, rise = ts[i - 1], ts[i + 1], max(G[i - 1], G[i + 1]) - gi
        if gi > dip_factor * rise:
            continue
        from scipy.optimize import minimize_scalar

        res = minimize_scalar(gs, bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-10 * (hi - lo) + 1e-15})
        tmin = float(res.x)
        if gs(tmin) <= 0:
            return (lo, tmin)
    if kneg < m:
        return (ts[kneg - 1], ts[kneg])
    return None
