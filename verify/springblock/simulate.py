"""Integrate the compiled spring–block (:mod:`landau.verify.springblock.model`) with the numba Radau IIA.

:func:`integrate` runs the default integrator between physical times (seconds), optionally
locating crossings of one component (e.g. w = ln(v/V) = 0, where X = x − x₀ is extremal)
and stopping after a given number of them; every failure raises
:class:`~landau.errors.IntegratorError` carrying the time and the physical state.

The integrator is the order-5 Radau IIA of :mod:`landau.verify.hybrid.radau` (Newton system
in the eigenbasis of A⁻¹, Hairer & Wanner 1996, IV.8), compiled once per machine; the law's
right-hand side and Jacobian reach it as compiled C callbacks.  A run is a :class:`RadauRecord`, the
common result type :class:`~landau.verify.hybrid.result.Simulation` with the integrator's counters
and the located crossings as arrays; :func:`record_run` streams a long run with bounded memory.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field, replace

import numpy as np

from landau.errors import InputError, IntegratorError
from landau.support.deprecation import former_names
from landau.verify.hybrid.log import Event, LazyEventLog
from landau.verify.hybrid.radau import STATUS, radau_core
from landau.verify.hybrid.result import Simulation, Status, status_from_text
from landau.verify.springblock.model import SpringBlockModel, compile_variational

#: index of w = ln(v/V) in the scaled state; w = 0 ⇔ ẋ = V ⇔ X = x − x₀ extremal
W_INDEX = 1

#: the one method :func:`integrate` knows (the name is accepted for existing callers)
METHODS = ("radau5",)


@dataclass(frozen=True, kw_only=True)
class RadauRecord(Simulation):
    """One compiled Radau IIA integration of the spring–block (eq. 4/5 of Putelat et al. 2010):
    a :class:`~landau.verify.hybrid.result.Simulation` with the integrator's counters and the
    located crossings as arrays.

    Returned by :func:`integrate` and :func:`record_run` and read by the shooting and analysis
    code.  Times are in seconds, states scaled as in the model (convert with
    ``model.to_physical``).  The base fields: ``t``, ``y`` (shape (n, m)) the recorded steps
    (``integrate(..., record=N)``; empty by default), ``t_final``, ``y_final`` the end of the run,
    ``status`` :attr:`~landau.verify.hybrid.result.Status.FINISHED` at the end of ``t_span`` or
    :attr:`~landau.verify.hybrid.result.Status.STOPPED` after ``stop_after`` crossings, ``nsteps``
    the accepted steps, ``events`` the located crossings as ``"section"`` events (guard
    ``"crossing"``, ``note`` ``"up"`` or ``"down"``).

    Attributes
    ----------
    rejected, njev, nlu : int
        Rejected steps, Jacobian evaluations, LU factorisations.
    cpu_seconds : float
        CPU time of the compiled loop (process time), s.
    event_t, event_y, event_dir : numpy.ndarray
        Times (s), scaled states (one row per crossing) and directions (+1 up, −1 down) of the
        located crossings: the arrays behind ``events``.
    """

    rejected: int
    njev: int
    nlu: int
    cpu_seconds: float
    event_t: np.ndarray = field(repr=False)
    event_y: np.ndarray = field(repr=False)
    event_dir: np.ndarray = field(repr=False)

    def simulation(self, model: str | None = None) -> "RadauRecord":
        """Deprecated: the record is already a :class:`~landau.verify.hybrid.result.Simulation`.

        Parameters
        ----------
        model : str, optional
            A model name replacing ``"spring-block"`` (a copy of the record is returned then).

        Returns
        -------
        RadauRecord
            The record itself.
        """
        warnings.warn("RadauRecord.simulation() is deprecated: the record is already a Simulation "
                      "(use it directly)", DeprecationWarning, stacklevel=2)
        return self if model is None or model == self.model else replace(self, model=model)

    def __repr__(self) -> str:
        return (f"RadauRecord({self.model}, {self.status.value}, t_final={self.t_final:.6g} s, "
                f"{len(self.t)} points, steps={self.nsteps}, rejected={self.rejected}, nfev={self.nfev}, "
                f"events={len(self.event_t)}, cpu={self.cpu_seconds:.3g} s)")


def _crossing_log(event_t: np.ndarray, event_y: np.ndarray, event_dir: np.ndarray) -> LazyEventLog:
    """The located crossings as ``"section"`` events (guard ``"crossing"``, note ``"up"`` or
    ``"down"``), made from the engine's arrays on first use: a run whose events nobody reads does
    not pay for them (an empty log costs 0.74 µs to make where the list built at once cost 1.96 µs,
    and a run with many crossings saves an :class:`Event` per crossing)."""
    def make():
        return [Event(t, y, "crossing", "slip", "slip", "section", y, "up" if d > 0 else "down")
                for t, y, d in zip(event_t.tolist(), event_y, event_dir.tolist(), strict=True)]
    return LazyEventLog(make)


def _record(status: Status, message: str, t_final: float, y_final: np.ndarray, counts, cpu: float,
            event_t: np.ndarray, event_y: np.ndarray, event_dir: np.ndarray, rec_t: np.ndarray,
            rec_y: np.ndarray) -> RadauRecord:
    """The one place a :class:`RadauRecord` is built: ``counts`` = (accepted, rejected, nfev, njev,
    nlu), ``rec_y`` of shape (m, n) as the compiled loop records it."""
    accepted, rejected, nfev, njev, nlu = counts[:5].tolist()
    return RadauRecord(model="spring-block", t=rec_t, y=rec_y.T,
                       events=_crossing_log(event_t, event_y, event_dir), status=status, message=message,
                       t_final=t_final, y_final=y_final, nsteps=accepted, nfev=nfev, rejected=rejected, njev=njev,
                       nlu=nlu, cpu_seconds=cpu, event_t=event_t, event_y=event_y, event_dir=event_dir)


def integrate(model: SpringBlockModel, y0, t_span: tuple[float, float], *, rtol: float = 1e-9,
              atol: float | np.ndarray | None = None, max_steps: int = 5_000_000,
              event_index: int = -1, event_value: float = 0.0, event_direction: int = 0,
              stop_after: int = 0, max_events: int = 100_000, record: int = 0,
              first_step: float | None = None, max_step: float = np.inf, variational: bool = False,
              method: str = "radau5") -> RadauRecord:
    """Integrate eq. (4) from ``y0`` (scaled state) over ``t_span`` seconds with the default integrator.

    ``atol`` defaults to ``rtol`` (all variables are O(1) by construction).  ``record`` is the
    maximum number of accepted steps kept for plotting.  ``variational=True`` integrates the
    state augmented with Φ' = J(y)Φ (``y0`` of length n + n², Φ row-major) for monodromy matrices.
    Raises IntegratorError on failure.

    Parameters
    ----------
    model : SpringBlockModel
        Eq. (4) of Putelat et al. (2010) for one law, V and k.
    y0 : array_like
        Initial scaled state (ξ = X/ℓ, ln(v/V), ln(φᵢ/φᵢ₀)); ``model.perturbed(a)`` gives one
        displaced by X = a [m] along the critical mode.
    t_span : (float, float)
        Start and end times (s).
    rtol : float, optional
        Relative tolerance of the Radau IIA step-size control.
    atol : float or array_like, optional
        Absolute tolerance (default: ``rtol``; the scaled variables are O(1)).
    event_index : int, optional
        Component whose crossings of ``event_value`` are located (−1: none).
    event_value : float, optional
        The value crossed.
    event_direction : int, optional
        +1 upward, −1 downward, 0 both.
    stop_after : int, optional
        End the run after that many located crossings (0: run to the end of ``t_span``).
    record : int, optional
        Number of accepted steps kept in ``t``, ``y`` (from the start; 0: none).
    method : {"radau5"}, optional
        The integrator (the only one: the order-5 Radau IIA, module docstring).

    Returns
    -------
    RadauRecord
        A :class:`~landau.verify.hybrid.result.Simulation`: the final time and state
        (``t_final``, ``y_final``), the status (``FINISHED`` or ``STOPPED`` after ``stop_after``
        crossings), the recorded steps ``t``, ``y`` (shape (n, m); convert states with
        ``model.to_physical(y.T)``), the located crossings (``events`` and the arrays
        ``event_t``, ``event_y``, ``event_dir``), step counts and CPU time.

    Raises
    ------
    IntegratorError
        With the time and the physical state at failure.

    References
    ----------
    Hairer, E., Wanner, G. (1996). Solving Ordinary Differential Equations II, 2nd ed.,
    Springer, Sec. IV.8 (Radau IIA).
    """
    if method not in METHODS:
        raise InputError(f"method must be {' or '.join(repr(m) for m in METHODS)} (the order-5 Radau IIA), "
                         f"got {method!r}")
    c = compile_variational(model.law, model.terms) if variational else model.compiled
    nn = c.n
    if not (0 < rtol < 1):
        raise InputError(f"rtol must be in (0, 1), got {rtol!r}")
    y0 = np.ascontiguousarray(y0, dtype=float)
    if y0.shape != (nn,):
        raise InputError(f"initial state must have {nn} components, got shape {y0.shape}")
    tu = model.time_unit
    t0, t1 = float(t_span[0]) / tu, float(t_span[1]) / tu
    if not t1 > t0:
        raise InputError("t_span must be increasing")
    at = np.full(nn, rtol if atol is None else 0.0) if atol is None or np.isscalar(atol) else None
    if at is None:
        at = np.ascontiguousarray(atol, dtype=float)
    elif atol is not None:
        at[:] = float(atol)
    h0 = (first_step / tu) if first_step else min(1e-3 * (t1 - t0), 1e-4)
    ms = max_step / tu if np.isfinite(max_step) else np.inf
    evbuf = np.empty((max_events if event_index >= 0 else 1, nn + 1))
    evdir = np.empty(evbuf.shape[0])
    tic = time.process_time()
    st, t, y, cnt, et, ey, rt, ry, _, _ = radau_core(c.rhs, c.jac, t0, y0, t1, model.p, float(rtol), at, float(h0),
                                                     float(ms), int(max_steps), int(event_index), float(event_value),
                                                     int(event_direction), int(stop_after), int(record), None, None,
                                                     evbuf, evdir)
    cpu = time.process_time() - tic
    if st < 0:
        phys = model.to_physical(y[:model.n])
        state = [float(phys["X"]), float(phys["v"])] + [float(phys[s.name]) for s in model.law.states]
        raise IntegratorError(f"spring-block[{model.law.name}] integration failed: {STATUS[int(st)]} after "
                              f"{int(cnt[0])} steps (state = X [m], v [m/s], phi...): "
                              f"{status_from_text(STATUS[int(st)]).advice}", t=float(t * tu), state=state)
    status = Status.STOPPED if st == 1 else Status.FINISHED
    return _record(status, status.advice, float(t * tu), y.copy(), cnt, cpu, et * tu, ey,
                   evdir[:len(et)].astype(int), rt * tu, ry)


#: step attempts per compiled call of :func:`record_run` (its accepted steps are recorded)
CHUNK_STEPS = 200_000
#: default bound on the points :func:`record_run` keeps (decimated past it)
MAX_POINTS = 200_000


def _thin_every_other(t: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every other point of a recorded series, the last one kept."""
    idx = np.arange(0, len(t), 2)
    if len(t) and idx[-1] != len(t) - 1:
        idx = np.append(idx, len(t) - 1)
    return t[idx], y[idx]


