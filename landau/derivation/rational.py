"""Exact cancellation for laws whose steady-state derivatives are rational in V.

For the Dieterich, Ruina and modified Dieterich laws every derivative at steady sliding is a
rational function of V (the logarithms vanish there).  With the parameters fixed (as the exact
binary rationals of the floats given) the Fredholm code of :mod:`landau.derivation.fredholm` runs in
ℚ(V)(ω): rational functions of V, cancelled as they are made, with the onset frequency adjoined
by ω² = ω_c²(V) (:class:`QuadraticElement`).  Each coefficient comes out as P(V) + ω·Q(V), P
and Q single cancelled fractions of polynomials with exact coefficients — e.g. Λ_D ∝ M V³(…)/(…)
with the factor V³ explicit.  A coefficient that vanishes identically (Λ_D at M = 0) comes out
as exactly 0.  With the parameters left symbolic the same code gives the closed forms of
:func:`closed_form` (multivariate gcds by FLINT: about a second).

Evaluation (:meth:`RationalCoefficient.evaluate`) is Horner's rule in float64 with a running
error bound (Higham, *Accuracy and Stability of Numerical Algorithms*, eq. 5.3:
|p̂ − p| ≤ γ₂ₙ Σ|cᵢ||V|ⁱ); a point whose bound exceeds the requested accuracy is evaluated
exactly in ℚ (the float V is an exact dyadic rational) and rounded once, ω = sqrt(ω_c²)
taken at 40 digits.  No value is returned without either a proof of its accuracy or an
exact computation.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from dataclasses import field as dc_field
from fractions import Fraction

import mpmath
import numpy as np
import sympy as sp
from sympy import QQ
from sympy.polys.fields import field

from landau.derivation.fredholm import cubic_coefficient, linear_coefficient, null_vectors
from landau.support.cx import as_expr
from landau.systems.system import V

_U = float(np.finfo(np.float64).eps) / 2
_DPS = 40


def _fraction(c) -> Fraction:
    return Fraction(int(c.numerator), int(c.denominator))


def _log2(c: Fraction) -> int:
    return abs(c.numerator).bit_length() - c.denominator.bit_length()


@dataclass(frozen=True)
class Polynomial:
    """Σ cᵢ Vⁱ with exact rational coefficients (ascending powers).

    Evaluated in float64 as 2^e Σ c'ᵢ sⁱ with s = V/2^k: the powers of two k, e (chosen by a
    least-squares balance of log₂|cᵢ| + k·i) keep the coefficients inside the float range —
    a cancelled Λ has coefficients beyond 1e300 for some laws — and are exact, so the error
    bound is unchanged."""

    coeffs: tuple[Fraction, ...]
    _desc: np.ndarray = dc_field(init=False, repr=False, compare=False)
    _abs: np.ndarray = dc_field(init=False, repr=False, compare=False)
    _k: int = dc_field(init=False, repr=False, compare=False)
    _e: int = dc_field(init=False, repr=False, compare=False)
    _safe: bool = dc_field(init=False, repr=False, compare=False)

    def __post_init__(self):
        nz = [(i, _log2(c)) for i, c in enumerate(self.coeffs) if c]
        k = 0
        if len(nz) > 1:
            i_, l_ = np.array(nz, dtype=float).T
            k = -round(float(np.polyfit(i_, l_, 1)[0]))
        scaled = [c * Fraction(2) ** (k * i) for i, c in enumerate(self.coeffs)]
        e = max((_log2(c) for c in scaled if c), default=0)
        scaled = [c / Fraction(2) ** e for c in scaled]
        desc = np.array([float(c) for c in reversed(scaled)] or [0.0])
        # not strict: the zero polynomial has no coefficients but ``desc`` = [0.0]
        safe = all(np.isfinite(x) and (x != 0 or c == 0) for x, c in zip(desc, reversed(scaled), strict=False))
        for name, val in (("_desc", desc), ("_abs", np.abs(desc)), ("_k", k), ("_e", e), ("_safe", safe)):
            object.__setattr__(self, name, val)

    @classmethod
    def from_ring(cls, p) -> Polynomial:
        """From a univariate sympy PolyElement in V."""
        coeffs: dict[int, Fraction] = {}
        for (i,), c in p.terms():
            coeffs[i] = _fraction(c)
        n = max(coeffs, default=-1) + 1
        return cls(tuple(coeffs.get(i, Fraction(0)) for i in range(n)))

    @property
    def is_zero(self) -> bool:
        return all(c == 0 for c in self.coeffs)

    def evaluate(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
        """(p(x)/2^e, relative error bound, e) in float64; x > 0.  A batch of
        :data:`~landau.derivation.precision.BOUNDED_MIN` points or more is evaluated by the
        compiled :func:`landau.codegen.horner.horner_bounded` (one pass, the same bits)."""
        from landau.derivation.precision import BOUNDED_MIN

        factor = (2 * len(self._desc) + 1) * _U
        if np.size(x) >= BOUNDED_MIN:
            from landau.codegen.horner import horner_bounded

            val, rel = horner_bounded(self._desc, self._abs, self._k, x, factor, self._safe)
            return val, rel, self._e
        with np.errstate(all="ignore"):
            s = np.ldexp(x, -self._k)
            val = np.polyval(self._desc, s)
            mag = np.polyval(self._abs, s)
            rel = factor * mag / np.abs(val)
        ok = np.isfinite(rel) & self._safe
        return val, np.where(ok, rel, np.inf), self._e

    def exact(self, x: Fraction) -> Fraction:
        out = Fraction(0)
        for c in reversed(self.coeffs):
            out = out * x + c
        return out


@dataclass(frozen=True)
class RationalFunction:
    """N(V)/D(V), cancelled."""

    num: Polynomial
    den: Polynomial

    @classmethod
    def from_field(cls, f) -> RationalFunction:
        return cls(Polynomial.from_ring(f.numer), Polynomial.from_ring(f.denom))

    @property
    def is_zero(self) -> bool:
        return self.num.is_zero

    def evaluate(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        n, rn, en = self.num.evaluate(x)
        d, rd, ed = self.den.evaluate(x)
        with np.errstate(all="ignore"):
            val = np.ldexp(n / d, en - ed)
        return val, np.where(np.isfinite(val), rn + rd + _U, np.inf)

    def exact(self, x: Fraction) -> Fraction | None:
        d = self.den.exact(x)
        return None if d == 0 else self.num.exact(x) / d


@dataclass(frozen=True)
class RationalCoefficient:
    """value(V) = P(V) + ω_c(V)·Q(V), P and Q cancelled fractions in V (parameters fixed)."""

    name: str
    P: RationalFunction
    Q: RationalFunction

    @property
    def identically_zero(self) -> bool:
        return self.P.is_zero and self.Q.is_zero

    def evaluate(self, Vs: np.ndarray, omega: np.ndarray,
                 omega_rel: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """(value, relative error bound) in float64; ``omega_rel`` bounds the error of ``omega``."""
        p, rp = self.P.evaluate(Vs)
        if self.Q.is_zero:
            return p, rp
        q, rq = self.Q.evaluate(Vs)
        if self.P.is_zero:
            return omega * q, rq + omega_rel + _U
        with np.errstate(all="ignore"):
            wq = omega * q
            val = p + wq
            err = np.abs(p) * (rp + _U) + np.abs(wq) * (rq + omega_rel + 2 * _U)
            rel = err / np.abs(val)
        return val, np.where(np.isfinite(rel), rel, np.inf)

    def __call__(self, Vs: np.ndarray, omega: np.ndarray) -> np.ndarray:
        return self.evaluate(np.asarray(Vs, dtype=float), np.asarray(omega, dtype=float), 0.0)[0]

    def exact(self, V0: float, W: RationalFunction) -> float:
        """The value at V0 computed exactly in ℚ (ω = sqrt(ω_c²) at 40 digits), rounded once."""
        x = Fraction(V0)
        p, q = self.P.exact(x), self.Q.exact(x)
        if p is None or q is None:
            return float("nan")
        if q == 0:
            return float(p)
        w2 = W.exact(x)
        if w2 is None or w2 <= 0:
            return float("nan")
        with mpmath.workdps(_DPS):
            om = mpmath.sqrt(mpmath.mpf(w2.numerator) / w2.denominator)
            return float(mpmath.mpf(p.numerator) / p.denominator + om * mpmath.mpf(q.numerator) / q.denominator)


@dataclass(frozen=True)
class RationalForms:
    """k_c, ω_c² and the requested coefficients of one law at one parameter set."""

    kc: RationalFunction
    W: RationalFunction
    coefficients: dict[str, RationalCoefficient]

    def __getitem__(self, name: str) -> RationalCoefficient:
        return self.coefficients[name]

    def __contains__(self, name: str) -> bool:
        return name in self.coefficients

    def evaluate(self, Vs: np.ndarray, names: Sequence[str], rel: float) -> dict[str, np.ndarray]:
        """{"kc", "W", *names}: float64 where the error bound is ≤ ``rel``, else exact."""
        Vs = np.asarray(Vs, dtype=float)
        kc, rk = self.kc.evaluate(Vs)
        self._fix(Vs, kc, rk, rel, self.kc.exact)
        W, rW = self.W.evaluate(Vs)
        fixed = self._fix(Vs, W, rW, rel, self.W.exact)
        with np.errstate(all="ignore"):
            om = np.sqrt(np.where(W > 0, W, np.nan))
        rom = np.where(fixed, _U, rW / 2 + _U)
        out = {"kc": kc, "W": W}
        for n in names:
            c = self.coefficients[n]
            if c.identically_zero:
                out[n] = np.zeros_like(Vs)
                continue
            val, r = c.evaluate(Vs, om, rom)
            for i in np.flatnonzero((r > rel) & (W > 0)):
                val.flat[i] = c.exact(float(Vs.flat[i]), self.W)
            out[n] = val
        return out

    @staticmethod
    def _fix(Vs, val, r, rel, exact) -> np.ndarray:
        """Replace the values whose bound exceeds ``rel`` by the exact ones; return where."""
        bad = r > rel
        for i in np.flatnonzero(bad):
            e = exact(Fraction(float(Vs.flat[i])))
            val.flat[i] = float("nan") if e is None else float(e)
        return bad


def _exact(x: float) -> sp.Rational:
    """The exact binary value of the float the caller passed (not its decimal reading): near a
    zero of Λ the coefficient is so sensitive to the parameters that 0.0349 and
    float(0.0349) give values differing in the 8th digit."""
    f = Fraction(float(x))
    return sp.Rational(f.numerator, f.denominator)


class QuadraticElement:
    """a + b·ω in ℚ(V)(ω), ω² = W ∈ ℚ(V): the onset frequency adjoined to the field of
    rational functions.  Keeping ω out of the polynomial ring (instead of a second
    generator reduced at the end) keeps every gcd univariate — several times faster."""

    __slots__ = ("W", "a", "b")

    def __init__(self, a, b, W):
        self.a, self.b, self.W = a, b, W

    def _lift(self, o) -> QuadraticElement:
        return o if isinstance(o, QuadraticElement) else QuadraticElement(self.W.field(o), self.W.field(0), self.W)

    def __add__(self, o):
        o = self._lift(o)
        return QuadraticElement(self.a + o.a, self.b + o.b, self.W)

    __radd__ = __add__

    def __sub__(self, o):
        o = self._lift(o)
        return QuadraticElement(self.a - o.a, self.b - o.b, self.W)

    def __rsub__(self, o):
        return self._lift(o) - self

    def __neg__(self):
        return QuadraticElement(-self.a, -self.b, self.W)

    def __mul__(self, o):
        if not isinstance(o, QuadraticElement):
            return QuadraticElement(self.a * o, self.b * o, self.W)
        return QuadraticElement(self.a * o.a + self.b * o.b * self.W, self.a * o.b + self.b * o.a, self.W)

    __rmul__ = __mul__

    def __truediv__(self, o):
        if not isinstance(o, QuadraticElement):
            return QuadraticElement(self.a / o, self.b / o, self.W)
        norm = o.a * o.a - o.b * o.b * self.W
        return self * QuadraticElement(o.a / norm, -o.b / norm, self.W)

    def __eq__(self, o):
        o = self._lift(o)
        return self.a == o.a and self.b == o.b

    __hash__ = None  # type: ignore[assignment]  # compared by value, not hashable


class _FlintFraction:
    """n/d in ℚ(x₁…xₘ) with n, d in ℤ[x₁…xₘ] (FLINT multivariate polynomials), kept reduced:
    gcd(n, d) = 1 and d with a positive leading coefficient.  The same interface as the
    elements of ``sympy.polys.fields`` that :class:`QuadraticElement` and the Fredholm code
    use; FLINT's multivariate gcd makes the symbolic-parameter closed forms ~100x faster."""

    __slots__ = ("num", "den", "field")

    def __init__(self, num, den, field: "_FlintField", reduce: bool = True):
        if reduce:
            if num.is_zero():
                den = field.one
            else:
                g = num.gcd(den)
                if not g.is_one():
                    num, den = num / g, den / g
                if den.leading_coefficient() < 0:
                    num, den = -num, -den
        self.num, self.den, self.field = num, den, field

    def _lift(self, o) -> "_FlintFraction":
        return o if isinstance(o, _FlintFraction) else self.field(o)

    def __add__(self, o):
        o = self._lift(o)
        if self.den == o.den:
            return _FlintFraction(self.num + o.num, self.den, self.field)
        return _FlintFraction(self.num * o.den + o.num * self.den, self.den * o.den, self.field)

    __radd__ = __add__

    def __sub__(self, o):
        return self + (-self._lift(o))

    def __rsub__(self, o):
        return self._lift(o) - self

    def __neg__(self):
        return _FlintFraction(-self.num, self.den, self.field, reduce=False)

    def __mul__(self, o):
        o = self._lift(o)
        if self.num.is_zero() or o.num.is_zero():
            return self.field(0)
        # cross-cancel first: the products stay small
        g1, g2 = self.num.gcd(o.den), o.num.gcd(self.den)
        n = (self.num / g1) * (o.num / g2)
        d = (self.den / g2) * (o.den / g1)
        if d.leading_coefficient() < 0:
            n, d = -n, -d
        return _FlintFraction(n, d, self.field, reduce=False)

    __rmul__ = __mul__

    def __truediv__(self, o):
        o = self._lift(o)
        if o.num.is_zero():
            raise ZeroDivisionError("division by zero in the field of rational functions")
        return self * _FlintFraction(o.den, o.num, self.field, reduce=True)

    def __rtruediv__(self, o):
        return self._lift(o) / self

    def __eq__(self, o):
        try:
            o = self._lift(o)
        except TypeError:
            return NotImplemented
        return self.num == o.num and self.den == o.den

    __hash__ = None  # type: ignore[assignment]  # compared by value, not hashable

    @property
    def numer(self):
        return self.num

    @property
    def denom(self):
        return self.den

    def _poly_expr(self, p) -> sp.Expr:
        return sp.Add(*[sp.Integer(int(c)) * sp.Mul(*[g ** e for g, e in zip(self.field.symbols, m, strict=True) if e])
                        for m, c in p.to_dict().items()])

    def as_expr(self) -> sp.Expr:
        return self._poly_expr(self.num) / self._poly_expr(self.den)

    def factored(self) -> sp.Expr:
        """num/den factored over ℤ (FLINT), as an unevaluated sympy product."""
        def parts(p):
            try:
                c, fs = p.factor()
            except OverflowError:
                # python-flint sorts the factors by a key that overflows on large coefficients or
                # degrees (a law with 3e-9 (v/V_s)^4): the polynomial is kept whole (correct, unfactored)
                return sp.Integer(1), [(self._poly_expr(p), 1)]
            return sp.Integer(int(c)), [(self._poly_expr(f), e) for f, e in fs]

        if self.num.is_zero():
            return sp.Integer(0)
        cn, fn = parts(self.num)
        cd, fd = parts(self.den)
        const = sp.Rational(cn, cd)
        factors = [f ** e for f, e in fn] + [f ** -e for f, e in fd]
        if const != 1 or not factors:
            factors.insert(0, const)
        return sp.Mul(*factors, evaluate=False) if len(factors) > 1 else factors[0]


