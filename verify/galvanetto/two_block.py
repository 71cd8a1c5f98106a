"""Bifurcations of the two-block event map, Galvanetto (2004) Sec. 4.1–4.2 and Figs 12, 15: type
I/II sliding in V (:func:`two_block_sliding`), the kink of f (grazing of block 1's sticking region,
:func:`kink`), and the sequence in β of Fig. 12 — discontinuous fold, period doubling, border
collision, boundary crisis — and the grazing-sliding of Fig. 15, each searched upward from the
previous one.
"""

from __future__ import annotations

from typing import Callable

import numpy as np
from scipy.optimize import brentq

from landau.errors import InputError, IntegratorError, LandauError
from landau.laws.kinetic import KineticFriction, resolve_kinetic_law
from landau.verify.galvanetto.maps import MapUndefined, d_range, default_stepper, f_n, two_block_map
from landau.verify.galvanetto.model import StickSlipParams, _make_rhs, two_blocks
from landau.verify.galvanetto.periodic import (
    SCAN_RTOL,
    NoBifurcationError,
    PeriodicPoint,
    _grow_bracket,
    _locate,
    _margins,
    _velocity_scale,
    _Warm,
    attractor,
    map_slope,
    orbit_events,
    periodic_point,
    scan_bracket,
)
from landau.verify.hybrid.analysis import Located

# ----------------------------------------------------------------- two blocks (Sec. 4.1)


def two_block_sliding(kind: str, alpha: float = 1.2, beta: float = 1.3, gamma: float | None = None,
                      delta: float | None = None, bracket: tuple[float, float] | None = None,
                      period: int | None = None, d0: float | None = None, stepper=None, *,
                      law: KineticFriction | None = None) -> Located:
    """Type II / type I sliding point of the two blocks in V (Figs 8, 9).

    H is evaluated on the stable periodic point of f^period (warm-started); for type I the
    blocks are made to stick virtually at r = 0 from r > 0 so that the map stays defined
    past the bifurcation (where the g.s.p. disappears).

    Parameters
    ----------
    kind : "II" or "I".
    alpha, beta : inter-block stiffness α and block 2's static level β.
    gamma, delta : parameters of the default law, eq. (7) (defaults γ = 3, δ = 0).
    bracket : search interval in V.  Default derived from the law: the minimum of the margin
        over the map's attractor (80 transient iterations, warm-started along the scan, DOP853 at
        rtol 1e-8) is scanned on a logarithmic grid of V from 0.1 to 10 times the law's weakening
        velocity (1/γ for eq. (7)); the first sign change brackets the bifurcation.
    period : period of the map orbit the bifurcation happens on; default: the attractor's
        period at the bracket's lower end.
    d0 : start of the periodic-point iteration (default: the attractor at the lower end).
    stepper : mode integrator (default DOP853, rtol 1e-11).
    law : the kinetic law (default eq. (7) with ``gamma``, ``delta``).

    Returns
    -------
    Located

    References
    ----------
    U. Galvanetto, J. Sound Vib. 276 (2004) 121–139, Sec. 4.1, Figs 8, 9.
    """
    if kind not in ("II", "I"):
        raise InputError(f"two_block_sliding: kind must be 'II' or 'I', not {kind!r}")
    law = resolve_kinetic_law(law, gamma, delta)
    side = "n" if kind == "II" else "p"
    virt = frozenset() if kind == "II" else frozenset({"stick1:p", "stick2:p"})

    if bracket is None:
        scan_st = default_stepper(SCAN_RTOL)
        warm_scan = _Warm(0.0)
        periods = {}

        def H_attractor(V):
            p = two_blocks(V, alpha, beta, law=law)
            try:
                orb, per = attractor(p, warm_scan.d, 60 if warm_scan.d == 0.0 else 30, 8, scan_st, virt, tol=1e-6)
                evs = orbit_events(p, orb[0], 8, scan_st, transparent=virt)
            except (MapUndefined, IntegratorError):
                warm_scan.d = 0.0
                raise
            warm_scan.d = float(orb[-1])
            periods[V] = (per, float(orb[0]))
            m = _margins(p, evs, side)
            return min(m) if m else 1.0   # no slip phase on that side ends: before the bifurcation

        vs = _velocity_scale(law)
        a, b = scan_bracket(H_attractor, vs * 10.0 ** (np.arange(-8, 9) / 8), f"two-block type {kind} sliding")
        # bisect on the attractor until both ends sit on periodic orbits of the same period
        ha = H_attractor(a)
        for _ in range(12):
            if periods[a][0] is not None and periods[a][0] == periods[b][0]:
                break
            m = 0.5 * (a + b)
            warm_scan.d = periods[a][1]
            hm = H_attractor(m)
            if np.sign(hm) == np.sign(ha):
                a, ha = m, hm
            else:
                b = m
        if period is None and periods[a][0] is not None and periods[a][0] == periods[b][0]:
            period = periods[a][0]
            d0 = periods[a][1] if d0 is None else d0
        bracket = (a, b)
    p0 = two_blocks(bracket[0], alpha, beta, law=law)
    if d0 is None or period is None:
        orb, per = attractor(p0, 0.0, 80, 8, stepper, virt)
        d0 = float(orb[0]) if d0 is None else d0
        if period is None:
            if per is None:
                raise NoBifurcationError(
                    f"two-block type {kind} sliding: the test function changes sign for V in [{bracket[0]:.6g}, "
                    f"{bracket[1]:.6g}], but the map's attractor at V = {bracket[0]:.6g} is not periodic (period <= "
                    f"8): "
                    "the sliding happens on a non-periodic attractor, not at a point of a periodic orbit "
                    "(pass period= to follow a periodic orbit of that period)")
            period = per
    warm = _Warm(d0)

    def H(V):
        p = two_blocks(V, alpha, beta, law=law)
        pp = periodic_point(p, warm.d, period, stepper, transparent=virt)
        warm.d = pp.d
        return min(_margins(p, orbit_events(p, pp.d, period, stepper, transparent=virt), side))

    V, res, n, sec = _locate(H, bracket)
    return Located(f"two-block-type-{kind}", "V", V, res, n, sec,
                   {"alpha": alpha, "beta": beta, "gamma": law.gamma, "delta": law.delta, "d": warm.d, "period": period,
                    "bracket": tuple(map(float, bracket))})


