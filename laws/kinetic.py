"""Velocity-weakening kinetic friction of Galvanetto (2004), eq. (7), and its Coulomb limit.

Source: U. Galvanetto, *Sliding bifurcations in the dynamics of mechanical systems with
dry friction*, J. Sound Vib. 276 (2004) 121–139, eq. (7) (garbled in the scanned print; the
reading below is the one confirmed by reproducing the paper's
two-block results).  With the relative velocity r = Ẋ − V (block minus belt):

    F_k(r) = (1 − δ)/(1 − γ r) + δ        for r < 0   (block slower than the belt)
    F_k(r) = −(1 − δ)/(1 + γ r) − δ       for r > 0

so |F_k(0±)| = 1 = F_s (the static level) and |F_k| decays to δ for |r| → ∞.  γ > 0 sets
the velocity weakening, 0 ≤ δ ≤ 1 the residual level.  γ = 0 gives Coulomb friction with
equal static and kinetic levels (F_k = −sign r); the force is scaled by F_si for block i
(eq. 8b).  Defaults are those of the paper's examples: γ = 3 (Figs 7–15), δ = 0 (as
printed; Sec. 4.1's one-block values are reproduced only with δ = 0.2).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np
import sympy as sp

from landau.errors import InputError
from landau.laws.base import Law

#: the symbols the branch expressions are written in: relative velocity r and the parameters γ, δ
R = sp.Symbol("r", real=True)
GAMMA, DELTA = sp.symbols("gamma delta", positive=True)

_PAPER_NEG = (1 - DELTA) / (1 - GAMMA * R) + DELTA      # eq. (7), r < 0
_PAPER_POS = -(1 - DELTA) / (1 + GAMMA * R) - DELTA     # eq. (7), r > 0


@lru_cache(maxsize=256)
def _numeric(expr: sp.Expr):
    """expr(r, γ, δ) compiled once (per expression, shared by every law that uses it: sweeps build
    many laws with the same branches) to a numpy function of (r, gamma, delta).  The derivative of
    a jump (``sign(r + 0.5)`` → DiracDelta) is zero away from it and infinite on it."""
    from landau.support.lambdify import numeric_modules

    return sp.lambdify((R, GAMMA, DELTA), expr, modules=numeric_modules("numpy"))


#: |r| where a branch is checked to be real when the law is built (a NaN there: sqrt or log of a
#: negative number, the branch is not a friction force)
_REAL_PROBE = 10.0 ** np.arange(-6, 3)

#: names an extra parameter of a user's kinetic law may not take: the relative velocity, γ, δ and
#: the Galvanetto models' own parameters
_TAKEN = {"r": "the relative velocity", "gamma": "the law's velocity weakening",
          "delta": "the law's residual level", "V": "the belt velocity", "c": "the damping",
          "alpha": "the coupling stiffness", "beta": "block 2's static level", "X": "a state", "n": "the block count"}


SOURCE = "Galvanetto 2004, J. Sound Vib. 276:121, eq. (7)"


@dataclass(frozen=True)
class KineticFriction(Law):
    """F_k(r) of eq. (7), or a user-written law of the same two-branch form.

    The law lives once, symbolically: ``neg_expr``/``pos_expr`` are sympy expressions of the
    two smooth branches in the relative velocity :data:`R` (and optionally the parameters
    :data:`GAMMA`, :data:`DELTA`, whose values are ``gamma``/``delta``).  The numeric branch
    functions ``neg``/``pos`` and the derivatives ``dneg``/``dpos``/``d3neg`` are generated from
    them (sympy differentiation, lambdified once per law).  The branches are defined beyond
    r = 0, which the grazing analysis uses to continue a slip field past the switching surface.
    The default expressions are Galvanetto's eq. (7); see :meth:`from_expression` for others.
    """

    gamma: float = 3.0
    delta: float = 0.0
    neg_expr: sp.Expr = field(default=_PAPER_NEG, repr=False)
    pos_expr: sp.Expr = field(default=_PAPER_POS, repr=False)
    #: further parameters of a user's branches, as (name, value) pairs (:meth:`from_expression`)
    extra: tuple[tuple[str, float], ...] = ()
    #: the branches in r, γ, δ and the ``extra`` symbols; ``neg_expr``/``pos_expr`` are these with
    #: the extra values substituted (so every consumer sees expressions in r, γ, δ only)
    template: tuple[sp.Expr, sp.Expr] | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        import math

        for name in ("gamma", "delta"):
            x = getattr(self, name)
            if not isinstance(x, (int, float)) or not math.isfinite(x):
                raise InputError(f"KineticFriction: {name} must be a finite number, got {x!r}")
        extra = tuple((str(k), float(x)) for k, x in self.extra)
        for k, x in extra:
            _check_extra_name(k)
            if not math.isfinite(x):
                raise InputError(f"KineticFriction: parameter {k!r} must be finite, got {x!r}")
        object.__setattr__(self, "extra", extra)
        if extra and self.template is None:
            raise InputError("KineticFriction: extra parameters need the branches' template "
                             "(build the law with KineticFriction.from_expression(..., name=value))")
        if self.template is not None:
            syms = {sp.Symbol(k, real=True): x for k, x in extra}
            for e, side in zip(self.template, ("neg", "pos"), strict=True):
                if not isinstance(e, sp.Expr):
                    raise InputError(f"KineticFriction: the {side} branch must be a sympy expression in r")
                unknown = e.free_symbols - {R, GAMMA, DELTA, *syms}
                if unknown:
                    raise InputError(f"KineticFriction: the {side} branch uses {', '.join(sorted(map(str, unknown)))} "
                                     "without a value")
            neg, pos = (e.xreplace(syms) for e in self.template)
            object.__setattr__(self, "neg_expr", neg)
            object.__setattr__(self, "pos_expr", pos)
        for name in ("neg_expr", "pos_expr"):
            e = getattr(self, name)
            if not isinstance(e, sp.Expr):
                raise InputError(f"KineticFriction: {name} must be a sympy expression in r")
            unknown = e.free_symbols - {R, GAMMA, DELTA}
            if unknown:
                raise InputError(f"KineticFriction: {name} uses unknown symbol(s) "
                                 f"{', '.join(sorted(map(str, unknown)))}; give their values "
                                 "(KineticFriction.from_expression(..., name=value), --param name=value)")
        if self.is_paper_law and not (self.gamma >= 0 and 0 <= self.delta <= 1):
            raise InputError(f"Galvanetto's law (2004, eq. 7) needs gamma >= 0 (velocity weakening; 0: Coulomb) and "
                             f"0 <= delta <= 1 (the residual kinetic level), got gamma = {self.gamma:g}, "
                             f"delta = {self.delta:g}")
        fns = {"_neg": self.neg_expr, "_pos": self.pos_expr,
               "_dneg": sp.diff(self.neg_expr, R), "_dpos": sp.diff(self.pos_expr, R),
               "_d3neg": sp.diff(self.neg_expr, R, 3)}
        for k, e in fns.items():
            object.__setattr__(self, k, _numeric(e))
        if not self.is_paper_law:
            self._check_real()

    def _check_real(self) -> None:
        """Refuse a branch that is not real (NaN) at |r| = 1e-6 … 100 on its own side."""
        from landau.errors import DomainError

        for side, fn, rs in (("r < 0", self.neg, -_REAL_PROBE), ("r > 0", self.pos, _REAL_PROBE)):
            with np.errstate(all="ignore"):
                vals = np.broadcast_to(np.asarray(fn(rs), dtype=complex), rs.shape)
            bad = np.isnan(vals) | (vals.imag != 0)
            if np.any(bad):
                r0 = float(rs[np.argmax(bad)])
                raise DomainError(f"the kinetic law's {side} branch is not real at r = {r0:g} ({self!r}): "
                                  "a friction force must be a real function of the relative velocity")

    def __reduce__(self):
        # rebuilt from its fields (the generated numeric functions are not picklable)
        return (type(self), (self.gamma, self.delta, self.neg_expr, self.pos_expr, self.extra, self.template))

    # ---------------------------------------------------------------- symbolic form
    def branch(self, side: str = "neg", *, symbolic: bool = False) -> sp.Expr:
        """The sympy expression of one branch in :data:`R`.

        Parameters
        ----------
        side : "neg" (r < 0, block slower than the belt) or "pos" (r > 0).
        symbolic : keep γ, δ as the symbols :data:`GAMMA`, :data:`DELTA` (True) or substitute
            this law's values (False).

        Returns
        -------
        sympy.Expr
        """
        if side not in ("neg", "pos"):
            raise InputError(f"KineticFriction.branch: side must be 'neg' or 'pos', not {side!r}")
        e = self.neg_expr if side == "neg" else self.pos_expr
        return e if symbolic else e.subs({GAMMA: self.gamma, DELTA: self.delta})

    @classmethod
    def from_expression(cls, neg, pos=None, *, gamma: float = 3.0, delta: float = 0.0,
                        names: tuple[str, str] = ("neg", "pos"), **params: float) -> "KineticFriction":
        """A kinetic law from its r < 0 branch (and optionally its r > 0 branch).

        Parameters
        ----------
        neg : sympy expression in :data:`R` (and :data:`GAMMA`, :data:`DELTA`), or a string in
            the names ``r``, ``gamma``, ``delta`` parsed by :func:`landau.laws.parse.parse_expression`
            (never evaluated).
        pos : the same for r > 0; default the odd reflection −neg(−r).
        gamma, delta : values of the parameters γ, δ if the expressions use them.
        names : how the two branches are named in error messages (e.g. the CLI's option names).
        **params : float
            Values of any further parameter the branches use, e.g. ``eta=0.05`` for
            ``"(1 - delta)/(1 - gamma*r)**2 + delta - eta*r"``.

        Returns
        -------
        KineticFriction

        Raises
        ------
        ParseError, InputError
            On a string the parser refuses, or an expression in other symbols.

        References
        ----------
        U. Galvanetto, J. Sound Vib. 276 (2004) 121–139, eq. (7) (the law's two-branch form).
        """
        from landau.laws.law import user_parameter

        for k in params:
            _check_extra_name(k)
        values: dict[str, float] = {}
        for k, x in params.items():
            prm = user_parameter(k, x, positive=False)
            if prm.default is None:
                raise InputError(f"parameter {k!r} of the kinetic law needs a value")
            values[k] = float(prm.default)
        symbols = {"r": R, "gamma": GAMMA, "delta": DELTA, **{k: sp.Symbol(k, real=True) for k in values}}

        def as_expr(x, what):
            if isinstance(x, str):
                import re

                from landau.laws.parse import parse_expression, referenced_names

                # names that could be parameters (anything else is the parser's to refuse)
                missing = sorted(m for m in referenced_names(x, what=what) - set(symbols) - _functions()
                                 if re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", m))
                if missing:
                    raise InputError(f"{what}: the kinetic law uses {', '.join(missing)} without a value: give "
                                     + ", ".join(f"{m}=VALUE" for m in missing)
                                     + " (--param on the command line, a keyword of from_expression)")
                return parse_expression(x, symbols, what=what)
            if isinstance(x, sp.Expr):
                return x
            raise InputError(f"KineticFriction.from_expression: {what} must be a string or a sympy expression")
        n = as_expr(neg, names[0])
        p = -n.subs(R, -R) if pos is None else as_expr(pos, names[1])
        used = {s.name for s in n.free_symbols | p.free_symbols}
        unused = sorted(set(values) - used)
        if unused:
            raise InputError(f"unknown parameter(s) {', '.join(unused)}: the kinetic law uses "
                             + (", ".join(sorted(used - {"r"})) or "no parameter"))
        if not values:
            return cls(gamma=float(gamma), delta=float(delta), neg_expr=n, pos_expr=p)
        return cls(gamma=float(gamma), delta=float(delta), extra=tuple(values.items()), template=(n, p))

    # ---------------------------------------------------------------- numeric form
    def neg(self, r):
        """Branch r < 0: (1 − δ)/(1 − γ r) + δ for eq. (7)  (> 0: the belt drags the block forward)."""
        return self._neg(_float(r), self.gamma, self.delta)

    def pos(self, r):
        """Branch r > 0: −(1 − δ)/(1 + γ r) − δ for eq. (7)."""
        return self._pos(_float(r), self.gamma, self.delta)

    def dneg(self, r):
        """dF_k/dr on the r < 0 branch (γ(1 − δ)/(1 − γ r)² for eq. (7))."""
        return self._dneg(_float(r), self.gamma, self.delta)

    def dpos(self, r):
        """dF_k/dr on the r > 0 branch (γ(1 − δ)/(1 + γ r)² for eq. (7))."""
        return self._dpos(_float(r), self.gamma, self.delta)

    def d3neg(self, r):
        """d³F_k/dr³ on the r < 0 branch (6γ³(1 − δ)/(1 − γ r)⁴ for eq. (7))."""
        return self._d3neg(_float(r), self.gamma, self.delta)

    def __call__(self, r):
        """F_k(r) for r ≠ 0 (at r = 0 the force is set-valued, [−1, 1]; returns nan)."""
        r = np.asarray(r, dtype=float)
        out = np.where(r < 0, self.neg(np.minimum(r, 0.0)), self.pos(np.maximum(r, 0.0)))
        out = np.where(r == 0, np.nan, out)
        return out if out.ndim else float(out)

    def weakening_velocity(self) -> float | None:
        """The velocity scale of the r < 0 branch: the |r| at which F_k has made half its drop
        from F_k(0⁻) to its far level F_k(r → −∞) (1/γ for eq. (7)); None when the branch does
        not weaken (Coulomb friction).  Locators use it to set their search ranges in V.

        Returns
        -------
        float or None
        """
        ks = np.arange(-6.0, 10.0)
        with np.errstate(all="ignore"):
            vals = np.array([float(self.neg(-10.0 ** k)) for k in ks])
        ok = np.isfinite(vals)
        f0 = float(self.neg(0.0))
        if not ok.any() or not np.isfinite(f0):
            return None
        far = vals[ok][-1]
        if not abs(f0 - far) > 1e-9 * max(1.0, abs(f0)):
            return None
        half = 0.5 * (f0 + far)
        g = lambda v: float(self.neg(-v)) - half
        lo = 0.0
        for k, v in zip(ks[ok], vals[ok], strict=True):
            if np.sign(v - half) != np.sign(f0 - half):
                from scipy.optimize import brentq
                return float(brentq(g, lo, 10.0 ** k, xtol=1e-14, rtol=1e-12))
            lo = 10.0 ** k
        return None

    @classmethod
    def coulomb(cls) -> "KineticFriction":
        """The Coulomb limit γ → 0: F_k = −sign(r), kinetic level = static level = 1."""
        return cls(gamma=0.0, delta=0.0)

    @property
    def is_paper_law(self) -> bool:
        """True for Galvanetto's eq. (7) (the default branches)."""
        return not self.extra and self.neg_expr == _PAPER_NEG and self.pos_expr == _PAPER_POS

    # ------------------------------------------------------------ the Law interface
    @property  # computed from the branches: read-only here, a field of other laws
    def name(self) -> str:  # type: ignore[override]
        """``"galvanetto-2004"`` for eq. (7), ``"user-kinetic"`` for other branches."""
        return "galvanetto-2004" if self.is_paper_law else "user-kinetic"

    @property  # computed from the branches: read-only here, a field of other laws
    def source(self) -> str:  # type: ignore[override]
        """Galvanetto (2004) eq. (7), or "user-defined"."""
        return SOURCE if self.is_paper_law else "user-defined"

    @property  # computed from the branches: read-only here, a field of other laws
    def parameters(self) -> tuple:  # type: ignore[override]
        """γ and δ as :class:`~landau.laws.law.Parameter` objects (dimensionless)."""
        from landau.laws.law import Parameter

        return (Parameter("gamma", float(self.gamma), "", SOURCE, "velocity weakening γ", positive=False),
                Parameter("delta", float(self.delta), "", SOURCE, "residual kinetic level δ", positive=False),
                *(Parameter(k, x, source="user", positive=False) for k, x in self.extra))

    def with_defaults(self, **values: float) -> "KineticFriction":
        """A copy with γ and/or δ changed.

        Parameters
        ----------
        **values : float
            ``gamma`` and/or ``delta``.

        Returns
        -------
        KineticFriction
        """
        own = [k for k, _ in self.extra]
        unknown = sorted(set(values) - {"gamma", "delta", *own})
        if unknown:
            raise InputError(f"law {self.name!r} has no parameter(s) {', '.join(unknown)} "
                             f"(known: {', '.join(['gamma', 'delta', *own])})")
        import dataclasses

        kw: dict[str, Any] = {k: float(values.pop(k)) for k in ("gamma", "delta") if k in values}
        if values:
            kw["extra"] = tuple((k, float(values.get(k, x))) for k, x in self.extra)
        return dataclasses.replace(self, **kw)

    def latex(self) -> str:
        """The two branches as one line of LaTeX.

        Returns
        -------
        str
        """
        neg, pos = self.template or (self.neg_expr, self.pos_expr)
        return (rf"F_k(r) = {sp.latex(neg)}\ (r < 0),\quad "
                rf"F_k(r) = {sp.latex(pos)}\ (r > 0)")

    def __repr__(self) -> str:
        if self.is_paper_law:
            return f"KineticFriction(γ={self.gamma:g}, δ={self.delta:g})  # Galvanetto 2004 eq. (7)"
        neg, pos = self.template or (self.neg_expr, self.pos_expr)
        return (f"KineticFriction(r<0: {neg}, r>0: {pos}, "
                f"γ={self.gamma:g}, δ={self.delta:g}" + "".join(f", {k}={x:g}" for k, x in self.extra) + ")")


def _float(r):
    """r as numpy floats (a Python float would make the generated code raise OverflowError where
    numpy gives inf, and divide by zero with ZeroDivisionError)."""
    return np.float64(r) if np.ndim(r) == 0 else np.asarray(r, dtype=float)


def _functions() -> set[str]:
    from landau.laws.parse import CONSTANTS, FUNCTIONS

    return set(FUNCTIONS) | set(CONSTANTS)


def _check_extra_name(name: str) -> None:
    """An extra parameter's name: a plain identifier that is not r, γ, δ, a Galvanetto model
    parameter or a name the rate-and-state laws reserve."""
    from landau.laws.law import _check_name

    if name in _TAKEN:
        raise InputError(f"parameter name {name!r} is reserved: it is {_TAKEN[name]}; choose another name")
    _check_name(name, "parameter")


def resolve_kinetic_law(law: KineticFriction | None = None, gamma: float | None = None,
                        delta: float | None = None, *, default_gamma: float = 3.0,
                        default_delta: float = 0.0) -> KineticFriction:
    """The kinetic law of a Galvanetto-model computation, from a law object and/or γ, δ values.

    Parameters
    ----------
    law : KineticFriction, optional
        The law; default Galvanetto's eq. (7).
    gamma, delta : float, optional
        Values of the law's parameters γ, δ.  Without ``law`` they build eq. (7) (missing ones
        take ``default_gamma``/``default_delta``); with ``law`` they must equal the law's own.
    default_gamma, default_delta : float
        The values used for eq. (7) when ``gamma``/``delta`` are not given.

    Returns
    -------
    KineticFriction

    Raises
    ------
    InputError
        ``law`` is not a :class:`KineticFriction`, or ``gamma``/``delta`` conflict with it.
    """
    if law is None:
        return KineticFriction(float(default_gamma if gamma is None else gamma),
                               float(default_delta if delta is None else delta))
    if not isinstance(law, KineticFriction):
        raise InputError(f"law must be a KineticFriction, not {type(law).__name__}")
    for name, v in (("gamma", gamma), ("delta", delta)):
        if v is not None and float(v) != getattr(law, name):
            raise InputError(f"{name}={v} conflicts with the law's {name}={getattr(law, name)}; give one of them")
    return law
