"""The inputs every model's run function checks the same way: end time, step budget, initial state
and output times (:func:`landau.simulate`, ``landau simulate``).

A model's run function (``simulate(setup, *, t_end, y0, history, t_eval, max_steps, sections)``,
declared as :attr:`landau.models.Model.simulate`) takes plain values; the words of its errors name
the argument (``y0 ...``, ``t_end ...``), which the command line shows with its flag.
"""

from __future__ import annotations

import math
from typing import Callable, Sequence

import numpy as np

from landau.errors import InputError


def positive(value, what: str) -> float:
    """``value`` as a finite number > 0, else an InputError naming ``what`` (a flag or a parameter)."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what}: {value!r} is not a number") from None
    if not (math.isfinite(x) and x > 0):
        raise InputError(f"{what} must be a finite number > 0, got {value!r}")
    return x


def end_time(t_end, default: float) -> float:
    """``t_end`` (None: ``default``) as a finite number > 0."""
    if t_end is None:
        return float(default)
    try:
        x = float(t_end)
    except (TypeError, ValueError):
        raise InputError(f"t_end must be a number, got {t_end!r}") from None
    if not (math.isfinite(x) and x > 0):
        raise InputError(f"t_end must be a finite number > 0, got {t_end!r}")
    return x


def step_budget(max_steps, default: int) -> int:
    """``max_steps`` (None: ``default``) as a whole number >= 1."""
    if max_steps is None:
        return int(default)
    try:
        n = float(max_steps)
    except (TypeError, ValueError):
        n = float("nan")
    if not (math.isfinite(n) and n >= 1 and n == int(n)):
        raise InputError(f"max_steps must be a whole number >= 1, got {max_steps!r}")
    return int(n)


def initial_state(y0, names: Sequence[str]) -> np.ndarray:
    """``y0`` (a sequence, or the command line's ``"a,b,..."``) as one finite number per state of ``names``."""
    try:
        vals = np.array([float(x) for x in (str(y0).split(",") if isinstance(y0, str) else np.ravel(y0))])
    except (TypeError, ValueError):
        raise InputError(f"y0 {y0!r}: give {len(names)} comma-separated numbers ({', '.join(names)})") from None
    if vals.shape != (len(names),) or not np.all(np.isfinite(vals)):
        raise InputError(f"y0 {y0!r}: give {len(names)} finite numbers ({', '.join(names)})")
    return vals


def no_history(history, model: str) -> None:
    """A velocity history given to a model that is not driven by one: InputError."""
    if history is not None:
        raise InputError(f"{model}: a load-point velocity history (history=, --V-history) applies to the "
                         "spring-block only")


def unknown_parameters(params, known: Sequence[str], model: str) -> None:
    """Parameters outside ``known``: InputError naming them and the known ones."""
    unknown = sorted(set(params) - set(known))
    if unknown:
        raise InputError(f"{model}: unknown parameter(s) {', '.join(unknown)} (known: {', '.join(known)})")


def output_times(t_eval, t_end: float) -> np.ndarray | None:
    """The output times: ``t_eval`` as an array, or called with the run's end time when it is a
    callable (a uniform grid made before the end time is known); checked increasing in [0, t_end]."""
    if t_eval is None:
        return None
    ts = np.asarray(t_eval(t_end) if callable(t_eval) else t_eval, float).reshape(-1)
    if not (len(ts) and np.all(np.isfinite(ts)) and np.all(np.diff(ts) > 0)):
        raise InputError("t_eval must hold increasing finite times")
    if ts[0] < 0 or ts[-1] > t_end * (1 + 1e-12):
        raise InputError(f"t_eval must lie in [0, t_end] = [0, {t_end:g}], got [{ts[0]:g}, {ts[-1]:g}]")
    return np.minimum(ts, t_end)


def interpolated(sim, t_eval, t_end: float, how: str):
    """``sim`` with its series at the output times ``t_eval`` (:func:`output_times`), interpolated
    from the recorded run (:meth:`~landau.verify.hybrid.result.Simulation.on_times`: cubic Hermite
    where the field is recorded, else linear); ``how`` says between what (the note).  Times past the
    end of a run that stopped early are left out (said in the note)."""
    ts = output_times(t_eval, t_end)
    if ts is None:
        return sim
    if len(sim.t) < 2:
        raise InputError(f"{sim.model}: the run recorded fewer than two points: no output times to give")
    kept = ts[(ts >= sim.t[0]) & (ts <= sim.t[-1])]
    note = (f"{len(kept)} output times: the series {'cubic Hermite' if sim.f is not None else 'linearly'} "
            f"interpolated between {how}")
    if len(kept) < len(ts):
        note += f" ({len(ts) - len(kept)} times past the record's end t = {sim.t[-1]:.6g} left out)"
    return sim.on_times(kept, note)


#: the type of ``t_eval``: times, or a function of the run's end time giving them
TimeGrid = Callable[[float], np.ndarray]

__all__ = ["TimeGrid", "end_time", "initial_state", "interpolated", "no_history", "output_times", "step_budget",
           "unknown_parameters"]
