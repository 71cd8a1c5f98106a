"""The multi-sliding bifurcation of the two blocks, Galvanetto (2004) Sec. 4.3, Fig. 16: the
minimum of K₂ over a stick phase of block 2 touches −β (:func:`multi_sliding`), found from the
periodic windows of the map's attractor in a γ scan and followed in γ along the periodic orbit.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from landau.errors import InputError, IntegratorError, LandauError
from landau.laws.kinetic import KineticFriction, resolve_kinetic_law
from landau.verify.galvanetto.maps import MapUndefined, d_range, default_stepper, two_block_map
from landau.verify.galvanetto.model import K_of, two_blocks
from landau.verify.galvanetto.periodic import (
    SCAN_RTOL,
    NoBifurcationError,
    _continuation_scan,
    _locate,
    _velocity_scale,
    _Warm,
    attractor,
    map_slope,
    periodic_point,
)
from landau.verify.hybrid.analysis import Located

#: derived start of :func:`multi_sliding`: γ is scanned on a geometric grid (neighbours 2 % apart) from
#: the γ at which the law's weakening velocity is ten times the belt velocity V to the γ at which it
#: equals V; the attractor at each grid point is iterated ``MS_TRANSIENT`` times from the middle of the
#: map's domain before its period is read
MS_SCAN_STEP, MS_SCAN_DECADE, MS_TRANSIENT = 0.02, 10.0, 50


def _multi_sliding_test(p, d, period, stepper) -> float:
    """min K₂ + β over the stick phases of block 2 entered from 'ps' along the orbit of d (the
    guard K₂ = −β made transparent to continue the stick phase)."""
    virt = frozenset({"K2=-Fs"})
    for _ in range(period):
        ms = two_block_map(p, d, stepper, sections=True, transparent=virt)
        mins = [K_of(p, e.y)[1] + p.beta for e in ms.events if e.guard == "Kmin2" and e.from_mode == "ps"]
        if mins:
            return min(mins)
        d = ms.d1
    raise MapUndefined("no stick phase of block 2 during an r1 > 0 slip")


def _multi_sliding_range(law, V: float) -> tuple[float, float]:
    """The γ range of the derived multi-sliding search: from the γ at which the law's weakening velocity
    (:meth:`KineticFriction.weakening_velocity`, 1/γ for eq. (7)) is ``MS_SCAN_DECADE``·V down to the γ
    at which it equals V (γ is taken as an inverse velocity scale, v_w ∝ 1/γ, as in eq. (7))."""
    if not (np.isfinite(V) and V > 0):
        raise InputError(f"multi-sliding: the belt velocity V = {V!r} must be positive and finite")
    vs = _velocity_scale(law)
    if not law.gamma > 0:
        raise InputError(f"multi-sliding: the law's gamma = {law.gamma!r} must be positive (it scales the "
                         "weakening velocity that sets the derived search range)")
    c = vs * law.gamma              # v_w(γ) = c/γ
    return c / (MS_SCAN_DECADE * V), c / V


#: the periodic windows found by the derived multi-sliding scan, per model and d0
_WINDOW_CACHE: dict = {}


def _multi_sliding_windows(params, grid, d0: float, scan_st) -> list[dict]:
    """The periodic windows of the map's attractor along ``grid``: at each γ the attractor from d0
    (``MS_TRANSIENT`` iterations, period ≤ 8 to 10⁻⁶); neighbouring grid points with the same period
    form one window, kept when the test function is defined on its orbit (a stick phase of block 2
    during an r₁ > 0 slip) and represented by its grid point of smallest |H|."""
    windows, last = [], None
    for i, g in enumerate(grid):
        p = params(g)
        try:
            orb, per = attractor(p, d0, MS_TRANSIENT, 8, scan_st, tol=1e-6)
            h = _multi_sliding_test(p, float(orb[0]), per, scan_st) if per is not None else None
        except (MapUndefined, IntegratorError):
            per, h = None, None
        if per is None or h is None:
            last = None
            continue
        pt = {"gamma": float(g), "d": float(orb[0]), "period": per, "H": float(h)}
        if last is not None and last[0] == i - 1 and last[1]["period"] == per:
            if abs(h) < abs(last[1]["H"]):
                last[1].update(pt)
        else:
            windows.append(pt)
        last = (i, windows[-1])
    return windows


def multi_sliding(bracket=None, V=0.05, alpha=1.2, beta=2.0, delta=None, stepper=None,
                  d0: float | None = None, *, law: KineticFriction | None = None,
                  gamma: float | None = None) -> Located:
    """γ of Fig. 16: during a stick phase of block 2 (block 1 slipping with r₁ > 0) the
    minimum of K₂ touches −β, so a slip phase of block 2 with r₂ > 0 is born from the stick
    phase.  H = min K₂ + β in that stick phase (guard made transparent to continue it),
    on a periodic orbit of the map.

    Parameters
    ----------
    bracket : search interval in γ (the attractor at its lower end from ``d0`` gives the orbit).
    V, alpha, beta : belt velocity, inter-block stiffness, block 2's static level (Fig. 16: 0.05,
        1.2, 2).
    delta : δ of the default law, eq. (7) (default 0).
    stepper : mode integrator (default DOP853, rtol 1e-11).
    d0 : start of the attractor iterations (default: the middle of the map's domain,
        :func:`d_range`, i.e. d = 0).
    law : the kinetic law; its parameter γ is the one varied (its own value is not used: default
        eq. (7) with ``delta``).
    gamma : γ where the search starts.  Given, the map's attractor there (from ``d0``; 80
        iterations, DOP853 at rtol 1e-8) gives the period n ≤ 8 of the orbit (period detection
        as in :func:`two_block_sliding`); that periodic point is continued in γ (warm-started
        secant) to both sides with steps 10⁻⁴·γ·2ᵏ (at most 10⁻²·γ) up to 0.2·γ away, as long as it
        moves by less than 1 % of the map's domain per step; the first sign change of H brackets
        the multi-sliding point (Fig. 16's start is ``gamma=10.756, d0=0.1969494``: from d = 0
        the attractor at γ = 10.756 is not periodic).  Default (with no ``bracket``) derived from
        the model:

        1. γ is scanned on a geometric grid (neighbours 2 % apart) from the γ where the law's
           weakening velocity (1/γ for eq. (7)) is 10·V to the γ where it equals V
           (:func:`_multi_sliding_range`); at each grid point the attractor from ``d0``
           (50 iterations, rtol 1e-8) is tested for a period n ≤ 8 and H evaluated on it;
        2. neighbouring grid points with the same period form a *window*; windows whose orbit has
           no stick phase of block 2 during an r₁ > 0 slip (H undefined) are dropped;
        3. the windows are tried lowest period first, and within a period nearest first (smallest
           |H| on the window's attractor, the margin K₂ + β that the bifurcation closes): from the
           window's grid point of smallest |H| the orbit is continued in γ as above;
        4. the first root at which the orbit is stable (|(fⁿ)'(d*)| < 1, :func:`map_slope`: the
           multi-sliding of an attractor) is the answer; roots on an unstable continuation of
           the orbit are skipped.

        Lower periods first: their continuation costs fewer map evaluations per step, and where
        several periodic attractors have a multi-sliding point (at Fig. 16's parameters also a
        period-3 orbit, at γ ≈ 10.276) the selection is fixed by a rule of the model's orbits,
        not by the grid.

    Returns
    -------
    Located
        ``details``: the periodic point ``d``, its ``period``, the bracket; for the derived
        start also ``start_gamma``, the ``slope`` (fⁿ)'(d*), the γ ``range`` scanned and
        ``windows_tried`` (the number of windows followed, the successful one included).

    Raises
    ------
    NoBifurcationError
        The attractor at a given start is not periodic, or H does not change sign along the
        continued orbit in the derived range; for the derived start: no periodic window with a
        stable multi-sliding point in the scanned γ range (the message gives it and the windows
        tried).

    References
    ----------
    U. Galvanetto, J. Sound Vib. 276 (2004) 121–139, Sec. 4.3, Fig. 16.
    """
    law = resolve_kinetic_law(law, None, delta)
    params = lambda g: two_blocks(V, alpha, beta, law=replace(law, gamma=float(g)))
    if d0 is None:
        lo, hi = d_range(params(law.gamma))
        d0 = 0.5 * (lo + hi)
    d0 = float(d0)
    scan_st = default_stepper(SCAN_RTOL)

    given = float(bracket[0]) if bracket is not None else None if gamma is None else float(gamma)
    if given is not None:
        start = given
        orb, period = attractor(params(start), d0, 80, 8, scan_st, tol=1e-6)
        if period is None:
            raise NoBifurcationError(f"multi-sliding: the map's attractor at gamma = {start:g} from d0 = {d0:g} is "
                                     "not periodic (period <= 8); the multi-sliding point is searched along a "
                                     "periodic orbit (start from another gamma or d0)")
        return _multi_sliding_from(params, start, float(orb[0]), period, stepper, bracket)

    g_lo, g_hi = _multi_sliding_range(law, V)
    t0 = time.perf_counter()
    n = int(np.ceil(np.log(g_hi / g_lo) / np.log1p(MS_SCAN_STEP)))
    # the scan depends on the model and d0 only (its integrator is fixed): reused by calls that differ in
    # the stepper of the root (convergence checks) or repeat the search
    key = (float(V), float(alpha), float(beta), law, d0)
    windows = _WINDOW_CACHE.get(key)
    if windows is None:
        if len(_WINDOW_CACHE) > 16:
            _WINDOW_CACHE.clear()
        windows = _WINDOW_CACHE[key] = _multi_sliding_windows(
            params, g_lo * (g_hi / g_lo) ** (np.arange(n + 1) / n), d0, scan_st)
    tried = []
    for w in sorted(windows, key=lambda w: (w["period"], abs(w["H"]))):
        try:
            loc = _multi_sliding_from(params, w["gamma"], w["d"], w["period"], stepper, None)
            slope = map_slope(params(loc.value), loc.details["d"], w["period"], stepper)
        except LandauError as err:
            tried.append(f"period {w['period']} at gamma = {w['gamma']:.5g}: {type(err).__name__}")
            continue
        if abs(slope) < 1:
            return replace(loc, seconds=time.perf_counter() - t0,
                           details={**loc.details, "start_gamma": w["gamma"], "slope": float(slope),
                                    "range": (float(g_lo), float(g_hi)), "windows_tried": len(tried) + 1})
        tried.append(f"period {w['period']} at gamma = {w['gamma']:.5g}: unstable orbit at "
                     f"gamma* = {loc.value:.8g} (slope {slope:.3g})")
    raise NoBifurcationError(
        f"multi-sliding: no periodic attractor (period <= 8, from d0 = {d0:g}) with a stable multi-sliding point "
        f"for gamma in [{g_lo:.6g}, {g_hi:.6g}] (the range derived from the law's weakening velocity, 10·V to V); "
        + (f"windows tried: {'; '.join(tried)}" if tried else "no periodic window with a stick phase of block 2 "
           "during an r1 > 0 slip was found") + " (pass gamma= or bracket= to search elsewhere)")


def _multi_sliding_from(params, start: float, dp: float, period: int, stepper, bracket) -> Located:
    """The multi-sliding point on the periodic orbit of the point near ``dp`` at γ = ``start``,
    continued in γ (:func:`_continuation_scan`) unless a ``bracket`` is given."""
    warm = _Warm(dp)

    def H(g):
        p = params(g)
        # a secant from a warm start converges in < 10 steps; 20 bounds the cost where the orbit is lost
        pp = periodic_point(p, warm.d, period, stepper, maxiter=20)
        warm.d = pp.d
        return _multi_sliding_test(p, pp.d, period, stepper)

    if bracket is None:
        lo, hi = d_range(params(start))
        bracket = _continuation_scan(H, warm, start, 0.2 * start, "multi-sliding", 0.01 * (hi - lo))
    g, res, n, sec = _locate(H, bracket)
    return Located("multi-sliding", "gamma", g, res, n, sec,
                   {"d": warm.d, "period": period, "bracket": tuple(map(float, bracket))})
