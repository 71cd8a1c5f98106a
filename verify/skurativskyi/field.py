"""The vector field of eq. (1) of Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019), compiled
once for every friction law.

    m ẍ = m₀e ω² sin ωt − k x − F_R(ẋ) − F_I(x, ẋ)

The friction F_R reaches these functions as first-class functions (numba's documented
``types.FunctionType``): ``fr`` is the tuple ``(friction, friction_derivative,
subtract_friction, built_in, data_pointer)`` of
:attr:`landau.verify.skurativskyi.friction.CompiledFriction.pointers`: C callbacks of signature
``(v, p*) -> float`` and ``(a, v, p*) -> float`` that read the law's parameters from the packed
vector's data (:meth:`landau.verify.skurativskyi.model.Params.packed`), the built-in flag, and
the identity ``p* -> p*`` the loop uses once to hold that data pointer.
So the field, the SDIRK4 of :mod:`landau.verify.skurativskyi.sdirk` and the event-driven
loop of :mod:`landau.verify.skurativskyi.rk` are ordinary ``@njit(cache=True)`` functions,
compiled once per machine; a new law compiles only its three small callbacks.  A call
through the pointer costs ~15 ns more than the inlined law, so the paper's law is compiled in
as well (``built_in``, below); the arithmetic is that of eq. (1) written by hand, in the same
order, so the results do not depend on how the law is reached.

``p`` is the packed vector (an array) or, in the compiled loop, its data pointer
(``CPointer(float64)``: indexing reads the same numbers, and a pointer carries no reference
count into the calls of the inner loop).  All are ordinary compiled calls.  With the tangent
vector ``rhs`` makes one call of :func:`field_values`, which computes the contact force's powers
once for the field and its Jacobian (two calls, ``accel`` and ``accel_grad``, computed each power
twice): measured at ω = 16 the 4-D runs 10–15 % faster, every step bit for bit the same.
Inlining ``rhs`` into the steps at numba's IR level (with its calls taking scalars only, so no
array reference counts) measured another ~5–10 % on the 2-D runs but took the loop's first
build (part of a truly cold first run) from ~12 to ~17 CPU-s.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, types
from numba.extending import overload

from landau.verify.skurativskyi.model import IB, IK, IKI, ILAW, IM, IM0E, IN1, IN2, IN3, IOM, IVF, IXI

#: positions of the law's callbacks in the tuple ``fr``, and of the flag that selects the
#: built-in regularised Coulomb law
FRICTION, FRICTION_DERIVATIVE, SUBTRACT_FRICTION, BUILT_IN, DATA_POINTER = 0, 1, 2, 3, 4


def data(p):
    """The data pointer of the packed vector ``p`` for the law's callbacks: ``p.ctypes`` for an
    array (numba converts it at the call), ``p`` itself when it is already a pointer (in the
    compiled loop, which reads ``p`` through its pointer: see ``rk.integrate_mixed``).

    Called from Python (the field runs as plain Python under ``NUMBA_DISABLE_JIT=1``, and the
    law's callbacks are then its generated Python functions, which index an array) it returns
    ``p`` itself; compiled code uses the overload below."""
    return p


@overload(data, inline="always")
def _data(p):
    if isinstance(p, types.Array):
        return lambda p: p.ctypes
    return lambda p: p


def hold(p_arr, fr):
    """The packed vector as the compiled loop reads it: its data pointer, through the identity
    callback ``fr[DATA_POINTER]`` (no array, so no reference counts in the inner loop; the
    caller owns ``p_arr`` for the whole call).  Called from Python (``NUMBA_DISABLE_JIT=1``) it
    returns the array itself; compiled code uses the overload below."""
    return p_arr


@overload(hold, inline="always")
def _hold(p_arr, fr):
    return lambda p_arr, fr: fr[DATA_POINTER](p_arr.ctypes)


# The paper's law F_R = c ẋ + T ẋ/sqrt(ẋ² + ε²) (parameters c, T, ε from p[ILAW] on) is also
# compiled in: an indirect call cannot be inlined, and with it a run of eq. (1) measured
# 20–45 % slower than the specialised loop.  These are the expressions the generator of
# landau.verify.skurativskyi.friction prints for that law, operation for operation, so the
# two paths agree to the bit (checked in the tests); ``fr[BUILT_IN]`` is set only when the
# law is that law (same expressions and parameter order, see friction.is_built_in).
@njit(cache=True, inline="always")
def _friction(v, p, fr):
    if fr[BUILT_IN]:
        q0, q1, q2 = p[ILAW], p[ILAW + 1], p[ILAW + 2]
        return q0*v + q1*v/math.sqrt((q2*q2) + (v*v))
    return fr[FRICTION](v, data(p))


@njit(cache=True, inline="always")
def _friction_derivative(v, p, fr):
    if fr[BUILT_IN]:
        q0, q1, q2 = p[ILAW], p[ILAW + 1], p[ILAW + 2]
        return q0 + q1*q2*q2/(((q2*q2) + (v*v))*math.sqrt((q2*q2) + (v*v)))
    return fr[FRICTION_DERIVATIVE](v, data(p))


@njit(cache=True, inline="always")
def _subtract_friction(a, v, p, fr):
    if fr[BUILT_IN]:
        q0, q1, q2 = p[ILAW], p[ILAW + 1], p[ILAW + 2]
        return a - (q0*v) - (q1*v/math.sqrt((q2*q2) + (v*v)))
    return fr[SUBTRACT_FRICTION](a, v, data(p))


@njit(cache=True)
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


@njit(cache=True)
def accel(t, x, v, p, fr):
    """ẍ from eq. (1); ``fr`` the law's callbacks (module docstring)."""
    om = p[IOM]
    return (p[IM0E] * om * om * np.sin(om * t) - p[IK] * x - _friction(v, p, fr)
            - contact_force(x, v, p)) / p[IM]


@njit(cache=True)
def accel_grad(t, x, v, p, fr):
    """(∂ẍ/∂x, ∂ẍ/∂ẋ).  The |ẋ|^{n₃−1} slope of the Hertz damping is unbounded at ẋ = 0; it
    is evaluated with |ẋ| floored at p[IVF] (in the variational equation the tangent crosses
    ẋ = 0 in an integrable way: the slope is O(|ẋ|^{−0.81}); the floor keeps it finite)."""
    dfr = _friction_derivative(v, p, fr)
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


@njit(cache=True)
def field_values(t, x, v, dx, dv, tangent, p, fr):
    """The field at (x, ẋ) and, if ``tangent``, the variational equation at (δx, δẋ), in one call
    of scalars: returns (ẋ, ẍ, δẋ, δẍ) (the last two 0 without ``tangent``).

    The same operations as :func:`accel` and :func:`accel_grad` (bit for bit), with the powers of
    the contact force (x − x_I)^{n₁}, (x − x_I)^{n₂} and |ẋ|^{n₃} computed once for both (each is
    a power routine, the costliest operations of the field) and one call instead of two."""
    om = p[IOM]
    d = x - p[IXI]
    fc = 0.0
    cx = 0.0
    cv = 0.0
    active = False
    if d > 0.0:
        sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
        av = abs(v)
        pw = av ** p[IN3]
        same = p[IN2] == p[IN1]
        dn1 = d ** p[IN1]
        dn2 = dn1 if same else d ** p[IN2]
        f = dn1 + p[IB] * dn2 * sv * pw
        if f > 0.0:
            fc = p[IKI] * f
            if tangent:
                active = True
                dm1 = d ** (p[IN1] - 1.0)
                dm2 = dm1 if same else d ** (p[IN2] - 1.0)
                cx = p[IKI] * (p[IN1] * dm1 + p[IB] * p[IN2] * dm2 * sv * pw)
                avf = max(av, p[IVF])
                cv = p[IKI] * p[IB] * dn2 * p[IN3] * avf ** (p[IN3] - 1.0)
    a = (p[IM0E] * om * om * np.sin(om * t) - p[IK] * x - _friction(v, p, fr) - fc) / p[IM]
    if not tangent:
        return v, a, 0.0, 0.0
    gx = -p[IK]
    gv = -_friction_derivative(v, p, fr)
    if active:
        gx -= cx
        gv -= cv
    return v, a, dv, gx / p[IM] * dx + gv / p[IM] * dv


@njit(cache=True)
def rhs(t, y, p, out, fr):
    """The field the compiled integrators use: (x, ẋ) if len(y) == 2, with the variational
    equation for one tangent vector (δx, δẋ) if len(y) == 4 (one call of :func:`field_values`)."""
    if y.shape[0] == 4:
        f0, f1, f2, f3 = field_values(t, y[0], y[1], y[2], y[3], True, p, fr)
        out[0] = f0
        out[1] = f1
        out[2] = f2
        out[3] = f3
    else:
        out[0] = y[1]
        out[1] = accel(t, y[0], y[1], p, fr)


@njit(cache=True)
def accel_partials(t, x, v, p, fr):
    """ẍ and its partials split for the stiff stepper (:mod:`landau.verify.skurativskyi.sdirk`):
    returns (a, ∂a/∂x, ∂a/∂ẋ without the Hertz damping, κ) with κ = k_I b (x − x_I)^{n₂}/m
    when the contact force is active (else 0), so that the Hertz damping contributes
    −κ sgn(ẋ)|ẋ|^{n₃} to ẍ — exactly linear in w = sgn(ẋ)|ẋ|^{n₃}.  Nothing is floored here."""
    om = p[IOM]
    m = p[IM]
    # F_R's terms subtracted one by one (for the paper's law: ... - c v - T v/sqrt(v² + ε²),
    # the rounding of eq. (1) written by hand, on which the stiff path's bifurcations depend)
    a = _subtract_friction(p[IM0E] * om * om * np.sin(om * t) - p[IK] * x, v, p, fr)
    av = -_friction_derivative(v, p, fr) / m
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
