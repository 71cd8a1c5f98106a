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

:class:`HermiteScreen` spares most steps that scan: it evaluates the same tests on the
step's cubic Hermite interpolant (free: step ends and vector field there), widened by an
estimate of that interpolant's error, and passes a step only if no value within those
bounds could trigger the scan on the dense output.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


def guard_on_dense(fun, dense):
    """Scalar function s -> g(s, dense(s))."""
    return lambda s: float(fun(s, dense(s)))


def root_new_side(gs, a: float, b: float, xtol: float) -> float:
    """Root of ``gs`` in [a, b] (gs(a) > 0 >= gs(b)), returned on the side gs <= 0."""
    seen: dict[float, float] = {}  # every value once: the dense output is the costly part

    def g(s):
        v = seen.get(s)
        if v is None:
            v = seen[s] = gs(s)
        return v

    if g(b) > 0:  # defensive: caller guarantees the sign change
        return b
    ga = g(a)
    if ga <= 0:
        return a
    from scipy.optimize import brentq

    r = brentq(g, a, b, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=200)
    # Brent returns a point within xtol of the root, on either side; walk to the new side.
    step = max(xtol, 4 * np.finfo(float).eps * abs(r))
    while g(r) > 0 and r < b:
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


class HermiteScreen:
    """Cheap per-step screen: does any guard need the step's dense output at all?

    Building a dense output can cost extra right-hand-side evaluations (three per step for
    DOP853) and Python overhead, yet on most steps every guard stays well clear of zero.  The
    screen samples the guards on the cubic Hermite interpolant of the step instead — built
    from the step ends and the vector field there, which every step already has — and widens
    each sample into an interval that covers the interpolant's error.  Only when some value
    of those intervals could trigger the dense-output scan (:func:`first_crossing`: a sample
    <= 0, or a local minimum within ``dip_factor`` times its rise of zero) is the step
    scanned on the dense output as before, so a step is skipped only if the dense-output
    scan would also have passed it.

    Error of the interpolant: for y with a continuous fourth derivative the cubic Hermite
    interpolant on a step of length h errs by h⁴ s²(1-s)²/24 · y⁽⁴⁾ at the fraction s
    (at most h⁴/384 · |y⁽⁴⁾|).  Its third derivative approximates y''' at the middle of the
    step, so y⁽⁴⁾ is estimated from the change of that third derivative between consecutive
    steps of a phase.  Each guard is evaluated on the samples moved by ``safety`` times that
    error in either direction along every component; the spread of the three values bounds
    the sample's uncertainty.  On the first step of a phase y'' at the start comes from one
    extra evaluation of the vector field and y⁽⁴⁾ from the quartic through the end data.

    Parameters
    ----------
    samples : int
        Interior samples per step (the engine's ``EngineOptions.samples``, >= 1).
    safety : float, optional
        Factor on the estimated interpolation error.
    dip_factor : float, optional
        As in :func:`first_crossing`.

    References
    ----------
    Hairer, E., Nørsett, S. P. and Wanner, G. (1993), *Solving Ordinary Differential
    Equations I*, 2nd ed., Springer, Sec. II.6 (dense output, Hermite interpolation).
    """

    __slots__ = ("s", "safety", "dip_factor", "ya", "fa", "d3", "d3_prev", "mid", "has_prev", "ts", "Ys", "vals",
                 "rhs", "nfev")

    def __init__(self, samples: int, safety: float = 10.0, dip_factor: float = 2.0):
        self.s = np.arange(1, samples + 1) / (samples + 1)
        self.safety, self.dip_factor = float(safety), float(dip_factor)
        self.nfev = 0
        self.start(np.zeros(0), np.zeros(0), 0)

    def start(self, y0: np.ndarray, f0: np.ndarray, n_guards: int, rhs=None) -> None:
        """Begin a phase at state ``y0`` with vector field ``f0`` and ``n_guards`` guards
        (forgets the previous step).  With the mode's ``rhs`` the first step is screened too:
        y'' at the phase start is taken from one extra evaluation of ``rhs`` (a forward
        difference along the flow), and y⁽⁴⁾ from the quartic through y, y' and y'' at the
        start and y, y' at the end of the step."""
        n, m = len(y0), len(self.s)
        self.ya, self.fa = np.array(y0, dtype=float), np.array(f0, dtype=float)
        self.d3, self.d3_prev = np.empty(n), np.empty(n)
        self.mid = np.zeros(1)
        self.has_prev = False
        self.ts, self.Ys = np.empty(3 * m + 1), np.empty((n, 3 * m + 1))
        self.vals = np.empty((n_guards, 3 * m + 1))
        self.rhs = rhs

    def advance(self, t0: float, t1: float, y1: np.ndarray, f1: np.ndarray) -> int:
        """Take the step from the previous state (the phase start or the last step end) to
        ``(t1, y1)`` with vector field ``f1`` there.

        Returns 1 when the step can be screened (:meth:`quiet`), 0 when there is no error
        estimate (the first step of a phase started without ``rhs``), -1 when ``y1`` is not
        finite.
        """
        first = not self.has_prev
        a0 = self.d3_prev  # unused unless first (then a scratch buffer for y'' at t0)
        if first and self.rhs is not None and t1 > t0:
            delta = 1e-6 * (t1 - t0)
            a0 = (np.asarray(self.rhs(t0 + delta, self.ya + delta * self.fa), dtype=float) - self.fa) / delta
            self.nfev += 1
        else:
            first = False
            self.d3, self.d3_prev = self.d3_prev, self.d3
        code = _hermite_probe(self.s, self.safety, t0, t1, self.ya, self.fa, y1, f1,
                              self.d3, self.d3_prev, self.mid, self.has_prev, first and self.rhs is not None, a0,
                              self.ts, self.Ys)
        self.has_prev = True
        return code

    def quiet(self, guards, g_start: np.ndarray, dec_before: np.ndarray, state: np.ndarray, atol: float) -> bool:
        """Whether no guard needs a dense-output scan of the step just taken.

        The guards are evaluated at the times ``self.ts`` and states ``self.Ys``: the m
        interpolated interior samples, the exact step end, then the interior samples moved by
        + and - the error bound.  ``g_start``: the guards at the step start; ``dec_before``:
        whether each was decreasing at the end of the previous step; ``state``: 1 armed, 0
        pending (armed by the scan at its first sample above ``atol``), -1 disarmed (a section
        that has just fired or starts on its surface: armed by the scan at its first sample
        above ``atol``, quiet while no sample can be above it).  When quiet, all three are
        advanced in place to the step end (the decrease taken pessimistically: True if a guard
        may be decreasing there; pending guards armed; disarmed ones stay disarmed).
        """
        vals, ts, Ys = self.vals, self.ts, self.Ys
        for j, g in enumerate(guards):
            vals[j] = g.fun(ts, Ys)
        return _quiet_guards(vals, len(self.s), g_start, dec_before, state, atol, self.dip_factor)


