"""One result type for every simulation: a dense time series, the events and a status.

Every simulator returns a :class:`Simulation`: the hybrid engine's
:class:`~landau.verify.hybrid.simulate.HybridSolution`, the spring–block's
:class:`~landau.verify.springblock.simulate.RadauRecord` and the forced oscillator's
:class:`~landau.verify.skurativskyi.simulate.ForcedRun` are subclasses that add only what their
engine alone knows (counters, located crossings, impacts, the final mode):

* ``t``, ``y``: the recorded time series (accepted step ends or dense-output samples; ``y``
  has shape (n, m)), and :meth:`Simulation.at` interpolating it (cubic Hermite where the
  field's values are recorded, else linear);
* ``events``: an :class:`~landau.verify.hybrid.EventLog` (impacts, switches, section
  crossings) in time order;
* ``status``: a :class:`Status` with an actionable ``message`` (what stopped the run and
  what to change).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np

from landau.verify.hybrid.log import EventLog


class Status(enum.Enum):
    """How a simulation ended; ``advice`` says what to change when it is not a success."""

    FINISHED = "finished"
    STOPPED = "stopped"
    STEP_SIZE_UNDERFLOW = "step-size-underflow"
    MAX_STEPS = "max-steps"
    MAX_EVENTS = "max-events"
    NON_FINITE = "non-finite"
    ZENO = "zeno"
    EVENT_RATE = "event-rate"
    WALL_TIME = "wall-time"
    FAILED = "failed"

    @property
    def success(self) -> bool:
        """True when the run reached its final time or a requested stop."""
        return self in (Status.FINISHED, Status.STOPPED)

    @property
    def advice(self) -> str:
        return _ADVICE[self]


_ADVICE = {
    Status.FINISHED: "reached the final time",
    Status.STOPPED: "stopped by a terminal event or the stop condition, as requested",
    Status.STEP_SIZE_UNDERFLOW: "the step size fell below rounding level: the field is singular or not "
                                "smooth enough there — check the state and parameters at the failure "
                                "time, or loosen rtol",
    Status.MAX_STEPS: "the step budget ran out: raise max_steps, shorten the time span or loosen rtol",
    Status.MAX_EVENTS: "the event budget ran out: raise max_events or shorten the time span",
    Status.NON_FINITE: "the state or field became NaN/inf: check the parameters (a stiffness, mass or "
                       "law parameter of the wrong sign) and the initial state",
    Status.ZENO: "events accumulate (Zeno): see the diagnosis; give the mode an on_zeno handler "
                 "(e.g. a sticking mode) or stop the run at the accumulation point",
    Status.EVENT_RATE: "the event rate exceeded its cap: raise max_event_rate if the chattering is real",
    Status.WALL_TIME: "the wall-clock budget ran out: raise it or shorten the time span",
    Status.FAILED: "the integrator failed: see the message",
}

#: the status strings used by the engines → Status
_FROM_TEXT = {
    "t_end": Status.FINISHED, "finished": Status.FINISHED, "stop": Status.STOPPED,
    "terminal event": Status.STOPPED, "zeno": Status.ZENO, "event-rate": Status.EVENT_RATE,
    "max_events": Status.MAX_EVENTS, "max_steps": Status.MAX_STEPS,
    "maximum number of steps": Status.MAX_STEPS, "step-size-underflow": Status.STEP_SIZE_UNDERFLOW,
    "step size too small": Status.STEP_SIZE_UNDERFLOW, "non-finite state": Status.NON_FINITE,
}


def status_from_text(text: str) -> Status:
    """The :class:`Status` of an engine's status string (``FAILED`` if unknown)."""
    return _FROM_TEXT.get(text, Status.FAILED)


