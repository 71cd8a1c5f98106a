"""Periodic points of the stick–slip event maps and the scalar root searches of the locators.

The bifurcation locators of Galvanetto (2004), Sec. 4 (:mod:`landau.verify.galvanetto.bifurcations`)
reduce each bifurcation to a test function H(parameter) evaluated on a steady state: a periodic
point of the event map f (secant iteration, warm-started along a parameter sweep), the map's
attractor, the events of an orbit.  This module holds those steady states and the searches for a
sign change of H (grid scans, growing brackets, continuation of a periodic orbit) and its root
(Brent's method, xtol 1e-12 in the parameter).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.optimize import brentq

from landau.errors import InputError, IntegratorError, LandauError
from landau.support.deprecation import former_names
from landau.verify.galvanetto.maps import MapUndefined, f_n, two_block_map
from landau.verify.galvanetto.model import K_of, StickSlipParams

XTOL = 1e-12


class NoBifurcationError(InputError):
    """The test function of a locator does not change sign in the search range derived from the
    model: the bifurcation does not exist there for these parameters (the message gives the range)."""


@dataclass(frozen=True)
class PeriodicPoint:
    d: float
    period: int
    residual: float

    def __repr__(self) -> str:
        return f"PeriodicPoint(d={self.d:.14g}, period={self.period}, residual={self.residual:.2g})"


def periodic_point(p: StickSlipParams, d0: float, period: int = 1, stepper=None, tol: float = 1e-13,
                   transparent: frozenset = frozenset(), bracket: tuple[float, float] | None = None,
                   maxiter: int = 40) -> PeriodicPoint:
    """A point with f^period(d) = d, by secant from d0 (or Brent inside ``bracket``)."""
    h = lambda d: f_n(p, d, period, stepper, transparent) - d
    if bracket is not None:
        d = brentq(h, *bracket, xtol=1e-15, rtol=1e-15)
        return PeriodicPoint(d, period, abs(h(d)))
    x0, x1 = d0, d0 + 1e-6
    h0, h1 = h(x0), h(x1)
    for _ in range(maxiter):
        if h1 == h0:
            break
        x2 = x1 - h1 * (x1 - x0) / (h1 - h0)
        x0, h0, x1 = x1, h1, x2
        h1 = h(x1)
        if abs(x1 - x0) < 1e-15 or abs(h1) < tol:
            break
    if not abs(h1) < 1e-10:
        raise LandauError(f"periodic point of period {period} not converged from d0={d0!r}: residual {h1:.3g}")
    return PeriodicPoint(x1, period, abs(h1))


def map_slope(p: StickSlipParams, d: float, period: int = 1, stepper=None, h: float = 2e-5) -> float:
    """(f^period)'(d) by central differences, Richardson-extrapolated (error O(h⁴))."""
    def cd(hh):
        return (f_n(p, d + hh, period, stepper) - f_n(p, d - hh, period, stepper)) / (2 * hh)
    return (4 * cd(h / 2) - cd(h)) / 3


def orbit_events(p: StickSlipParams, d: float, period: int, stepper=None, sections: bool = False,
                 transparent: frozenset = frozenset()) -> list:
    """Events of the map orbit d, f(d), ..., (one list over ``period`` map steps)."""
    evs: list = []
    for _ in range(period):
        ms = two_block_map(p, d, stepper, sections=sections, transparent=transparent)
        evs.extend(ms.events)
        d = ms.d1
    return evs


def _margins(p: StickSlipParams, events, side: str) -> list[float]:
    """K + F_s at r = 0 events leaving r < 0 (side 'n'), F_s − K at those leaving r > 0 ('p')."""
    Fs = p.Fs
    out = []
    for e in events:
        if e.kind == "section" or not e.guard.startswith("r"):
            continue
        i = int(e.guard[1]) - 1
        if e.from_mode[i] != side:
            continue
        K = K_of(p, e.y)[i]
        out.append(K + Fs[i] if side == "n" else Fs[i] - K)
    return out


