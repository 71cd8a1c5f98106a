"""Detection of event accumulation (Zeno behaviour, chattering) and event-rate caps.

A bouncing contact produces impacts whose spacing shrinks geometrically; an exact
simulation would never pass the accumulation time.  The monitor watches the spacing of
consecutive switching events and declares accumulation when the latest spacing falls
below ``min_interval`` *and* the last ``history - 1`` spacings all shrink (so one short
phase near a grazing, a legitimate event pair, is not mistaken for accumulation).  The accumulation
point is then extrapolated with the geometric series of the last spacings:
t_inf = t_n + dt_n q / (1 - q), q = dt_n / dt_{n-1}.  Independently, more than
``max_rate`` events per unit time (over the last ``rate_window``) stops the run: that
catches a hang that is not geometric.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class ZenoDiagnosis:
    """Why the run stopped (or changed regime) because events accumulated."""

    kind: str                 # "zeno" (geometric accumulation) or "event-rate"
    t_detect: float           # time of the last event seen
    t_accumulation: float     # extrapolated accumulation point (nan for "event-rate")
    ratio: float              # last spacing ratio dt_n / dt_{n-1}
    n_events: int             # events in the accumulating sequence / window
    last_interval: float

    def __repr__(self) -> str:
        return (f"ZenoDiagnosis({self.kind}: accumulation at t={self.t_accumulation:.12g}, "
                f"ratio={self.ratio:.6g}, {self.n_events} events, last dt={self.last_interval:.3g})")


class ZenoMonitor:
    """Feeds on switching-event times; returns a diagnosis when accumulation is seen."""

    def __init__(self, min_interval: float = 1e-6, max_rate: float = 1e6, rate_window: float = 1e-3,
                 history: int = 6, relative: bool = True) -> None:
        self.min_interval = min_interval
        self.relative = relative  # False: min_interval is an absolute time (the impact papers' rule)
        self.max_rate = max_rate
        self.rate_window = rate_window
        self._history = max(history, 3)
        self.times: deque[float] = deque(maxlen=self._history)
        self.window: deque[float] = deque()

    def reset(self) -> None:
        self.times.clear()
        self.window.clear()

    def push(self, t: float) -> ZenoDiagnosis | None:
        self.times.append(t)
        self.window.append(t)
        while self.window and self.window[0] < t - self.rate_window:
            self.window.popleft()
        ts = np.asarray(self.times)
        if len(ts) >= self._history:  # a run of shrinking spacings, not one short phase
            dt = np.diff(ts)
            last = dt[-1]
            scale = max(1.0, abs(t)) if self.relative else 1.0
            if last < self.min_interval * scale and dt[-2] > 0:
                q = last / dt[-2]
                shrinking = np.all(np.diff(dt) <= 0)
                if 0 < q < 1 and shrinking:
                    t_inf = t + last * q / (1 - q)
                    return ZenoDiagnosis("zeno", t, t_inf, q, len(ts), last)
                if last == 0 and dt[-2] == 0:
                    return ZenoDiagnosis("zeno", t, t, 0.0, len(ts), 0.0)
        if len(self.window) > self.max_rate * self.rate_window:
            dt = np.diff(np.asarray(self.window))
            return ZenoDiagnosis("event-rate", t, float("nan"), float("nan"), len(self.window),
                                 float(dt[-1]) if len(dt) else float("nan"))
        return None
