"""A model as data: its name, parameters (default, unit, domain, source), the law it takes and what it offers.

A :class:`Model` is the one description of a mechanical model that every stage reads: the
command line (``landau hopf``, ``landau simulate``, ``landau sweep``), :func:`landau.sweep` and
:func:`landau.simulate`.  It holds

* its **parameters** (:class:`Parameter`: default, unit, domain, meaning, source — one place),
  which may depend on the friction law and the model's options (a spring–block has its law's
  parameters, a user system the names its expressions use): :meth:`Model.parameters`;
* the **kind of friction law** it takes (:class:`LawKind`);
* its **offerings**, plain callables with one signature each — ``hopf(setup) -> HopfResult``
  and ``simulate(setup, ...)`` — and the sweep tasks it runs (:attr:`Model.tasks`);
* its **options** (the model-specific settings such as a chain's number of blocks or a user
  system's right-hand side), by name, with one help line each.

A model is found by name through :func:`landau.models.get` (the registry, filled from the
``landau.models`` entry points); nothing compares model names: code asks the model.

Design after sympy.physics.mechanics (a model is data) and xarray's backends (plug-ins found
through entry points, not imported by string).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping

import numpy as np

from landau.errors import InputError


class LawKind(enum.Enum):
    """The kind of friction law a model takes (how the command line and the sweep declare it)."""

    #: a rate-and-state law μ(v, φ…), dφ/dt (:class:`landau.laws.FrictionLaw`): a built-in name or
    #: ``--mu``/``--state``
    RATE_AND_STATE = "rate-and-state"
    #: a velocity-only law F(v) (:class:`landau.laws.velocity.VelocityFriction`): ``--friction EXPR``
    VELOCITY = "velocity"
    #: a kinetic friction law of the relative velocity r (Galvanetto 2004, eq. 7): ``--kinetic EXPR``
    KINETIC = "kinetic"
    #: no friction law (a user system writes its own equations)
    NONE = "none"


#: the domains a parameter may declare, with the test and the words of the error
DOMAINS: dict[str, tuple[Callable[[np.ndarray], np.ndarray], str]] = {
    "real": (lambda x: np.isfinite(x), "finite"),
    "positive": (lambda x: np.isfinite(x) & (x > 0), "> 0"),
    "nonnegative": (lambda x: np.isfinite(x) & (x >= 0), ">= 0"),
    "negative": (lambda x: np.isfinite(x) & (x < 0), "< 0"),
    "nonzero": (lambda x: np.isfinite(x) & (x != 0), "nonzero"),
}


@dataclass(frozen=True)
class Parameter:
    """One declared parameter of a model.

    Parameters
    ----------
    name : str
        The name used by ``--param NAME=VALUE``, ``--grid NAME=...`` and ``params={...}``.
    default : float or None
        Its default value (None: it must be given).
    unit : str
        Its SI unit (``"1"`` for a number).
    domain : str
        One of :data:`DOMAINS` (``real``, ``positive``, ``nonnegative``, ``negative``, ``nonzero``).
    meaning : str
        One line saying what it is.
    source : str
        Where it (and its default) comes from: paper and equation or table.
    """

    name: str
    default: float | None
    unit: str = "1"
    domain: str = "real"
    meaning: str = ""
    source: str = ""

    def __post_init__(self) -> None:
        if self.domain not in DOMAINS:
            raise ValueError(f"parameter {self.name!r}: unknown domain {self.domain!r} (known: {', '.join(DOMAINS)})")

    def invalid(self, values) -> np.ndarray:
        """A boolean mask of the ``values`` outside this parameter's domain."""
        x = np.asarray(values, dtype=float)
        with np.errstate(invalid="ignore"):
            return ~DOMAINS[self.domain][0](x)

    def check(self, value, model: str = "") -> float:
        """``value`` as a float in the domain, else an :class:`InputError` naming the parameter and its domain."""
        try:
            x = float(value)
        except (TypeError, ValueError):
            raise InputError(f"{model + ': ' if model else ''}parameter {self.name!r} must be a number, "
                             f"got {value!r}") from None
        if bool(self.invalid(x)):
            raise InputError(self.message(x, model))
        return x

    def message(self, value: float, model: str = "") -> str:
        """The error for a ``value`` outside the domain (one line)."""
        what = f" ({self.meaning})" if self.meaning else ""
        return (f"{model + ': ' if model else ''}parameter {self.name!r}{what} must be "
                f"{DOMAINS[self.domain][1]}, got {value!r}")