def _root(H: Callable[[float], float], a: float, b: float, xtol: float = XTOL):
    count = [0]

    def Hc(x):
        count[0] += 1
        return H(x)

    t0 = time.perf_counter()
    ha, hb = Hc(a), Hc(b)
    if ha == 0:
        return a, 0.0, count[0], time.perf_counter() - t0
    if hb == 0:
        return b, 0.0, count[0], time.perf_counter() - t0
    if np.sign(ha) == np.sign(hb):
        raise InputError(f"the test function has the same sign at both ends of the bracket [{a!r}, {b!r}] "
                         f"(H = {ha:.3g}, {hb:.3g}): the bifurcation is not inside it for these parameters")
    x = brentq(Hc, a, b, xtol=xtol, rtol=1e-15, maxiter=200)
    return x, abs(H(x)), count[0] + 1, time.perf_counter() - t0


def scan_bracket(H: Callable[[float], float], grid, what: str) -> tuple[float, float]:
    """The first pair of neighbouring grid points where the test function H changes sign.

    Points where H is undefined (:class:`MapUndefined`, an integrator failure) or not finite
    break the chain: a bracket is made of two neighbours both defined.

    Parameters
    ----------
    H : the test function.
    grid : increasing (or decreasing) parameter values, in the order they are tried.
    what : the bifurcation's name for the error message.

    Returns
    -------
    (a, b) : a bracket of the sign change, in grid order.

    Raises
    ------
    NoBifurcationError
        No sign change on the grid (the bifurcation is not in the range for these parameters).
    """
    prev = None
    for x in grid:
        x = float(x)
        try:
            h = float(H(x))
        except (MapUndefined, IntegratorError):
            prev = None
            continue
        if not np.isfinite(h):
            prev = None
            continue
        if h == 0.0:
            return x, x
        if prev is not None and np.sign(h) != np.sign(prev[1]):
            return prev[0], x
        prev = (x, h)
    raise NoBifurcationError(f"{what}: the test function does not change sign for the parameter in "
                             f"[{float(grid[0]):.6g}, {float(grid[-1]):.6g}] (the range derived from the model); "
                             "the bifurcation does not exist in that range for these parameters")


def _locate(H, bracket, xtol: float = XTOL):
    a, b = bracket
    if a == b:
        return a, 0.0, 1, 0.0
    return _root(H, min(a, b), max(a, b), xtol)


def _velocity_scale(law) -> float:
    """The kinetic law's weakening velocity (1/γ for eq. (7)); InputError if it does not weaken."""
    v = law.weakening_velocity()
    if v is None or not v > 0:
        raise InputError(f"the kinetic law {law!r} does not weaken with the slip velocity: "
                         "no sliding bifurcation to locate")
    return v


class _Warm:
    """Warm start of the periodic point along a parameter sweep."""

    def __init__(self, d0: float | None):
        self.d = d0   # None: no periodic point followed yet


#: a cheaper integrator for the coarse scans that only bracket a sign change (the root itself is
#: refined with the caller's stepper)
SCAN_RTOL = 1e-8


def attractor(p: StickSlipParams, d0: float = 0.0, n_transient: int = 80, max_period: int = 8, stepper=None,
              transparent: frozenset = frozenset(), tol: float = 1e-9) -> tuple[np.ndarray, int | None]:
    """Iterate the event map from ``d0``: the last ``max_period`` + 1 points and the smallest period
    p ≤ ``max_period`` with |f^p(d) − d| < ``tol`` on them (None when not periodic to that tolerance)."""
    d = float(d0)
    for _ in range(n_transient):
        d = f_n(p, d, 1, stepper, transparent)
    orb = [d]
    for _ in range(max_period):
        orb.append(f_n(p, orb[-1], 1, stepper, transparent))
    orb = np.array(orb)
    period = next((k for k in range(1, max_period + 1) if abs(orb[k] - orb[0]) < tol), None)
    return orb, period


