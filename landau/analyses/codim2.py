"""The generalised-Hopf (Bautin) point and the fold of cycles: one type each, for every route.

A **generalised-Hopf point** is a point (p₁*, p₂*) of a Hopf curve where the first Lyapunov
coefficient l₁ (equivalently landau's Landau coefficient Λ) vanishes (Kuznetsov 2004, §8.3).
The same type is returned by the general two-parameter continuation
(:func:`landau.analyses.continuation.generalised_hopf`, p₁ the system's parameter, p₂ a second one), by the
spring–block's Hopf line k_c(V) (:func:`landau.analyses.transition.codim2_points`,
:func:`landau.analyses.bautin.bautin_point`: p₁ = k, p₂ = V) and by the check from periodic orbits alone
(:func:`landau.verify.springblock.continuation.codim2_velocity`).

Near the point Λ ≈ Λ'·(p₂ − p₂*) and the quintic amplitude equation

    dA/dT = a (p₁ − p₁,c) A + b A|A|² + c A|A|⁴,   Λ = 2 Re b,  Λ₅ = 2 Re c,

has a **fold of cycles** at p₁,fold − p₁,c = Λ²/(8 Λ₅ Re a) with amplitude sqrt(−2Λ/Λ₅) where Λ and
Λ₅ have opposite signs (:func:`landau.analyses.bautin.fold_of_cycles`).  A fold of cycles — predicted so,
or located on a continued branch of periodic orbits — is a :class:`FoldOfCycles`.

References
----------
Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, §8.3.
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a spring–block
system. J. Mech. Phys. Solids 58, 27–53 (Figs 11, 12).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Mapping

if TYPE_CHECKING:  # pragma: no cover
    import numpy as np

    from landau.derivation.hopf import HopfResult

#: the spring–block's two parameters: p₁ = k (the Hopf parameter), p₂ = V
SPRING_BLOCK_PARAMETERS = ("k", "V")

_SIDE = {-1: "V < V*", 1: "V > V*", 0: "none"}


@dataclass(frozen=True)
class FoldOfCycles:
    """A fold (saddle-node) of cycles: where a stable and an unstable cycle meet (a Floquet multiplier +1).

    Parameters
    ----------
    parameter : str
        Name of the parameter the fold is a turning point in (p₁; ``"k"``, ``"V"``, …).
    p_fold : float
        Its value at the fold.
    amplitude : float
        max|y_n − y₀,n| of the cycle at the fold (normalised component; the slip X in m for the
        spring–block).
    p_c : float, optional
        The Hopf point the branch of cycles is born at (for a prediction of the amplitude equation:
        p_fold = p_c + Λ²/(8 Λ₅ Re a)).
    fixed : mapping
        The other parameters' values at the fold (e.g. ``{"k": …, "kappa": …}`` on a fold curve in V).
    half_peak_to_peak : float, optional
        Half the peak-to-peak slip of the cycle (branches of periodic orbits).
    z : ndarray, optional
        The cycle's point on the Poincaré section (periodic-orbit routes; seeds a fold curve).
    """

    parameter: str
    p_fold: float
    amplitude: float
    p_c: float | None = None
    fixed: Mapping[str, float] = field(default_factory=dict)
    half_peak_to_peak: float | None = None
    z: "np.ndarray | None" = field(default=None, repr=False, compare=False)

    @property
    def offset(self) -> float:
        """p_fold − p_c (NaN without a Hopf point)."""
        return math.nan if self.p_c is None else self.p_fold - self.p_c

    @property
    def side(self) -> int:
        """+1 if the fold lies at p > p_c, −1 if at p < p_c (0 without a Hopf point)."""
        off = self.offset
        return 0 if not math.isfinite(off) else (1 if off > 0 else -1)

    def value(self, name: str) -> float:
        """The value of parameter ``name`` at the fold (``parameter`` or one of ``fixed``)."""
        if name == self.parameter:
            return self.p_fold
        if name in self.fixed:
            return float(self.fixed[name])
        raise KeyError(f"{name!r} (known: {', '.join([self.parameter, *self.fixed])})")

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready fields (``p_fold``, ``p_c``, ``offset``, ``amplitude``, ``side`` for a prediction)."""
        out: dict[str, Any] = {"p_fold": self.p_fold}
        if self.p_c is not None:
            out.update(p_c=self.p_c, offset=self.offset)
        out["amplitude"] = self.amplitude
        if self.p_c is not None:
            out["side"] = self.side
        if self.half_peak_to_peak is not None:
            out["half_peak_to_peak"] = self.half_peak_to_peak
        out.update(self.fixed)
        return out

    def __repr__(self) -> str:
        at = "".join(f", {k} = {v:.6g}" for k, v in self.fixed.items())
        if self.p_c is None:
            return f"FoldOfCycles({self.parameter} = {self.p_fold:.10g}{at}, amplitude {self.amplitude:.4g})"
        return (f"FoldOfCycles(p_fold = {self.p_fold:.10g} (p_c {'+' if self.offset >= 0 else '-'} "
                f"{abs(self.offset):.4g}){at}, amplitude {self.amplitude:.4g})")


