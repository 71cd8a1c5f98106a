"""Locators for the sliding bifurcations of Galvanetto (2004), Sec. 4.

Each locator reduces the bifurcation to a scalar *test function* H(parameter) that
changes sign at the bifurcation and finds its root with Brent's method (xtol 1e-12 in the
parameter).  H is evaluated on the steady state: the stick–slip cycle of the one block
(determined by the stick end) or a periodic point of the event map f (found by a secant
iteration warm-started from the previous parameter value).

Test functions (r = Ẋ − V, K the spring force, F_s the static level):

* type II sliding: a slip phase with r < 0 ends (r = 0) exactly at the left end of the
  sticking interval: H = min over r = 0 events from r < 0 of (K + F_s);
* type I sliding: a slip phase with r > 0 ends exactly at the right end: H = min over
  r = 0 events from r > 0 of (F_s − K); past it the orbit has no stick phase there, so H
  is continued by a *virtual* orbit that sticks anyway (``stick{i}:p``);
* grazing of the sticking region by a slip phase (the kink of f): the maximum of r in
  that phase, with the stick guard made transparent so that the maximum is a smooth
  function (the virtual orbit continues on the same slip branch through r = 0);
* multi-sliding: the minimum of K₂ + β over a stick phase of block 2 (transparent guard);
* fold / border collision of the map: fⁿ(d_k) − d_k = 0 at the kink d_k(β);
* period doubling: f'(d*) + 1 = 0 at the fixed point (central differences with Richardson
  extrapolation).

Without a ``bracket`` every locator derives its search interval from the model, never from a
published value: the law's weakening velocity (sliding points in V), the Hopf point c₁ (c₂), a β
scan from equal static levels (the fold) and, upward from each bifurcation, the next one of the
Fig. 12 sequence and the grazing-sliding (the next period-2 orbit through the kink), and for the
multi-sliding the periodic windows of the map's attractor in a γ scan over the law's weakening
velocity (10·V down to V), whose orbits are followed in γ.  When the test function does not change
sign there, :class:`NoBifurcationError` names the range searched.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np
from scipy.optimize import brentq

from landau.errors import InputError, IntegratorError, LandauError
from landau.verify.galvanetto.maps import (MapUndefined, d_range, default_stepper, f_n, one_block_cycle,
                                           two_block_map)
from landau.laws.kinetic import KineticFriction, resolve_kinetic_law
from landau.verify.galvanetto.model import K_of, StickSlipParams, _make_rhs, one_block, two_blocks

XTOL = 1e-12


class NoBifurcationError(InputError):
    """The test function of a locator does not change sign in the search range derived from the
    model: the bifurcation does not exist there for these parameters (the message gives the range)."""


@dataclass(frozen=True)
class Located:
    """A located bifurcation: the parameter value and how it was obtained."""

    name: str
    parameter: str
    value: float
    residual: float
    evaluations: int
    seconds: float
    details: dict = field(default_factory=dict)

    def __repr__(self) -> str:
        return (f"Located({self.name}: {self.parameter} = {self.value:.12g}, |H| = {self.residual:.2g}, "
                f"{self.evaluations} evaluations, {self.seconds:.2f} s)")


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
    evs = []
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


# ----------------------------------------------------------------- one block (Sec. 4.1, 4.2)

def one_block_sliding(kind: str, gamma: float | None = None, delta: float | None = None, c: float = 0.0,
                      bracket: tuple[float, float] | None = None, stepper=None, *,
                      law: KineticFriction | None = None) -> Located:
    """Type II (``kind="II"``) or type I (``"I"``) sliding point of the one block, in V.

    The cycle starts at the end of the stick interval (X = F_s − cV, Ẋ = V).  Type II:
    the first return to r = 0 (from r < 0) happens at K = X + cV = −F_s.  Type I: the
    return from r > 0 happens at K = +F_s.  Paper (δ misprinted as 0; δ = 0.2 reproduces them):
    1.241, 10.801.

    Parameters
    ----------
    kind : "II" or "I".
    gamma, delta : parameters of the default law, eq. (7) (defaults γ = 3, δ = 0.2).
    c : viscous damping.
    bracket : search interval in V; default derived from the law: the test function is
        scanned on a logarithmic grid of V from 0.01 to 10⁴ times the law's weakening velocity
        (:meth:`KineticFriction.weakening_velocity`, 1/γ for eq. (7)) — type I from the type II
        point upward, as the r > 0 slip phase is born there.
    stepper : mode integrator (default DOP853, rtol 1e-11).
    law : the kinetic law (default eq. (7) with ``gamma``, ``delta``).

    Returns
    -------
    Located

    References
    ----------
    U. Galvanetto, J. Sound Vib. 276 (2004) 121–139, Sec. 4.1, Fig. 7.
    """
    if kind not in ("II", "I"):
        raise InputError(f"one_block_sliding: kind must be 'II' or 'I', not {kind!r}")
    law = resolve_kinetic_law(law, gamma, delta, default_delta=0.2)
    side = "n" if kind == "II" else "p"

    def H(V):
        p = one_block(V, c=c, law=law)
        sol = one_block_cycle(p, stepper, stop=lambda ev: ev.guard == "r1=0" and ev.from_mode == side)
        if sol.status != "stop":
            return 1.0  # never reaches r = 0 from that side: still before the bifurcation
        return _margins(p, sol.events, side)[-1]

    if bracket is None:
        vs = _velocity_scale(law)
        start = 0.01 * vs if kind == "II" else one_block_sliding("II", c=c, stepper=stepper, law=law).value
        grid = start * 10.0 ** (np.arange(0, 1 + 8 * np.log10(1e4 * vs / start)) / 8)
        bracket = scan_bracket(H, grid, f"one-block type {kind} sliding")
    V, res, n, sec = _locate(H, bracket)
    return Located(f"one-block-type-{kind}", "V", V, res, n, sec,
                   {"gamma": law.gamma, "delta": law.delta, "c": c, "bracket": tuple(map(float, bracket))})


# ----------------------------------------------------------------- two blocks (Sec. 4.1)

class _Warm:
    """Warm start of the periodic point along a parameter sweep."""

    def __init__(self, d0: float):
        self.d = d0


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
                    f"{bracket[1]:.6g}], but the map's attractor at V = {bracket[0]:.6g} is not periodic (period <= 8): "
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
        except (MapUndefined, IntegratorError, InputError):
            warm.d = None
            raise MapUndefined("no kink")
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

    if gamma is not None or bracket is not None:
        start = float(gamma) if bracket is None else float(bracket[0])
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
    ends = {-1: None, +1: None}                      # where a side was lost
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


# ----------------------------------------------------------------- damped one block (Sec. 4.2)

def hopf_c1(V: float = 0.5, gamma: float | None = None, delta: float | None = None, law=None) -> float:
    """c₁ = F_k'(−V): the linearised slip field u'' + (c − F_k'(−V))u' + u = 0 about the
    equilibrium X = F_k(−V) loses its damping.  ``law`` is the kinetic law (default Galvanetto's
    eq. (7) with ``gamma`` = 3, ``delta`` = 0, where c₁ = γ(1 − δ)/(1 + γV)²); the slope is that
    of its r < 0 branch, differentiated symbolically."""
    from landau.verify.galvanetto.smooth import kinetic_law
    return float(kinetic_law(gamma, delta, law).dneg(-V))


def hopf_c1_normal_form(V: float = 0.5, gamma: float | None = None, delta: float | None = None, law=None):
    """The damped one block's Hopf point c₁ located by the landau engine (:mod:`landau.derivation.general`) on
    the smooth slip field of the kinetic law ``law`` (default eq. (7) with ``gamma``, ``delta``),
    with its amplitude equation: Λ > 0 means subcritical (an unstable cycle for c > c₁ whose
    displacement amplitude is C·sqrt(c − c₁))."""
    from landau.derivation.general import hopf_normal_form
    from landau.verify.galvanetto.smooth import damped_slip_system, kinetic_law

    law = kinetic_law(gamma, delta, law)
    c1 = hopf_c1(V, law=law)
    return hopf_normal_form(damped_slip_system(V, law=law), {"V": V, "gamma": law.gamma, "delta": law.delta},
                            (0.5 * c1, 1.5 * c1))


def nonsmooth_fold_c2(V: float = 0.5, gamma: float | None = None, delta: float | None = None,
                      bracket: tuple[float, float] | None = None, stepper=None, *,
                      law: KineticFriction | None = None) -> Located:
    """c₂: the unstable cycle of the smooth slip field touches the stick line Ẋ = V at the
    stick end X = F_s − cV (Fig. 10c), where stick–slip and slip–stick transitions merge.

    The unstable cycle attracts in *backward* time, so from the stick end (X = F_s − cV,
    Ẋ = V, a velocity maximum of the slip field) the r < 0 slip field is integrated backward
    to its previous velocity maximum: H(c) = r there.  c < c₂: the point lies outside the
    cycle, the backward orbit shrinks onto it, H < 0; c > c₂: inside, H > 0.  H is smooth
    and bounded (the backward orbit never leaves the cycle's neighbourhood).

    Parameters
    ----------
    V : belt velocity.
    gamma, delta : parameters of the default law, eq. (7) (defaults γ = 3, δ = 0).
    bracket : search interval in c; default derived from the Hopf point c₁ = F_k'(−V) (the
        unstable cycle is born there): H is scanned on a logarithmic grid of c − c₁ from
        10⁻⁴ c₁ to 10² c₁.
    stepper : mode integrator (default DOP853, rtol 1e-11).
    law : the kinetic law (default eq. (7) with ``gamma``, ``delta``).

    Returns
    -------
    Located

    Raises
    ------
    NoHopfError
        c₁ ≤ 0: the law does not weaken at r = −V, steady sliding has no Hopf point.

    References
    ----------
    U. Galvanetto, J. Sound Vib. 276 (2004) 121–139, Sec. 4.2, Fig. 10.
    """
    from landau.errors import NoHopfError
    from landau.verify.hybrid import Guard, HybridModel, Mode, simulate
    from landau.verify.hybrid.simulate import EngineOptions
    law = resolve_kinetic_law(law, gamma, delta)
    c1 = hopf_c1(V, law=law)
    if not c1 > 0:
        raise NoHopfError(f"F_k'(-V) = {c1:.6g} <= 0 at V = {V:g}: no Hopf point c1 > 0 for {law!r}")
    st = stepper or default_stepper()

    def H(c):
        slip = _make_rhs(one_block(V, c=c, law=law), "n")   # the r < 0 slip field of the model
        back = lambda t, y: -slip(t, y)
        model = HybridModel.from_modes(Mode("slip-back", back, (Guard("vmax", lambda t, y: -slip(t, y)[1]),)))
        sol = simulate(model, "slip-back", [1.0 - c * V, V], (0.0, 100.0), st, EngineOptions(record=False),
                       stop=lambda ev: ev.guard == "vmax")
        if sol.status != "stop":
            raise MapUndefined("no velocity maximum in backward time")
        return float(sol.y[1] - V)

    if bracket is None:
        bracket = scan_bracket(H, c1 * (1.0 + 10.0 ** (np.arange(-16, 9) / 4)), "non-smooth fold c2")
    c, res, n, sec = _locate(H, bracket)
    return Located("one-block-c2", "c", c, res, n, sec, {"c1": c1, "bracket": tuple(map(float, bracket))})
