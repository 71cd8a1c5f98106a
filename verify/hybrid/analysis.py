"""The periodic-orbit toolkit: return maps, shooting with the monodromy, bisection, sweeps.

* :func:`shoot_fixed_point` — Newton's method on a return map P(z) − z = 0 with its Jacobian
  (the monodromy restricted to the section), damped to stay in the section's domain; the
  Floquet multipliers are the eigenvalues of that Jacobian;
* :func:`bisect_change` — locate by bisection where a yes/no property of a run changes
  along a parameter (e.g. decay vs growth to a large cycle);
* :class:`Located` — a located bifurcation or transition of a model (a root of a test function,
  or the final bracket of a bisection), the result type of every model's locators;

* :func:`poincare` — states at the crossings of a section guard (a guard without
  transition in the model) after a transient;
* :func:`event_map_orbit` — iterate any scalar event map x_{k+1} = f(x_k);
* :func:`sweep` — evaluate a function along a parameter list, passing each result to the
  next call as warm start (continuation of attractors), collecting failures instead of
  stopping;
* :class:`SweepResult` — the outputs of a computation along a parameter list in sweep order,
  the result type of every model's sweeps;
* :func:`map_bifurcation_diagram` — attractor points of a one-dimensional map along a
  parameter (transient discarded), warm-started from the previous parameter value.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any, Callable, Sequence

import numpy as np

from landau.errors import LandauError
from landau.verify.hybrid.model import HybridModel
from landau.verify.hybrid.simulate import EngineOptions, simulate


class ShootingError(LandauError):
    """Newton's method on a return map did not converge (or the map failed)."""


@dataclass(frozen=True)
class FixedPoint:
    """A fixed point z* = P(z*) of a return map with its Jacobian DP (monodromy on the section).

    ``extra`` is whatever the return map returned besides (P(z), DP) at the last evaluation
    (e.g. the return time and the run)."""

    z: np.ndarray
    DP: np.ndarray = field(repr=False)
    iterations: int
    residual: float
    extra: tuple = field(default=(), repr=False)

    @property
    def multipliers(self) -> tuple[complex, ...]:
        """Floquet multipliers: the eigenvalues of DP."""
        return tuple(complex(m) for m in np.linalg.eigvals(self.DP))


def shoot_fixed_point(return_map: Callable, z0, *, tol: float = 1e-9, maxiter: int = 30,
                      admissible: Callable[[np.ndarray], bool] | None = None, scale_floor: float = 1e-6,
                      label: str = "") -> FixedPoint:
    """Newton's method on P(z) − z = 0.

    Parameters
    ----------
    return_map : callable
        ``return_map(z) -> (P(z), DP(z), *extra)`` with the exact Jacobian (monodromy).
    z0 : array_like
        Initial guess on the section.
    tol : float
        Convergence when |P(z) − z| / max(|z|, ``scale_floor``) < tol.
    maxiter : int
        Newton iterations.
    admissible : callable, optional
        ``admissible(z)``: a Newton step is halved (up to 20 times) until it lands where this
        holds (e.g. where the section is crossed in the right direction).
    label : str
        Names the problem in error messages.

    Returns
    -------
    FixedPoint
        P(z) at convergence (one more application of the map than the last Newton point).

    Raises
    ------
    ShootingError
        No convergence within ``maxiter`` iterations, or the map raised a LandauError.
    """
    z = np.asarray(z0, dtype=float).copy()
    res = np.inf
    for it in range(1, maxiter + 1):
        try:
            Pz, DP, *extra = return_map(z)
        except ShootingError:
            raise
        except LandauError as exc:
            raise ShootingError(f"shooting{' at ' + label if label else ''}: {exc}") from exc
        r = Pz - z
        res = float(np.linalg.norm(r) / max(np.linalg.norm(z), scale_floor))
        if res < tol:
            return FixedPoint(Pz, DP, it, res, tuple(extra))
        dz = np.linalg.solve(DP - np.eye(len(z)), -r)
        lam = 1.0
        if admissible is not None:
            for _ in range(20):
                if admissible(z + lam * dz):
                    break
                lam *= 0.5
        z = z + lam * dz
    raise ShootingError(f"shooting{' at ' + label if label else ''} did not converge in {maxiter} "
                        f"iterations (relative residual {res:.3g})")


