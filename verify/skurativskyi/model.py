"""The forced impacting oscillator of Skurativskyi et al. (2019), eq. (1).

    m ẍ + k x + F_R(ẋ) + F_I(x, ẋ) = m₀e ω² sin ωt,
    F_R = c ẋ + T ẋ/sqrt(ẋ² + ε²)                                  (laws/regularised.py)
    F_I = k_I f   if x − x_I ≥ 0 and f ≥ 0, else 0,
    f   = (x − x_I)^{n₁} + b (x − x_I)^{n₂} sgn(ẋ) |ẋ|^{n₃}.

Parameters: Sec. 2 of the paper.  Contact is the side x ≥ x_I (the obstacle is
above the cart; at rest the springs press the cart on it by ≈ 5 µm).

Structure used by the integrator (why the contact switching needs no saltation)
------------------------------------------------------------------------------
Both switching surfaces — x = x_I and f = 0 — are crossed with a *continuous* vector field:
F_I → 0 as x → x_I⁺ (n₁, n₂ = 3/2 > 0) and F_I = k_I f → 0 as f → 0⁺.  Hence the saltation
matrix S = I + (f⁺ − f⁻) nᵀ / (n·f⁻) is the identity at every switching (checked
numerically by :func:`saltation_matrix`), and the variational equations are continued
through a contact switching unchanged.  The surface f = 0 with x > x_I needs ẋ < −b^{−1/n₃}
≈ −2.4 m/s, two orders of magnitude above the velocities of the paper's regimes: it is
handled by the max(f, 0) in the field (continuous), not by a guard.

The field is, however, only C¹ across x = x_I (δ^{3/2}) and only Hölder in ẋ at ẋ = 0 inside
contact (|ẋ|^{n₃}, n₃ ≈ 0.187), and the friction slope T/ε makes slip reversal stiff.  The
compiled integrator (:mod:`landau.verify.skurativskyi.rk`) ends steps exactly on x = x_I.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, fields

import numpy as np
from numba import njit

from landau.errors import InputError

SOURCE = "Skurativskyi, Kudra, Witkowski, Awrejcewicz 2019, Nonlinear Dyn. 98:1795-1806"

# indices into the packed parameter vector used by the compiled kernels
IM, IM0E, IEPS, IN1, IN2, IN3, IK, IC, IT, IKI, IB, IXI, IOM = range(13)


@dataclass(frozen=True)
class Params:
    """Model parameters of eq. (1); defaults are the identified set of Sec. 2 (SI units)."""

    m: float = 8.735            # kg, cart mass (measured)
    m0e: float = 0.01805        # kg m, unbalance (measured)
    eps: float = 1e-6           # m/s, regularisation of sgn
    n1: float = 1.5             # Hertz exponent (fixed)
    n2: float = 1.5
    n3: float = 0.18667
    k: float = 1418.9           # N/m
    c: float = 6.6511           # N s/m
    T: float = 0.63133          # N
    kI: float = 2.3983e8        # N/m^{3/2}
    b: float = 0.8485           # (s/m)^{n3}
    xI: float = -2.086e-3       # m, obstacle position
    omega: float = 16.0         # rad/s, forcing frequency

    def __post_init__(self) -> None:
        for name in ("m", "k", "kI", "n1", "n2", "n3", "omega"):
            val = getattr(self, name)
            if not (np.isfinite(val) and val > 0):
                raise InputError(f"Skurativskyi model: {name} must be a positive number (got {val!r})")
        for name in ("m0e", "eps", "c", "T", "b"):
            val = getattr(self, name)
            if not (np.isfinite(val) and val >= 0):
                raise InputError(f"Skurativskyi model: {name} must be >= 0 (got {val!r})")
        if not np.isfinite(self.xI):
            raise InputError("Skurativskyi model: xI must be finite")
        if self.eps == 0:
            raise InputError("Skurativskyi model: eps = 0 is the set-valued Coulomb limit; "
                             "the simulator needs the regularised law (eps > 0)")

    def packed(self) -> np.ndarray:
        return np.array([self.m, self.m0e, self.eps, self.n1, self.n2, self.n3, self.k, self.c, self.T,
                         self.kI, self.b, self.xI, self.omega], dtype=float)

    def with_(self, **kw) -> "Params":
        d = asdict(self)
        unknown = set(kw) - set(d)
        if unknown:
            raise InputError(f"unknown parameter(s) {sorted(unknown)} (known: {sorted(d)})")
        d.update({k: float(v) for k, v in kw.items()})
        return Params(**d)

    @property
    def period(self) -> float:
        return 2 * np.pi / self.omega

    @classmethod
    def names(cls) -> list[str]:
        return [f.name for f in fields(cls)]


PAPER = Params()


@njit(cache=True)
def contact_force(x, v, p):
    """F_I(x, ẋ) of eq. (1)."""
    d = x - p[IXI]
    if d <= 0.0:
        return 0.0
    sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
    f = d ** p[IN1] + p[IB] * d ** p[IN2] * sv * abs(v) ** p[IN3]
    return p[IKI] * f if f > 0.0 else 0.0


@njit(cache=True)
def accel(t, x, v, p):
    """ẍ from eq. (1)."""
    eps = p[IEPS]
    fr = p[IC] * v + p[IT] * v / np.sqrt(v * v + eps * eps)
    om = p[IOM]
    return (p[IM0E] * om * om * np.sin(om * t) - p[IK] * x - fr - contact_force(x, v, p)) / p[IM]


@njit(cache=True)
def accel_grad(t, x, v, p):
    """(∂ẍ/∂x, ∂ẍ/∂ẋ).  The |ẋ|^{n₃−1} slope of the Hertz damping is unbounded at ẋ = 0; it
    is evaluated with |ẋ| floored at ε (in the variational equation the tangent crosses ẋ = 0
    in an integrable way: the slope is O(|ẋ|^{−0.81}); the floor keeps it finite)."""
    eps = p[IEPS]
    s = v * v + eps * eps
    dfr = p[IC] + p[IT] * eps * eps / (s * np.sqrt(s))
    dx = -p[IK]
    dv = -dfr
    d = x - p[IXI]
    if d > 0.0:
        av = abs(v)
        sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
        pw = av ** p[IN3]
        f = d ** p[IN1] + p[IB] * d ** p[IN2] * sv * pw
        if f > 0.0:
            dx -= p[IKI] * (p[IN1] * d ** (p[IN1] - 1.0) + p[IB] * p[IN2] * d ** (p[IN2] - 1.0) * sv * pw)
            avf = max(av, eps)
            dv -= p[IKI] * p[IB] * d ** p[IN2] * p[IN3] * avf ** (p[IN3] - 1.0)
    return dx / p[IM], dv / p[IM]


@njit(cache=True)
def rhs2(t, y, p, out):
    """State (x, ẋ)."""
    out[0] = y[1]
    out[1] = accel(t, y[0], y[1], p)


@njit(cache=True)
def rhs(t, y, p, out):
    """The field the compiled integrator uses: (x, ẋ) if len(y) == 2, with the variational
    equation for one tangent vector (δx, δẋ) if len(y) == 4."""
    if y.shape[0] == 4:
        rhs4(t, y, p, out)
    else:
        rhs2(t, y, p, out)


@njit(cache=True)
def rhs4(t, y, p, out):
    """State (x, ẋ, δx, δẋ): the flow and one tangent vector (variational equation)."""
    out[0] = y[1]
    out[1] = accel(t, y[0], y[1], p)
    ax, av = accel_grad(t, y[0], y[1], p)
    out[2] = y[3]
    out[3] = ax * y[2] + av * y[3]


def field(params: Params, t: float, y) -> np.ndarray:
    """The vector field (ẋ, ẍ) in Python (for checks and the engine's guard/rate calls)."""
    p = params.packed()
    y = np.asarray(y, float)
    return np.array([y[1], accel(float(t), float(y[0]), float(y[1]), p)])


def saltation_matrix(params: Params, t: float, y, side_eps: float = 1e-13) -> np.ndarray:
    """S = I + (f⁺ − f⁻) nᵀ/(n·f⁻) at a point on x = x_I (n = (1, 0)); f± are the fields
    evaluated just inside/outside contact.  Equals I because F_I is continuous there."""
    y = np.asarray(y, float)
    xi = params.xI
    fp = field(params, t, [xi + side_eps, y[1]])
    fm = field(params, t, [xi - side_eps, y[1]])
    n = np.array([1.0, 0.0])
    den = n @ fm
    if den == 0:
        raise InputError("saltation matrix undefined at a grazing point (ẋ = 0 on x = x_I)")
    return np.eye(2) + np.outer(fp - fm, n) / den


@njit(cache=True)
def accel_partials(t, x, v, p):
    """ẍ and its partials split for the stiff stepper (:mod:`landau.verify.skurativskyi.sdirk`):
    returns (a, ∂a/∂x, ∂a/∂ẋ without the Hertz damping, κ) with κ = k_I b (x − x_I)^{n₂}/m
    when the contact force is active (else 0), so that the Hertz damping contributes
    −κ sgn(ẋ)|ẋ|^{n₃} to ẍ — exactly linear in w = sgn(ẋ)|ẋ|^{n₃}.  Nothing is floored here."""
    eps = p[IEPS]
    s = v * v + eps * eps
    rs = np.sqrt(s)
    om = p[IOM]
    m = p[IM]
    a = p[IM0E] * om * om * np.sin(om * t) - p[IK] * x - p[IC] * v - p[IT] * v / rs
    av = -(p[IC] + p[IT] * eps * eps / (s * rs)) / m
    ax = -p[IK]
    kap = 0.0
    d = x - p[IXI]
    if d > 0.0:
        sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
        pw = abs(v) ** p[IN3]
        dn2 = d ** p[IN2]
        f = d ** p[IN1] + p[IB] * dn2 * sv * pw
        if f > 0.0:
            a -= p[IKI] * f
            ax -= p[IKI] * (p[IN1] * d ** (p[IN1] - 1.0) + p[IB] * p[IN2] * d ** (p[IN2] - 1.0) * sv * pw)
            kap = p[IKI] * p[IB] * dn2 / m
    return a / m, ax / m, av, kap
