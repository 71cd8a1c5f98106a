"""Rate-and-state friction laws declared as data.

A :class:`FrictionLaw` is the friction coefficient μ(v, φ₁…φₙ) and the rate of each
state variable dφᵢ/dt, as sympy expressions over the slip rate ``v``, the states and
named parameters.  **Sign convention:** the law declares dφ/dt itself; Putelat et al.
(2010) write dφ/dt = −G(v, φ), so G = −rate (e.g. the Dieterich law, eq. 28,
G = −1 + vφ/L, is declared as ``rate = 1 - v*phi/L``).

The slip rate is always ``v``; the driving velocity ``V`` belongs to the mechanical
system, never to the law.  Velocities in m/s, lengths in m, times in s.

Writing a new law takes a few lines::

    from landau.laws import FrictionLaw
    law = FrictionLaw.from_strings(
        "my-law", mu="a_v + a*log(v/V_s) + b*log(V_s*phi/L)",
        state={"phi": "1 - v*phi/L"})          # Table 1 values for a_v, a, b, L, V_s

Strings are parsed by :mod:`landau.laws.parse` (a whitelist walk of the syntax tree), never
evaluated.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Mapping

import numpy as np
import sympy as sp

from landau.errors import DomainError, InputError
from landau.laws.base import Law
from landau.laws.parse import parse_expression
from landau.support.lambdify import lambdify_positional

#: the slip-rate symbol shared by every law
v = sp.Symbol("v", positive=True)


#: names a law may not declare, with what they already mean: the mechanical system's symbols,
#: the engine's internal symbols and the names of the expression language and generated code
RESERVED: dict[str, str] = {
    "v": "the slip rate of every law",
    "V": "the driving velocity (give it with --V, or as the first argument of evaluate)",
    "k": "the spring stiffness, the bifurcation parameter: its critical value k_c is what is computed",
    "M": "the block mass, a system parameter (--param M=...)",
    "g": "the gravitational acceleration, a system parameter (--param g=...)",
    "sigma": "the normal load, a system parameter (--param sigma=...)",
    "X": "the slip coordinate of the spring-block",
    "u": "the slip-rate perturbation of the spring-block",
    "omega": "the onset frequency", "W": "the squared onset frequency",
    "Gamma_bar": "an amplitude-equation coefficient", "Omega_bar": "an amplitude-equation coefficient",
    "Lambda": "the Landau coefficient", "chi": "an amplitude-equation coefficient",
    "pi": "the constant pi", "E": "the constant e", "I": "the imaginary unit",
    "nan": "not-a-number", "inf": "infinity", "oo": "infinity", "zoo": "complex infinity",
    "numpy": "a module name in generated code", "mpmath": "a module name in generated code",
    "math": "a module name in generated code", "builtins": "a module name in generated code",
    "DiracDelta": "a function in generated code", "Heaviside": "a function in generated code",
}
#: patterns of internal names (derivative atoms of the engine, e.g. d2_u_phi_phi, dp_u)
_RESERVED_PATTERNS = (r"d\d+_\w*", r"dp_\w*")


def _check_name(name: str, what: str) -> None:
    """Names become sympy symbols and, in generated code, variable names: plain identifiers
    only, and none that already means something to the mechanical system or the engine
    (:data:`RESERVED`) — a law declaring ``V`` or ``k`` would otherwise be merged with the
    driving velocity or the stiffness and give a wrong answer."""
    import keyword
    import re

    from landau.laws.parse import FUNCTIONS

    if not isinstance(name, str) or not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", name) or keyword.iskeyword(name):
        raise InputError(f"{what} name {name!r} must be a plain identifier (a letter, then letters, digits, _)")
    if name in RESERVED and name != "v":
        raise InputError(f"{what} name {name!r} is reserved: it is {RESERVED[name]}; choose another name")
    if name in FUNCTIONS:
        raise InputError(f"{what} name {name!r} is reserved: it is a function of the expression language")
    if any(re.fullmatch(pat, name) for pat in _RESERVED_PATTERNS):
        raise InputError(f"{what} name {name!r} is reserved for the engine's derivative symbols; choose another name")


#: sympy function classes a law may contain (those the string parser produces)
def _allowed_functions() -> tuple[type, ...]:
    return (sp.log, sp.exp, sp.sin, sp.cos, sp.tan, sp.sinh, sp.cosh, sp.tanh, sp.asinh, sp.acosh, sp.atanh,
            sp.atan, sp.Abs, sp.sign)


#: time budget of the symbolic steady-state solve (s); beyond it the steady state is solved numerically
SOLVE_SECONDS = 10.0


def _solve_steady_state(rates, states):
    """The unique positive closed-form solution of rates = 0, or None (runs in a bounded child)."""
    try:
        sols = sp.solve(list(rates), list(states), dict=True)
    except (NotImplementedError, ValueError, TypeError):
        return None
    good = []
    allowed = _allowed_functions()
    for sol in sols:
        if all(s in sol for s in states):
            vals = tuple(sp.simplify(sol[s]) for s in states)
            # a closed form in a function outside the law's own vocabulary (LambertW, Piecewise, …)
            # is not one the code generators compile, and often not one float64 can evaluate
            # (LambertW(v·exp(v/c)/c) overflows long before its value does): the steady state is
            # then solved numerically, as for a law sympy cannot solve
            if any(not isinstance(f, allowed) for val in vals for f in val.atoms(sp.Function)):
                return None
            if all(val.is_positive is not False and not val.has(sp.I) and val.is_extended_real is not False
                   for val in vals):
                good.append(vals)
    return good[0] if len(good) == 1 else None


@dataclass(frozen=True)
class Parameter:
    """A named constant of a law with its default value, units and provenance.

    Parameters
    ----------
    name : str
        The symbol's name in the law's expressions (e.g. ``"a"``, ``"V_s"``).
    default : float or None
        The published value (None: the user must give one).
    units : str, optional
        SI units, e.g. ``"m/s"``.
    source : str, optional
        Where the default comes from (paper, table).
    description : str, optional
        What the constant is.
    positive : bool, optional
        Whether the constant is positive (its sympy symbol is declared so; default True).
    """

    name: str
    default: float | None
    units: str = ""
    source: str = ""
    description: str = ""
    positive: bool = True

    @property
    def symbol(self) -> sp.Symbol:
        """The sympy symbol (declared positive, or real)."""
        return sp.Symbol(self.name, positive=True) if self.positive else sp.Symbol(self.name, real=True)

    def __repr__(self) -> str:
        return f"{self.name} = {self.default!r} {self.units}".rstrip() + (f"  [{self.source}]" if self.source else "")


def user_parameter(name: str, value, positive: bool = True) -> Parameter:
    """A :class:`Parameter` from a user's value (a number, or a :class:`Parameter` kept as it is).

    Parameters
    ----------
    name : str
        The parameter's name.
    value : float or Parameter
        Its value.
    positive : bool, optional
        Whether its symbol is declared positive (else real).

    Returns
    -------
    Parameter

    Raises
    ------
    InputError
        The value is not a finite number.
    """
    if isinstance(value, Parameter):
        return value
    try:
        x = float(value)
    except (TypeError, ValueError, OverflowError):
        raise InputError(f"parameter {name!r} must be a number, got {value!r}") from None
    if not math.isfinite(x):
        raise InputError(f"parameter {name!r} must be finite, got {value!r}")
    return Parameter(name, x, source="user", positive=positive)


#: Table 1 of Putelat, Dawes & Willis (2010), the parameter set that reproduces their numbers
#: (L = 0.9e-6 m and V_* = 1e-6 m/s; the values of Sec. 3.1 and of the Fig. 15/17 captions do not).
TABLE1: dict[str, Parameter] = {
    p.name: p
    for p in (
        Parameter("a_v", 0.369, "", "Putelat et al. 2010, Table 1", "reference friction coefficient a_v"),
        Parameter("a", 0.0349, "", "Putelat et al. 2010, Table 1", "direct-effect coefficient a"),
        Parameter("b", 0.0489, "", "Putelat et al. 2010, Table 1", "evolution-effect coefficient b"),
        Parameter("L", 0.9e-6, "m", "Putelat et al. 2010, Table 1", "memory length L"),
        Parameter("V_s", 1e-6, "m/s", "Putelat et al. 2010, Table 1", "reference slip rate V_*"),
    )
}


@dataclass(frozen=True, eq=False)
class FrictionLaw(Law):
    """μ(v, φ…) and dφᵢ/dt for any number of states, with parameters and provenance.

    Parameters
    ----------
    name : short CLI name.
    mu : friction coefficient μ (dimensionless), a sympy expression.
    states : the state symbols φᵢ.
    rates : dφᵢ/dt for each state (declared directly; G = −rate in Putelat's notation).
    parameters : every other symbol in ``mu``/``rates``, with defaults and provenance.
    source : paper and equation numbers.
    steady_state : optional closed forms φᵢ,ss(v); solved with sympy when omitted.
    """

    name: str
    mu: sp.Expr
    states: tuple[sp.Symbol, ...]
    rates: tuple[sp.Expr, ...]
    parameters: tuple[Parameter, ...] = ()
    source: str = ""
    description: str = ""
    steady_state: tuple[sp.Expr, ...] | None = None

    def __post_init__(self) -> None:
        if len(self.states) == 0:
            raise InputError(f"law {self.name!r}: at least one state variable is needed")
        if len(self.states) != len(self.rates):
            raise InputError(f"law {self.name!r}: {len(self.states)} states but {len(self.rates)} rates")
        if not isinstance(self.name, str) or not self.name.strip() or len(self.name) > 200:
            raise InputError(f"a law needs a name (a non-empty string of at most 200 characters), got {self.name!r}")
        for what, expr in [("mu", self.mu), *(("a rate", r) for r in self.rates)]:
            if not isinstance(expr, sp.Expr):
                raise InputError(f"law {self.name!r}: {what} must be a sympy expression, got {type(expr).__name__} "
                                 "(use FrictionLaw.from_strings for strings)")
        for s in self.states:
            if not isinstance(s, sp.Symbol):
                raise InputError(f"law {self.name!r}: states must be sympy symbols, got {s!r}")
            if s == v:
                raise InputError(f"law {self.name!r}: 'v' is the slip rate and cannot be a state")
            _check_name(s.name, "state")
        for p in self.parameters:
            _check_name(p.name, "parameter")
        names = [s.name for s in self.states] + [p.name for p in self.parameters]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise InputError(f"law {self.name!r}: name {dup[0]!r} is declared twice")
        for s in self.states:
            if f"{s.name}_0" in names:
                raise InputError(f"law {self.name!r}: name '{s.name}_0' is reserved for the steady state of {s.name}")
        known = {v, *self.states, *(p.symbol for p in self.parameters)}
        allowed = _allowed_functions()
        for what, expr in [("mu", self.mu), *((f"d{s}/dt", r) for s, r in zip(self.states, self.rates, strict=True))]:
            extra = expr.free_symbols - known
            if extra:
                raise InputError(f"law {self.name!r}: {what} uses undeclared symbol(s) "
                                 + ", ".join(sorted(map(str, extra))))
            bad = [f for f in expr.atoms(sp.Function) if not isinstance(f, allowed)]
            if bad:
                raise InputError(f"law {self.name!r}: {what} uses the function {type(bad[0]).__name__!r}, which is "
                                 "not one the toolkit can differentiate and compile (allowed: "
                                 + ", ".join(sorted({c.__name__ for c in allowed})) + ")")
            if expr.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
                raise InputError(f"law {self.name!r}: {what} is not finite")
            if expr.has(sp.I) or expr.is_extended_real is False:
                raise DomainError(f"law {self.name!r}: {what} = {str(expr)[:80]} is not real for v > 0, states > 0")
        if v not in self.mu.free_symbols:
            raise InputError(f"law {self.name!r}: mu does not depend on the slip rate v")
        if self.steady_state is not None and len(self.steady_state) != len(self.states):
            raise InputError(f"law {self.name!r}: {len(self.states)} states but {len(self.steady_state)} steady states")
        for e in self.steady_state or ():
            bad = [f for f in sp.sympify(e).atoms(sp.Function) if not isinstance(f, allowed)]
            if bad:
                raise InputError(f"law {self.name!r}: the declared steady state uses the function "
                                 f"{type(bad[0]).__name__!r}, which the toolkit cannot compile; leave steady_state "
                                 "out and it is solved numerically")

    # --- construction -------------------------------------------------------------
    @classmethod
    def from_strings(
        cls,
        name: str,
        mu: str,
        state: Mapping[str, str],
        params: Mapping[str, float | Parameter] | None = None,
        *,
        source: str = "user-defined",
        description: str = "",
    ) -> "FrictionLaw":
        """Declare a law from strings, parsed safely.

        ``state`` maps each state name to its rate dφ/dt.  Every other name must be a
        parameter: given in ``params`` (a value or a :class:`Parameter`) or one of the
        Table 1 names (a_v, a, b, L, V_s), which then take their Table 1 values.
        Unknown names are errors naming the symbol.

        Parameters
        ----------
        name : str
            Name of the law.
        mu : str
            Friction coefficient μ in the slip rate ``v``, the states and the parameters,
            e.g. ``"a_v + a*log(v/V_s) + b*log(V_s*phi/L)"`` (``^`` means power).
        state : mapping of str to str
            Each state variable's name and its rate dφ/dt, e.g. ``{"phi": "1 - v*phi/L"}``.
        params : mapping, optional
            Parameter values (floats) or :class:`Parameter` objects.
        source : str, optional
            Provenance (paper and equation), shown by ``landau laws``.
        description : str, optional
            A one-line description.

        Returns
        -------
        FrictionLaw

        Raises
        ------
        InputError
            For an empty state, a reserved name used as a parameter, or an unknown symbol;
            a :class:`~landau.errors.ParseError` names the offending token.
        """
        if not state:
            raise InputError("a law needs at least one state variable (state={'phi': 'rate'})")
        params = dict(params or {})
        if not isinstance(state, Mapping):
            raise InputError("state must map each state name to its rate, e.g. {'phi': '1 - v*phi/L'}")
        from landau.laws.parse import referenced_names

        names: set[str] = set()
        names |= referenced_names(mu, what="mu")
        for sname, text in state.items():
            names |= referenced_names(text, what=f"d{sname}/dt")
        reserved = {"v", *state}
        for s in reserved:
            if s in params:
                raise InputError(f"{s!r} is a {'slip rate' if s == 'v' else 'state'} and cannot also be a parameter")
        for sname in state:
            _check_name(sname, "state")
        for pname in params:
            _check_name(pname, "parameter")
        plist: list[Parameter] = []
        for pname, val in params.items():
            _check_name(pname, "parameter")
            plist.append(user_parameter(pname, val))
        given = {p.name for p in plist}
        from landau.laws.parse import CONSTANTS, FUNCTIONS

        for n in sorted(names - reserved - given - set(FUNCTIONS) - set(CONSTANTS)):
            if n in TABLE1:
                plist.append(TABLE1[n])
        symbols = {"v": v}
        state_syms = []
        for sname in state:
            _check_name(sname, "state")
            sym = sp.Symbol(sname, positive=True)
            symbols[sname] = sym
            state_syms.append(sym)
        for p in plist:
            symbols[p.name] = p.symbol
        mu_expr = parse_expression(mu, symbols, what="mu")
        rates = tuple(parse_expression(r, symbols, what=f"d{s}/dt") for s, r in state.items())
        used = mu_expr.free_symbols.union(*(r.free_symbols for r in rates))
        plist = [p for p in plist if p.symbol in used]
        return cls(name, mu_expr, tuple(state_syms), rates, tuple(plist), source, description)

    # --- parameters ---------------------------------------------------------------
    @property
    def v(self) -> sp.Symbol:
        """The slip-rate symbol v."""
        return v

    def symbol(self, name: str) -> sp.Symbol:
        """The sympy symbol of the slip rate ``"v"``, a state or a parameter.

        Parameters
        ----------
        name : str
            ``"v"``, a state name or a parameter name.

        Returns
        -------
        sympy.Symbol
        """
        if name == "v":
            return v
        for s in self.states:
            if s.name == name:
                return s
        return self.parameter(name).symbol

    # --- steady state -------------------------------------------------------------
    @cached_property
    def steady_state_closed_form(self) -> tuple[sp.Expr, ...] | None:
        """φᵢ,ss(v) solving dφᵢ/dt = 0 at slip rate v, or None if sympy finds no single
        positive closed form within :data:`SOLVE_SECONDS` (then :meth:`steady_state_values`
        solves numerically)."""
        if self.steady_state is not None:
            return tuple(self.steady_state)
        from landau.errors import BudgetError
        from landau.support.budget import run_bounded

        try:
            return run_bounded(_solve_steady_state, (self.rates, self.states), seconds=SOLVE_SECONDS,
                               what=f"closed-form steady state of law {self.name!r}")
        except (BudgetError, RecursionError, MemoryError):
            return None

    @cached_property
    def _numeric_rates(self):
        """Compiled (rates, ∂rates/∂φ) over (v, φ…, parameters…)."""
        args = [v, *self.states, *(p.symbol for p in self.parameters)]
        jac = sp.Matrix(self.rates).jacobian(list(self.states))
        f = lambdify_positional(args, list(self.rates), modules="numpy", cse=True)
        J = lambdify_positional(args, jac.tolist(), modules="numpy", cse=True)
        return f, J

    def steady_state_values(self, vs, params: Mapping[str, float | np.ndarray]) -> np.ndarray:
        """φᵢ,ss at slip rates ``vs`` (any shape), shape (number of states, *vs.shape).

        The closed form where there is one; otherwise every positive root of dφ/dt = 0 is
        found numerically at each point, and the one that is *stable* at fixed slip rate
        (every eigenvalue of ∂(dφ/dt)/∂φ has a negative real part — the state relaxes to it,
        so it is the steady sliding the spring–block settles on) is chosen.

        Parameters
        ----------
        vs : float or array_like
            Slip rates in m/s.
        params : mapping of str to float
            Values of the law's parameters.

        Returns
        -------
        numpy.ndarray
            The steady states, shape (number of states, *vs.shape).

        Raises
        ------
        DomainError
            No positive stable steady state, or more than one (the law is then ambiguous:
            declare ``steady_state`` explicitly), or a steady state that is not finite.
        """
        vs = np.asarray(vs, dtype=float)
        values = [params[p.name] for p in self.parameters]
        ss = self.steady_state_closed_form
        if ss is not None:
            fn = self._closed_steady_state
            with np.errstate(all="ignore"):
                out = np.array([np.broadcast_to(np.asarray(x, dtype=float), vs.shape) for x in fn(vs, *values)])
            if np.all(np.isfinite(out)) and np.all(out > 0):
                self._check_stable(vs, out, params)
        else:
            flat = vs.ravel()
            pars = [np.broadcast_to(np.asarray(x, dtype=float), vs.shape).ravel() for x in values]
            out = np.empty((len(self.states), flat.size))
            if len(self.states) == 1:
                out[0] = self._numeric_steady_state_1(flat, pars)
            else:
                for i, vi in enumerate(flat):
                    out[:, i] = self._numeric_steady_state(float(vi), [float(x[i]) for x in pars])
            out = out.reshape((len(self.states), *vs.shape))
        if not np.all(np.isfinite(out)) or np.any(out <= 0):
            idx = np.argwhere(~(np.isfinite(out) & (out > 0)))[0]
            raise DomainError(f"law {self.name!r}: steady state {self.states[idx[0]]} = {out[tuple(idx)]:g} at "
                              f"v = {float(vs.ravel()[0] if vs.ndim == 0 else vs[tuple(idx[1:])]):g} m/s "
                              "is not finite and positive")
        return out

    @cached_property
    def _closed_steady_state(self):
        return lambdify_positional([v, *(p.symbol for p in self.parameters)], list(self.steady_state_closed_form),
                                   modules="numpy")

    def _check_stable(self, vs: np.ndarray, phis: np.ndarray, params: Mapping[str, float | np.ndarray]) -> None:
        """Refuse a closed-form steady state that is unstable at fixed slip rate (the state runs
        away from it, so the block never slides steadily there)."""
        _, J = self._numeric_rates
        n = len(self.states)
        values = [np.broadcast_to(np.asarray(params[p.name], dtype=float), vs.shape) for p in self.parameters]
        with np.errstate(all="ignore"):
            rows = J(vs, *phis, *values)
            jac = np.empty((*vs.shape, n, n))
            for i in range(n):
                for j in range(n):
                    jac[..., i, j] = np.broadcast_to(np.asarray(rows[i][j], dtype=float), vs.shape)
        ok = np.all(np.isfinite(jac), axis=(-2, -1))
        growth = np.full(vs.shape, -1.0)
        if n == 1:
            growth = np.where(ok, jac[..., 0, 0], -1.0)
        elif np.any(ok):
            growth[ok] = np.linalg.eigvals(jac[ok]).real.max(axis=-1)
        bad = ok & (growth >= 0)
        if np.any(bad):
            at = tuple(np.argwhere(np.atleast_1d(bad))[0]) if vs.ndim else ()
            raise DomainError(f"law {self.name!r}: the steady state at v = {float(vs[at]):g} m/s is not stable at "
                              "fixed slip rate (an eigenvalue of d(rates)/d(states) has a non-negative real part)")

    #: the log grid of φ on which the sign changes of a single state's rate are looked for (60 decades)
    _PHI_GRID = np.logspace(-30, 30, 1201)

    def _numeric_steady_state_1(self, vs: np.ndarray, pars: list[np.ndarray]) -> np.ndarray:
        """φ_ss of a one-state law at every slip rate of ``vs`` (1-D): every sign change of the rate
        on a log grid of φ over 60 decades (one vectorised evaluation for all points), refined by
        Brent in log φ; the stable root (∂(dφ/dt)/∂φ < 0) is kept, exactly one per point."""
        from scipy.optimize import brentq

        f, J = self._numeric_rates
        grid = self._PHI_GRID
        out = np.empty(vs.size)
        chunk = 512   # points per vectorised evaluation (512 × 1201 values, 5 MB)
        with np.errstate(all="ignore"):
            for start in range(0, vs.size, chunk):
                sl = slice(start, min(start + chunk, vs.size))
                n = sl.stop - sl.start
                r = np.asarray(f(vs[sl, None], grid[None, :], *(x[sl, None] for x in pars))[0], dtype=float)
                r = np.broadcast_to(r, (n, grid.size))
                fin = np.isfinite(r)
                change = fin[:, :-1] & fin[:, 1:] & (r[:, :-1] * r[:, 1:] < 0)
                exact = fin & (r == 0)
                for k in range(n):
                    i = sl.start + k
                    vi, values = float(vs[i]), [float(x[i]) for x in pars]
                    g = lambda lp, vi=vi, values=values: float(np.asarray(f(vi, math.exp(lp), *values)[0],
                                                                          dtype=float))
                    roots = [float(grid[j]) for j in np.flatnonzero(exact[k])]
                    roots += [math.exp(brentq(g, math.log(grid[j]), math.log(grid[j + 1]), xtol=1e-15))
                              for j in np.flatnonzero(change[k])]
                    out[i] = self._pick_stable(vi, values, [np.array([x]) for x in roots])[0]
        return out

    def _pick_stable(self, vi: float, values: list[float], roots: list[np.ndarray]) -> list[float]:
        """The one root at which every eigenvalue of ∂(rates)/∂φ has a negative real part; a
        :class:`DomainError` when there is none or more than one."""
        _, J = self._numeric_rates
        n = len(self.states)
        stable = []
        with np.errstate(all="ignore"):
            for x in roots:
                jac = np.asarray(J(vi, *x, *values), dtype=float).reshape(n, n)
                if np.all(np.isfinite(jac)) and np.all(np.linalg.eigvals(jac).real < 0):
                    stable.append(x)
        if len(stable) == 1:
            return [float(z) for z in stable[0]]
        what = ", ".join("(" + ", ".join(f"{z:.6g}" for z in x) + ")" for x in (stable or roots)) or "none"
        if not stable:
            raise DomainError(f"law {self.name!r}: no stable positive steady state at v = {vi:g} m/s "
                              f"(positive roots of the rates: {what})")
        raise DomainError(f"law {self.name!r}: {len(stable)} stable positive steady states at v = {vi:g} m/s: "
                          f"{what}; declare the one you mean with FrictionLaw(..., steady_state=...)")

    def _numeric_steady_state(self, vi: float, values: list[float]) -> list[float]:
        """The stable positive steady state of a law with several states at slip rate ``vi``:
        Powell's hybrid method in log φ from 51 starts, the distinct genuine roots kept."""
        from scipy.optimize import root

        f, J = self._numeric_rates
        n = len(self.states)
        roots: list[np.ndarray] = []
        with np.errstate(all="ignore"):
            fun = lambda z: np.asarray(f(vi, *np.exp(z), *values), dtype=float)
            for start in np.linspace(-25, 25, 51):
                sol = root(fun, np.full(n, start), method="hybr", tol=1e-14)
                if np.all(np.isfinite(sol.x)):
                    x = np.exp(sol.x)
                    res = fun(sol.x)
                    # a root, not a stall: the residual is round-off of the rate's own terms
                    jac = np.asarray(J(vi, *x, *values), dtype=float).reshape(n, n)
                    scale = np.abs(jac) @ np.abs(x) + 1e-300
                    if (np.all(np.isfinite(res)) and np.all(np.abs(res) <= 1e-9 * np.maximum(scale, 1.0))
                            and not any(np.allclose(x, y, rtol=1e-8) for y in roots)):
                        roots.append(x)
        return self._pick_stable(vi, values, roots)

    def check_real(self, vs, phis, params: Mapping[str, float | np.ndarray]) -> None:
        """Refuse (:class:`DomainError`) a law whose μ, rates or their first derivatives are not
        real and finite at slip rates ``vs`` and states ``phis`` (the numeric half of the
        reality check; the symbolic half runs when the law is built).

        Parameters
        ----------
        vs : array_like
            Slip rates in m/s.
        phis : sequence of array_like
            The states at those slip rates (one array per state).
        params : mapping of str to float
            Values of the law's parameters.

        Returns
        -------
        None
        """
        exprs = self._reality_exprs
        if not exprs:       # real and finite for every v > 0, states > 0, proved symbolically
            return
        with np.errstate(all="ignore"):
            args = [np.asarray(vs, dtype=complex), *(np.asarray(p, dtype=complex) for p in phis),
                    *(np.asarray(params[p.name], dtype=complex) for p in self.parameters)]
            for label, fn in exprs:
                val = np.asarray(fn(*args), dtype=complex)
                bad = ~np.isfinite(val) | (np.abs(val.imag) > 1e-9 * np.maximum(np.abs(val.real), 1e-300))
                if np.any(bad):
                    vb = np.broadcast_to(np.asarray(vs, dtype=float), np.shape(bad))
                    i = tuple(np.argwhere(np.atleast_1d(bad))[0]) if np.ndim(bad) else ()
                    x = complex(np.broadcast_to(val, np.shape(bad))[i])
                    raise DomainError(f"law {self.name!r}: {label} = {x:.6g} at steady sliding, v = {float(vb[i]):g} "
                                      "m/s: the law must be real and finite for v > 0, states > 0")

    @cached_property
    def _reality_exprs(self):
        args = [v, *self.states, *(p.symbol for p in self.parameters)]
        exprs = []
        for label, e in [("mu", self.mu), *((f"d{s}/dt", r) for s, r in zip(self.states, self.rates, strict=True))]:
            exprs.append((label, e))
            exprs += [(f"d({label})/d{x}", sp.diff(e, x)) for x in (v, *self.states) if x in e.free_symbols]
        if all(e.is_extended_real and e.is_finite for _, e in exprs):
            return []
        return [(label, lambdify_positional(args, e, modules="numpy")) for label, e in exprs]

    def mu_ss(self) -> sp.Expr:
        """Steady-state friction coefficient μ_ss(v) (closed form).

        Returns
        -------
        sympy.Expr
            μ_ss in v and the parameters.

        Raises
        ------
        InputError
            The law's steady state has no closed form.
        """
        ss = self.steady_state_closed_form
        if ss is None:
            raise InputError(f"law {self.name!r}: no closed-form steady state; use numeric evaluation")
        return self.mu.subs(dict(zip(self.states, ss, strict=True)))

    # --- display ------------------------------------------------------------------
    def latex(self) -> str:
        """The law (μ and the state rates) as one line of LaTeX.

        Returns
        -------
        str
        """
        lines = [rf"\mu = {sp.latex(self.mu)}"]
        for s, r in zip(self.states, self.rates, strict=True):
            lines.append(rf"\frac{{d{sp.latex(s)}}}{{dt}} = {sp.latex(r)}")
        return r",\quad ".join(lines)

    def __repr__(self) -> str:
        rates = ", ".join(f"d{s}/dt = {r}" for s, r in zip(self.states, self.rates, strict=True))
        return f"FrictionLaw({self.name!r}: mu = {self.mu}; {rates}; source={self.source!r})"

