"""Analysis tools on top of the engine: Poincaré sections, event maps, one-parameter sweeps.

* :func:`poincare` — states at the crossings of a section guard (a guard without
  transition in the model) after a transient;
* :func:`event_map_orbit` — iterate any scalar event map x_{k+1} = f(x_k);
* :func:`sweep` — evaluate a function along a parameter list, passing each result to the
  next call as warm start (continuation of attractors), collecting failures instead of
  stopping;
* :func:`map_bifurcation_diagram` — attractor points of a one-dimensional map along a
  parameter (transient discarded), warm-started from the previous parameter value.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

import numpy as np

from landau.errors import LandauError
from landau.verify.hybrid.model import HybridModel
from landau.verify.hybrid.simulate import EngineOptions, simulate


@dataclass(frozen=True)
class Section:
    """Crossings of one section: times and states (shape (n, m))."""

    guard: str
    t: np.ndarray
    y: np.ndarray

    def __repr__(self) -> str:
        return f"Section({self.guard!r}, {len(self.t)} crossings)"


def poincare(model: HybridModel, mode: str, y0, t_span, section: str, stepper,
             options: EngineOptions = EngineOptions(record=False), t_transient: float = 0.0) -> Section:
    """Poincaré section: states where the section guard ``section`` fires (after t_transient)."""
    sol = simulate(model, mode, y0, t_span, stepper, options)
    evs = [e for e in sol.events if e.guard == section and e.t >= t_transient]
    if not evs:
        return Section(section, np.empty(0), np.empty((len(np.atleast_1d(y0)), 0)))
    return Section(section, np.array([e.t for e in evs]), np.column_stack([e.y for e in evs]))


def event_map_orbit(fmap: Callable[[float], float], x0: float, n: int) -> np.ndarray:
    """x0, f(x0), ..., fⁿ(x0)."""
    out = [float(x0)]
    for _ in range(n):
        out.append(float(fmap(out[-1])))
    return np.array(out)


@dataclass(frozen=True)
class SweepResult:
    """Parameter values, the outputs (None where the evaluation failed) and failures."""

    params: np.ndarray
    values: list
    failures: dict = field(default_factory=dict)

    def __repr__(self) -> str:
        return f"SweepResult({len(self.params)} points, {len(self.failures)} failures)"


def sweep(fn: Callable[[float, Any], Any], params: Sequence[float], warm: Any = None,
          next_warm: Callable[[Any], Any] = lambda out: out) -> SweepResult:
    """Evaluate ``fn(param, warm)`` along ``params``; ``next_warm(out)`` feeds the next call."""
    vals, fails = [], {}
    for q in params:
        try:
            out = fn(float(q), warm)
            warm = next_warm(out)
        except LandauError as exc:  # a failed point is recorded, the sweep goes on
            out = None
            fails[float(q)] = str(exc)
        vals.append(out)
    return SweepResult(np.asarray(params, float), vals, fails)


def map_bifurcation_diagram(make_map: Callable[[float], Callable[[float], float]], params: Sequence[float],
                            x0: float, n_transient: int = 60, n_keep: int = 32) -> SweepResult:
    """Attractor of a 1-D map along a parameter: for each value iterate ``n_transient``
    times from the previous attractor, then keep ``n_keep`` iterates."""
    def one(q, x):
        orbit = event_map_orbit(make_map(q), x, n_transient + n_keep)
        return orbit[n_transient + 1:]

    return sweep(one, params, x0, next_warm=lambda out: float(out[-1]))