# ----------------------------------------------------------------- map bifurcations in β (Sec. 4.2)

GRAZE1 = frozenset({"r1=0:n"})


def kink_function(p: StickSlipParams, d: float, stepper=None) -> float:
    """Grazing test of block 1's first slip phase with both blocks slipping (r₁ < 0 branch):
    max r₁ (< 0) when the phase turns back before reaching r₁ = 0; when it crosses r₁ = 0 with
    ṙ₁ = a > 0, r̈₁ = j < 0, the height a²/(2|j|) of the local parabola's vertex (the continued
    maximum, > 0).  Both tend to 0 at the tangency, so the function is continuous; its zero is
    the grazing of block 1's sticking region, i.e. the slope discontinuity of f in Figs 13–14."""
    ms = two_block_map(p, d, stepper, sections=True, transparent=GRAZE1,
                       stop=lambda ev: ev.to_mode == "ss" or (ev.guard in ("rmax1", "rzero1") and ev.from_mode == "nn"))
    for e in ms.events:
        if e.from_mode == "nn" and e.guard == "rmax1":
            return float(e.y[2] - p.V)
        if e.from_mode == "nn" and e.guard == "rzero1":
            # crossing with ṙ₁ = a > 0 and r̈₁ = j: near the tangency r₁ is a parabola whose vertex
            # lies a²/(2|j|) above 0 (the continued maximum, without integrating into the region
            # where the r < 0 branch may be singular)
            rhs = _make_rhs(p, "nn")
            y = np.asarray(e.y, float)
            fy = rhs(e.t, y)
            h = 1e-7
            jerk = (rhs(e.t + h, y + h * fy)[2] - rhs(e.t - h, y - h * fy)[2]) / (2 * h)
            a = float(fy[2])
            return a * a / (2 * -jerk) if jerk < 0 else a
    raise MapUndefined("no r1 maximum in an 'nn' phase")