@njit(cache=True)
def _hermite_probe(s, safety, t0, t1, ya, fa, y1, f1, d3, d3_prev, mid, has_prev, first, a0, ts, Ys):
    """Fill ``ts``/``Ys`` for :meth:`HermiteScreen.quiet`; advance ``ya``/``fa`` to the step
    end; return 1, 0 (no error estimate) or -1 (``y1`` not finite).  y⁽⁴⁾ comes from the change
    of the cubic's third derivative since the previous step (``has_prev``) or, on the first step
    (``first``), from the quartic with y''(t0) = ``a0``."""
    n, m = ya.shape[0], s.shape[0]
    for i in range(n):
        if not math.isfinite(y1[i]):
            return -1
    h = t1 - t0
    new_mid = t0 + 0.5 * h
    dmid = new_mid - mid[0]
    ok = (has_prev and dmid > 0.0) or (first and h > 0.0)
    for i in range(n):
        d3[i] = (12.0 * (ya[i] - y1[i]) + 6.0 * h * (fa[i] + f1[i])) / h ** 3
    if ok:
        for k in range(m):
            sk = s[k]
            s2, s3 = sk * sk, sk * sk * sk
            h00, h10, h01, h11 = 2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + sk, -2 * s3 + 3 * s2, s3 - s2
            w = safety * h ** 4 * s2 * (1 - sk) ** 2 / 24.0
            tk = t0 + h * sk
            ts[k], ts[m + 1 + k], ts[2 * m + 1 + k] = tk, tk, tk
            for i in range(n):
                yk = h00 * ya[i] + h10 * h * fa[i] + h01 * y1[i] + h11 * h * f1[i]
                if has_prev:
                    d4 = abs(d3[i] - d3_prev[i]) / dmid
                else:
                    r1 = y1[i] - ya[i] - h * fa[i] - 0.5 * h * h * a0[i]
                    r2 = h * (f1[i] - fa[i]) - h * h * a0[i]
                    d4 = 24.0 * abs(r2 - 3.0 * r1) / h ** 4
                e = w * d4
                Ys[i, k] = yk
                Ys[i, m + 1 + k] = yk + e
                Ys[i, 2 * m + 1 + k] = yk - e
        ts[m] = t1
        for i in range(n):
            Ys[i, m] = y1[i]
    mid[0] = new_mid
    for i in range(n):
        ya[i] = y1[i]
        fa[i] = f1[i]
    return 1 if ok else 0