@dataclass(frozen=True)
class Simulation:
    """A simulated trajectory with its events and how the run ended.

    Attributes
    ----------
    model : str
        Which model was simulated.
    t : ndarray, shape (m,)
        Recorded times (increasing; repeated at a reset).
    y : ndarray, shape (n, m)
        Recorded states.
    events : EventLog
        The events in time order.
    status : Status
        How the run ended.
    message : str
        A readable account of the end (the status's advice, with details).
    t_final : float
    y_final : ndarray
        Where the run ended.
    nsteps, nfev : int
        Accepted steps and field evaluations.
    f : ndarray or None, shape (n, m)
        The field at the recorded points, when known (enables cubic interpolation).
    state_names : tuple of str
        Names of the state components.
    regimes : tuple of (float, float, str)
        The run's regimes in time order, ``(t0, t1, name)`` with names such as ``"stick"``,
        ``"slip"``, ``"flight"``, ``"contact"`` (empty when the model has none).
    law : str
        The friction law's name (``""`` where the run does not say).
    units : mapping of str to str
        The unit of each series by state name, and of ``"t"`` (used by :meth:`plot` and
        :meth:`to_csv` when none are given).
    parameters : mapping
        Every parameter value the run used (the defaults completed), by name.
    notes : tuple of str
        What a reader of the run should know (the start, a default chosen, the output times).
    plot_hints : mapping
        How :meth:`plot` draws the run where not told: ``title``, ``phase`` (the phase portrait's
        components), ``section_phase``, ``section_label`` and ``period`` (a stroboscopic section).
    """

    model: str
    t: np.ndarray = field(repr=False)
    y: np.ndarray = field(repr=False)
    events: EventLog = field(repr=False)
    status: Status
    message: str
    t_final: float
    y_final: np.ndarray = field(repr=False)
    nsteps: int = 0
    nfev: int = 0
    f: np.ndarray | None = field(default=None, repr=False)
    state_names: tuple[str, ...] = ()
    regimes: tuple[tuple[float, float, str], ...] = field(default=(), repr=False)
    law: str = ""
    units: Mapping[str, str] = field(default_factory=dict, repr=False)
    parameters: Mapping[str, Any] = field(default_factory=dict, repr=False)
    notes: tuple[str, ...] = field(default=(), repr=False)
    plot_hints: Mapping[str, Any] = field(default_factory=dict, repr=False)

    @property
    def success(self) -> bool:
        """Whether the run reached its end time (or a requested stop)."""
        return self.status.success

    def at(self, times) -> np.ndarray:
        """The state at ``times`` (scalar → (n,), array → (n, k)) from the recorded series:
        cubic Hermite on each recorded interval when the field is recorded, else linear.
        Times outside [t[0], t[-1]] raise ValueError.

        Parameters
        ----------
        times : float or array_like
            Times inside the recorded interval.

        Returns
        -------
        numpy.ndarray
            Shape (n,) for a scalar time, (n, k) for k times.
        """
        if len(self.t) < 2:
            raise ValueError("the run recorded fewer than two points: nothing to interpolate")
        if np.ndim(times) == 0:
            return self._at_one(float(times))
        ts = np.atleast_1d(np.asarray(times, float))
        if ts.min() < self.t[0] or ts.max() > self.t[-1]:
            raise ValueError(f"times outside the recorded span [{self.t[0]:.6g}, {self.t[-1]:.6g}]")
        i = np.clip(np.searchsorted(self.t, ts, side="right") - 1, 0, len(self.t) - 2)
        t0, t1 = self.t[i], self.t[i + 1]
        h = t1 - t0
        s = np.where(h > 0, (ts - t0) / np.where(h > 0, h, 1.0), 1.0)
        return self._between(i, s, h)

    def _at_one(self, time: float) -> np.ndarray:
        """:meth:`at` for one time, in scalar arithmetic: the right-hand side of an integration
        along the run (the monodromy of :mod:`landau.analyses.shooting`) asks for one time per
        call, where the array path cost 46 µs a call, most of it the set-up of arrays of one
        element (the same interpolant, :meth:`_between`, the same rounding)."""
        t = self.t
        if not t[0] <= time <= t[-1]:
            raise ValueError(f"times outside the recorded span [{t[0]:.6g}, {t[-1]:.6g}]")
        i = min(max(int(np.searchsorted(t, time, side="right")) - 1, 0), len(t) - 2)
        t0 = float(t[i])
        h = float(t[i + 1]) - t0
        s = (time - t0) / h if h > 0 else 1.0
        return self._between(i, s, h)

    def _between(self, i, s, h) -> np.ndarray:
        """The interpolant on the recorded intervals ``i`` (an index or an array of them) at the
        fractions ``s`` of their lengths ``h``: cubic Hermite where the field is recorded, else
        linear (scalars or arrays alike, the same operations)."""
        y0, y1 = self.y[:, i], self.y[:, i + 1]
        if self.f is None:
            return y0 + s * (y1 - y0)
        h00 = (1 + 2 * s) * (1 - s) ** 2
        h10 = s * (1 - s) ** 2
        h01 = s * s * (3 - 2 * s)
        h11 = s * s * (s - 1)
        return h00 * y0 + h10 * h * self.f[:, i] + h01 * y1 + h11 * h * self.f[:, i + 1]

    def on_times(self, times, note: str = "") -> "Simulation":
        """The run with its series at ``times`` (inside the recorded span) by :meth:`at`, the
        events, regimes, final state and counters unchanged; ``note`` is added to the notes.

        Parameters
        ----------
        times : array_like
            Increasing times inside [t[0], t[-1]].
        note : str, optional
            How the values were obtained (appended to :attr:`notes`).

        Returns
        -------
        Simulation

        Raises
        ------
        ValueError
            Times not increasing, or outside the recorded span.
        """
        from dataclasses import replace

        ts = np.asarray(times, float).reshape(-1)
        if len(ts) and not (np.all(np.isfinite(ts)) and np.all(np.diff(ts) > 0)):
            raise ValueError("the output times must be finite and increasing")
        y = self.at(ts).reshape(self.y.shape[0], -1) if len(ts) else self.y[:, :0]
        return replace(self, t=ts, y=y, f=None, notes=tuple(self.notes) + ((note,) if note else ()))

    def after(self, t_from: float) -> "Simulation":
        """The run without its transient: the recorded points, events and regimes at t ≥ ``t_from``
        (the final state and the counters unchanged).

        Parameters
        ----------
        t_from : float
            First time kept.

        Returns
        -------
        Simulation

        Raises
        ------
        ValueError
            ``t_from`` is not finite or leaves no recorded point.
        """
        from dataclasses import replace

        t_from = float(t_from)
        if not np.isfinite(t_from):
            raise ValueError(f"the time to discard before must be finite, got {t_from!r}")
        keep = self.t >= t_from
        if not keep.any():
            last = f"{self.t[-1]:.6g}" if len(self.t) else "nothing"
            raise ValueError(f"discarding t < {t_from:g} leaves no recorded point (the record ends at {last})")
        log = EventLog()
        for e in self.events:
            if e.t >= t_from:
                log.append(e)
        regimes = tuple((max(a, t_from), b, nm) for a, b, nm in self.regimes if b > t_from)
        return replace(self, t=self.t[keep], y=self.y[:, keep], events=log,
                       f=None if self.f is None else self.f[:, keep], regimes=regimes)

    # --- output ---------------------------------------------------------------------
    def _names(self) -> tuple[str, ...]:
        m = self.y.shape[0] if self.y.ndim == 2 else len(self.y_final)
        names = tuple(self.state_names[:m])
        return names + tuple(f"y{i}" for i in range(len(names), m))

    def section_points(self, period: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Points of a Poincaré section: ``(t, y)`` with ``y`` of shape (n, k).

        The logged section events (``kind == "section"``) when there are any and ``period``
        is None; otherwise the stroboscopic samples t₀ + i·``period`` of the recorded series.
        Raises ValueError when neither is available.

        Parameters
        ----------
        period : float, optional
            Sampling period of a stroboscopic section (e.g. the forcing period).

        Returns
        -------
        t : numpy.ndarray, shape (k,)
        y : numpy.ndarray, shape (n, k)
        """
        if period is None:
            ev = [e for e in self.events if e.kind == "section"]
            if not ev:
                raise ValueError("the run logged no section events: give period= for a stroboscopic section")
            return np.array([e.t for e in ev]), np.column_stack([np.asarray(e.y, float) for e in ev])
        if not (np.isfinite(period) and period > 0):
            raise ValueError(f"period must be > 0, got {period!r}")
        ts = self.t[0] + period * np.arange(int(np.floor((self.t[-1] - self.t[0]) / period)) + 1)
        return ts, self.at(ts).reshape(self.y.shape[0], -1)

    def plot(self, kind: str = "overview", *, phase: tuple[int, int] | None = None, period: float | None = None,
             units=None, fig=None, discard: float = 0.0, log=None, section_label: str | None = None,
             title: str | None = None):
        """Draw the run with matplotlib (:func:`landau.verify.hybrid.plotting.plot_simulation`): the
        figure ``landau simulate --out run.png`` writes.  What is not given comes from the run
        (:attr:`units`, :attr:`plot_hints`); it never calls ``pyplot.show``.

        Parameters
        ----------
        kind : {"overview", "poincare"}
            ``"overview"``: the time series of every state (regimes shaded, a logarithmic axis
            for a positive quantity spanning decades) and a phase portrait coloured by regime;
            ``"poincare"``: the Poincaré section (see :meth:`section_points`).
        phase : (int, int), optional
            The two state components of the phase plane (default the run's ``phase`` hint, or
            ``section_phase`` for a section, else the first two).
        period : float, optional
            Strobe period for ``"poincare"`` (default the run's ``period`` hint, else the logged
            section events).
        units : mapping, optional
            State name (and ``"t"``) → unit for the axis labels (default :attr:`units`).
        fig : matplotlib Figure, optional
            Draw into this figure instead of a new one.
        discard : float, optional
            Leave out the transient t < ``discard``.
        log : sequence of str, optional
            States on a logarithmic axis (default: chosen from the data).
        section_label : str, optional
            What the section events are, for the Poincaré plot's legend.
        title : str, optional
            The figure's title (default the run's ``title`` hint: the model, law and key parameters).

        Returns
        -------
        matplotlib.figure.Figure
            A new figure (shown once in a notebook, by the toolkit's plotting convention) or ``fig``.
        """
        from landau.verify.hybrid.plotting import plot_simulation

        hints = self.plot_hints
        if phase is None:
            phase = tuple(hints.get("section_phase" if kind == "poincare" else "phase", None)
                          or hints.get("phase", (0, 1)))
        if period is None and kind == "poincare":
            period = hints.get("period")
        return plot_simulation(self, kind, phase=phase, period=period,
                               units=self.units if units is None else units, fig=fig, discard=discard, log=log,
                               section_label=section_label or hints.get("section_label"),
                               title=title or hints.get("title"))

    def to_csv(self, path, units=None):
        """Write the time series as CSV (header ``t [s], name [unit], ...``), atomically.

        Parameters
        ----------
        path : str or os.PathLike
            The file to write.
        units : mapping of str to str, optional
            Units by state name (and ``"t"``, default s) for the header (default :attr:`units`).

        Returns
        -------
        pathlib.Path
            The file written.
        """
        from landau.support.io import atomic_write_text

        units = dict(self.units if units is None else units)
        names = self._names()
        tu = units.get("t", "s")
        head = [f"t [{tu}]" if tu else "t"] + [f"{nm} [{units[nm]}]" if units.get(nm) else nm for nm in names]
        rows = np.column_stack([self.t, self.y.T])
        lines = [",".join(head)] + [",".join(repr(float(v)) for v in r) for r in rows]
        return atomic_write_text(path, "\n".join(lines) + "\n")

    def to_npz(self, path):
        """Write ``t``, ``y``, ``state_names``, event times/guards and the status as ``.npz``, atomically.

        Parameters
        ----------
        path : str or os.PathLike
            The file to write.

        Returns
        -------
        pathlib.Path
            The file written.
        """
        from landau.support.io import atomic_write

        arrays = dict(t=self.t, y=self.y, state_names=np.array(self._names()), model=np.array(self.model),
                      status=np.array(self.status.value), t_final=np.array(self.t_final),
                      y_final=np.asarray(self.y_final, float),
                      event_t=np.array([e.t for e in self.events], float),
                      event_guard=np.array([e.guard for e in self.events], str))
        return atomic_write(path, lambda fh: np.savez(fh, **arrays), mode="wb")

    def _repr_html_(self) -> str:
        from html import escape

        names = self._names()
        span = f"[{self.t[0]:.6g}, {self.t[-1]:.6g}]" if len(self.t) else f"up to {self.t_final:.6g}"
        final = ", ".join(f"{nm} = {float(v):.6g}" for nm, v in zip(names, np.ravel(self.y_final), strict=True))
        rows = [("model", self.model), ("status", f"{self.status.value}: {self.message}"), ("t span", span),
                ("points", str(len(self.t))), ("events", str(len(self.events))), ("final state", final)]
        body = "".join(f"<tr><th style='text-align:left'>{escape(k)}</th><td style='text-align:left'>"
                       f"{escape(v)}</td></tr>" for k, v in rows)
        return f"<table><caption>Simulation</caption>{body}</table>"

    def __repr__(self) -> str:
        return (f"Simulation({self.model}, {self.status.value}, t_final={self.t_final:.6g}, "
                f"{len(self.t)} points, {len(self.events)} events, {self.nsteps} steps, {self.nfev} fev)")
