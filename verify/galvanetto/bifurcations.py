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
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np
from scipy.optimize import brentq

from landau.errors import InputError, IntegratorError, LandauError
from landau.verify.galvanetto.maps import (MapUndefined, default_stepper, f_n, one_block_cycle, two_block_map)
from landau.laws.kinetic import KineticFriction, resolve_kinetic_law
from landau.verify.galvanetto.model import K_of, StickSlipParams, _make_rhs, one_block, two_blocks

XTOL = 1e-12


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
    InputError
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
    raise InputError(f"{what}: the test function does not change sign for the parameter in "
                     f"[{float(grid[0]):.6g}, {float(grid[-1]):.6g}]; the bifurcation is not in that range "
                     "for these parameters (give a bracket)")


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


def two_block_sliding(kind: str, alpha: float = 1.2, beta: float = 1.3, gamma: float | None = None,
                      delta: float | None = None, bracket: tuple[float, float] = (0.18, 0.19),
                      period: int = 2, d0: float | None = None, stepper=None, *,
                      law: KineticFriction | None = None) -> Located:
    """Type II / type I sliding point of the two blocks in V (Figs 8, 9).

    H is evaluated on the stable periodic point of f^period (warm-started); for type I the
    blocks are made to stick virtually at r = 0 from r > 0 so that the map stays defined
    past the bifurcation (where the g.s.p. disappears).
    """
    law = resolve_kinetic_law(law, gamma, delta)
    side = "n" if kind == "II" else "p"
    virt = frozenset() if kind == "II" else frozenset({"stick1:p", "stick2:p"})
    p0 = two_blocks(bracket[0], alpha, beta, law=law)
    if d0 is None:
        d = 0.0
        for _ in range(80):
            d = f_n(p0, d, 1, stepper, virt)
        d0 = d
    warm = _Warm(d0)

    def H(V):
        p = two_blocks(V, alpha, beta, law=law)
        pp = periodic_point(p, warm.d, period, stepper, transparent=virt)
        warm.d = pp.d
        return min(_margins(p, orbit_events(p, pp.d, period, stepper, transparent=virt), side))

    V, res, n, sec = _root(H, *bracket)
    return Located(f"two-block-type-{kind}", "V", V, res, n, sec,
                   {"alpha": alpha, "beta": beta, "gamma": law.gamma, "delta": law.delta, "d": warm.d, "period": period})


# ----------------------------------------------------------------- map bifurcations in β (Sec. 4.2)

GRAZE1 = frozenset({"r1=0:n"})


def kink_function(p: StickSlipParams, d: float, stepper=None) -> float:
    """max r₁ in the first slip phase of block 1 with both blocks slipping (r₁ < 0 branch,
    continued through r₁ = 0): zero where the orbit grazes the sticking region of block 1,
    i.e. at the slope discontinuity of f in Figs 13–14."""
    ms = two_block_map(p, d, stepper, sections=True, transparent=GRAZE1,
                       stop=lambda ev: ev.to_mode == "ss" or (ev.guard == "rmax1" and ev.from_mode == "nn"))
    for e in ms.events:
        if e.guard == "rmax1" and e.from_mode == "nn":
            return float(e.y[2] - p.V)
    raise MapUndefined("no r1 maximum in an 'nn' phase")


def kink(p: StickSlipParams, d0: float = -0.096, stepper=None) -> float:
    """The slope-discontinuity point d_k of f (root of :func:`kink_function`, secant)."""
    x0, x1 = d0, d0 + 1e-4
    h0, h1 = kink_function(p, x0, stepper), kink_function(p, x1, stepper)
    for _ in range(40):
        if h1 == h0:
            break
        x0, h0, x1 = x1, h1, x1 - h1 * (x1 - x0) / (h1 - h0)
        h1 = kink_function(p, x1, stepper)
        if abs(x1 - x0) < 1e-15 or h1 == 0:
            break
    return x1


