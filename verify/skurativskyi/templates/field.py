"""Template: the vector field of eq. (1) of Skurativskyi et al. (2019) for one friction law (see
landau.verify.hybrid.specialise for how templates are bound; landau.verify.skurativskyi.model
binds it).

Free names: ``friction(v, p) -> F``, ``friction_slope(v, p) -> (F, dF/dv)`` and
``friction_derivative(v, p) -> dF/dv``, ``subtract_friction(a, v, p) -> a - F(v)`` (generated
from the law by landau.verify.skurativskyi.friction), ``jit`` (the numba decorator).
"""

import numpy as np

from landau.verify.skurativskyi.model import IB, IK, IKI, IM, IM0E, IN1, IN2, IN3, IOM, IVF, IXI


@jit
def contact_force(x, v, p):
    """F_I(x, ẋ) of eq. (1)."""
    d = x - p[IXI]
    if d <= 0.0:
        return 0.0
    sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
    dn1 = d ** p[IN1]
    dn2 = dn1 if p[IN2] == p[IN1] else d ** p[IN2]  # one power routine when n₁ = n₂ (the paper's)
    f = dn1 + p[IB] * dn2 * sv * abs(v) ** p[IN3]
    return p[IKI] * f if f > 0.0 else 0.0


@jit
def accel(t, x, v, p):
    """ẍ from eq. (1)."""
    om = p[IOM]
    return (p[IM0E] * om * om * np.sin(om * t) - p[IK] * x - friction(v, p) - contact_force(x, v, p)) / p[IM]


@jit
def accel_grad(t, x, v, p):
    """(∂ẍ/∂x, ∂ẍ/∂ẋ).  The |ẋ|^{n₃−1} slope of the Hertz damping is unbounded at ẋ = 0; it
    is evaluated with |ẋ| floored at p[IVF] (in the variational equation the tangent crosses
    ẋ = 0 in an integrable way: the slope is O(|ẋ|^{−0.81}); the floor keeps it finite)."""
    dfr = friction_derivative(v, p)
    dx = -p[IK]
    dv = -dfr
    d = x - p[IXI]
    if d > 0.0:
        av = abs(v)
        sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
        pw = av ** p[IN3]
        same = p[IN2] == p[IN1]
        dn1 = d ** p[IN1]
        dn2 = dn1 if same else d ** p[IN2]
        f = dn1 + p[IB] * dn2 * sv * pw
        if f > 0.0:
            dm1 = d ** (p[IN1] - 1.0)
            dm2 = dm1 if same else d ** (p[IN2] - 1.0)
            dx -= p[IKI] * (p[IN1] * dm1 + p[IB] * p[IN2] * dm2 * sv * pw)
            avf = max(av, p[IVF])
            dv -= p[IKI] * p[IB] * dn2 * p[IN3] * avf ** (p[IN3] - 1.0)
    return dx / p[IM], dv / p[IM]


@jit
def rhs2(t, y, p, out):
    """State (x, ẋ)."""
    out[0] = y[1]
    out[1] = accel(t, y[0], y[1], p)


@jit
def rhs4(t, y, p, out):
    """State (x, ẋ, δx, δẋ): the flow and one tangent vector (variational equation)."""
    out[0] = y[1]
    out[1] = accel(t, y[0], y[1], p)
    ax, av = accel_grad(t, y[0], y[1], p)
    out[2] = y[3]
    out[3] = ax * y[2] + av * y[3]


@jit
def rhs(t, y, p, out):
    """The field the compiled integrator uses: (x, ẋ) if len(y) == 2, with the variational
    equation for one tangent vector (δx, δẋ) if len(y) == 4 (written out rather than calling
    rhs2/rhs4: measured ~10 % faster in the integrators)."""
    out[0] = y[1]
    out[1] = accel(t, y[0], y[1], p)
    if y.shape[0] == 4:
        ax, av = accel_grad(t, y[0], y[1], p)
        out[2] = y[3]
        out[3] = ax * y[2] + av * y[3]


@jit
def accel_partials(t, x, v, p):
    """ẍ and its partials split for the stiff stepper (landau.verify.skurativskyi.sdirk):
    returns (a, ∂a/∂x, ∂a/∂ẋ without the Hertz damping, κ) with κ = k_I b (x − x_I)^{n₂}/m
    when the contact force is active (else 0), so that the Hertz damping contributes
    −κ sgn(ẋ)|ẋ|^{n₃} to ẍ — exactly linear in w = sgn(ẋ)|ẋ|^{n₃}.  Nothing is floored here."""
    om = p[IOM]
    m = p[IM]
    # F_R's terms subtracted one by one (for the paper's law: ... - c v - T v/sqrt(v² + ε²),
    # the rounding of eq. (1) written by hand, on which the stiff path's bifurcations depend)
    a = subtract_friction(p[IM0E] * om * om * np.sin(om * t) - p[IK] * x, v, p)
    av = -friction_derivative(v, p) / m
    ax = -p[IK]
    kap = 0.0
    d = x - p[IXI]
    if d > 0.0:
        sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
        pw = abs(v) ** p[IN3]
        same = p[IN2] == p[IN1]
        dn1 = d ** p[IN1]
        dn2 = dn1 if same else d ** p[IN2]
        f = dn1 + p[IB] * dn2 * sv * pw
        if f > 0.0:
            a -= p[IKI] * f
            dm1 = d ** (p[IN1] - 1.0)
            dm2 = dm1 if same else d ** (p[IN2] - 1.0)
            ax -= p[IKI] * (p[IN1] * dm1 + p[IB] * p[IN2] * dm2 * sv * pw)
            kap = p[IKI] * p[IB] * dn2 / m
    return a / m, ax / m, av, kap