def bisect_change(has_property: Callable[[float], bool], lo: float, hi: float, n: int) -> tuple[float, float]:
    """Bracket where ``has_property`` changes between ``lo`` and ``hi`` by ``n`` bisections.

    ``has_property(lo)`` and ``has_property(hi)`` must differ (checked).  Returns the final
    bracket (a, b), ``has_property(a) == has_property(lo)``, |b − a| = |hi − lo|/2ⁿ.
    """
    p_lo = bool(has_property(lo))
    if bool(has_property(hi)) == p_lo:
        raise LandauError(f"the property does not change between {lo!r} and {hi!r}: nothing to bisect")
    for _ in range(n):
        mid = 0.5 * (lo + hi)
        if bool(has_property(mid)) == p_lo:
            lo = mid
        else:
            hi = mid
    return lo, hi


@dataclass(frozen=True)
class Located:
    """A located bifurcation or transition: the value of one parameter where a test function H
    changes sign, and how it was found.

    Two searches produce it.  A root of a continuous H (Brent's method, e.g. the locators of
    Galvanetto 2004, Sec. 4): ``value`` is the root and ``residual`` = |H(value)|.  Bisection on a
    yes/no property of a run (e.g. the impact count of Skurativskyi et al. 2019, Sec. 4): ``lo`` and
    ``hi`` are the final bracket and ``value`` its midpoint; ``lo`` is the end where the property
    has its value at the search's start, which may be the larger one.

    Attributes
    ----------
    name : str
        What was located (e.g. ``"period-doubling"``, ``"first detachment"``).
    parameter : str
        The parameter's name (e.g. ``"V"``, ``"beta"``, ``"omega"``).
    value : float
        The located parameter value.
    residual : float
        |H(value)|; NaN for a bisection on a yes/no property (no value of H to give).
    evaluations : int
        Evaluations of H (or runs of the model for a property).
    seconds : float
        Wall time of the search; NaN where it was not measured.
    details : dict
        Locator-specific data (the periodic point, its period, the search's initial bracket, ...).
    lo, hi : float
        The final bracket of a bisection; NaN for a root of a continuous H.
    """

    name: str
    parameter: str
    value: float
    residual: float
    evaluations: int
    seconds: float = math.nan
    details: dict = field(default_factory=dict)
    lo: float = math.nan
    hi: float = math.nan

    @property
    def what(self) -> str:
        """Deprecated name of :attr:`name` (the bisection results of the forced oscillator)."""
        warnings.warn("Located.what is deprecated: use Located.name", DeprecationWarning, stacklevel=2)
        return self.name

    def __repr__(self) -> str:
        where = (f"{self.parameter} ∈ [{self.lo:.6f}, {self.hi:.6f}]" if not math.isnan(self.lo)
                 else f"{self.parameter} = {self.value:.12g}")
        res = "" if math.isnan(self.residual) else f", |H| = {self.residual:.2g}"
        sec = "" if math.isnan(self.seconds) else f", {self.seconds:.2f} s"
        return f"Located({self.name}: {where}{res}, {self.evaluations} evaluations{sec})"


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
    """The outputs of one computation along a parameter list, in sweep order (a continuation: each
    point warm-started from the one before).

    Attributes
    ----------
    params : numpy.ndarray
        The parameter values in sweep order.
    values : sequence
        The output at each of them (None where the evaluation failed), e.g. the attractor points of a
        map (:func:`map_bifurcation_diagram`) or the forced oscillator's attractors at each ω.
    failures : dict
        Parameter value → message, for the points that failed.
    direction : str or None
        ``"up"`` or ``"down"`` for a continuation in increasing or decreasing parameter; None where the
        order is the caller's.
    out : str or None
        The file the sweep was written to, if any.
    """

    params: np.ndarray
    values: Sequence[Any]
    failures: dict = field(default_factory=dict)
    direction: str | None = None
    out: str | None = None

    @property
    def attractors(self) -> Sequence[Any]:
        """Deprecated name of :attr:`values` (the forced oscillator's ω-sweep)."""
        warnings.warn("SweepResult.attractors is deprecated: use SweepResult.values", DeprecationWarning,
                      stacklevel=2)
        return self.values

    @property
    def omegas(self) -> np.ndarray:
        """Deprecated name of :attr:`params` (the forced oscillator's ω-sweep)."""
        warnings.warn("SweepResult.omegas is deprecated: use SweepResult.params", DeprecationWarning, stacklevel=2)
        return self.params

    def __repr__(self) -> str:
        how = "" if self.direction is None else f"{self.direction}, "
        out = "" if self.out is None else f", out={self.out!r}"
        return f"SweepResult({how}{len(self.params)} points, {len(self.failures)} failures{out})"


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
