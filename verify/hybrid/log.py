"""The event log: every switch, section crossing and Zeno diagnosis, in time order."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Iterable, Iterator, Sequence

import numpy as np


@dataclass(frozen=True)
class Event:
    """One logged event.

    ``kind`` is ``"switch"`` (mode change / reset), ``"section"`` (a section crossing,
    no switch), ``"zero-length"`` (a switch fired at the very start of a phase: the
    previous transition landed where this mode's guard was already violated) or
    ``"zeno"`` (accumulation of events handled by the mode's ``on_zeno``).
    ``y`` is the state at the root, on the new side of the guard; ``y_after`` the state
    after the transition (equal to ``y`` for sections).
    """

    t: float
    y: np.ndarray
    guard: str
    from_mode: str
    to_mode: str
    kind: str = "switch"
    y_after: np.ndarray | None = None
    note: str = ""

    def __repr__(self) -> str:
        ys = np.array2string(np.asarray(self.y), precision=6, separator=", ")
        note = f", {self.note}" if self.note else ""
        return (f"Event(t={self.t:.12g}, {self.kind} {self.guard!r}: "
                f"{self.from_mode} -> {self.to_mode}, y={ys}{note})")


class EventLog(Sequence[Event]):
    """An append-only, time-ordered list of :class:`Event` with small query helpers."""

    def __init__(self) -> None:
        self._events: list[Event] = []

    def _list(self) -> list[Event]:
        """The events (a subclass may fill the list on first use)."""
        return self._events

    def append(self, ev: Event) -> None:
        self._list().append(ev)

    def __getitem__(self, i):
        return self._list()[i]

    def __len__(self) -> int:
        return len(self._list())

    def __iter__(self) -> Iterator[Event]:
        return iter(self._list())

    def filter(self, guard: str | None = None, kind: str | None = None,
               from_mode: str | None = None, to_mode: str | None = None) -> list[Event]:
        return [e for e in self._list()
                if (guard is None or e.guard == guard) and (kind is None or e.kind == kind)
                and (from_mode is None or e.from_mode == from_mode)
                and (to_mode is None or e.to_mode == to_mode)]

    def times(self, **kw) -> np.ndarray:
        return np.array([e.t for e in (self.filter(**kw) if kw else self._list())])

    def __repr__(self) -> str:
        head = "\n  ".join(repr(e) for e in self._list()[:8])
        more = f"\n  ... ({len(self) - 8} more)" if len(self) > 8 else ""
        return f"EventLog({len(self)} events\n  {head}{more})"


class LazyEventLog(EventLog):
    """An :class:`EventLog` whose events are made on first use by ``make()`` (from a compiled run's
    arrays, say): a run whose events nobody reads pays no Python work per event (a sweep runs a
    simulator thousands of times and reads the arrays only).

    Parameters
    ----------
    make : callable
        No arguments; returns the events in time order.  Called at most once, then dropped.
    """

    def __init__(self, make: Callable[[], Iterable[Event]]) -> None:
        super().__init__()
        self._make: Callable[[], Iterable[Event]] | None = make

    def _list(self) -> list[Event]:
        if self._make is not None:
            make, self._make = self._make, None
            self._events.extend(make())
        return self._events