class _FlintField:
    """ℚ(x₁…xₘ) on FLINT: ``field(3)``, ``field.from_expr(expr)``."""

    def __init__(self, symbols: Sequence[sp.Symbol]):
        import flint

        self.symbols = tuple(symbols)
        self.ctx = flint.fmpz_mpoly_ctx.get(tuple(f"x{i}" for i in range(len(symbols))), "lex")
        self.one = self.ctx.from_dict({(0,) * len(symbols): 1})
        self._sympy, *_ = field(list(symbols), QQ)

    def __call__(self, x) -> _FlintFraction:
        if isinstance(x, _FlintFraction):
            return x
        if isinstance(x, (int, Fraction)) or (isinstance(x, sp.Basic) and x.is_Rational):
            f = Fraction(int(sp.Integer(x).p), 1) if isinstance(x, int) else Fraction(
                int(sp.Rational(x).p), int(sp.Rational(x).q)) if isinstance(x, sp.Basic) else x
            zero = (0,) * len(self.symbols)
            return _FlintFraction(self.ctx.from_dict({zero: f.numerator}), self.ctx.from_dict({zero: f.denominator}),
                                  self, reduce=False)
        raise TypeError(f"cannot convert {type(x).__name__} to a rational function")

    def from_expr(self, e: sp.Expr) -> _FlintFraction:
        """A sympy expression rational in the symbols (small: entries of a Jacobian)."""
        f = self._sympy.from_expr(e)
        num, den = dict(f.numer.terms()), dict(f.denom.terms())
        scale = 1
        for c in (*num.values(), *den.values()):
            scale = scale * int(c.denominator) // np.gcd(scale, int(c.denominator))
        conv = lambda t: self.ctx.from_dict({m: int(c * scale) for m, c in t.items()})
        return _FlintFraction(conv(num), conv(den), self)


