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

from dataclasses import dataclass
from functools import cached_property
from typing import Mapping

import sympy as sp

from landau.errors import InputError
from landau.laws.parse import parse_expression

#: the slip-rate symbol shared by every law
v = sp.Symbol("v", positive=True)


def _check_name(name: str, what: str) -> None:
    """Names become sympy symbols and, in generated code, variable names: plain identifiers only."""
    import keyword
    import re

    if not re.fullmatch(r"[A-Za-z][A-Za-z0-9_]*", name) or keyword.iskeyword(name):
        raise InputError(f"{what} name {name!r} must be a plain identifier (a letter, then letters, digits, _)")


@dataclass(frozen=True)
class Parameter:
    """A named constant of a law with its default value, units and provenance."""

    name: str
    default: float | None
    units: str = ""
    source: str = ""
    description: str = ""
    positive: bool = True

    @property
    def symbol(self) -> sp.Symbol:
        return sp.Symbol(self.name, positive=True) if self.positive else sp.Symbol(self.name, real=True)

    def __repr__(self) -> str:
        return f"{self.name} = {self.default!r} {self.units}".rstrip() + (f"  [{self.source}]" if self.source else "")


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
class FrictionLaw:
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
        known = {v, *self.states, *(p.symbol for p in self.parameters)}
        for what, expr in [("mu", self.mu), *((f"d{s}/dt", r) for s, r in zip(self.states, self.rates))]:
            extra = expr.free_symbols - known
            if extra:
                raise InputError(f"law {self.name!r}: {what} uses undeclared symbol(s) "
                                 + ", ".join(sorted(map(str, extra))))
        if v not in self.mu.free_symbols:
            raise InputError(f"law {self.name!r}: mu does not depend on the slip rate v")

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
        names = set()
        import ast

        for text in [mu, *state.values()]:
            try:
                tree = ast.parse(str(text).strip(), mode="eval")
            except SyntaxError:
                continue  # parse_expression reports it with context
            for node in ast.walk(tree):
                if isinstance(node, ast.Name):
                    names.add(node.id)
        reserved = {"v", *state}
        for s in reserved:
            if s in params:
                raise InputError(f"{s!r} is a {'slip rate' if s == 'v' else 'state'} and cannot also be a parameter")
        plist: list[Parameter] = []
        for pname, val in params.items():
            _check_name(pname, "parameter")
            plist.append(val if isinstance(val, Parameter) else Parameter(pname, float(val), source="user"))
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
        return v

    def defaults(self) -> dict[str, float]:
        return {p.name: p.default for p in self.parameters if p.default is not None}

    def parameter(self, name: str) -> Parameter:
        for p in self.parameters:
            if p.name == name:
                return p
        raise InputError(f"law {self.name!r} has no parameter {name!r} "
                         f"(known: {', '.join(p.name for p in self.parameters)})")

    def symbol(self, name: str) -> sp.Symbol:
        if name == "v":
            return v
        for s in self.states:
            if s.name == name:
                return s
        return self.parameter(name).symbol

    def with_defaults(self, **values: float) -> "FrictionLaw":
        """A copy with some parameter defaults changed."""
        new = []
        for p in self.parameters:
            if p.name in values:
                new.append(Parameter(p.name, float(values.pop(p.name)), p.units, p.source, p.description, p.positive))
            else:
                new.append(p)
        if values:
            raise InputError(f"law {self.name!r} has no parameter(s) {', '.join(sorted(values))}")
        return FrictionLaw(self.name, self.mu, self.states, self.rates, tuple(new), self.source,
                           self.description, self.steady_state)

    # --- steady state -------------------------------------------------------------
    @cached_property
    def steady_state_closed_form(self) -> tuple[sp.Expr, ...] | None:
        """φᵢ,ss(v) solving dφᵢ/dt = 0 at slip rate v, or None if sympy finds no closed form."""
        if self.steady_state is not None:
            return tuple(self.steady_state)
        try:
            sols = sp.solve(list(self.rates), list(self.states), dict=True)
        except (NotImplementedError, ValueError):
            return None
        good = []
        for sol in sols:
            if all(s in sol for s in self.states):
                vals = tuple(sp.simplify(sol[s]) for s in self.states)
                if all(val.is_positive is not False for val in vals):
                    good.append(vals)
        if len(good) == 1:
            return good[0]
        return None

    def mu_ss(self) -> sp.Expr:
        """Steady-state friction coefficient μ_ss(v) (closed form)."""
        ss = self.steady_state_closed_form
        if ss is None:
            raise InputError(f"law {self.name!r}: no closed-form steady state; use numeric evaluation")
        return self.mu.subs(dict(zip(self.states, ss)))

    # --- display ------------------------------------------------------------------
    def latex(self) -> str:
        lines = [rf"\mu = {sp.latex(self.mu)}"]
        for s, r in zip(self.states, self.rates):
            lines.append(rf"\frac{{d{sp.latex(s)}}}{{dt}} = {sp.latex(r)}")
        return r",\quad ".join(lines)

    def __repr__(self) -> str:
        rates = ", ".join(f"d{s}/dt = {r}" for s, r in zip(self.states, self.rates))
        return f"FrictionLaw({self.name!r}: mu = {self.mu}; {rates}; source={self.source!r})"

    def _repr_latex_(self) -> str:
        return f"${self.latex()}$"
