"""The check's contract: a verdict that rests on the amplitude equation's own scaling.

The cubic amplitude equation predicts the cycle's amplitude to leading order, A = C·sqrt|p − p_c|;
the next order of the same expansion changes it by a relative amount κ·ε² (Kuznetsov 2004,
Sec. 3.5; Putelat et al. 2010, eqs 20–23).  So a right prediction has a measured relative error
e(ε²) = A_sim/A_pred − 1 that **falls like ε¹ in ε²** and **extrapolates to zero** as ε² → 0, whatever
the size of κ; a wrong Landau coefficient Λ (off by a factor q) leaves an error q^{−1/2} − 1 that
does not fall.  A fixed margin at one ε² cannot tell these apart (a law with a large κ fails it, a
wrong Λ with a small error passes it); the two measured properties can:

* the **fitted exponent** p of |e| ∝ (ε²)^p over the measured ε² lies in :data:`EXPONENT_BAND`
  (1 when κ ≠ 0; 2 when κ vanishes by symmetry, as for van der Pol's half peak-to-peak swing);
* the **extrapolated error** e₀ of the fit e = e₀ + κ·ε² (+ κ₂·ε⁴ when three or more ε² are
  measured) is at most :data:`EXTRAPOLATION_BOUND` in magnitude (κ is the *measured next-order
  coefficient*).  From two points the fit leaves −κ₂ε⁴/4 in e₀; where that exceeds the bound the
  check measures a third ε² (:func:`landau.check` refines by ε²/4) and fits the ε⁴ term as well.

An error below its point's resolution — :data:`ERROR_FLOOR`, or 3·rtol/|1 − m| where the
shooting's residual rtol is amplified by the amplitude multiplier m, whichever is larger — carries
no exponent; when no two points are above their floors only the extrapolated error is judged.

**Resolution.**  The cycle's amplitude Floquet multiplier is m ≈ exp(−2 Re λ(p)·T), so
|1 − m| ≈ 2|Re λ'(p_c)|·|p − p_c|·2π/ω_c.  Shooting fixes the amplitude only to its residual
divided by |1 − m|; below :data:`MULTIPLIER_RESOLUTION` every nearby closed-looking orbit passes
(the stability cannot be told from 1 in float64 arithmetic) and the check reports "cannot resolve
at this ε²", naming the resolvable range, never a disagreement.

References
----------
Kuznetsov, Y. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed. Springer, Sec. 3.5.
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a spring–block
system. J. Mech. Phys. Solids 58, 27–53.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

#: fitted exponent p of |rel. error| ∝ (ε²)^p that agrees: 1 expected, 2 when the O(ε²) term vanishes
EXPONENT_BAND = (0.75, 2.5)
#: largest |error extrapolated to ε² → 0| that agrees (a Landau coefficient 2 % off moves it by 1 %)
EXTRAPOLATION_BOUND = 0.01
#: relative errors below this are at the shooting's resolution (also: 3·rtol/|1 − m|, whichever is larger)
ERROR_FLOOR = 1e-5
#: the default companion of a single ε² is ε²/RATIO (the error should fall by RATIO)
RATIO = 4.0
#: smallest |1 − m| of the amplitude Floquet multiplier that the shooting resolves (residual 1e-10)
MULTIPLIER_RESOLUTION = 1e-6
#: how many times the check divides ε² by RATIO looking for the range where the scaling holds
REFINEMENTS = 2


def multiplier_gap(prediction, eps2: float, scale: float) -> float:
    """Predicted |1 − m| of the cycle's amplitude Floquet multiplier at distance ε²·scale from p_c.

    Parameters
    ----------
    prediction : HopfResult
        The Hopf point (``dlambda_dp``, ``omega_c``).
    eps2 : float
        Distance ε² from the Hopf point (relative to ``scale``).
    scale : float
        |p_c|, or 1 where ε² is an absolute distance.

    Returns
    -------
    float
        2|Re λ'(p_c)|·ε²·scale·2π/ω_c (the radial Floquet exponent −2 Re λ over one period).
    """
    return 2.0 * abs(prediction.dlambda_dp.real) * eps2 * scale * 2.0 * math.pi / prediction.omega_c


def smallest_resolvable_eps2(prediction, scale: float) -> float:
    """The ε² at which :func:`multiplier_gap` equals :data:`MULTIPLIER_RESOLUTION` (inf if Re λ' = 0)."""
    per = multiplier_gap(prediction, 1.0, scale)
    return MULTIPLIER_RESOLUTION / per if per > 0 and math.isfinite(per) else math.inf


def error_floor(gap: float | None, rtol: float = 1e-10) -> float:
    """The relative amplitude error a shot cycle resolves: max(ERROR_FLOOR, 3·rtol/|1 − m|).

    Parameters
    ----------
    gap : float or None
        Measured |1 − m| of the amplitude Floquet multiplier (None: unknown).
    rtol : float
        The shooting's residual / integration tolerance.

    Returns
    -------
    float
    """
    if gap is None or not gap > 0:
        return ERROR_FLOOR
    return max(ERROR_FLOOR, 3.0 * rtol / gap)


def measurement_set(eps2, lo: float, hi: float) -> tuple[tuple[float, ...], str]:
    """The ε² to measure for a request, inside the resolvable range [lo, hi].

    A single ε² gets the companion ε²/:data:`RATIO` (or ε²·RATIO when ε²/RATIO is not resolvable
    and ε²·RATIO is); a sequence is used as given (sorted, largest first).  Returns the set and, when
    no second ε² fits, an empty set with the reason.
    """
    if isinstance(eps2, (int, float, np.floating)):
        e = float(eps2)
        if e / RATIO >= lo:
            return (e, e / RATIO), ""
        if e * RATIO <= hi:
            return (e * RATIO, e), ""
        return (), (f"no second eps2 within the resolvable range [{lo:.3g}, {hi:.3g}] to measure the "
                    f"next-order coefficient")
    vals = tuple(sorted({float(v) for v in eps2}, reverse=True))
    return vals, ""


@dataclass(frozen=True)
class Scaling:
    """The measured error against the theory's scaling e(ε²) = e₀ + κ·ε² + O(ε⁴).

    Parameters
    ----------
    eps2 : tuple of float
        The measured ε², largest first.
    rel_errors : tuple of float
        A_sim/A_pred − 1 at each.
    exponent : float or None
        Fitted p in |e| ∝ (ε²)^p over the errors above :data:`ERROR_FLOOR` (None when fewer than two).
    coefficient : float or None
        κ, the measured next-order coefficient (slope of e against ε² at ε² = 0).
    extrapolated : float or None
        e₀, the error extrapolated to ε² → 0 (linear in ε² from two points, quadratic from three on).
    holds : bool
        Whether the contract holds (exponent in band, |e₀| within bound, or all errors below the floor).
    reason : str
        Why not, in one phrase.
    """

    eps2: tuple[float, ...]
    rel_errors: tuple[float, ...]
    exponent: float | None
    coefficient: float | None
    extrapolated: float | None
    holds: bool
    reason: str = ""

    def describe(self) -> str:
        """One phrase: exponent, next-order coefficient and extrapolated error."""
        parts = []
        if self.exponent is not None:
            parts.append(f"error ~ (eps2)^{self.exponent:.2f}")
        if self.coefficient is not None:
            parts.append(f"next-order coefficient {self.coefficient:.3g}")
        if self.extrapolated is not None:
            parts.append(f"extrapolated to eps2 -> 0: {self.extrapolated:+.3%}")
        return ", ".join(parts)

    def as_dict(self) -> dict:
        return {"eps2": list(self.eps2), "rel_errors": list(self.rel_errors), "exponent": self.exponent,
                "next_order_coefficient": self.coefficient, "extrapolated_error": self.extrapolated,
                "holds": self.holds, "reason": self.reason, "exponent_band": list(EXPONENT_BAND),
                "extrapolation_bound": EXTRAPOLATION_BOUND, "error_floor": ERROR_FLOOR}


def fit_scaling(eps2s: Sequence[float], rel_errors: Sequence[float],
                floors: Sequence[float] | None = None) -> Scaling:
    """Fit the measured errors against e = e₀ + κ·ε² and |e| ∝ (ε²)^p; decide the contract.

    Parameters
    ----------
    eps2s, rel_errors : sequence of float
        At least two distinct ε² and the relative amplitude error at each.
    floors : sequence of float, optional
        Each point's resolution (:func:`error_floor`; default :data:`ERROR_FLOOR`): an error below it
        takes no part in the exponent.

    Returns
    -------
    Scaling
    """
    x = np.asarray(eps2s, dtype=float)
    e = np.asarray(rel_errors, dtype=float)
    order = np.argsort(-x)
    fl = np.full(x.size, ERROR_FLOOR) if floors is None else np.asarray(floors, dtype=float)
    x, e, fl = x[order], e[order], fl[order]
    ex, ee = tuple(float(v) for v in x), tuple(float(v) for v in e)
    if x.size < 2 or np.unique(x).size < 2:
        return Scaling(ex, ee, None, None, None, False, "fewer than two eps2 measured")
    coef = np.polyfit(x, e, min(2, np.unique(x).size - 1))     # e₀ + κε² (+ κ₂ε⁴ from three ε² on)
    kappa, e0 = float(coef[-2]), float(coef[-1])
    big = np.abs(e) > fl
    if not big.any():
        return Scaling(ex, ee, None, kappa, e0, True, "")
    p = float(np.polyfit(np.log(x[big]), np.log(np.abs(e[big])), 1)[0]) if big.sum() >= 2 else None
    if p is None:
        # at most one ε² is above its floor: the exponent is not resolved, the extrapolation is
        return Scaling(ex, ee, None, kappa, e0, abs(e0) <= EXTRAPOLATION_BOUND,
                       "" if abs(e0) <= EXTRAPOLATION_BOUND else
                       f"the error extrapolates to {e0:+.2%} at eps2 -> 0 (bound {EXTRAPOLATION_BOUND:.0%})")
    why = []
    if not (EXPONENT_BAND[0] <= p <= EXPONENT_BAND[1]):
        why.append(f"the error falls like (eps2)^{p:.2f}, not like eps2 (band {EXPONENT_BAND[0]:g} to "
                   f"{EXPONENT_BAND[1]:g})")
    if abs(e0) > EXTRAPOLATION_BOUND:
        why.append(f"it extrapolates to {e0:+.2%} at eps2 -> 0 (bound {EXTRAPOLATION_BOUND:.0%})")
    return Scaling(ex, ee, p, kappa, e0, not why, "; ".join(why))
