"""Friction that depends on the sliding velocity only, Coulomb (set-valued) or regularised.

A :class:`VelocityFriction` is the friction F(v) as a function of the relative sliding
velocity ``v`` (its sign convention is the model's: positive ``v`` is positive slip), given
by a sympy expression for v > 0 and, optionally, another one for v < 0 (by default the odd
extension F(−v) = −F(v)).  When the two one-sided limits at v = 0 differ the law is
**set-valued** there (Coulomb friction: while sticking the force takes any value in
[F(0⁻), F(0⁺)]) and the models treat v = 0 as a stick phase; when they agree the law is
smooth (a regularised law) and v = 0 is an ordinary point.

Derivatives come from sympy; numeric functions (numpy, vectorised) are generated from the
expressions once per law.  Two built-in laws, with their sources:

* :func:`coulomb` — μ Sgn(v), the plain Coulomb friction coefficient of the frictional impact
  oscillator of Lancioni, Lenci & Galvanetto (dimensionless, multiplies the normal force);
* :func:`regularised_coulomb` — F_R(v) = c v + T v / sqrt(v² + ε²) [N], the viscous plus
  regularised dry (rolling) resistance of Skurativskyi, Kudra, Witkowski & Awrejcewicz
  (2019), eq. (1).

A new law takes one line, e.g. a Stribeck-type coefficient written as strings (parsed safely
by :mod:`landau.laws.parse`, never evaluated)::

    law = VelocityFriction.from_strings(
        "stribeck", "mu_k + (mu_s - mu_k)*exp(-v/v_s)", params={"mu_k": 0.3, "mu_s": 0.42, "v_s": 0.5})
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Callable, Mapping

import numpy as np
import sympy as sp

from landau.errors import DomainError, InputError
from landau.laws.base import Law
from landau.laws.law import Parameter, user_parameter
from landau.laws.parse import parse_expression
from landau.support.lambdify import lambdify_positional

#: the sliding-velocity symbol of every velocity-only law (real: both signs occur)
V_SLIP = sp.Symbol("v", real=True)

#: quantities a law may give, with their SI units
QUANTITIES = {"coefficient": "", "force": "N"}

_RESERVED = {"v": "the sliding velocity", "t": "the time", "x": "a displacement", "pi": "the constant pi",
             "E": "the constant e", "I": "the imaginary unit"}


def _check_parameter_name(name: str) -> None:
    if not isinstance(name, str) or not name.isidentifier() or name.startswith("_"):
        raise InputError(f"parameter name {name!r} is not a valid identifier")
    if name in _RESERVED:
        raise InputError(f"{name!r} cannot be a parameter: it is {_RESERVED[name]}")


@dataclass(frozen=True, eq=False)
class VelocityFriction(Law):
    """F(v): friction depending on the sliding velocity ``v`` only.

    Parameters
    ----------
    name : str
        Short name (shown by ``landau laws`` and in results).
    positive : sympy.Expr
        F(v) for v > 0 in the symbol :data:`V_SLIP` and the parameters' symbols.
    negative : sympy.Expr or None
        F(v) for v < 0; None (default) for the odd extension −F(−v).
    parameters : tuple of Parameter
        Every other symbol of the expressions, with default and provenance.
    quantity : {"coefficient", "force"}
        A friction coefficient (multiplies the normal force; dimensionless) or a force [N].
    source : str
        Paper and equation.
    description : str
        One line.

    Notes
    -----
    The law is set-valued at v = 0 when F(0⁺) ≠ F(0⁻) (:attr:`is_set_valued`); then
    ``value(0)`` is NaN and :attr:`static_level` is F(0⁺), the largest friction a stuck contact
    can transmit in the positive direction (``static_level_negative`` the other way).
    """

    name: str
    positive: sp.Expr
    negative: sp.Expr | None = None
    parameters: tuple[Parameter, ...] = ()
    quantity: str = "coefficient"
    source: str = ""
    description: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip() or len(self.name) > 200:
            raise InputError(f"a law needs a name (a non-empty string of at most 200 characters), got {self.name!r}")
        if self.quantity not in QUANTITIES:
            raise InputError(f"law {self.name!r}: quantity must be one of {', '.join(QUANTITIES)}, got "
                             f"{self.quantity!r}")
        names = [p.name for p in self.parameters]
        for n in names:
            _check_parameter_name(n)
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise InputError(f"law {self.name!r}: parameter {dup[0]!r} is declared twice")
        known = {V_SLIP, *(p.symbol for p in self.parameters)}
        for side, e in (("positive", self.positive), ("negative", self.negative)):
            if e is None:
                continue
            if not isinstance(e, sp.Expr):
                raise InputError(f"law {self.name!r}: the {side} branch must be a sympy expression, got "
                                 f"{type(e).__name__} (use VelocityFriction.from_strings for strings)")
            extra = e.free_symbols - known
            if extra:
                raise InputError(f"law {self.name!r}: the {side} branch uses undeclared symbol(s) "
                                 + ", ".join(sorted(map(str, extra))))
            if e.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
                raise InputError(f"law {self.name!r}: the {side} branch is not finite")
            if e.has(sp.I):
                raise DomainError(f"law {self.name!r}: the {side} branch {str(e)[:80]} is not real")
            # the branch is used on its own side of v = 0 only: sqrt(-v) for v > 0 is imaginary
            on_side = e.xreplace({V_SLIP: (1 if side == "positive" else -1) * sp.Dummy("w", positive=True)})
            if on_side.has(sp.I) or on_side.is_extended_real is False:
                raise DomainError(f"law {self.name!r}: the {side} branch {str(e)[:80]} is not real for "
                                  f"{'v > 0' if side == 'positive' else 'v < 0'}")
        for p in self.parameters:
            if p.default is not None and not math.isfinite(p.default):
                raise InputError(f"law {self.name!r}: parameter {p.name!r} must be finite, got {p.default!r}")

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_strings(cls, name: str, positive: str, negative: str | None = None,
                     params: Mapping[str, float | Parameter] | None = None, *, quantity: str = "coefficient",
                     source: str = "user-defined", description: str = "") -> "VelocityFriction":
        """Declare a law from strings, parsed safely (a whitelist walk of the syntax tree).

        Parameters
        ----------
        name : str
            Name of the law.
        positive : str
            F(v) for v > 0 in the sliding velocity ``v`` and the parameters, e.g.
            ``"mu_k + (mu_s - mu_k)*exp(-v/v_s)"`` (``^`` means power).
        negative : str, optional
            F(v) for v < 0; default: the odd extension −F(−v).
        params : mapping, optional
            Every parameter's value (a float) or :class:`~landau.laws.law.Parameter`.
        quantity : {"coefficient", "force"}, optional
            What F is (default: a friction coefficient).
        source, description : str, optional
            Provenance and a one-line description.

        Returns
        -------
        VelocityFriction

        Raises
        ------
        InputError
            An unknown symbol (named), a reserved name used as a parameter, a parameter that is
            not a finite number; a :class:`~landau.errors.ParseError` names an offending token.
        """
        from landau.laws.parse import CONSTANTS, FUNCTIONS, referenced_names

        plist: list[Parameter] = []
        for pname, val in dict(params or {}).items():
            _check_parameter_name(pname)
            plist.append(user_parameter(pname, val, positive=False))
        texts = {"F(v > 0)": positive} | ({"F(v < 0)": negative} if negative is not None else {})
        used: set[str] = set()
        for what, text in texts.items():
            used |= referenced_names(text, what=what)
        unknown = sorted(used - {"v"} - {p.name for p in plist} - set(FUNCTIONS) - set(CONSTANTS))
        if unknown:
            raise InputError(f"law {name!r}: unknown symbol(s) {', '.join(unknown)} "
                             "(give each parameter a value, e.g. --param NAME=VALUE)")
        symbols = {"v": V_SLIP, **{p.name: p.symbol for p in plist}}
        pos = parse_expression(positive, symbols, what="F(v > 0)")
        neg = parse_expression(negative, symbols, what="F(v < 0)") if negative is not None else None
        syms = pos.free_symbols | (neg.free_symbols if neg is not None else set())
        plist = [p for p in plist if p.symbol in syms]
        return cls(name, pos, neg, tuple(plist), quantity, source, description)

    # ------------------------------------------------------------------ symbolic form
    @property
    def v(self) -> sp.Symbol:
        """The sliding-velocity symbol."""
        return V_SLIP

    @property
    def units(self) -> str:
        """SI units of F ('' for a coefficient, 'N' for a force)."""
        return QUANTITIES[self.quantity]

    def branch(self, side: int = 1, order: int = 0) -> sp.Expr:
        """The symbolic branch F(v) (``side`` = +1: v > 0; −1: v < 0) or its ``order``-th derivative.

        Parameters
        ----------
        side : {+1, -1}
            Which side of v = 0.
        order : int
            Derivative order in v (0: the branch itself).

        Returns
        -------
        sympy.Expr
        """
        if side not in (1, -1):
            raise InputError(f"side must be +1 or -1, got {side!r}")
        if side == 1 or self.negative is None:
            e = self.positive if side == 1 else -self.positive.subs(V_SLIP, -V_SLIP)
        else:
            e = self.negative
        return sp.diff(e, V_SLIP, order) if order else e

    def _values(self, params: Mapping[str, float] | None) -> list[float]:
        vals = self.defaults() | dict(params or {})
        unknown = sorted(set(params or {}) - {p.name for p in self.parameters})
        if unknown:
            raise InputError(f"law {self.name!r} has no parameter(s) {', '.join(unknown)}")
        missing = [p.name for p in self.parameters if p.name not in vals]
        if missing:
            raise InputError(f"law {self.name!r}: parameter(s) {', '.join(missing)} need a value")
        return [float(vals[p.name]) for p in self.parameters]

    def numeric(self, side: int = 1, order: int = 0):
        """The branch (or its derivative) as a vectorised numpy function f(v, *parameter values),
        parameters in the order of :attr:`parameters`; generated once per law and kept.

        Parameters
        ----------
        side : {+1, -1}
        order : int

        Returns
        -------
        callable
        """
        key = (side, order)
        cache = self._lambdified
        if key not in cache:
            args = [V_SLIP, *(p.symbol for p in self.parameters)]
            cache[key] = lambdify_positional(args, self.branch(side, order), modules="numpy")
        return cache[key]

    @cached_property
    def _lambdified(self) -> dict:
        return {}

    # ------------------------------------------------------------------ numbers
    def limits_at_zero(self, params: Mapping[str, float] | None = None) -> tuple[float, float]:
        """(F(0⁻), F(0⁺)): the one-sided limits at zero sliding velocity.

        Parameters
        ----------
        params : mapping, optional
            Parameter values (default: the defaults).

        Returns
        -------
        tuple of float
        """
        vals = dict(zip((p.symbol for p in self.parameters), self._values(params), strict=True))
        out = []
        for side in (-1, 1):
            e = self.branch(side).subs(vals)
            lim = e.subs(V_SLIP, 0)
            if lim.has(sp.nan, sp.zoo, sp.oo, -sp.oo) or not lim.is_number:
                lim = sp.limit(e, V_SLIP, 0, "+" if side == 1 else "-")
            try:
                x = float(lim)
                if not math.isfinite(x):
                    raise ValueError
            except (TypeError, ValueError):
                raise DomainError(f"law {self.name!r}: F has no finite limit at v = 0{'+' if side == 1 else '-'}") \
                    from None
            out.append(x)
        return out[0], out[1]

    def is_set_valued(self, params: Mapping[str, float] | None = None) -> bool:
        """Whether F jumps at v = 0 (Coulomb-type; stick is a phase of its own).

        Parameters
        ----------
        params : mapping, optional
            Parameter values (default: the defaults).

        Returns
        -------
        bool
        """
        lo, hi = self.limits_at_zero(params)
        return not math.isclose(lo, hi, rel_tol=1e-12, abs_tol=1e-300)

    def static_level(self, params: Mapping[str, float] | None = None) -> float:
        """F(0⁺): the friction at the onset of positive slip (for a Coulomb law, the static level).

        Parameters
        ----------
        params : mapping, optional
            Parameter values (default: the defaults).

        Returns
        -------
        float
        """
        return self.limits_at_zero(params)[1]

    def value(self, vs, params: Mapping[str, float] | None = None, *, order: int = 0):
        """F(v) (or its ``order``-th derivative) at sliding velocities ``vs`` (any shape).

        At v = 0 a set-valued law gives NaN (the force is any value between the one-sided
        limits there); a smooth law gives its value.

        Parameters
        ----------
        vs : array_like
            Sliding velocities.
        params : mapping, optional
            Parameter values (default: the defaults).
        order : int, optional
            Derivative order (0: F itself).

        Returns
        -------
        float or numpy.ndarray
        """
        vals = self._values(params)
        x = np.asarray(vs, dtype=float)
        with np.errstate(all="ignore"):
            pos = np.broadcast_to(np.asarray(self.numeric(1, order)(x, *vals), dtype=float), x.shape)
            neg = np.broadcast_to(np.asarray(self.numeric(-1, order)(x, *vals), dtype=float), x.shape)
        out = np.where(x > 0, pos, np.where(x < 0, neg, np.nan))
        zero = x == 0
        if np.any(zero) and not self.is_set_valued(params):
            lo, hi = self.limits_at_zero(params)
            if order == 0:
                out = np.where(zero, hi, out)
            else:
                with np.errstate(all="ignore"):
                    d0 = float(np.asarray(self.numeric(1, order)(0.0, *vals), dtype=float))
                out = np.where(zero, d0, out)
        return out if out.ndim else float(out)

    def slope(self, vs, params: Mapping[str, float] | None = None):
        """dF/dv at ``vs`` (see :meth:`value`).

        Parameters
        ----------
        vs : array_like
        params : mapping, optional

        Returns
        -------
        float or numpy.ndarray
        """
        return self.value(vs, params, order=1)

    def __call__(self, vs, params: Mapping[str, float] | None = None):
        return self.value(vs, params)

    # ------------------------------------------------------------------ display
    def latex(self) -> str:
        """The law as one line of LaTeX.

        Returns
        -------
        str
        """
        lhs = r"\mu(v)" if self.quantity == "coefficient" else r"F(v)"
        pos = sp.latex(self.positive)
        if self.negative is None:
            return rf"{lhs} = {pos}\ (v > 0),\quad {lhs} = -{lhs[:-3]}(-v)\ (v < 0)"
        return rf"{lhs} = {pos}\ (v > 0),\quad {lhs} = {sp.latex(self.negative)}\ (v < 0)"

    def __repr__(self) -> str:
        neg = "odd extension" if self.negative is None else str(self.negative)
        params = ", ".join(f"{p.name}={p.default:g}" for p in self.parameters if p.default is not None)
        return (f"VelocityFriction({self.name!r}: F(v>0) = {self.positive}; F(v<0) = {neg}; {params}"
                f"{'; ' if params else ''}{self.quantity}{'; source=' + repr(self.source) if self.source else ''})")

    def __reduce__(self):
        return (type(self), (self.name, self.positive, self.negative, self.parameters, self.quantity, self.source,
                             self.description))


# ---------------------------------------------------------------------- built-in laws
LANCIONI = "Lancioni, Lenci & Galvanetto (c. 2008), frictional impact oscillator, eq. (1): Coulomb friction"
SKURATIVSKYI = "Skurativskyi, Kudra, Witkowski, Awrejcewicz 2019, Nonlinear Dyn. 98:1795, eq. (1), Sec. 2"


def coulomb(mu: float = 0.4) -> VelocityFriction:
    """Plain Coulomb friction μ Sgn(v): μ while slipping forwards, −μ backwards, any value in
    [−μ, μ] while stuck.

    Parameters
    ----------
    mu : float, optional
        Friction coefficient (default 0.4).

    Returns
    -------
    VelocityFriction

    References
    ----------
    Lancioni, G., Lenci, S. & Galvanetto, U., the frictional impact oscillator, eq. (1):
    Coulomb friction λ_T = −μ λ_N sgn(g_T) in slip, |λ_T| ≤ μ λ_N in stick.
    """
    m = Parameter("mu", float(mu), "", LANCIONI, "Coulomb friction coefficient", positive=False)
    return VelocityFriction("coulomb", m.symbol + 0 * V_SLIP, None, (m,), "coefficient", LANCIONI,
                            "plain Coulomb friction")


def regularised_coulomb(c: float = 6.6511, T: float = 0.63133, eps: float = 1e-6) -> VelocityFriction:
    """F_R(v) = c v + T v / sqrt(v² + ε²) [N]: viscous plus regularised dry (rolling) resistance.

    Parameters
    ----------
    c : float, optional
        Viscous coefficient [N s/m] (identified value 6.6511).
    T : float, optional
        Rolling resistance [N] (0.63133).
    eps : float, optional
        Regularisation of sgn v [m/s] (1e-6).

    Returns
    -------
    VelocityFriction

    References
    ----------
    Skurativskyi, S., Kudra, G., Witkowski, K. & Awrejcewicz, J. (2019), "Bifurcation phenomena
    and statistical regularities in dynamics of forced impacting oscillator", Nonlinear Dyn.
    98, 1795–1806, eq. (1) and the identified parameters of Sec. 2.
    """
    ps = (Parameter("c", float(c), "N s/m", SKURATIVSKYI, "viscous coefficient", positive=False),
          Parameter("T", float(T), "N", SKURATIVSKYI, "rolling resistance", positive=False),
          Parameter("eps", float(eps), "m/s", SKURATIVSKYI, "regularisation of sgn v", positive=False))
    cs, Ts, es = (p.symbol for p in ps)
    expr = cs * V_SLIP + Ts * V_SLIP / sp.sqrt(V_SLIP ** 2 + es ** 2)
    # one expression for both signs (odd, smooth through v = 0)
    return VelocityFriction("regularised-coulomb", expr, expr, ps, "force", SKURATIVSKYI,
                            "viscous + regularised dry resistance")


BUILTIN_VELOCITY: dict[str, Callable[..., VelocityFriction]] = {"coulomb": coulomb,
                                                                 "regularised-coulomb": regularised_coulomb}


def law_from_options(text: str | None, negative: str | None, name: str | None, default: VelocityFriction,
                     params: dict, *, quantity: str = "coefficient") -> VelocityFriction:
    """A model's velocity law: ``default`` with any of ``params`` that are its parameters, or the law
    declared by the strings ``text`` (v > 0) and ``negative`` (v < 0; default the odd extension).

    The law's own values are removed from ``params`` (what is left are the model's).

    Parameters
    ----------
    text, negative : str or None
        The declared branches (parsed by the whitelist parser, never evaluated).
    name : str or None
        The declared law's name (default ``user-friction``).
    default : VelocityFriction
        The model's published law.
    params : dict
        Parameter values by name (modified in place).
    quantity : {"coefficient", "force"}
        What the model expects the law to give.

    Raises
    ------
    InputError
        ``negative`` without ``text``; an expression outside the whitelist.
    """
    from landau.laws.parse import referenced_names

    if text is None:
        if negative is not None:
            raise InputError("--friction-neg needs --friction (the branch for v > 0)")
        own = {p.name for p in default.parameters}
        law_params = {k: params.pop(k) for k in list(params) if k in own}
        return default.with_defaults(**law_params) if law_params else default
    names = referenced_names(text, what="--friction") | (referenced_names(negative, what="--friction-neg")
                                                         if negative else set())
    law_params = {k: params.pop(k) for k in list(params) if k in names}
    return VelocityFriction.from_strings(name or "user-friction", text, negative, law_params, quantity=quantity)


def declared_names(text: str | None, negative: str | None) -> tuple[str, ...]:
    """The parameter names of a law declared by the strings ``text`` and ``negative`` (every name
    they use but the sliding velocity ``v``), sorted; () without ``text``."""
    from landau.laws.parse import referenced_names

    if text is None:
        return ()
    names = referenced_names(text, what="--friction") | (referenced_names(negative, what="--friction-neg")
                                                         if negative else set())
    return tuple(sorted(names - {V_SLIP.name}))
