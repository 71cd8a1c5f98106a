"""The frictional impact oscillator of Lancioni, Lenci & Galvanetto, eq. (1).

Coordinates q = (φ, y): the bar angle and the height of m₂; state y = (φ, y, φ̇, ẏ) in
every mode.  Eq. (1), M(q) q̈ = W λ − h (re-derived from the energies and virtual work):

    M = [[m₁l², m₁l sin φ], [m₁l sin φ, m₁ + m₂]],   W = [w_N w_T] = [[l sin φ, l cos φ], [1, 0]],
    h = (c_φφ̇ + k_φ(φ − φ₀) + m₁gl sin φ,  c_yẏ + k_y(y − y₀) + m₁lφ̇² cos φ + (m₁+m₂)g),

gap g_N = y − l cos φ (γ_N = ẏ + lφ̇ sin φ, ŵ_N = lφ̇² cos φ), relative tangential
velocity g_T = lφ̇ cos φ − v(t) (ŵ_T = −lφ̇² sin φ − v̇).  The regimes (free flight,
slip±, stick), transitions, Poisson impact law and Painlevé checks are the generic ones
of :mod:`landau.verify.lancioni.contact`; this module only supplies the mechanics.

Belt.  The paper's constant belt speed is not printed; |v| = 1 m/s (the amplitude of the
sinusoidal belt v = sin(πt/2) of Fig. 6) is used, in the direction that has the Hopf
point: v = −1 (g_T > 0 on the slip equilibrium, *positive slip*; see
:mod:`landau.verify.lancioni.slip`).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Mapping

import numpy as np

from landau.verify.lancioni.contact import ContactMechanics, ContactModel, Section
from landau.verify.hybrid.contact import check_contact_coefficients
from landau.verify.lancioni.slip import SET1, SET2, resolve


@dataclass(frozen=True)
class ConstantBelt:
    """v(t) = v (m/s)."""

    v: float = -1.0

    def __call__(self, t):
        return self.v + 0.0 * np.asarray(t, float)

    def rate(self, t):
        return 0.0 * np.asarray(t, float)


@dataclass(frozen=True)
class SineBelt:
    """v(t) = A sin(Ω t) (Fig. 6: A = 1 m/s, Ω = π/2 rad/s)."""

    A: float = 1.0
    Omega: float = float(np.pi / 2)

    def __call__(self, t):
        return self.A * np.sin(self.Omega * np.asarray(t, float))

    def rate(self, t):
        return self.A * self.Omega * np.cos(self.Omega * np.asarray(t, float))


@dataclass(frozen=True)
class Lancioni(ContactMechanics):
    """Eq. (1) with Coulomb coefficient ``mu``, restitution ``eN`` and belt ``belt``."""

    params: Mapping[str, float] = field(default_factory=lambda: dict(SET1))
    mu: float = 0.4
    eN: float = 0.0
    belt: object = ConstantBelt()
    n: int = 2
    name: str = "lancioni"

    def __post_init__(self):
        object.__setattr__(self, "params", resolve(self.params))
        check_contact_coefficients(self.mu, self.eN)
        p = self.params
        object.__setattr__(self, "_c", (p["m1"], p["m2"], p["l"], p["k_y"], p["k_phi"], p["c_y"], p["c_phi"],
                                         p["phi0"], p["y0"], p["g"]))

    def with_(self, **kw) -> "Lancioni":
        return replace(self, **kw)

    def terms(self, t, q, qd):
        m1, m2, l, ky, kp, cy, cp, p0, y0, g = self._c
        phi, y = q[0], q[1]
        w, yd = qd[0], qd[1]
        sn, cs = np.sin(phi), np.cos(phi)
        det = m1 * l * l * (m2 + m1 * cs * cs)
        i11, i12, i22 = (m1 + m2) / det, -m1 * l * sn / det, m1 * l * l / det
        f1 = -(cp * w + kp * (phi - p0) + m1 * g * l * sn)
        f2 = -(cy * yd + ky * (y - y0) + m1 * l * w * w * cs + (m1 + m2) * g)
        a0 = np.array([i11 * f1 + i12 * f2, i12 * f1 + i22 * f2])
        # M⁻¹ w_N, M⁻¹ w_T
        nN1, nN2 = l * sn, 1.0
        nT1 = l * cs
        MiN = np.array([i11 * nN1 + i12 * nN2, i12 * nN1 + i22 * nN2])
        MiT = np.array([i11 * nT1, i12 * nT1])
        MiW = np.stack([MiN, MiT], axis=1)
        GNN = nN1 * MiN[0] + nN2 * MiN[1]
        GNT = nN1 * MiT[0] + nN2 * MiT[1]
        GTT = nT1 * MiT[0]
        G = np.array([[GNN, GNT], [GNT, GTT]])
        bN = nN1 * a0[0] + nN2 * a0[1] + l * cs * w * w
        bT = nT1 * a0[0] - l * sn * w * w - self.belt.rate(t)
        return a0, MiW, G, np.array([bN, bT])

    def gap(self, q):
        return q[1] - self._c[2] * np.cos(q[0])

    def gammas(self, t, q, qd):
        l = self._c[2]
        return qd[1] + l * np.sin(q[0]) * qd[0], l * np.cos(q[0]) * qd[0] - self.belt(t)

    def project(self, t, y, normal_velocity: bool = False):
        y = np.array(y, dtype=float)
        l = self._c[2]
        y[1] = l * np.cos(y[0])
        if normal_velocity:
            y[3] = -l * np.sin(y[0]) * y[2]
        return y

    def project_stick(self, t, y):
        """γ_T = 0 exactly: φ̇ = v(t)/(l cos φ) (a rounding-size correction), then γ_N = 0."""
        y = np.array(y, dtype=float)
        y[2] = float(self.belt(t)) / (self._c[2] * np.cos(y[0]))
        return self.project(t, y, normal_velocity=True)


#: section guards: φ̇ maxima (φ̈ → 0 from above) and upward crossings of φ = 0
PHIDOT_MAX = Section("phidot-max", lambda t, y, acc: acc[0])
PHI_ZERO_UP = Section("phi=0 up", lambda t, y, acc: -y[0])


def build(mu: float, eN: float = 0.0, params: Mapping[str, float] | None = None, belt=None,
          sections=(PHIDOT_MAX,), stick_tol: float = 0.0, stick_tol_reset: str = "project") -> ContactModel:
    """The hybrid model of eq. (1) (set 1 by default, g = 10) at friction coefficient μ.

    ``stick_tol`` > 0 switches on the numerical stick tolerance of
    :class:`landau.verify.lancioni.contact.ContactModel` (default 0: the exact model).

    Parameters
    ----------
    mu : float
        Friction coefficient μ.
    eN : float, optional
        Normal coefficient of restitution of the Poisson impact law.
    params : mapping of str to float, optional
        Mechanical parameters (default: set 1, :data:`SET1`).
    belt : callable, optional
        Belt velocity v(t) in m/s (default constant, v = −1 m/s).
    sections : tuple of Section, optional
        Poincaré sections to log (default: maxima of φ̇).
    stick_tol : float, optional
        Numerical stick tolerance (0: the exact model).
    stick_tol_reset : str, optional
        How the state is reset when the tolerance is used (see ``ContactModel``).

    Returns
    -------
    ContactModel
        A hybrid model for :func:`landau.verify.hybrid.simulate`.

    References
    ----------
    Lancioni, G., Lenci, S. & Galvanetto, U., the frictional impact oscillator (hopping of a
    windscreen wiper), eq. (1).
    """
    mech = Lancioni(params=dict(params or SET1), mu=float(mu), eN=float(eN), belt=belt or ConstantBelt())
    return ContactModel(mech, sections=sections, stick_tol=float(stick_tol), stick_tol_reset=stick_tol_reset)


def slip_state(mech: Lancioni, phi: float, phidot: float = 0.0) -> np.ndarray:
    """A state on the surface (g_N = 0, γ_N = 0) with angle φ and rate φ̇."""
    l = mech.params["l"]
    return np.array([phi, l * np.cos(phi), phidot, -l * np.sin(phi) * phidot])


__all__ = ["Lancioni", "ConstantBelt", "SineBelt", "build", "slip_state", "PHIDOT_MAX", "PHI_ZERO_UP",
           "SET1", "SET2"]