def _grow_bracket(H, x0: float, w0: float, limit: float, what: str) -> tuple[float, float]:
    """A sign change of H around x0: [x0 − w, x0 + w] with w = w0·4ᵏ up to ``limit`` (the sides are
    tried separately, so one undefined side does not stop the other)."""
    h0 = H(x0)
    if h0 == 0.0:
        return x0, x0
    w = w0
    while w <= limit:
        for x in (x0 - w, x0 + w):
            try:
                if np.sign(H(x)) != np.sign(h0):
                    return (x, x0) if x < x0 else (x0, x)
            except (MapUndefined, IntegratorError, LandauError):
                pass
        w *= 4
    raise NoBifurcationError(f"{what}: the test function does not change sign for the parameter in "
                             f"[{x0 - limit:.8g}, {x0 + limit:.8g}] (around the coarse root {x0:.8g})")


def _continuation_scan(H, warm: _Warm, x0: float, limit: float, what: str, max_jump: float) -> tuple[float, float]:
    """Bracket of a sign change of H (evaluated on a periodic point warm-started from ``warm.d``)
    next to x0.  The point is followed to both sides of x0 in steps 10⁻⁴|x0|·2ᵏ, at most 10⁻²|x0|,
    up to distance ``limit``; a side ends where the orbit is lost: the periodic point does not
    converge, the map is undefined, or the point jumps by more than ``max_jump`` in one step (the
    secant has found another orbit); where it is lost after a step longer than 10⁻⁴|x0| the step is
    halved back towards the last point followed until that resolution."""
    def follow(x, dp):
        """H at x on the orbit continued from the point dp, or None where it is lost."""
        warm.d = dp
        try:
            h = H(x)
        except (MapUndefined, IntegratorError, LandauError):
            return None
        return h if abs(warm.d - dp) <= max_jump else None

    h0 = follow(x0, warm.d)
    if h0 is None:
        raise NoBifurcationError(f"{what}: the periodic orbit of the attractor at {x0:.8g} cannot be followed (its "
                                 "periodic point does not converge at full precision or the test function is "
                                 "undefined on it)")
    if h0 == 0.0:
        return x0, x0
    reached = {-1: (x0, warm.d), +1: (x0, warm.d)}   # the last point followed on each side
    ends: dict[int, float | None] = {-1: None, +1: None}   # where a side was lost
    dist, step = 0.0, 1e-4 * abs(x0)
    while reached and dist < limit:
        dist = min(dist + step, limit)
        for side in list(reached):
            xp, dp = reached[side]
            x = x0 + side * dist
            h = follow(x, dp)
            # the orbit lost after a long step: halve back towards the last point followed (a sign
            # change may lie just before the orbit ends, as at Fig. 16's multi-sliding)
            lost = x
            while h is None and abs(lost - xp) > 1e-4 * abs(x0):
                mid = 0.5 * (xp + lost)
                hm = follow(mid, dp)
                if hm is None:
                    lost = mid
                elif np.sign(hm) != np.sign(h0):
                    x, h = mid, hm            # the sign change lies between xp and mid
                else:
                    xp, dp = mid, warm.d      # still followed, same sign: go on from there
            if h is None:
                ends[side] = xp
                del reached[side]
                continue
            if np.sign(h) != np.sign(h0):
                if xp < x:
                    warm.d = dp     # the root search starts at the lower end, on the orbit followed
                return (xp, x) if xp < x else (x, xp)
            reached[side] = (x, warm.d)
        step = min(2 * step, 1e-2 * abs(x0))
    lo = ends[-1] if ends[-1] is not None else x0 - limit
    hi = ends[+1] if ends[+1] is not None else x0 + limit
    raise NoBifurcationError(f"{what}: the test function does not change sign along the periodic orbit followed "
                             f"from {x0:.8g} over [{lo:.8g}, {hi:.8g}] (searched within [{x0 - limit:.8g}, "
                             f"{x0 + limit:.8g}]; the orbit was lost at an end inside that range); the "
                             "bifurcation does not exist on that orbit")


def _located():
    from landau.verify.hybrid.analysis import Located

    return Located


# the locators' result type lives in the simulation engine's toolkit, shared with the other models
__getattr__ = former_names(__name__, {"Located": (_located, "import Located from landau.verify.galvanetto.bifurcations "
                                                            "or landau.verify.hybrid.analysis")})
