"""Bifurcation diagrams in μ (Figs 2, 4) and the sinusoidal-belt runs (Fig. 6).

Poincaré section.  The paper plots "the maximum angular velocity φ̇_max" with the section
printed (OCR) as "φ = 0 when φ̇ > 0".  The slip oscillations born at the Hopf point stay
within ~0.01 rad of φ_e ≈ 0.389 and never reach φ = 0, so that section would be empty on
the branch the paper plots; we read it as φ̈ = 0 with φ̇ > 0 — the local maxima of φ̇, which
is what "φ̇_max" says — and log them with the section guard ``phidot-max`` of
:mod:`landau.verify.lancioni.model` (``PHI_ZERO_UP`` is available for the literal reading).

Continuation: each μ starts from the final state (and mode) of the previous one, so
sweeping up and down exposes the hysteresis between the slip and the detached branches.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from landau.verify.hybrid import simulate
from landau.verify.hybrid.dop853 import CompiledDOP853
from landau.verify.lancioni.contact import default_options
from landau.verify.lancioni.model import ConstantBelt, SineBelt, build, slip_state
from landau.verify.lancioni.slip import SET1, equilibrium_phi, resolve

STEPPER = CompiledDOP853(1e-10, 1e-12)


@dataclass(frozen=True)
class DiagramPoint:
    mu: float
    phidot_max: np.ndarray      # φ̇ at the φ̇-maxima (φ̇ > 0) after the transient
    modes: tuple[str, ...]      # modes visited after the transient
    state: np.ndarray
    mode: str

    def __repr__(self) -> str:
        n_values = len(np.unique(np.round(self.phidot_max, 6)))
        return f"DiagramPoint(mu={self.mu:.6g}, {n_values} values, modes={self.modes})"


def diagram_point(mu: float, y0, mode: str | None, eN: float = 0.0, params: Mapping[str, float] | None = None,
                  t_transient: float = 20.0, t_keep: float = 5.0, v: float = -1.0,
                  chatter_tol: float = 1e-6) -> DiagramPoint:
    cm = build(mu, eN, params, ConstantBelt(v))
    y0 = np.asarray(y0, float)
    mode = mode or cm.initial_mode(0.0, y0)
    sol = simulate(cm.model, mode, y0, (0.0, t_transient + t_keep), STEPPER,
                   default_options(chatter_tol, record=False))
    late = [e for e in sol.events if e.t >= t_transient]
    mx = np.array([e.y[2] for e in late if e.guard == "phidot-max" and e.y[2] > 0])
    modes = tuple(sorted({e.from_mode for e in late if e.kind != "section"} | {sol.final_mode}))
    return DiagramPoint(mu, mx, modes, sol.y_final, sol.final_mode)


def diagram(mus: Sequence[float], y0, mode: str | None = None, eN: float = 0.0,
            params: Mapping[str, float] | None = None, **kw) -> list[DiagramPoint]:
    """Continuation along ``mus`` (in the given order) from (y0, mode)."""
    out = []
    for m in mus:
        pt = diagram_point(float(m), y0, mode, eN, params, **kw)
        out.append(pt)
        y0, mode = pt.state, pt.mode
    return out


def equilibrium_state(mu: float, params: Mapping[str, float] | None = None, kick: float = 0.0) -> np.ndarray:
    p = resolve(params)
    cm = build(mu, 0.0, p)
    return slip_state(cm.mech, equilibrium_phi(p, mu, 1) + kick)


@dataclass(frozen=True)
class SineBeltRun:
    """Fig. 6 run: v = sin(πt/2); free-flight phases and whether they are hopping."""

    mu: float
    t: np.ndarray
    y: np.ndarray
    modes: list
    flights: tuple[tuple[float, float], ...]   # (start, duration)
    hop_time: float                            # flight time while φ̇·v < 0

    @property
    def hopping(self) -> bool:
        return self.hop_time > 0

    def __repr__(self) -> str:
        return (f"SineBeltRun(mu={self.mu:g}, {len(self.flights)} flights, total "
                f"{sum(d for _, d in self.flights):.4g} s, hopping time {self.hop_time:.4g} s)")


def sine_belt_run(mu: float, params: Mapping[str, float] | None = None, eN: float = 0.0,
                  t_end: float = 16.0) -> SineBeltRun:
    """Start at rest on the belt (φ = φ₀, v(0) = 0) and run ``t_end`` s (4 belt periods by default)."""
    p = resolve(params or SET1)
    belt = SineBelt()
    cm = build(mu, eN, p, belt)
    y0 = slip_state(cm.mech, p["phi0"])
    sol = simulate(cm.model, cm.initial_mode(0.0, y0), y0, (0.0, t_end), STEPPER, default_options())
    t, y, modes = sol.trajectory()
    flights = tuple((float(s.t[0]), float(s.t[-1] - s.t[0])) for s in sol.segments if s.mode == "flight")
    hop = 0.0
    for s in sol.segments:
        if s.mode == "flight" and len(s.t) > 1:
            opp = (s.y[2] * belt(s.t)) < 0
            hop += float(np.sum(np.diff(s.t) * opp[1:]))
    return SineBeltRun(mu, t, y, modes, flights, hop)
