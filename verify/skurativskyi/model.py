"""The forced impacting oscillator of Skurativskyi et al. (2019), eq. (1).

    m ẍ + k x + F_R(ẋ) + F_I(x, ẋ) = m₀e ω² sin ωt,
    F_R = c ẋ + T ẋ/sqrt(ẋ² + ε²)          (the default law: landau.laws.velocity.regularised_coulomb)
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

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from landau.errors import InputError
from landau.laws.velocity import VelocityFriction, regularised_coulomb

SOURCE = "Skurativskyi, Kudra, Witkowski, Awrejcewicz 2019, Nonlinear Dyn. 98:1795-1806"

# indices into the packed parameter vector used by the compiled kernels; the friction law's
# parameters follow from ILAW on (then F(0), F'(0)), see :mod:`landau.verify.skurativskyi.friction`
IM, IM0E, IVF, IN1, IN2, IN3, IK, IKI, IB, IXI, IOM = range(11)
ILAW = 11

#: |ẋ| [m/s] at which the unbounded slope |ẋ|^{n₃−1} of the Hertz damping is frozen in the
#: variational equation (the ε = 1e-6 m/s of the paper's law; with the paper's law its own ε
#: is used, see :attr:`Params.velocity_floor`)
V_FLOOR = 1e-6

#: the mechanical parameters of eq. (1) (the friction's live in its law)
MECHANICAL = ("m", "m0e", "n1", "n2", "n3", "k", "kI", "b", "xI", "omega")



@dataclass(frozen=True, init=False)
class Params:
    """Parameters of eq. (1); defaults are the identified set of Sec. 2 (SI units).

    The friction F_R(ẋ) is a :class:`~landau.laws.velocity.VelocityFriction` (``friction``;
    default the paper's regularised Coulomb law c ẋ + T ẋ/sqrt(ẋ² + ε²),
    :func:`~landau.laws.velocity.regularised_coulomb`); its parameters live in the law.  For
    convenience ``Params(c=..., T=..., eps=...)``, ``with_(T=...)`` and ``p.c``, ``p.T``,
    ``p.eps`` set and read the law's parameters of those names (any law parameter works in
    ``with_``).

    Parameters
    ----------
    m : float
        Cart mass [kg] (8.735).
    m0e : float
        Unbalance [kg m] (0.01805).
    n1, n2, n3 : float
        Hertz exponents (1.5, 1.5, 0.18667).
    k : float
        Spring stiffness [N/m] (1418.9).
    kI : float
        Contact stiffness [N/m^{3/2}] (2.3983e8).
    b : float
        Hertz damping coefficient [(s/m)^{n₃}] (0.8485).
    xI : float
        Obstacle position [m] (−2.086e-3).
    omega : float
        Forcing frequency [rad/s] (16).
    friction : VelocityFriction, optional
        F_R(ẋ) [N], continuous through ẋ = 0.
    c, T, eps : float, optional
        Values of the law's parameters of these names.

    References
    ----------
    Skurativskyi, S., Kudra, G., Witkowski, K. & Awrejcewicz, J. (2019), Nonlinear Dyn. 98,
    1795–1806, eq. (1) and Sec. 2.
    """

    m: float
    m0e: float
    n1: float
    n2: float
    n3: float
    k: float
    kI: float
    b: float
    xI: float
    omega: float
    friction: VelocityFriction

    def __init__(self, m: float = 8.735, m0e: float = 0.01805, eps: float | None = None, n1: float = 1.5,
                 n2: float = 1.5, n3: float = 0.18667, k: float = 1418.9, c: float | None = None,
                 T: float | None = None, kI: float = 2.3983e8, b: float = 0.8485, xI: float = -2.086e-3,
                 omega: float = 16.0, friction: VelocityFriction | None = None) -> None:
        law = _paper_law() if friction is None else friction
        own = {k_: v for k_, v in (("c", c), ("T", T), ("eps", eps)) if v is not None}
        if own:
            law = _with_law_values(law, own)
        for name, val in (("m", m), ("m0e", m0e), ("n1", n1), ("n2", n2), ("n3", n3), ("k", k), ("kI", kI),
                          ("b", b), ("xI", xI), ("omega", omega)):
            try:
                val = float(val)
            except (TypeError, ValueError):
                raise InputError(f"Skurativskyi model: {name} must be a number (got {val!r})") from None
            object.__setattr__(self, name, val)
        object.__setattr__(self, "friction", law)
        self.__post_init__()

    def __post_init__(self) -> None:
        for name in ("m", "k", "kI", "n1", "n2", "n3", "omega"):
            val = getattr(self, name)
            if not (np.isfinite(val) and val > 0):
                raise InputError(f"Skurativskyi model: {name} must be a positive number (got {val!r})")
        for name in ("m0e", "b"):
            val = getattr(self, name)
            if not (np.isfinite(val) and val >= 0):
                raise InputError(f"Skurativskyi model: {name} must be >= 0 (got {val!r})")
        if not np.isfinite(self.xI):
            raise InputError("Skurativskyi model: xI must be finite")
        from landau.verify.skurativskyi.friction import check_regularised
        check_regularised(self.friction)
        if self.friction.name == "regularised-coulomb":  # the paper's law: c, T, eps are magnitudes
            for name, val in self.friction.defaults().items():
                if not val >= 0:
                    raise InputError(f"Skurativskyi model: {name} must be >= 0 (got {val!r})")

    # ------------------------------------------------------------------ the law's parameters
    def _law_value(self, name: str) -> float:
        try:
            return self.friction.defaults()[name]
        except KeyError:
            raise AttributeError(f"the friction law {self.friction.name!r} has no parameter {name!r}") from None

    @property
    def c(self) -> float:
        """The friction law's parameter ``c`` (viscous coefficient of the paper's law) [N s/m]."""
        return self._law_value("c")

    @property
    def T(self) -> float:
        """The friction law's parameter ``T`` (rolling resistance of the paper's law) [N]."""
        return self._law_value("T")

    @property
    def eps(self) -> float:
        """The friction law's parameter ``eps`` (regularisation of sgn ẋ in the paper's law) [m/s]."""
        return self._law_value("eps")

    @property
    def linear_damping(self) -> float:
        """The law's viscous coefficient lim F(v)/v, v → ∞ [N s/m] (c for the paper's law): the
        damping of the linearised solution and harmonic balance of Sec. 5
        (:func:`landau.verify.skurativskyi.friction.viscous_coefficient`)."""
        from landau.verify.skurativskyi.friction import viscous_coefficient
        return viscous_coefficient(self.friction)

    @property
    def velocity_floor(self) -> float:
        """|ẋ| [m/s] below which the slope of the Hertz damping is frozen in the variational
        equation: ε of the paper's law (as in eq. (1) written by hand), else :data:`V_FLOOR`."""
        if self.friction.name == "regularised-coulomb":
            return self.eps
        return V_FLOOR

    def packed(self) -> np.ndarray:
        """The parameter vector of the compiled kernels (indices IM … IOM, then the law's entries)."""
        from landau.verify.skurativskyi.friction import packed_values
        head = [self.m, self.m0e, self.velocity_floor, self.n1, self.n2, self.n3, self.k, self.kI, self.b, self.xI,
                self.omega]
        return np.array(head + packed_values(self.friction), dtype=float)

    def with_(self, **kw) -> "Params":
        """A copy with some parameters changed: mechanical ones, ``friction`` (a law) or any
        parameter of the friction law by name.

        Returns
        -------
        Params
        """
        d = {name: getattr(self, name) for name in MECHANICAL}
        law = kw.pop("friction", self.friction)
        law_names = {p.name for p in law.parameters}
        unknown = set(kw) - set(d) - law_names
        if unknown:
            raise InputError(f"unknown parameter(s) {sorted(unknown)} (known: {sorted(set(d) | law_names)})")
        own = {k_: float(v) for k_, v in kw.items() if k_ in law_names and k_ not in d}
        d.update({k_: float(v) for k_, v in kw.items() if k_ in d})
        if own:
            law = _with_law_values(law, own)
        return Params(**d, friction=law)

    @property
    def period(self) -> float:
        return 2 * np.pi / self.omega

    @classmethod
    def names(cls) -> list[str]:
        """The parameter names of the paper's model: the mechanical ones and the paper's law's (c, T, eps)."""
        return ["m", "m0e", "eps", "n1", "n2", "n3", "k", "c", "T", "kI", "b", "xI", "omega"]

    def parameter_names(self) -> list[str]:
        """The mechanical parameters and this law's parameters."""
        return list(MECHANICAL) + [p.name for p in self.friction.parameters]

    def values(self) -> dict[str, float]:
        """Every parameter's value: the mechanical ones, then the law's."""
        return {**{n: getattr(self, n) for n in MECHANICAL}, **self.friction.defaults()}

    def __repr__(self) -> str:
        mech = ", ".join(f"{n}={getattr(self, n)!r}" for n in MECHANICAL)
        return f"Params({mech}, friction={self.friction!r})"


