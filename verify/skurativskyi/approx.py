"""Approximate solutions of Sec. 5 (Skurativskyi et al. 2019): static equilibrium and the
two estimates of the first grazing frequency.

* Static equilibrium X₀ (Sec. 5): k X₀ + k_I (X₀ − x_I)^{n₁} = 0  →  X₀ = −2.0807e-3 m.
* Linearised solution, eq. (4): x = X₀ + A₁ sin ωt + A₂ cos ωt with
  A₁ = m₀eω²Δ/((ωc)² + Δ²), A₂ = −c m₀e ω³/((ωc)² + Δ²), Δ = k + 1.5 k_I sqrt(X₀ − x_I) − mω².
  Grazing when the trough reaches the obstacle: x_I = X₀ − m₀eω²/sqrt((ωc)² + Δ²) → 15.657 rad/s.
* Harmonic balance, eqs (5)–(6): y = A sin(ωt − α) with
      −mAω² + k(A + X₀) + k_I (A + X₀ − x_I)^{n₁} = m₀eω² cos α,   cAω = m₀eω² sin α.
  At ω = 14 the root A > 0, cos α > 0 reproduces eq. (6) (:func:`harmonic_amplitude`).
  Grazing, "x_I = X₀ + A(ω)", leaves a sign choice; three readings are computed by
  :func:`grazing_harmonic_branches`:
  - ``cos_alpha_negative``: the signed amplitude A = x_I − X₀ < 0 substituted literally
    (the Hertz term vanishes) with cos α = −sqrt(1 − sin²α): **ω = 12.789 rad/s, the
    printed value** — this is the paper's choice;
  - ``cos_alpha_positive``: the same A with cos α > 0: no real root (m|A|ω² ≪ m₀eω²);
  - ``trough``: the physical grazing of the trough, X₀ − A = x_I with A = X₀ − x_I > 0 on
    the branch of eq. (6) (cos α > 0): 17.283 rad/s.
  The simulated first detachment, ≈ 14.05 rad/s, lies between 12.789 and 15.657 (as the
  paper says: the linear estimate is too high, the harmonic-balance one too low).

The damping c of both estimates is the friction law's viscous coefficient lim F_R(v)/v
(:attr:`Params.linear_damping`; c of eq. (1) for the paper's law): the paper writes F_R as
c ẏ plus the dry part T sgn ẏ and drops the latter as a small nonlinear term, and any law
of the model is split the same way (e.g. c v + T tanh(v/ε) also gives c).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.optimize import brentq

from landau.errors import InputError
from landau.verify.skurativskyi.model import Params


def static_equilibrium(p: Params) -> float:
    """X₀ solving k X₀ + k_I (X₀ − x_I)^{n₁} = 0 with X₀ > x_I (needs x_I < 0: the springs
    press the cart on the obstacle).  Sec. 5: X₀ = −2.0807e-3 m."""
    if p.xI >= 0:
        raise InputError(f"static equilibrium in contact needs x_I < 0 (got x_I = {p.xI})")
    g = lambda X: p.k * X + p.kI * (X - p.xI) ** p.n1
    # g(x_I) = k x_I < 0 and g(0) > 0: a unique root in (x_I, 0)
    return brentq(g, p.xI, 0.0, xtol=1e-18, rtol=1e-15, maxiter=500)


@dataclass(frozen=True)
class LinearSolution:
    """Eq. (4): x = X₀ + A₁ sin ωt + A₂ cos ωt."""

    omega: float
    X0: float
    A1: float
    A2: float
    Delta: float

    @property
    def amplitude(self) -> float:
        return math.hypot(self.A1, self.A2)

    def __repr__(self) -> str:
        return (f"LinearSolution(ω={self.omega:g}: x = {self.X0:.5g} {self.A2:+.5g} cos ωt "
                f"{self.A1:+.5g} sin ωt)  # eq. (4)")


def contact_stiffness(p: Params) -> float:
    """Linearised stiffness at the static equilibrium, k + n₁ k_I (X₀ − x_I)^{n₁−1} [N/m]."""
    X0 = static_equilibrium(p)
    return p.k + p.n1 * p.kI * (X0 - p.xI) ** (p.n1 - 1)


def contact_resonance(p: Params) -> float:
    """Undamped resonance of the oscillator linearised about X₀, sqrt(k_lin/m) [rad/s] (Δ = 0 in eq. 4)."""
    return math.sqrt(contact_stiffness(p) / p.m)


def linear_solution(p: Params, omega: float | None = None) -> LinearSolution:
    om = p.omega if omega is None else float(omega)
    X0 = static_equilibrium(p)
    c = p.linear_damping
    D = contact_stiffness(p) - p.m * om ** 2
    den = (om * c) ** 2 + D ** 2
    return LinearSolution(om, X0, p.m0e * om ** 2 * D / den, -c * p.m0e * om ** 3 / den, D)


def grazing_linear(p: Params, bracket: tuple[float, float] | None = None) -> float:
    """ω with x_I = X₀ − m₀eω²/sqrt((ωc)² + Δ²) (Sec. 5, after eq. 4): 15.657 rad/s.

    The root below the contact resonance (Δ > 0) is returned: the linear response amplitude grows
    monotonically from 0 at ω = 0 up to the resonance :func:`contact_resonance`, so (0, ω_r) brackets
    exactly one root when the trough reaches the obstacle there at all.  ``bracket`` overrides the
    interval."""
    X0 = static_equilibrium(p)
    g = lambda om: X0 - linear_solution(p, om).amplitude - p.xI
    lo, hi = bracket if bracket is not None else (1e-9 * contact_resonance(p), contact_resonance(p))
    if not g(hi) < 0 < g(lo):
        raise InputError(f"no linearised grazing frequency in ({lo:.6g}, {hi:.6g}) rad/s for these parameters: "
                         "the linear trough does not reach the obstacle below the contact resonance")
    return brentq(g, lo, hi, xtol=1e-13)


def _harmonic_residual(p: Params, om: float, sign: float, trough: bool = False) -> float:
    X0 = static_equilibrium(p)
    A = X0 - p.xI if trough else p.xI - X0
    F = p.m0e * om ** 2
    c = p.linear_damping
    s = c * A * om / F
    if abs(s) > 1:
        return math.nan
    cos_a = sign * math.sqrt(1 - s * s)
    lhs = -p.m * A * om ** 2 + p.k * (A + X0) + p.kI * max(A + X0 - p.xI, 0.0) ** p.n1
    return lhs - F * cos_a


def grazing_harmonic_branches(p: Params, omegas=None) -> dict[str, float | None]:
    """Roots of the harmonic-balance grazing condition for the three readings of the module
    docstring (None where there is no root).  The scan runs up to the contact resonance
    (:func:`contact_resonance`), above which the harmonic solution of eq. (5) is not the
    small-forcing branch; ``omegas`` overrides it."""
    import numpy as np
    omegas = np.linspace(1e-3, 1.0, 4000) * contact_resonance(p) if omegas is None else omegas
    out: dict[str, float | None] = {}
    for name, sgn, tr in (("cos_alpha_negative", -1.0, False), ("cos_alpha_positive", 1.0, False),
                          ("trough", 1.0, True)):
        vals = np.array([_harmonic_residual(p, w, sgn, tr) for w in omegas])
        idx = np.nonzero(np.isfinite(vals[:-1]) & np.isfinite(vals[1:]) & (np.sign(vals[:-1]) != np.sign(vals[1:])))[0]
        out[name] = (brentq(lambda w, sgn=sgn, tr=tr: _harmonic_residual(p, w, sgn, tr), omegas[idx[0]],
                            omegas[idx[0] + 1], xtol=1e-13) if len(idx) else None)
    return out


def grazing_harmonic(p: Params) -> float:
    """Eqs (5)–(6): ω with x_I = X₀ + A(ω), branch cos α < 0 (reproduces 12.789 rad/s)."""
    root = grazing_harmonic_branches(p)["cos_alpha_negative"]
    if root is None:
        raise InputError("no harmonic-balance grazing frequency (cos α < 0 branch) for these parameters")
    return root


def harmonic_amplitude(p: Params, omega: float) -> tuple[float, float]:
    """(A, α) of eq. (5) at ω: the root A > 0, cos α > 0 (at ω = 14 this gives eq. (6):
    A cos α = 3.6833e-6, A sin α = 3.5707e-10)."""
    X0 = static_equilibrium(p)
    F = p.m0e * omega ** 2
    c = p.linear_damping

    def res(A):
        s = c * A * omega / F
        cos_a = math.sqrt(max(0.0, 1 - s * s))
        return -p.m * A * omega ** 2 + p.k * (A + X0) + p.kI * max(A + X0 - p.xI, 0.0) ** p.n1 - F * cos_a

    A = brentq(res, 0.0, 1e-2, xtol=1e-18, rtol=1e-14)
    return A, math.asin(c * A * omega / F)
