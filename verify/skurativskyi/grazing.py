"""Grazing margins of the attractors of eq. (1) (Skurativskyi et al. 2019, Sec. 4, Fig. 3b).

A grazing bifurcation of this impact oscillator is the ω at which a local maximum of x in
free flight (ẋ = 0, x < x_I) reaches the obstacle x = x_I: beyond it that maximum becomes an
impact (a new branch of inter-impact intervals T_j appears in Fig. 3b) — or the reverse.
The impact count per forcing period changes there, but only for a periodic attractor; on a
chaotic attractor (or when an impact is traded for another) the count can stay put.  The
robust signature is the *grazing margin* of the continued periodic orbit

    g(ω) = min over the free-flight maxima x_max of the attractor of (x_I − x_max),

and, for an impact that disappears, the smallest penetration max(x) − x_I.  The field is C¹
across x = x_I (compliant Hertz contact, no velocity jump), so a family of orbits is smooth
in ω through the grazing and the margin vanishes *linearly* (measured: residuals < 1 % of a
straight line over 4e-4 rad/s) — the square-root law of rigid impacts does not apply.
:func:`locate_grazing_margin` brackets the point by bisection on the impact count and checks
it against the straight-line zero of the margin (they agree to < 1e-4 rad/s at a grazing; a
fold or a crisis would end the orbit with a finite margin).

The other non-smooth surface of eq. (1) is ẋ = 0 (dry friction, regularised over ε = 1e-6
m/s).  :func:`velocity_stops` gives the near-stops of an orbit (extrema of ẋ that do not
reach 0); :func:`locate_friction_grazing` extrapolates their margin min|ẋ| to 0 — the point
where a stick phase is born (it ends the period-3, 4-impact window at ω ≈ 23.0637).

Sampling: the fast path :func:`landau.verify.skurativskyi.simulate.run` advanced in chunks of
P/N (P = 2π/ω) — every chunk integrated with the exact contact switching —; each interval
where ẋ changes sign from + to − is re-integrated in finer chunks and the maximum taken on
the cubic Hermite interpolant of (x, ẋ) there (error ~ h⁴ x⁗/384).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from landau.errors import InputError
from landau.verify.skurativskyi.model import PAPER, Params
from landau.verify.skurativskyi.simulate import RTOL, run


@dataclass(frozen=True)
class Maxima:
    """Local maxima of x(t) over an observed window of the attractor at ω.

    ``t``, ``x``: times [s] and values [m] of every local maximum (ẋ: + → −); ``impacting``:
    whether the maximum lies in contact (x ≥ x_I, i.e. it belongs to an impact)."""

    omega: float
    xI: float
    t: np.ndarray
    x: np.ndarray
    impacting: np.ndarray
    n_periods: int
    impacts_per_period: float
    y_end: np.ndarray

    @property
    def margin(self) -> float:
        """Grazing margin g = min (x_I − x_max) over the free-flight maxima [m] (inf if none)."""
        free = self.x[~self.impacting]
        return float(np.min(self.xI - free)) if len(free) else float("inf")

    @property
    def penetration(self) -> float:
        """Smallest impact penetration min (x_max − x_I) over the impacting maxima [m]."""
        imp = self.x[self.impacting]
        return float(np.min(imp - self.xI)) if len(imp) else float("inf")

    @property
    def signed_closest(self) -> float:
        """x_max − x_I of the maximum closest to the obstacle (< 0: free, ≥ 0: impact)."""
        i = int(np.argmin(np.abs(self.x - self.xI)))
        return float(self.x[i] - self.xI)

    def __repr__(self) -> str:
        return (f"Maxima(ω={self.omega:.6g}, {len(self.x)} maxima over {self.n_periods} periods, "
                f"margin={self.margin * 1e6:.4g} µm, penetration={self.penetration * 1e6:.4g} µm, "
                f"{self.impacts_per_period:.4g} impacts/period)")


def _hermite_max(t0, t1, x0, x1, v0, v1):
    """Maximum of the cubic Hermite interpolant of x on [t0, t1] with slopes v0 > 0 ≥ v1."""
    h = t1 - t0
    # x(s) = a s³ + b s² + c s + d on s ∈ [0, 1]; x'(s)/h = v
    c = v0 * h
    a = 2 * (x0 - x1) + (v0 + v1) * h
    b = 3 * (x1 - x0) - (2 * v0 + v1) * h
    # roots of 3a s² + 2b s + c = 0 in [0, 1] with x'' < 0
    if abs(a) < 1e-300:
        s = -c / (2 * b) if b != 0 else 0.5
    else:
        disc = max(b * b - 3 * a * c, 0.0)
        r = np.sqrt(disc)
        cand = [(-b + r) / (3 * a), (-b - r) / (3 * a)]
        cand = [z for z in cand if -1e-9 <= z <= 1 + 1e-9 and 6 * a * z + 2 * b <= 0]
        s = cand[0] if cand else (0.0 if x0 > x1 else 1.0)
    s = min(max(s, 0.0), 1.0)
    return t0 + s * h, ((a * s + b) * s + c) * s + x0


def _samples(p: Params, y0, n_periods: int, per_period: int, t0: float, rtol: float):
    """States on the grid t0 + i·P/N over n_periods (chunked exact-switching runs) and the
    number of impacts."""
    if n_periods < 1 or per_period < 8:
        raise InputError("need n_periods >= 1 and samples_per_period >= 8")
    P = p.period
    y = np.asarray(y0, float)[:2].copy()
    n = n_periods * per_period
    ts = t0 + np.arange(n + 1) * (P / per_period)
    ys = np.empty((n + 1, 2))
    ys[0] = y
    n_imp = 0
    for i in range(1, n + 1):
        # every chunk starts on the grid (no drift of the sampling phase)
        r = run(p, 1.0 / per_period, y, t0=ts[i - 1], rtol=rtol, strobe=False)
        n_imp += len(r.impacts)
        y = r.y_final[:2].copy()
        ys[i] = y
    return ts, ys, n_imp


def _refined_max(p: Params, t0: float, t1: float, y0, rtol: float, k: int):
    """Max of x on [t0, t1] (ẋ: + → −): re-integrate the interval in k chunks from y0 and take
    the Hermite maximum on the sub-interval where ẋ changes sign (interpolation error / k⁴)."""
    y = np.asarray(y0, float).copy()
    h = (t1 - t0) / k
    for i in range(k):
        r = run(p, h / p.period, y, t0=t0 + i * h, rtol=rtol, strobe=False)
        yn = r.y_final[:2].copy()
        if y[1] > 0 >= yn[1] or i == k - 1:
            return _hermite_max(t0 + i * h, t0 + (i + 1) * h, y[0], yn[0], y[1], yn[1])
        y = yn
    raise AssertionError("unreachable")


def maxima(omega: float, y0, n_periods: int = 40, samples_per_period: int = 200, t0: float = 0.0,
           params: Params = PAPER, rtol: float = RTOL, refine: int = 32) -> Maxima:
    """Local maxima of x over ``n_periods`` forcing periods from the state ``y0`` at phase
    ωt0 (no transient is discarded here: pass a state on the attractor).  Each maximum is
    re-integrated in ``refine`` sub-chunks of its sampling interval (measured against scipy
    DOP853 at rtol 1e-12 on the period-3 orbit at ω = 20.62: free-flight maximum to ~1 nm,
    maxima inside contact — where the oscillation is ~15× faster — to ~0.4 µm without the
    refinement, to the nm level with it)."""
    p = params.with_(omega=omega)
    ts, ys, n_imp = _samples(p, y0, n_periods, samples_per_period, t0, rtol)
    y = ys[-1].copy()
    v = ys[:, 1]
    idx = np.nonzero((v[:-1] > 0) & (v[1:] <= 0))[0]
    tm = np.empty(len(idx))
    xm = np.empty(len(idx))
    for j, i in enumerate(idx):
        tm[j], xm[j] = _refined_max(p, ts[i], ts[i + 1], ys[i], rtol, refine)
    return Maxima(float(omega), p.xI, tm, xm, xm >= p.xI, n_periods, n_imp / n_periods, y)


# --------------------------------------------------------------------------- locating a grazing
@dataclass(frozen=True)
class GrazingPoint:
    """A grazing bifurcation of a periodic attractor, located from the side where it exists.

    ``lo``/``hi``: bisection bracket (on the ``orbit_side`` end the attractor continued from
    the orbit keeps its section period and impact count); ``extrapolated``: root of the
    straight line through s(ω) = x_max − x_I of the free maximum nearest to the obstacle
    (s = −g) or of the shallowest impact, whichever vanishes there, sampled
    within a few tol on the orbit side — an independent estimate: on a smooth family of
    orbits (the field is C¹ across x = x_I) s is smooth in ω and crosses 0 linearly at a
    grazing, whereas at a saddle-node or a crisis the orbit would end with s ≠ 0.
    ``slope`` ds/dω [m/(rad/s)]; ``samples`` (ω, s); ``period`` and ``impacts``: section
    period of the orbit and its impacts per ``period`` forcing periods.  s < 0 on the orbit
    side means a free maximum rises to the obstacle (an impact is added beyond the point);
    s > 0 means the shallowest impact shrinks to zero (an impact is lost)."""

    lo: float
    hi: float
    extrapolated: float
    slope: float
    samples: tuple
    period: int
    impacts: int
    orbit_side: str
    evaluations: int

    @property
    def value(self) -> float:
        return 0.5 * (self.lo + self.hi)

    def root_at_bracket(self, slack: float = 2e-4) -> bool:
        """True when the straight-line zero of s(ω) lies within ``slack`` [rad/s] of the bracket:
        the orbit ends by grazing (s → 0 linearly there).  False when the orbit ends with s ≠ 0
        (a fold, a crisis, a period doubling: the impact count or the section period changes
        without a maximum touching x = x_I)."""
        return self.lo - slack <= self.extrapolated <= self.hi + slack

    @property
    def kind(self) -> str:
        return "impact added" if self.samples[0][1] < 0 else "impact lost"

    def __repr__(self) -> str:
        return (f"GrazingPoint(ω ∈ [{self.lo:.5f}, {self.hi:.5f}], linear root {self.extrapolated:.5f}, "
                f"period-{self.period} orbit with {self.impacts} impacts {self.orbit_side} ({self.kind} "
                f"beyond), ds/dω={self.slope * 1e6:.4g} µm/(rad/s), {self.evaluations} runs)")


#: section points of a period-p orbit repeat to this (m) after the transient; 1 µm is far
#: below the spread of the section points of the orbits here (≥ 0.1 mm) and far above the
#: residual transient (multipliers |μ| ≲ 0.9 per period over 150 periods)
_SECTION_TOL = 1e-6


def _orbit_signature(omega, y, n_transient, n_keep, params, rtol):
    """(section period, impacts in n_keep periods, the maxima) of the attractor from y."""
    from landau.verify.skurativskyi.analysis import attractor, section_period
    a = attractor(omega, y, n_transient, n_keep, params, rtol)
    m = maxima(omega, a.y_end, n_keep, 200, 0.0, params, rtol)
    return section_period(a, _SECTION_TOL, 24), int(round(m.impacts_per_period * n_keep)), m


def locate_grazing_margin(omega_orbit: float, omega_gone: float, y_orbit, tol: float = 1e-4,
                          params: Params = PAPER, rtol: float = RTOL, n_transient: int = 150,
                          n_keep: int = 84, n_fit: int = 4, fit_step: float | None = None) -> GrazingPoint:
    """Grazing of the periodic attractor that exists at ``omega_orbit`` (``y_orbit``: a state
    at phase 0 on or near it) and has changed by ``omega_gone`` (either order of the two).

    Bisection to ``tol`` on "the attractor continued from the orbit keeps its section period
    and its impact count" (every run from the orbit at ``omega_orbit``, so the same branch is
    followed; both sweep directions are covered by choosing the side), then the straight-line
    root of s(ω) — the free margin −g or the shallowest penetration, whichever vanishes at
    the bracket — from ``n_fit`` samples spaced ``fit_step`` (default min(tol, 1e-4)) on the
    orbit side (close, so that the extreme maximum stays the same one: s is kinked where
    another maximum takes over).  ``n_keep`` = 84 observed periods is a multiple of the
    periods 1–4, 6, 7 met here."""
    from landau.verify.skurativskyi.analysis import attractor, bisect, section_period
    if omega_orbit == omega_gone or not tol > 0:
        raise InputError("need omega_orbit != omega_gone and tol > 0")
    ref = attractor(omega_orbit, y_orbit, n_transient, n_keep, params, rtol)
    period = section_period(ref, _SECTION_TOL, 24)
    if period == 0:
        raise InputError(f"the attractor at ω = {omega_orbit} is not periodic (section period > 24 or chaotic)")
    y_ref = ref.y_end
    p_ref, n_ref, _ = _orbit_signature(omega_orbit, y_ref, n_transient, n_keep, params, rtol)

    def same(w):
        p, n, _ = _orbit_signature(w, y_ref, n_transient, n_keep, params, rtol)
        return p == p_ref and n == n_ref

    loc = bisect(same, omega_orbit, omega_gone, tol, f"grazing of the period-{p_ref} orbit of ω = {omega_orbit}")
    a, b = loc.lo, loc.hi                 # a: orbit side
    runs = [loc.evaluations + 2]
    step = np.sign(omega_orbit - omega_gone) * (min(tol, 1e-4) if fit_step is None else fit_step)
    free, pen = [], []
    for i in range(1, n_fit + 1):
        w = a + step * i
        _, _, m = _orbit_signature(w, y_ref, n_transient, n_keep, params, rtol)
        runs[0] += 1
        free.append((float(w), -m.margin))
        pen.append((float(w), m.penetration))
    # the quantity that vanishes here: the free margin (an impact is added beyond the point)
    # or the shallowest penetration (an impact is lost); each is a minimum over maxima, so
    # it is smooth only while the same maximum is the extreme one — take the straight line
    # whose root lies nearest the bracket
    fits = []
    for smp in (free, pen):
        ws, ss = np.array(smp).T
        if np.all(np.isfinite(ss)):
            slope, icpt = np.polyfit(ws, ss, 1)
            fits.append((abs(-icpt / slope - 0.5 * (a + b)), float(-icpt / slope), float(slope), tuple(smp)))
    if not fits:
        raise InputError("no maximum of x next to the grazing point")
    _, root, slope, samples = min(fits)
    side = "above" if omega_orbit > omega_gone else "below"
    return GrazingPoint(min(a, b), max(a, b), root, slope, samples, period,
                        int(round(ref.impacts_per_period * period)), side, runs[0])


# --------------------------------------------------------------------------- friction grazing
@dataclass(frozen=True)
class VelocityStops:
    """Local extrema of ẋ(t) that do not reach ẋ = 0 over an observed window at ω: the
    near-stops of the cart.  When one of them touches 0 the orbit grazes the switching
    surface ẋ = 0 of the dry friction (a stick phase is born): a grazing bifurcation of
    the friction discontinuity, the other non-smooth surface of eq. (1).

    ``v``: the extremal velocities [m/s] (parabolic refinement on the samples); ``x``: where."""

    omega: float
    v: np.ndarray
    x: np.ndarray

    @property
    def margin(self) -> float:
        """min |ẋ| over the near-stops [m/s] (inf if none)."""
        return float(np.min(np.abs(self.v))) if len(self.v) else float("inf")

    def __repr__(self) -> str:
        return f"VelocityStops(ω={self.omega:.6g}, {len(self.v)} near-stops, margin={self.margin * 1e3:.4g} mm/s)"


def velocity_stops(omega: float, y0, n_periods: int = 6, samples_per_period: int = 2000, t0: float = 0.0,
                   params: Params = PAPER, rtol: float = RTOL) -> VelocityStops:
    """Near-stops of the attractor through ``y0`` (phase ωt0) over ``n_periods`` periods."""
    p = params.with_(omega=omega)
    ts, ys, _ = _samples(p, y0, n_periods, samples_per_period, t0, rtol)
    v = ys[:, 1]
    i = np.arange(1, len(v) - 1)
    ext = i[((v[i] - v[i - 1]) * (v[i + 1] - v[i]) <= 0) & (np.sign(v[i - 1]) == np.sign(v[i]))
            & (np.sign(v[i + 1]) == np.sign(v[i])) & (v[i] != 0)]
    # parabola through the three samples around each extremum
    a = 0.5 * (v[ext + 1] - 2 * v[ext] + v[ext - 1])
    b = 0.5 * (v[ext + 1] - v[ext - 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        vext = np.where(a != 0, v[ext] - b * b / (4 * a), v[ext])
    return VelocityStops(float(omega), vext, ys[ext, 0])


@dataclass(frozen=True)
class FrictionGrazing:
    """ω at which the near-stop margin min|ẋ| of a continued orbit vanishes (straight-line
    root through the last ``len(samples)`` points (ω, margin [m/s]) of the continuation)."""

    omega: float
    slope: float
    samples: tuple
    impacts_per_period: float

    def __repr__(self) -> str:
        return (f"FrictionGrazing(ω={self.omega:.5f}, d(min|ẋ|)/dω={self.slope * 1e3:.4g} mm/s per rad/s, "
                f"last sample ω={self.samples[-1][0]:.5f} at {self.samples[-1][1] * 1e3:.3g} mm/s, "
                f"{self.impacts_per_period:.4g} impacts/period)")


def locate_friction_grazing(omegas, y0, n_transient: int = 250, n_fit: int = 4, params: Params = PAPER,
                            rtol: float = RTOL) -> FrictionGrazing:
    """Continue the orbit through ``omegas`` (warm starts, ``n_transient`` periods each) and
    extrapolate min|ẋ| over its near-stops linearly to 0 from the last ``n_fit`` points.
    Raises InputError if the impact count changes along the way (the orbit was lost)."""
    from landau.verify.skurativskyi.analysis import attractor
    if len(omegas) < n_fit or n_fit < 2:
        raise InputError("need at least n_fit >= 2 frequencies")
    y, ipp, smp = y0, None, []
    for w in omegas:
        a = attractor(float(w), y, n_transient, 12, params, rtol)
        if ipp is not None and abs(a.impacts_per_period - ipp) > 1e-9:
            raise InputError(f"the orbit changed at ω = {w} ({ipp:.4g} → {a.impacts_per_period:.4g} impacts/period)")
        ipp, y = a.impacts_per_period, a.y_end
        smp.append((float(w), velocity_stops(float(w), y, 3, 2000, 0.0, params, rtol).margin))
    if ipp is None:
        raise InputError("locate_friction_grazing needs at least one ω to continue the orbit over")
    ws, ms = np.array(smp[-n_fit:]).T
    slope, icpt = np.polyfit(ws, ms, 1)
    return FrictionGrazing(float(-icpt / slope), float(slope), tuple(smp[-n_fit:]), float(ipp))
