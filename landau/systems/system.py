"""Mechanical systems as data: E·ẏ = f(y; p), and the spring–block of Putelat et al. (eq. 4).

A :class:`DynamicalSystem` is the general smooth first-order (descriptor) system the
multiple-scales engine works on: states y, right-hand side f, a diagonal "mass" E (1 for
an ODE; a zero entry makes the system a DAE, which is how the quasi-static spring–block
M = 0 is handled), the Hopf parameter p, and the equilibrium y₀ as expressions of the
other parameters.  Where the equilibrium has no closed form it contains *unknown*
symbols defined by ``equilibrium_equations = 0`` and solved numerically.

:class:`SpringBlock` builds eq. (4), M ẍ = k(Vt − x) − σ μ(ẋ, φ), dφ/dt = rate(ẋ, φ),
from any :class:`~laws.FrictionLaw`, in coordinates that make steady sliding the
origin of the mechanical part: X = x − x₀(t), u = ẋ − V, with x₀(t) = Vt − σμ_ss(V)/k.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Mapping

import numpy as np
import sympy as sp

from landau.errors import InputError
from landau.laws.law import FrictionLaw
from landau.laws.law import v as v_slip
from landau.systems import springblock_terms as _terms

#: system-level symbols shared by every spring–block
V = sp.Symbol("V", positive=True)          # driving velocity [m/s]
k = sp.Symbol("k", real=True)              # spring stiffness [N/m] (Hopf parameter)
M = sp.Symbol("M", nonnegative=True)       # block mass [kg]
sigma = sp.Symbol("sigma", positive=True)  # normal load σ = Mg [N]
g = sp.Symbol("g", positive=True)          # gravity [m/s²]

#: Default mechanical parameters (Putelat et al. 2010, Sec. 3: M = 1.2 kg; g = 9.81 m/s²)
M_DEFAULT = 1.2
G_DEFAULT = 9.81
SYSTEM_UNITS = {"M": "kg", "g": "m/s^2", "sigma": "N", "V": "m/s", "k": "N/m"}


def default_normal_load(M, g):
    """σ = M·g, the normal load where only g is given (M_DEFAULT·g for the quasi-static M = 0); vectorised."""
    M, g = np.asarray(M, dtype=float), np.asarray(g, dtype=float)
    return np.where(M > 0, M * g, M_DEFAULT * g)


def _as_sympy(x, what: str) -> sp.Expr:
    """A sympy expression from a sympy object or a plain int/float (never from a string)."""
    if isinstance(x, sp.Basic):
        return x
    if isinstance(x, bool) or not isinstance(x, (int, float, np.integer, np.floating)):
        raise InputError(f"{what}: expected a sympy expression or a number, got {type(x).__name__} {x!r}")
    if isinstance(x, (int, np.integer)):
        return sp.Integer(int(x))
    if not np.isfinite(x):
        raise InputError(f"{what}: {x!r} is not finite")
    return sp.Float(float(x))


def finite_parameter(name: str, value) -> float:
    """A parameter value as a finite float, else an :class:`InputError` naming the parameter
    (:func:`landau.models.model.finite`)."""
    from landau.models.model import finite

    return finite(value, f"parameter {name!r}")


@dataclass(frozen=True, eq=False)
class DynamicalSystem:
    """E·ẏ = f(y; p, q) with Hopf parameter p and other parameters q (all sympy).

    Parameters
    ----------
    name : str
        A short name (used in reprs and cache keys).
    states : tuple of sympy.Symbol
        The state symbols y.
    rhs : tuple of sympy.Expr
        f(y), one expression per state.
    mass : tuple of sympy.Expr or sympy.Matrix
        E, either its diagonal (n expressions; 1 for an ODE row, 0 for an algebraic row) or
        the full n×n matrix (n rows of n expressions, or a sympy Matrix); entries may depend on
        the parameters and on the Hopf parameter p (E(p)), not on the states.
    parameter : sympy.Symbol
        The Hopf (bifurcation) parameter p.
    equilibrium : tuple of sympy.Expr
        y₀ as expressions of the other parameters (and of ``unknowns``); it
        must not depend on p — or, if it does, the engine accounts for it.
    defaults : mapping of str to float, optional
        Default values of the other parameters, by name (plain ints are accepted).
    normalise : int, optional
        Index of the state whose component of the critical eigenvector is 1
        (fixes the normalisation of the Landau coefficient Λ).
    unknowns, unknown_equations : tuple of sympy.Symbol, tuple of sympy.Expr, optional
        Equilibrium pieces with no closed form, defined by ``unknown_equations = 0``
        (solved numerically at each evaluation point).
    unknown_guess : tuple of sympy.Expr, optional
        Starting values for ``unknowns``.
    description : str, optional
        One line describing the system.

    References
    ----------
    Kuznetsov, Y. A. (2004), *Elements of Applied Bifurcation Theory*, 3rd ed., Springer,
    Section 3.5 (the Hopf normal form the engine computes).
    """

    name: str
    states: tuple[sp.Symbol, ...]
    rhs: tuple[sp.Expr, ...]
    mass: tuple[sp.Expr, ...]
    parameter: sp.Symbol
    equilibrium: tuple[sp.Expr, ...]
    defaults: Mapping[str, float] = field(default_factory=dict)
    normalise: int = 0
    unknowns: tuple[sp.Symbol, ...] = ()
    unknown_equations: tuple[sp.Expr, ...] = ()
    unknown_guess: tuple[sp.Expr, ...] = ()
    description: str = ""

    def __post_init__(self) -> None:
        # plain Python numbers (mass=(1, 1), equilibrium=(0, 0)) are accepted as sympy numbers
        for name in ("rhs", "equilibrium", "unknown_equations", "unknown_guess"):
            object.__setattr__(self, name, tuple(_as_sympy(x, name) for x in getattr(self, name)))
        n = len(self.states)
        mass = self.mass
        if isinstance(mass, sp.MatrixBase) or (len(mass) and isinstance(mass[0], (tuple, list, sp.MatrixBase))):
            rows = tuple(tuple(_as_sympy(x, "mass") for x in row)
                         for row in (mass.tolist() if isinstance(mass, sp.MatrixBase) else mass))
            if len(rows) != n or any(len(r) != n for r in rows):
                raise InputError(f"system {self.name!r}: a full mass matrix must be {n}x{n}")
            if any(rows[i][j] != 0 for i in range(n) for j in range(n) if i != j):
                object.__setattr__(self, "mass", rows)
            else:  # a diagonal matrix is stored as its diagonal, as every route expects
                object.__setattr__(self, "mass", tuple(rows[i][i] for i in range(n)))
        else:
            object.__setattr__(self, "mass", tuple(_as_sympy(x, "mass") for x in mass))
        if not (len(self.rhs) == len(self.mass) == len(self.equilibrium) == n):
            raise InputError(f"system {self.name!r}: states, rhs, mass and equilibrium must have equal length")
        if set().union(*(e.free_symbols for e in self.mass_matrix)) & set(self.states):
            raise InputError(f"system {self.name!r}: the mass matrix must not depend on the states")

    @property
    def mass_is_diagonal(self) -> bool:
        """True if E is stored as its diagonal (every route supports this form)."""
        return not (len(self.mass) and isinstance(self.mass[0], tuple))

    @property
    def mass_matrix(self) -> sp.Matrix:
        """E as an n×n sympy matrix."""
        return sp.diag(*self.mass) if self.mass_is_diagonal else sp.Matrix(self.mass)

    @cached_property
    def parameters(self) -> tuple[sp.Symbol, ...]:
        """Every free symbol except the states, the Hopf parameter and the unknowns, sorted by name."""
        syms = set().union(*(e.free_symbols for e in (*self.rhs, *self.mass_matrix, *self.equilibrium)))
        syms -= set(self.states) | {self.parameter} | set(self.unknowns)
        return tuple(sorted(syms, key=lambda s: s.name))

    # --- construction from strings --------------------------------------------------------
    @classmethod
    def from_strings(cls, rhs: Mapping[str, str], parameter: str, params: Mapping[str, float] | None = None, *,
                     equilibrium: Mapping[str, str] | None = None, guess: Mapping[str, float] | None = None,
                     mass: Mapping[str, str] | None = None, name: str = "system", normalise: str | None = None,
                     description: str = "") -> "DynamicalSystem":
        """A system E·ẏ = f(y; p) written as strings, parsed by the friction laws' whitelist parser.

        Every expression goes through :func:`landau.laws.parse.parse_expression`: only numbers,
        the declared names, the arithmetic operators and the whitelisted functions; anything else
        is a :class:`~landau.errors.ParseError` naming the token.  Every name an expression uses
        must be a state, the Hopf parameter or a key of ``params``.

        Parameters
        ----------
        rhs : mapping of str to str
            Each state's name and its right-hand side f_i, in order, e.g.
            ``{"x": "a - (b + 1)*x + x^2*y", "y": "b*x - x^2*y"}`` (the Brusselator).
        parameter : str
            The Hopf parameter p (a name the expressions may use; not a state, not in ``params``).
        params : mapping of str to float, optional
            Every other parameter and its default value.
        equilibrium : mapping of str to str, optional
            The equilibrium y₀ of each state as an expression of the parameters and p.
        guess : mapping of str to float, optional
            Instead of ``equilibrium``: a starting guess of y₀ for Newton's method (states
            left out start at 0).
        mass : mapping of str to str, optional
            Diagonal entries E_ii (default 1; ``"0"`` makes the row algebraic, a DAE), as
            expressions of the parameters and p, not of the states.
        name, description : str, optional
            A name for reprs and results, and one line describing the system.
        normalise : str, optional
            The state whose component of the critical mode is 1 (default: the first).

        Returns
        -------
        DynamicalSystem

        Raises
        ------
        InputError
            An empty system, a bad or reserved name, a name an expression uses but nobody
            declares, ``equilibrium`` and ``guess`` both or neither given, a mass entry that
            depends on a state; :class:`~landau.errors.ParseError` for a token outside the
            whitelist.
        """
        from landau.laws.parse import parse_expression, referenced_names

        if not isinstance(rhs, Mapping) or not rhs:
            raise InputError("a system needs at least one state: rhs={'x': 'EXPR', ...}")
        params = dict(params or {})
        if (equilibrium is None) == (guess is None):
            raise InputError("give either the equilibrium (closed-form expressions) or a guess of it (numbers), "
                             "not both and not neither")
        states = list(rhs)
        for s in states:
            _check_system_name(s, "state")
        _check_system_name(parameter, "Hopf parameter")
        for pname in params:
            _check_system_name(pname, "parameter")
        if parameter in rhs:
            raise InputError(f"{parameter!r} is a state and cannot also be the Hopf parameter")
        if parameter in params:
            raise InputError(f"{parameter!r} is the Hopf parameter: its critical value is computed, not given")
        both = sorted(set(states) & set(params))
        if both:
            raise InputError(f"{both[0]!r} is a state and cannot also be a parameter")
        values: dict[str, float] = {}
        for pname, val in params.items():
            values[pname] = _finite(val, f"parameter {pname!r}")
        state_syms = {s: sp.Symbol(s, real=True) for s in states}
        p_sym = sp.Symbol(parameter, real=True)
        par_syms = {n: sp.Symbol(n, real=True) for n in values}
        every = {**state_syms, parameter: p_sym, **par_syms}
        no_states = {parameter: p_sym, **par_syms}

        def parse(text, what, symbols):
            if not isinstance(text, str):
                text = str(text) if isinstance(text, (int, float)) and not isinstance(text, bool) else text
            if not isinstance(text, str):
                raise InputError(f"{what}: expected an expression string, got {type(text).__name__}")
            states_used = sorted((referenced_names(text, what=what) & set(state_syms)) - set(symbols))
            if states_used:
                raise InputError(f"{what}: {states_used[0]!r} is a state; the equilibrium and the mass are "
                                 "expressions of the parameters only")
            return parse_expression(text, symbols, what=what)

        f = tuple(parse(rhs[s], f"d{s}/dt", every) for s in states)
        for what, mp in (("equilibrium", equilibrium), ("guess", guess), ("mass", mass)):
            if mp is not None:
                if not isinstance(mp, Mapping):
                    raise InputError(f"{what} must map state names to values")
                extra = sorted(set(mp) - set(states))
                if extra:
                    raise InputError(f"{what}: {extra[0]!r} is not a state (states: {', '.join(states)})")
        if equilibrium is not None:
            missing = [s for s in states if s not in equilibrium]
            if missing:
                raise InputError(f"equilibrium: no expression for state {missing[0]!r}")
            eq = tuple(parse(equilibrium[s], f"equilibrium {s}", no_states) for s in states)
        else:
            assert guess is not None   # one of equilibrium and guess is given (checked above)
            eq = tuple(sp.Float(_finite(guess.get(s, 0.0), f"guess {s}")) for s in states)
        E = tuple(parse(mass[s], f"mass {s}", no_states) if mass and s in mass else sp.Integer(1) for s in states)
        norm = 0
        if normalise is not None:
            if normalise not in state_syms:
                raise InputError(f"normalise: {normalise!r} is not a state (states: {', '.join(states)})")
            norm = states.index(normalise)
        if all(e == 0 for e in E):
            raise InputError("mass: every row is algebraic; at least one state needs a non-zero mass")
        return cls(name=name, states=tuple(state_syms.values()), rhs=f, mass=E, parameter=p_sym, equilibrium=eq,
                   defaults=values, normalise=norm, description=description)

    def __repr__(self) -> str:
        return (f"DynamicalSystem({self.name!r}, states={[s.name for s in self.states]}, "
                f"parameter={self.parameter.name}, parameters={[s.name for s in self.parameters]})")


#: names of the expression language (functions and constants), never a state or a parameter
def _language() -> set[str]:
    from landau.laws.parse import CONSTANTS, FUNCTIONS

    return set(FUNCTIONS) | set(CONSTANTS)


_LANGUAGE = _language()


def _check_system_name(name, what: str) -> None:
    """A state or parameter name of :meth:`DynamicalSystem.from_strings`: a plain identifier that
    is not a Python keyword, a function or constant of the expression language, or an engine name
    (``__`` is reserved for the engine's equilibrium symbols)."""
    import keyword
    import re

    if not isinstance(name, str) or not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", name) or keyword.iskeyword(name):
        raise InputError(f"{what} name {name!r} must be a plain identifier (a letter, then letters, digits, _)")
    if name in _LANGUAGE:
        raise InputError(f"{what} name {name!r} is reserved: it is a function or constant of the expression language")
    if "__" in name or re.fullmatch(r"d\d+_\w*|dp_\w*", name):
        raise InputError(f"{what} name {name!r} is reserved for the engine's symbols; choose another name")


def _finite(val, what: str) -> float:
    if isinstance(val, bool):
        raise InputError(f"{what} must be a number, got {val!r}")
    try:
        x = float(val)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a number, got {val!r}") from None
    if not np.isfinite(x):
        raise InputError(f"{what} must be finite, got {val!r}")
    return x


@dataclass(frozen=True, eq=False)
class SpringBlock:
    """The spring–block of Putelat et al. (2010), eq. (4), driven at velocity V.

    σ (normal load) is its own parameter, default M·g with M = 1.2 kg, g = 9.81 m/s²
    (σ = 11.772 N).  Changing M alone changes the inertia only — as the paper's M = 0
    (quasi-static) curves do; give ``g`` or ``sigma`` to change the load.

    Optional terms (:mod:`landau.systems.springblock_terms`), each a system parameter with
    default 0: radiation damping ``eta`` η [N·s/m] (Rice 1993; with M = 0 the quasi-dynamic
    limit), variable normal stress ``gamma_ld`` γ_LD and the state response ``alpha_ld`` α_LD
    (Linker & Dieterich 1992); ``sigma`` is then σ₀, the normal load at zero spring force; with states of
    their own (:mod:`landau.systems.fault_terms`), pore pressure and dilatancy ``eps_dil`` (σ − p, Segall &
    Rice 1995) and thermal pressurisation ``lambda_tp`` (Rice 2006), with their further parameters.
    All quantities may be per unit area (σ in Pa, k in Pa/m, η in Pa·s/m, M in kg/m²).

    Parameters
    ----------
    law : FrictionLaw or str
        The friction law, or a built-in law's name (:func:`landau.laws.get_law`).
    terms : tuple of str, optional
        The optional terms to build in (``"eta"``, ``"gamma_ld"``, ``"alpha_ld"``);
        :meth:`for_params` picks them from the parameters given.

    References
    ----------
    Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), "Regimes of frictional sliding of a
    spring–block system", J. Mech. Phys. Solids 58(1), 27–53, eq. (4).
    Rice, J. R. (1993), J. Geophys. Res. 98(B6), 9885–9907 (radiation damping).
    Linker, M. F. & Dieterich, J. H. (1992), J. Geophys. Res. 97(B4), 4923–4940 (variable normal stress).
    """

    @classmethod
    def for_params(cls, law, params: Mapping[str, float] | None = None) -> "SpringBlock":
        """The spring–block of ``law`` with every optional term whose parameter appears in ``params``.

        Parameters
        ----------
        law : FrictionLaw or str
        params : mapping, optional
            Parameter overrides; a key ``eta``, ``gamma_ld``, ``alpha_ld``, ``eps_dil``, ``lambda_tp`` or one of
            their further parameters (``t_drain``…; any value, 0 too) builds that term in.

        Returns
        -------
        SpringBlock
        """
        given = {_terms.term_of(key) for key in (params or {})}
        return cls(law, tuple(t for t in _terms.TERMS if t in given))

    law: FrictionLaw
    terms: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "terms", _terms.check_terms(self.terms))
        if isinstance(self.law, str):  # SpringBlock("dieterich"): a built-in law by name
            from landau.laws import get_law

            object.__setattr__(self, "law", get_law(self.law))
        if not isinstance(self.law, FrictionLaw):
            raise InputError(f"SpringBlock needs a FrictionLaw or a built-in law's name, got {type(self.law).__name__}")
        taken = {s.name for s in (*self.law.states, *(q.symbol for q in self.law.parameters))} | \
            {"X", "u", "V", "k", "M", "g", "sigma"}
        clash = sorted(st.symbol.name for st in _terms.states(self.terms) if st.symbol.name in taken)
        if clash:
            raise InputError(f"law {self.law.name!r}: its symbol(s) {', '.join(clash)} are the names of the states "
                             f"the terms {', '.join(self.terms)} add; rename them in the law")

    @cached_property
    def defaults(self) -> dict[str, float]:
        d = dict(self.law.defaults())
        d.update(M=M_DEFAULT, g=G_DEFAULT, sigma=M_DEFAULT * G_DEFAULT)
        d.update({name: default for name, _, _, default in _terms.parameters(self.terms)})
        return d

    @property
    def units(self) -> dict[str, str]:
        """Units of the system parameters (SI, per block; per unit area: N → Pa)."""
        return {**SYSTEM_UNITS, **{name: unit for name, _, unit, _ in _terms.parameters(self.terms)}}

    def resolve(self, overrides: Mapping[str, float] | None = None) -> dict[str, float]:
        """Full parameter dict (law + M, g, sigma) with overrides applied and checked.

        Parameters
        ----------
        overrides : mapping of str to float, optional
            Values replacing the defaults, by parameter name.

        Returns
        -------
        dict of str to float

        Raises
        ------
        InputError
            An unknown parameter, or a value that is not a finite number.
        """
        p = dict(self.defaults)
        over = dict(overrides or {})
        declared = {prm.name for prm in self.law.parameters} | set(p)
        for key, val in over.items():
            if (term := _terms.term_of(key)) is not None and key not in declared:
                raise InputError(f"parameter {key!r} is of the optional spring-block term {term!r}, not built "
                                 f"into this block: use SpringBlock(law, terms=({term!r},)) or "
                                 "SpringBlock.for_params(law, params)")
            if key not in declared:
                raise InputError(f"unknown parameter {key!r} for law {self.law.name!r} "
                                 f"(known: {', '.join(sorted(p))})")
            p[key] = finite_parameter(key, val)
        missing = [prm.name for prm in self.law.parameters if prm.name not in p]
        if missing:
            raise InputError(f"law {self.law.name!r}: parameter(s) {', '.join(missing)} have no default; "
                             "give them with --param NAME=VALUE")
        if "sigma" not in over and "g" in over:
            p["sigma"] = float(default_normal_load(p["M"], p["g"]))
        if p["M"] < 0:
            raise InputError(f"parameter 'M' must be >= 0, got {p['M']!r}")
        if p["sigma"] <= 0:
            raise InputError(f"parameter 'sigma' must be > 0, got {p['sigma']!r}")
        for prm in self.law.parameters:
            if prm.positive and p[prm.name] <= 0:
                raise InputError(f"parameter {prm.name!r} must be > 0, got {p[prm.name]!r}")
        _terms.check_values(p)
        return p

    @cached_property
    def phi0(self) -> tuple[sp.Symbol, ...]:
        """Symbols for the steady state φᵢ,₀ (replaced by closed forms where they exist)."""
        return tuple(sp.Symbol(f"{s.name}_0", positive=True) for s in self.law.states)

    @cached_property
    def steady_state(self) -> tuple[sp.Expr, ...] | None:
        """Closed-form φᵢ,ss(V) or None."""
        ss = self.law.steady_state_closed_form
        return None if ss is None else tuple(e.subs(v_slip, V) for e in ss)

    @cached_property
    def system(self) -> DynamicalSystem:
        """Eq. (4) as E·ẏ = f(y; k): y = (X, u, φ…), E = diag(1, M, 1…)."""
        X, u = sp.symbols("X u", real=True)
        phis = self.law.states
        at_slip = {v_slip: V + u}
        ss = self.steady_state
        eq_phi = ss if ss is not None else self.phi0
        # the terms' states (pore pressure, temperature) as their excesses over steady sliding
        extra = {st.symbol.name: st.symbol for st in _terms.states(self.terms)}
        force, rates = _terms.mechanical_rhs(self.law, self.terms, X, u, at_slip, eq_phi, k, sigma, V, extra=extra)
        rhs = (u, force, *rates)
        ts = tuple(extra.values())
        unknowns: tuple = ()
        eqs: tuple = ()
        if ss is None:
            unknowns = self.phi0
            eqs = tuple(r.subs({v_slip: V, **dict(zip(phis, self.phi0, strict=True))}) for r in self.law.rates)
        named = "".join(f"+{t}" for t in self.terms)
        return DynamicalSystem(
            name=f"spring-block[{self.law.name}]{named}",
            states=(X, u, *phis, *ts),
            rhs=rhs,
            mass=(sp.Integer(1), M, *([sp.Integer(1)] * (len(phis) + len(ts)))),
            parameter=k,
            equilibrium=(sp.Integer(0), sp.Integer(0), *eq_phi, *([sp.Integer(0)] * len(ts))),
            defaults=self.defaults,
            normalise=0,
            unknowns=unknowns,
            unknown_equations=eqs,
            description="Putelat et al. 2010 eq. (4) in X = x - x0(t), u = dx/dt - V",
        )

    @cached_property
    def args(self) -> tuple[sp.Symbol, ...]:
        """Argument order of every compiled function: (V, law parameters…, M, g, sigma, the optional
        terms' parameters…), then the steady states φᵢ,₀ where they have no closed form (solved
        numerically by :meth:`argvals`)."""
        unknowns = self.phi0 if self.steady_state is None else ()
        return (V, *(p.symbol for p in self.law.parameters), M, g, sigma, *_terms.symbols(self.terms), *unknowns)

    def argvals(self, Vs, params: Mapping[str, float | np.ndarray]) -> list:
        """Values for :attr:`args`; checks that the law is real and finite at steady sliding.

        Parameters
        ----------
        Vs : float or array_like
            Driving velocities, m/s.
        params : mapping of str to float
            Resolved parameters (:meth:`resolve`).

        Returns
        -------
        list
            One value (or array) per entry of :attr:`args`, broadcast together.
        """
        n = len(self.law.parameters) + 3 + len(_terms.symbols(self.terms))
        vals = [Vs, *(params[s.name] for s in self.args[1:n + 1])]
        shape = np.broadcast(*[np.asarray(x, dtype=float) for x in vals]).shape
        Vb = np.broadcast_to(np.asarray(Vs, dtype=float), shape)
        lp = {p.name: np.broadcast_to(np.asarray(params[p.name], dtype=float), shape) for p in self.law.parameters}
        phis = self.law.steady_state_values(Vb, lp)
        self.law.check_real(Vb, phis, lp)
        if _terms.loads_block(self.terms):
            with np.errstate(all="ignore"):
                mu_ss = self._mu_numeric(Vb, *phis, *(lp[p.name] for p in self.law.parameters))
            _terms.check_steady_sliding(self.law, mu_ss, params, Vb)
        if self.steady_state is None:
            vals += [phi if np.ndim(Vs) or shape else phi.item() for phi in phis]
        return vals

    def name_terms(self, result):
        """``result`` located at V and at the value of each optional term (shown in its repr, first
        in its JSON), with the terms' units.

        Parameters
        ----------
        result : HopfResult
            A spring–block result whose ``params`` hold the terms' values.

        Returns
        -------
        HopfResult
        """
        if not self.terms:
            return result
        from dataclasses import replace

        return replace(result, at=(*result.at, *self.terms),
                       units={**result.units, **{name: unit for name, _, unit, _ in _terms.parameters(self.terms)}})

    @cached_property
    def _mu_numeric(self):
        """μ(v, φ…, law parameters…) as a numpy function (the steady-sliding checks of the terms)."""
        return sp.lambdify([v_slip, *self.law.states, *(p.symbol for p in self.law.parameters)],
                           self.law.mu, "numpy")

    def mu_ss(self) -> sp.Expr:
        """μ_ss(V) (closed form).

        Returns
        -------
        sympy.Expr
            The steady-state friction coefficient in V and the law's parameters.
        """
        return self.law.mu_ss().subs(v_slip, V)

    def __repr__(self) -> str:
        return f"SpringBlock({self.law.name!r}{', terms=' + repr(self.terms) if self.terms else ''})"
