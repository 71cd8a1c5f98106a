"""The laboratory protocols as load-point velocity histories: velocity steps, slide-hold-slide, any history.

A protocol drives the load point at a piecewise-constant velocity V(t) (Dieterich 1979; Ruina
1983; Marone 1998):

* :func:`velocity_step` — V₁ → V₂ at a time (or after a load-point displacement);
* :func:`velocity_steps` — a staircase V₁ → V₂ → … of pieces of equal duration or displacement;
* :func:`slide_hold_slide` — slides at V separated by holds (V = 0) of the given durations;
* :func:`velocity_history` — ``"1um/s@0,10um/s@10"`` (velocity @ start time, with units) or pairs.

Each returns a :class:`Protocol`: the :class:`~landau.verify.springblock.history.LoadHistory`
(SI) and a suggested end time.  Velocities, times and displacements may be numbers or unit
strings (:mod:`landau.lab.units`); a bare number is in the preset's units (µm/s and µm for
:data:`~landau.lab.preset.LAB`, the default here; m/s and m for :data:`~landau.lab.preset.SI`),
a time always in s.  :func:`run_protocol` simulates it
(:func:`~landau.verify.springblock.history.simulate_history`; with the lab preset the quasi-static
spring–slider) and returns a :class:`ProtocolRun`, the series with the flow of the run for the
measurements of :mod:`landau.lab.measure`.

References
----------
Dieterich, J. H. (1979), J. Geophys. Res. 84, 2161–2168.
Ruina, A. (1983), J. Geophys. Res. 88, 10359–10370.
Marone, C. (1998), Annu. Rev. Earth Planet. Sci. 26, 643–696.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from landau.errors import InputError
from landau.lab.preset import LAB, Preset
from landau.lab.units import parse_value, split_value
from landau.verify.hybrid.result import Simulation
from landau.verify.springblock.history import LoadHistory
from landau.verify.springblock.history_flow import HistoryFlow


@dataclass(frozen=True)
class Protocol:
    """A load-point velocity history (SI) and the end time of its run [s]."""

    history: LoadHistory
    t_end: float

    def __post_init__(self):
        if not (np.isfinite(self.t_end) and self.t_end > self.history.times[-1]):
            raise InputError(f"a protocol's end time must be after its last piece's start "
                             f"t = {self.history.times[-1]:g} s, got {self.t_end!r}")

    def pieces(self) -> list[tuple[float, float, float]]:
        """(V, start, end) of every piece [m/s, s, s]."""
        T = [*self.history.times, self.t_end]
        return [(V, a, b) for V, a, b in zip(self.history.velocities, T[:-1], T[1:], strict=True)]


def split_value_ok(text: str) -> bool:
    """Whether ``text`` reads as a number with an optional unit text (the unit not yet checked)."""
    try:
        split_value(text, "")
    except InputError:
        return False
    return True


def _time(x, what: str) -> float:
    t, _ = parse_value(x, "time", what, "s")
    return t


def _velocity(x, what: str, preset: Preset, allow_zero: bool = False) -> float:
    v = preset.velocity_value(x, what)
    if not (v > 0 or (allow_zero and v == 0)):
        raise InputError(f"{what}: a load-point velocity must be {'>= 0 (0: a hold)' if allow_zero else '> 0'}, "
                         f"got {x!r}")
    return v


def _duration(V: float, every, displacement, preset: Preset, what: str) -> float:
    """A piece's duration [s]: ``every`` (a time) or ``displacement`` (a load-point travel, at V)."""
    if (every is None) == (displacement is None):
        raise InputError(f"{what}: give the duration of a piece (a time) or its load-point displacement, one of them")
    d = _time(every, f"{what} duration") if every is not None else \
        preset.length_value(displacement, f"{what} displacement") / V
    if not d > 0:
        raise InputError(f"{what}: a piece must last > 0, got {every if every is not None else displacement!r}")
    return d


def velocity_step(V1, V2, *, at=None, displacement=None, after=None, preset: Preset = LAB) -> Protocol:
    """A velocity step V₁ → V₂: at time ``at`` [s] (or after the load-point ``displacement`` at V₁),
    the run ending as long after the step (or ``after``, a time, later)."""
    v1, v2 = _velocity(V1, "V1", preset), _velocity(V2, "V2", preset)
    t_step = _duration(v1, at, displacement, preset, "velocity step")
    rest = _time(after, "after") if after is not None else t_step
    if not rest > 0:
        raise InputError(f"after: the run must go on past the step, got {after!r}")
    return Protocol(LoadHistory((v1, v2), (0.0, t_step)), t_step + rest)


def velocity_steps(velocities: Sequence, *, every=None, displacement=None, preset: Preset = LAB) -> Protocol:
    """A staircase of velocities, each piece lasting ``every`` [s] or a load-point ``displacement``."""
    vs = [_velocity(v, f"velocity {i}", preset) for i, v in enumerate(velocities)]
    if len(vs) < 2:
        raise InputError(f"velocity steps need at least two velocities, got {list(velocities)!r}")
    times = [0.0]
    for V in vs:
        times.append(times[-1] + _duration(V, every, displacement, preset, "velocity steps"))
    return Protocol(LoadHistory(tuple(vs), tuple(times[:-1])), times[-1])


