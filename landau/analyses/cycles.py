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
    end: str = ""
    end_message: str = ""

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


def _special_amplitude(branch, sp) -> float:
    """The half peak-to-peak of the measured state at a located special point: from its located cycle
    where the engine kept it, else linear in the parameter between the branch points around it."""
    j = branch.problem.measure
    if sp.cycle is not None:
        from landau.periodic.collocation import evaluate

        mesh, Y = sp.cycle
        y = evaluate(mesh, Y, np.linspace(0.0, 1.0, 8 * (mesh.npts - 1) + 1))[j]
        return float((y.max() - y.min()) / 2)
    amp = branch.amplitude
    i = min(max(int(sp.index), 0), len(branch) - 2)
    p0, p1 = branch.parameter[i], branch.parameter[i + 1]
    w = 0.0 if p1 == p0 else (sp.parameter - p0) / (p1 - p0)
    return float(amp[i] + min(max(w, 0.0), 1.0) * (amp[i + 1] - amp[i]))


def branch_table(branch, problem=None) -> BranchTable:
    """The :class:`BranchTable` of the engine's :class:`~landau.periodic.CycleBranch` (its columns
    along the branch, its located special points with their amplitude, and the Hopf point)."""
    problem = problem if problem is not None else branch.problem
    special = tuple(SpecialPoint(str(sp.kind), float(sp.parameter), float(sp.period), _special_amplitude(branch, sp),
                                 float("nan") if sp.coefficient is None else float(sp.coefficient))
                    for sp in branch.special) if len(branch) > 1 else ()
    return BranchTable(problem.name, problem.parameter, problem.states[problem.measure], "",
                       np.asarray(branch.parameter, dtype=float), np.asarray(branch.period, dtype=float),
                       np.asarray(branch.amplitude, dtype=float), np.asarray(branch.stable, dtype=bool), special,
                       hopf_mark(problem), str(branch.end.name), str(branch.message))


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
    doc["end"] = {"reason": table.end, "message": table.end_message}
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
    if table.end:
        lines.append(f"end: {table.end}" + (f" ({table.end_message})" if table.end_message else ""))
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
    # the engine's default Newton tolerance (1e-10 on the scaled step) lies below the round-off floor of a
    # spring-block's collocation (slips of 1e-9 m beside states of 1e-2): steps fail as "Newton diverges"
    kw.setdefault("tol", 1e-8)
    if "ds_max" not in kw and problem.hopf is not None:
        # the engine's pseudo-arclength norm takes the parameter unscaled: a step moves p by at most
        # ds_max, so a stiffness of 2e5 N/m would crawl at 0.5 N/m a step; 2.5e-4 |p_c| a step at most
        kw["ds_max"] = max(0.5, 2.5e-4 * abs(problem.hopf.p_c))
    if ds is not None:
        kw["ds"] = ds
    if direction is not None:
        kw["direction"] = direction
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):   # a predictor outside the field's domain:
        return continue_cycles(problem, start, **kw)                       # NaN, and the engine halves the step


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
        +1 (the engine's default): away from the Hopf point, the cycle growing; −1 the other way.
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