@njit(cache=True)
def _quiet_guards(vals, m, g_start, dec_before, state, atol, dip_factor):
    """:meth:`HermiteScreen.quiet` on the guard values ``vals`` (one row per guard): the
    worst case of :func:`first_crossing`'s tests over the samples' uncertainty intervals,
    each sample as low and its neighbours as high as their intervals allow.  A pending guard
    is quiet only if every sample is above ``atol`` (the scan would arm it at the first one
    and find nothing after it); a disarmed guard only if no sample can be above ``atol`` (the
    scan would not arm it: it only takes its value at the step end)."""
    k_guards = vals.shape[0]
    for j in range(k_guards):
        if state[j] < 0:
            if not _stays_disarmed(vals[j], m, atol):
                return False
            continue
        thr = atol if state[j] == 0 else 0.0
        if _guard_code(vals[j], m, g_start[j], dec_before[j] and state[j] > 0, dip_factor, thr) == 0:
            return False
    for j in range(k_guards):
        if state[j] < 0:
            g_start[j] = vals[j, m]
            continue
        thr = atol if state[j] == 0 else 0.0
        dec = _guard_code(vals[j], m, g_start[j], dec_before[j] and state[j] > 0, dip_factor, thr) == 2
        g_start[j] = vals[j, m]
        dec_before[j] = dec
        state[j] = 1
    return True


@njit(cache=True)
def _stays_disarmed(values, m, atol):
    """Whether every sample of a disarmed guard, widened by its uncertainty, and its value at the
    step end are <= ``atol`` (the scan of :func:`landau.verify.hybrid.simulate.simulate` then
    leaves it disarmed)."""
    if not values[m] <= atol:
        return False
    for k in range(m):
        g = values[k]
        spread = max(abs(values[m + 1 + k] - g), abs(values[2 * m + 1 + k] - g))
        if not g + spread <= atol:
            return False
    return True


@njit(cache=True)
def _guard_code(values, m, g_start, dec_before, dip_factor, thr):
    """0: the dense-output scan is needed; 1: quiet, not decreasing at the end; 2: quiet,
    possibly decreasing at the end.  Every sample must be above ``thr``."""
    g_end = values[m]
    if not g_end > thr:
        return 0
    hi_prev = g_start
    hi_first = 0.0
    hi_last = 0.0
    for k in range(m):
        g = values[k]
        spread = max(abs(values[m + 1 + k] - g), abs(values[2 * m + 1 + k] - g))
        lo = g - spread
        if not lo > thr:
            return 0
        if k + 1 < m:
            gn = values[k + 1]
            hi_next = gn + max(abs(values[m + 2 + k] - gn), abs(values[2 * m + 2 + k] - gn))
        else:
            hi_next = g_end
        if lo <= min(hi_prev, hi_next) and lo <= dip_factor * (max(hi_prev, hi_next) - lo):
            return 0
        if k == 0:
            hi_first = g + spread
        hi_last = g + spread
        hi_prev = g + spread
    if m > 0 and dec_before and hi_first >= g_start and g_start <= dip_factor * (hi_first - g_start):
        return 0
    return 2 if g_end < hi_last else 1
