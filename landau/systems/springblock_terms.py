"""Optional terms of the spring–block: radiation damping and variable normal stress.

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

from dataclasses import dataclass

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
class Term:
    """One optional spring–block term: its parameter symbol, unit, meaning and source."""

    symbol: sp.Symbol
    unit: str
    meaning: str
    source: str
    nonnegative: bool = False


#: the optional terms, in their argument order
TERMS: dict[str, Term] = {
    "eta": Term(eta, "N s/m", "radiation damping, force eta*v (quasi-dynamic)", "Rice (1993)", True),
    "gamma_ld": Term(gamma_ld, "1", "normal load sigma = sigma0 + gamma_ld * spring force",
                     "Linker & Dieterich (1992)"),
    "alpha_ld": Term(alpha_ld, "1", "state response -alpha_ld dsigma/sigma to normal-stress changes",
                     "Linker & Dieterich (1992)"),
}


def check_terms(terms) -> tuple[str, ...]:
    """The requested terms, validated and in canonical order."""
    if isinstance(terms, str):
        terms = (terms,)
    terms = tuple(terms)
    unknown = [t for t in terms if t not in TERMS]
    if unknown:
        raise InputError(f"unknown spring-block term(s) {', '.join(map(repr, unknown))} "
                         f"(known: {', '.join(TERMS)})")
    return tuple(t for t in TERMS if t in terms)


def symbols(terms) -> tuple[sp.Symbol, ...]:
    """The parameter symbols of ``terms`` (canonical order)."""
    return tuple(TERMS[t].symbol for t in check_terms(terms))


def normal_load_ss(sigma0, mu0, V, terms):
    """σ_ss = (σ₀ + γ_LD ηV)/(1 − γ_LD μ_ss): the normal load at steady sliding (σ₀ without γ_LD)."""
    if "gamma_ld" not in terms:
        return sigma0
    damping = eta * V if "eta" in terms else 0
    return (sigma0 + gamma_ld * damping) / (1 - gamma_ld * mu0)


def mechanical_rhs(law, terms, X, u, at_slip, eq_phi, k, sigma0, V):
    """(u-row, state rates) of the spring–block with ``terms``, in X = x − x_ss(t), u = ẋ − V.

    Parameters
    ----------
    law : FrictionLaw
    terms : tuple of str
        Checked terms (:func:`check_terms`).
    X, u : sympy.Symbol
        Slip from steady sliding and slip-rate excess.
    at_slip : dict
        {v: V + u}.
    eq_phi : tuple of sympy.Expr
        The steady states φᵢ,ss (closed form or unknown symbols).
    k, sigma0, V : sympy.Symbol
        Stiffness, normal load σ₀ and driving velocity.

    Returns
    -------
    (sympy.Expr, tuple of sympy.Expr)
        The right-hand side of M u̇ and of each dφᵢ/dt.
    """
    from landau.laws.law import v as v_slip

    phis = law.states
    mu = law.mu
    mu_now = mu.subs(at_slip)
    mu_0 = mu.subs({v_slip: V, **dict(zip(phis, eq_phi, strict=True))})
    sig_ss = normal_load_ss(sigma0, mu_0, V, terms)
    rates = [r.subs(at_slip) for r in law.rates]
    if "gamma_ld" in terms:
        sig = sig_ss - gamma_ld * k * X
        force = -k * X - (sig * mu_now - sig_ss * mu_0)
        if "alpha_ld" in terms:
            sig_dot = -gamma_ld * k * u
            rates[0] = rates[0] - alpha_ld * sig_dot / (sig * sp.diff(mu, phis[0]).subs(at_slip))
    else:
        force = -k * X - sig_ss * (mu_now - mu_0)
    if "eta" in terms:
        force = force - eta * u
    return force, tuple(rates)


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


def check_values(params) -> None:
    """η ≥ 0 and finite term values."""
    if params.get("eta", 0.0) < 0:
        raise InputError(f"parameter 'eta' (radiation damping) must be >= 0, got {params['eta']!r}")


__all__ = ["TERMS", "Term", "alpha_ld", "check_steady_sliding", "check_terms", "eta", "gamma_ld",
           "mechanical_rhs", "normal_load_ss", "symbols"]
