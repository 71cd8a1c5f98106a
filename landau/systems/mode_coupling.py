"""Friction-induced flutter: an N-DOF structure pressed onto a sliding surface (the mode-coupling model).

The structure M ẍ + C ẋ + K x = f_c(x, ẋ) touches a surface sliding at v₀ > 0 through one contact,
with coordinate ``normal`` the penetration y into the surface and coordinate ``tangential`` the
displacement x along the sliding direction:

    f_c[normal] = P − N(y),    f_c[tangential] = μ(v_rel) N(y),    v_rel = v₀ − ẋ_t,

N(y) = k_H y (``linear``), k_H y + k_NL y³ (``cubic``) or k_H y^{3/2} (``hertz``) while the contact is
closed (N > 0); μ is a constant Coulomb coefficient or any velocity law of the library (a friction
*coefficient* of the sliding velocity v).  The built-in 2-DOF model is that of Hoffmann, Fischer,
Allgaier & Gaul (2002): a mass m held by springs k₁, k₂ at angles α₁, α₂,

    k₁₁ = k₁cos²α₁ + k₂cos²α₂,  k₁₂ = k₁ sinα₁ cosα₁ − k₂ sinα₂ cosα₂,  k₂₂ = k₁sin²α₁ + k₂sin²α₂,

with diagonal damping c₁, c₂ (Hoffmann & Gaul 2003).  Its linearisation about steady sliding has the
non-symmetric stiffness K + N'(y*)(e_n − μ e_t)e_nᵀ: two modes merge into a flutter above μ_c.

:class:`ModeCoupling` holds the structure; :meth:`ModeCoupling.equilibrium` is the steady sliding state
(refused, :class:`ContactOpensError`, where the contact opens there);
:meth:`ModeCoupling.sliding_system` is the smooth :class:`~landau.systems.system.DynamicalSystem` of the
closed, sliding contact, for :func:`landau.hopf_normal_form` (Λ in landau's convention).

References
----------
Hoffmann, N., Fischer, M., Allgaier, R. & Gaul, L. (2002), A minimal model for studying properties of the
mode-coupling type instability in friction induced oscillations, Mech. Res. Commun. 29, 197–205.
Hoffmann, N. & Gaul, L. (2003), Effects of damping on mode-coupling instability in friction induced
oscillations, Z. Angew. Math. Mech. 83, 524–534.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, Mapping

import numpy as np
import sympy as sp

from landau.errors import InputError, NoSteadySlidingError
from landau.systems.system import DynamicalSystem

#: the contact laws N(y) of the penetration y > 0
CONTACT_LAWS = ("linear", "cubic", "hertz")
#: the parameters of the 2-DOF model of Hoffmann et al. (2002), in the order of the command line
HOFFMANN_NAMES = ("m", "k1", "k2", "alpha1", "alpha2", "kH", "kNL", "P", "c1", "c2", "mu", "v0")
#: illustrative defaults of the 2-DOF model (SI units, angles in degrees): a flutter near mu = 0.58
HOFFMANN_DEFAULTS: dict[str, float] = {"m": 1.0, "k1": 1.0e4, "k2": 1.0e4, "alpha1": 30.0, "alpha2": 150.0,
                                       "kH": 2.0e4, "kNL": 5.0e8, "P": 50.0, "c1": 2.0, "c2": 0.5, "mu": 0.3,
                                       "v0": 0.1}
#: the parameters of the contact and the friction (every member of the family has them)
CONTACT_NAMES = ("kH", "kNL", "P", "v0")


class ContactOpensError(NoSteadySlidingError):
    """The steady sliding state has N ≤ 0: the contact opens at equilibrium (no sliding contact to analyse)."""


@dataclass(frozen=True)
class ContactLaw:
    """The normal contact force N(y) of the penetration y (``linear``, ``cubic`` or ``hertz``).

    Parameters
    ----------
    kind : {"linear", "cubic", "hertz"}
        N = k_H y, N = k_H y + k_NL y³ or N = k_H y^{3/2} (y > 0).
    kH : float
        Contact stiffness k_H (N/m; N/m^{3/2} for Hertz), > 0.
    kNL : float
        Cubic stiffness k_NL (N/m³; ``cubic`` only): > 0 hardening, < 0 softening.
    """

    kind: str = "linear"
    kH: float = 1.0
    kNL: float = 0.0

    def __post_init__(self) -> None:
        if self.kind not in CONTACT_LAWS:
            raise InputError(f"contact law must be one of {', '.join(CONTACT_LAWS)}, got {self.kind!r}")
        if not (math.isfinite(self.kH) and self.kH > 0):
            raise InputError(f"contact stiffness kH must be > 0 and finite, got {self.kH!r}")
        if not math.isfinite(self.kNL):
            raise InputError(f"cubic contact stiffness kNL must be finite, got {self.kNL!r}")

    def symbolic(self, y: sp.Expr, kH: sp.Expr, kNL: sp.Expr) -> sp.Expr:
        """N(y) as a sympy expression."""
        if self.kind == "linear":
            return kH * y
        if self.kind == "cubic":
            return kH * y + kNL * y**3
        return kH * y ** sp.Rational(3, 2)

    def force(self, y: float) -> float:
        """N(y) (the closed-contact branch, y > 0 for Hertz)."""
        if self.kind == "linear":
            return self.kH * y
        if self.kind == "cubic":
            return self.kH * y + self.kNL * y**3
        return self.kH * max(y, 0.0) ** 1.5

    def stiffness(self, y: float) -> float:
        """N'(y)."""
        if self.kind == "linear":
            return self.kH
        if self.kind == "cubic":
            return self.kH + 3.0 * self.kNL * y**2
        return 1.5 * self.kH * math.sqrt(max(y, 0.0))


