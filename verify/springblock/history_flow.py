"""A load-point history's solution at any time: the flow of its compiled field, for measurements.

:func:`~landau.verify.springblock.history.simulate_history` records the run at the integrator's
accepted steps.  A quantity that lives between two steps — the time and height of a friction
peak, where dμ/dt = 0 — is not at a recorded point: read there, a direct-effect peak comes out
about 1e-6 low (the step near a peak is a sizeable fraction of its width).  :class:`HistoryFlow`
gives the solution at any time instead: :meth:`HistoryFlow.advance` integrates the same compiled
Radau IIA field (:func:`~landau.verify.springblock.history.history_kernel`) from a recorded state
to any later time, crossing the jumps of V(t) piece by piece as the run does, so that the state at
t is an end point of a run at the history's tolerance; :meth:`HistoryFlow.mu_rate` is
dμ/dt = ∇μ·y′ there, exactly from the symbolic law.  A peak is then a root of dμ/dt found by
Brent's method on this dense solution (:mod:`landau.lab.measure`).

In the variables of the history (u = x_lp − x, w = ln v, ψᵢ = ln φᵢ), the recorded series give
the state back: u = u₀ + x_lp − slip, w = ln v, ψᵢ = ln φᵢ (:meth:`HistoryFlow.state_of`).

References
----------
Brent, R. P. (1973), Algorithms for Minimization without Derivatives, Prentice-Hall, ch. 4.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Callable, Mapping

import numpy as np
import sympy as sp

from landau.errors import InputError, IntegratorError
from landau.laws.law import FrictionLaw
from landau.verify.hybrid.radau import STATUS
from landau.verify.hybrid.result import Simulation
from landau.verify.springblock.compiled_runs import CompiledField, drive, per_law
from landau.verify.springblock.history import (
    MAX_STEPS,
    LoadHistory,
    _history_law,
    _piece_vector,
    history_kernel,
    prepare_history,
)


@dataclass(frozen=True)
class HistoryFlow:
    """The compiled field of one history's run (law, history, k, resolved parameters, tolerance).

    Build it with :func:`history_flow`.  ``y0`` is the state (u, w, ψ…) of steady sliding at the
    first velocity, where the run starts.
    """

    law: FrictionLaw
    history: LoadHistory
    k: float
    p: Mapping[str, float]
    terms: tuple[str, ...]
    quasidynamic: bool
    y0: np.ndarray
    scale: np.ndarray
    rtol: float
    _kernel: CompiledField = field(repr=False, compare=False)

    def piece(self, t: float) -> int:
        """The index of the piece of the history in effect at ``t`` (a jump time starts its piece)."""
        return int(np.clip(np.searchsorted(self.history.times, float(t), side="right") - 1, 0,
                           len(self.history.times) - 1))

    def _vector(self, i: int) -> np.ndarray:
        V = self.history.velocities
        return _piece_vector(self._kernel, self.law, self.p, self.k, self.terms, self.quasidynamic, V[i], V[0],
                             float(self.scale[0]))

    def advance(self, t0: float, y, t1: float) -> np.ndarray:
        """The state (u, w, ψ…) at ``t1`` ≥ ``t0`` from ``y`` at ``t0``, integrated across the pieces."""
        y = np.asarray(y, float).copy()
        if not t1 >= t0:
            raise InputError(f"advance: the end time {t1!r} is before the start {t0!r}")
        T = list(self.history.times) + [np.inf]
        t = float(t0)
        while t < t1:
            i = self.piece(t)
            b = min(float(t1), T[i + 1])
            run = drive(self._kernel, self._vector(i), y, t, b, rtol=self.rtol, atol=self.rtol * self.scale,
                        max_steps=MAX_STEPS)
            if run.status != 0:
                raise IntegratorError(f"load-point history from t = {t:g} s: {STATUS[run.status]}",
                                      t=float(run.t), state=list(run.y))
            y, t = run.y, b
        return y

    def rate(self, t: float, y, piece: int | None = None) -> np.ndarray:
        """The field y′ at (t, y), with the load-point velocity of the piece at ``t`` (or of ``piece``:
        the left limit at a jump time)."""
        i = self.piece(t) if piece is None else int(piece)
        return self._kernel.f(float(t), np.asarray(y, float), self._vector(i))

    @cached_property
    def _mu_grad(self) -> Callable[..., Any]:
        return _mu_and_gradient(self.law)

    def mu(self, y) -> float:
        """μ(v, φ) at the state ``y``."""
        return float(self._mu_grad(np.asarray(y, float), *self._law_values)[0])

    def mu_rate(self, t: float, y, piece: int | None = None) -> float:
        """dμ/dt = ∇μ · y′ at (t, y) (the gradient from the symbolic law; ``piece`` as in :meth:`rate`)."""
        y = np.asarray(y, float)
        _, grad = self._mu_grad(y, *self._law_values)
        grad = np.broadcast_to(np.asarray(grad, float), y.shape)
        return float(np.dot(grad, self.rate(t, y, piece)))

    @cached_property
    def _law_values(self) -> list[float]:
        return [float(self.p[prm.name]) for prm in self.law.parameters]

    def state_of(self, sim: Simulation, i: int) -> np.ndarray:
        """The state (u, w, ψ…) at the recorded point ``i`` of ``sim`` (a run of this flow)."""
        col = {n: j for j, n in enumerate(sim.state_names)}
        u = self.y0[0] + sim.y[col["x_lp"], i] - sim.y[col["slip"], i]
        psi = [np.log(sim.y[col[s.name], i]) for s in self.law.states]
        return np.array([u, np.log(sim.y[col["v"], i]), *psi])


def _mu_and_gradient(law: FrictionLaw) -> Callable[..., Any]:
    """(μ, ∂μ/∂(u, w, ψ…)) at a state, lambdified once per law with its parameters as arguments."""
    def build():
        lp = {prm.name: sp.Symbol(f"_q{i}", real=True) for i, prm in enumerate(law.parameters)}
        u, w, psi, _, _, mu, _, _ = _history_law(law, {**lp, "sigma": 1.0}, 1.0, ())
        ys = [u, w, *psi]
        return sp.lambdify([ys, *lp.values()], (mu, [sp.diff(mu, q) for q in ys]), "numpy")

    return per_law(law, ("history mu gradient",), build)


def history_flow(law: FrictionLaw, history: LoadHistory, k: float, params: Mapping[str, float] | None = None,
                 rtol: float = 1e-9) -> HistoryFlow:
    """The flow of the run ``simulate_history(law, history, k, params, rtol=rtol)`` (same checks)."""
    p, terms, quasidynamic, y0, scale = prepare_history(law, history, k, params)
    kern = history_kernel(law, terms, quasidynamic)
    return HistoryFlow(law, history, float(k), p, terms, quasidynamic, y0, scale, float(rtol), kern)


__all__ = ["HistoryFlow", "history_flow"]
