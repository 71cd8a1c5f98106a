"""Fault-physics terms of the spring–block with states of their own: pore pressure with dilatancy,
and thermal pressurisation.

Both are declared on :class:`~landau.systems.springblock_terms.Term` (each term's own parameter is 0,
off, by default) and reach every consumer of the spring–block's terms from this one declaration.
Units are those of the fault per unit area: σ, p in Pa, k in Pa/m, η in Pa·s/m (a block in N is
consistent too, with p in N and β in 1/N).

``eps_dil`` — pore pressure and dilatancy (Segall & Rice 1995)
    The normal load is the effective one, σ̄ = σ − p (the term's load −p), and the porosity follows the
    law's *first* state φ₁ (θ of the aging and slip laws; for any other law the dependence is written
    through its first state in the same way)::

        φ_p = φ₀ − ε ln(V₀ φ₁/D_c),
        dp/dt = −(p − p_∞)/t_f − (1/β) dφ_p/dt = −(p − p_∞)/t_f + (ε/β) (dφ₁/dt)/φ₁.

    V₀ and D_c fix φ₀ only and drop out of the rate (the reference V₀ is the plate rate V, D_c the law's
    L: φ_p = φ₀ at steady sliding).  Steady sliding has p = p_∞ and σ̄_ss = σ − p_∞ (> 0 required).
    Parameters: ``eps_dil`` ε [1], ``p_inf`` p_∞ [Pa], ``t_drain`` t_f [s], ``beta`` β [1/Pa].
    For the aging law (μ = a_v + a ln(v/V*) + b ln(V*θ/L)), with inertia M and E = μ_ss ε/β, the
    characteristic equation of steady sliding is, with c = 1/t_f::

        MVλ + kV/λ + σ̄a − (V/L) [σ̄b − E λ/(λ + c)] / (λ + V/L) = 0,

    so the two named limits are plain spring–blocks (:func:`drained_kc`, :func:`undrained_kc`):
    drained (t_f → 0): the block without dilatancy at σ → σ − p_∞; undrained (t_f → ∞): the block at
    σ̄ with b → b − E/σ̄, k_c = [σ̄(b − a) − E]/L · [1 + MV²/(Lσ̄a)].  Undrained, steady sliding has no
    Hopf point for any k once ε ≥ ε_c = βσ̄(b − a)/μ_ss (:func:`stabilising_eps`), the
    dilatancy-stabilised regime; at finite t_f the quasi-static (M = 0) block keeps a Hopf point with
    k_c > c σ̄(b − a)/(L(c + V/L)) (it falls as t_f grows), so the stabilisation is the undrained limit.

``lambda_tp`` — thermal pressurisation, lumped (Rice 2006; Segall & Rice 2006)
    A slip zone of half-width w carries a uniform temperature rise T over the ambient and the pore
    pressure p of ``eps_dil`` (built in with it: p, p_∞, and t_f the hydraulic diffusion time).  The
    diffusion out of the zone, in Rice (2006) and Segall & Rice (2006) a diffusion equation across the
    zone, is reduced here to one relaxation each (the slowest mode of a slab: t = 4w²/(π²α))::

        dT/dt = τ v/(ρc · 2w) − T/t_th,       τ = σ̄ μ (the frictional shear stress),
        dp/dt = Λ dT/dt − (p − p_∞)/t_f + (dilatancy, above),

    with Λ = (α_f − α_n)/(β_f + β_n) [Pa/K] the pressurisation coefficient of Rice (2006).  Steady
    sliding: T_ss = τ_ss V t_th/(ρc·2w), p = p_∞.  Parameters: ``lambda_tp`` Λ [Pa/K], ``rho_c`` ρc
    [J/(m³K)], ``w_sz`` w [m], ``t_th`` t_th [s].  Valid while the zone is thin against the diffusion
    lengths (one mode represents the profile) and T stays where the coefficients are constant.

The block's state variables (the derivation's, and the columns of ``landau simulate``) are the excesses
over steady sliding, named ``p`` (p − p_∞, Pa) and ``T`` (T − T_ss, K); a law whose own symbols take
these names cannot carry the terms (:class:`~landau.systems.system.SpringBlock` refuses it).

References
----------
Segall, P. & Rice, J. R. (1995), Dilatancy, compaction, and slip instability of a fluid-infiltrated
fault, J. Geophys. Res. 100(B11), 22155–22171.
Rice, J. R. (2006), Heating and weakening of faults during earthquake slip, J. Geophys. Res. 111, B05311.
Segall, P. & Rice, J. R. (2006), Does shear heating of pore fluid contribute to earthquake nucleation?,
J. Geophys. Res. 111, B09316.
"""

