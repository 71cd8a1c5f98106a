"""Regime diagram of the spring–block in the (V, k) plane (Putelat et al. 2010, Figs 5b, 12, 14a).

* the Hopf line k = k_c(V) (eq. 7), split where Λ < 0 (supercritical: a small stable
  stick–slip cycle is born as k decreases through k_c) and Λ > 0 (subcritical: bistability
  between steady sliding and a large cycle above k_c);
* its codimension-two points (:func:`landau.analyses.transition.codim2_points`);
* the transition line k*(V*(p)) = k_c(V*(p)) traced by the codimension-two point as a law
  parameter p varies (Fig. 14a, for the residual strength c);
* the inertial boundary k = Mω_c² (Sec. 4.2: the inertial regime lies below it), and the
  naive crossover M/k = (L/V)² for comparison;
* the same with M = 0 (quasi-static) via ``params={"M": 0}``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np

from landau.analyses.codim2 import GeneralisedHopfPoint
from landau.analyses.transition import TransitionCurve, codim2_points, transition_curve
from landau.derivation.multiscale import Derivation


@dataclass(frozen=True)
class RegimeDiagram:
    """Arrays over the velocity grid ``V`` (m/s); NaN where there is no Hopf point."""

    V: np.ndarray
    kc: np.ndarray
    Lambda: np.ndarray
    inertial_boundary: np.ndarray  # M ω_c² (N/m)
    codim2: tuple[GeneralisedHopfPoint, ...]
    params: Mapping[str, float]

    @property
    def k_c(self) -> np.ndarray:
        """The critical stiffness k_c(V) (N/m), NaN where there is no Hopf point (the field ``kc``)."""
        return self.kc

    @property
    def supercritical(self) -> np.ndarray:
        """k_c where Λ < 0, NaN elsewhere (plot-ready)."""
        return np.where(self.Lambda < 0, self.kc, np.nan)

    @property
    def subcritical(self) -> np.ndarray:
        """k_c where Λ > 0, NaN elsewhere."""
        return np.where(self.Lambda > 0, self.kc, np.nan)

    def _repr_html_(self) -> str:
        from landau.report.display import html_record

        n = int(np.sum(np.isfinite(self.kc)))
        fields = {"velocities": f"{self.V[0]:.4g} .. {self.V[-1]:.4g} m/s ({len(self.V)} points)",
                  "Hopf points": n, "subcritical": int(np.sum(self.Lambda > 0)),
                  "supercritical": int(np.sum(self.Lambda < 0))}
        for i, c in enumerate(self.codim2):
            fields[f"codimension-two point {i + 1}"] = f"V = {c.V:.8g} m/s, k_c = {c.k_c:.6g} N/m"
        return html_record("Regime diagram (V, k)", fields, note="Λ < 0: supercritical, Λ > 0: subcritical")

    def plot(self, ax=None):
        """The diagram on matplotlib axes (see :func:`landau.report.plotting.plot_regime_diagram`); returns the Axes."""
        from landau.report.plotting import plot_regime_diagram

        return plot_regime_diagram(self, ax)

    def __repr__(self) -> str:
        n = int(np.sum(np.isfinite(self.kc)))
        return (f"RegimeDiagram({n} Hopf points on [{self.V[0]:.3g}, {self.V[-1]:.3g}] m/s, "
                f"{int(np.sum(self.Lambda > 0))} subcritical, {len(self.codim2)} codimension-two point(s))")


def regime_diagram(d: Derivation, Vs, params: Mapping[str, float] | None = None) -> RegimeDiagram:
    """The Hopf line over ``Vs`` split by the sign of Λ, the codimension-two points in
    [min Vs, max Vs] and the inertial boundary Mω_c²."""
    p = d.block.resolve(params)
    Vs = np.asarray(Vs, dtype=float)
    r = d.evaluate(Vs, p, ["Lambda"])
    pts = codim2_points(d, float(Vs.min()), float(Vs.max()), p)
    return RegimeDiagram(Vs, r["kc"], r["Lambda"], p["M"] * r["omega_c"] ** 2, tuple(pts), dict(p))


def transition_line(d: Derivation, name: str, lo: float, hi: float,
                    params: Mapping[str, float] | None = None, n: int = 30) -> TransitionCurve:
    """k*(V*(p)) over p in [lo, hi] (Fig. 14a): the rows of the curve, ending at p* with k = 0."""
    return transition_curve(d, name, lo, hi, params, n=n)


def naive_crossover(Vs, M: float, L: float) -> np.ndarray:
    """k = M (V/L)²: the creep/inertia crossover of Heslot et al. (τ_in = τ_cr), Fig. 14a."""
    return M * (np.asarray(Vs, dtype=float) / L) ** 2