def _matrix(value: Any, what: str, n: int | None = None) -> np.ndarray:
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a square matrix of numbers, got {value!r}") from None
    if a.ndim != 2 or a.shape[0] != a.shape[1] or a.shape[0] < 2:
        raise InputError(f"{what} must be a square matrix of size 2 or more, got shape {a.shape}")
    if n is not None and a.shape[0] != n:
        raise InputError(f"{what} must be {n}x{n} like the mass matrix, got {a.shape[0]}x{a.shape[1]}")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{what} has an entry that is not finite")
    a.setflags(write=False)
    return a


def _law_of(friction: Any) -> Any:
    """A friction coefficient: a number (Coulomb μ) or a velocity law (a string in v, or a VelocityFriction)."""
    from landau.laws.velocity import VelocityFriction

    if isinstance(friction, str):
        return VelocityFriction.from_strings("user-friction", friction, None, {})
    if isinstance(friction, VelocityFriction):
        if friction.quantity != "coefficient":
            raise InputError(f"friction law {friction.name!r} gives a force: the mode-coupling model takes a "
                             "friction coefficient (quantity='coefficient')")
        return friction
    if isinstance(friction, bool):
        raise InputError(f"friction must be a number (Coulomb mu) or a velocity law, got {friction!r}")
    try:
        mu = float(friction)
    except (TypeError, ValueError):
        raise InputError(f"friction must be a number (Coulomb mu) or a velocity law, got {friction!r}") from None
    if not (math.isfinite(mu) and mu >= 0):
        raise InputError(f"the friction coefficient mu must be >= 0 and finite, got {friction!r}")
    return mu