def kink(p: StickSlipParams, d0: float | None = None, stepper=None, tol: float = 1e-10) -> float:
    """The slope-discontinuity point d_k of f (root of :func:`kink_function`).

    From ``d0`` by secant; without ``d0`` (or when the secant does not converge inside the map's
    domain) :func:`kink_function` is scanned on 25 points of the domain (:func:`d_range`, from the
    parameters) and the sign change is refined by Brent's method.

    Parameters
    ----------
    p : two-block parameters.
    d0 : a start near the kink (e.g. the kink at a neighbouring β).
    stepper : mode integrator (default DOP853, rtol 1e-11).
    tol : the secant's result is accepted when |kink_function| < tol.

    Returns
    -------
    float
        d_k.
    """
    lo, hi = d_range(p)

    def g(d, st):
        # the r₁ < 0 branch continued beyond r₁ = 0 may become singular (eq. (7) has a pole at
        # r = 1/γ): then the maximum of r₁ is certainly positive
        try:
            return kink_function(p, d, st)
        except IntegratorError:
            return 1.0

    def refine(a, b):
        x = brentq(lambda d: g(d, stepper), min(a, b), max(a, b), xtol=1e-15 if tol <= 1e-10 else 0.1 * tol,
                   rtol=1e-15)
        if not abs(g(x, stepper)) < max(tol, 1e-9):
            raise MapUndefined(f"no grazing of block 1's sticking region near d = {x:.6g} (a jump, not a kink)")
        return x

    if d0 is not None:
        try:   # secant from d0 (a few evaluations when d0 is close)
            x0, x1 = d0, d0 + 1e-4
            h0, h1 = kink_function(p, x0, stepper), kink_function(p, x1, stepper)
            for _ in range(12):
                if h1 == h0:
                    break
                x0, h0, x1 = x1, h1, x1 - h1 * (x1 - x0) / (h1 - h0)
                h1 = kink_function(p, x1, stepper)
                if abs(x1 - x0) < 1e-15 or h1 == 0:
                    break
            if lo < x1 < hi and abs(h1) < tol:
                return x1
        except (MapUndefined, IntegratorError):
            pass
        w = 1e-3 * (hi - lo)   # else a bracket grown around d0
        g0 = g(d0, stepper)
        while w < hi - lo:
            for e in (d0 - w, d0 + w):
                if lo < e < hi:
                    try:
                        if np.sign(g(e, stepper)) != np.sign(g0):
                            return refine(d0, e)
                    except MapUndefined:
                        pass
            w *= 4
    scan_st = default_stepper(SCAN_RTOL)
    a, b = scan_bracket(lambda d: g(d, scan_st), np.linspace(lo, hi, 27)[1:-1], "slope discontinuity of the map")
    return refine(a, b)


def fig12_params(beta: float, V: float = 0.25, alpha: float = 1.2, gamma: float | None = None,
                 delta: float | None = None, *, law: KineticFriction | None = None) -> StickSlipParams:
    """The two blocks of Fig. 12 (V = 0.25, α = 1.2, eq. (7) with γ = 3, δ = 0) at static level β."""
    return two_blocks(V, alpha, beta, gamma, delta, law=law)


def fixed_point_beside_kink(p: StickSlipParams, dk: float, side: int, stepper=None) -> PeriodicPoint:
    """The fixed point of f on one side of the kink d_k (``side`` −1: left, +1: right), when f has
    its minimum at the kink below the diagonal (f(d_k) < d_k): steps away from d_k by 2ʲ|f(d_k) − d_k|
    until f(d) − d changes sign, then Brent's method."""
    h = lambda d: f_n(p, d, 1, stepper) - d
    h0 = h(dk)
    if not h0 < 0:
        raise MapUndefined(f"f(d_k) - d_k = {h0:.3g} >= 0: no fixed point next to the kink")
    lo, hi = d_range(p)
    w = max(abs(h0), 1e-12)
    inner = dk + side * 1e-12
    for _ in range(60):
        d = dk + side * w
        if not lo < d < hi:
            break
        if h(d) > 0:
            x = brentq(h, min(inner, d), max(inner, d), xtol=1e-15, rtol=1e-15)
            return PeriodicPoint(x, 1, abs(h(x)))
        inner, w = d, 2 * w
    raise MapUndefined(f"no fixed point of f {'left' if side < 0 else 'right'} of the kink d_k = {dk:.6g}")


#: first step and growth of the upward scans in β that chain the Fig. 12 bifurcations
BETA_STEP, BETA_GROWTH = 1e-4, 2.0


def _chain_scan(H, start: float, what: str, limit: float = 0.5) -> tuple[float, float]:
    """Bracket of the first sign change of H above ``start``: β = start + 10⁻⁴·2ᵏ (k = 0, 1, ...)
    up to start + ``limit``."""
    steps = BETA_STEP * BETA_GROWTH ** np.arange(0, 1 + np.log(limit / BETA_STEP) / np.log(BETA_GROWTH))
    return scan_bracket(H, start + steps, what)


