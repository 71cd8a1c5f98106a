"""A compiled event-driven loop: DOPRI5 with exact contact switching, and a stiff step for the
stick phases, built for a given field.

:func:`integrate_mixed` is an ordinary ``@njit(cache=True)`` function over the field of
:mod:`landau.verify.skurativskyi.field`, compiled once per machine on first use
(:func:`mixed_loop`, through :func:`landau.verify.compiling.compile_once`); the friction law
reaches it as a tuple ``fr`` of first-class functions (numba's ``types.FunctionType``: the C
callbacks of :attr:`landau.verify.skurativskyi.friction.CompiledFriction.pointers`), so a new
law compiles only its own small callbacks (under ``NUMBA_DISABLE_JIT=1`` everything here runs
as plain Python, with the law's generated Python functions as ``fr``: slow, for a debugger, and
step for step the compiled run).  ``integrate_mixed`` (the default path
of :func:`landau.verify.skurativskyi.simulate.run`) takes every step that starts with |ẋ|
below a threshold (stick: the cart rests on the obstacle or on the track, |ẋ| ~ 1e-9…1e-6
m/s) with the L-stable SDIRK4 (stage equations solved as scalar monotone equations, robust on
the |ẋ|^{n₃} cusp) and all other steps with DOPRI5 (term for term the arithmetic of the generic
compiled DOPRI5 step of Dormand & Prince (1980) that the published values were computed with:
the tests keep that step as an oracle and check the two bit for bit);
``integrate`` is the explicit path alone.  Event location (the compiled locator of
:mod:`landau.verify.hybrid.crossing`), stroboscopic clipping and tangent renormalisation are
the same for both steppers.

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

Loose tolerances (:data:`LOOSE_RTOL`, :data:`LOW_ORDER_RTOL`): at rtol ≥ 1e-6
the explicit steps are PI-controlled (Gustafsson 1991; Hairer, Nørsett & Wanner II.4: factor
0.9 err^{−α} err_prev^{β}, no growth right after a rejection), and at rtol ≥ 1e-5 they are
Bogacki–Shampine 3(2) steps (Bogacki & Shampine 1989; 4 stages with FSAL, 3 f evaluations) —
the non-smooth layers of eq. (1) (the friction regularised over |ẋ| < ε, the Hertz damping's
|ẋ|^{n₃}) cap the steps below where DOPRI5's order pays.  Measured at ω = 16, 20 periods from
rest: f evaluations 22.5k → 18.4k at rtol 1e-4, 33.0k → 28.9k at 1e-5, 45.0k → 40.2k at 1e-6,
with smaller final-state errors.  Tighter tolerances run the loop exactly as before, step for
step (the published bifurcation values are computed at rtol 1e-7…1e-9, and the period-doubling
cascade near ω = 20.4 follows the last bit of the step sequence).

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

Speed (not the arithmetic): the steps are inlined into the loop (``inline="always"``), the
stage vectors are borrowed views (:mod:`landau.verify.hybrid.borrowed`) of an array the call
owns, and the field reads the packed parameters through their data pointer
(:mod:`landau.verify.skurativskyi.field`), so numba's atomic reference counts (paid for every
array handed to a compiled call that is not inlined) stay out of the steps, the field's own
calls included: the borrowed views took 20 periods at ω = 16 from 3.57 to 2.43 ms at rtol 1e-5
and from 5.78 to 4.31 ms at 1e-7 (every step the same; Intel Xeon, the other core busy).  The
paper's friction law is compiled into the field; any other law costs one indirect call per
evaluation (two with the tangent vector).  With the tangent vector the field and its Jacobian
are one call that computes the contact force's powers once
(:func:`landau.verify.skurativskyi.field.field_values`).  Measured at ω = 16, 20 periods
from rest (CPU time, best of 3 in 2 alternated rounds, 2 shared cores), against the earlier loop
specialised per law from a source template: 3.1 → 4.0 ms at rtol 1e-6, 12.6 → 14.8 ms at
1e-9; with the tangent vector (Lyapunov exponent) 18.4 → 18.4 ms and 59.8 → 58.0 ms; every
step, event and final state unchanged to the bit.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numba import njit

from landau.verify.hybrid.borrowed import borrowed, keep_alive
from landau.verify.hybrid.crossing import cubic_crossing
from landau.verify.skurativskyi.field import hold, rhs
from landau.verify.skurativskyi.sdirk import sdirk_step

OK, MAX_STEPS, STEP_TOO_SMALL, MAX_EVENTS = 0, 1, 2, 3
STATUS = {OK: "t_end", MAX_STEPS: "max_steps", STEP_TOO_SMALL: "step-size-underflow", MAX_EVENTS: "max_events"}

#: Dormand & Prince (1980) 5(4): nodes c, coefficients a, 5th-order weights b and the error
#: weights e = b − b̂ (Hairer, Nørsett & Wanner, Solving ODEs I, Table II.5.2)
C2, C3, C4, C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
B1, B3, B4, B5, B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
E1, E3, E4, E5, E6, E7 = 71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40

#: loose tolerances (rtol ≥ LOOSE_RTOL) take explicit steps with PI step-size control and no
#: growth right after a rejection (Hairer, Nørsett & Wanner, Solving ODEs I, II.4; their code
#: DOPRI5): it damps the accept/reject cycles of the steps limited by the friction and
#: Hertz-damping layers near velocity reversals (measured at ω = 16, 20 periods: 10–25 % fewer
#: f evaluations).  Tighter tolerances keep the plain controller: the published bifurcation
#: values were computed with it at rtol 1e-7…1e-9 and the period-doubling cascade near
#: ω = 20.4 moves with any change of the step sequence.
LOOSE_RTOL = 1e-6
#: PI memory exponents of the DOPRI5 (Hairer's 0.04) and Bogacki–Shampine steps
PI_BETA_DP = 0.04
PI_BETA_BS = 0.08
#: from this rtol on, the explicit steps are Bogacki–Shampine 3(2) (3 f evaluations a step
#: instead of 6): at such tolerances the non-smooth layers (friction regularised over
#: |ẋ| < ε, the |ẋ|^{n₃} Hertz damping) cap DOPRI5's steps below where its order pays
LOW_ORDER_RTOL = 1e-5


@njit(cache=True, inline="always")
def err_norm(err, y, ynew, rtol, atol):
    """RMS of err / (atol + rtol·max(|y|, |ynew|)) (Hairer's norm)."""
    s = 0.0
    n = err.shape[0]
    for a in range(n):
        sc = atol[a] + rtol * max(abs(y[a]), abs(ynew[a]))
        q = err[a] / sc
        s += q * q
    return math.sqrt(s / n)


@njit(cache=True, inline="always")
def dp5_step(p, t, y, k1, h, ynew, k7, err, yt, k2, k3, k4, k5, k6, fr):
    """One Dormand–Prince 5(4) step (FSAL): the arithmetic of the generic compiled DOPRI5 step
    (the tests' oracle, ``stages``) term for term, into preallocated stage buffers."""
    n = y.shape[0]
    for a in range(n):
        yt[a] = y[a] + h * A21 * k1[a]
    rhs(t + C2 * h, yt, p, k2, fr)
    for a in range(n):
        yt[a] = y[a] + h * (A31 * k1[a] + A32 * k2[a])
    rhs(t + C3 * h, yt, p, k3, fr)
    for a in range(n):
        yt[a] = y[a] + h * (A41 * k1[a] + A42 * k2[a] + A43 * k3[a])
    rhs(t + C4 * h, yt, p, k4, fr)
    for a in range(n):
        yt[a] = y[a] + h * (A51 * k1[a] + A52 * k2[a] + A53 * k3[a] + A54 * k4[a])
    rhs(t + C5 * h, yt, p, k5, fr)
    for a in range(n):
        yt[a] = y[a] + h * (A61 * k1[a] + A62 * k2[a] + A63 * k3[a] + A64 * k4[a] + A65 * k5[a])
    rhs(t + h, yt, p, k6, fr)
    for a in range(n):
        ynew[a] = y[a] + h * (B1 * k1[a] + B3 * k3[a] + B4 * k4[a] + B5 * k5[a] + B6 * k6[a])
    rhs(t + h, ynew, p, k7, fr)
    for a in range(n):
        err[a] = h * (E1 * k1[a] + E3 * k3[a] + E4 * k4[a] + E5 * k5[a] + E6 * k6[a] + E7 * k7[a])


@njit(cache=True, inline="always")
def bs3_step(p, t, y, k1, h, ynew, k4, err, yt, k2, k3, fr):
    """One Bogacki–Shampine 3(2) step (FSAL; Bogacki & Shampine 1989): from (t, y) with
    k1 = f(t, y), fills ynew (order 3), k4 = f(t + h, ynew) and the embedded error estimate;
    yt, k2, k3 are scratch."""
    n = y.shape[0]
    for a in range(n):
        yt[a] = y[a] + h * (0.5 * k1[a])
    rhs(t + 0.5 * h, yt, p, k2, fr)
    for a in range(n):
        yt[a] = y[a] + h * (0.75 * k2[a])
    rhs(t + 0.75 * h, yt, p, k3, fr)
    for a in range(n):
        ynew[a] = y[a] + h * (2.0 / 9.0 * k1[a] + 1.0 / 3.0 * k2[a] + 4.0 / 9.0 * k3[a])
    rhs(t + h, ynew, p, k4, fr)
    for a in range(n):
        err[a] = h * (-5.0 / 72.0 * k1[a] + 1.0 / 12.0 * k2[a] + 1.0 / 9.0 * k3[a] - 0.125 * k4[a])


@njit(cache=True, inline="always")
def any_step(stiff, low, p, t, y, k1, h, rtol, atol, ynew, k7, err, yt, k2, k3, k4, k5, k6, fr):
    """One step of the chosen method (the stick stepper, Bogacki–Shampine 3(2) if ``low``,
    else DOPRI5); returns (ok, f evaluations).  yt, k2…k6 are stage scratch."""
    if stiff:
        return sdirk_step(p, t, y, h, rtol, atol, ynew, k7, err, fr)
    if low:
        bs3_step(p, t, y, k1, h, ynew, k7, err, yt, k2, k3, fr)
        return True, 3
    dp5_step(p, t, y, k1, h, ynew, k7, err, yt, k2, k3, k4, k5, k6, fr)
    return True, 6


@njit(cache=True, inline="always")
def _first_strobe(strobe_t0, strobe_dt, t):
    """``(ist, ts)``: the index and time of the first stroboscopic sample t₀ + i·dt at or after
    ``t`` (to a relative 1e-12), or ts = inf without samples (``strobe_dt`` ≤ 0)."""
    ist = 0
    ts = strobe_t0 if strobe_dt > 0 else np.inf
    while ts < t - 1e-12 * max(1.0, abs(t)):
        ist += 1
        ts = strobe_t0 + ist * strobe_dt
    return ist, ts


@njit(cache=True, inline="always")
def _strobe_sample(t, y, p, k1, renorm, st_t, st_y, nst, lyap, nly, nfev, fr):
    """At a stroboscopic time: keep the sample (t, y) while ``st_t`` has room, and with
    ``renorm`` (4-D systems) renormalise the tangent vector y[2:4] to length 1, adding the log of
    its length to ``lyap`` (k1 = f(t, y) recomputed).  Returns the updated
    ``(nst, lyap, nly, nfev)``."""
    if nst < st_t.shape[0]:
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
            rhs(t, y, p, k1, fr)
            nfev += 1
    return nst, lyap, nly, nfev


@njit(cache=True, inline="always")
def _clip_step(t, h, hmax, t_end, ts):
    """The next step's length: ``h`` at most ``hmax``, clipped onto the next target (the end
    ``t_end`` or the stroboscopic time ``ts``) when it would reach it to a relative 1e-13.
    Returns ``(h, clipped, h_free, t_target)`` with ``h_free`` the length before the clip."""
    h = min(h, hmax)
    clipped = False
    h_free = h
    t_target = min(t_end, ts)
    if t + h >= t_target - 1e-13 * max(1.0, abs(t_target)):
        h = t_target - t
        clipped = True
    return h, clipped, h_free, t_target


@njit(cache=True, inline="always")
def _keep_sample(t, y, k1, rec_t, rec_y, rec_f, nrec):
    """Record (t, y, f) as sample ``nrec`` of the time series while it has room; the new count."""
    if nrec < rec_t.shape[0]:
        rec_t[nrec] = t
        rec_y[nrec, :] = y
        rec_f[nrec, :] = k1
        nrec += 1
    return nrec


@njit(cache=True, inline="always")
def _accepted_factor(en, expo, stiff, loose, pi_beta, en_old, after_reject):
    """The step factor after an accepted step with error norm ``en``: 0.9·en^(−expo) clipped at 10
    (PI-controlled, 0.9·en^(0.75β − expo)·en_old^β, for the loose explicit steps; Gustafsson 1991;
    Hairer, Nørsett & Wanner II.4), at most 1 right after a rejection."""
    if en == 0:
        fac = 10.0
    elif stiff or not loose:
        fac = min(10.0, 0.9 * en ** -expo)
    else:  # PI control (Gustafsson 1991; Hairer, Nørsett & Wanner II.4)
        fac = min(10.0, 0.9 * en ** (pi_beta * 0.75 - expo) * en_old ** pi_beta)
    if after_reject:  # no growth right after a rejection (Hairer, Norsett & Wanner, II.4)
        fac = min(fac, 1.0)
    return fac


@njit(cache=True, inline="always")
def _contact_fraction(y, ynew, h, xI, contact):
    """s* ∈ (0, 1]: the fraction of the step (y → ynew, length h) at the first crossing of x = xI
    on the cubic Hermite interpolant of x (values and slopes ẋ at both ends), leaving the side
    ``contact`` says the step started on; −1 when the step stays on that side."""
    g0 = y[0] - xI
    dx = ynew[0] - y[0]
    m0 = h * y[1]
    m1 = h * ynew[1]
    q1 = 3 * dx - 2 * m0 - m1
    q2 = -2 * dx + m0 + m1
    sgn = -1.0 if contact else 1.0
    # |g(s) − g₀| ≤ |m₀| + |q₁| + |q₂| on [0, 1]: a step that stays inside by more than
    # that bound (plus a rounding margin) cannot cross, and cubic_crossing would return
    # −1; skipping it changes no step
    bnd = abs(m0) + abs(q1) + abs(q2)
    if g0 * sgn + bnd + 1e-12 * (abs(g0) + bnd) < 0.0:
        s_star = -1.0
    else:
        s_star = cubic_crossing(g0, m0, q1, q2, 0.0, sgn, False)
    if s_star <= 0.0 and (ynew[0] - xI) * sgn > 0.0:
        s_star = 1.0  # defensive: the end state is outside
    return s_star


@njit(cache=True, inline="always")
def _step_onto_contact(stiff, low, p, t, y, k1, h, s_star, rtol, atol, ynew, k7, err, yt, k2, k3, k4, k5, k6,
                       xI, fr):
    """Re-take the step from (t, y) onto the contact surface: Newton's method on the step length
    (slope ẋ) from s*·h until |x − xI| is at rounding level (at most 8 steps), the end state
    projected onto x = xI and k7 = f there.  Returns ``(h*, f evaluations, |x − xI| before the
    projection)``."""
    nfev = 0
    hs = s_star * h
    for _it in range(8):
        ok, nf = any_step(stiff, low, p, t, y, k1, hs, rtol, atol, ynew, k7, err, yt, k2, k3,
                          k4, k5, k6, fr)
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
    mismatch = abs(ynew[0] - xI)
    ynew[0] = xI
    rhs(t + hs, ynew, p, k7, fr)
    nfev += 1
    return hs, nfev, mismatch


@njit(cache=True)
def integrate_mixed(p_arr, t0, y0, t_end, rtol, atol, h0, hmax, xI, guard, strobe_t0, strobe_dt,
                    n_strobe_max, renorm, max_events, max_steps, v_stiff, a_stiff, rec_cap, fr):
    """Integrate with contact switching at x = xI (``guard``), stroboscopic samples every
    ``strobe_dt`` from ``strobe_t0`` (if > 0) and tangent renormalisation there
    (``renorm``, 4-D systems).  A step that starts in stick — |ẋ| < ``v_stiff`` and
    |ẍ| < ``a_stiff`` (a velocity reversal crosses the band |ẋ| < v_stiff in ~2 v_stiff/|ẍ|,
    a few explicit steps; a stick stays in it) — is taken by the L-stable SDIRK4 of
    :mod:`landau.verify.skurativskyi.sdirk`, any other by DOPRI5 (``v_stiff`` ≤ 0: DOPRI5 only).
    ``fr``: the friction law's callbacks (:mod:`landau.verify.skurativskyi.field`).
    See the module docstring.  Returns a tuple (see :func:`landau.verify.skurativskyi.simulate.run`)."""
    n = y0.shape[0]
    # the packed parameters are read through their data pointer (no reference counts in the
    # calls of the field: measured 20-40 % of a step); ``p_arr`` is owned by the caller for the
    # whole call
    p = hold(p_arr, fr)
    # the state and the stage vectors: arrays owned by this call, used through borrowed views
    # (no reference counts at the field's calls, landau.verify.hybrid.borrowed); the owners are
    # kept alive to the end, and the state is returned as its owner
    y_own = np.empty(n)
    y_own[:] = y0
    y = borrowed(y_own)
    S = np.empty((10, n))
    k1, ynew, k7, err = borrowed(S[0]), borrowed(S[1]), borrowed(S[2]), borrowed(S[3])
    yt, k2, k3, k4, k5, k6 = borrowed(S[4]), borrowed(S[5]), borrowed(S[6]), borrowed(S[7]), borrowed(S[8]), \
        borrowed(S[9])
    t = t0
    rhs(t, y, p, k1, fr)
    nfev = 1
    ev_t = np.empty(max_events)
    ev_k = np.empty(max_events, np.int64)
    ev_v = np.empty(max_events)
    nev = 0
    st_t = np.empty(n_strobe_max)
    st_y = np.empty((n_strobe_max, n))
    nst = 0
    # the recorded time series (t, y, f at accepted step ends), at most rec_cap points
    rec_t = np.empty(rec_cap)
    rec_y = np.empty((rec_cap, n))
    rec_f = np.empty((rec_cap, n))
    nrec = _keep_sample(t, y, k1, rec_t, rec_y, rec_f, 0)
    lyap = 0.0
    nly = 0
    g = y[0] - xI
    contact = g > 0.0 or (g == 0.0 and y[1] > 0.0)
    h = h0
    ist, ts = _first_strobe(strobe_t0, strobe_dt, t)
    nsteps = 0
    nrej = 0
    nstiff = 0
    status = OK
    max_mismatch = 0.0
    en_old = 1e-4  # the error norm of the last accepted step (PI control), Hairer's initial value
    after_reject = False
    loose = rtol >= LOOSE_RTOL
    low = rtol >= LOW_ORDER_RTOL
    pi_beta = (PI_BETA_BS if low else PI_BETA_DP) if loose else 0.0
    while True:
        # stroboscopic sample at the current time?
        if ts <= t_end and abs(t - ts) <= 1e-13 * max(1.0, abs(ts)):
            nst, lyap, nly, nfev = _strobe_sample(t, y, p, k1, renorm, st_t, st_y, nst, lyap, nly, nfev, fr)
            ist += 1
            ts = strobe_t0 + ist * strobe_dt
        if t >= t_end:
            break
        if nsteps >= max_steps:
            status = MAX_STEPS
            break
        h, clipped, h_free, t_target = _clip_step(t, h, hmax, t_end, ts)
        if h <= 1e-15 * max(1.0, abs(t)):
            status = STEP_TOO_SMALL
            break
        stiff = abs(y[1]) < v_stiff and abs(k1[1]) < a_stiff
        # 1/(q + 1) for the embedded orders q = 3 (SDIRK4), 2 (Bogacki–Shampine), 4 (DOPRI5)
        expo = 0.25 if stiff else (1.0 / 3.0 if low else 0.2)
        ok, nf = any_step(stiff, low, p, t, y, k1, h, rtol, atol, ynew, k7, err, yt, k2, k3, k4, k5, k6, fr)
        nfev += nf
        en = err_norm(err, y, ynew, rtol, atol) if ok else np.nan
        if not (en <= 1.0):
            nrej += 1
            after_reject = loose
            if en != en:  # NaN or a failed stage solve
                h *= 0.2
            else:
                h *= max(0.2, 0.9 * en ** -expo)
            continue
        fac = _accepted_factor(en, expo, stiff, loose, pi_beta, en_old, after_reject)
        after_reject = False
        en_old = max(en, 1e-4)
        h_next = h * fac
        if clipped:
            h_next = max(h_next, min(h_free, h_free * fac))
        switched = False
        if guard:
            # a contact crossing inside the step: re-take it onto the root
            s_star = _contact_fraction(y, ynew, h, xI, contact)
            if s_star > 0.0:
                h, nf, mismatch = _step_onto_contact(stiff, low, p, t, y, k1, h, s_star, rtol, atol, ynew, k7, err,
                                                     yt, k2, k3, k4, k5, k6, xI, fr)
                nfev += nf
                max_mismatch = max(max_mismatch, mismatch)
                switched = True
                clipped = False
        nsteps += 1
        if stiff:
            nstiff += 1
        t = ts if clipped and t_target == ts else (t_end if clipped else t + h)
        for a in range(n):
            y[a] = ynew[a]
            k1[a] = k7[a]
        nrec = _keep_sample(t, y, k1, rec_t, rec_y, rec_f, nrec)
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
    keep_alive(S)
    return (t, y_own, status, ev_t[:nev].copy(), ev_k[:nev].copy(), ev_v[:nev].copy(), st_t[:nst].copy(),
            st_y[:nst].copy(), lyap, nly, nsteps, nfev, nrej, max_mismatch, nstiff, rec_t[:nrec].copy(),
            rec_y[:nrec].copy(), rec_f[:nrec].copy())


@njit(cache=True)
def integrate(p, t0, y0, t_end, rtol, atol, h0, hmax, xI, guard, strobe_t0, strobe_dt,
              n_strobe_max, renorm, max_events, max_steps, rec_cap, fr):
    """The explicit path: :func:`integrate_mixed` with the stiff stepper disabled (the
    returned tuple has the stiff-step count as its last entry, always 0 here)."""
    return integrate_mixed(p, t0, y0, t_end, rtol, atol, h0, hmax, xI, guard, strobe_t0, strobe_dt,
                           n_strobe_max, renorm, max_events, max_steps, 0.0, 0.0, rec_cap, fr)


@lru_cache(maxsize=None)
def loop_signature():
    """The argument types of :func:`integrate_mixed` as :func:`landau.verify.skurativskyi.simulate.run`
    calls it (arrays C-contiguous float64, the friction callbacks of
    :func:`landau.verify.skurativskyi.friction.callbacks_type`)."""
    from numba import types

    from landau.verify.skurativskyi.friction import callbacks_type

    arr, f8, i8, b1 = types.float64[::1], types.float64, types.int64, types.boolean
    return (arr, f8, arr, f8, f8, arr, f8, f8, f8, b1, f8, f8, i8, b1, i8, i8, f8, f8, i8, callbacks_type())


def mixed_loop():
    """:func:`integrate_mixed`, compiled for :func:`loop_signature` on first use (once per
    machine: numba's disk cache keeps it for every later process and every friction law).
    Under ``NUMBA_DISABLE_JIT=1`` it is the Python function, and a warning says so once."""
    from landau.verify.compiling import compile_once
    from landau.verify.hybrid.callbacks import jit_enabled
    from landau.verify.skurativskyi.friction import quiet_first_class, warn_plain_python

    if not jit_enabled():
        warn_plain_python()
        return integrate_mixed
    with quiet_first_class():
        return compile_once(integrate_mixed, loop_signature(), "the forced-oscillator integrator")


def __getattr__(name: str):
    # the engine-facing piece, imported on use
    if name == "CompiledField":
        from landau.verify.hybrid.kernel import Kernel
        return Kernel
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["STATUS", "integrate", "integrate_mixed", "loop_signature", "mixed_loop"]
