"""Optional terms of the spring–block: radiation damping and variable normal stress (and, declared in
:mod:`landau.systems.fault_terms` on the same classes, the terms with states of their own: pore pressure
with dilatancy, thermal pressurisation).

Each term is a declared system parameter, default 0 (off), built into the equations in this
module only; :class:`~landau.systems.system.SpringBlock` asks for them by name
(``SpringBlock(law, terms=("eta",))``, or :meth:`~landau.systems.system.SpringBlock.for_params`,
which adds every term whose parameter is given).

Equations (X = x − x_ss(t), u = ẋ − V; μ the law's friction coefficient, φ its states)::

    M u̇ = k(Vt − x) − σ(x, t) μ(V + u, φ) − η(V + u)
    σ(x, t) = σ₀ + γ_LD k(Vt − x)                       (normal load follows the spring)
    dφ₁/dt = G₁(v, φ) − α_LD σ̇ / (σ ∂μ/∂φ₁)              (the Linker–Dieterich state response)

* ``eta`` — radiation damping η [N·s/m, or Pa·s/m per unit area], the quasi-dynamic
  approximation of the waves radiated from the slipping surface, η = ρc_s/2 for a half space
  (Rice 1993).  With σ constant it is an additive velocity term: σμ + ηv = σ[μ + ηv/σ], so at
  steady sliding it acts as a larger direct effect, ∂μ/∂v → ∂μ/∂v + η/σ.  For the aging law this
  gives (a → a + ηV/σ in Putelat et al. 2010, eq. 30)::

      k_c = [σ(b − a) − ηV]/L · [1 + M V²/(L(σa + ηV))].

  M = 0 with η > 0 is the quasi-dynamic limit (a DAE: the u row is algebraic).
* ``gamma_ld`` — γ_LD [1]: the normal load changes with the spring force, γ = tan ψ for a
  spring inclined at angle ψ to the sliding surface (Linker & Dieterich 1992; Dieterich &
  Linker 1992); σ₀ is the parameter ``sigma``.  Steady sliding carries the spring force
  F_ss = σ_ss μ_ss + ηV, so σ_ss = (σ₀ + γ_LD ηV)/(1 − γ_LD μ_ss): it exists only for
  1 − γ_LD μ_ss > 0, for any law (velocity weakening or strengthening); otherwise
  :class:`~landau.errors.NoSteadySlidingError`.
* ``alpha_ld`` — α_LD [1]: the state's response to a change of normal stress (Linker &
  Dieterich 1992, eq. 6: dθ/dt = 1 − vθ/L − (αθ/(bσ)) dσ/dt for the aging law).  For a
  general law the term is written so that the state part of μ changes by −α_LD dσ/σ, the
  Linker–Dieterich response: dφ₁/dt gains −α_LD σ̇/(σ ∂μ/∂φ₁) on the *first* state φ₁
  (∂μ/∂θ = b/θ for the Dieterich law recovers eq. 6).  It acts only where σ varies
  (γ_LD ≠ 0): σ̇ = −γ_LD k u, so the stiffness k enters the state row as well as the force row;
  the characteristic polynomial stays affine in k.  For the aging law (Dieterich law of Putelat et
  al. 2010, eqs 26 + 28: μ = a_v + a ln(v/V*) + b ln(V*θ/L), dθ/dt = 1 − vθ/L) with all three
  terms and inertia M, write σ_ss as above, μ_ss = a_v + (a − b) ln(V/V*) and A = σ_ss a + ηV;
  then det(λE − J) = Mλ³ + (MV/L + A/V)λ² + (A/L + k[1 − γ_LD(μ_ss − α_LD)] − σ_ss b/L)λ +
  k(1 − γ_LD μ_ss)V/L, whose roots λ = ±iω give::

      k_c = [σ_ss(b − a) − ηV]/L · (A + MV²/L) / [(1 − γ_LD(μ_ss − α_LD)) A + α_LD γ_LD MV²/L],
      ω_c² = k_c (1 − γ_LD μ_ss) V² / (L A + M V²).

  α_LD = 0 gives k_c⁰(σ → σ_ss)/(1 − γ_LD μ_ss) (the ``gamma_ld`` closed form); γ_LD = 0 the
  ``eta`` one; M = η = 0 gives σ_ss(b − a)/(L[1 − γ_LD(μ_ss − α_LD)]).  ``landau derive`` takes the
  term (:class:`~landau.derivation.parameter_jets.ParameterJets` keeps k visible in both rows).

References
----------
Rice, J. R. (1993), Spatio-temporal complexity of slip on a fault, J. Geophys. Res. 98(B6), 9885–9907.
Linker, M. F. & Dieterich, J. H. (1992), Effects of variable normal stress on rock friction: observations
and constitutive equations, J. Geophys. Res. 97(B4), 4923–4940.
Dieterich, J. H. & Linker, M. F. (1992), Fault stability under conditions of variable normal stress,
Geophys. Res. Lett. 19(16), 1691–1694.
Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), Regimes of frictional sliding of a spring–block
system, J. Mech. Phys. Solids 58(1), 27–53.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Callable, Mapping

import numpy as np
import sympy as sp

from landau.errors import InputError, NoSteadySlidingError

#: η, radiation damping [N s/m] (Rice 1993)
eta = sp.Symbol("eta", nonnegative=True)
#: γ_LD, normal-load coupling to the spring force [1] (Linker & Dieterich 1992)
gamma_ld = sp.Symbol("gamma_ld", real=True)
#: α_LD, state response to normal-stress changes [1] (Linker & Dieterich 1992)
alpha_ld = sp.Symbol("alpha_ld", real=True)


@dataclass(frozen=True)
class Balance:
    """What a term's contribution is written in: the force balance of the block at one instant.

    M v̇ = F − σ μ(v, φ) + Σ forces,   σ = σ₀ + Σ loads(F),   dφᵢ/dt = Gᵢ(v, φ) + Σ rate contributions,

    with F = k(x_lp − x) the spring force and Ḟ = k(V_lp − v) its rate.  Each consumer (the derivation's
    X, u form, the compiled scaled field, the quasi-dynamic cell, the load histories) fills these with
    its own expressions and the terms' contributions are substituted into them.

    Attributes
    ----------
    v : sympy.Expr
        The slip rate.
    phis : tuple of sympy.Expr
        The law's states.
    F, F_dot : sympy.Expr
        The spring force and its time derivative.
    V_lp : sympy.Expr
        The load-point velocity.
    k, sigma0 : sympy.Expr
        The stiffness and σ₀, the normal load at zero spring force.
    sigma, sigma_dot : sympy.Expr
        The normal load and its time derivative (from the terms' loads).
    mu : sympy.Expr
        μ(v, φ) at this instant.
    dmu_dphi : tuple of sympy.Expr
        ∂μ/∂φᵢ at this instant.
    symbol : mapping of str to sympy.Symbol
        Each term's parameter symbol as the consumer names it.
    """

    v: sp.Expr
    phis: tuple
    F: sp.Expr
    F_dot: sp.Expr
    V_lp: sp.Expr
    k: sp.Expr
    sigma0: sp.Expr
    sigma: sp.Expr = sp.Integer(0)
    sigma_dot: sp.Expr = sp.Integer(0)
    mu: sp.Expr = sp.Integer(0)
    dmu_dphi: tuple = ()
    symbol: Mapping[str, sp.Symbol] = field(default_factory=dict)
    #: the terms' own states (:class:`TermState`) at this instant, by name (their full values)
    extra: Mapping[str, sp.Expr] = field(default_factory=dict)
    #: dφᵢ/dt with every term's contribution (given to the terms' state rates)
    phi_rates: tuple = ()
    #: the rates of the terms' states computed so far (a term's contribution to another's state uses them)
    extra_rates: Mapping[str, sp.Expr] = field(default_factory=dict)


@dataclass(frozen=True)
class TermParameter:
    """A further parameter of a term (beyond the term's own, which switches it on): a drainage time, a
    storage coefficient.  It has a default (the term is off while the term's own parameter is 0)."""

    symbol: sp.Symbol
    unit: str
    meaning: str
    default: float
    #: "positive", "nonnegative" or "real"
    domain: str = "real"


@dataclass(frozen=True)
class TermState:
    """A state a term adds to the block (a pore pressure, a temperature).

    ``symbol`` is the derivation's variable: the state's excess over its steady value (0 at steady
    sliding).  ``steady`` and ``rate`` are functions of a :class:`Balance` and give the state's steady
    value (the balance at steady sliding: v = V, σ = σ_ss, μ = μ_ss; a state the normal load depends on
    must have a steady value free of σ) and its rate d/dt written in the full values
    (:attr:`Balance.extra`).  ``scale`` is a typical size, the unit of a consumer's scaled variable.
    """

    symbol: sp.Symbol
    unit: str
    meaning: str
    steady: Callable[[Balance], sp.Expr]
    rate: Callable[[Balance], sp.Expr]
    scale: Callable[[Balance], sp.Expr]


@dataclass(frozen=True)
class Term:
    """One optional spring–block term: its parameter, and its contributions to the force balance.

    Each contribution is a function of a :class:`Balance` (None: the term makes none): ``load`` is
    added to the normal load σ and may depend on the spring force ``F`` only; ``force`` is added to
    the force on the block; ``rates`` to the state rates dφᵢ/dt (a tuple, the first states).  This
    is the one place a term is written: the derivation, its LaTeX, the compiled field, the
    quasi-dynamic cell and the load histories all build their equations from it
    (:func:`force_balance`, :func:`mechanical_rhs`).

    A term may add states (``states``, :class:`TermState`: a pore pressure p, a temperature T) whose
    full values the load, the force and the rates read from :attr:`Balance.extra` (the effective
    normal stress σ̄ = σ − p is the load −p); ``state_rates`` adds to the rates of states other terms
    declare (name → contribution; the rates computed so far in :attr:`Balance.extra_rates`), and
    ``requires`` names the terms it needs built in with it (their states).  ``parameters`` are its
    further parameters (:class:`TermParameter`), system parameters whenever the term is built in.
    """

    symbol: sp.Symbol
    unit: str
    meaning: str
    source: str
    nonnegative: bool = False
    load: Callable[[Balance], sp.Expr] | None = None
    force: Callable[[Balance], sp.Expr] | None = None
    rates: Callable[[Balance], tuple] | None = None
    #: the stiffness enters the state rates through this term (the Hopf line is then not affine in k
    #: in the derivation's parameters: its Hopf point comes from the general engine)
    stiffness_in_rates: bool = False
    parameters: tuple[TermParameter, ...] = ()
    states: tuple[TermState, ...] = ()
    state_rates: Callable[[Balance], Mapping[str, sp.Expr]] | None = None
    requires: tuple[str, ...] = ()


#: the optional terms, in their argument order
TERMS: dict[str, Term] = {
    "eta": Term(eta, "N s/m", "radiation damping, force eta*v (quasi-dynamic)", "Rice (1993)", True,
                force=lambda b: -b.symbol["eta"] * b.v),
    "gamma_ld": Term(gamma_ld, "1", "normal load sigma = sigma0 + gamma_ld * spring force",
                     "Linker & Dieterich (1992)", load=lambda b: b.symbol["gamma_ld"] * b.F),
    # Linker & Dieterich (1992), eq. 6, for a general law: the state part of mu changes by -alpha dsigma/sigma
    "alpha_ld": Term(alpha_ld, "1", "state response -alpha_ld dsigma/sigma to normal-stress changes",
                     "Linker & Dieterich (1992)",
                     rates=lambda b: (-b.symbol["alpha_ld"] * b.sigma_dot / (b.sigma * b.dmu_dphi[0]),),
                     stiffness_in_rates=True),
}


def register_term(name: str, term: Term) -> Term:
    """Add an optional term (a plug-in, a test); its parameter ``name`` is then a parameter of every
    spring–block that gives it (:meth:`~landau.systems.system.SpringBlock.for_params`)."""
    if name in TERMS:
        raise InputError(f"a spring-block term named {name!r} exists already")
    if term.symbol.name != name:
        raise InputError(f"term {name!r}: its parameter symbol is named {term.symbol.name!r}")
    TERMS[name] = term
    return term


def unregister_term(name: str) -> None:
    """Remove a term added by :func:`register_term`."""
    TERMS.pop(name, None)


def check_terms(terms) -> tuple[str, ...]:
    """The requested terms, validated and in canonical order, with the terms they require."""
    if isinstance(terms, str):
        terms = (terms,)
    terms = tuple(terms)
    unknown = [t for t in terms if t not in TERMS]
    if unknown:
        raise InputError(f"unknown spring-block term(s) {', '.join(map(repr, unknown))} "
                         f"(known: {', '.join(TERMS)})")
    wanted = set(terms)
    todo = list(terms)
    while todo:
        for r in TERMS[todo.pop()].requires:
            if r not in wanted:
                wanted.add(r)
                todo.append(r)
    return tuple(t for t in TERMS if t in wanted)


def parameters(terms) -> tuple[tuple[str, sp.Symbol, str, float], ...]:
    """(name, symbol, unit, default) of every parameter of ``terms``: each term's own (default 0, off),
    then its further ones (:class:`TermParameter`), in canonical order."""
    out = []
    for t in check_terms(terms):
        term = TERMS[t]
        out.append((t, term.symbol, term.unit, 0.0))
        out += [(q.symbol.name, q.symbol, q.unit, float(q.default)) for q in term.parameters]
    return tuple(out)


def term_of(name: str) -> str | None:
    """The term a parameter ``name`` belongs to (its own or a further one), or None."""
    for t, term in TERMS.items():
        if name == t or any(q.symbol.name == name for q in term.parameters):
            return t
    return None


def symbols(terms) -> tuple[sp.Symbol, ...]:
    """The parameter symbols of ``terms`` (canonical order, each term's own then its further ones)."""
    return tuple(q[1] for q in parameters(terms))


def states(terms) -> tuple[TermState, ...]:
    """The states the terms add (canonical order)."""
    return tuple(st for t in check_terms(terms) for st in TERMS[t].states)


def has_states(terms) -> bool:
    """True where one of ``terms`` adds a state (pore pressure, temperature)."""
    return bool(states(terms))


def refuse_states(terms, consumer: str) -> None:
    """InputError where ``terms`` add states that ``consumer`` does not carry."""
    with_states = [t for t in check_terms(terms) if TERMS[t].states]
    if with_states:
        raise InputError(f"{consumer} does not carry the states of the term(s) {', '.join(with_states)} "
                         "(pore pressure, temperature) yet; landau simulate and check without a history do, "
                         "and landau hopf and derive analyse them")


def _symbols(terms, symbol: Mapping[str, sp.Symbol] | None) -> dict[str, sp.Symbol]:
    return {name: (symbol or {}).get(name, sym) for name, sym, _, _ in parameters(terms)}


def steady_extra(terms, b: Balance) -> dict[str, sp.Expr]:
    """The steady values of the terms' states (canonical order; each sees those before it in ``b.extra``)."""
    out: dict[str, sp.Expr] = {}
    for st in states(terms):
        out[st.symbol.name] = st.steady(Balance(**{**b.__dict__, "extra": dict(out)}))
    return out


def _extra_for_load(terms, sym, sigma0, V, mu0) -> dict[str, sp.Expr]:
    """The steady states the normal load reads: their steady values must not depend on σ."""
    if not has_states(terms):
        return {}
    sd = sp.Dummy("sigma_ss")
    b = Balance(v=V, phis=(), F=sp.Integer(0), F_dot=sp.Integer(0), V_lp=V, k=sp.Integer(0), sigma0=sigma0,
                sigma=sd, mu=mu0, symbol=sym)
    ex = steady_extra(terms, b)
    return {n: e for n, e in ex.items() if not sp.sympify(e).has(sd)}


def _loads(terms, b: Balance) -> sp.Expr:
    """Σ loads(F): the terms' part of the normal load."""
    return sp.Add(*(load(b) for t in terms if (load := TERMS[t].load) is not None))


def _forces(terms, b: Balance) -> sp.Expr:
    """Σ forces: the terms' forces on the block."""
    return sp.Add(*(force(b) for t in terms if (force := TERMS[t].force) is not None))


def steady_spring_force(terms, sigma0, mu0, V, symbol=None) -> sp.Expr:
    """F_ss, the spring force at steady sliding: the root of F − σ(F) μ_ss + Σ forces(V) = 0 (the
    loads are affine in F, so the root is unique where it exists)."""
    Fs = sp.Dummy("F")
    sym = _symbols(terms, symbol)
    b = Balance(v=V, phis=(), F=Fs, F_dot=sp.Integer(0), V_lp=V, k=sp.Integer(0), sigma0=sigma0,
                symbol=sym, extra=_extra_for_load(terms, sym, sigma0, V, mu0))
    eq = Fs - (sigma0 + _loads(terms, b)) * mu0 + _forces(terms, b)
    roots = sp.solve(eq, Fs)
    if len(roots) != 1:
        raise InputError(f"the steady sliding of the spring-block with terms {', '.join(terms)} has no unique spring "
                         "force (a term's load must be affine in the spring force)")
    return roots[0]


def normal_load_ss(sigma0, mu0, V, terms, symbol=None):
    """σ_ss = σ₀ + Σ loads(F_ss), the normal load at steady sliding (σ₀ where no term loads the
    block); with ``gamma_ld`` (and ``eta``): (σ₀ + γ_LD ηV)/(1 − γ_LD μ_ss)."""
    terms = check_terms(terms)
    if not loads_block(terms):
        return sigma0
    sym = _symbols(terms, symbol)
    m = sp.Dummy("mu_ss")   # solved with μ_ss a symbol, then substituted: its expression is kept whole
    F_ss = steady_spring_force(terms, sigma0, m, V, sym)
    b = Balance(v=V, phis=(), F=F_ss, F_dot=sp.Integer(0), V_lp=V, k=sp.Integer(0), sigma0=sigma0, symbol=sym,
                extra=_extra_for_load(terms, sym, sigma0, V, m))
    num, den = sp.fraction(sp.cancel(sigma0 + _loads(terms, b)))
    if den.as_coeff_add()[0] < 0:   # written as (…)/(1 − γ μ_ss)
        num, den = -num, -den
    return (num / den).xreplace({m: mu0})


def mechanical_rhs(law, terms, X, u, at_slip, eq_phi, k, sigma0, V, *, mu0=None, sigma_ss=None, symbol=None,
                   extra=None):
    """(u-row, state rates) of the spring–block with ``terms``, in X = x − x_ss(t), u = ẋ − V.

    The force balance of :class:`Balance` with F = F_ss − kX, Ḟ = −k u, v = V + u, written so that
    its steady values cancel term by term: M u̇ = −kX − σ_ss(μ − μ_ss) − Δσ μ + Σ(forces − forces_ss),
    with σ = σ_ss + Δσ, Δσ = Σ(loads(F, s) − loads(F_ss, s_ss)) (s the terms' states).

    Parameters
    ----------
    law : FrictionLaw
    terms : tuple of str
        Checked terms (:func:`check_terms`).
    X, u : sympy.Expr
        Slip from steady sliding and slip-rate excess (symbols, or a consumer's scaled expressions).
    at_slip : dict
        The substitution of the law's symbols at this instant ({v: V + u}, and a consumer's own:
        states, parameters), applied with ``xreplace``.
    eq_phi : tuple of sympy.Expr
        The steady states φᵢ,ss (closed form or unknown symbols).
    k, sigma0, V : sympy.Expr
        Stiffness, normal load σ₀ and driving velocity.
    mu0, sigma_ss : sympy.Expr, optional
        μ_ss and σ_ss where the consumer has them as parameters (default: from the law and the terms).
    symbol : mapping, optional
        The terms' parameter symbols as the consumer names them (default their own).
    extra : mapping, optional
        Where the terms add states (:func:`states`): each one's excess over its steady value, by name, as
        the consumer writes it; required then.

    Returns
    -------
    (sympy.Expr, tuple of sympy.Expr)
        The right-hand side of M u̇ and of each dφᵢ/dt, then (with ``extra``) the rate of each term state.
    """
    from landau.laws.law import v as v_slip

    sym = _symbols(terms, symbol)
    phis = law.states
    mu = law.mu
    mu_now = mu.xreplace(at_slip)
    mu_0 = mu0 if mu0 is not None else mu.subs({v_slip: V, **dict(zip(phis, eq_phi, strict=True))}).xreplace(at_slip)
    sig_ss = sigma_ss if sigma_ss is not None else normal_load_ss(sigma0, mu_0, V, terms, sym)
    rates = [r.xreplace(at_slip) for r in law.rates]
    tstates = states(terms)
    if tstates and extra is None:
        raise InputError(f"the term(s) {', '.join(t for t in terms if TERMS[t].states)} add states; this "
                         "consumer does not carry them")
    # the terms are evaluated in plain symbols for X, u and the states' excesses (their differences from
    # steady sliding expanded there, then put back whole: a consumer's u = V(e^w − 1) is never expanded
    # into a difference of large numbers)
    Fs, Fv, Xd, ud = sp.Dummy("F_ss"), sp.Dummy("F"), sp.Dummy("X"), sp.Dummy("u")
    sd = {st.symbol.name: sp.Dummy(st.symbol.name) for st in tstates}
    back = {Xd: X, ud: u, **{sd[n]: (extra or {})[n] for n in sd}}
    ss_b = Balance(v=V, phis=tuple(eq_phi), F=Fs, F_dot=sp.Integer(0), V_lp=V, k=k, sigma0=sigma0, sigma=sig_ss,
                   mu=mu_0, symbol=sym)
    ex_ss = steady_extra(terms, ss_b)
    ex_now = {n: ex_ss[n] + sd[n] for n in sd}

    def balance(F, v, sigma=sp.Integer(0), sigma_dot=sp.Integer(0), dmu=(), ex=None):
        return Balance(v=v, phis=tuple(p.xreplace(at_slip) for p in phis), F=F, F_dot=-k * ud, V_lp=V, k=k,
                       sigma0=sigma0, sigma=sigma, sigma_dot=sigma_dot, mu=mu_now, dmu_dphi=dmu, symbol=sym,
                       extra=ex_now if ex is None else ex)

    # σ = σ_ss + Δσ; σμ − σ_ss μ_ss = σ_ss(μ − μ_ss) + Δσ μ
    dsig = sp.expand(_loads(terms, balance(Fs - k * Xd, V + ud)) - _loads(terms, balance(Fs, V, ex=ex_ss)))
    dsig = dsig.xreplace(back)
    force = -k * X - sig_ss * (mu_now - mu_0)
    if dsig != 0:
        force = force - dsig * mu_now
    extra_f = sp.expand(_forces(terms, balance(Fs - k * Xd, V + ud)) - _forces(terms, balance(Fs, V, ex=ex_ss)))
    extra_f = extra_f.xreplace(back)
    if extra_f != 0:
        force = force + extra_f
    sig = sig_ss + dsig
    sig_dot = (sp.diff(_loads(terms, balance(Fv, V + ud)), Fv) * (-k * ud)).xreplace(back)
    dmu = tuple(sp.diff(mu, ph).xreplace(at_slip) for ph in phis)
    b = balance(Fs - k * X, V + u, sig, sig_dot, dmu, ex={n: e.xreplace(back) for n, e in ex_now.items()})
    _add_term_rates(terms, b, rates)
    srates = _state_rates(terms, b, rates)
    out = [*rates, *(srates[st.symbol.name] for st in tstates)]
    if force.has(Fs) or any(r.has(Fs) for r in out):
        F_ss = steady_spring_force(terms, sigma0, mu_0, V, sym)
        force, out = force.xreplace({Fs: F_ss}), [r.xreplace({Fs: F_ss}) for r in out]
    return force, tuple(out)


def _add_term_rates(terms, b: Balance, rates: list) -> None:
    """Add every term's contribution to the law's state rates (in place)."""
    for t in terms:
        if (term_rates := TERMS[t].rates) is not None:
            for i, r in enumerate(term_rates(b)):
                if r != 0:
                    rates[i] = rates[i] + r


def _state_rates(terms, b: Balance, rates) -> dict[str, sp.Expr]:
    """The rates of the terms' states: each state's own rate (canonical order), then the contributions of
    other terms (``state_rates``), all read with dφᵢ/dt (``rates``) complete."""
    from dataclasses import replace

    b = replace(b, phi_rates=tuple(rates))
    out: dict[str, sp.Expr] = {}
    for st in states(terms):
        out[st.symbol.name] = st.rate(replace(b, extra_rates=dict(out)))
    for t in terms:
        if (contrib := TERMS[t].state_rates) is not None:
            for name, r in contrib(replace(b, extra_rates=dict(out))).items():
                out[name] = out[name] + r
    return out


def state_scales(terms, b: Balance) -> dict[str, sp.Expr]:
    """Each term state's typical size (:attr:`TermState.scale`) at the balance ``b`` (steady sliding)."""
    return {st.symbol.name: st.scale(b) for st in states(terms)}


def force_balance(law, terms, at, *, v, F, F_dot, V_lp, k, sigma0, symbol=None):
    """The force balance of :class:`Balance` at one instant, in physical form, for the consumers that
    integrate it as it stands (the load histories): σ = σ₀ + Σ loads(F), μ(v, φ), Σ forces and the state
    rates with every term's contribution, so that M v̇ = F − σ μ + Σ forces.

    Parameters
    ----------
    law : FrictionLaw
    terms : tuple of str
    at : dict
        The substitution of the law's symbols at this instant (v, φ…, parameters), applied with ``xreplace``.
    v, F, F_dot, V_lp, k, sigma0 : sympy.Expr or float
        Slip rate, spring force, its rate, load-point velocity, stiffness, σ₀.
    symbol : mapping, optional
        The terms' parameters as the consumer has them (symbols, or numbers).

    Returns
    -------
    (sigma, mu, forces, rates)
    """
    terms = check_terms(terms)
    refuse_states(terms, "the load histories (landau simulate --history)")
    sym = _symbols(terms, symbol)
    phis = tuple(p.xreplace(at) for p in law.states)
    mu_now = law.mu.xreplace(at)
    Fv = sp.Dummy("F")
    b = Balance(v=v, phis=phis, F=Fv, F_dot=F_dot, V_lp=V_lp, k=k, sigma0=sigma0, mu=mu_now, symbol=sym)
    loads = _loads(terms, b)
    sigma = sigma0 + loads.xreplace({Fv: F})
    sigma_dot = sp.diff(loads, Fv).xreplace({Fv: F}) * F_dot
    dmu = tuple(sp.diff(law.mu, ph).xreplace(at) for ph in law.states)
    b = Balance(v=v, phis=phis, F=F, F_dot=F_dot, V_lp=V_lp, k=k, sigma0=sigma0, sigma=sigma, sigma_dot=sigma_dot,
                mu=mu_now, dmu_dphi=dmu, symbol=sym)
    rates = [r.xreplace(at) for r in law.rates]
    _add_term_rates(terms, b, rates)
    return sigma, mu_now, _forces(terms, b), tuple(rates)


def steady_values(terms, sigma0: float, mu0: float, V: float, params) -> tuple[float, float]:
    """(F_ss, σ_ss) at steady sliding as numbers: the spring force and the normal load of
    :func:`steady_spring_force` and :func:`normal_load_ss` at these values.

    Both are solved once per set of terms in symbols (:func:`_steady_functions`) and evaluated
    here in floats: solving with the numbers themselves (sympy turns every float of the equation
    into a rational first, by PSLQ) cost 17 ms a call, which was most of the CPU of a compiled
    load history (``benchmarks/sections_springblock_paths.py``)."""
    terms = check_terms(terms)
    values = [float(sigma0), float(mu0), float(V)] + [float(params[name]) for name, *_ in parameters(terms)]
    try:
        F_ss, sigma_ss = (float(x) for x in _steady_functions(tuple((t, TERMS[t]) for t in terms))(*values))
    except (ArithmeticError, ValueError):   # a division by zero, an overflow, a root of a negative load
        F_ss = sigma_ss = math.inf
    if not (math.isfinite(F_ss) and math.isfinite(sigma_ss)):
        raise InputError(f"the steady sliding of the spring-block with terms {', '.join(terms)} has no finite spring "
                         f"force and normal load at sigma = {sigma0:g}, mu_ss = {mu0:g}, V = {V:g}")
    return F_ss, sigma_ss


@lru_cache(maxsize=None)
def _steady_functions(declared: tuple[tuple[str, Term], ...]) -> Callable[..., tuple[float, float]]:
    """(F_ss, σ_ss)(σ₀, μ_ss, V, the terms' parameters…) in floats, from :func:`steady_spring_force`
    and :func:`normal_load_ss` solved in symbols.  Keyed by the terms' declarations, not only their
    names, so that a term registered again under an old name is solved again."""
    terms = tuple(t for t, _ in declared)
    s0, m0, v = sp.Dummy("sigma0"), sp.Dummy("mu_ss"), sp.Dummy("V")
    sym = {name: symbol for name, symbol, *_ in parameters(terms)}
    F_ss = steady_spring_force(terms, s0, m0, v, sym)
    sigma_ss = normal_load_ss(s0, m0, v, terms, sym)
    # math first; a function math lacks (a term may write any sympy function) from mpmath
    return sp.lambdify([s0, m0, v, *sym.values()], (F_ss, sigma_ss), ["math", "mpmath"])


def loads_block(terms) -> bool:
    """True where one of ``terms`` changes the normal load (σ then follows the spring force)."""
    return any(TERMS[t].load is not None for t in terms)


def stiffness_in_rates(terms) -> bool:
    """True where one of ``terms`` makes the stiffness enter the state rates (α_LD): the Hopf point
    then comes from the general engine, not the Hopf line affine in k."""
    return any(TERMS[t].stiffness_in_rates for t in terms)


def load_slope(terms, params) -> float:
    """dσ/dF, the normal load's change per unit spring force (γ_LD with ``gamma_ld``, else 0)."""
    Fv = sp.Dummy("F")
    terms = check_terms(terms)
    b = Balance(v=sp.Integer(0), phis=(), F=Fv, F_dot=sp.Integer(0), V_lp=sp.Integer(0), k=sp.Integer(0),
                sigma0=sp.Integer(0), symbol=_symbols(terms, None),
                extra={st.symbol.name: sp.Dummy(st.symbol.name) for st in states(terms)})
    slope = sp.diff(_loads(terms, b), Fv)
    return float(slope.subs({sym: params.get(name, d) for name, sym, _, d in parameters(terms)})) if slope != 0 \
        else 0.0


def check_steady_sliding(law, mu_ss, params, V=None) -> None:
    """Raise :class:`~landau.errors.NoSteadySlidingError` where 1 − γ_LD μ_ss ≤ 0.

    Parameters
    ----------
    law : FrictionLaw
    mu_ss : float or ndarray
        The steady-state friction coefficient(s).
    params : mapping
        Resolved parameters (with ``gamma_ld``).
    V : float or ndarray, optional
        The driving velocities (for the message).
    """
    if "p_inf" in params:
        _check_effective_stress(law, params, V)
    g = np.asarray(params.get("gamma_ld", 0.0), dtype=float)
    margin = 1.0 - g * np.asarray(mu_ss, dtype=float)
    if np.any(~(margin > 0)):
        i = int(np.argmax(np.ravel(~(margin > 0) * np.ones_like(margin))))
        mu_i = float(np.ravel(np.broadcast_to(mu_ss, margin.shape))[i])
        g_i = float(np.ravel(np.broadcast_to(g, margin.shape))[i])
        where = "" if V is None else f" at V = {float(np.ravel(np.broadcast_to(V, margin.shape))[i]):g} m/s"
        raise NoSteadySlidingError(
            f"law {law.name!r}{where}: no steady sliding with gamma_ld = {g_i:g}: gamma_ld * mu_ss = "
            f"{g_i * mu_i:.6g} >= 1 (mu_ss = {mu_i:.6g}), so the normal load grows without bound as the "
            "spring pulls (Dieterich & Linker 1992); steady sliding needs gamma_ld * mu_ss < 1")


def _check_effective_stress(law, params, V) -> None:
    """NoSteadySlidingError where the effective normal stress σ₀ − p_∞ (+ γ_LD ηV) is not positive."""
    eff = (np.asarray(params["sigma"], dtype=float) - np.asarray(params["p_inf"], dtype=float)
           + np.asarray(params.get("gamma_ld", 0.0), dtype=float) * np.asarray(params.get("eta", 0.0), dtype=float)
           * np.asarray(1.0 if V is None else V, dtype=float))
    if np.any(~(eff > 0)):
        i = int(np.argmax(np.ravel(~(eff > 0) * np.ones_like(eff))))
        raise NoSteadySlidingError(
            f"law {law.name!r}: no steady sliding with pore pressure p_inf = "
            f"{float(np.ravel(np.broadcast_to(params['p_inf'], eff.shape))[i]):g}: the effective normal stress "
            f"sigma - p_inf = {float(np.ravel(eff)[i]):g} must be > 0 (Segall & Rice 1995)")


def check_values(params) -> None:
    """Each nonnegative term's value ≥ 0 (η, radiation damping), each further parameter in its domain."""
    for name, t in TERMS.items():
        if t.nonnegative and params.get(name, 0.0) < 0:
            raise InputError(f"parameter {name!r} ({t.meaning}) must be >= 0, got {params[name]!r}")
        for q in t.parameters:
            val = params.get(q.symbol.name)
            if val is None:
                continue
            if q.domain == "positive" and not val > 0:
                raise InputError(f"parameter {q.symbol.name!r} ({q.meaning}) must be > 0, got {val!r}")
            if q.domain == "nonnegative" and not val >= 0:
                raise InputError(f"parameter {q.symbol.name!r} ({q.meaning}) must be >= 0, got {val!r}")


__all__ = ["TERMS", "Balance", "Term", "TermParameter", "TermState", "alpha_ld", "check_steady_sliding",
           "check_terms", "eta", "force_balance",
           "gamma_ld", "load_slope", "loads_block", "mechanical_rhs", "normal_load_ss", "register_term",
           "steady_spring_force", "steady_values", "stiffness_in_rates", "symbols", "unregister_term", "parameters",
           "term_of", "states", "has_states", "refuse_states", "steady_extra", "state_scales"]

# the fault-physics terms with states (pore pressure and dilatancy, thermal pressurisation), declared in
# their own module on the classes above
from landau.systems import fault_terms as _fault_terms  # noqa: E402

TERMS.update(_fault_terms.FAULT_TERMS)
