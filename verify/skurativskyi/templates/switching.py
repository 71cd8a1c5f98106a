"""Template: the event-driven DOPRI5/stick-stepper loop of landau.verify.skurativskyi.rk over a
second-order field (see landau.verify.hybrid.specialise for how templates are bound).

Free names: ``fun(t, y, p, out)`` (the field, a numba function: it is inlined), ``stiff_step``
(the stick-phase step), ``jit`` (the numba decorator).
"""

import math

import numba as _nb
import numpy as np

from landau.verify.hybrid.compiled import (A21, A31, A32, A41, A42, A43, A51, A52, A53, A54, A61, A62, A63, A64,
                                           A65, B1, B3, B4, B5, B6, C2, C3, C4, C5, E1, E3, E4, E5, E6, E7)
from landau.verify.hybrid.compiled import err_norm as _err_norm
from landau.verify.hybrid.crossing import cubic_crossing
from landau.verify.skurativskyi.rk import MAX_EVENTS, MAX_STEPS, OK, STEP_TOO_SMALL, borrowed

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

#: the field and the steps below are inlined into the loop (numba IR inlining): a compiled call
#: that takes arrays pays two atomic reference-count updates per array, which measured ~40 % of
#: a run at ω = 16; inlining changes no arithmetic (the steps are bit-identical)
_fun = _nb.njit(inline="always")(fun.py_func) if hasattr(fun, "py_func") else fun


@_nb.njit(inline="always")
def dp5_step(p, t, y, k1, h, ynew, k7, err, yt, k2, k3, k4, k5, k6):
    """One Dormand–Prince 5(4) step (FSAL): the arithmetic of the compiled DOPRI5 of
    landau.verify.hybrid.compiled (``templates/dopri5.py``, ``stages``) term for term, into
    preallocated stage buffers."""
    n = y.shape[0]
    for a in range(n):
        yt[a] = y[a] + h * A21 * k1[a]
    _fun(t + C2 * h, yt, p, k2)
    for a in range(n):
        yt[a] = y[a] + h * (A31 * k1[a] + A32 * k2[a])
    _fun(t + C3 * h, yt, p, k3)
    for a in range(n):
        yt[a] = y[a] + h * (A41 * k1[a] + A42 * k2[a] + A43 * k3[a])
    _fun(t + C4 * h, yt, p, k4)
    for a in range(n):
        yt[a] = y[a] + h * (A51 * k1[a] + A52 * k2[a] + A53 * k3[a] + A54 * k4[a])
    _fun(t + C5 * h, yt, p, k5)
    for a in range(n):
        yt[a] = y[a] + h * (A61 * k1[a] + A62 * k2[a] + A63 * k3[a] + A64 * k4[a] + A65 * k5[a])
    _fun(t + h, yt, p, k6)
    for a in range(n):
        ynew[a] = y[a] + h * (B1 * k1[a] + B3 * k3[a] + B4 * k4[a] + B5 * k5[a] + B6 * k6[a])
    _fun(t + h, ynew, p, k7)
    for a in range(n):
        err[a] = h * (E1 * k1[a] + E3 * k3[a] + E4 * k4[a] + E5 * k5[a] + E6 * k6[a] + E7 * k7[a])


@_nb.njit(inline="always")
def bs3_step(p, t, y, k1, h, ynew, k4, err, yt, k2, k3):
    """One Bogacki–Shampine 3(2) step (FSAL; Bogacki & Shampine 1989): from (t, y) with
    k1 = f(t, y), fills ynew (order 3), k4 = f(t + h, ynew) and the embedded error estimate;
    yt, k2, k3 are scratch."""
    n = y.shape[0]
    for a in range(n):
        yt[a] = y[a] + h * (0.5 * k1[a])
    _fun(t + 0.5 * h, yt, p, k2)
    for a in range(n):
        yt[a] = y[a] + h * (0.75 * k2[a])
    _fun(t + 0.75 * h, yt, p, k3)
    for a in range(n):
        ynew[a] = y[a] + h * (2.0 / 9.0 * k1[a] + 1.0 / 3.0 * k2[a] + 4.0 / 9.0 * k3[a])
    _fun(t + h, ynew, p, k4)
    for a in range(n):
        err[a] = h * (-5.0 / 72.0 * k1[a] + 1.0 / 12.0 * k2[a] + 1.0 / 9.0 * k3[a] - 0.125 * k4[a])


@_nb.njit(inline="always")
def any_step(stiff, low, p, t, y, k1, h, rtol, atol, ynew, k7, err, yt, k2, k3, k4, k5, k6):
    """One step of the chosen method (the stick stepper, Bogacki–Shampine 3(2) if ``low``,
    else DOPRI5); returns (ok, f evaluations).  yt, k2…k6 are stage scratch."""
    if stiff:
        return stiff_step(p, t, y, h, rtol, atol, ynew, k7, err)
    if low:
        bs3_step(p, t, y, k1, h, ynew, k7, err, yt, k2, k3)
        return True, 3
    dp5_step(p, t, y, k1, h, ynew, k7, err, yt, k2, k3, k4, k5, k6)
    return True, 6