def fig12_params(beta: float, V: float = 0.25, alpha: float = 1.2, gamma: float | None = None,
                 delta: float | None = None, *, law: KineticFriction | None = None) -> StickSlipParams:
    """The two blocks of Fig. 12 (V = 0.25, α = 1.2, eq. (7) with γ = 3, δ = 0) at static level β."""
    return two_blocks(V, alpha, beta, gamma, delta, law=law)


def discontinuous_fold(bracket=(1.7210, 1.7225), V=0.25, alpha=1.2, gamma=None, delta=None, stepper=None, *,
                law: KineticFriction | None = None) -> Located:
    """β where a fixed point of f sits at the kink: f(d_k) = d_k (Fig. 12, β ≈ 1.7217)."""
    warm = _Warm(-0.096)

    law = resolve_kinetic_law(law, gamma, delta)
    def H(beta):
        p = fig12_params(beta, V, alpha, law=law)
        warm.d = kink(p, warm.d, stepper)
        return f_n(p, warm.d, 1, stepper) - warm.d

    b, res, n, sec = _root(H, *bracket)
    return Located("fold", "beta", b, res, n, sec, {"d_kink": warm.d})


def period_doubling(bracket=(1.7225, 1.7235), V=0.25, alpha=1.2, gamma=None, delta=None, stepper=None, *,
                law: KineticFriction | None = None) -> Located:
    """β where the stable fixed point (left of the kink) has slope −1 (Fig. 12, β ≈ 1.7231)."""
    warm = _Warm(-0.0975)

    law = resolve_kinetic_law(law, gamma, delta)
    def H(beta):
        p = fig12_params(beta, V, alpha, law=law)
        dk = kink(p, -0.096, stepper)
        pp = periodic_point(p, warm.d, 1, stepper, bracket=(dk - 0.004, dk - 1e-9))
        warm.d = pp.d
        return map_slope(p, pp.d, 1, stepper, h=min(2e-5, (dk - pp.d) / 3)) + 1.0

    b, res, n, sec = _root(H, *bracket)
    return Located("period-doubling", "beta", b, res, n, sec, {"d_fixed": warm.d})


def border_collision(bracket=(1.7233, 1.7239), V=0.25, alpha=1.2, gamma=None, delta=None, stepper=None, *,
                law: KineticFriction | None = None) -> Located:
    """β where the period-2 orbit reaches the kink: f²(d_k) = d_k (Fig. 12/14, β ≈ 1.7236)."""
    warm = _Warm(-0.096)

    law = resolve_kinetic_law(law, gamma, delta)
    def H(beta):
        p = fig12_params(beta, V, alpha, law=law)
        warm.d = kink(p, warm.d, stepper)
        return f_n(p, warm.d, 2, stepper) - warm.d

    b, res, n, sec = _root(H, *bracket)
    return Located("border-collision", "beta", b, res, n, sec, {"d_kink": warm.d})


def boundary_crisis(bracket=(1.7280, 1.7295), V=0.25, alpha=1.2, gamma=None, delta=None, stepper=None, *,
                law: KineticFriction | None = None) -> Located:
    """β where the chaotic attractor born at the border collision touches the unstable
    period-1 point u (right of the kink) and disappears (Fig. 12, tick label ≈ 1.7280).

    f has a minimum at the kink d_k, so the attractor is the interval [f(d_k), f²(d_k)];
    it collides with u when f²(d_k) = u: H(β) = f²(d_k) − u.
    """
    warm = _Warm(-0.095)

    law = resolve_kinetic_law(law, gamma, delta)
    def H(beta):
        p = fig12_params(beta, V, alpha, law=law)
        warm.d = dk = kink(p, warm.d, stepper)
        u = periodic_point(p, 0.0, 1, stepper, bracket=(dk + 1e-10, dk + 0.004)).d
        return f_n(p, dk, 2, stepper) - u

    b, res, n, sec = _root(H, *bracket)
    return Located("crisis", "beta", b, res, n, sec, {"d_kink": warm.d})


