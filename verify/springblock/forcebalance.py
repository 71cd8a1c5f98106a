"""The quasi-dynamic force balance solved for the slip rate (Rice 1993).

Without inertia (M = 0) the momentum equation of the spring–block with radiation damping η is
algebraic, 0 = F_spring − σ μ(v, φ) − η v, and fixes the slip rate at every instant.  With η > 0
and ∂μ/∂v ≥ 0 its residual R decreases strictly in w = ln(v/v_ref), so the root is unique.
:func:`solve_log_rate` finds it by a safeguarded Newton iteration in w (a bracket kept and
bisected where a Newton step would leave it).  The constant-velocity cell
(:mod:`landau.verify.springblock.quasidynamic`) takes its slip rate from it wherever a state is given
without one (the start of a run, a point of the section v = V); the compiled runs then carry w as a
state (:mod:`landau.verify.springblock.compiled_runs`).

References
----------
Rice, J. R. (1993), Spatio-temporal complexity of slip on a fault, J. Geophys. Res. 98(B6), 9885–9907.
"""

from __future__ import annotations

import math
from typing import Any, Callable, Sequence

from landau.errors import IntegratorError

#: bound on |w − w_centre| of the slip-rate root (v between v_ref e^-600 and v_ref e^600)
W_BOUND = 600.0


def solve_log_rate(fn: Callable[..., Any], y: Sequence[float], w0: float = 0.0, centre: float = 0.0) -> float:
    """w solving R(w, y) = 0, where ``fn(w, *y)`` returns (R, R_w, ...) with R decreasing in w.

    Parameters
    ----------
    fn : callable
        ``fn(w, *y) -> (R, R_w, ...)``: the force residual and its derivative in w.
    y : sequence of float
        The other variables (slip or spring stretch, log states).
    w0 : float
        Starting guess (the previous step's root).
    centre : float
        Centre of the bracket [centre − W_BOUND, centre + W_BOUND].

    Returns
    -------
    float
        The root, to round-off (the last Newton step below 1e-8).

    Raises
    ------
    IntegratorError
        R_w ≥ 0 somewhere on the way (no unique slip rate), or no root in the bracket.
    """
    y = [float(q) for q in y]
    lo, hi = centre - W_BOUND, centre + W_BOUND
    w = min(max(float(w0), lo), hi)
    for _ in range(200):
        R, Rw = fn(w, *y)[:2]
        if not (math.isfinite(R) and math.isfinite(Rw)):
            hi = w            # overflow lies above the root (R decreases in w)
            w = 0.5 * (lo + hi)
            continue
        if R > 0:
            lo = w
        else:
            hi = w
        if Rw >= 0:
            raise IntegratorError("quasi-dynamic force balance: the friction force decreases with the slip "
                                  "rate faster than eta*v grows (no unique slip rate)", t=float("nan"),
                                  state=list(y))
        step = -R / Rw
        if abs(step) <= 1e-8:      # quadratic convergence: this step leaves an error ~ step² (round-off)
            return w + step
        wn = w + max(-4.0, min(4.0, step))
        if not (lo < wn < hi):
            wn = 0.5 * (lo + hi)
        w = wn
    if hi - lo < 1e-9:
        return w
    raise IntegratorError("quasi-dynamic force balance: no slip rate found (the state left the range "
                          f"e^-{W_BOUND:g} < v/v_ref < e^{W_BOUND:g})", t=float("nan"), state=list(y))


__all__ = ["W_BOUND", "solve_log_rate"]