def _field(gens: Sequence[sp.Symbol]):
    """The field ℚ(gens): FLINT's multivariate polynomials when python-flint is installed and
    there are several generators, else sympy's (pure Python; the univariate ℚ(V) case is
    fast either way)."""
    if len(gens) > 1:
        try:
            return _FlintField(gens)
        except ImportError:
            pass
    K, *_ = field(list(gens), QQ)
    return K


def _fredholm_in_field(d, names: Sequence[str], sub: Mapping[sp.Symbol, sp.Expr], gens: Sequence[sp.Symbol]):
    """The Fredholm code of :mod:`landau.derivation.fredholm` in ℚ(gens)(ω), ω² = ω_c²: returns
    (k_c, ω_c², {name: a + b·ω}) as field elements, or None when a derivative at steady
    state is not rational in ``gens`` (after ``sub``)."""
    if any(n not in ("Gamma_bar", "Omega_bar", "Lambda", "chi") for n in names):
        return None  # the fifth order (Lambda5) has no exactly cancelled route: the general one is used
    J, E, r, c = d._structure()
    kc, W_c = d.hopf.closed_form
    need_cubic = any(n in ("Lambda", "chi") for n in names)
    need_linear = any(n in ("Gamma_bar", "Omega_bar") for n in names)
    fp, Jp = d.jets.parameter_derivatives() if need_linear else ([], [])
    B2 = d.jets.order(2) if need_cubic or any(f != 0 for f in fp) else {}
    C3 = d.jets.order(3) if need_cubic else {}
    atoms = {a: e.xreplace(sub) for a, e in d.jets.atoms.items()}   # after the jets are built
    if not all(e.is_rational_function(*gens) for e in atoms.values()):
        return None
    plain = [sp.Symbol(g.name) for g in gens]
    K = _field(plain)
    local = dict(zip(gens, plain, strict=True))

    def conv_field(e):
        e = as_expr(e).xreplace({d.k: kc}).xreplace(atoms).xreplace(sub).xreplace(local)
        return K.from_expr(e) if e.free_symbols else K(sp.Rational(e))

    Wf = conv_field(W_c)
    zero = K(0)

    def conv(e):
        return QuadraticElement(conv_field(e), zero, Wf)

    om = QuadraticElement(zero, K(1), Wf)
    values: dict[str, QuadraticElement] = {}
    if need_linear or need_cubic:
        Jk = [[conv(x) for x in row] for row in J]
        Ek = [conv(x) for x in E]
        vec = null_vectors(Jk, Ek, om, d.system.normalise, r, c)
        B2k = {k: conv(v) for k, v in B2.items()}
    if need_linear:
        a = linear_coefficient(vec, Jk, [[conv(x) for x in row] for row in Jp], [conv(x) for x in fp], B2k)
        values["Gamma_bar"], values["Omega_bar"] = -a.re, a.im
    if need_cubic:
        b = cubic_coefficient(vec, Jk, Ek, om, B2k, {k: conv(v) for k, v in C3.items()}, conv(sp.Rational(1, 2)))
        values["Lambda"], values["chi"] = 2 * b.re, 2 * b.im
    return conv_field(kc), Wf, {n: values[n] for n in names}


