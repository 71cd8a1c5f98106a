"""Stick–slip amplitudes, growth rate and apparent critical stiffness near the Hopf line.

Putelat et al. (2010), eqs (22)–(25) and Sec. 3.2.  With the engine's coefficients
(:mod:`landau.derivation.multiscale`; C = 2 sqrt(2Γ̄/|Λ|) is normalisation-free):

* slip amplitude, eq. (23):        max|x − x₀| ≈ C sqrt(k_c − k)              (Λ < 0, k < k_c)
* slip-rate amplitude, eq. (24):   max|ẋ − V| ≈ max|x − x₀| · [ω_c − (Ω̄ + χΓ̄/Λ)(k_c − k)]
* growth rate:                     Γ = 2Γ̄ (k_c − k)   (Γ of eq. 21 with ε = 1, k₂ = k − k_c; 1/s)
* apparent critical stiffness, eq. (25), for a noise/measurement level Δx:
      k̂ = k_c + |δ|²Λ(Δx)²/(16ω_c²F_V) = k_c + Λ(Δx)²/(8Γ̄)
  (16ω_c²F_V/|δ|² = 8Γ̄ by eq. 21).  Eq. (25) has (Δx)²; the M = 0 formula printed at the
  end of Sec. 3.2 has (Δx)³ (a misprint: eq. (25) gives (Δx)²).

Where Λ ≥ 0 there is no small stable cycle below threshold: the amplitudes are NaN there
(the same C with |Λ| is the unstable cycle for k > k_c).  The figures of the paper plot
these at k_c − k = 0.001 k_c (``rel_distance``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np
from scipy.optimize import minimize_scalar

from landau.derivation.multiscale import Derivation
from landau.errors import InputError

#: distance from threshold used by the paper's figures: k_c − k = 0.001 k_c
PAPER_DISTANCE = 1e-3


def _check_distance(rel_distance: float) -> None:
    if not (np.isfinite(rel_distance) and 0 < rel_distance < 1):
        raise InputError(f"relative distance to threshold (k_c - k)/k_c must be in (0, 1), got {rel_distance!r}")


def growth_rate(d: Derivation, Vs, params: Mapping[str, float] | None = None,
                rel_distance: float = PAPER_DISTANCE) -> np.ndarray:
    """Γ = 2Γ̄(k_c − k) at k_c − k = rel_distance·k_c (1/s; eqs 21, 32)."""
    _check_distance(rel_distance)
    r = d.evaluate(Vs, params, ["Gamma_bar"])
    return 2 * r["Gamma_bar"] * rel_distance * r["kc"]


def slip_amplitude(d: Derivation, Vs, params: Mapping[str, float] | None = None,
                   rel_distance: float = PAPER_DISTANCE) -> np.ndarray:
    """max|x − x₀| ≈ C sqrt(k_c − k) at k_c − k = rel_distance·k_c (m; eq. 23); NaN where Λ ≥ 0."""
    _check_distance(rel_distance)
    r = d.evaluate(Vs, params, ["Gamma_bar", "Lambda"])
    lam = r["Lambda"]
    C = 2 * np.sqrt(2 * r["Gamma_bar"] / np.abs(np.where(lam < 0, lam, np.nan)))
    return C * np.sqrt(rel_distance * r["kc"])


def slip_rate_amplitude(d: Derivation, Vs, params: Mapping[str, float] | None = None,
                        rel_distance: float = PAPER_DISTANCE) -> np.ndarray:
    """max|ẋ − V| ≈ max|x − x₀|·[ω_c − (Ω̄ + χΓ̄/Λ)(k_c − k)] (m/s; eq. 24); NaN where Λ ≥ 0
    or where the frequency correction exceeds ω_c (the expansion is not valid at that distance)."""
    _check_distance(rel_distance)
    r = d.evaluate(Vs, params, ["Gamma_bar", "Omega_bar", "Lambda", "chi"])
    lam = np.where(r["Lambda"] < 0, r["Lambda"], np.nan)
    dk = rel_distance * r["kc"]
    slip = 2 * np.sqrt(2 * r["Gamma_bar"] / np.abs(lam)) * np.sqrt(dk)
    freq = r["omega_c"] - (r["Omega_bar"] + r["chi"] * r["Gamma_bar"] / lam) * dk
    # a frequency correction larger than ω_c means the expansion is not valid at this distance
    return slip * np.where(freq > 0, freq, np.nan)


def apparent_stiffness(d: Derivation, Vs, dx: float, params: Mapping[str, float] | None = None) -> np.ndarray:
    """k̂(V; Δx) of eq. (25): k_c + Λ(Δx)²/(8Γ̄) (N/m).

    For Λ < 0 the stable cycle reaches the amplitude Δx at k = k̂ < k_c; for Λ > 0 k̂ > k_c
    is where the unstable cycle has amplitude Δx.  NaN where there is no Hopf point."""
    if not (np.isfinite(dx) and dx > 0):
        raise InputError(f"measurement/noise level dx must be > 0 (m), got {dx!r}")
    r = d.evaluate(Vs, params, ["Gamma_bar", "Lambda"])
    return r["kc"] + r["Lambda"] * dx ** 2 / (8 * r["Gamma_bar"])


@dataclass(frozen=True)
class GrowthRateMax:
    """Maximum over V of Γ/(k_c − k) = 2Γ̄ (Sec. 3.2: Γ_DR^max) and where it is reached."""

    V: float
    value: float  # 2Γ̄ at V [1/(N s) · m ... i.e. s/kg]

    def __repr__(self) -> str:
        return f"GrowthRateMax(Gamma/(kc-k) = {self.value:.8g} s/kg at V = {self.V:.8g} m/s)"


def growth_rate_max(d: Derivation, params: Mapping[str, float] | None = None,
                    lo: float = 1e-9, hi: float = 1.0) -> GrowthRateMax:
    """Γ_max/(k_c − k) = max_V 2Γ̄(V) in [lo, hi] (Sec. 3.2; inertia makes Γ non-monotonic).

    A grid in log V brackets the maximum, a bounded Brent search refines it.  Raises
    :class:`InputError` when the maximum sits on an end of [lo, hi] (no interior maximum,
    e.g. M = 0 where Γ grows linearly with V)."""
    if not (0 < lo < hi):
        raise InputError(f"need 0 < lo < hi, got {lo!r}:{hi!r}")
    p = d.block.resolve(params)
    Vs = np.logspace(math.log10(lo), math.log10(hi), 400)
    g = 2 * d.evaluate(Vs, p, ["Gamma_bar"])["Gamma_bar"]
    if not np.any(np.isfinite(g)):
        raise InputError("no Hopf point in the velocity range")
    i = int(np.nanargmax(g))
    if i == 0 or i == len(Vs) - 1:
        raise InputError(f"Gamma_bar has no interior maximum in [{lo:g}, {hi:g}] m/s")

    def f(x: float) -> float:
        return -2 * float(d.evaluate(np.array([math.exp(x)]), p, ["Gamma_bar"])["Gamma_bar"][0])

    res = minimize_scalar(f, bounds=(math.log(Vs[i - 1]), math.log(Vs[i + 1])), method="bounded",
                          options={"xatol": 1e-12})
    return GrowthRateMax(math.exp(res.x), -float(res.fun))
