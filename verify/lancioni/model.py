"""The frictional impact oscillator of Lancioni, Lenci & Galvanetto, eq. (1).

Coordinates q = (φ, y): the bar angle and the height of m₂; state y = (φ, y, φ̇, ẏ) in
every mode.  Eq. (1), M(q) q̈ = W λ − h (re-derived from the energies and virtual work):

    M = [[m₁l², m₁l sin φ], [m₁l sin φ, m₁ + m₂]],   W = [w_N w_T] = [[l sin φ, l cos φ], [1, 0]],
    h = (c_φφ̇ + k_φ(φ − φ₀) + m₁gl sin φ,  c_yẏ + k_y(y − y₀) + m₁lφ̇² cos φ + (m₁+m₂)g),

gap g_N = y − l cos φ (γ_N = ẏ + lφ̇ sin φ, ŵ_N = lφ̇² cos φ), relative tangential
velocity g_T = lφ̇ cos φ − v(t) (ŵ_T = −lφ̇² sin φ − v̇).  The regimes (free flight,
slip±, stick), transitions, Poisson impact law and Painlevé checks are the generic ones
of :mod:`landau.verify.lancioni.contact`; this module only supplies the mechanics.

Friction.  The paper's plain Coulomb friction (coefficient μ) is the default law,
:func:`landau.laws.velocity.coulomb`; any :class:`~landau.laws.velocity.VelocityFriction`
coefficient law F(g_T) can replace it: in slip λ_T = −F(g_T) λ_N at the current relative
velocity, in stick −F(0⁺)λ_N ≤ λ_T ≤ −F(0⁻)λ_N (the law's one-sided limits), and the
impulsive friction of an impact takes the limit of the sliding direction.

Belt.  The paper's constant belt speed is not printed; |v| = 1 m/s (the amplitude of the
sinusoidal belt v = sin(πt/2) of Fig. 6) is used, in the direction that has the Hopf
point: v = −1 (g_T > 0 on the slip equilibrium, *positive slip*; see
:mod:`landau.verify.lancioni.slip`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Mapping

import numpy as np
from numba import njit

from landau.errors import InputError
from landau.laws.velocity import V_SLIP, VelocityFriction, coulomb
from landau.verify.hybrid.contact import check_contact_coefficients
from landau.verify.lancioni.contact import ContactMechanics, ContactModel, Section
from landau.verify.lancioni.slip import PARAM_NAMES, SET1, SET2, check_friction, hopf_parameter, resolve


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
    """Eq. (1) with friction ``friction`` (default: Coulomb coefficient ``mu``, 0.4), restitution
    ``eN`` and belt ``belt``.

    With a law, ``mu`` becomes its static level F(0⁺) (give ``mu`` or a law, not two
    different values).
    """

    params: Mapping[str, float] = field(default_factory=lambda: dict(SET1))
    mu: float | None = None  # type: ignore[assignment]  # None: from the law; a float after __post_init__
    eN: float = 0.0
    belt: object = ConstantBelt()
    n: int = 2
    name: str = "lancioni"
    friction: VelocityFriction | None = None
    # derived in __post_init__: the static limits (μ₊, μ₋), the compiled branches, the law's
    # parameter values and the mechanical constants in the order of eq. (1)
    _static: tuple[float, float] = field(init=False, repr=False, compare=False)
    _branch: dict = field(init=False, repr=False, compare=False)
    _law_values: tuple = field(init=False, repr=False, compare=False)
    _c: tuple[float, ...] = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "params", resolve(self.params))
        law = self.friction
        if law is None:
            mu = 0.4 if self.mu is None else self.mu
            check_contact_coefficients(mu, self.eN)
            law = coulomb(float(mu))
        check_friction(law)
        vals = [float(law.defaults()[p.name]) if p.name in law.defaults() else None for p in law.parameters]
        missing = [p.name for p, x in zip(law.parameters, vals, strict=True) if x is None]
        if missing:
            raise InputError(f"friction law {law.name!r}: parameter(s) {', '.join(missing)} need a value")
        dep = any(V_SLIP in law.branch(s).free_symbols for s in (1, -1))
        if dep:
            lo, hi = law.limits_at_zero()
        else:  # constant branches (Coulomb): the limits are their values
            at = {p.symbol: x for p, x in zip(law.parameters, vals, strict=True)}
            lo, hi = (float(law.branch(s).xreplace(at)) for s in (-1, 1))
        if self.mu is not None and self.friction is not None and not np.isclose(float(self.mu), hi, rtol=1e-14,
                                                                                 atol=0.0):
            raise InputError(f"give the friction either as mu or as a law, not both (mu={self.mu!r}, law "
                             f"{law.name!r} has F(0+) = {hi!r})")
        object.__setattr__(self, "friction", law)
        object.__setattr__(self, "mu", hi)
        check_contact_coefficients(self.mu, self.eN)
        object.__setattr__(self, "velocity_dependent", dep)
        object.__setattr__(self, "_static", (hi, -lo))
        object.__setattr__(self, "_branch", {s: law.numeric(s) for s in (1, -1)} if dep else {})
        object.__setattr__(self, "_law_values", tuple(vals))
        p = self.params
        object.__setattr__(self, "_c", (p["m1"], p["m2"], p["l"], p["k_y"], p["k_phi"], p["c_y"], p["c_phi"],
                                         p["phi0"], p["y0"], p["g"]))
        object.__setattr__(self, "_cv", np.array(self._c, dtype=float))

    def __repr__(self) -> str:
        # with a velocity-dependent law, ``mu`` is only its static level F(0+): say so, rather than
        # print a bare ``mu=`` that reads like one of the law's parameters
        friction = (f"friction={self.friction!r}, static level F(0+)={self.mu!r}" if self.velocity_dependent
                    else f"mu={self.mu!r}")
        return (f"Lancioni(params={dict(self.params)!r}, {friction}, eN={self.eN!r}, belt={self.belt!r}, "
                f"n={self.n!r}, name={self.name!r})")

    def with_(self, **kw) -> "Lancioni":
        if "mu" in kw and "friction" not in kw:
            kw["friction"] = None  # a new Coulomb coefficient replaces the law
        elif "friction" in kw and "mu" not in kw:
            kw["mu"] = None
        return replace(self, **kw)

    def slip_mu(self, s: int, gT):
        """|F(g_T)| in slip s: λ_T = −s·slip_mu·λ_N = −F(g_T)·λ_N; a γ_T a rounding error on the wrong
        side of 0 (at the end of a slip phase) is taken as 0 on the slip side."""
        if not self.velocity_dependent:
            return self._static[0] if s > 0 else self._static[1]
        v = s * np.maximum(s * np.asarray(gT, float), 0.0)
        return s * self._branch[s](v, *self._law_values)

    def static_mu(self) -> tuple[float, float]:
        """(F(0⁺), −F(0⁻)): the stick cone −F(0⁺)λ_N ≤ λ_T ≤ −F(0⁻)λ_N."""
        return self._static

    def terms(self, t, q, qd):
        if isinstance(q, np.ndarray) and isinstance(qd, np.ndarray) and q.shape == qd.shape and q.ndim >= 1 \
                and q.dtype == float and qd.dtype == float:
            shape = q.shape[1:]
            m = math.prod(shape)
            Q, QD = np.ascontiguousarray(q).reshape(2, m), np.ascontiguousarray(qd).reshape(2, m)
            phi, y, w, yd = Q[0], Q[1], QD[0], QD[1]
        else:  # sequences or mixed shapes (vectorised over the broadcast of the sample axes)
            shape = np.broadcast_shapes(np.shape(q[0]), np.shape(q[1]), np.shape(qd[0]), np.shape(qd[1]))
            phi, y, w, yd = (np.ascontiguousarray(np.broadcast_to(np.asarray(x, dtype=float), shape)).reshape(-1)
                             for x in (q[0], q[1], qd[0], qd[1]))
        rate = np.asarray(self.belt.rate(t), dtype=float)
        if rate.ndim == 0:
            vdot = np.full(1, float(rate))
        else:
            vdot = np.ascontiguousarray(rate if rate.shape == shape else np.broadcast_to(rate, shape)).reshape(-1)
        a0, MiW, G, b = _terms(phi, y, w, yd, vdot, self._cv)
        return (a0.reshape((2,) + shape), MiW.reshape((2, 2) + shape), G.reshape((2, 2) + shape),
                b.reshape((2,) + shape))

    def mode_kernel(self, mode: str):
        """The compiled field of ``mode`` (:mod:`landau.verify.lancioni.kernels`), built on first use;
        None for a belt other than :class:`ConstantBelt` and :class:`SineBelt`."""
        from landau.verify.lancioni.kernels import mode_kernel_factory

        return mode_kernel_factory(self, mode)

    def guard_kernel(self, mode: str, sections=()):
        """The compiled guards of ``mode`` (:func:`landau.verify.lancioni.kernels.guard_kernel_factory`),
        built on first use; None for a belt other than :class:`ConstantBelt` and :class:`SineBelt`
        or a section without a symbolic form."""
        from landau.verify.lancioni.kernels import guard_kernel_factory

        return guard_kernel_factory(self, mode, sections)

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


@njit(cache=True)
def _terms(phi, y, w, yd, vdot, c):
    """(a₀, M⁻¹W, G, b) of eq. (1) at the samples (φ, y, φ̇, ẏ)[k] with belt acceleration v̇[k] (or v̇[0] for all)
    (:meth:`Lancioni.terms`, whose arithmetic this is, sample by sample)."""
    m1, m2, l, ky, kp, cy, cp, p0, y0, g = c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], c[9]
    m = phi.shape[0]
    one_rate = vdot.shape[0] == 1
    a0, MiW, G, b = np.empty((2, m)), np.empty((2, 2, m)), np.empty((2, 2, m)), np.empty((2, m))
    for k in range(m):
        sn, cs = np.sin(phi[k]), np.cos(phi[k])
        wk = w[k]
        det = m1 * l * l * (m2 + m1 * cs * cs)
        i11, i12, i22 = (m1 + m2) / det, -m1 * l * sn / det, m1 * l * l / det
        f1 = -(cp * wk + kp * (phi[k] - p0) + m1 * g * l * sn)
        f2 = -(cy * yd[k] + ky * (y[k] - y0) + m1 * l * wk * wk * cs + (m1 + m2) * g)
        a00, a01 = i11 * f1 + i12 * f2, i12 * f1 + i22 * f2
        nN1 = l * sn
        nT1 = l * cs
        MiN0, MiN1 = i11 * nN1 + i12 * 1.0, i12 * nN1 + i22 * 1.0
        MiT0, MiT1 = i11 * nT1, i12 * nT1
        GNN = nN1 * MiN0 + 1.0 * MiN1
        GNT = nN1 * MiT0 + 1.0 * MiT1
        a0[0, k], a0[1, k] = a00, a01
        MiW[0, 0, k], MiW[1, 0, k], MiW[0, 1, k], MiW[1, 1, k] = MiN0, MiN1, MiT0, MiT1
        G[0, 0, k], G[0, 1, k], G[1, 0, k], G[1, 1, k] = GNN, GNT, GNT, nT1 * MiT0
        b[0, k] = nN1 * a00 + 1.0 * a01 + l * cs * wk * wk
        b[1, k] = nT1 * a00 - l * sn * wk * wk - vdot[0 if one_rate else k]
    return a0, MiW, G, b


#: section guards: φ̇ maxima (φ̈ → 0 from above) and upward crossings of φ = 0
def _phidot_max(t, y, acc):
    return acc[0]


def _phi_zero_up(t, y, acc):
    return -y[0]


PHIDOT_MAX = Section("phidot-max", _phidot_max, symbolic=_phidot_max)
PHI_ZERO_UP = Section("phi=0 up", _phi_zero_up, symbolic=_phi_zero_up)


def build(mu: float | None = None, eN: float = 0.0, params: Mapping[str, float] | None = None, belt=None,
          sections=(PHIDOT_MAX,), stick_tol: float = 0.0, stick_tol_reset: str = "project", *,
          friction: VelocityFriction | None = None) -> ContactModel[Lancioni]:
    """The hybrid model of eq. (1) (set 1 by default, g = 10) at Coulomb coefficient μ, or with a
    velocity-dependent friction law.

    ``stick_tol`` > 0 switches on the numerical stick tolerance of
    :class:`landau.verify.lancioni.contact.ContactModel` (default 0: the exact model).

    Parameters
    ----------
    mu : float, optional
        Coulomb friction coefficient μ (default 0.4 when no ``friction`` law is given).
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
    friction : VelocityFriction, optional
        A friction-coefficient law F(g_T) of the relative sliding velocity g_T, with its
        parameter values as defaults (instead of ``mu``), e.g.
        ``VelocityFriction.from_strings("mine", "mu*(1 + alpha*exp(-v/v0))", params=...)``.

    Returns
    -------
    ContactModel
        A hybrid model for :func:`landau.verify.hybrid.simulate`.

    References
    ----------
    Lancioni, G., Lenci, S. & Galvanetto, U., the frictional impact oscillator (hopping of a
    windscreen wiper), eq. (1).
    """
    mech = Lancioni(params=dict(params or SET1), mu=None if mu is None else float(mu), eN=float(eN),
                    belt=belt or ConstantBelt(), friction=friction)
    return ContactModel(mech, sections=sections, stick_tol=float(stick_tol), stick_tol_reset=stick_tol_reset)


def at_parameter(value: float, params: Mapping[str, float] | None = None, friction: VelocityFriction | None = None,
                 parameter: str | None = None) -> tuple[dict[str, float], VelocityFriction]:
    """Mechanical parameters and friction law with the bifurcation parameter set to ``value``.

    Parameters
    ----------
    value : float
        Value of the bifurcation parameter: the Coulomb μ by default; with a law, its parameter
        ``parameter`` (default the first) or a mechanical parameter.
    params : mapping, optional
        Mechanical parameters (default: set 1).
    friction : VelocityFriction, optional
        Friction-coefficient law (default: Coulomb).
    parameter : str, optional
        The bifurcation parameter's name.

    Returns
    -------
    tuple
        (mechanical parameters, friction law) for :func:`build`.
    """
    p = resolve(params)
    if friction is None and parameter in (None, "mu"):
        check_contact_coefficients(value, 0.0)
        return p, coulomb(float(value))
    law = check_friction(friction if friction is not None else coulomb())
    par = hopf_parameter(friction, parameter)
    if par in PARAM_NAMES:
        return resolve({**p, par: value}), law
    return p, law.with_defaults(**{par: float(value)})


def build_at(value: float, eN: float = 0.0, params: Mapping[str, float] | None = None, belt=None, *,
             friction: VelocityFriction | None = None, parameter: str | None = None,
             **kw) -> ContactModel[Lancioni]:
    """:func:`build` with the bifurcation parameter at ``value`` (see :func:`at_parameter`).

    Parameters
    ----------
    value : float
        The Coulomb μ (default) or the value of ``parameter`` of the law ``friction``.
    eN, params, belt
        As for :func:`build`.
    friction : VelocityFriction, optional
        Friction-coefficient law (default: Coulomb).
    parameter : str, optional
        Its bifurcation parameter (default the first).
    **kw
        Further arguments of :func:`build` (sections, stick tolerance).

    Returns
    -------
    ContactModel
    """
    if friction is None and parameter in (None, "mu"):
        return build(value, eN, params, belt, **kw)
    p, law = at_parameter(value, params, friction, parameter)
    return build(None, eN, p, belt, friction=law, **kw)


def slip_state(mech: Lancioni, phi: float, phidot: float = 0.0) -> np.ndarray:
    """A state on the surface (g_N = 0, γ_N = 0) with angle φ and rate φ̇."""
    l = mech.params["l"]
    return np.array([phi, l * np.cos(phi), phidot, -l * np.sin(phi) * phidot])


__all__ = ["Lancioni", "at_parameter", "build_at", "check_friction", "ConstantBelt", "SineBelt", "build", "slip_state",
           "PHIDOT_MAX", "PHI_ZERO_UP",
           "SET1", "SET2"]