def rational_forms(derivation, names: Sequence[str], params: Mapping[str, float]) -> RationalForms | None:
    """k_c, ω_c² and the requested base coefficients in cancelled form at fixed ``params``, or
    None when some derivative at steady state is not rational in V (then the general route is
    used)."""
    d = derivation
    sub = {s: _exact(params[s.name]) for s in d.args[1:]}
    res = _fredholm_in_field(d, names, sub, [V])
    if res is None:
        return None
    kc, W, values = res
    out = {n: RationalCoefficient(n, RationalFunction.from_field(q.a), RationalFunction.from_field(q.b))
           for n, q in values.items()}
    return RationalForms(RationalFunction.from_field(kc), RationalFunction.from_field(W), out)


def closed_form_parts(derivation, names: Sequence[str]) -> dict | None:
    """Factored closed forms in V and the parameters, for display: {"kc": k_c, "W": ω_c²,
    name: (P, Q)} with each base coefficient = P + ω_c·Q (P, Q factored rational functions);
    None when the law's derivatives at steady state are not rational in V and the parameters.
    One pass of the Fredholm code in ℚ(V, parameters)(ω_c) for all ``names``."""
    from landau.support import cache

    d = derivation
    key = cache.make_key("closed-form-parts", cache.system_key(d.system), sorted(names))
    return cache.cached("closed-form-parts", key, lambda: _closed_form_parts(d, names))


