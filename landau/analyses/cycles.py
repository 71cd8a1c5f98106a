"""The front door of the cycle continuation by model name: :func:`landau.cycles`.

``landau.cycles("spring-block", "dieterich", {"V": 1e-5}, steps=100)`` asks the model
(:func:`landau.models.get`) for its ``cycles`` declaration — the smooth vector field with the
Hopf parameter as the continuation parameter and the Hopf point as the start
(:class:`~landau.periodic.problem.CycleProblem`) — and follows the branch of cycles born there
with :func:`landau.periodic.continue_cycles` (orthogonal collocation, Floquet multipliers, the
folds, period doublings and Neimark–Sacker points located on the way).  The result is the
engine's :class:`~landau.periodic.CycleBranch`; ``.to_dataset()`` labels it along the branch
(an xarray Dataset).

References
----------
Kuznetsov, Y. A. (2004), *Elements of Applied Bifurcation Theory*, 3rd ed., Springer, Ch. 10.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from landau.errors import InputError


@dataclass(frozen=True)
class SpecialPoint:
    """A located bifurcation of cycles on a branch: ``kind`` LPC, PD or NS, where (parameter ``p``,
    ``period``, ``amplitude``) and its first normal-form coefficient (NaN where not computed)."""

    kind: str
    p: float
    period: float
    amplitude: float
    coefficient: float = float("nan")


@dataclass(frozen=True)
class HopfMark:
    """The Hopf point a branch starts at, as the diagram draws it: p_c, ω_c and whether the
    equilibrium is stable for p < p_c (all eigenvalues of J(y₀; p) in the left half-plane)."""

    p_c: float
    omega: float
    equilibrium_stable_below: bool


@dataclass(frozen=True)
class BranchTable:
    """A branch of cycles as columns (one entry per point) and its special points: what the text
    table, the JSON, the CSV, the figure and the sweep read (:func:`branch_table`)."""

    name: str
    parameter: str
    measure: str
    unit: str
    p: np.ndarray
    period: np.ndarray
    amplitude: np.ndarray
    stable: np.ndarray
    special: tuple[SpecialPoint, ...]
    hopf: HopfMark | None

    def first(self, kind: str) -> SpecialPoint | None:
        """The first special point of ``kind`` along the branch (None where there is none)."""
        return next((sp for sp in self.special if sp.kind == kind), None)


def hopf_mark(problem) -> HopfMark | None:
    """The :class:`HopfMark` of ``problem``'s Hopf start (None without one): the equilibrium's
    stability below p_c from the eigenvalues of J(y₀; p_c − δ), δ = 1e-4·max(|p_c|, 1)."""
    h = problem.hopf
    if h is None:
        return None
    delta = 1e-4 * max(abs(h.p_c), 1.0)
    # the eigenvalues of J(y₀; p_c − δ) (the equilibrium at p_c: the branch of steady states drawn flat)
    lam = np.linalg.eigvals(np.asarray(problem.jac(h.equilibrium, h.p_c - delta), dtype=float))
    return HopfMark(h.p_c, h.omega, bool(np.all(lam.real < 0)))


def branch_table(branch, problem) -> BranchTable:
    """The :class:`BranchTable` of the engine's branch of cycles of ``problem`` (its columns along the
    branch and its located special points, read from :meth:`CycleBranch.to_dataset`)."""
    ds = branch.to_dataset()
    p = np.asarray(ds[problem.parameter].values, dtype=float)
    special = tuple(SpecialPoint(str(sp.kind), float(sp.p), float(sp.period), float(sp.amplitude),
                                 float(getattr(sp, "coefficient", np.nan)))
                    for sp in getattr(branch, "special", ()))
    return BranchTable(problem.name, problem.parameter, problem.states[problem.measure], "",
                       p, np.asarray(ds["period"].values, dtype=float), np.asarray(ds["amplitude"].values, dtype=float),
                       np.asarray(ds["stable"].values, dtype=bool), special, hopf_mark(problem))


def branch_document(table: BranchTable) -> dict[str, Any]:
    """The JSON document of a branch: its columns, special points, Hopf point and the text table."""
    doc: dict[str, Any] = {
        "system": table.name, "parameter": table.parameter, "measure": table.measure,
        "points": int(table.p.size),
        "branch": {"p": table.p.tolist(), "period": table.period.tolist(), "amplitude": table.amplitude.tolist(),
                   "stable": [bool(x) for x in table.stable]},
        "special_points": [{"kind": sp.kind, "p": sp.p, "period": sp.period, "amplitude": sp.amplitude,
                            "coefficient": sp.coefficient} for sp in table.special],
    }
    if table.hopf is not None:
        doc["hopf"] = {"p_c": table.hopf.p_c, "omega_c": table.hopf.omega,
                       "equilibrium_stable_below": table.hopf.equilibrium_stable_below}
    doc["text"] = branch_text(table)
    return doc


def branch_text(table: BranchTable, rows: int = 25) -> str:
    """The branch as a text table (at most ``rows`` points, evenly spaced, the ends included) and its
    special points."""
    n = table.p.size
    pick = sorted(set(np.linspace(0, n - 1, min(rows, n)).round().astype(int).tolist())) if n else []
    unit = f" [{table.unit}]" if table.unit else ""
    lines = [f"cycles of {table.name} in {table.parameter}: {n} points"]
    if table.hopf is not None:
        lines.append(f"Hopf point {table.parameter}_c = {table.hopf.p_c:.8g}, omega_c = {table.hopf.omega:.6g}, "
                     f"period {2 * np.pi / table.hopf.omega:.6g}")
    lines.append(f"{table.parameter:>16} {'period':>14} {'amplitude ' + table.measure + unit:>22}  stable")
    for i in pick:
        lines.append(f"{table.p[i]:16.8g} {table.period[i]:14.6g} {table.amplitude[i]:22.6g}  "
                     f"{'yes' if table.stable[i] else 'no'}")
    if table.special:
        lines.append("special points:")
        for sp in table.special:
            coef = "" if not np.isfinite(sp.coefficient) else f", coefficient {sp.coefficient:.6g}"
            lines.append(f"  {sp.kind:<4} {table.parameter} = {sp.p:.8g}, period {sp.period:.6g}, amplitude "
                         f"{sp.amplitude:.6g}{coef}")
    else:
        lines.append("no fold, period doubling or Neimark-Sacker point on the branch")
    return "\n".join(lines)


def branch_csv(table: BranchTable) -> str:
    """The branch's columns as CSV text (header ``p, period, amplitude, stable``, the parameter's name first)."""
    head = f"{table.parameter},period,amplitude_{table.measure},stable"
    body = [f"{p!r},{T!r},{A!r},{int(bool(st))}" for p, T, A, st in
            zip(table.p.tolist(), table.period.tolist(), table.amplitude.tolist(), table.stable, strict=True)]
    return "\n".join([head, *body]) + "\n"


def cycle_problem_of(model, law=None, params: Mapping[str, Any] | None = None, *,
                     options: Mapping[str, Any] | None = None):
    """The model's :class:`~landau.periodic.problem.CycleProblem` for this law, these parameter
    values and options (its ``cycles`` declaration); the arguments as :func:`landau.simulate` takes them.

    Raises
    ------
    InputError
        An unknown model, law, parameter or option; a model without a ``cycles`` declaration (the
        message names the models that have one).
    """
    from landau.models import Setup, all_models
    from landau.simulation import _checked_options, _law_and_options, _model, _params

    m = _model(model)
    if m.cycles is None:
        have = [x.name for x in all_models() if x.cycles is not None]
        raise InputError(f"model {m.name!r} declares no cycles (models that do: {', '.join(have)})")
    opts = _checked_options(m, options)
    the_law = _law_and_options(m, law, opts)
    return m.cycles(Setup(the_law, _params(m, params, the_law, opts), opts))


def follow(problem, start: Any = "hopf", *, steps: int = 100, ds: float | None = None,
           direction: int | None = None, detect: bool = True, **engine: Any):
    """The branch of cycles of ``problem`` (a :class:`~landau.periodic.problem.CycleProblem`) by
    :func:`landau.periodic.continue_cycles`, its arguments checked (the parameters of :func:`cycles`)."""
    from landau.periodic import continue_cycles

    if isinstance(steps, bool) or not isinstance(steps, int) or steps < 1:
        raise InputError(f"cycles: steps must be a positive integer, got {steps!r}")
    if direction is not None and direction not in (1, -1):
        raise InputError(f"cycles: direction must be +1 or -1, got {direction!r}")
    if ds is not None:
        from landau.models.model import finite

        ds = finite(ds, "cycles: ds")
        if ds <= 0:
            raise InputError(f"cycles: ds must be > 0, got {ds!r}")
    if isinstance(start, str):
        if start != "hopf":
            raise InputError(f"cycles: start must be 'hopf' or a start the engine takes, got {start!r}")
        if problem.hopf is None:
            raise InputError(f"cycles: {problem.name} has no Hopf point to start from")
        start = None
    kw: dict[str, Any] = {"steps": steps, "detect": detect, **engine}
    if ds is not None:
        kw["ds"] = ds
    if direction is not None:
        kw["direction"] = direction
    return continue_cycles(problem, start, **kw)


def cycles(model: Any = "spring-block", law=None, params: Mapping[str, Any] | None = None, *,
           start: Any = "hopf", steps: int = 100, ds: float | None = None, direction: int | None = None,
           detect: bool = True, options: Mapping[str, Any] | None = None, **engine: Any):
    """The branch of cycles of a registered model from its Hopf point.

    Parameters
    ----------
    model : str or landau.models.Model
        The model's name (``landau.models.names()``) or the model.
    law : str or law object, optional
        The friction law of the kind the model takes (as :func:`landau.simulate`).
    params : mapping, optional
        Parameter values by declared name (not the continuation parameter: its value at the start
        is the Hopf point's).
    start : "hopf" or object
        ``"hopf"``: the amplitude equation's cycle near the Hopf point (C·sqrt|p − p_c| along
        the critical mode) as the first point; anything else is handed to the engine as its start.
    steps : int
        Number of continuation steps.
    ds : float, optional
        The first arclength step (the engine's default where None).
    direction : {+1, -1}, optional
        The direction in the parameter (default: the side of p_c where the cycle is born).
    detect : bool
        Locate the folds (LPC), period doublings (PD) and Neimark–Sacker points (NS) on the way.
    options : mapping, optional
        The model's options (a chain's ``blocks``, a user system's ``rhs``…).
    **engine
        Further keywords of :func:`landau.periodic.continue_cycles`.

    Returns
    -------
    landau.periodic.CycleBranch
        ``.to_dataset()``: the branch as an xarray Dataset.

    Raises
    ------
    InputError
        Bad input (see :func:`cycle_problem_of`), a non-positive ``steps``, a ``direction`` other
        than ±1.

    Examples
    --------
    >>> import landau
    >>> branch = landau.cycles("spring-block", "dieterich", {"V": 1e-4}, steps=40)   # doctest: +SKIP
    >>> branch.to_dataset()                                                           # doctest: +SKIP
    """
    problem = cycle_problem_of(model, law, params, options=options)
    return follow(problem, start, steps=steps, ds=ds, direction=direction, detect=detect, **engine)


__all__ = ["BranchTable", "HopfMark", "SpecialPoint", "branch_csv", "branch_document", "branch_table",
           "branch_text", "cycle_problem_of", "cycles", "follow", "hopf_mark"]
