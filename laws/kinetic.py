"""Velocity-weakening kinetic friction of Galvanetto (2004), eq. (7), and its Coulomb limit.

Source: U. Galvanetto, *Sliding bifurcations in the dynamics of mechanical systems with
dry friction*, J. Sound Vib. 276 (2004) 121–139, eq. (7) (garbled in the scanned print; the
reading below is the one confirmed by reproducing the paper's
two-block results).  With the relative velocity r = Ẋ − V (block minus belt):

    F_k(r) = (1 − δ)/(1 − γ r) + δ        for r < 0   (block slower than the belt)
    F_k(r) = −(1 − δ)/(1 + γ r) − δ       for r > 0

so |F_k(0±)| = 1 = F_s (the static level) and |F_k| decays to δ for |r| → ∞.  γ > 0 sets
the velocity weakening, 0 ≤ δ ≤ 1 the residual level.  γ = 0 gives Coulomb friction with
equal static and kinetic levels (F_k = −sign r); the force is scaled by F_si for block i
(eq. 8b).  Defaults are those of the paper's examples: γ = 3 (Figs 7–15), δ = 0 (as
printed; Sec. 4.1's one-block values are reproduced only with δ = 0.2).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class KineticFriction:
    """F_k(r) of eq. (7).  ``neg``/``pos`` are the two smooth branches (defined beyond r = 0,
    which the grazing analysis uses to continue a slip field past the switching surface)."""

    gamma: float = 3.0
    delta: float = 0.0

    def neg(self, r):
        """Branch r < 0: (1 − δ)/(1 − γ r) + δ  (> 0: the belt drags the block forward)."""
        return (1.0 - self.delta) / (1.0 - self.gamma * r) + self.delta

    def pos(self, r):
        """Branch r > 0: −(1 − δ)/(1 + γ r) − δ."""
        return -(1.0 - self.delta) / (1.0 + self.gamma * r) - self.delta

    def dneg(self, r):
        """dF_k/dr on the r < 0 branch: γ(1 − δ)/(1 − γ r)²."""
        return self.gamma * (1.0 - self.delta) / (1.0 - self.gamma * r) ** 2

    def dpos(self, r):
        """dF_k/dr on the r > 0 branch: γ(1 − δ)/(1 + γ r)²."""
        return self.gamma * (1.0 - self.delta) / (1.0 + self.gamma * r) ** 2

    def d3neg(self, r):
        """d³F_k/dr³ on the r < 0 branch: 6γ³(1 − δ)/(1 − γ r)⁴."""
        return 6.0 * self.gamma ** 3 * (1.0 - self.delta) / (1.0 - self.gamma * r) ** 4

    def __call__(self, r):
        """F_k(r) for r ≠ 0 (at r = 0 the force is set-valued, [−1, 1]; returns nan)."""
        r = np.asarray(r, dtype=float)
        out = np.where(r < 0, self.neg(np.minimum(r, 0.0)), self.pos(np.maximum(r, 0.0)))
        out = np.where(r == 0, np.nan, out)
        return out if out.ndim else float(out)

    @classmethod
    def coulomb(cls) -> "KineticFriction":
        """The Coulomb limit γ → 0: F_k = −sign(r), kinetic level = static level = 1."""
        return cls(gamma=0.0, delta=0.0)

    def __repr__(self) -> str:
        return f"KineticFriction(γ={self.gamma:g}, δ={self.delta:g})  # Galvanetto 2004 eq. (7)"
