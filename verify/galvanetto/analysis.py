"""Poincaré sections, map curves and bifurcation diagrams of the Galvanetto models."""

from __future__ import annotations

import numpy as np

from landau.laws.kinetic import KineticFriction, resolve_kinetic_law
from landau.verify.galvanetto.maps import MapUndefined, default_stepper, f, model_for
from landau.verify.galvanetto.model import StickSlipParams, two_blocks
from landau.verify.hybrid import EngineOptions, simulate
from landau.verify.hybrid.analysis import SweepResult, map_bifurcation_diagram

FIG_STEPPER = default_stepper(1e-9)  # plots need ~1e-9, not the locators' 1e-11


def map_curve(p: StickSlipParams, ds, period: int = 1, stepper=FIG_STEPPER) -> np.ndarray:
    """f^period on a grid of d (nan where the map is undefined)."""
    out = []
    for d in ds:
        try:
            x = float(d)
            for _ in range(period):
                x = f(p, x, stepper)
            out.append(x)
        except MapUndefined:
            out.append(np.nan)
    return np.array(out)


def beta_diagram(betas, d0: float, V: float = 0.25, alpha: float = 1.2, gamma: float | None = None,
                 delta: float | None = None, n_transient: int = 40, n_keep: int = 24, stepper=FIG_STEPPER, *,
                 law: KineticFriction | None = None) -> SweepResult:
    """Bifurcation diagram of the event map in β (Figs 12, 15): attractor points of d, for the
    kinetic law ``law`` (default eq. (7) with ``gamma`` = 3, ``delta`` = 0)."""
    law = resolve_kinetic_law(law, gamma, delta)
    return map_bifurcation_diagram(lambda b: (lambda d: f(two_blocks(V, alpha, b, law=law), d, stepper)),
                                   betas, d0, n_transient, n_keep)


def trajectory(p: StickSlipParams, mode: str, y0, t_end: float, stepper=FIG_STEPPER, t_keep: float = 0.0):
    """Recorded hybrid trajectory (t, y) for phase portraits, samples after ``t_keep``."""
    sol = simulate(model_for(p), mode, np.asarray(y0, float), (0.0, t_end), stepper,
                   EngineOptions(record=True, samples=8))
    t, y = sol.t, sol.y
    keep = t >= t_keep
    return t[keep], y[:, keep], sol


def gsp_orbit_trajectory(p: StickSlipParams, d: float, n_steps: int, stepper=FIG_STEPPER):
    """Trajectory of ``n_steps`` map steps from the g.s.p. d, including the g.s.p. segments."""
    from landau.verify.galvanetto.maps import gsp_start
    ys = []
    for _ in range(n_steps):
        mode, y0 = gsp_start(p, d)
        sol = simulate(model_for(p), mode, y0, (0.0, 500.0), stepper, EngineOptions(record=True, samples=8),
                       stop=lambda ev: ev.to_mode == "ss")
        ys.append(sol.y)
        d = float(sol.y_final[1] - sol.y_final[0])
        # the g.s.p. segment: both at V from the landing to the next start
        mode2, y1 = gsp_start(p, d)
        ys.append(np.column_stack([sol.y_final, y1]))
    return np.concatenate(ys, axis=1)