@dataclass(frozen=True)
class GeneralisedHopfPoint:
    """A generalised-Hopf (Bautin) point: a Hopf point with l₁ = 0 (Λ = 0), Kuznetsov (2004) §8.3.

    Parameters
    ----------
    system : str
        Name of the system (the friction law for the spring–block).
    parameters : (str, str)
        Names of p₁ (the Hopf parameter) and p₂ (``("k", "V")`` for the spring–block).
    p1, p2 : float
        The point.
    omega : float
        Angular frequency ω of the critical pair (rad/s).
    equilibrium : tuple of float
        The equilibrium at the point (empty where not computed).
    l1 : float, optional
        The first Lyapunov coefficient at the located point — zero to the located accuracy (the
        check of the point); None where not evaluated there.
    l2 : float, optional
        Second Lyapunov coefficient Re c₂ in Kuznetsov's normalisation (⟨q, q⟩ = 1, ⟨p, q⟩ = 1),
        not divided by ω: the number MatCont (``nf_GH.m``) and BifurcationKit print.  NaN where
        the system is a DAE (no Kuznetsov normalisation); None where not computed.
    Lambda5 : float, optional
        Quintic coefficient Λ₅ = 2 Re c of landau's amplitude equation (normalised component 1).
    sign_below, sign_above : int
        Signs of Λ (or l₁) just below and above p₂* (−1 supercritical, +1 subcritical; 0 unknown).
    re_a : float, optional
        Re a = d Re λ/dp₁ at the point (spring–block: −Γ̄).
    dLambda_dp2 : float, optional
        Slope dΛ/dp₂ along the Hopf curve at the point.
    hopf : HopfResult, optional
        The full Hopf analysis at the point.
    iterations : int
        Iterations of the locating method (periodic-orbit route).
    history : tuple of (float, float)
        (p₂, test function) pairs evaluated while locating the point (periodic-orbit route: the
        branch curvature c₂ of :func:`~landau.verify.springblock.continuation.branch_curvature`).

    Notes
    -----
    The fold of cycles born at the point: with Λ ≈ Λ'(p₂ − p₂*), the quintic amplitude equation
    gives p₁,fold − p₁,c ≈ :attr:`fold_p1_coefficient` (p₂ − p₂*)² and amplitude
    ≈ :attr:`fold_amplitude_coefficient` |p₂ − p₂*|^{1/2} on the side :attr:`fold_side`
    (:meth:`predicted_fold`).  The spring–block's coordinates read by name: :attr:`V`,
    :attr:`k_c` (= :attr:`k`; ``kc`` is its deprecated alias), :attr:`omega_c` (= ``omega``).
    """

    system: str
    parameters: tuple[str, str]
    p1: float
    p2: float
    omega: float
    equilibrium: tuple[float, ...] = ()
    l1: float | None = None
    l2: float | None = None
    Lambda5: float | None = None
    sign_below: int = 0
    sign_above: int = 0
    re_a: float | None = None
    dLambda_dp2: float | None = None
    hopf: "HopfResult | None" = field(default=None, repr=False, compare=False)
    iterations: int = 0
    history: tuple[tuple[float, float], ...] = field(default=(), repr=False, compare=False)

    # --- named coordinates ----------------------------------------------------------------
    def value(self, name: str) -> float:
        """The value of the parameter ``name`` (p₁ or p₂) at the point."""
        if name == self.parameters[0]:
            return self.p1
        if name == self.parameters[1]:
            return self.p2
        raise KeyError(f"{name!r} (the point's parameters: {', '.join(self.parameters)})")

    def _named(self, name: str) -> float:
        try:
            return self.value(name)
        except KeyError:
            raise AttributeError(f"this generalised-Hopf point has no parameter {name!r} "
                                 f"(its parameters: {', '.join(self.parameters)})") from None

    @property
    def V(self) -> float:
        """Spring–block: the driving velocity V* (m/s), p₂."""
        return self._named("V")

    @property
    def k_c(self) -> float:
        """Spring–block: the critical stiffness k_c(V*) (N/m), p₁."""
        return self._named("k")

    k = k_c
    kc = k_c    # deprecated alias of k_c, kept for one release

    @property
    def omega_c(self) -> float:
        """The angular frequency ω (rad/s)."""
        return self.omega

    @property
    def Gamma_bar(self) -> float | None:
        """Spring–block: Γ̄ = −Re a (1/(N s))."""
        return None if self.re_a is None else -self.re_a

    # --- the fold of cycles ------------------------------------------------------------------
    @property
    def fold_side(self) -> int:
        """−1: the fold of cycles exists for p₂ < p₂*, +1 for p₂ > p₂*, 0: none (Λ₅ or Λ' zero or unknown)."""
        L5, dl = self.Lambda5, self.dLambda_dp2
        if L5 is None or dl is None or L5 == 0 or dl == 0 or not (math.isfinite(L5) and math.isfinite(dl)):
            return 0
        return 1 if dl * L5 < 0 else -1

    @property
    def fold_p1_coefficient(self) -> float:
        """p₁,fold − p₁,c(p₂) ≈ this × (p₂ − p₂*)²: Λ'²/(8 Λ₅ Re a) (NaN without a fold)."""
        L5, dl, ra = self.Lambda5, self.dLambda_dp2, self.re_a
        if self.fold_side == 0 or not ra or L5 is None or dl is None:  # (fold_side == 0 covers None)
            return math.nan
        return dl ** 2 / (8 * L5 * ra)

    @property
    def fold_amplitude_coefficient(self) -> float:
        """Amplitude at the fold ≈ this × |p₂ − p₂*|^{1/2}: sqrt(2|Λ'|/|Λ₅|) (NaN without a fold)."""
        L5, dl = self.Lambda5, self.dLambda_dp2
        if self.fold_side == 0 or L5 is None or dl is None:  # (fold_side == 0 covers None)
            return math.nan
        return math.sqrt(2 * abs(dl) / abs(L5))

    def predicted_fold(self, p2: float) -> FoldOfCycles | None:
        """The fold of cycles at p₂ from the expansion about the point, or None on the side without one.

        Its ``p_c`` is p₁* (the Hopf curve's own slope is not part of the expansion): read
        ``offset`` as p₁,fold − p₁,c(p₂)."""
        dv = p2 - self.p2
        if self.fold_side == 0 or dv == 0 or (dv > 0) != (self.fold_side > 0):
            return None
        return FoldOfCycles(self.parameters[0], self.p1 + self.fold_p1_coefficient * dv * dv,
                            self.fold_amplitude_coefficient * math.sqrt(abs(dv)), p_c=self.p1,
                            fixed={self.parameters[1]: float(p2)})

    # --- rendering -------------------------------------------------------------------------------
    def as_dict(self) -> dict[str, Any]:
        """JSON-ready fields.

        The spring–block (parameters k, V) names the point ``V``, ``kc``, ``omega_c`` with the signs
        of Λ and, where Λ₅ is known, ``Lambda5``, ``l2``, ``Gamma_bar``, ``dLambda_dV`` and the
        ``fold_of_cycles`` expansion; other systems give ``parameters``, ``p1``, ``p2``, ``omega``,
        ``equilibrium``, ``l2`` and ``l1``."""
        if tuple(self.parameters) != SPRING_BLOCK_PARAMETERS:
            return {"system": self.system, "parameters": list(self.parameters), "p1": self.p1, "p2": self.p2,
                    "omega": self.omega, "equilibrium": list(self.equilibrium), "l2": self.l2, "l1": self.l1}
        out: dict[str, Any] = {"V": self.p2, "k_c": self.p1, "kc": self.p1, "omega_c": self.omega}
        if self.Lambda5 is not None:
            out.update(Lambda5=self.Lambda5, l2=self.l2, Gamma_bar=self.Gamma_bar, dLambda_dV=self.dLambda_dp2)
        out.update(sign_below=self.sign_below, sign_above=self.sign_above)
        if self.Lambda5 is not None:
            out["fold_of_cycles"] = {
                "side": _SIDE[self.fold_side], "k_minus_kc_per_dV2": self.fold_p1_coefficient,
                "amplitude_per_sqrt_dV": self.fold_amplitude_coefficient,
                "formula": "k_fold - k_c(V) = -Lambda(V)^2/(8 Lambda5 Gamma_bar), "
                           "amplitude = sqrt(-2 Lambda(V)/Lambda5)"}
        return out

    def __repr__(self) -> str:
        if tuple(self.parameters) == SPRING_BLOCK_PARAMETERS:
            head = f"V* = {self.p2:.8g} m/s, k_c = {self.p1:.6g} N/m, omega_c = {self.omega:.6g} rad/s"
        else:
            head = (f"{self.system}: {self.parameters[0]} = {self.p1:.10g}, {self.parameters[1]} = {self.p2:.10g}, "
                    f"ω = {self.omega:.8g}")
        parts = [head]
        nat = {-1: "super", 1: "sub"}
        if self.sign_below and self.sign_above:
            parts.append(f"{nat[self.sign_below]}critical below, {nat[self.sign_above]}critical above")
        if self.Lambda5 is not None:
            parts.append(f"Lambda5 = {self.Lambda5:.6g}")
        if self.l2 is not None or tuple(self.parameters) != SPRING_BLOCK_PARAMETERS:
            parts.append("l2 = " + ("not computed" if self.l2 is None else f"{self.l2:.6g}"))
        if self.fold_side:
            parts.append(f"fold of cycles for {self.parameters[1]} {'>' if self.fold_side > 0 else '<'} "
                         f"{self.parameters[1]}*: {self.parameters[0]} - {self.parameters[0]}c = "
                         f"{self.fold_p1_coefficient:.4g} ({self.parameters[1]} - {self.parameters[1]}*)^2")
        return f"GeneralisedHopfPoint({'; '.join(parts)})"