def _with_law_values(law: VelocityFriction, values: dict) -> VelocityFriction:
    unknown = sorted(set(values) - {p.name for p in law.parameters})
    if unknown:
        raise InputError(f"the friction law {law.name!r} has no parameter(s) {', '.join(unknown)} "
                         f"(its parameters: {', '.join(p.name for p in law.parameters) or 'none'})")
    return law.with_defaults(**{k_: float(v) for k_, v in values.items()})


@lru_cache(maxsize=None)
def _paper_law() -> VelocityFriction:
    """The identified law of Sec. 2 (one object)."""
    return regularised_coulomb()


PAPER = Params()


# ------------------------------------------------------------------ compiled field per law
class CompiledField:
    """The field of eq. (1) for one friction law: the compiled functions of
    :mod:`landau.verify.skurativskyi.field` with the law's callbacks bound (see
    :func:`compiled_field`).

    Attributes
    ----------
    friction : CompiledFriction
        The law's compiled friction term (:mod:`landau.verify.skurativskyi.friction`).
    pointers : tuple
        Its C callbacks, the ``fr`` argument of the compiled field, SDIRK4 and loop.
    """

    def __init__(self, friction) -> None:
        self.friction = friction
        self.pointers = friction.pointers

    def contact_force(self, x, v, p):
        """F_I(x, ẋ) [N]."""
        from landau.verify.skurativskyi import field as F
        return F.contact_force(x, v, p)

    def accel(self, t, x, v, p):
        """ẍ of eq. (1)."""
        from landau.verify.skurativskyi import field as F
        from landau.verify.skurativskyi.friction import quiet_first_class
        with quiet_first_class():
            return F.accel(t, x, v, p, self.pointers)

    def accel_grad(self, t, x, v, p):
        """(∂ẍ/∂x, ∂ẍ/∂ẋ), the Hertz-damping slope floored at |ẋ| = p[IVF]."""
        from landau.verify.skurativskyi import field as F
        from landau.verify.skurativskyi.friction import quiet_first_class
        with quiet_first_class():
            return F.accel_grad(t, x, v, p, self.pointers)

    def accel_partials(self, t, x, v, p):
        """(ẍ, ∂ẍ/∂x, ∂ẍ/∂ẋ without the Hertz damping, κ) for the stiff stepper."""
        from landau.verify.skurativskyi import field as F
        from landau.verify.skurativskyi.friction import quiet_first_class
        with quiet_first_class():
            return F.accel_partials(t, x, v, p, self.pointers)

    @property
    def rhs(self):
        """``rhs(t, y, p, out)`` as a numba function (the engine's kernel and the compiled
        steppers take it): the field with this law's callbacks bound, built on first use in a
        process (a small wrapper; the field it calls is compiled once per machine)."""
        if not hasattr(self, "_rhs"):
            self._rhs = _bound_rhs(*self.pointers)
        return self._rhs