def grazing_sliding(bracket=(1.7652, 1.7656), V=0.25, alpha=1.2, gamma=None, delta=None, stepper=None,
                    d0: float = -0.0858, *, law: KineticFriction | None = None) -> Located:
    """β* of Fig. 15: on the period-2 attractor, the slip phase of block 1 that follows the
    start of block 2's slip grazes block 1's sticking region (max r₁ = 0 at K₁ = F_s1).

    What the computation shows (the paper's text says block 2): for β > β* that phase
    contains a short stick phase of *block 1* (duration growing like sqrt(β − β*)), for
    β < β* it does not; block 2's stick phases keep their length.  H(β) = max r₁ in that
    phase (continued through r₁ = 0, :func:`kink_function`) at the period-2 point.
    """
    warm = _Warm(d0)

    law = resolve_kinetic_law(law, gamma, delta)
    def H(beta):
        p = fig12_params(beta, V, alpha, law=law)
        pp = periodic_point(p, warm.d, 2, stepper)
        warm.d = pp.d
        return kink_function(p, pp.d, stepper)

    b, res, n, sec = _root(H, *bracket)
    return Located("grazing-sliding", "beta", b, res, n, sec, {"d": warm.d, "grazing_block": 1})


def multi_sliding(bracket=(10.745, 10.756), V=0.05, alpha=1.2, beta=2.0, delta=None, stepper=None,
                  d0: float = 0.19664, *,
                  law: KineticFriction | None = None) -> Located:
    """γ of Fig. 16: during a stick phase of block 2 (block 1 slipping with r₁ > 0) the
    minimum of K₂ touches −β, so a slip phase of block 2 with r₂ > 0 is born from the stick
    phase.  H = min K₂ + β in that stick phase (guard made transparent to continue it)."""
    law = resolve_kinetic_law(law, None, delta)
    warm = _Warm(d0)
    virt = frozenset({"K2=-Fs"})

    def H(gamma):
        p = two_blocks(V, alpha, beta, law=replace(law, gamma=float(gamma)))
        pp = periodic_point(p, warm.d, 2, stepper)
        warm.d = pp.d
        d = pp.d
        for _ in range(2):
            ms = two_block_map(p, d, stepper, sections=True, transparent=virt)
            mins = [K_of(p, e.y)[1] + p.beta for e in ms.events if e.guard == "Kmin2" and e.from_mode == "ps"]
            if mins:
                return min(mins)
            d = ms.d1
        raise MapUndefined("no stick phase of block 2 during an r1 > 0 slip")

    g, res, n, sec = _root(H, *bracket)
    return Located("multi-sliding", "gamma", g, res, n, sec, {"d": warm.d})


# ----------------------------------------------------------------- damped one block (Sec. 4.2)

def hopf_c1(V: float = 0.5, gamma: float | None = None, delta: float | None = None, law=None) -> float:
    """c₁ = F_k'(−V): the linearised slip field u'' + (c − F_k'(−V))u' + u = 0 about the
    equilibrium X = F_k(−V) loses its damping.  ``law`` is the kinetic law (default Galvanetto's
    eq. (7) with ``gamma`` = 3, ``delta`` = 0, where c₁ = γ(1 − δ)/(1 + γV)²); the slope is that
    of its r < 0 branch, differentiated symbolically."""
    from landau.verify.galvanetto.smooth import kinetic_law
    return float(kinetic_law(gamma, delta, law).dneg(-V))


def hopf_c1_normal_form(V: float = 0.5, gamma: float | None = None, delta: float | None = None, law=None):
    """The damped one block's Hopf point c₁ located by the landau engine (:mod:`landau.general`) on
    the smooth slip field of the kinetic law ``law`` (default eq. (7) with ``gamma``, ``delta``),
    with its amplitude equation: Λ > 0 means subcritical (an unstable cycle for c > c₁ whose
    displacement amplitude is C·sqrt(c − c₁))."""
    from landau.general import hopf_normal_form
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
