"""Runs of eq. (1): the compiled fast path and the hybrid-engine model.

* :func:`run` — the default path: compiled DOPRI5 with exact contact switching, stick
  phases (|ẋ| < :data:`V_STIFF`, |ẍ| < :data:`A_STICK`) by the L-stable SDIRK4 of
  :mod:`landau.verify.skurativskyi.sdirk`, stroboscopic samples t = 2πi/ω and (optionally) one tangent vector for the
  top Lyapunov exponent.  Returns a :class:`ForcedRun`, a
  :class:`~landau.verify.hybrid.result.Simulation` (impact times, inter-impact intervals, section points).
* :func:`hybrid_model` — the same model as a :class:`landau.verify.hybrid.HybridModel` with the
  modes ``"free"`` (x < x_I) and ``"contact"`` (x ≥ x_I) and guards ±(x − x_I); run it with
  ``landau.verify.hybrid.simulate(..., CompiledDOP853())`` (:mod:`landau.verify.hybrid.dop853`) or any
  scipy stepper.  Used to cross-check the fast path and to draw trajectories.

Impacts are the crossings of x = x_I with increasing x (the paper's definition, Sec. 5).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, replace

import numpy as np

from landau.errors import InputError, IntegratorError
from landau.support.deprecation import former_names
from landau.verify.hybrid import Event, Guard, HybridModel, Jump, Mode
from landau.verify.hybrid.log import LazyEventLog
from landau.verify.hybrid.result import Simulation, Status
from landau.verify.skurativskyi import rk as R
from landau.verify.skurativskyi.friction import quiet_first_class
from landau.verify.skurativskyi.model import Params, compiled_field


def integrators(params: Params):
    """The compiled event-driven loops for eq. (1) with the friction law of ``params``.

    The loops (:func:`landau.verify.skurativskyi.rk.integrate`, ``integrate_mixed``) are
    compiled once per machine for every law; this binds the law's friction callbacks
    (:attr:`landau.verify.skurativskyi.friction.CompiledFriction.pointers`, compiled once per
    law expression and cached on disk) as their last argument.

    Parameters
    ----------
    params : Params

    Returns
    -------
    (integrate, integrate_mixed)
        Functions of the loops' arguments without the last (``fr``).
    """
    fr = compiled_field(params).pointers
    mixed = R.mixed_loop()

    def integrate_mixed(*args):
        with quiet_first_class():
            return mixed(*args, fr)

    def integrate(*args):
        with quiet_first_class():
            return R.integrate(*args, fr)

    return integrate, integrate_mixed

#: default tolerances of the fast path: event/bifurcation locations converge at rtol ≲ 1e-8
#: (at rtol 1e-6 they move by ~0.01 rad/s); atol in m and m/s (the cart moves by mm at mm/s–cm/s): by default
#: atol = (rtol·1e-4 m, rtol·1e-2 m/s), i.e. (1e-12, 1e-10) at the default rtol.
RTOL = 1e-8
ATOL = None
#: |ẋ| [m/s] below which a step is taken by the stiff SDIRK4 (= 10 ε): there the regularised
#: friction slope T ε²/(m(ẋ² + ε²)^{3/2}) and the Hertz-damping slope ∝ |ẋ|^{n₃−1} (≳ 1e3 1/s)
#: bound the explicit step.  Measured (work-precision problems, rtol 1e-9…1e-5, without the
#: A_STICK test): 1e-5 is as fast as 1e-4/1e-3 at ω = 15 and 1.5–2× faster at ω = 16 (1e-3
#: puts whole contact phases on the costlier implicit stepper), with equal or better accuracy
V_STIFF = 1e-5
#: |ẍ| [m/s²] below which a step with |ẋ| < V_STIFF counts as stick: a velocity reversal
#: (|ẍ| ≳ 0.3 m/s² at ω = 15…25, measured) crosses the band in < 1e-4 s, where the implicit
#: steps would cost more than the few explicit ones; a stick (quasi-static creep, |ẍ| ≲ 1e-3)
#: lasts 5e-3…0.1 s
A_STICK = 0.05
#: run(method=...) → the (v_stiff, a_stiff) arguments of rk.integrate_mixed (0: explicit only)
METHODS = {"mixed": (V_STIFF, A_STICK), "dopri5": (0.0, 0.0)}
#: bound on the stroboscopic samples one run keeps (memory; later samples are not kept)
MAX_STROBES = 2_000_000


class ContactLog(LazyEventLog):
    """The impacts and detachments of a :class:`ForcedRun` as an :class:`EventLog`, its
    :class:`Event` objects built on first use from the run's arrays (a sweep over ω runs the
    simulator thousands of times and reads the arrays only: no Python work per event there).

    Parameters
    ----------
    xI : float
        The obstacle's position x_I (every event lies on x = x_I).
    impacts, impact_v, detachments : numpy.ndarray
        Times of the crossings x ↑ x_I, ẋ there, and times of the crossings x ↓ x_I.
    """

    def __init__(self, xI: float, impacts: np.ndarray, impact_v: np.ndarray, detachments: np.ndarray) -> None:
        xI = float(xI)

        def make() -> list[Event]:
            ev = sorted([(t, v, "impact") for t, v in zip(impacts, impact_v, strict=True)]
                        + [(t, np.nan, "detach") for t in detachments])
            out = []
            for t, v, g in ev:
                frm, to = ("free", "contact") if g == "impact" else ("contact", "free")
                out.append(Event(float(t), np.array([xI, v]), g, frm, to))
            return out

        super().__init__(make)


def _contact_regimes(start: float, t_final: float, impacts: np.ndarray, detachments: np.ndarray,
                     in_contact: bool) -> tuple:
    """``(t0, t1, "free" | "contact")`` between the contact events from ``start`` to ``t_final``
    (in contact from an impact to the next detachment; ``in_contact``: the mode of a run without
    events, else the mode before the first event is the one it leaves)."""
    if len(impacts) == 0 and len(detachments) == 0:   # most short runs: one regime
        return ((start, float(t_final), "contact" if in_contact else "free"),) if t_final > start else ()
    times = np.concatenate([impacts, detachments])
    order = np.argsort(times, kind="stable")
    is_impact = (order < len(impacts)).tolist()
    regimes = []
    inside = not is_impact[0] if is_impact else in_contact
    for t, imp in zip(times[order].tolist(), is_impact, strict=True):
        if t > start:
            regimes.append((start, t, "contact" if inside else "free"))
            start = t
        inside = imp
    if t_final > start:
        regimes.append((start, float(t_final), "contact" if inside else "free"))
    return tuple(regimes)


@dataclass(frozen=True, kw_only=True)
class ForcedRun(Simulation):
    """One run of the forced impacting oscillator (eq. 1 of Skurativskyi et al. 2019) by the
    compiled loop: a :class:`~landau.verify.hybrid.result.Simulation` (final state, recorded
    series, impacts and detachments as events, status) with the loop's own results.

    Returned by :func:`run` and read by the analyses (attractors, grazing, bifurcation diagrams).
    Times are in seconds, states (x, ẋ) in the model's units.  The base fields: ``t``, ``y``,
    ``f`` the recorded step ends (times, states and field, shape (n, m); ``run(..., record=N)``,
    empty otherwise), ``t_final``, ``y_final`` where the run ended (the tangent vector appended
    when the Lyapunov exponent is computed), ``events`` the impacts (guard ``"impact"``, free →
    contact) and detachments (``"detach"``) on x = x_I, ``regimes`` free/contact, ``nsteps``,
    ``nfev``, ``status``.

    Attributes
    ----------
    params : Params
        The parameters of the run.
    impacts, impact_v : numpy.ndarray
        Times of the crossings x ↑ x_I and ẋ there.
    detachments : numpy.ndarray
        Times of the crossings x ↓ x_I.
    strobe_t, strobe_y : numpy.ndarray
        Stroboscopic samples t = t0 + 2πi/ω and the states there, shape (k, 2) or (k, 4).
    lyap_sum : float
        Sum of the logarithms of the tangent vector's renormalisations.
    lyap_count : int
        Number of renormalisations (forcing periods).
    nrejected, nstiff : int
        Rejected steps, steps by the stiff SDIRK4.
    max_mismatch : float
        Largest |x − x_I| of a re-taken switching step before projection.
    method : str
        The integrator (``"mixed"`` or ``"dopri5"``).
    """

    params: Params
    impacts: np.ndarray = field(repr=False)          # times of x ↑ x_I
    impact_v: np.ndarray = field(repr=False)         # ẋ at impact
    detachments: np.ndarray = field(repr=False)      # times of x ↓ x_I
    strobe_t: np.ndarray = field(repr=False)
    strobe_y: np.ndarray = field(repr=False)         # (k, 2) or (k, 4)
    lyap_sum: float = 0.0
    lyap_count: int = 0
    nrejected: int = 0
    max_mismatch: float = 0.0    # |x − x_I| of a re-taken switching step before projection
    nstiff: int = 0              # steps taken by the stiff SDIRK4 (stick phases)
    method: str = "dopri5"

    @property
    def intervals(self) -> np.ndarray:
        """Inter-impact intervals T_j."""
        return np.diff(self.impacts)

    def impacts_per_period(self, t_from: float | None = None) -> float:
        """Mean number of impacts per forcing period after ``t_from`` (default: first strobe)."""
        t0 = self.strobe_t[0] if t_from is None else t_from
        n = np.count_nonzero(self.impacts >= t0)
        return n / ((self.t_final - t0) / self.params.period)

    @property
    def lyapunov(self) -> float:
        """Top Lyapunov exponent [1/s] from the tangent renormalisations (NaN without them)."""
        if self.lyap_count == 0:
            return float("nan")
        return self.lyap_sum / (self.lyap_count * self.params.period)

    def simulation(self) -> "ForcedRun":
        """Deprecated: the record is already a :class:`~landau.verify.hybrid.result.Simulation`;
        returns the record itself."""
        warnings.warn("ForcedRun.simulation() is deprecated: the record is already a Simulation (use it "
                      "directly)", DeprecationWarning, stacklevel=2)
        return self

    def __repr__(self) -> str:
        return (f"ForcedRun(ω={self.params.omega:g}, t={self.t_final:.6g}, {len(self.impacts)} impacts, "
                f"{len(self.strobe_t)} strobe points, {self.nsteps} steps, {self.nfev} fev)")


_STATE_NAMES = ("x", "xdot", "dx", "dxdot")


def _forced_run(params: Params, t_start: float, t_final: float, y_final: np.ndarray, status: Status, ev_t, ev_k,
                ev_v, rec_t, rec_y, rec_f, **extra) -> ForcedRun:
    """The :class:`ForcedRun` of the loop's arrays (events ``ev_k`` > 0 impacts, else
    detachments; recorded rows (m, n) stored as (n, m))."""
    if len(ev_k):
        up = ev_k > 0
        impacts, impact_v, detachments = ev_t[up], ev_v[up], ev_t[~up]
    else:
        impacts, impact_v, detachments = ev_t, ev_v, ev_t[:0]
    msg = status.advice
    if status is not Status.FINISHED:
        msg = f"stopped at t = {t_final:.6g} s by its limit: {status.advice}"
    return ForcedRun(model=f"skurativskyi2019(ω={params.omega:g})", t=rec_t, y=rec_y.T,
                     events=ContactLog(params.xI, impacts, impact_v, detachments), status=status, message=msg,
                     t_final=t_final, y_final=y_final, f=rec_f.T, state_names=_STATE_NAMES[:len(y_final)],
                     regimes=_contact_regimes(t_start, t_final, impacts, detachments, bool(y_final[0] > params.xI)),
                     params=params, impacts=impacts, impact_v=impact_v, detachments=detachments, **extra)


def rest_state(params: Params) -> np.ndarray:
    """Static equilibrium X₀ at rest (Sec. 5) as the default initial state."""
    from landau.verify.skurativskyi.approx import static_equilibrium
    return np.array([static_equilibrium(params), 0.0])


def run(params: Params, n_periods: float, y0=None, t0: float = 0.0, rtol: float = RTOL, atol=None,
        lyapunov: bool = False, strobe: bool = True, max_events: int = 200_000,
        max_steps: int = 50_000_000, tangent0=(1.0, 0.0), method: str = "mixed", record: int = 0,
        at_limit: str = "raise") -> ForcedRun:
    """Integrate eq. (1) over ``n_periods`` forcing periods from (t0, y0) (default: rest at X₀).

    Strobe times are t0 + i·2π/ω.  ``lyapunov=True`` adds the variational equation and
    renormalises the tangent vector every period.  ``method``: ``"mixed"`` (default) takes
    steps that start in stick (|ẋ| < :data:`V_STIFF`, |ẍ| < :data:`A_STICK`) with the
    L-stable SDIRK4 (:mod:`landau.verify.skurativskyi.sdirk`) and all others with DOPRI5;
    ``"dopri5"`` is the explicit path alone.  ``record``: keep up to that many accepted step ends
    (t, y, f) as the run's time series (``t``, ``y``, ``f`` of the :class:`ForcedRun`).  Raises
    IntegratorError on failure.

    Parameters
    ----------
    params : Params
        Model parameters (the forcing frequency among them).
    n_periods : float
        Length of the run in forcing periods.
    y0 : array_like, optional
        Starting state (default: rest at X₀).
    t0 : float, optional
        Starting time, s.
    rtol, atol : float, optional
        Integration tolerances.
    lyapunov : bool, optional
        Also compute the largest Lyapunov exponent (see above).
    strobe : bool, optional
        Record the stroboscopic (Poincaré) samples.
    max_events, max_steps : int, optional
        Limits that end a run which would not finish.
    tangent0 : tuple of float, optional
        Starting tangent vector of the variational equation.
    method : {"mixed", "dopri5"}
        The integrator (see above).
    record : int, optional
        Keep up to that many step ends as the time series.
    at_limit : {"raise", "return"}, optional
        At ``max_steps`` or ``max_events``: raise IntegratorError (default) or return the run
        up to there with its ``status`` (:attr:`Status.MAX_STEPS`, :attr:`Status.MAX_EVENTS`).

    Returns
    -------
    ForcedRun
        Final state, impacts, detachments, stroboscopic points and (with ``record``) the time series.

    References
    ----------
    Skurativskyi, S., Kudra, G., Witkowski, K. & Awrejcewicz, J. (2019), "Bifurcation phenomena
    and statistical regularities in dynamics of forced impacting oscillator", Nonlinear Dyn. 98,
    1795–1806, eq. (1).
    """
    if method not in METHODS:
        raise InputError(f"method must be one of {sorted(METHODS)} (got {method!r})")
    if at_limit not in ("raise", "return"):
        raise InputError(f"at_limit must be 'raise' or 'return' (got {at_limit!r})")
    if not (n_periods > 0 and np.isfinite(n_periods)):
        raise InputError(f"n_periods must be positive (got {n_periods!r})")
    if not (0 < rtol < 1):
        raise InputError(f"rtol must be in (0, 1) (got {rtol!r})")
    if n_periods * 20 > max_steps:
        # the largest step is a twentieth of the period: such a run cannot end within its step budget
        raise InputError(f"the run spans {n_periods:.3g} forcing periods (omega = {params.omega:g} rad/s), and "
                         f"takes at least 20 steps a period: more than its step budget of {max_steps} steps; lower "
                         "omega or shorten the time span")
    y0 = rest_state(params) if y0 is None else np.asarray(y0, float)[:2]
    P = params.period
    p = params.packed()
    at = np.ascontiguousarray((rtol * 1e-4, rtol * 1e-2) if atol is None else atol, float)
    if lyapunov:
        tv = np.asarray(tangent0, float)
        y = np.concatenate([y0, tv / np.linalg.norm(tv)])
        at = np.concatenate([at, [1e-9, 1e-9]])
    else:
        y = y0.copy()
    t_end = t0 + n_periods * P if float(n_periods) != int(n_periods) else t0 + int(n_periods) * P
    # strobe samples past the buffer are not kept (the steps still end on the strobe times)
    n_st = min(int(n_periods) + 2, MAX_STROBES) if strobe else 1
    fr = compiled_field(params).pointers
    loop = R.mixed_loop()
    with quiet_first_class():
        out = loop(p, float(t0), y, float(t_end), float(rtol), at, 1e-5, float(P / 20), float(params.xI), True,
                   float(t0), float(P) if strobe or lyapunov else 0.0, int(n_st), bool(lyapunov), int(max_events),
                   int(max_steps), *METHODS[method], int(record), fr)
    (t, yend, status, ev_t, ev_k, ev_v, st_t, st_y, ly, nly, nsteps, nfev, nrej, mism, nstiff,
     rec_t, rec_y, rec_f) = out
    st = Status.FINISHED
    if status != R.OK:
        st = {R.MAX_STEPS: Status.MAX_STEPS, R.STEP_TOO_SMALL: Status.STEP_SIZE_UNDERFLOW,
              R.MAX_EVENTS: Status.MAX_EVENTS}.get(status, Status.FAILED)
    if st is not Status.FINISHED and not (at_limit == "return" and st in (Status.MAX_STEPS, Status.MAX_EVENTS)):
        raise IntegratorError(f"compiled {method} integrator stopped: {R.STATUS[status]} (ω={params.omega}): "
                              f"{st.advice}", t=t, state=yend)
    return _forced_run(params, float(t0), t, yend, st, ev_t, ev_k, ev_v, rec_t, rec_y, rec_f, nsteps=nsteps,
                       nfev=nfev, strobe_t=st_t, strobe_y=st_y, lyap_sum=ly, lyap_count=nly, nrejected=nrej,
                       max_mismatch=mism, nstiff=nstiff, method=method)


def hybrid_model(params: Params) -> HybridModel:
    """Eq. (1) as an engine model: modes ``free``/``contact`` switching at x = x_I (the state is
    kept, the field is continuous there; the transition only relabels the mode)."""
    fld = R.CompiledField(compiled_field(params).rhs, params.packed())
    xI = params.xI

    def to_contact(t, y):
        return Jump("contact", np.array([xI, y[1]]), "impact")

    def to_free(t, y):
        return Jump("free", np.array([xI, y[1]]), "detachment")

    free = Mode("free", fld, (Guard("impact", lambda t, y: xI - y[0], to_contact,
                                    rate=lambda t, y: -y[1]),))
    contact = Mode("contact", fld, (Guard("detach", lambda t, y: y[0] - xI, to_free,
                                          rate=lambda t, y: y[1]),))
    return HybridModel.from_modes(free, contact, name="skurativskyi2019")


def _thin(n: int) -> np.ndarray:
    """Every other index of range(n), the last one kept."""
    idx = np.arange(0, n, 2)
    return idx if n == 0 or idx[-1] == n - 1 else np.append(idx, n - 1)


def record_run(params: Params, t_end: float, y0=None, *, rtol: float = RTOL, max_steps: int = 5_000_000,
               max_events: int = 200_000, max_points: int = 200_000, chunk_steps: int = 200_000,
               method: str = "mixed") -> ForcedRun:
    """Eq. (1) from t = 0 to ``t_end`` [s] with bounded steps, events and memory, as a :class:`ForcedRun`.

    The run is taken in compiled calls of at most ``chunk_steps`` steps (each continuing from the
    previous one's state, the stroboscopic phase kept at t = 2πi/ω); the recorded step ends are
    streamed out of each call and decimated (every other point dropped, then every 2ᵏ-th step
    end kept) whenever they would exceed ``max_points``, so that a run of any length keeps at most
    about ``max_points`` points spread over its whole span.  At ``max_steps`` steps or
    ``max_events`` contact events it ends with status ``max-steps`` / ``max-events`` and the
    record up to there.  A run shorter than ``chunk_steps`` is the one call of :func:`run`.

    Parameters
    ----------
    params : Params
        Model parameters.
    t_end : float
        End time [s].
    y0 : array_like, optional
        Starting (x, ẋ) (default: rest at X₀).
    rtol : float, optional
        Relative tolerance (absolute tolerances as in :func:`run`).
    max_steps, max_events, max_points, chunk_steps : int, optional
        The bounds (see above).
    method : {"mixed", "dopri5"}
        The integrator (:func:`run`).

    Returns
    -------
    ForcedRun
        A :class:`~landau.verify.hybrid.result.Simulation`: times in s, states (x, ẋ) with the field
        at each point; impacts and detachments as events.
    """
    if method not in METHODS:
        raise InputError(f"method must be one of {sorted(METHODS)} (got {method!r})")
    if not (np.isfinite(t_end) and t_end > 0):
        raise InputError(f"t_end must be a finite time > 0 (got {t_end!r})")
    if not (int(max_steps) >= 1 and int(chunk_steps) >= 1 and int(max_points) >= 16 and int(max_events) >= 1):
        raise InputError("max_steps, max_events and chunk_steps must be >= 1 and max_points >= 16")
    y = rest_state(params) if y0 is None else np.asarray(y0, float)[:2].copy()
    P = params.period
    if not P > 2e-13 * max(1.0, t_end):
        # the loop takes at least 20 steps a period and stops below a step of 1e-15·max(1, t)
        raise InputError(f"the forcing period {P:.3g} s (omega = {params.omega:g} rad/s) is shorter than the "
                         f"integrator resolves up to t = {t_end:g} s (its steps would fall below "
                         "1e-15·max(1, t)): lower omega or shorten the time span")
    p = params.packed()
    at = np.ascontiguousarray((rtol * 1e-4, rtol * 1e-2), float)
    fr = compiled_field(params).pointers
    loop = R.mixed_loop()
    t = 0.0
    rec_t: list = []
    rec_y: list = []
    rec_f: list = []
    kept, stride = 0, 1
    ev_t: list = []
    ev_k: list = []
    ev_v: list = []
    steps = nfev = 0
    status = Status.FINISHED
    while True:
        budget = min(int(chunk_steps), int(max_steps) - steps)
        room = int(max_events) - sum(len(e) for e in ev_t)
        with quiet_first_class():
            out = loop(p, float(t), y, float(t_end), float(rtol), at, 1e-5, float(P / 20), float(params.xI), True,
                       0.0, float(P), 1, False, int(room), int(budget), *METHODS[method], int(budget) + 1, fr)
        (tn, yn, st, et, ek, ev, _, _, _, _, ns, nf, _, _, _, rt, ry, rf) = out
        steps += int(ns)
        nfev += int(nf)
        ev_t.append(et)
        ev_k.append(ek)
        ev_v.append(ev)
        if rec_t:   # the call's first point is the previous call's last
            rt, ry, rf = rt[1:], ry[1:], rf[1:]
        if stride > 1 and len(rt):   # every stride-th step end, and the call's last (the state it ends in)
            sel = np.unique(np.append(np.arange(stride - 1, len(rt), stride), len(rt) - 1))
            rt, ry, rf = rt[sel], ry[sel], rf[sel]
        rec_t.append(rt)
        rec_y.append(ry)
        rec_f.append(rf)
        kept += len(rt)
        while kept > max_points:
            tt, yy, ff = np.concatenate(rec_t), np.concatenate(rec_y), np.concatenate(rec_f)
            keep = _thin(len(tt))
            rec_t, rec_y, rec_f, kept = [tt[keep]], [yy[keep]], [ff[keep]], len(keep)
            stride *= 2
        t, y = float(tn), np.array(yn[:2], float)
        if st == R.OK:
            break
        if st == R.MAX_EVENTS:
            status = Status.MAX_EVENTS
            break
        if st != R.MAX_STEPS:
            raise IntegratorError(f"compiled {method} integrator stopped: {R.STATUS[st]} (ω={params.omega})",
                                  t=t, state=y)
        if steps >= max_steps:
            status = Status.MAX_STEPS
            break
    tt, yy, ff = np.concatenate(rec_t), np.concatenate(rec_y), np.concatenate(rec_f)
    ek_all, et_all, ev_all = np.concatenate(ev_k), np.concatenate(ev_t), np.concatenate(ev_v)
    sim = _forced_run(params, 0.0, t, y, status, et_all, ek_all, ev_all, tt, yy, ff, nsteps=steps, nfev=nfev,
                      strobe_t=np.empty(0), strobe_y=np.empty((0, 2)), method=method)
    if status is not Status.FINISHED:
        sim = replace(sim, message=f"stopped at the {'step' if status is Status.MAX_STEPS else 'event'} limit "
                                   f"({int(max_steps) if status is Status.MAX_STEPS else int(max_events)}) at "
                                   f"t = {t:.6g} s before the end t = {t_end:.6g} s: {status.advice}")
    return sim


# the former name of the raw record, kept for one release
_RENAMED = {"Run": (lambda: ForcedRun,
                "use ForcedRun (the record of one forced-oscillator run, a Simulation)")}
__getattr__ = former_names(__name__, _RENAMED)
