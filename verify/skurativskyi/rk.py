"""A compiled (numba) Dormand–Prince 5(4) integrator with exact contact switching, and a
stiff SDIRK4 for the stick phases.

:func:`integrate_mixed` (the default path of :func:`landau.verify.skurativskyi.simulate.run`) takes
every step that starts with |ẋ| below a threshold (stick: the cart rests on the obstacle or
on the track, |ẋ| ~ 1e-9…1e-6 m/s) with the L-stable SDIRK4 of :mod:`landau.verify.skurativskyi.sdirk`
(stage equations solved as scalar monotone equations, robust on the |ẋ|^{n₃} cusp) and all
other steps with DOPRI5; :func:`integrate` is the explicit path alone.  Event location,
stroboscopic clipping and tangent renormalisation below are the same for both steppers.

Why explicit outside stick (measured, see ``verify/benchmarks/skurativskyi_work_precision.py``): the
Hertz damping term sgn(ẋ)|ẋ|^{n₃} (n₃ ≈ 0.187) is not Lipschitz at ẋ = 0 inside contact:
its slope grows like |ẋ|^{−0.81}, so the Newton iteration of an implicit method (Radau,
BDF) diverges whenever a stage velocity is near zero — the classic failure of Newton on a
cusp-type root (a first version of this module was a compiled Radau IIA and diverged at the
very first step from rest).  The stiffness of the regularised friction is moderate
(T/(εm) ≈ 7.2e4 1/s), so an error-controlled explicit method runs at its stability bound
(h ≈ 3e-5 s) through stick phases and takes long steps elsewhere.  Compiled, a step costs
~1 µs, which is what makes the method fast — not its stability.  (In stick phases on the
obstacle the explicit steps are in fact ~1e-6 s, chattering across ẋ = 0 on the cusp: >95 %
of all steps at ω = 15; that is what the SDIRK4 of the mixed path removes.)

Method (Dormand & Prince 1980; Hairer, Nørsett & Wanner, *Solving ODEs I*, II.5): 7 stages
with FSAL, 5th-order solution, embedded 4th-order error estimate, step factor
0.9 err^{−1/5} clipped to [0.2, 10].

Contact switching (guard g = x − x_I), exact to rounding:
1. each accepted step is scanned on the cubic Hermite interpolant of x (values and slopes
   ẋ at both ends) at its interior critical points, so a short excursion across x = x_I
   inside one step (near-grazing impact) is not missed; the first crossing is bisected;
2. the step is *re-taken* from its start with the length s*·h, and the length is corrected
   by Newton's method on g(t + h*) (slope ẋ) until |g| is at rounding level — the event time
   does not depend on the interpolant's accuracy, and every step lies on one side of the
   surface (the field is only C¹ there).  The end state is projected onto x = x_I.
No saltation is needed: the field is continuous across x = x_I (see ``model``).

Stroboscopic samples t = t₀ + i·2π/ω are step ends (steps are clipped onto them); with the
4-D variational system the tangent vector is renormalised there (top Lyapunov exponent).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from landau.errors import InputError
from landau.verify.skurativskyi.model import rhs as _rhs
from landau.verify.skurativskyi.sdirk import sdirk_step as _sdirk_step

OK, MAX_STEPS, STEP_TOO_SMALL, MAX_EVENTS = 0, 1, 2, 3
STATUS = {OK: "t_end", MAX_STEPS: "max_steps", STEP_TOO_SMALL: "step-size-underflow", MAX_EVENTS: "max_events"}

# Dormand–Prince 5(4) tableau
C2, C3, C4, C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
B1, B3, B4, B5, B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
E1, E3, E4, E5, E6, E7 = 71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40


@njit(cache=True)
def _dp_step(p, t, y, k1, h, ynew, k7, err):
    """One DOPRI5 step from (t, y) with k1 = f(t, y); fills ynew, k7 = f(t+h, ynew), err."""
    n = y.shape[0]
    yt = np.empty(n)
    k2 = np.empty(n); k3 = np.empty(n); k4 = np.empty(n); k5 = np.empty(n); k6 = np.empty(n)
    for a in range(n):
        yt[a] = y[a] + h * A21 * k1[a]
    _rhs(t + C2 * h, yt, p, k2)
    for a in range(n):
        yt[a] = y[a] + h * (A31 * k1[a] + A32 * k2[a])
    _rhs(t + C3 * h, yt, p, k3)
    for a in range(n):
        yt[a] = y[a] + h * (A41 * k1[a] + A42 * k2[a] + A43 * k3[a])
    _rhs(t + C4 * h, yt, p, k4)
    for a in range(n):
        yt[a] = y[a] + h * (A51 * k1[a] + A52 * k2[a] + A53 * k3[a] + A54 * k4[a])
    _rhs(t + C5 * h, yt, p, k5)
    for a in range(n):
        yt[a] = y[a] + h * (A61 * k1[a] + A62 * k2[a] + A63 * k3[a] + A64 * k4[a] + A65 * k5[a])
    _rhs(t + h, yt, p, k6)
    for a in range(n):
        ynew[a] = y[a] + h * (B1 * k1[a] + B3 * k3[a] + B4 * k4[a] + B5 * k5[a] + B6 * k6[a])
    _rhs(t + h, ynew, p, k7)
    for a in range(n):
        err[a] = h * (E1 * k1[a] + E3 * k3[a] + E4 * k4[a] + E5 * k5[a] + E6 * k6[a] + E7 * k7[a])


@njit(cache=True)
def _err_norm(err, y, ynew, rtol, atol):
    s = 0.0
    n = err.shape[0]
    for a in range(n):
        sc = atol[a] + rtol * max(abs(y[a]), abs(ynew[a]))
        q = err[a] / sc
        s += q * q
    return math.sqrt(s / n)


@njit(cache=True)
def _cubic(q0, q1, q2, s):
    return s * (q0 + s * (q1 + s * q2))


@njit(cache=True)
def _first_crossing(g0, q0, q1, q2, outside_sign):
    """First s in (0, 1] where g0 + q0 s + q1 s² + q2 s³ has sign ``outside_sign`` (strictly),
    or −1.  The cubic is monotone between its critical points, which are all checked."""
    pts = np.empty(3)
    npts = 0
    a, b, c = 3 * q2, 2 * q1, q0
    if a != 0.0:
        disc = b * b - 4 * a * c
        if disc >= 0:
            r = math.sqrt(disc)
            s1 = (-b - r) / (2 * a)
            s2 = (-b + r) / (2 * a)
            if s1 > s2:
                s1, s2 = s2, s1
            if 0.0 < s1 < 1.0:
                pts[npts] = s1
                npts += 1
            if 0.0 < s2 < 1.0:
                pts[npts] = s2
                npts += 1
    elif b != 0.0:
        s = -c / b
        if 0.0 < s < 1.0:
            pts[npts] = s
            npts += 1
    pts[npts] = 1.0
    npts += 1
    lo = 0.0
    for k in range(npts):
        hi = pts[k]
        if (g0 + _cubic(q0, q1, q2, hi)) * outside_sign > 0.0:
            for _ in range(100):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                if (g0 + _cubic(q0, q1, q2, mid)) * outside_sign > 0.0:
                    hi = mid
                else:
                    lo = mid
            return hi
        lo = hi
    return -1.0


@njit(cache=True)
def _any_step(stiff, p, t, y, k1, h, rtol, atol, ynew, k7, err):
    """One step of the chosen method; returns (ok, f evaluations)."""
    if stiff:
        return _sdirk_step(p, t, y, h, rtol, atol, ynew, k7, err)
    _dp_step(p, t, y, k1, h, ynew, k7, err)
    return True, 6


@njit(cache=True)
def integrate(p, t0, y0, t_end, rtol, atol, h0, hmax, xI, guard, strobe_t0, strobe_dt,
              n_strobe_max, renorm, max_events, max_steps):
    """The explicit path: :func:`integrate_mixed` with the stiff stepper disabled (the
    returned tuple has the stiff-step count as its last entry, always 0 here)."""
    return integrate_mixed(p, t0, y0, t_end, rtol, atol, h0, hmax, xI, guard, strobe_t0, strobe_dt,
                           n_strobe_max, renorm, max_events, max_steps, 0.0, 0.0)


@njit(cache=True)
def integrate_mixed(p, t0, y0, t_end, rtol, atol, h0, hmax, xI, guard, strobe_t0, strobe_dt,
                    n_strobe_max, renorm, max_events, max_steps, v_stiff, a_stiff):
    """Integrate with contact switching at x = xI (``guard``), stroboscopic samples every
    ``strobe_dt`` from ``strobe_t0`` (if > 0) and tangent renormalisation there
    (``renorm``, 4-D systems).  A step that starts in stick — |ẋ| < ``v_stiff`` and
    |ẍ| < ``a_stiff`` (a velocity reversal crosses the band |ẋ| < v_stiff in ~2 v_stiff/|ẍ|,
    a few explicit steps; a stick stays in it) — is taken by the L-stable SDIRK4 of
    :mod:`landau.verify.skurativskyi.sdirk`, any other by DOPRI5 (``v_stiff`` ≤ 0: DOPRI5 only).
    See the module docstring.  Returns a tuple (see :func:`landau.verify.skurativskyi.simulate.run`)."""
    n = y0.shape[0]
    y = y0.copy()
    t = t0
    k1 = np.empty(n)
    _rhs(t, y, p, k1)
    nfev = 1
    ynew = np.empty(n)
    k7 = np.empty(n)
    err = np.empty(n)
    ev_t = np.empty(max_events)
    ev_k = np.empty(max_events, np.int64)
    ev_v = np.empty(max_events)
    nev = 0
    st_t = np.empty(n_strobe_max)
    st_y = np.empty((n_strobe_max, n))
    nst = 0
    lyap = 0.0
    nly = 0
    g = y[0] - xI
    contact = g > 0.0 or (g == 0.0 and y[1] > 0.0)
    h = h0
    ist = 0
    ts = strobe_t0 if strobe_dt > 0 else np.inf
    while ts < t - 1e-12 * max(1.0, abs(t)):
        ist += 1
        ts = strobe_t0 + ist * strobe_dt
    nsteps = 0
    nrej = 0
    nstiff = 0
    status = OK
    max_mismatch = 0.0
    while True:
        # stroboscopic sample at the current time?
        if ts <= t_end and abs(t - ts) <= 1e-13 * max(1.0, abs(ts)):
            if nst < n_strobe_max:
                st_t[nst] = t
                st_y[nst, :] = y
                nst += 1
            if renorm:
                nv = math.sqrt(y[2] * y[2] + y[3] * y[3])
                if nv > 0:
                    lyap += math.log(nv)
                    nly += 1
                    y[2] /= nv
                    y[3] /= nv
                    _rhs(t, y, p, k1)
                    nfev += 1
            ist += 1
            ts = strobe_t0 + ist * strobe_dt
        if t >= t_end:
            break
        if nsteps >= max_steps:
            status = MAX_STEPS
            break
        h = min(h, hmax)
        clipped = False
        h_free = h
        t_target = min(t_end, ts)
        if t + h >= t_target - 1e-13 * max(1.0, abs(t_target)):
            h = t_target - t
            clipped = True
        if h <= 1e-15 * max(1.0, abs(t)):
            status = STEP_TOO_SMALL
            break
        stiff = abs(y[1]) < v_stiff and abs(k1[1]) < a_stiff
        expo = 0.25 if stiff else 0.2  # embedded orders 3 (SDIRK4) and 4 (DOPRI5)
        ok, nf = _any_step(stiff, p, t, y, k1, h, rtol, atol, ynew, k7, err)
        nfev += nf
        en = _err_norm(err, y, ynew, rtol, atol) if ok else np.nan
        if not (en <= 1.0):
            nrej += 1
            if en != en:  # NaN or a failed stage solve
                h *= 0.2
            else:
                h *= max(0.2, 0.9 * en ** -expo)
            continue
        fac = 10.0 if en == 0 else min(10.0, 0.9 * en ** -expo)
        h_next = h * fac
        if clipped:
            h_next = max(h_next, min(h_free, h_free * fac))
        switched = False
        if guard:
            g0 = y[0] - xI
            dx = ynew[0] - y[0]
            m0 = h * y[1]
            m1 = h * ynew[1]
            q1 = 3 * dx - 2 * m0 - m1
            q2 = -2 * dx + m0 + m1
            sgn = -1.0 if contact else 1.0
            s_star = _first_crossing(g0, m0, q1, q2, sgn)
            if s_star <= 0.0 and (ynew[0] - xI) * sgn > 0.0:
                s_star = 1.0  # defensive: the end state is outside
            if s_star > 0.0:
                # re-take the step onto the root; Newton on the step length (slope ẋ)
                hs = s_star * h
                for it in range(8):
                    ok, nf = _any_step(stiff, p, t, y, k1, hs, rtol, atol, ynew, k7, err)
                    nfev += nf
                    if not ok:
                        hs *= 0.5
                        continue
                    gr = ynew[0] - xI
                    if abs(gr) <= 4e-16 * abs(xI) or ynew[1] == 0.0:
                        break
                    dh = -gr / ynew[1]
                    hn = hs + dh
                    if hn <= 0.0:
                        hn = 0.5 * hs
                    elif hn > h:
                        hn = 0.5 * (hs + h)
                    hs = hn
                h = hs
                max_mismatch = max(max_mismatch, abs(ynew[0] - xI))
                ynew[0] = xI
                _rhs(t + h, ynew, p, k7)
                nfev += 1
                switched = True
                clipped = False
        nsteps += 1
        if stiff:
            nstiff += 1
        t = ts if clipped and t_target == ts else (t_end if clipped else t + h)
        for a in range(n):
            y[a] = ynew[a]
            k1[a] = k7[a]
        if switched:
            if nev < max_events:
                ev_t[nev] = t
                ev_k[nev] = -1 if contact else 1
                ev_v[nev] = y[1]
                nev += 1
            else:
                status = MAX_EVENTS
                break
            contact = not contact
            h_next = max(h_next, h_free)
        h = h_next
    return (t, y, status, ev_t[:nev].copy(), ev_k[:nev].copy(), ev_v[:nev].copy(), st_t[:nst].copy(),
            st_y[:nst].copy(), lyap, nly, nsteps, nfev, nrej, max_mismatch, nstiff)


# ---------------------------------------------------------------------------------------
@dataclass(frozen=True)
class CompiledField:
    """A numba vector field ``kernel(t, y, p, out)`` with its packed parameters; callable like
    a Python rhs (the engine evaluates it at phase starts)."""

    kernel: object
    p: np.ndarray

    def __call__(self, t, y):
        y = np.asarray(y, float)
        out = np.empty(len(y))
        self.kernel(float(t), y, self.p, out)
        return out


@njit(cache=True)
def _one_step(p, t, y, k1, h, hmax, t_bound, rtol, atol):
    """Advance one accepted DOPRI5 step.  Returns (ok, t_new, y_new, k7, h_used, h_next, nfev)."""
    n = y.shape[0]
    ynew = np.empty(n)
    k7 = np.empty(n)
    err = np.empty(n)
    nfev = 0
    for _ in range(500):
        h = min(h, hmax, t_bound - t)
        if h <= 1e-15 * max(1.0, abs(t)):
            break
        _dp_step(p, t, y, k1, h, ynew, k7, err)
        nfev += 6
        en = _err_norm(err, y, ynew, rtol, atol)
        if en <= 1.0:
            fac = 10.0 if en == 0 else min(10.0, 0.9 * en ** -0.2)
            tn = t + h if t + h < t_bound else t_bound
            return True, tn, ynew, k7, h, h * fac, nfev
        h *= 0.2 if en != en else max(0.2, 0.9 * en ** -0.2)
    return False, t, y.copy(), k1.copy(), h, h, nfev


class _Hermite:
    """Cubic Hermite interpolant on one step (values and slopes at both ends)."""

    def __init__(self, t0, t1, y0, y1, f0, f1):
        self.t0, self.h = t0, t1 - t0
        self.y0, self.y1, self.f0, self.f1 = y0, y1, f0, f1

    def __call__(self, t):
        s = (np.asarray(t, float) - self.t0) / self.h
        h00 = (1 + 2 * s) * (1 - s) ** 2
        h10 = s * (1 - s) ** 2
        h01 = s * s * (3 - 2 * s)
        h11 = s * s * (s - 1)
        if s.ndim == 0:
            return h00 * self.y0 + h10 * self.h * self.f0 + h01 * self.y1 + h11 * self.h * self.f1
        c = lambda v: v[:, None]
        return (h00 * c(self.y0) + h10 * self.h * c(self.f0) + h01 * c(self.y1) + h11 * self.h * c(self.f1))


class _EngineStepper:
    """The compiled DOPRI5 behind the scipy ``OdeSolver`` members the engine uses."""

    def __init__(self, field: CompiledField, t0, y0, t_bound, rtol, atol, h0, hmax):
        self.field = field
        self.t = self.t_old = float(t0)
        self.y = np.array(y0, float)
        self.t_bound = float(t_bound)
        self.rtol = rtol
        self.atol = np.broadcast_to(np.asarray(atol, float), self.y.shape).copy()
        self.h, self.hmax = h0, hmax
        self.status = "running" if t_bound > t0 else "finished"
        self.f = field(t0, self.y)
        self.nfev = 1
        self._dense = None

    def step(self):
        ok, tn, yn, k7, h, hn, nf = _one_step(self.field.p, self.t, self.y, self.f, self.h,
                                              self.hmax, self.t_bound, self.rtol, self.atol)
        self.nfev += nf
        if not ok:
            self.status = "failed"
            return "compiled DOPRI5: step size underflow"
        self._dense = _Hermite(self.t, tn, self.y.copy(), np.array(yn), self.f.copy(), np.array(k7))
        self.t_old, self.t, self.y, self.f = self.t, tn, np.array(yn), np.array(k7)
        self.h = hn
        if self.t >= self.t_bound:
            self.status = "finished"
        return None

    def dense_output(self):
        return self._dense


@dataclass(frozen=True)
class CompiledDOPRI5:
    """Stepper factory for :func:`landau.verify.hybrid.simulate` (the engine's stepper contract):
    modes whose ``rhs`` is a :class:`CompiledField` are advanced by the compiled DOPRI5
    with a cubic Hermite dense output."""

    rtol: float = 1e-8
    atol: tuple = (1e-12, 1e-10)
    first_step: float = 1e-5
    max_step: float = 0.01

    def __call__(self, fun, t0, y0, t_bound, jac=None):
        if not isinstance(fun, CompiledField):
            raise InputError("CompiledDOPRI5 needs a mode whose rhs is a CompiledField "
                             "(use verify.skurativskyi.simulate.hybrid_model)")
        return _EngineStepper(fun, t0, y0, t_bound, self.rtol, self.atol, self.first_step, self.max_step)

