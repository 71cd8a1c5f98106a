"""Hybrid-model declarations: modes, guards and transitions.

A hybrid model is a set of named :class:`Mode` objects.  Each mode carries a smooth
vector field ``rhs(t, y)`` and the :class:`Guard` functions that bound its domain.

Conventions (the whole engine relies on them)
---------------------------------------------
* **A mode is valid while every one of its guards is positive.**  An event happens when a
  guard reaches zero from above.  A guard that must fire in both directions is written as
  two guards (``g`` and ``-g``).
* A guard with a ``transition`` is a *switching* guard: at its root the engine calls
  ``transition(t, y)``, which returns the new mode and the (possibly reset, possibly
  re-dimensioned) state, either as a :class:`Jump` or as a ``(mode_name, y)`` tuple.  The
  transition decides the new mode from the state at the root, which the engine always
  takes on the *new* side of the switching surface (guard value ``<= 0``).
* A guard without a transition is a *section*: its root is logged (Poincaré sections,
  extrema of an observable, ...) and integration continues in the same mode.
* Guards are evaluated on whole arrays of dense-output samples: ``fun(t, y)`` must accept
  ``t`` of shape ``(m,)`` and ``y`` of shape ``(n, m)`` and return shape ``(m,)`` (plain
  arithmetic on ``y[i]`` does this automatically), as well as scalar ``t`` and ``y`` of
  shape ``(n,)``.

Subclass contract (models built in code)
----------------------------------------
A model class only has to provide :attr:`HybridModel.modes` (a mapping name -> Mode);
subclassing :class:`HybridModel` and filling the mapping in ``__init__`` is the usual
pattern.  Modes may have different state dimensions: the transitions map between them.
Optional per-mode ``on_zeno(t, y)`` says how to continue when events accumulate (e.g. a
bouncing contact becomes a persistent one); without it the engine stops and reports the
accumulation.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Mapping, Union

import numpy as np

Array = np.ndarray
RHS = Callable[[float, Array], Array]
GuardFun = Callable[[Union[float, Array], Array], Union[float, Array]]


@dataclass(frozen=True)
class Jump:
    """Result of a transition: the new mode, the state in it, and a note for the log."""

    mode: str
    y: Array
    note: str = ""


TransitionFun = Callable[[float, Array], Union[Jump, tuple]]


@dataclass(frozen=True)
class Guard:
    """A scalar function that is positive inside the mode; an event when it reaches 0.

    ``transition=None`` makes it a section (logged, no switch).  ``terminal=True`` stops
    the simulation after the event has been applied.  ``rate(t, y)`` (optional) is the
    guard's time derivative along the mode's flow: a phase that starts with the guard
    slightly negative (|g| < ``EngineOptions.recover_tol``) but increasing is entered
    instead of being left at once — this resolves the Filippov corner cases where a
    transition lands, to rounding, just outside a region that the flow is entering.
    ``affine = (w, b)`` (optional) declares that ``fun(t, y) = w·y + b``, and ``(w, b, u)`` that
    ``fun(t, y) = w·y + u·f(t, y) + b`` with f the mode's vector field (e.g. an extremum of a
    velocity: its acceleration): a compiled stepper that offers ``run_quiet``
    (:class:`~landau.verify.hybrid.dop853.CompiledDOP853`) then screens the guard inside its
    compiled loop.
    """

    name: str
    fun: GuardFun
    transition: TransitionFun | None = None
    terminal: bool = False
    rate: Callable[[float, Array], float] | None = None
    affine: tuple | None = None

    def __repr__(self) -> str:
        kind = "section" if self.transition is None else "switch"
        return f"Guard({self.name!r}, {kind}{', terminal' if self.terminal else ''})"


@dataclass(frozen=True)
class Mode:
    """One smooth regime: a vector field and the guards that bound it.

    ``kernel`` (optional) is a function of no arguments returning the same field compiled (a
    :class:`~landau.verify.hybrid.kernel.Kernel`, built on first use): the engine integrates
    it instead of ``rhs`` when the stepper is a compiled one.

    ``guard_kernel`` (optional) is a function of no arguments returning every guard of the mode
    compiled as one vector function (a :class:`~landau.verify.hybrid.kernel.Kernel` whose
    ``fun(t, y, p, out)`` writes ``out[j] = guards[j].fun(t, y)``, in the order of ``guards``,
    e.g. made by :func:`landau.codegen.kernels.generate_vector_function`): with a compiled
    stepper the engine then tests the guards inside the stepper's compiled loop
    (:mod:`landau.verify.hybrid.guarded`) and returns to Python only at a step where one may
    cross.  The Python ``Guard.fun`` stay the reference: they locate the event on that step.
    """

    name: str
    rhs: RHS
    guards: tuple[Guard, ...] = ()
    jac: Callable[[float, Array], Array] | None = None
    on_zeno: TransitionFun | None = None
    kernel: Callable[[], object] | None = None
    guard_kernel: Callable[[], object] | None = None

    def __repr__(self) -> str:
        return f"Mode({self.name!r}, guards={[g.name for g in self.guards]})"


@dataclass(frozen=True)
class HybridModel:
    """A named set of modes.  See the module docstring for the conventions."""

    modes: Mapping[str, Mode] = field(default_factory=dict)
    name: str = "hybrid"

    def mode(self, name: str) -> Mode:
        try:
            return self.modes[name]
        except KeyError:
            raise KeyError(f"model {self.name!r} has no mode {name!r} (modes: {sorted(self.modes)})") from None

    @classmethod
    def from_modes(cls, *modes: Mode, name: str = "hybrid") -> "HybridModel":
        return cls(modes={m.name: m for m in modes}, name=name)

    def __repr__(self) -> str:
        return f"HybridModel({self.name!r}, modes={sorted(self.modes)})"


def as_jump(out) -> Jump:
    """Normalise a transition's return value."""
    if isinstance(out, Jump):
        return out
    mode, y, *rest = out
    return Jump(mode, np.asarray(y, dtype=float), rest[0] if rest else "")