def slide_hold_slide(V, holds: Sequence, *, slide=None, displacement=None, V_reload=None,
                     preset: Preset = LAB) -> Protocol:
    """Slides at V (each ``slide`` [s] or a load-point ``displacement`` long) separated by holds of the
    durations ``holds`` [s]; reloading at ``V_reload`` (default V).  The run starts with a slide and
    ends with one after the last hold."""
    v = _velocity(V, "V", preset)
    vr = _velocity(V_reload, "V_reload", preset) if V_reload is not None else v
    hs = [_time(h, f"hold {i}") for i, h in enumerate(holds)]
    if not hs or any(not h > 0 for h in hs):
        raise InputError(f"slide-hold-slide: give one or more hold times > 0, got {list(holds)!r}")
    first = _duration(v, slide, displacement, preset, "slide-hold-slide")
    again = _duration(vr, slide, displacement, preset, "slide-hold-slide")
    vel, times, t = [v], [0.0], first
    for h in hs:
        vel += [0.0, vr]
        times += [t, t + h]
        t += h + again
    return Protocol(LoadHistory(tuple(vel), tuple(times)), t)


def velocity_history(spec: str | Sequence[tuple], t_end=None, *, preset: Preset = LAB) -> Protocol:
    """Any piecewise-constant history: ``"1um/s@0,10um/s@10"`` (velocity @ start time) or pairs (V, t),
    the run ending at ``t_end`` (default: the last piece as long as the longest earlier one)."""
    if isinstance(spec, str):
        if not spec.strip():
            raise InputError("--V-history: give 'V0@t0,V1@t1,...' (velocity @ start time, e.g. '1um/s@0,10um/s@10')")
        items = []
        for item in spec.split(","):
            parts = item.split("@")
            if len(parts) != 2:
                raise InputError(f"--V-history: {item.strip()!r} is not 'V@t' (velocity @ start time, e.g. '1um/s@0')")
            items.append((parts[0].strip(), parts[1].strip()))
    else:
        try:
            items = [(V, t) for V, t in spec]
        except (TypeError, ValueError):
            raise InputError(f"--V-history: give pairs (V_i, t_i) or the text 'V0@t0,V1@t1', got {spec!r}") from None
    for V, t in items:
        for x in (V, t):
            if isinstance(x, str) and split_value_ok(x) is False:
                raise InputError(f"--V-history: {V}@{t!s}: velocity and time must be numbers, with optional "
                                 "units (e.g. '1um/s@10s')")
    vel = tuple(_velocity(V, "--V-history", preset, allow_zero=True) for V, _ in items)
    times = tuple(_time(t, "--V-history (time)") for _, t in items)
    h = LoadHistory(vel, times)
    if t_end is None:
        from landau.verify.springblock.history import default_end

        end = default_end(h, {})
    else:
        end = _time(t_end, "t_end")
    return Protocol(h, end)


@dataclass(frozen=True)
class ProtocolRun:
    """A protocol's run: the series (SI, :class:`~landau.verify.hybrid.result.Simulation` with the
    columns V, v, mu, the states, x_lp, slip) and the flow of its field for dense measurements."""

    protocol: Protocol
    sim: Simulation
    flow: HistoryFlow

    def column(self, name: str) -> np.ndarray:
        """The series of a column (SI)."""
        try:
            return self.sim.y[list(self.sim.state_names).index(name)]
        except ValueError:
            raise InputError(f"no column {name!r} (columns: {', '.join(self.sim.state_names)})") from None


def run_protocol(protocol: Protocol, law, k, params: Mapping[str, float] | None = None, *,
                 preset: Preset = LAB, rtol: float = 1e-9) -> ProtocolRun:
    """Simulate ``protocol`` with the friction ``law`` (a FrictionLaw or a built-in law's name) at the
    spring stiffness ``k`` (a number in the preset's stiffness unit, or a unit string: ``"1e-3/um"``),
    the law's parameters ``params`` (SI) over the preset's block (lab: M = 0, η = 0, σ = 1)."""
    from landau.laws import get_law
    from landau.verify.springblock.history import simulate_history
    from landau.verify.springblock.history_flow import history_flow

    law = get_law(law) if isinstance(law, str) else law
    p = {**preset.block, **(params or {})}
    sigma = p.get("sigma")
    if sigma is None:
        from landau.systems.system import SpringBlock

        sigma = SpringBlock.for_params(law, p).resolve(p)["sigma"]
    kk = preset.stiffness_value(k, float(sigma), "k")
    if not (0 < rtol < 1):
        raise InputError(f"rtol must be in (0, 1), got {rtol!r}")
    flow = history_flow(law, protocol.history, kk, p, rtol)
    sim = simulate_history(law, protocol.history, kk, p, protocol.t_end, rtol=rtol)
    return ProtocolRun(protocol, sim, flow)


__all__ = ["Protocol", "ProtocolRun", "run_protocol", "slide_hold_slide", "velocity_history", "velocity_step",
           "velocity_steps"]