@dataclass(frozen=True)
class Option:
    """A model-specific setting that is not a number to sweep (a chain's block count, a system's equations)."""

    name: str
    help: str
    #: the command-line spelling (``--blocks``); default ``--`` + the name with ``_`` as ``-``
    flag: str = ""

    @property
    def cli_flag(self) -> str:
        return self.flag or "--" + self.name.replace("_", "-")


@dataclass(frozen=True)
class Setup:
    """What an offering of a model is called with: the friction law (or None), the parameter values
    given (not yet completed by the defaults) and the model's options."""

    law: Any = None
    params: Mapping[str, float] = field(default_factory=dict)
    options: Mapping[str, Any] = field(default_factory=dict)

    def option(self, name: str, default: Any = None) -> Any:
        val = self.options.get(name, default)
        # an empty list or tuple is "not given"; an array (a matrix option) is compared by its type, never
        # by ==, whose truth value numpy refuses
        empty = val is None or (isinstance(val, (list, tuple)) and len(val) == 0)
        return default if empty else val


@dataclass(frozen=True, eq=False)
class Model:
    """A registered mechanical model (module docstring).

    Parameters
    ----------
    name : str
        The registry key (``spring-block``, ``impact-oscillator``, …).
    description : str
        One line: what it is and its source.
    law_kind : LawKind
        The kind of friction law it takes.
    declare : callable
        ``declare(setup) -> tuple[Parameter, ...]``: every parameter of the model for this law and
        these options (the Hopf parameter included; see :attr:`hopf_parameter`).
    hopf_parameter : callable or str or None
        The bifurcation parameter of :attr:`hopf` (its critical value is computed: it is never a
        given or swept value of the ``hopf`` task); a callable of the setup where it is chosen
        by an option (a user system's ``--parameter``).
    hopf : callable, optional
        ``hopf(setup) -> HopfResult``: the Hopf point and amplitude equation at one point.
    simulate : callable, optional
        The model's simulation, ``simulate(setup, *, t_end, y0, history, t_eval, max_steps, sections)
        -> Simulation`` (what :func:`landau.simulate` and ``landau simulate`` run).
    check : callable, optional
        The model's own check of its amplitude equation by simulation (``landau verify MODEL``),
        ``check(setup, eps2, tolerance) -> dict``: the JSON document, with ``exit_code`` and ``text`` (the
        human report).
    cycles : callable, optional
        ``cycles(setup) -> CycleProblem``: its smooth vector field, the Hopf parameter as the
        continuation parameter and the Hopf point as the start (:mod:`landau.periodic`; what
        :func:`landau.cycles` and ``landau cycles`` continue).
    tasks : mapping of str to callable
        The sweep tasks the model runs besides ``hopf`` (which it runs when it has :attr:`hopf`):
        task name -> ``factory(task, model, law, fixed, options) -> Task``.
    options : tuple of Option
        The model-specific settings it takes.
    defaults : mapping
        Defaults of the command line (``t_end``, the driving velocity, …), by name.
    convention : str
        The convention of its amplitude equation (written into sweep files), if it has one.
    source : str
        The papers it comes from.
    """

    name: str
    description: str
    law_kind: LawKind
    declare: Callable[[Setup], tuple[Parameter, ...]]
    hopf_parameter: Callable[[Setup], str | None] | str | None = None
    hopf: Callable[[Setup], Any] | None = None
    simulate: Callable[..., Any] | None = None
    check: Callable[..., dict] | None = None
    cycles: Callable[[Setup], Any] | None = None
    tasks: Mapping[str, Callable[..., Any]] = field(default_factory=dict)
    options: tuple[Option, ...] = ()
    defaults: Mapping[str, Any] = field(default_factory=dict)
    convention: str = ""
    convention_description: str = ""
    source: str = ""
    #: the law of this model used when none is named (a rate-and-state law's name), if any
    default_law: str | None = None
    #: figures of its sweeps beyond the generic one (``landau plot --sweep``): task -> ``plot(ds, fig) -> dict``
    plots: Mapping[str, Callable[..., dict]] = field(default_factory=dict)

    # --- parameters --------------------------------------------------------------------------
    def parameters(self, setup: Setup | None = None) -> tuple[Parameter, ...]:
        """Every declared parameter for this law and these options (:class:`Parameter`)."""
        return tuple(self.declare(setup or Setup()))

    def parameter(self, name: str, setup: Setup | None = None) -> Parameter:
        """The declared parameter ``name`` (InputError with the known names otherwise)."""
        params = {p.name: p for p in self.parameters(setup)}
        if name not in params:
            raise InputError(f"{self.name}: unknown parameter {name!r} (known: {', '.join(sorted(params))})")
        return params[name]

    def bifurcation_parameter(self, setup: Setup | None = None) -> str | None:
        """The Hopf parameter for this setup (None where the model has no Hopf analysis)."""
        hp = self.hopf_parameter
        return hp(setup or Setup()) if callable(hp) else hp

    def check_params(self, names, setup: Setup | None = None, *, what: str = "") -> dict[str, Parameter]:
        """The declared parameters named in ``names``; an unknown name is an InputError that lists
        the known ones (and says which is close)."""
        import difflib

        declared = {p.name: p for p in self.parameters(setup)}
        for name in names:
            if name not in declared:
                close = difflib.get_close_matches(name, declared, n=1)
                hint = f"; did you mean {close[0]!r}?" if close else ""
                raise InputError(f"{what or self.name}: unknown parameter {name!r} for model {self.name!r}"
                                 f"{self._law_words(setup)} (known: {', '.join(sorted(declared))}){hint}")
        return {n: declared[n] for n in names}

    def invalid_points(self, values: Mapping[str, Any], setup: Setup | None = None) -> tuple[np.ndarray, list[str]]:
        """The points outside a parameter's domain: (mask, message per point; '' where valid).

        Parameters
        ----------
        values : mapping of str to array_like
            Parameter values by name, broadcast together (one entry per point).
        """
        declared = self.check_params(list(values), setup)
        arrays = {k: np.asarray(v, dtype=float) for k, v in values.items()}
        shape = np.broadcast(*arrays.values()).shape if arrays else ()
        n = int(np.prod(shape)) if shape else 1
        bad = np.zeros(n, dtype=bool)
        messages = [""] * n
        for name, arr in arrays.items():
            flat = np.broadcast_to(arr, shape).ravel() if shape else arr.reshape(1)
            mask = declared[name].invalid(flat)
            for j in np.flatnonzero(mask & ~bad):
                messages[j] = declared[name].message(float(flat[j]), self.name)
            bad |= mask
        return bad, messages

    def _law_words(self, setup: Setup | None) -> str:
        law = setup.law if setup is not None else None
        return f" with law {law.name!r}" if law is not None and hasattr(law, "name") else ""

    # --- offerings ---------------------------------------------------------------------------
    def offers(self, task: str) -> bool:
        """True where the model runs the sweep task (or offering) ``task``."""
        if task == "hopf":
            return self.hopf is not None
        if task == "cycles" and "cycles" not in self.tasks:
            return self.cycles is not None
        return task in self.tasks

    def offered(self) -> tuple[str, ...]:
        """The sweep tasks this model runs."""
        return tuple(t for t in dict.fromkeys(("hopf", *self.tasks, "cycles")) if self.offers(t))

    def __repr__(self) -> str:
        return f"Model({self.name!r}, law={self.law_kind.value}, offers={list(self.offered())})"


def finite(value, what: str) -> float:
    """``value`` as a finite float, else an InputError naming ``what``."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a number, got {value!r}") from None
    if not math.isfinite(x):
        raise InputError(f"{what} must be finite, got {value!r}")
    return x


__all__ = ["DOMAINS", "LawKind", "Model", "Option", "Parameter", "Setup", "finite"]
