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
    many laws with the same branches) to a numpy function of (r, gamma, delta)."""
    return sp.lambdify((R, GAMMA, DELTA), expr, modules="numpy")


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

    def __post_init__(self) -> None:
        for name in ("neg_expr", "pos_expr"):
            e = getattr(self, name)
            if not isinstance(e, sp.Expr):
                raise InputError(f"KineticFriction: {name} must be a sympy expression in r")
            extra = e.free_symbols - {R, GAMMA, DELTA}
            if extra:
                raise InputError(f"KineticFriction: {name} uses unknown symbol(s) "
                                 f"{', '.join(sorted(map(str, extra)))}; only r, gamma, delta are allowed")
        fns = {"_neg": self.neg_expr, "_pos": self.pos_expr,
               "_dneg": sp.diff(self.neg_expr, R), "_dpos": sp.diff(self.pos_expr, R),
               "_d3neg": sp.diff(self.neg_expr, R, 3)}
        for k, e in fns.items():
            object.__setattr__(self, k, _numeric(e))

    def __reduce__(self):
        # rebuilt from its fields (the generated numeric functions are not picklable)
        return (type(self), (self.gamma, self.delta, self.neg_expr, self.pos_expr))

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
                        names: tuple[str, str] = ("neg", "pos")) -> "KineticFriction":
        """A kinetic law from its r < 0 branch (and optionally its r > 0 branch).

        Parameters
        ----------
        neg : sympy expression in :data:`R` (and :data:`GAMMA`, :data:`DELTA`), or a string in
            the names ``r``, ``gamma``, ``delta`` parsed by :func:`landau.laws.parse.parse_expression`
            (never evaluated).
        pos : the same for r > 0; default the odd reflection −neg(−r).
        gamma, delta : values of the parameters γ, δ if the expressions use them.
        names : how the two branches are named in error messages (e.g. the CLI's option names).

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
        def as_expr(x, what):
            if isinstance(x, str):
                from landau.laws.parse import parse_expression
                return parse_expression(x, {"r": R, "gamma": GAMMA, "delta": DELTA}, what=what)
            if isinstance(x, sp.Expr):
                return x
            raise InputError(f"KineticFriction.from_expression: {what} must be a string or a sympy expression")
        n = as_expr(neg, names[0])
        p = -n.subs(R, -R) if pos is None else as_expr(pos, names[1])
        return cls(gamma=float(gamma), delta=float(delta), neg_expr=n, pos_expr=p)

    # ---------------------------------------------------------------- numeric form
    def neg(self, r):
        """Branch r < 0: (1 − δ)/(1 − γ r) + δ for eq. (7)  (> 0: the belt drags the block forward)."""
        return self._neg(r, self.gamma, self.delta)

    def pos(self, r):
        """Branch r > 0: −(1 − δ)/(1 + γ r) − δ for eq. (7)."""
        return self._pos(r, self.gamma, self.delta)

    def dneg(self, r):
        """dF_k/dr on the r < 0 branch (γ(1 − δ)/(1 − γ r)² for eq. (7))."""
        return self._dneg(r, self.gamma, self.delta)

    def dpos(self, r):
        """dF_k/dr on the r > 0 branch (γ(1 − δ)/(1 + γ r)² for eq. (7))."""
        return self._dpos(r, self.gamma, self.delta)

    def d3neg(self, r):
        """d³F_k/dr³ on the r < 0 branch (6γ³(1 − δ)/(1 − γ r)⁴ for eq. (7))."""
        return self._d3neg(r, self.gamma, self.delta)

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
        return self.neg_expr == _PAPER_NEG and self.pos_expr == _PAPER_POS

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
                Parameter("delta", float(self.delta), "", SOURCE, "residual kinetic level δ", positive=False))

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
        unknown = sorted(set(values) - {"gamma", "delta"})
        if unknown:
            raise InputError(f"law {self.name!r} has no parameter(s) {', '.join(unknown)}")
        import dataclasses

        return dataclasses.replace(self, **{k: float(v) for k, v in values.items()})

    def latex(self) -> str:
        """The two branches as one line of LaTeX.

        Returns
        -------
        str
        """
        return (rf"F_k(r) = {sp.latex(self.neg_expr)}\ (r < 0),\quad "
                rf"F_k(r) = {sp.latex(self.pos_expr)}\ (r > 0)")

    def __repr__(self) -> str:
        if self.is_paper_law:
            return f"KineticFriction(γ={self.gamma:g}, δ={self.delta:g})  # Galvanetto 2004 eq. (7)"
        return (f"KineticFriction(r<0: {self.neg_expr}, r>0: {self.pos_expr}, "
                f"γ={self.gamma:g}, δ={self.delta:g})")


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