def _fold_scan(V, alpha, law) -> tuple[float, float]:
    """Bracket in β of the discontinuous fold of Fig. 12 type, from the model alone.

    β is scanned upward from 1 (equal static levels) in steps of 0.05 up to 1 + 2(1 + α) with
    H(β) = f(d_k) − d_k (DOP853, rtol 1e-8).  A fold of Fig. 12's kind is a sign change from + to −
    (the minimum of f at its kink drops below the diagonal, two fixed points are born) at which f
    decreases left of the kink and has slope > 1 right of it (Galvanetto 2004, Sec. 2.2 case (3):
    the left slope is in (−1, 0) at the fold itself; at the scan's grid point, up to 0.05 later, it
    may already be below −1, past the period doubling).
    """
    st = default_stepper(SCAN_RTOL)
    warm = _Warm(None)

    def H(beta):
        p = fig12_params(beta, V, alpha, law=law)
        try:
            warm.d = kink(p, warm.d, st, tol=1e-6)
        except (MapUndefined, IntegratorError, InputError) as err:
            warm.d = None
            raise MapUndefined("no kink") from err
        return f_n(p, warm.d, 1, st) - warm.d

    betas = 1.0 + 0.05 * np.arange(1, 1 + int(round(2 * (1 + alpha) / 0.05)))
    prev = None
    for beta in betas:
        try:
            h = H(beta)
        except (MapUndefined, IntegratorError):
            prev = None
            continue
        if prev is not None and prev[1] > 0 > h:
            p = fig12_params(beta, V, alpha, law=law)
            dk = warm.d
            assert dk is not None  # H(beta) has just located the kink
            off = 2e-4 * (d_range(p)[1] - d_range(p)[0])
            try:
                left = map_slope(p, dk - off, 1, st, h=off / 20)
                right = map_slope(p, dk + off, 1, st, h=off / 20)
            except (MapUndefined, IntegratorError):
                left = right = np.nan
            if left < 0.0 and right > 1.0:
                return prev[0], beta
        prev = (beta, h)
    raise NoBifurcationError(f"discontinuous fold: no fold of Galvanetto's case (3) for beta in (1, {betas[-1]:.3g}] "
                     f"at V = {V:g}, alpha = {alpha:g}, {law!r}")


def discontinuous_fold(bracket=None, V=0.25, alpha=1.2, gamma=None, delta=None, stepper=None, *,
                       law: KineticFriction | None = None) -> Located:
    """β where a fixed point of f sits at the kink: f(d_k) = d_k (Fig. 12, β ≈ 1.7217).

    Parameters
    ----------
    bracket : search interval in β; default from the model (:func:`_fold_scan`: the first fold of
        the paper's case (3) above β = 1).
    V, alpha : belt velocity and inter-block stiffness (Fig. 12: 0.25, 1.2).
    gamma, delta : parameters of the default law, eq. (7) (defaults γ = 3, δ = 0).
    stepper : mode integrator (default DOP853, rtol 1e-11).
    law : the kinetic law (default eq. (7) with ``gamma``, ``delta``).

    Returns
    -------
    Located

    References
    ----------
    U. Galvanetto, J. Sound Vib. 276 (2004) 121–139, Sec. 2.2 and 4.2, Figs 12, 13.
    """
    return _sequence_point("fold", bracket, V, alpha, gamma, delta, stepper, law)


def _kink_test(V, alpha, law, stepper, warm: _Warm, test) -> Callable[[float], float]:
    """H(β) = test(p, d_k, stepper) at the kink d_k of the two blocks' map at static level β (found
    from the previous kink ``warm.d``, which is updated)."""
    def H(beta):
        p = fig12_params(beta, V, alpha, law=law)
        warm.d = dk = kink(p, warm.d, stepper)
        return test(p, dk, stepper)
    return H


def _fold_test(p, dk, stepper):
    """f(d_k) − d_k: a fixed point of f at the kink."""
    return f_n(p, dk, 1, stepper) - dk


def _period_doubling_test(p, dk, stepper):
    """(slope of f at the fixed point left of the kink) + 1."""
    pp = fixed_point_beside_kink(p, dk, -1, stepper)
    return map_slope(p, pp.d, 1, stepper, h=min(2e-5, (dk - pp.d) / 3)) + 1.0


def _period_two_at_kink_test(p, dk, stepper):
    """f²(d_k) − d_k: a period-2 orbit through the kink."""
    return f_n(p, dk, 2, stepper) - dk