def _closed_form_parts(d, names: Sequence[str]) -> dict | None:
    res = _fredholm_in_field(d, list(names), {}, list(d.args))
    if res is None:
        return None
    kc, W, values = res
    back = {sp.Symbol(g.name): g for g in d.args}
    factor = (lambda x: x.factored()) if isinstance(W, _FlintFraction) else (lambda x: sp.factor(x.as_expr()))
    out: dict = {"kc": factor(kc).xreplace(back), "W": factor(W).xreplace(back)}
    for n, q in values.items():
        out[n] = (factor(q.a).xreplace(back), factor(q.b).xreplace(back))
    return out


def closed_form(derivation, name: str) -> sp.Expr | None:
    """Base coefficient ``name`` as one factored expression in V and the parameters (ω_c
    written as the square root of its cancelled square), or None when the law's derivatives
    at steady state are not rational in V and the parameters.  The field arithmetic runs on
    FLINT's multivariate polynomials (python-flint): about a second per coefficient (Ruina Λ
    ~1 s, Dieterich law with residual strength c ~2 s; sympy's own fields took 20 s and
    ~6 minutes)."""
    parts = closed_form_parts(derivation, [name])
    if parts is None:
        return None
    P, Q = parts[name]
    if Q == 0:
        return P
    return P + sp.sqrt(parts["W"]) * Q

