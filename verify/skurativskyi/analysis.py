"""Analysis of eq. (1) (Skurativskyi et al. 2019): attractors at one ω, impact counting,
first detachment, continuation sweeps in ω, grazing location, Lyapunov exponent, Tsallis q.

Conventions (as in the paper):
* Poincaré section: x at t = 2πi/ω (Sec. 4, Fig. 3a);
* impacts: crossings of x = x_I with increasing x; T_j = inter-impact intervals (Fig. 3b);
* sweeps: 100 forcing periods of transient at the first ω and 50 after each step of ω, the
  attractor continued from the previous ω (warm start), for increasing ("up") and
  decreasing ("down") ω (Sec. 4, caption of Fig. 5);
* top Lyapunov exponent: one tangent vector of the variational equation, renormalised every
  forcing period (Sec. 4, Fig. 5); no saltation correction is needed (continuous field at
  both switching surfaces, see :mod:`landau.verify.skurativskyi.model`);
* Tsallis index q: maximiser of the redundancy R_T(q) = 1 − S_T/S_T,max of the normalised
  T_j histogram on (0.05, 0.3) s with bins of 0.001 s, empty bins dropped (Sec. 4, Fig. 6).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

from landau.errors import InputError
from landau.verify.hybrid.analysis import Located
from landau.verify.skurativskyi.model import PAPER, Params
from landau.verify.skurativskyi.simulate import ATOL, RTOL, run


@dataclass(frozen=True)
class Attractor:
    """The attractor reached at one ω: section points, inter-impact intervals, impacts per
    forcing period, the state at the last section point (phase ωt ≡ 0: warm start for the
    next ω) and, if computed, the top Lyapunov exponent [1/s]."""

    omega: float
    x_section: np.ndarray
    intervals: np.ndarray
    impact_times: np.ndarray
    impacts_per_period: float
    y_end: np.ndarray
    lyapunov: float = float("nan")
    periods: int = 0

    def __repr__(self) -> str:
        ly = "" if np.isnan(self.lyapunov) else f", λ₁={self.lyapunov:.4g}/s"
        return (f"Attractor(ω={self.omega:.6g}, {self.impacts_per_period:.4g} impacts/period, "
                f"{len(np.unique(np.round(self.x_section, 7)))} distinct section points (0.1 µm){ly})")

    def to_json(self) -> dict:
        return {"omega": self.omega, "x_section": self.x_section.tolist(), "intervals": self.intervals.tolist(),
                "impacts_per_period": self.impacts_per_period, "y_end": self.y_end.tolist(),
                "lyapunov": None if np.isnan(self.lyapunov) else self.lyapunov, "periods": self.periods}

    @classmethod
    def from_json(cls, d: dict) -> "Attractor":
        return cls(d["omega"], np.array(d["x_section"]), np.array(d["intervals"]), np.empty(0),
                   d["impacts_per_period"], np.array(d["y_end"]),
                   float("nan") if d.get("lyapunov") is None else d["lyapunov"], d.get("periods", 0))


def attractor(omega: float, y0=None, n_transient: int = 100, n_keep: int = 50, params: Params = PAPER,
              rtol: float = RTOL, atol=ATOL, lyapunov: bool = False) -> Attractor:
    """Discard ``n_transient`` periods from y0 (phase 0; default rest at X₀), then record
    ``n_keep`` periods (with the tangent vector if ``lyapunov``)."""
    if n_keep < 1 or n_transient < 0:
        raise InputError("need n_keep >= 1 and n_transient >= 0")
    p = params.with_(omega=omega)
    y = None if y0 is None else np.asarray(y0, float)[:2]
    if n_transient:
        y = run(p, n_transient, y, rtol=rtol, atol=atol, strobe=False).y_final[:2]
    r = run(p, n_keep, y, rtol=rtol, atol=atol, lyapunov=lyapunov)
    xs = r.strobe_y[1:, 0]  # section points after the start point
    return Attractor(float(omega), xs, r.intervals, r.impacts, len(r.impacts) / n_keep, r.y_final[:2].copy(),
                     r.lyapunov if lyapunov else float("nan"), n_keep)


# --------------------------------------------------------------------------- first detachment
def detaches(omega: float, params: Params = PAPER, n_transient: int = 60, n_keep: int = 20,
             rtol: float = RTOL) -> bool:
    """True when the attractor reached from rest leaves the obstacle (x < x_I) at ω."""
    p = params.with_(omega=omega)
    y = run(p, n_transient, None, rtol=rtol, strobe=False).y_final[:2]
    r = run(p, n_keep, y, rtol=rtol, strobe=False)
    return len(r.detachments) > 0


def bisect(pred, lo: float, hi: float, tol: float, what: str = "") -> Located:
    """Bisection in ω on a boolean predicate with pred(lo) != pred(hi); ``lo`` > ``hi`` is allowed
    (the bracket keeps ``lo`` on the side where the predicate has its ``lo`` value).

    Returns
    -------
    Located
        ``name`` = ``what``, parameter ``"omega"``, the final bracket ``lo``/``hi`` and its midpoint
        as ``value``; ``evaluations`` counts the runs (residual NaN: a yes/no property)."""
    plo, phi = pred(lo), pred(hi)
    n = 2
    if plo == phi:
        raise InputError(f"{what}: the property does not change on [{lo}, {hi}] (both {plo})")
    while abs(hi - lo) > tol:
        mid = 0.5 * (lo + hi)
        pm = pred(mid)
        n += 1
        if pm == plo:
            lo = mid
        else:
            hi = mid
    return Located(what, "omega", 0.5 * (lo + hi), math.nan, n, lo=lo, hi=hi)


def first_detachment(lo: float = 14.0, hi: float = 14.1, tol: float = 1e-3, params: Params = PAPER,
                     rtol: float = RTOL) -> Located:
    """First ω at which the cart leaves the obstacle (impact adding starts; paper: between
    14.0 and 14.1 rad/s, Sec. 5, Fig. 8)."""
    return bisect(lambda w: detaches(w, params, rtol=rtol), lo, hi, tol, "first detachment")


def impacts_per_period(omega: float, params: Params = PAPER, n_transient: int = 100, n_keep: int = 20,
                       y0=None, rtol: float = RTOL) -> float:
    return attractor(omega, y0, n_transient, n_keep, params, rtol).impacts_per_period


# --------------------------------------------------------------------------- sweeps
def continuation(omegas, y0=None, n_first: int = 100, n_step: int = 50, n_keep: int = 50,
                 params: Params = PAPER, rtol: float = RTOL, lyapunov: bool = False,
                 on_point=None) -> list[Attractor]:
    """Attractors along ``omegas`` (in the given order), each warm-started from the previous
    one: ``n_first`` transient periods at the first ω, ``n_step`` after each change."""
    out: list[Attractor] = []
    y = y0
    for i, w in enumerate(omegas):
        a = attractor(float(w), y, n_first if i == 0 else n_step, n_keep, params, rtol, lyapunov=lyapunov)
        y = a.y_end
        out.append(a)
        if on_point is not None:
            on_point(a)
    return out


# --------------------------------------------------------------------------- grazing
def locate_grazing(lo: float, hi: float, y_lo, tol: float = 1e-4, params: Params = PAPER, rtol: float = RTOL,
                   n_transient: int = 150, n_keep: int = 40) -> Located:
    """A change of the number of impacts per forcing period between lo and hi (a grazing
    bifurcation adds or removes an impact), by bisection; every run starts from ``y_lo`` (the
    attractor at lo, phase 0) so the same branch is followed."""
    cache = {}

    def count(w):
        if w not in cache:
            cache[w] = attractor(w, y_lo, n_transient, n_keep, params, rtol).impacts_per_period
        return cache[w]

    c_lo = count(lo)
    return bisect(lambda w: abs(count(w) - c_lo) < 1e-9, lo, hi, tol, "impacts/period change")


# --------------------------------------------------------------------------- Lyapunov
def lyapunov_exponent(omega: float, y0=None, n_transient: int = 100, n_periods: int = 1000,
                      params: Params = PAPER, rtol: float = RTOL) -> float:
    """Top Lyapunov exponent [1/s] over ``n_periods`` after the transient (paper: 10³)."""
    return attractor(omega, y0, n_transient, n_periods, params, rtol, lyapunov=True).lyapunov


# --------------------------------------------------------------------------- Tsallis q
@dataclass(frozen=True)
class TsallisFit:
    """Entropy index q (maximiser of R_T) with the histogram it came from."""

    q: float
    redundancy: float
    probabilities: np.ndarray
    n_states: int
    n_samples: int

    def __repr__(self) -> str:
        return f"TsallisFit(q={self.q:.4g}, R_T={self.redundancy:.4g}, N={self.n_states}, {self.n_samples} T_j)"


def redundancy(q: float, p: np.ndarray) -> float:
    """R_T(q) = 1 − S_T/S_T,max with S_T = (1 − Σ p_i^q)/(q − 1), S_max = (1 − N^{1−q})/(q − 1)."""
    N = len(p)
    if abs(q - 1) < 1e-9:  # Shannon limit
        return 1 - (-np.sum(p * np.log(p))) / np.log(N)
    return 1 - (1 - np.sum(p ** q)) / (1 - N ** (1 - q))


def tsallis_q(intervals, lo: float = 0.05, hi: float = 0.3, width: float = 0.001,
              q_range=(0.05, 5.0)) -> TsallisFit:
    """Sec. 4: normalised histogram of T_j on (lo, hi) with bins ``width``; zero bins dropped;
    q = argmax R_T(q)."""
    T = np.asarray(intervals, float)
    T = T[(T > lo) & (T < hi)]
    if len(T) < 10:
        raise InputError(f"Tsallis q needs at least 10 inter-impact intervals in ({lo}, {hi}) (got {len(T)})")
    counts, _ = np.histogram(T, bins=np.arange(lo, hi + width / 2, width))
    p = counts[counts > 0] / counts.sum()
    if len(p) < 2:
        raise InputError("Tsallis q undefined: all intervals fall in one bin (a periodic attractor)")
    qs = np.linspace(q_range[0], q_range[1], 400)
    r = np.array([redundancy(q, p) for q in qs])
    i = int(np.argmax(r))
    a, b = qs[max(i - 1, 0)], qs[min(i + 1, len(qs) - 1)]
    res = minimize_scalar(lambda q: -redundancy(q, p), bounds=(a, b), method="bounded", options={"xatol": 1e-8})
    return TsallisFit(float(res.x), float(-res.fun), p, len(p), len(T))


# --------------------------------------------------------------------------- period doubling
def section_period(a: Attractor, tol: float = 1e-8, max_period: int = 16) -> int:
    """Period of the stroboscopic sequence (smallest p with |x_{i+p} − x_i| < tol for all i),
    or 0 if none up to ``max_period`` (chaotic or not settled)."""
    xs = a.x_section
    for p in range(1, min(max_period, len(xs) // 2) + 1):
        if np.all(np.abs(xs[p:] - xs[:-p]) < tol):
            return p
    return 0


def is_doubled(a: Attractor, tol: float = 1e-7) -> bool:
    """Period-2 alternation of the section that persists: |x_{i+1} − x_i| above ``tol`` and
    not decaying over the window (tol = 0.1 µm: above integration noise, far below the period-2
    amplitude 1e-5 m at 1e-4 rad/s past the doubling; below a doubling the alternation decays like |μ|ⁿ with the
    multiplier μ → −1, above it settles on the period-2 amplitude)."""
    d = np.abs(np.diff(a.x_section))
    k = max(3, len(d) // 5)
    return bool(d[-k:].mean() > tol and d[-k:].mean() >= 0.8 * d[:k].mean())


def locate_period_doubling(lo: float, hi: float, y_lo, tol: float = 1e-4, params: Params = PAPER,
                           rtol: float = RTOL, n_transient: int = 200, n_keep: int = 100) -> Located:
    """ω of a period doubling between lo (not doubled) and hi (doubled), by bisection on
    :func:`is_doubled`, every run from the attractor ``y_lo`` at lo."""
    return bisect(lambda w: not is_doubled(attractor(w, y_lo, n_transient, n_keep, params, rtol)), lo, hi, tol,
                  "period doubling")


# --------------------------------------------------------------------------- entering a window
@dataclass(frozen=True)
class WindowEntry:
    """The first ω of an up-sweep whose attractor is a given periodic orbit, with the grid point
    one fine step below it (:func:`sweep_to_window`).

    ``orbit_omega``: first grid ω where the attractor has section period ``period`` and
    ``impacts`` impacts per ``period`` forcing periods; ``gone_omega`` = orbit_omega − step, where
    it has not; ``y_orbit``: state at phase 0 on the attractor at orbit_omega (warm start for a
    continuation of that orbit); ``gone_period``: section period at gone_omega (0: aperiodic up
    to ``n_keep``/2 — the sweep leaves a chaotic band there); ``start``: first ω of the sweep;
    ``points``: attractors computed, ``periods``: forcing periods integrated; ``path``: (ω,
    section period, impacts per period) of every point the sweep kept, in sweep order."""

    orbit_omega: float
    gone_omega: float
    y_orbit: np.ndarray
    gone_period: int
    period: int
    impacts: int
    start: float
    step: float
    points: int
    periods: int
    path: tuple

    def __repr__(self) -> str:
        came = "chaos" if self.gone_period == 0 else f"a period-{self.gone_period} attractor"
        return (f"WindowEntry(period-{self.period} orbit with {self.impacts} impacts from ω = {self.orbit_omega:.6g}, "
                f"{came} at {self.gone_omega:.6g}; sweep from {self.start:.6g} in steps ≥ {self.step:g}: "
                f"{self.points} attractors, {self.periods} periods)")


def sweep_to_window(start: float, period: int = 7, impacts: int = 14, params: Params = PAPER, rtol: float = RTOL,
                    step: float = 0.0025, max_stride: int = 32, settle: int = 3, n_first: int = 100, n_step: int = 50,
                    n_keep: int | None = None, stop: float | None = None, section_tol: float = 1e-6,
                    y0=None) -> WindowEntry:
    """Continue the attractor upward in ω from ``start`` until it enters a periodic orbit of
    section period ``period`` with ``impacts`` impacts per ``period`` forcing periods (the first
    point with that signature after one without it: a sweep that starts on such an orbit first
    leaves it, so a sweep resumed from a window's orbit finds the next window).

    Every ω is a multiple of ``step`` (the grid does not depend on ``start``).  The sweep moves
    one ``step`` at a time, except along a settled periodic orbit (the last ``settle`` points
    kept have the same section period and impact count), where the stride doubles at each point
    up to ``max_stride`` steps; a stride > 1 that lands on another attractor is discarded and
    tried again at half the stride from the last point kept.  A change of the attractor — in
    particular the entry into the window — is thus only ever accepted across a single step and
    is resolved to ``step``, while the long stretches of period-1 orbits (impact adding,
    Skurativskyi et al. 2019, Sec. 5) cost a few points each.  A window narrower than ``step``
    on the sweep can be missed, and so could one that opens and closes between two points of
    the same settled orbit (a stride skips only stretches that begin and end on it).

    Each point: ``n_step`` transient periods from the previous attractor (``n_first`` at the first
    point, from ``y0`` — a state at phase 0 — or from rest at X₀), then ``n_keep`` observed periods (default
    4·``period``, a multiple of
    the period; the section period is searched up to ``n_keep``/2 with ``section_tol`` [m]) —
    the paper's sweep protocol (100 / 50 transient periods, Sec. 4).

    Raises :class:`~landau.errors.InputError` when the window is not met below ``stop`` (default
    2·start); when, after a settled orbit with two or more impacts per period, the sweep settles
    on the single-impact period-1 orbit (the impact count has come down through the whole
    grazing cascade, Fig. 3b, without meeting the window)."""
    if not (step > 0 and start > 0 and period >= 1 and impacts >= 1 and max_stride >= 1 and settle >= 1):
        raise InputError("sweep_to_window needs start > 0, step > 0, and period, impacts, max_stride, settle >= 1")
    n_keep = 4 * period if n_keep is None else int(n_keep)
    if n_keep < 2 * period or n_keep % period:
        raise InputError(f"n_keep must be a multiple of the period >= 2 * period (got {n_keep})")
    stop = 2.0 * start if stop is None else float(stop)
    grid = lambda j: round(j * step, 10)       # decimal grid: the same floats whatever the start
    j0 = int(np.floor(start / step + 1e-9))
    target = (period, impacts * n_keep // period)

    def signature(a: Attractor) -> tuple[int, int]:
        return section_period(a, section_tol, n_keep // 2), int(round(a.impacts_per_period * n_keep))

    a = attractor(grid(j0), y0, n_first, n_keep, params, rtol)
    kept = [(j0, a.y_end, signature(a))]       # (grid index, state at phase 0, signature)
    points, periods = 1, n_first + n_keep
    stride, many = 1, False                    # many: a settled orbit with >= 2 impacts per period was passed
    while True:
        j, y, sig0 = kept[-1]
        if grid(j + stride) > stop:
            raise InputError(f"no period-{period} attractor with {impacts} impacts on the up-sweep from ω = "
                             f"{grid(j0)} to {stop:g} rad/s (steps of {step:g})")
        a = attractor(grid(j + stride), y, n_step, n_keep, params, rtol)
        points, periods = points + 1, periods + n_step + n_keep
        sig = signature(a)
        if stride > 1 and sig != sig0:
            stride //= 2                       # the attractor changed inside the stride: try half of it
            continue
        kept.append((j + stride, a.y_end, sig))
        if sig == target and kept[-2][2] != target:
            prev = kept[-2]
            path = tuple((grid(i), s[0], s[1] / n_keep) for i, _, s in kept)
            return WindowEntry(grid(j + stride), grid(prev[0]), a.y_end.copy(), prev[2][0], period, impacts,
                               grid(j0), step, points, periods, path)
        settled = len(kept) >= settle and len({s for _, _, s in kept[-settle:]}) == 1 and sig[0] > 0
        if settled:
            if sig[1] >= 2 * n_keep:
                many = True
            elif many and sig == (1, n_keep):
                raise InputError(f"the up-sweep from ω = {grid(j0)} settled on the single-impact period-1 orbit at "
                                 f"ω = {grid(j + stride)} without meeting a period-{period} window with {impacts} "
                                 "impacts")
        stride = min(2 * stride, max_stride) if settled else 1