@dataclass(frozen=True, eq=False)
class ModeCoupling:
    """An N-DOF structure in sliding contact (module docstring).

    Parameters
    ----------
    M, C, K : array_like
        Mass (invertible), damping and stiffness matrices of the structure alone (n×n, n ≥ 2).
    normal, tangential : int
        Index of the normal coordinate (the penetration y, positive into the surface) and of the
        tangential coordinate (along the sliding direction) at the contact.
    preload : float
        The preload P pressing the normal coordinate onto the surface (N).
    v0 : float
        Sliding speed of the surface (m/s), > 0.
    contact : ContactLaw
        The normal contact law N(y).
    friction : float or VelocityFriction or str
        The friction coefficient: a constant Coulomb μ, or a velocity law of the sliding velocity v
        (a :class:`~landau.laws.velocity.VelocityFriction` coefficient, or a string in v).
    params : mapping, optional
        The parameters of :meth:`hoffmann2002` where the structure is that model (then every one of
        them can be the bifurcation parameter of :meth:`sliding_system`); None for matrices.
    """

    M: Any
    C: Any
    K: Any
    normal: int
    tangential: int
    preload: float
    v0: float
    contact: ContactLaw = field(default_factory=ContactLaw)
    friction: Any = 0.3
    params: Mapping[str, float] | None = None

    def __post_init__(self) -> None:
        M = _matrix(self.M, "the mass matrix M")
        n = M.shape[0]
        object.__setattr__(self, "M", M)
        object.__setattr__(self, "C", _matrix(self.C, "the damping matrix C", n))
        object.__setattr__(self, "K", _matrix(self.K, "the stiffness matrix K", n))
        if abs(np.linalg.det(M)) <= 1e-300 or np.linalg.cond(M) > 1e12:
            raise InputError("the mass matrix M must be invertible")
        for what in ("normal", "tangential"):
            idx = getattr(self, what)
            if isinstance(idx, bool) or not isinstance(idx, (int, np.integer)) or not 0 <= idx < n:
                raise InputError(f"the {what} coordinate must be an index 0 to {n - 1}, got {idx!r}")
        if self.normal == self.tangential:
            raise InputError(f"the normal and the tangential coordinate must differ (both {self.normal})")
        if not isinstance(self.contact, ContactLaw):
            raise InputError(f"contact must be a ContactLaw, got {self.contact!r}")
        for what in ("preload", "v0"):
            try:
                x = float(getattr(self, what))
            except (TypeError, ValueError):
                raise InputError(f"{what} must be a number, got {getattr(self, what)!r}") from None
            if not math.isfinite(x):
                raise InputError(f"{what} must be finite, got {x!r}")
            object.__setattr__(self, what, x)
        if not self.v0 > 0:
            raise InputError(f"the sliding speed v0 must be > 0 (the surface slides past the contact), got {self.v0!r}")
        object.__setattr__(self, "friction", _law_of(self.friction))

    # --- construction ------------------------------------------------------------------------
    @classmethod
    def hoffmann2002(cls, *, contact: str = "cubic", friction: Any = None, **params: float) -> "ModeCoupling":
        """The 2-DOF model of Hoffmann et al. (2002) with diagonal damping (Hoffmann & Gaul 2003).

        Parameters
        ----------
        contact : {"linear", "cubic", "hertz"}
            The contact law (``kNL`` is used by ``cubic`` only).
        friction : VelocityFriction or str, optional
            A velocity law of the friction coefficient instead of the constant ``mu``.
        **params : float
            Any of :data:`HOFFMANN_NAMES` (SI units, the angles ``alpha1``, ``alpha2`` in degrees);
            the others take the illustrative :data:`HOFFMANN_DEFAULTS`.

        Returns
        -------
        ModeCoupling
            Coordinates (x, y): x tangential (index 0), y the penetration (index 1).
        """
        unknown = sorted(set(params) - set(HOFFMANN_NAMES))
        if unknown:
            raise InputError(f"hoffmann2002: unknown parameter(s) {', '.join(unknown)} "
                             f"(known: {', '.join(HOFFMANN_NAMES)})")
        p = {**HOFFMANN_DEFAULTS, **{k: float(v) for k, v in params.items()}}
        k11, k12, k22 = hoffmann_stiffness(p["k1"], p["k2"], p["alpha1"], p["alpha2"])
        M, C, K = np.diag([p["m"], p["m"]]), np.diag([p["c1"], p["c2"]]), np.array([[k11, k12], [k12, k22]])
        return cls(M, C, K, 1, 0, p["P"], p["v0"], ContactLaw(contact, p["kH"], p["kNL"]),
                   p["mu"] if friction is None else friction, params=p)

    @property
    def n(self) -> int:
        """The number of degrees of freedom."""
        return int(self.M.shape[0])

    # --- parameters --------------------------------------------------------------------------
    def parameter_values(self) -> dict[str, float]:
        """Every parameter a :meth:`sliding_system` can take as its Hopf parameter, with its value."""
        out = dict(self.params) if self.params is not None else {}
        out.update({"kH": self.contact.kH, "kNL": self.contact.kNL, "P": self.preload, "v0": self.v0})
        law = self.friction
        if isinstance(law, float):
            out["mu"] = law
        else:
            out.pop("mu", None)
            out.update({k: float(v) for k, v in law.defaults().items()})
        if self.params is None:
            out["c_scale"] = 1.0
        return out

    def with_value(self, name: str, value: float) -> "ModeCoupling":
        """The same system with the parameter ``name`` set to ``value`` (a parameter of
        :meth:`parameter_values`; ``c_scale`` multiplies the damping matrix of a matrix family)."""
        known = self.parameter_values()
        if name not in known:
            raise InputError(f"mode-coupling: unknown parameter {name!r} (known: {', '.join(sorted(known))})")
        value = float(value)
        law = None if isinstance(self.friction, float) else self.friction
        if law is not None and name in {p.name for p in law.parameters}:
            return replace(self, friction=law.with_defaults(**{name: value}))
        if self.params is not None and name in HOFFMANN_NAMES:
            if name in ("m", "k1", "k2", "alpha1", "alpha2", "c1", "c2"):   # the structure's matrices change
                return ModeCoupling.hoffmann2002(contact=self.contact.kind, friction=law,
                                                 **{**self.params, name: value})
            return replace(self, params={**self.params, name: value}).with_value_of_contact(name, value)
        return self.with_value_of_contact(name, value)

    def with_value_of_contact(self, name: str, value: float) -> "ModeCoupling":
        """:meth:`with_value` for ``c_scale`` and the contact's and friction's parameters."""
        if name == "c_scale":
            return replace(self, C=self.C * value)
        if name == "kH":
            return replace(self, contact=replace(self.contact, kH=value))
        if name == "kNL":
            return replace(self, contact=replace(self.contact, kNL=value))
        if name == "P":
            return replace(self, preload=value)
        if name == "v0":
            return replace(self, v0=value)
        return replace(self, friction=value)   # the constant Coulomb mu

    # --- steady sliding ----------------------------------------------------------------------
    def friction_at(self, v_rel: float) -> tuple[float, float]:
        """(μ(v_rel), dμ/dv at v_rel)."""
        law = self.friction
        if isinstance(law, float):
            return law, 0.0
        mu = float(law.value(v_rel))
        slope = float(law.slope(v_rel))
        if not (math.isfinite(mu) and math.isfinite(slope)):
            raise InputError(f"friction law {law.name!r} is not finite at the sliding speed v0 = {v_rel!r}")
        return mu, slope

    def equilibrium(self) -> np.ndarray:
        """The steady sliding displacements x* (ẋ = 0, v_rel = v₀): K x* + N(y*)(e_n − μ(v₀) e_t) = P e_n.

        Raises
        ------
        ContactOpensError
            Where N(y*) ≤ 0 (the contact opens at equilibrium).
        NoSteadySlidingError
            Where Newton's method finds no closed-contact equilibrium.
        """
        n, t, N = self.normal, self.tangential, self.contact
        mu0, _ = self.friction_at(self.v0)
        d = np.zeros(self.n)
        d[n], d[t] = 1.0, -mu0
        e_n = np.zeros(self.n)
        e_n[n] = 1.0
        # linear contact: (K + k_H d e_nᵀ) x = P e_n, the linear-contact equilibrium (Newton's start otherwise)
        A = self.K + N.kH * np.outer(d, e_n)
        try:
            x = np.linalg.solve(A, self.preload * e_n)
        except np.linalg.LinAlgError:
            raise NoSteadySlidingError("mode-coupling: the stiffness with the contact is singular at mu = "
                                       f"{mu0:g}: no steady sliding state") from None
        if N.kind != "linear":
            x = self._newton(x, d, e_n)
        y = float(x[n])
        force = N.force(y)
        if not (y > 0 and force > 0):
            raise ContactOpensError(f"mode-coupling: the contact opens at the steady sliding state (penetration "
                                    f"y* = {y:.6g} m, N = {force:.6g} N): press it on with a preload P > 0 "
                                    "(or a friction mu that does not lift it)")
        return x

    def _newton(self, x: np.ndarray, d: np.ndarray, e_n: np.ndarray) -> np.ndarray:
        n, N = self.normal, self.contact
        if not x[n] > 0:
            raise ContactOpensError(f"mode-coupling: the contact opens at the steady sliding state (linear-contact "
                                    f"penetration {x[n]:.6g} m <= 0)")
        for _ in range(60):
            y = float(x[n])
            F = self.K @ x + N.force(y) * d - self.preload * e_n
            # Newton step: (K + N'(y) d e_nᵀ) dx = −F
            J = self.K + N.stiffness(y) * np.outer(d, e_n)
            dx = np.linalg.solve(J, -F)
            # keep the penetration positive (Hertz: y^{3/2}) by halving a step that would open the contact
            step = 1.0
            while x[n] + step * dx[n] <= 0 and step > 1e-12:
                step *= 0.5
            x = x + step * dx
            if np.max(np.abs(dx)) <= 1e-14 * (1 + np.max(np.abs(x))):
                return x
        raise NoSteadySlidingError(f"mode-coupling: no closed-contact steady sliding state found with the {N.kind} "
                                   "contact (Newton's method did not converge)")

    def linearised(self, x: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(M, C_eff, K_eff) of the sliding motion about the equilibrium ``x`` (default :meth:`equilibrium`):
        K_eff = K + N'(y*)(e_n − μ e_t)e_nᵀ, C_eff = C + μ'(v₀) N(y*) e_t e_tᵀ."""
        x = self.equilibrium() if x is None else x
        n, t = self.normal, self.tangential
        mu0, slope = self.friction_at(self.v0)
        y = float(x[n])
        K = np.array(self.K, dtype=float)
        kN = self.contact.stiffness(y)
        K[n, n] += kN
        K[t, n] -= mu0 * kN
        C = np.array(self.C, dtype=float)
        C[t, t] += slope * self.contact.force(y)
        return np.array(self.M), C, K

    def first_order(self, x: np.ndarray | None = None) -> np.ndarray:
        """The 2n×2n matrix A of ż = A z, z = (x − x*, ẋ)."""
        M, C, K = self.linearised(x)
        n = self.n
        # A = [[0, I], [−M⁻¹K, −M⁻¹C]]: one solve of M [X | Y] = [K | C]
        MK = np.linalg.solve(M, np.hstack([K, C]))
        A = np.zeros((2 * n, 2 * n))
        A[:n, n:] = np.eye(n)
        A[n:, :n] = -MK[:, :n]
        A[n:, n:] = -MK[:, n:]
        return A

    def undamped(self) -> bool:
        """True where the linearisation has no damping at all (C = 0 and μ'(v₀) = 0): its eigenvalues then
        come in quartets ±λ, ±λ̄ and the flutter threshold is a collision of two imaginary pairs."""
        _, slope = self.friction_at(self.v0)
        return bool(np.all(self.C == 0) and slope == 0)

    # --- the smooth system ---------------------------------------------------------------------
    def state_names(self) -> tuple[str, ...]:
        """The names of the states: positions then velocities ((x, y, xdot, ydot) for the 2-DOF model)."""
        if self.n == 2 and self.tangential == 0 and self.normal == 1:
            pos = ["x", "y"]
        else:
            pos = [f"q{i + 1}" for i in range(self.n)]
        return (*pos, *(f"{s}dot" for s in pos))

    def sliding_system(self, parameter: str = "mu") -> DynamicalSystem:
        """The smooth system of the closed, sliding contact, with ``parameter`` as its Hopf parameter.

        States (x, ẋ) (positions, then velocities); the equilibrium is a numeric starting guess
        (the steady sliding state at the present values), which the engine's Newton method follows in
        the parameter.  The tangential position is the normalised component (C is its amplitude).
        """
        values = self.parameter_values()
        if parameter not in values:
            raise InputError(f"mode-coupling: unknown bifurcation parameter {parameter!r} "
                             f"(known: {', '.join(sorted(values))})")
        sym = _symbols(values)
        n, t, nn = self.n, self.tangential, self.normal
        if self.params is not None:
            Ms, Cs, Ks = _hoffmann_matrices(sym)
        else:
            Ms, Cs, Ks = (sp.Matrix(np.asarray(X).tolist()) for X in (self.M, self.C, self.K))
            Cs = Cs * sym["c_scale"]
        names = self.state_names()
        states = tuple(sp.Symbol(s, real=True) for s in names)
        q, v = sp.Matrix(states[:n]), sp.Matrix(states[n:])
        Nf = self.contact.symbolic(q[nn], sym["kH"], sym["kNL"])
        vrel = sym["v0"] - v[t]
        if isinstance(self.friction, float):
            mu: sp.Expr = sym["mu"]
        else:
            law = self.friction
            mu = law.branch(1).xreplace({law.v: vrel, **{p.symbol: sym[p.name] for p in law.parameters}})
        fc = sp.zeros(n, 1)
        fc[nn] += sym["P"] - Nf
        fc[t] += mu * Nf
        force = fc - Cs * v - Ks * q
        diagonal = all(Ms[i, j] == 0 for i in range(n) for j in range(n) if i != j)
        if diagonal:
            mass = (*([sp.Integer(1)] * n), *(Ms[i, i] for i in range(n)))
            acc = list(force)
        else:   # a full numeric M: the velocities' rows are multiplied by M⁻¹ (E = I)
            mass = tuple([sp.Integer(1)] * (2 * n))
            acc = list(sp.Matrix(np.linalg.inv(np.asarray(self.M)).tolist()) * force)
        x0 = self.equilibrium()
        eq = (*(float(a) for a in x0), *([0.0] * n))
        defaults = {k: float(val) for k, val in values.items() if k != parameter}
        return DynamicalSystem("mode-coupling", states, (*v, *acc), mass, sym[parameter], eq, defaults=defaults,
                               normalise=t, description="an N-DOF structure in sliding frictional contact")


def _symbols(names) -> dict[str, sp.Symbol]:
    return {k: sp.Symbol(k, real=True) for k in names}


def _hoffmann_matrices(s: Mapping[str, sp.Symbol]) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
    """M, C, K of Hoffmann et al. (2002) in the symbols ``s`` (the angles in degrees)."""
    a1, a2 = s["alpha1"] * sp.pi / 180, s["alpha2"] * sp.pi / 180
    k1, k2 = s["k1"], s["k2"]
    k11 = k1 * sp.cos(a1) ** 2 + k2 * sp.cos(a2) ** 2
    k12 = k1 * sp.sin(a1) * sp.cos(a1) - k2 * sp.sin(a2) * sp.cos(a2)
    k22 = k1 * sp.sin(a1) ** 2 + k2 * sp.sin(a2) ** 2
    return (sp.diag(s["m"], s["m"]), sp.diag(s["c1"], s["c2"]), sp.Matrix([[k11, k12], [k12, k22]]))


def hoffmann_stiffness(k1: float, k2: float, alpha1: float, alpha2: float) -> tuple[float, float, float]:
    """(k₁₁, k₁₂, k₂₂) of Hoffmann et al. (2002) (angles in degrees)."""
    a1, a2 = math.radians(alpha1), math.radians(alpha2)
    return (k1 * math.cos(a1) ** 2 + k2 * math.cos(a2) ** 2,
            k1 * math.sin(a1) * math.cos(a1) - k2 * math.sin(a2) * math.cos(a2),
            k1 * math.sin(a1) ** 2 + k2 * math.sin(a2) ** 2)


__all__ = ["CONTACT_LAWS", "HOFFMANN_DEFAULTS", "HOFFMANN_NAMES", "ContactLaw", "ContactOpensError", "ModeCoupling",
           "hoffmann_stiffness"]