from __future__ import annotations

import math
from typing import Mapping

import sympy as sp

from landau.errors import InputError
from landau.systems.springblock_terms import Balance, Term, TermParameter, TermState

eps_dil = sp.Symbol("eps_dil", nonnegative=True)
p_inf = sp.Symbol("p_inf", real=True)
t_drain = sp.Symbol("t_drain", positive=True)
beta = sp.Symbol("beta", positive=True)
lambda_tp = sp.Symbol("lambda_tp", nonnegative=True)
rho_c = sp.Symbol("rho_c", positive=True)
w_sz = sp.Symbol("w_sz", positive=True)
t_th = sp.Symbol("t_th", positive=True)
#: the derivation's variables: p − p_∞ and T − T_ss
p_pore = sp.Symbol("p", real=True)
T_slip = sp.Symbol("T", real=True)

SEGALL_RICE_1995 = "Segall & Rice (1995)"
TP_SOURCE = "Rice (2006); Segall & Rice (2006)"


def _pore_rate(b: Balance) -> sp.Expr:
    s = b.symbol
    # dp/dt = −(p − p_∞)/t_f + (ε/β) (dφ₁/dt)/φ₁  (Segall & Rice 1995, through the first state)
    return -(b.extra["p"] - s["p_inf"]) / s["t_drain"] + s["eps_dil"] / s["beta"] * b.phi_rates[0] / b.phis[0]


def _steady_temperature(b: Balance) -> sp.Expr:
    s = b.symbol
    # T_ss = τ_ss V t_th/(ρc·2w)
    return b.sigma * b.mu * b.v * s["t_th"] / (s["rho_c"] * 2 * s["w_sz"])


def _heating(b: Balance) -> sp.Expr:
    s = b.symbol
    # dT/dt = τ v/(ρc·2w) − T/t_th, τ = σ̄ μ
    return b.sigma * b.mu * b.v / (s["rho_c"] * 2 * s["w_sz"]) - b.extra["T"] / s["t_th"]


PORE = Term(
    eps_dil, "1", "dilatancy coefficient: porosity phi0 - eps_dil ln(V theta/L), effective stress sigma - p",
    SEGALL_RICE_1995, True,
    load=lambda b: -b.extra["p"],
    parameters=(
        TermParameter(p_inf, "Pa", "ambient pore pressure (steady sliding: p = p_inf)", 0.0, "real"),
        TermParameter(t_drain, "s", "drainage (hydraulic diffusion) time", 1.0, "positive"),
        TermParameter(beta, "1/Pa", "storage coefficient of the pore fluid", 1e-9, "positive"),
    ),
    states=(TermState(p_pore, "Pa", "pore pressure excess p - p_inf", steady=lambda b: b.symbol["p_inf"],
                      rate=_pore_rate, scale=lambda b: b.sigma),),
)