@jit
def integrate_mixed(p, t0, y0, t_end, rtol, atol, h0, hmax, xI, guard, strobe_t0, strobe_dt,
                    n_strobe_max, renorm, max_events, max_steps, v_stiff, a_stiff, rec_cap):
    """Integrate with contact switching at x = xI (``guard``), stroboscopic samples every
    ``strobe_dt`` from ``strobe_t0`` (if > 0) and tangent renormalisation there
    (``renorm``, 4-D systems).  A step that starts in stick — |ẋ| < ``v_stiff`` and
    |ẍ| < ``a_stiff`` (a velocity reversal crosses the band |ẋ| < v_stiff in ~2 v_stiff/|ẍ|,
    a few explicit steps; a stick stays in it) — is taken by the L-stable SDIRK4 of
    :mod:`landau.verify.skurativskyi.sdirk`, any other by DOPRI5 (``v_stiff`` ≤ 0: DOPRI5 only).
    See the module docstring.  Returns a tuple (see :func:`landau.verify.skurativskyi.simulate.run`)."""
    n = y0.shape[0]
    # the state, the stage buffers and the parameter vectors are used through borrowed views
    # (no reference count: rk.borrowed); their owners ``own``, ``y0``… stay alive to the end
    own = np.empty((13, n))
    own[0, :] = y0
    y = borrowed(own[0])
    k1, ynew, k7, err = borrowed(own[1]), borrowed(own[2]), borrowed(own[3]), borrowed(own[4])
    yt, k2, k3, k4 = borrowed(own[5]), borrowed(own[6]), borrowed(own[7]), borrowed(own[8])
    k5, k6 = borrowed(own[9]), borrowed(own[10])
    p_own, atol_own = p, atol
    p, atol = borrowed(p_own), borrowed(atol_own)
    t = t0
    _fun(t, y, p, k1)
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
    nrec = 0
    if rec_cap > 0:
        rec_t[0] = t
        rec_y[0, :] = y
        rec_f[0, :] = k1
        nrec = 1
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
    en_old = 1e-4  # the error norm of the last accepted step (PI control), Hairer's initial value
    after_reject = False
    loose = rtol >= LOOSE_RTOL
    low = rtol >= LOW_ORDER_RTOL
    pi_beta = (PI_BETA_BS if low else PI_BETA_DP) if loose else 0.0
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
                    _fun(t, y, p, k1)
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
        # 1/(q + 1) for the embedded orders q = 3 (SDIRK4), 2 (Bogacki–Shampine), 4 (DOPRI5)
        expo = 0.25 if stiff else (1.0 / 3.0 if low else 0.2)
        ok, nf = any_step(stiff, low, p, t, y, k1, h, rtol, atol, ynew, k7, err, yt, k2, k3, k4, k5, k6)
        nfev += nf
        en = _err_norm(err, y, ynew, rtol, atol) if ok else np.nan
        if not (en <= 1.0):
            nrej += 1
            after_reject = loose
            if en != en:  # NaN or a failed stage solve
                h *= 0.2
            else:
                h *= max(0.2, 0.9 * en ** -expo)
            continue
        if en == 0:
            fac = 10.0
        elif stiff or not loose:
            fac = min(10.0, 0.9 * en ** -expo)
        else:  # PI control (Gustafsson 1991; Hairer, Nørsett & Wanner II.4)
            fac = min(10.0, 0.9 * en ** (pi_beta * 0.75 - expo) * en_old ** pi_beta)
        if after_reject:  # no growth right after a rejection (Hairer, Norsett & Wanner, II.4)
            fac = min(fac, 1.0)
            after_reject = False
        en_old = max(en, 1e-4)
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
            if s_star > 0.0:
                # re-take the step onto the root; Newton on the step length (slope ẋ)
                hs = s_star * h
                for it in range(8):
                    ok, nf = any_step(stiff, low, p, t, y, k1, hs, rtol, atol, ynew, k7, err, yt, k2, k3, k4, k5, k6)
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
                _fun(t + h, ynew, p, k7)
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
        if nrec < rec_cap:
            rec_t[nrec] = t
            rec_y[nrec, :] = y
            rec_f[nrec, :] = k1
            nrec += 1
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
    y_end = y.copy()
    if p_own.shape[0] < 0 or atol_own.shape[0] < 0:  # keeps the owners alive past the loop
        y_end[0] = own[0, 0]
    return (t, y_end, status, ev_t[:nev].copy(), ev_k[:nev].copy(), ev_v[:nev].copy(), st_t[:nst].copy(),
            st_y[:nst].copy(), lyap, nly, nsteps, nfev, nrej, max_mismatch, nstiff, rec_t[:nrec].copy(),
            rec_y[:nrec].copy(), rec_f[:nrec].copy())


@jit
def integrate(p, t0, y0, t_end, rtol, atol, h0, hmax, xI, guard, strobe_t0, strobe_dt,
              n_strobe_max, renorm, max_events, max_steps, rec_cap):
    """The explicit path: :func:`integrate_mixed` with the stiff stepper disabled (the
    returned tuple has the stiff-step count as its last entry, always 0 here)."""
    return integrate_mixed(p, t0, y0, t_end, rtol, atol, h0, hmax, xI, guard, strobe_t0, strobe_dt,
                           n_strobe_max, renorm, max_events, max_steps, 0.0, 0.0, rec_cap)


