"""The fold of cycles near a Bautin point: quintic amplitude equation vs periodic-orbit continuation.

For a driving velocity V near a codimension-two velocity V* (Λ(V*) = 0) the quintic amplitude
equation predicts a fold (saddle-node) of cycles at k_fold = k_c − Λ²/(8Λ₅Γ̄) with slip amplitude
sqrt(−2Λ/Λ₅) (:func:`landau.analyses.bautin.spring_block_fold`).  Here the fold is located independently of
the engine: Newton on P(z; k) = z, det(DP − I) = 0 (:func:`~landau.verify.springblock.continuation.fold_point`)
with the unknown log₁₀|k − k_c|, seeded by the prediction; k_c from the steady state's eigenvalues.
The relative error of k_fold − k_c must vanish like |V − V*|¹ (the omitted terms
(k − k_c)A|A|² and A|A|⁶ are one order smaller at the fold).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from landau.analyses.bautin import spring_block_fold
from landau.derivation.multiscale import Derivation
from landau.laws import get_law
from landau.systems.system import SpringBlock
from landau.verify.springblock.continuation import fold_point
from landau.verify.springblock.model import SpringBlockModel
from landau.verify.springblock.orbits import hopf_stiffness, section_point


@dataclass(frozen=True)
class FoldComparison:
    """Predicted and continued fold of cycles at one driving velocity."""

    V: float
    kc: float
    predicted_offset: float      # k_fold − k_c from the quintic amplitude equation [N/m]
    continued_offset: float      # the same from the periodic orbits [N/m]
    predicted_amplitude: float   # max slip at the fold [m]
    continued_amplitude: float

    @property
    def error(self) -> float:
        """Relative error of the predicted k_fold − k_c."""
        return self.predicted_offset / self.continued_offset - 1.0


def compare_fold(d: Derivation, V: float, params: Mapping[str, float] | None = None, *,
                 rtol: float = 1e-11) -> FoldComparison:
    """The fold of cycles at V: predicted (quintic amplitude equation) and located by shooting."""
    p = d.block.resolve(params)
    pred = spring_block_fold(d, V, p)
    if pred is None:
        raise ValueError(f"V = {V:g} m/s: Lambda and Lambda5 have the same sign, no fold of cycles")
    assert pred.p_c is not None  # fold_of_cycles sets the Hopf point
    law = d.block.law
    model = SpringBlockModel.build(law, V, pred.p_c, params)
    kc = hopf_stiffness(model, pred.p_c * (1 - 1e-3), pred.p_c * (1 + 1e-3))
    sgn = 1.0 if pred.offset > 0 else -1.0
    make = lambda x: model.with_(k=kc + sgn * x)  # noqa: E731  (x = |k − k_c| > 0)
    m0 = make(abs(pred.offset))
    z0 = section_point(m0, pred.amplitude)
    fp = fold_point(make, abs(pred.offset), z0, rtol=rtol, parameter="|k - kc|")
    return FoldComparison(V, kc, pred.offset, sgn * fp.p_fold, pred.amplitude, fp.amplitude)


def fold_convergence(name: str, params: Mapping[str, float], V_star: float, deltas: Sequence[float],
                     side: int) -> tuple[list[FoldComparison], float]:
    """compare_fold at V = V*(1 + side·δ) for each δ; returns the comparisons and the fitted exponent
    of |error| against |V − V*| (least squares in log–log)."""
    d = Derivation(SpringBlock(get_law(name)))
    rows = [compare_fold(d, V_star * (1 + side * dl), params) for dl in deltas]
    x = np.log([abs(r.V - V_star) for r in rows])
    y = np.log([abs(r.error) for r in rows])
    slope = float(np.polyfit(x, y, 1)[0])
    return rows, slope


@dataclass(frozen=True)
class AmplitudeComparison:
    """Stable-cycle amplitude below the Hopf line, k = k_c(1 − η): quintic and cubic predictions vs shooting."""

    V: float
    eta: float
    Lambda: float
    quintic: float               # max slip from the quintic amplitude equation [m]
    cubic: float                 # C sqrt(k_c − k), NaN where Λ ≥ 0 (no cubic cycle) [m]
    shooting: float              # max slip of the periodic orbit found by shooting [m]
    stable: bool

    @property
    def error(self) -> float:
        return self.quintic / self.shooting - 1.0


def compare_amplitude(d: Derivation, V: float, eta: float, params: Mapping[str, float] | None = None, *,
                      rtol: float = 1e-11) -> AmplitudeComparison:
    """At k = k_c(V)(1 − η) a single cycle exists on both sides of V* when Λ₅ < 0; the cubic prediction
    diverges as Λ → 0, the quintic one stays finite.  The cycle is found by shooting (Newton on the
    return map, seeded by the quintic prediction; settling by direct integration if Newton fails)."""
    from landau.analyses.bautin import cycle_amplitudes
    from landau.verify.springblock.checks import find_cycle

    p = d.block.resolve(params)
    mp = d.evaluate_mp(V, p, ["Gamma_bar", "Lambda", "Lambda5"])
    kc_e, lam, l5, gb = (float(mp[n]) for n in ("kc", "Lambda", "Lambda5", "Gamma_bar"))
    model = SpringBlockModel.build(d.block.law, V, kc_e, params)
    kc = hopf_stiffness(model, kc_e * (1 - 1e-3), kc_e * (1 + 1e-3))
    k = kc * (1 - eta)
    amps = cycle_amplitudes(lam, l5, -gb, kc_e, kc_e * (1 - eta))
    if len(amps) != 1:
        raise ValueError(f"V = {V:g}: expected one cycle below the Hopf line, the quintic equation gives {amps}")
    cubic = 2 * math.sqrt(2 * gb * eta * kc_e / abs(lam)) if lam < 0 else math.nan
    orbit = find_cycle(model.with_(k=k), amps[0], rtol=rtol)
    return AmplitudeComparison(V, eta, lam, amps[0], cubic, orbit.amplitude, orbit.stable)


if __name__ == "__main__":  # pragma: no cover - manual run
    import sys

    from landau.analyses.transition import codim2_points

    names = sys.argv[1:] or ["dieterich", "modified-dieterich", "spinodal"]
    cases = {"dieterich": ({}, 1.5e-4, 3e-4, [0.16, 0.08, 0.04, 0.02, 0.01]),
             "modified-dieterich": ({"c": 3e-4}, 1e-3, 1.25e-3, [0.04, 0.02, 0.01, 0.005]),
             "spinodal": ({"c": 3e-4}, 1e-3, 1.25e-3, [0.04, 0.02, 0.01, 0.005])}
    for name in names:
        params, lo, hi, deltas = cases[name]
        d = Derivation(SpringBlock(get_law(name)))
        (pt,) = codim2_points(d, lo, hi, params)
        side = -1 if pt.sign_below > 0 else 1
        print(name, "V* =", pt.V, "fold side", side,
              [spring_block_fold(d, pt.V * (1 + side * x), params) for x in deltas],
              flush=True)
        rows, slope = fold_convergence(name, params, pt.V, deltas, side)
        for r in rows:
            print(f"{name} V={r.V:.6g} kc={r.kc:.8g} pred {r.predicted_offset:.6g} cont {r.continued_offset:.6g} "
                  f"err {r.error:+.3e} amp {r.predicted_amplitude:.4g}/{r.continued_amplitude:.4g}", flush=True)
        print(name, "exponent", slope, file=sys.stdout, flush=True)
