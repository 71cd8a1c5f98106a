"""Viscous + regularised dry (rolling) resistance of Skurativskyi et al. (2019), eq. (1).

Source: S. Skurativskyi, G. Kudra, K. Witkowski, J. Awrejcewicz, *Bifurcation phenomena and
statistical regularities in dynamics of forced impacting oscillator*, Nonlinear Dyn. 98
(2019) 1795–1806, eq. (1) and the identified parameters of Sec. 2:

    F_R(ẋ) = c ẋ + T ẋ / sqrt(ẋ² + ε²)

c = 6.6511 N·s/m (viscous), T = 0.63133 N (rolling resistance, independent of the normal
load), ε = 1e-6 m/s (regularisation of sgn ẋ).  The ε → 0 limit is the set-valued Coulomb
law c ẋ + T Sgn(ẋ) (:meth:`RegularisedFriction.coulomb`, which returns the sign branch and
NaN at ẋ = 0 where the force lies in [−T, T]).

Stiffness: dF_R/dẋ = c + T ε²/(ẋ² + ε²)^{3/2} reaches c + T/ε ≈ 6.3e5 N·s/m at ẋ = 0, so
on the 8.735 kg cart the slip-reversal region has a time scale m ε / T ≈ 1.4e-5 s.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

SOURCE = "Skurativskyi, Kudra, Witkowski, Awrejcewicz 2019, Nonlinear Dyn. 98:1795, eq. (1), Sec. 2"


@dataclass(frozen=True)
class RegularisedFriction:
    """F_R(ẋ) = c ẋ + T ẋ/sqrt(ẋ² + ε²) [N]; defaults: Sec. 2 of the paper."""

    c: float = 6.6511      # N s/m
    T: float = 0.63133     # N
    eps: float = 1e-6      # m/s

    def __post_init__(self) -> None:
        if not (self.c >= 0 and self.T >= 0 and self.eps >= 0):
            from landau.errors import InputError
            raise InputError(f"RegularisedFriction needs c, T, eps >= 0 (got c={self.c}, T={self.T}, eps={self.eps})")

    def __call__(self, v):
        """F_R(ẋ); with ε = 0 the Coulomb branch (NaN at ẋ = 0, where it is set-valued)."""
        v = np.asarray(v, dtype=float)
        if self.eps == 0:
            out = self.c * v + self.T * np.where(v == 0, np.nan, np.sign(v))
        else:
            out = self.c * v + self.T * v / np.sqrt(v * v + self.eps ** 2)
        return out if out.ndim else float(out)

    def slope(self, v):
        """dF_R/dẋ = c + T ε²/(ẋ² + ε²)^{3/2} (ε > 0)."""
        v = np.asarray(v, dtype=float)
        out = self.c + self.T * self.eps ** 2 / (v * v + self.eps ** 2) ** 1.5
        return out if out.ndim else float(out)

    def coulomb(self) -> "RegularisedFriction":
        """The ε → 0 limit: c ẋ + T sgn ẋ."""
        return RegularisedFriction(self.c, self.T, 0.0)

    def __repr__(self) -> str:
        return (f"RegularisedFriction(c={self.c:g} N·s/m, T={self.T:g} N, ε={self.eps:g} m/s)"
                f"  # {SOURCE}")