def _crisis_test(p, dk, stepper):
    """f²(d_k) − u, u the unstable fixed point right of the kink."""
    u = fixed_point_beside_kink(p, dk, +1, stepper).d
    return f_n(p, dk, 2, stepper) - u


#: the Fig. 12 sequence: name -> (test function at the kink, the bifurcation its default search
#: starts above (None: the fold's own scan), its name in messages)
_SEQUENCE = {
    "fold": (_fold_test, None, "discontinuous fold"),
    "period-doubling": (_period_doubling_test, "fold", "period doubling"),
    "border-collision": (_period_two_at_kink_test, "period-doubling", "border collision"),
    "crisis": (_crisis_test, "border-collision", "boundary crisis"),
}


def _sequence_point(name, bracket, V, alpha, gamma, delta, stepper, law) -> Located:
    """One bifurcation of the Fig. 12 sequence (see :data:`_SEQUENCE`), memoised per parameter set."""
    law = resolve_kinetic_law(law, gamma, delta)
    return _memo(name, V, alpha, law, bracket, stepper, lambda: _chained(name, bracket, V, alpha, stepper, law))


def _chained(name, bracket, V, alpha, stepper, law) -> Located:
    test, previous, what = _SEQUENCE[name]
    warm = _Warm(None)
    H = _kink_test(V, alpha, law, stepper, warm, test)
    if bracket is None:
        if previous is None:
            bracket = _fold_scan(V, alpha, law)
        else:
            prev = _sequence_point(previous, None, V, alpha, None, None, None, law)
            warm.d = prev.details["d_kink"]
            bracket = _chain_scan(H, prev.value, what)
    b, res, n, sec = _locate(H, bracket)
    assert warm.d is not None  # the last H evaluation located the kink
    return Located(name, "beta", b, res, n, sec, {"d_kink": float(warm.d), "bracket": tuple(map(float, bracket))})


#: the Fig. 12 sequence located with the default stepper and derived brackets, per parameter set
#: (each bifurcation is searched upward from the previous one, so they are reused)
_SEQ_CACHE: dict = {}


def _memo(name: str, V, alpha, law, bracket, stepper, compute) -> Located:
    if bracket is not None or stepper is not None:
        return compute()
    key = (name, float(V), float(alpha), law)
    if key not in _SEQ_CACHE:
        if len(_SEQ_CACHE) > 64:
            _SEQ_CACHE.clear()
        _SEQ_CACHE[key] = compute()
    return _SEQ_CACHE[key]


def period_doubling(bracket=None, V=0.25, alpha=1.2, gamma=None, delta=None, stepper=None, *,
                    law: KineticFriction | None = None) -> Located:
    """β where the stable fixed point (left of the kink) has slope −1 (Fig. 12, β ≈ 1.7231).

    The default ``bracket`` is searched upward from the discontinuous fold (where that fixed point
    is born at the kink with the left slope in (−1, 0)); other parameters as
    :func:`discontinuous_fold`.
    """
    return _sequence_point("period-doubling", bracket, V, alpha, gamma, delta, stepper, law)


def border_collision(bracket=None, V=0.25, alpha=1.2, gamma=None, delta=None, stepper=None, *,
                     law: KineticFriction | None = None) -> Located:
    """β where the period-2 orbit reaches the kink: f²(d_k) = d_k (Fig. 12/14, β ≈ 1.7236).

    The default ``bracket`` is searched upward from the period doubling (where the period-2 orbit
    is born); other parameters as :func:`discontinuous_fold`.
    """
    return _sequence_point("border-collision", bracket, V, alpha, gamma, delta, stepper, law)


def boundary_crisis(bracket=None, V=0.25, alpha=1.2, gamma=None, delta=None, stepper=None, *,
                    law: KineticFriction | None = None) -> Located:
    """β where the chaotic attractor born at the border collision touches the unstable
    period-1 point u (right of the kink) and disappears (Fig. 12, tick label ≈ 1.7280).

    f has a minimum at the kink d_k, so the attractor is the interval [f(d_k), f²(d_k)];
    it collides with u when f²(d_k) = u: H(β) = f²(d_k) − u.  The default ``bracket`` is
    searched upward from the border collision; other parameters as :func:`discontinuous_fold`.
    """
    return _sequence_point("crisis", bracket, V, alpha, gamma, delta, stepper, law)