THERMAL = Term(
    lambda_tp, "Pa/K", "thermal pressurisation coefficient (alpha_f - alpha_n)/(beta_f + beta_n)", TP_SOURCE, True,
    parameters=(
        TermParameter(rho_c, "J/(m^3 K)", "volumetric heat capacity of the slip zone", 2.7e6, "positive"),
        TermParameter(w_sz, "m", "half-width of the slip zone", 1e-3, "positive"),
        TermParameter(t_th, "s", "thermal diffusion time of the slip zone", 1.0, "positive"),
    ),
    states=(TermState(T_slip, "K", "slip-zone temperature rise over its steady value",
                      steady=_steady_temperature,
                      rate=_heating, scale=lambda b: b.sigma / b.symbol["rho_c"]),),
    # dp/dt gains Λ dT/dt
    state_rates=lambda b: {"p": b.symbol["lambda_tp"] * b.extra_rates["T"]},
    requires=("eps_dil",),
)

#: the terms, in their argument order (after those of :mod:`landau.systems.springblock_terms`)
FAULT_TERMS: dict[str, Term] = {"eps_dil": PORE, "lambda_tp": THERMAL}


# --- the named cases of the dilatant aging-law block (closed forms) --------------------------------
def _aging(params: Mapping[str, float]) -> tuple[float, float, float, float]:
    for name in ("a", "b", "L", "sigma"):
        if name not in params:
            raise InputError(f"the dilatancy closed forms need the aging law's {name!r}")
    sig_eff = float(params["sigma"]) - float(params.get("p_inf", 0.0))
    if not sig_eff > 0:
        raise InputError(f"the effective normal stress sigma - p_inf = {sig_eff:g} must be > 0")
    return float(params["a"]), float(params["b"]), float(params["L"]), sig_eff


def _mu_ss(V: float, params: Mapping[str, float]) -> float:
    return float(params["a_v"]) + (float(params["a"]) - float(params["b"])) * math.log(V / float(params["V_s"]))


def drained_kc(V: float, params: Mapping[str, float]) -> float:
    """k_c of the drained limit (t_f → 0) of the dilatant aging-law block: the plain block at σ − p_∞,
    k_c = σ̄(b − a)/L · [1 + MV²/(Lσ̄a)] (Putelat et al. 2010, eq. 30 with η = 0)."""
    a, b, L, s = _aging(params)
    M = float(params.get("M", 0.0))
    return s * (b - a) / L * (1 + M * V ** 2 / (L * s * a))


def undrained_kc(V: float, params: Mapping[str, float]) -> float:
    """k_c of the undrained limit (t_f → ∞) of the dilatant aging-law block: b → b − E/σ̄ with
    E = μ_ss ε/β, k_c = [σ̄(b − a) − E]/L · [1 + MV²/(Lσ̄a)]; ≤ 0 (no Hopf point) for ε ≥ ε_c."""
    a, b, L, s = _aging(params)
    M = float(params.get("M", 0.0))
    E = _mu_ss(V, params) * float(params["eps_dil"]) / float(params["beta"])
    return (s * (b - a) - E) / L * (1 + M * V ** 2 / (L * s * a))


def stabilising_eps(V: float, params: Mapping[str, float]) -> float:
    """ε_c = βσ̄(b − a)/μ_ss: the undrained dilatant aging-law block has no Hopf point for any k at
    ε ≥ ε_c (the dilatancy-stabilised regime)."""
    a, b, _, s = _aging(params)
    return float(params["beta"]) * s * (b - a) / _mu_ss(V, params)


def dilatancy_regime(V: float, params: Mapping[str, float]) -> str:
    """The named regime of the undrained dilatant aging-law block: ``"dilatancy-stabilised"`` (ε ≥ ε_c,
    no Hopf point for any k) or ``"unstable below k_c"``."""
    return "dilatancy-stabilised" if float(params["eps_dil"]) >= stabilising_eps(V, params) else "unstable below k_c"


__all__ = ["FAULT_TERMS", "PORE", "THERMAL", "dilatancy_regime", "drained_kc", "stabilising_eps",
           "undrained_kc"]
