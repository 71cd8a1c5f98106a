"""The recorded trajectory of a hybrid run (:func:`landau.verify.hybrid.simulate.simulate`): its
segments, one per phase, and the bound on the samples kept.

A run records the step ends and the guard samples of every step (``EngineOptions(record=True)``)
into the current phase's lists ``seg_t``, ``seg_y``; a phase's end closes them into a
:class:`Segment`.  Past ``EngineOptions.max_samples`` the record is thinned (:class:`Recorder`):
every other sample dropped, each segment's ends kept, and from then on only every 2ᵏ-th step end
recorded, so a long run keeps at most ~``max_samples`` points spread over the whole run.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Segment:
    """A sampled piece of trajectory inside one mode (step points + guard samples)."""

    mode: str
    t: np.ndarray
    y: np.ndarray  # shape (n, m)

    def __repr__(self) -> str:
        return f"Segment({self.mode!r}, t=[{self.t[0]:.6g}, {self.t[-1]:.6g}], {len(self.t)} points)"


class Recorder:
    """Recorded samples within ``cap`` (``max_samples`` of
    :class:`~landau.verify.hybrid.simulate.EngineOptions`): a stride over the steps (1: every
    sample of every step; 2ᵏ: the end of every 2ᵏ-th step only) and the thinning of what is kept
    when the count passes ``cap``."""

    __slots__ = ("cap", "stride", "count", "k")

    def __init__(self, cap: int):
        self.cap, self.stride, self.count, self.k = max(int(cap), 16), 1, 0, 0

    def push(self, seg_t, seg_y, ts, Y) -> None:
        if self.stride > 1:
            self.k += 1
            if self.k % self.stride:
                return
            ts, Y = ts[-1:], Y[:, -1:]
        seg_t.append(ts)
        seg_y.append(Y)
        self.count += len(ts)

    def bound(self, segs, seg_t, seg_y) -> None:
        if self.count <= self.cap:
            return
        for i, s in enumerate(segs):
            keep = _thin(len(s.t))
            segs[i] = Segment(s.mode, s.t[keep], s.y[:, keep])
        t, y = np.concatenate(seg_t), np.concatenate(seg_y, axis=1)
        keep = _thin(len(t))
        seg_t[:], seg_y[:] = [t[keep]], [y[:, keep]]
        self.count = sum(len(s.t) for s in segs) + len(seg_t[0])
        if self.count > self.cap and len(segs) > 1:
            # many short phases (each keeps its two ends): drop every other earlier phase
            segs[:] = segs[-2::-2][::-1] + segs[-1:]
            self.count = sum(len(s.t) for s in segs) + len(seg_t[0])
        self.stride *= 2


def _thin(n: int) -> np.ndarray:
    """Every other index of range(n), the last one included."""
    idx = np.arange(0, n, 2)
    return idx if n == 0 or idx[-1] == n - 1 else np.append(idx, n - 1)


def close_segment(segs, options, mname, seg_t, seg_y, ts, Y, th, yh):
    """When recording: close the phase's segment at the root ``(th, yh)`` inside the step with
    samples ``ts``, ``Y`` (the samples before the root kept, the root appended)."""
    if not options.record:
        return
    keep = ts[1:] < th
    seg_t.append(np.concatenate([ts[1:][keep], [th]]))
    seg_y.append(np.column_stack([Y[:, keep], yh]))
    segs.append(Segment(mname, np.concatenate(seg_t), np.concatenate(seg_y, axis=1)))