def record_run(model: SpringBlockModel, y0, t_span: tuple[float, float], *, rtol: float = 1e-9,
               max_steps: int = 5_000_000, max_points: int = MAX_POINTS, event_index: int = -1,
               event_value: float = 0.0, max_events: int = 100_000, chunk_steps: int = CHUNK_STEPS) -> RadauRecord:
    """Integrate eq. (4) over ``t_span`` with bounded steps and memory.

    The run is taken in compiled calls of at most ``chunk_steps`` step attempts each, every call
    continuing from the previous one's state and step size; the recorded series is streamed
    out of each call and decimated (every other point dropped, then every 2ᵏ-th step end
    kept) whenever it would exceed ``max_points``, so that a run of any length keeps at most
    about ``max_points`` points spread over its whole span.  After ``max_steps`` step attempts the
    run ends with status :attr:`~landau.verify.hybrid.result.Status.MAX_STEPS` and the series
    up to there (it does not raise); the other integrator failures raise as in
    :func:`integrate`.  A run shorter than ``chunk_steps`` is the same computation as one call
    of :func:`integrate`.

    Parameters
    ----------
    model : SpringBlockModel
        Eq. (4) of Putelat et al. (2010) for one law, V and k.
    y0 : array_like
        Initial scaled state.
    t_span : (float, float)
        Start and end times (s).
    rtol : float, optional
        Relative (and absolute) tolerance of the Radau IIA.
    max_steps : int, optional
        Budget of step attempts (accepted and rejected) of the whole run.
    max_points : int, optional
        Bound on the recorded points (times in seconds, scaled states).
    event_index, event_value : int, float, optional
        Crossings of ``y[event_index] = event_value`` logged as ``"section"`` events (−1: none).
    max_events : int, optional
        Bound on the logged crossings (later ones are not logged; the run goes on).
    chunk_steps : int, optional
        Step attempts per compiled call.

    Returns
    -------
    RadauRecord
        Status ``finished`` or ``max-steps``; ``t`` in seconds, ``y`` scaled; ``nsteps`` and
        ``rejected`` the accepted and rejected steps, the other counters summed over the calls.
    """
    if not (int(max_steps) >= 1 and int(max_points) >= 16 and int(chunk_steps) >= 1):
        raise InputError("max_steps and chunk_steps must be >= 1 and max_points >= 16")
    tu = model.time_unit
    t0, t1 = float(t_span[0]), float(t_span[1])
    if not (np.isfinite(t0) and np.isfinite(t1) and t1 > t0):
        raise InputError(f"t_span must be finite and increasing, got {tuple(t_span)!r}")
    c = model.compiled
    nn = c.n
    y = np.ascontiguousarray(y0, dtype=float)
    if y.shape != (nn,):
        raise InputError(f"initial state must have {nn} components, got shape {y.shape}")
    at = np.full(nn, float(rtol))
    t, h = t0 / tu, min(1e-3 * (t1 - t0) / tu, 1e-4)
    rec_t, rec_y = [np.array([t0])], [y[None, :].copy()]
    kept, stride = 1, 1
    ev_t: list = []
    ev_y: list = []
    ev_d: list = []
    steps = 0                          # step attempts, accepted and rejected
    counts = np.zeros(5, dtype=np.int64)   # accepted, rejected, nfev, njev, nlu
    n_ev = 0
    cpu = 0.0
    status = Status.FINISHED
    while True:
        budget = min(int(chunk_steps), int(max_steps) - steps)
        room = max(int(max_events) - n_ev, 0)
        evbuf = np.empty((max(room, 1) if event_index >= 0 else 1, nn + 1))
        evdir = np.empty(evbuf.shape[0])
        # a budget of step attempts (accepted and rejected), as integrate's max_steps; room for the
        # start and every step of the call in the record
        tic = time.process_time()
        st, tn, yn, cnt, et, ey, rt, ry, hn, _ = radau_core(
            c.rhs, c.jac, t, y, t1 / tu, model.p, float(rtol), at, float(h), np.inf, budget,
            int(event_index) if room else -1, float(event_value), 0, 0, budget + 1, None, None, evbuf, evdir)
        cpu += time.process_time() - tic
        steps += int(cnt[0]) + int(cnt[1])
        counts += cnt[:5]
        if st == -1 or st == -3:
            phys = model.to_physical(yn[:model.n])
            state = [float(phys["X"]), float(phys["v"])] + [float(phys[s.name]) for s in model.law.states]
            raise IntegratorError(f"spring-block[{model.law.name}] integration failed: {STATUS[int(st)]} after "
                                  f"{steps} steps (state = X [m], v [m/s], phi...): "
                                  f"{status_from_text(STATUS[int(st)]).advice}", t=float(tn * tu), state=state)
        ev_t.append(et * tu)
        ev_y.append(ey)
        ev_d.append(evdir[:len(et)].astype(int))
        n_ev += len(et)
        rt, ry = rt[1:] * tu, ry[1:]   # a call records its start: the previous call's end (or t0)
        if stride > 1:   # decimated recording: every stride-th step end of this call
            rt, ry = rt[stride - 1::stride], ry[stride - 1::stride]
        rec_t.append(rt)
        rec_y.append(ry)
        kept += len(rt)
        while kept > max_points:
            tt, yy = _thin_every_other(np.concatenate(rec_t), np.concatenate(rec_y))
            rec_t, rec_y, kept = [tt], [yy], len(tt)
            stride *= 2
        t, y, h = float(tn), yn.copy(), float(hn)
        if st == 0 or st == 1:
            break
        if steps >= max_steps:
            status = Status.MAX_STEPS
            break
    tt, yy = np.concatenate(rec_t), np.concatenate(rec_y)
    if tt[-1] < t * tu:   # a decimated record keeps the final state
        tt, yy = np.append(tt, t * tu), np.vstack([yy, y[None, :]])
    msg = status.advice
    if status is Status.MAX_STEPS:
        msg = (f"stopped at the step limit ({int(max_steps)} steps) at t = {t * tu:.6g} s before the end "
               f"t = {t1:.6g} s: {status.advice}")
    return _record(status, msg, t * tu, y, counts, cpu, np.concatenate(ev_t), np.concatenate(ev_y),
                   np.concatenate(ev_d), tt, yy)


# the former name of the record, kept for one release
_RENAMED = {"Run": (lambda: RadauRecord,
                "use RadauRecord (the record of one Radau IIA integration, a Simulation)")}
__getattr__ = former_names(__name__, _RENAMED)