def grazing_sliding(bracket=None, V=0.25, alpha=1.2, gamma=None, delta=None, stepper=None,
                    d0: float | None = None, *, law: KineticFriction | None = None) -> Located:
    """β* of Fig. 15: a period-2 orbit of the map passes through the kink d_k, i.e. one of its
    slip phases of block 1 (the first with both blocks slipping) grazes block 1's sticking region
    (max r₁ = 0 at K₁ = F_s1).

    What the computation shows (the paper's text says block 2): for β > β* that phase
    contains a short stick phase of *block 1* (duration growing like sqrt(β − β*)), for
    β < β* it does not; block 2's stick phases keep their length.  H(β) = max r₁ in that
    phase (continued through r₁ = 0, :func:`kink_function`) at the period-2 point.

    Parameters
    ----------
    bracket : search interval in β.  Default derived from the model: G(β) = f²(d_k) − d_k (zero when
        a period-2 orbit passes through the kink; DOP853 at rtol 1e-8) is scanned upward from the
        border collision (:func:`border_collision`, the previous zero of G, where the first
        period-2 orbit leaves the kink) with steps 10⁻⁴·2ᵏ up to 0.5; its first sign change is a
        root of G (a jump of f is rejected: |G| < 10⁻⁶ at the coarse root), around which H is
        bracketed with widths 10⁻⁶·4ᵏ.  Where the period-2 point does not converge (next to the
        kink f² has a square-root branch on one side) the root is refined on G itself at full
        precision (``details["test"]`` says which).
    V, alpha : belt velocity and inter-block stiffness (Fig. 15: as Fig. 12, 0.25 and 1.2).
    gamma, delta : parameters of the default law, eq. (7) (defaults γ = 3, δ = 0).
    stepper : mode integrator (default DOP853, rtol 1e-11).
    d0 : start of the period-2 point (default: the kink at the bracket's coarse root).
    law : the kinetic law (default eq. (7) with ``gamma``, ``delta``).

    Returns
    -------
    Located
        ``details``: the period-2 point ``d`` (the kink), the grazing block, the bracket.

    Raises
    ------
    NoBifurcationError
        G has no root in the derived range.

    References
    ----------
    U. Galvanetto, J. Sound Vib. 276 (2004) 121–139, Sec. 4.2, Fig. 15.
    """
    law = resolve_kinetic_law(law, gamma, delta)
    warm = _Warm(d0)

    def H(beta):
        p = fig12_params(beta, V, alpha, law=law)
        pp = periodic_point(p, warm.d, 2, stepper)
        warm.d = pp.d
        return kink_function(p, pp.d, stepper)

    coarse = None
    if bracket is None:
        bc = border_collision(None, V, alpha, law=law)
        scan_st = default_stepper(SCAN_RTOL)
        kwarm = _Warm(bc.details["d_kink"])
        G = _kink_test(V, alpha, law, scan_st, kwarm, _period_two_at_kink_test)
        a, b = _chain_scan(G, bc.value, "grazing-sliding (period-2 orbit through the kink)")
        coarse = brentq(G, a, b, xtol=1e-9, rtol=1e-15) if a != b else a
        if not abs(G(coarse)) < 1e-6:
            raise NoBifurcationError(f"grazing-sliding: f²(d_k) − d_k jumps across 0 at beta = {coarse:.8g} "
                                     f"(f is discontinuous there, no orbit grazes); searched beta in "
                                     f"[{bc.value:.8g}, {bc.value + 0.5:.8g}]")
        if d0 is None:
            warm.d = kwarm.d
    try:
        if coarse is not None:
            bracket = _grow_bracket(H, coarse, 1e-6, 1e-2, "grazing-sliding")
        b, res, n, sec = _locate(H, bracket)
        test = "max r1 at the period-2 point"
    except (MapUndefined, IntegratorError, LandauError) as err:
        # the secant for the period-2 point can fail next to the kink, where f² has a square-root
        # branch on one side: the root is then refined on f²(d_k) − d_k itself (the kink at full
        # precision), which needs no periodic point
        if coarse is None:
            raise err
        kwarm = _Warm(warm.d)
        G = _kink_test(V, alpha, law, stepper, kwarm, _period_two_at_kink_test)
        bracket = _grow_bracket(G, coarse, 1e-6, 1e-2, "grazing-sliding")
        b, res, n, sec = _locate(G, bracket)
        warm.d, test = kwarm.d, "f2(d_k) - d_k"
    return Located("grazing-sliding", "beta", b, res, n, sec,
                   {"d": warm.d, "grazing_block": 1, "bracket": tuple(map(float, bracket)), "test": test})
