"""A compiled L-stable SDIRK step for the stick phases of eq. (1) (stiff, non-Lipschitz).

Where the explicit DOPRI5 of :mod:`landau.verify.skurativskyi.rk` is slow (measured at ω = 15,
``verify/benchmarks/skurativskyi_work_precision.py``): while the cart rests *on the
obstacle* (contact, x − x_I ≈ 9 µm) its velocity sits at |ẋ| ~ 1e-9…1e-7 m/s.  There the
damping D(ẋ) = cẋ + Tẋ/sqrt(ẋ² + ε²) + k_I b (x − x_I)^{n₂} sgn(ẋ)|ẋ|^{n₃} is stiff (T/(εm)
≈ 7e4 1/s) and non-Lipschitz (slope ∝ |ẋ|^{n₃−1}, n₃ ≈ 0.187, ≈ 5e5 1/s at 1e-8 m/s); an
explicit method chatters around ẋ = 0 with steps ~1e-6 s, >95 % of all its steps.  The true
motion there is slow (ẋ follows the quasi-static balance D(ẋ) = residual force).  Off the
obstacle (e.g. ω = 24.5) the cart also sticks on the track, stiff through T/(εm) only.
Which steps this stepper takes is decided in :func:`landau.verify.skurativskyi.rk.integrate_mixed`.

Method: the 5-stage, order-4, stiffly accurate, L-stable SDIRK4 of Hairer & Wanner (*Solving
ODEs II*, IV.6, eq. (6.16), γ = 1/4) with its embedded order-3 solution; the error estimate
is filtered by (I − hγJ)⁻¹ (Shampine) so that stiff components do not cap the step.

Why not the Radau IIA of ``verify/hybrid/radau.py`` (simplified Newton on the coupled
3n stage system): that iteration linearises D at the step start, and on the cusp
sgn(ẋ)|ẋ|^{n₃} Newton diverges (for |ẋ|^{n₃} each Newton step multiplies the distance to a
root by −(1/n₃ − 1) ≈ −4.4).  Measured (work-precision benchmark, last table): on the stick
at ω = 15 it stalls — 1e5 Newton failures in 2e5 step attempts, 3 ms of a 50 ms window
advanced (2.8 µs from rest), where this stepper needs ~70 steps.  With a *diagonally*
implicit method each stage of the second-order system is one scalar equation for the stage
velocity V,

    G(V) = V − s_v − hγ a(t, s_x + hγV, V) = 0,    G'(V) = 1 − hγ(hγ ∂a/∂x + ∂a/∂ẋ) ≥ 1,

(∂a/∂x ≤ 0 and ∂a/∂ẋ ≤ 0 for |ẋ| below b^{−1/n₃} ≈ 2.4 m/s when n₁ = n₂, as in the paper),
so G is strictly increasing with
a unique root and |V − V*| ≤ |G(V)|: a bracket is known from any guess.  In contact the
root is found by Newton in w = sgn(V)|V|^{n₃}, in which the cusp term is *linear* (the
Hertz damping is −κw, κ = k_I b (x − x_I)^{n₂}/m) and G(w) is smooth with a positive slope
at w = 0; out of contact in V itself.  A Newton step that leaves the bracket is replaced
by bisection, so every stage solve converges.

With the 4-D variational system (one tangent vector, top Lyapunov exponent) the tangent
stages solve (I − hγJ(Y_i)) δY_i = δs_i exactly (2×2), J = :func:`model.accel_grad` (the
Hertz-damping slope floored at |ẋ| = ε, as in the explicit path).
"""

from __future__ import annotations

import math
from functools import lru_cache
from pathlib import Path

import numpy as np
from numba import njit

from landau.verify.hybrid.compiled import SDIRK_A as SA, SDIRK_BHAT as SBHAT, SDIRK_C as SC, SDIRK_E as SE
from landau.verify.hybrid.compiled import SDIRK_GAMMA as GAMMA
from landau.verify.hybrid.specialise import specialise
from landau.verify.skurativskyi.model import IN3, accel_grad, accel_partials

#: Hairer–Wanner SDIRK4 (6.16) — the tableau of the generic compiled SDIRK4
#: (:mod:`landau.verify.hybrid.compiled`); order conditions checked in the tests
MAX_ITER = 80


@njit(cache=True)
def _to_w(V, q, in_w):
    if not in_w:
        return V
    return math.copysign(abs(V) ** q, V)


@njit(cache=True)
def _to_v(w, q, in_w):
    if not in_w:
        return w
    return math.copysign(abs(w) ** (1.0 / q), w)


@lru_cache(maxsize=None)
def cusp_sdirk_method(accel_partials, accel_grad, exponent_index):
    """The SDIRK4 step for ẍ = a(t, x, ẋ) with a cusp term −κ sgn(ẋ)|ẋ|^q (module docstring).

    Parameters
    ----------
    accel_partials : numba function
        ``(t, x, v, p) -> (a, ∂a/∂x, ∂a/∂ẋ without the cusp term, κ)``.
    accel_grad : numba function
        ``(t, x, v, p) -> (∂a/∂x, ∂a/∂ẋ)`` (cusp slope floored), for the tangent stages.
    exponent_index : int
        Index of the cusp exponent q in the parameter vector.

    Returns
    -------
    (stage_velocity, sdirk_step)
        The jitted stage solve and step documented below.
    """

    mod = specialise(Path(__file__).parent / "templates" / "cusp_sdirk.py",
                     {"accel_partials": accel_partials, "accel_grad": accel_grad,
                      "exponent_index": int(exponent_index)}, "cusp_sdirk")
    return mod.stage_velocity, mod.sdirk_step


#: the instance for eq. (1) of Skurativskyi et al. (2019) (the Hertz damping exponent n₃)
stage_velocity, sdirk_step = cusp_sdirk_method(accel_partials, accel_grad, IN3)