def _bound_rhs(f0, f1, f2, built_in, ptr):
    from numba import njit, types

    from landau.verify.skurativskyi import field as F
    from landau.verify.skurativskyi.friction import quiet_first_class

    @njit
    def rhs(t, y, p, out):
        F.rhs(t, y, p, out, (f0, f1, f2, built_in, ptr))

    if not hasattr(rhs, "compile"):      # NUMBA_DISABLE_JIT=1: the Python function
        return rhs
    with quiet_first_class():
        arr = types.float64[::1]
        rhs.compile((types.float64, arr, arr, arr))
    return rhs


@lru_cache(maxsize=None)
def _compiled(key) -> CompiledField:
    from landau.verify.skurativskyi.friction import compile_friction

    return CompiledField(compile_friction(_LAWS[key], ILAW))


_LAWS: dict = {}
#: the compiled functions of the field (signatures as documented in :mod:`landau.verify.skurativskyi.field`)
_KERNELS = ("contact_force", "accel", "accel_grad", "accel_partials", "rhs")


def compiled_field(law: VelocityFriction | Params | None = None) -> CompiledField:
    """The compiled field of eq. (1) with the friction of ``law`` (a law, or a :class:`Params`
    whose law is taken; default: the paper's).

    The friction term and its slope are generated from the law's symbolic branches
    (:mod:`landau.verify.skurativskyi.friction`) and compiled as C callbacks, which the field
    of :mod:`landau.verify.skurativskyi.field` (compiled once for all laws) calls: ``accel``,
    ``accel_grad``, ``accel_partials``, ``rhs`` and ``contact_force``, all of signature
    ``(t, …, p)`` with ``p`` = :meth:`Params.packed`.  One compilation of the callbacks per law
    expression (parameter values live in ``p``), cached on disk across processes.

    Parameters
    ----------
    law : VelocityFriction or Params, optional

    Returns
    -------
    CompiledField
        ``friction`` (:class:`~landau.verify.skurativskyi.friction.CompiledFriction`), its
        ``pointers`` and the functions named above.
    """
    if isinstance(law, Params):
        law = law.friction
    law = _paper_law() if law is None else law
    from landau.verify.skurativskyi.friction import check_regularised, law_key
    check_regularised(law)
    key = law_key(law)
    _LAWS.setdefault(key, law)
    return _compiled(key)


def __getattr__(name: str):
    # the paper's compiled field as module attributes (model.accel, model.rhs, …), made on first use
    if name in _KERNELS:
        return getattr(compiled_field(), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def field(params: Params, t: float, y) -> np.ndarray:
    """The vector field (ẋ, ẍ) in Python (for checks and the engine's guard/rate calls)."""
    p = params.packed()
    y = np.asarray(y, float)
    return np.array([y[1], compiled_field(params).accel(float(t), float(y[0]), float(y[1]), p)])


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
