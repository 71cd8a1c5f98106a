"""One result type for every simulation: a dense time series, the events and a status.

Every model's run converts to a :class:`Simulation` (``.simulation()`` on the hybrid
engine's :class:`~landau.verify.hybrid.HybridSolution`, the spring–block's and the forced
oscillator's compiled runs):

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

    @property
    def success(self) -> bool:
        return self.status.success

    def at(self, times) -> np.ndarray:
        """The state at ``times`` (scalar → (n,), array → (n, k)) from the recorded series:
        cubic Hermite on each recorded interval when the field is recorded, else linear.
        Times outside [t[0], t[-1]] raise ValueError."""
        ts = np.atleast_1d(np.asarray(times, float))
        if len(self.t) < 2:
            raise ValueError("the run recorded fewer than two points: nothing to interpolate")
        if ts.min() < self.t[0] or ts.max() > self.t[-1]:
            raise ValueError(f"times outside the recorded span [{self.t[0]:.6g}, {self.t[-1]:.6g}]")
        i = np.clip(np.searchsorted(self.t, ts, side="right") - 1, 0, len(self.t) - 2)
        t0, t1 = self.t[i], self.t[i + 1]
        h = t1 - t0
        s = np.where(h > 0, (ts - t0) / np.where(h > 0, h, 1.0), 1.0)
        y0, y1 = self.y[:, i], self.y[:, i + 1]
        if self.f is None:
            out = y0 + s * (y1 - y0)
        else:
            f0, f1 = self.f[:, i], self.f[:, i + 1]
            h00 = (1 + 2 * s) * (1 - s) ** 2
            h10 = s * (1 - s) ** 2
            h01 = s * s * (3 - 2 * s)
            h11 = s * s * (s - 1)
            out = h00 * y0 + h10 * h * f0 + h01 * y1 + h11 * h * f1
        return out[:, 0] if np.ndim(times) == 0 else out

    def __repr__(self) -> str:
        return (f"Simulation({self.model}, {self.status.value}, t_final={self.t_final:.6g}, "
                f"{len(self.t)} points, {len(self.events)} events, {self.nsteps} steps, {self.nfev} fev)")
