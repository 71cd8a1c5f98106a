"""Check a predicted Hopf bifurcation by direct simulation: :func:`check`.

One entry point for the spring–block (any friction law) and for any smooth
:class:`~landau.systems.system.DynamicalSystem`.  The procedure is chosen from the prediction itself:

* **supercritical** (Λ < 0): the stable cycle on the side where it exists, at distance ε² from
  the Hopf point (spring–block: k = k_c(1 − ε²)); its amplitude against C·sqrt|p − p_c|;
* **subcritical** (Λ > 0): the unstable cycle on the other side (spring–block: k = k_c(1 + ε²))
  by shooting; for the spring–block also bistability (a perturbation below the unstable cycle
  decays, one above grows into a stick–slip cycle) by bisection on the initial amplitude.

The amplitude is measured the same way on both sides: the half peak-to-peak value
(max − min)/2 of the normalised component (the slip X for the spring–block), which cancels the
O(ε²) mean shift of the cycle (Putelat et al. 2010, eqs 20–23).

**Range of validity.**  The cubic amplitude equation describes a small harmonic cycle.  For the
spring–block the predicted slip rate v = V + Ẋ swings by A·ω_c around V; when A·ω_c ≥ V the
predicted cycle would reverse the slip, so the block must stop and the motion is stick–slip —
no weakly nonlinear prediction holds there.  Such a point is reported as
:attr:`Verdict.OUTSIDE_VALIDITY` together with the largest ε² for which the swing stays
below V (``eps2_max_valid``), not as a disagreement.  The same verdict is given when the
predicted frequency is not positive or Λ = 0 (a codimension-two point, where the cubic
equation predicts no amplitude).

**The verdict is a contract** (:mod:`landau.analyses.contract`, docs/guarantees.md "The check's
contract"): the check measures at two or more ε² (a single ε² gets the companion ε²/4) and
*agrees* when the relative amplitude error falls like ε¹ in ε² (fitted exponent within
:data:`~landau.analyses.contract.EXPONENT_BAND`) and extrapolates to within
:data:`~landau.analyses.contract.EXTRAPOLATION_BOUND` at ε² → 0 — the amplitude equation's own
O(ε²) remainder, whatever the size of its next-order coefficient.  Where the cycle's amplitude
Floquet multiplier is within :data:`~landau.analyses.contract.MULTIPLIER_RESOLUTION` of 1 (its
stability and amplitude are below float64 resolution) or the shooting lands on another solution,
the verdict is :attr:`Verdict.FAILED` ("cannot resolve at this ε²") with the resolvable range,
never a disagreement.  Where the scaling holds only below the requested ε², the verdict is
:attr:`Verdict.OUTSIDE_VALIDITY` with that ε² as ``eps2_max_valid``.

References
----------
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a
spring–block system. J. Mech. Phys. Solids 58, 27–53.
"""

from __future__ import annotations

import enum
import html
import math
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

import numpy as np

from landau.analyses import contract
from landau.analyses.contract import Scaling, fit_scaling
from landau.analyses.shooting import CycleShooter
from landau.derivation.hopf import Criticality, HopfResult
from landau.errors import InputError, IntegratorError, LandauError

#: bracket tolerance of the supercritical route's legacy single-point procedure at ε² = 1e-3
SUPERCRITICAL_TOLERANCE = 0.02
#: the subcritical bistability bracket (the bisection's width) must contain the prediction within this
SUBCRITICAL_TOLERANCE = 0.05
#: the bracket tolerance scales with ε² above 1e-3 (the remainder is O(ε²)), but never beyond this
MAX_TOLERANCE = 0.2
#: a shot cycle smaller than this fraction of the prediction is the steady state, not a cycle
LANDED_ON_STEADY_STATE = 1e-3
#: |p_c| below which a Hopf point counts as p_c = 0 and ε² is an absolute distance (general systems)
P_C_ZERO = 1e-9


class Verdict(str, enum.Enum):
    """Outcome of a :func:`check`, with an actionable message."""

    AGREES = "agrees"
    DISAGREES = "disagrees"
    OUTSIDE_VALIDITY = "outside-validity"
    FAILED = "failed"

    @property
    def message(self) -> str:
        return {
            "agrees": "the simulated amplitude error falls like eps2 and extrapolates to zero: the amplitude "
                      "equation holds",
            "disagrees": "the simulated amplitude error does not fall like eps2 towards zero (or the cycle has the "
                         "wrong stability): check the law and the parameters",
            "outside-validity": "the amplitude equation does not apply at this distance from the Hopf point; "
                                "choose eps2 below eps2_max_valid",
            "failed": "the simulation could not locate or resolve the cycle at this eps2 (see reason, which "
                      "names the resolvable range); choose eps2 inside it",
        }[self.value]

    def __str__(self) -> str:
        return self.value

    def __format__(self, spec: str) -> str:
        return format(self.value, spec)


def default_tolerance(criticality: Criticality | str, eps2: float) -> float:
    """Relative tolerance at ε² of the subcritical bistability bracket: 2 % (supercritical) or 5 %
    (subcritical) at ε² ≤ 1e-3, growing ∝ ε² above it, capped at 20 %.  The verdict on the amplitude
    itself rests on the scaling (:mod:`landau.analyses.contract`), not on this margin."""
    base = SUBCRITICAL_TOLERANCE if criticality == Criticality.SUBCRITICAL else SUPERCRITICAL_TOLERANCE
    return min(MAX_TOLERANCE, base * max(1.0, eps2 / 1e-3))


def _fmt(x: Any, spec: str = ".4g") -> str:
    if x is None:
        return "—"
    if isinstance(x, bool):
        return str(x)
    try:
        return format(float(x), spec)
    except (TypeError, ValueError):
        return str(x)


@dataclass(frozen=True)
class CheckResult:
    """A predicted-vs-simulated comparison at one point (amplitudes in the units of the normalised state).

    Parameters
    ----------
    system : str
        Law or system name.
    parameter : str
        Bifurcation parameter (``"k"`` for the spring–block).
    p : float
        Parameter value where the cycle was simulated.
    eps2 : float
        Relative distance |p − p_c|/|p_c| (absolute where p_c = 0).
    prediction : HopfResult
        The engine's Hopf point and amplitude-equation coefficients.
    amplitude_predicted, amplitude_simulated : float
        C·sqrt|p − p_c| and the simulated half peak-to-peak amplitude.
    rel_error : float
        amplitude_simulated / amplitude_predicted − 1.
    frequency_predicted, frequency_simulated, frequency_rel_error : float
        Angular frequencies (rad/s) and their relative difference.
    tolerance : float or None
        An optional extra bound on |rel_error| at ``eps2`` asked for by the caller (None: the contract
        alone decides).
    verdict : Verdict
        Agrees / disagrees / outside the range of validity / failed.
    reason : str
        Why (one sentence).
    eps2_max_valid : float or None
        Largest ε² at which the prediction is inside its range of validity (spring–block: slip-rate
        swing A·ω_c < V).
    bistable : bool or None
        Subcritical spring–block points: whether bistability was shown.
    cycle_stable : bool or None
        Floquet stability of the simulated cycle.
    detail : mapping
        Route-specific data (Floquet multipliers, bisection bracket, each measured ε², ...).
    scaling : Scaling or None
        The contract's fit over the measured ε² (:class:`landau.analyses.contract.Scaling`).
    eps2_resolvable : (float, float) or None
        The range of ε² that the simulation resolves: from where the amplitude Floquet multiplier
        leaves 1 by :data:`~landau.analyses.contract.MULTIPLIER_RESOLUTION` up to the range of validity.
    """

    system: str
    parameter: str
    p: float
    eps2: float
    prediction: Any = field(repr=False)
    amplitude_predicted: float | None
    amplitude_simulated: float | None
    rel_error: float | None
    frequency_predicted: float | None
    frequency_simulated: float | None
    frequency_rel_error: float | None
    tolerance: float | None
    verdict: Verdict
    reason: str = ""
    eps2_max_valid: float | None = None
    bistable: bool | None = None
    cycle_stable: bool | None = None
    detail: Mapping[str, Any] = field(default_factory=dict, repr=False)
    scaling: Scaling | None = field(default=None, repr=False)
    eps2_resolvable: tuple[float, float] | None = None

    @property
    def exponent(self) -> float | None:
        """Fitted p in |rel_error| ∝ (ε²)^p over the measured ε² (the theory: 1)."""
        return self.scaling.exponent if self.scaling is not None else None

    @property
    def extrapolated_error(self) -> float | None:
        """The relative amplitude error extrapolated to ε² → 0 (the theory: 0)."""
        return self.scaling.extrapolated if self.scaling is not None else None

    @property
    def next_order_coefficient(self) -> float | None:
        """κ in rel_error ≈ e₀ + κ·ε², measured."""
        return self.scaling.coefficient if self.scaling is not None else None

    @property
    def agrees(self) -> bool:
        """Whether the verdict is :attr:`Verdict.AGREES`."""
        return self.verdict is Verdict.AGREES

    @property
    def criticality(self) -> Criticality:
        """The predicted criticality (from the sign of Λ)."""
        return self.prediction.criticality

    def as_dict(self) -> dict[str, Any]:
        """The result as JSON-ready fields.

        Returns
        -------
        dict
            Predicted and simulated amplitude and frequency, errors, tolerance, verdict and
            the range of validity.
        """
        out = {"system": self.system, "parameter": self.parameter, "p": self.p, "eps2": self.eps2,
               "p_c": self.prediction.p_c, "criticality_predicted": str(self.criticality),
               "amplitude_predicted": self.amplitude_predicted, "amplitude_simulated": self.amplitude_simulated,
               "rel_error": self.rel_error, "frequency_predicted": self.frequency_predicted,
               "frequency_simulated": self.frequency_simulated, "frequency_rel_error": self.frequency_rel_error,
               "tolerance": self.tolerance, "verdict": self.verdict.value, "agrees": self.agrees,
               "reason": self.reason, "eps2_max_valid": self.eps2_max_valid, "bistable": self.bistable,
               "cycle_stable": self.cycle_stable, "exponent": self.exponent,
               "extrapolated_error": self.extrapolated_error, "next_order_coefficient": self.next_order_coefficient,
               "eps2_measured": list(self.scaling.eps2) if self.scaling is not None else None,
               "rel_errors_measured": list(self.scaling.rel_errors) if self.scaling is not None else None,
               "eps2_resolvable": list(self.eps2_resolvable) if self.eps2_resolvable is not None else None,
               "contract": {"exponent_band": list(contract.EXPONENT_BAND),
                            "extrapolation_bound": contract.EXTRAPOLATION_BOUND,
                            "error_floor": contract.ERROR_FLOOR,
                            "multiplier_resolution": contract.MULTIPLIER_RESOLUTION}}
        if isinstance(self.prediction, HopfResult):  # its route's numbers (V, kc, Γ̄, Ω̄ of the spring–block …)
            route = {**self.prediction.route_fields(), **self.prediction.extra}
            out.update({k: v for k, v in route.items() if k not in out})
        out["detail"] = dict(self.detail)
        return out

    def summary(self) -> str:
        """One line: what was compared and the verdict.

        Returns
        -------
        str
        """
        scaling = ""
        if self.scaling is not None and len(self.scaling.eps2) >= 2:
            scaling = ("; " + (self.scaling.describe() or "errors below the floor")
                       + " over eps2 = " + ", ".join(f"{e:.3g}" for e in self.scaling.eps2))
        tol = f", tolerance {self.tolerance:.1%}" if self.tolerance is not None else ""
        return (f"{self.system}: {self.criticality} Hopf at {self.parameter}_c = {self.prediction.p_c:.8g}; "
                f"eps2 = {self.eps2:.3g}: amplitude {_fmt(self.amplitude_simulated)} simulated vs "
                f"{_fmt(self.amplitude_predicted)} predicted "
                f"({_fmt(self.rel_error, '+.2%') if self.rel_error is not None else '—'}{tol}){scaling}"
                f" -> {self.verdict.value}" + (f" ({self.reason})" if self.reason else ""))

    def __repr__(self) -> str:
        return f"CheckResult({self.summary()})"

    def _repr_html_(self) -> str:
        rows = "".join(f"<tr><th style='text-align:left'>{html.escape(k)}</th>"
                       f"<td>{html.escape(_fmt(v, '.6g'))}</td></tr>"
                       for k, v in self.as_dict().items() if not isinstance(v, (dict, list)))
        return (f"<div><b>check of {html.escape(self.system)}</b>: {html.escape(self.verdict.value)}"
                f"<table>{rows}</table></div>")


# ---------------------------------------------------------------------------------------------
# the contract: measure at two or more ε² and judge the scaling
# ---------------------------------------------------------------------------------------------

@dataclass
class _Point:
    """One simulated cycle at one ε² (amplitude, frequency, stability, the resolution it was found at)."""

    eps2: float
    p: float
    amplitude_predicted: float | None
    frequency_predicted: float | None
    amplitude_simulated: float | None = None
    frequency_simulated: float | None = None
    stable: bool | None = None
    gap: float | None = None              # measured min |1 − |m|| over the non-trivial Floquet multipliers
    error: str = ""
    extra: dict = field(default_factory=dict)
    rtol: float = 1e-10                   # the shooting's tolerance (sets the resolution floor)

    @property
    def floor(self) -> float:
        return contract.error_floor(self.gap, self.rtol)

    @property
    def rel_error(self) -> float | None:
        if self.amplitude_simulated is None or not self.amplitude_predicted:
            return None
        return self.amplitude_simulated / self.amplitude_predicted - 1.0

    @property
    def frequency_rel_error(self) -> float | None:
        if self.frequency_simulated is None or not self.frequency_predicted:
            return None
        return self.frequency_simulated / self.frequency_predicted - 1.0

    def record(self) -> dict[str, Any]:
        return {"eps2": self.eps2, "p": self.p, "amplitude_predicted": self.amplitude_predicted,
                "amplitude_simulated": self.amplitude_simulated, "rel_error": self.rel_error,
                "frequency_rel_error": self.frequency_rel_error, "cycle_stable": self.stable,
                "multiplier_gap": self.gap, "error_floor": self.floor, "error": self.error or None}

    def set_multipliers(self, mults) -> None:
        mags = [abs(complex(m)) for m in mults]
        if mags:
            self.stable = bool(max(mags) < 1.0)
            self.gap = float(min(abs(1.0 - m) for m in mags))


def _resolvable_text(lo: float, hi: float) -> str:
    if lo <= hi:
        return f"resolvable for eps2 in [{lo:.3g}, {hi:.3g}]"
    return (f"no eps2 is resolvable here: the multiplier leaves 1 by {contract.MULTIPLIER_RESOLUTION:g} only at "
            f"eps2 = {lo:.3g}, beyond the largest usable eps2 {hi:.3g}")


def _unresolved(pt: _Point, subcritical: bool) -> str:
    """Why a simulated point cannot be trusted (empty when it can)."""
    if pt.error:
        return pt.error
    if pt.amplitude_simulated is not None and pt.amplitude_predicted and \
            pt.amplitude_simulated < LANDED_ON_STEADY_STATE * pt.amplitude_predicted:
        return f"the shooting landed on the steady state (amplitude {pt.amplitude_simulated:.3g})"
    if pt.gap is not None and pt.gap < contract.MULTIPLIER_RESOLUTION:
        return (f"the cycle's amplitude Floquet multiplier 1 {'+' if subcritical else '-'} {pt.gap:.2g} cannot be "
                f"told from 1 in float64 (needs a gap of {contract.MULTIPLIER_RESOLUTION:g})")
    return ""


def _err(pt: "_Point") -> float:
    """The relative amplitude error of a point that has one (a measured cycle)."""
    assert pt.rel_error is not None, "a point without a measured cycle has no amplitude error"
    return pt.rel_error


def _agreed(main: _Point, sc: Scaling, tolerance: float | None, pts: list[_Point]):
    """The contract holds: agrees, unless the caller's extra tolerance is exceeded."""
    if tolerance is not None and abs(_err(main)) > tolerance:
        return (main, sc, Verdict.DISAGREES, f"amplitude off by {main.rel_error:+.2%}, beyond the requested "
                                             f"tolerance {tolerance:.2%}", None, pts)
    return main, sc, Verdict.AGREES, "", None, pts


def _run_contract(measure: Callable[[float, bool], _Point], eps2_request, primary: float, lo: float, hi: float,
                  subcritical: bool, tolerance: float | None, gap_of: Callable[[float], float]):
    """Measure at the contract's ε² and decide.

    Returns (primary point, scaling, verdict, reason, eps2_max_valid or None, all points)."""
    pts: list[_Point] = []

    def cannot(e: float, why: str) -> str:
        return f"cannot resolve at this eps2 ({e:.3g}): {why}; {_resolvable_text(lo, hi)}"

    if primary < lo:
        why = (f"the cycle's amplitude Floquet multiplier 1 {'+' if subcritical else '-'} {gap_of(primary):.2g} "
               f"cannot be told from 1 in float64 (needs a gap of {contract.MULTIPLIER_RESOLUTION:g})")
        return None, None, Verdict.FAILED, cannot(primary, why), None, pts
    if isinstance(eps2_request, (int, float, np.floating)):
        eset, why = contract.measurement_set(primary, lo, hi)
    else:
        eset = tuple(e for e in contract.measurement_set(eps2_request, lo, hi)[0] if e >= lo)
        why = "" if len(eset) >= 2 else "fewer than two of the requested eps2 are resolvable"
    if not eset:
        return None, None, Verdict.FAILED, cannot(primary, why), None, pts
    for e in eset:
        pts.append(measure(e, e == primary))
    main = next(p for p in pts if p.eps2 == primary)
    bad = [(pt, _unresolved(pt, subcritical)) for pt in pts]
    bad = [(pt, why) for pt, why in bad if why]
    for pt, why in bad:      # below float64 resolution: no smaller ε² can do better
        if pt.gap is not None and pt.gap < contract.MULTIPLIER_RESOLUTION:
            return main, None, Verdict.FAILED, cannot(pt.eps2, why), None, pts
    good = [pt for pt in pts if not any(pt is q for q, _ in bad)]
    wrong = [pt for pt in good if pt.stable is not None and pt.stable == subcritical]
    sc = fit_scaling([p.eps2 for p in good], [_err(p) for p in good], [p.floor for p in good])
    if sc.holds and not wrong and not bad:
        return _agreed(main, sc, tolerance, pts)
    if bad:         # no cycle found, or the steady state: is that ε² beyond the weakly nonlinear range?
        failure, sc = f"{bad[0][1]} at eps2 = {bad[0][0].eps2:.3g}", None
    elif wrong:
        failure = (f"the cycle at eps2 = {wrong[0].eps2:.3g} is {'stable' if wrong[0].stable else 'unstable'} "
                   f"(Floquet multiplier gap {wrong[0].gap:.3g}) where the prediction is "
                   f"{'un' if subcritical else ''}stable")
    else:
        failure = f"{sc.reason} at eps2 = {', '.join(f'{q:.3g}' for q in sc.eps2)}"
    # the scaling fails: an ε⁴ term (fitted from a third ε²), or is the requested ε² beyond the weakly
    # nonlinear range (or on another solution)?
    tail = sorted(good, key=lambda q: -q.eps2)
    for _ in range(contract.REFINEMENTS):
        e = min(q.eps2 for q in pts) / contract.RATIO
        if e < lo:
            break
        pt = measure(e, False)
        pts.append(pt)
        if _unresolved(pt, subcritical) or (pt.stable is not None and pt.stable == subcritical):
            break
        tail.append(pt)
        if not wrong and not bad:
            full = fit_scaling([q.eps2 for q in tail], [_err(q) for q in tail], [q.floor for q in tail])
            if full.holds:
                return _agreed(main, full, tolerance, pts)
        if len(tail) < 2 or tail[-2].stable is not None and tail[-2].stable == subcritical:
            continue
        below = fit_scaling([q.eps2 for q in tail[-2:]], [_err(q) for q in tail[-2:]],
                            [q.floor for q in tail[-2:]])
        if below.holds:
            emax = tail[-2].eps2
            return (main, sc, Verdict.OUTSIDE_VALIDITY,
                    f"{failure}; the amplitude equation holds below eps2 = {emax:.3g} "
                    f"({below.describe() or 'errors at the resolution floor'})", emax, pts)
    if bad:
        return (main, None, Verdict.FAILED, f"cannot resolve at this eps2 ({bad[0][0].eps2:.3g}): {bad[0][1]}; "
                f"the Floquet multiplier is {_resolvable_text(lo, hi)}, the simulation found no cycle matching the "
                f"prediction below either", None, pts)
    return main, sc, Verdict.DISAGREES, failure, None, pts


def _result(common: dict, main: _Point | None, pr, p: float, verdict: Verdict, reason: str, sc: Scaling | None,
            pts: list[_Point], eps2_max_valid, lo: float, hi: float, **extra) -> CheckResult:
    """A CheckResult from the contract's outcome (the primary point's numbers)."""
    if main is None:
        A = pr.amplitude(p) if pr.criticality != Criticality.DEGENERATE else None
        w = pr.frequency(p) if pr.criticality != Criticality.DEGENERATE else None
        main = _Point(common["eps2"], p, A, w)
    detail = dict(main.extra, points=[q.record() for q in pts])
    if sc is not None:
        detail["scaling"] = sc.as_dict()
    return CheckResult(p=main.p, amplitude_predicted=main.amplitude_predicted,
                       amplitude_simulated=main.amplitude_simulated, rel_error=main.rel_error,
                       frequency_predicted=main.frequency_predicted, frequency_simulated=main.frequency_simulated,
                       frequency_rel_error=main.frequency_rel_error, verdict=verdict, reason=reason,
                       cycle_stable=main.stable, detail=detail, scaling=sc, eps2_resolvable=(lo, hi),
                       eps2_max_valid=eps2_max_valid, **common, **extra)


# ---------------------------------------------------------------------------------------------
# spring–block
# ---------------------------------------------------------------------------------------------

def spring_block_validity(pr, eps2: float) -> tuple[bool, str, float]:
    """(inside, reason, eps2_max_valid) for a spring–block prediction at ε².

    The predicted slip rate swings by A·ω_c around V with A = C·sqrt(ε² k_c); it must stay below V
    (v > 0): ε² < V²/(C² ω_c² k_c)."""
    V, kc, wc, C = pr.V, pr.p_c, pr.omega_c, pr.C
    if pr.criticality == Criticality.DEGENERATE:
        return False, "Lambda = 0 (codimension-two point): the cubic amplitude equation predicts no amplitude", 0.0
    eps2_max = V * V / (C * C * wc * wc * kc)
    k = kc * (1 - eps2) if pr.criticality == Criticality.SUPERCRITICAL else kc * (1 + eps2)
    A = pr.amplitude(k)
    swing = A * wc
    if swing >= V:
        return (False, f"the predicted slip-rate swing A*omega_c = {swing / V:.3g} V would reverse the slip "
                       f"(the block must stop: stick-slip, not a weakly nonlinear cycle); valid for eps2 < "
                       f"{eps2_max:.3g}",
                eps2_max)
    if pr.frequency(k) <= 0:
        return (False, f"the predicted frequency {pr.frequency(k):.3g} rad/s is not positive at eps2 = {eps2:g}",
                eps2_max)
    return True, "", eps2_max


def _check_spring_block(law, V: float, eps2, params, tolerance, bistability: bool) -> CheckResult:
    from landau.verify.springblock.checks import predict, subcritical_check, supercritical_check

    pr = predict(law, V, params)
    crit = pr.criticality
    sub = crit == Criticality.SUBCRITICAL
    primary = _primary(eps2)
    k = pr.p_c * (1 + primary) if sub else pr.p_c * (1 - primary)
    inside, reason, eps2_max = spring_block_validity(pr, primary)
    common = dict(system=law.name, parameter="k", eps2=primary, prediction=pr, tolerance=tolerance)
    if not inside:
        return _result(common, None, pr, k, Verdict.OUTSIDE_VALIDITY, reason, None, [], eps2_max, 0.0, 0.0)
    lo = contract.smallest_resolvable_eps2(pr, pr.p_c)
    hi = min(0.5, eps2_max)

    def measure(e: float, is_primary: bool) -> _Point:
        kk = pr.p_c * (1 + e) if sub else pr.p_c * (1 - e)
        pt = _Point(e, kk, pr.amplitude(kk), pr.frequency(kk))
        try:
            if sub:
                test = bistability and is_primary
                pc = subcritical_check(law, V, e, params, tolerance=default_tolerance(crit, e), prediction=pr,
                                       bisections=7 if test else 0, test_bistability=test)
                mults = pc.detail.get("unstable_cycle", {}).get("floquet_multipliers", [])
            else:
                pc = supercritical_check(law, V, e, params, prediction=pr)
                mults = pc.detail.get("floquet_multipliers", [])
        except LandauError as exc:
            pt.error = f"{type(exc).__name__}: {exc}"
            return pt
        pt.amplitude_simulated, pt.frequency_simulated = pc.amplitude_simulated, pc.frequency_simulated
        pt.set_multipliers(mults)
        if pt.amplitude_simulated is None:
            pt.error = "no cycle found by shooting: " + str(pc.detail.get("unstable_cycle", {}).get("error", ""))
        pt.extra = dict(pc.detail, max_abs_slip=pc.max_abs_slip, bistable=pc.bistable)
        return pt

    main, sc, verdict, why, emax, pts = _run_contract(measure, eps2, primary, lo, hi, sub, tolerance,
                                                      lambda e: contract.multiplier_gap(pr, e, pr.p_c))
    bistable = main.extra.get("bistable") if main is not None else None
    if verdict is Verdict.AGREES and sub and bistability:
        if not bistable:
            verdict, why = Verdict.DISAGREES, "no bistability shown"
        elif not main.extra.get("bracket_contains_prediction"):
            verdict, why = Verdict.DISAGREES, "the bisection bracket does not contain the predicted cycle"
    return _result(common, main, pr, k, verdict, why, sc, pts, emax if emax is not None else eps2_max, lo, hi,
                   bistable=bistable)


def _primary(eps2) -> float:
    """The reported ε² of a request: the ε² itself, or the largest of a sequence."""
    return float(eps2) if isinstance(eps2, (int, float, np.floating)) else max(float(e) for e in eps2)


# ---------------------------------------------------------------------------------------------
# general smooth systems
# ---------------------------------------------------------------------------------------------

def _check_system(system, params: Mapping[str, float], bracket, eps2, tolerance, rtol: float) -> CheckResult:
    """The check of a general smooth system: the normal form in ``bracket``, then the cycle at each
    measured ε² by shooting (:class:`~landau.analyses.shooting.CycleShooter`: from the critical mode,
    else by continuation from a cycle found closer to the Hopf point), judged by the contract."""
    from landau.derivation.general import hopf_normal_form

    if bracket is None:
        raise InputError(f"{system.name}: give bracket=(lo, hi) around the Hopf value of {system.parameter.name}")
    pr = hopf_normal_form(system, params, bracket)
    crit = Criticality(str(pr.criticality))
    sub = crit == Criticality.SUBCRITICAL
    scale = abs(pr.p_c) if abs(pr.p_c) > P_C_ZERO else 1.0   # a Hopf point at p = 0: absolute distance
    primary = _primary(eps2)
    common = dict(system=system.name, parameter=pr.parameter, eps2=primary, prediction=pr, tolerance=tolerance)
    if crit == Criticality.DEGENERATE or pr.cycle_side == 0:
        return _result(common, None, pr, pr.p_c, Verdict.OUTSIDE_VALIDITY,
                       "Lambda = 0 (codimension-two point): the cubic amplitude equation predicts no amplitude",
                       None, [], None, 0.0, 0.0)
    p = pr.p_c + pr.cycle_side * primary * scale
    lo, hi = contract.smallest_resolvable_eps2(pr, scale), 0.5
    if not pr.frequency(p) > 0:
        return _result(common, None, pr, p, Verdict.OUTSIDE_VALIDITY,
                       f"the predicted frequency {pr.frequency(p):.3g} rad/s is not positive at eps2 = {primary:g}",
                       None, [], None, lo, hi)
    shooter = CycleShooter(system, params, pr, scale, rtol)

    def measure(e: float, is_primary: bool, depth: int = 0) -> _Point:
        pp = pr.p_c + pr.cycle_side * e * scale
        pt = _Point(e, pp, pr.amplitude(pp), pr.frequency(pp), rtol=rtol)
        try:
            try:
                y0, z, T, sol, mult = shooter.shoot_at(e, shooter.from_mode(e))
            except IntegratorError:
                if not shooter.cycles and depth < 2 and e / contract.RATIO >= lo:
                    measure(e / contract.RATIO, False, depth + 1)     # a closer cycle to continue from
                if not shooter.cycles:
                    raise
                y0, z, T, sol, mult = shooter.continue_to(e)
        except (IntegratorError, ValueError, np.linalg.LinAlgError) as exc:
            pt.error = str(exc)
            return pt
        yn = sol.sol(np.linspace(0.0, T, 2001))[system.normalise]
        pt.amplitude_simulated = 0.5 * float(yn.max() - yn.min())
        pt.frequency_simulated = 2 * np.pi / T
        pt.set_multipliers(mult)
        pt.extra = {"floquet_multipliers": [float(abs(m)) for m in mult], "period": T,
                    "mean_shift": 0.5 * float(yn.max() + yn.min()) - float(y0[system.normalise])}
        return pt

    main, sc, verdict, why, emax, pts = _run_contract(measure, eps2, primary, lo, hi, sub, tolerance,
                                                      lambda e: contract.multiplier_gap(pr, e, scale))
    return _result(common, main, pr, p, verdict, why, sc, pts, emax, lo, hi)


# ---------------------------------------------------------------------------------------------
# the entry point
# ---------------------------------------------------------------------------------------------

def _eps2_request(eps2) -> float | tuple[float, ...]:
    """A float, or a tuple of at least two distinct floats, each in (0, 0.5)."""
    many = isinstance(eps2, (list, tuple, np.ndarray))
    vals = list(eps2) if many else [eps2]
    out = []
    for v in vals:
        try:
            x = float(v)
        except (TypeError, ValueError):
            raise InputError(f"eps2 must be a number or a sequence of numbers, got {v!r}") from None
        if not (0 < x < 0.5) or not math.isfinite(x):
            raise InputError(f"eps2 must be in (0, 0.5), got {v!r}")
        out.append(x)
    if not many:
        return out[0]
    if len(set(out)) < 2:
        raise InputError(f"a sequence of eps2 needs at least two distinct values, got {list(eps2)!r}")
    return tuple(out)


def check(target, V: float | None = None, eps2: float | Sequence[float] = 1e-3,
          params: Mapping[str, float] | None = None, *,
          bracket: tuple[float, float] | None = None, tolerance: float | None = None, bistability: bool = True,
          rtol: float = 1e-10) -> CheckResult:
    """Check the predicted Hopf bifurcation of a law or system by direct simulation.

    Parameters
    ----------
    target : FrictionLaw, str, SpringBlock or DynamicalSystem
        A friction law (or the name of a built-in law) is put in the default spring–block of
        Putelat et al. (2010) eq. (4); a general system is simulated as E·ẏ = f(y; p); an object with
        its own ``amplitude_check(eps2, tolerance=...)`` (the non-smooth mode-coupling structure,
        :class:`landau.verify.modecoupling.nonsmooth.Structure`) runs that.
    V : float
        Driving velocity [m/s] (spring–block only).
    eps2 : float or sequence of float
        Relative distance from the Hopf point, ε² = |p − p_c|/|p_c|, in (0, 0.5) (absolute distance
        |p − p_c| for a general system whose Hopf point is at p_c = 0, |p_c| < 1e-9).  The side is chosen
        from the prediction: where the stable (supercritical) or unstable (subcritical) cycle exists.
        A single ε² is measured together with ε²/4 (the companion that measures the next-order
        coefficient); a sequence of two or more is measured as given and reported at its largest.
    params : mapping, optional
        Parameter values (overrides of the law's and system's defaults).
    bracket : (float, float), optional
        General systems: an interval of the bifurcation parameter containing one Hopf point.
    tolerance : float, optional
        An extra bound on |relative amplitude error| at ``eps2`` (default: none; the verdict rests on
        the contract: the error falls like ε² and extrapolates to within 1 % at ε² → 0).
    bistability : bool
        Subcritical spring–block points: also show bistability by bisection (slower).
    rtol : float
        Integration tolerance of the general route (its shooting integrates with the compiled Radau IIA,
        :func:`landau.analyses.system_simulation.shooting_flow`).

    Returns
    -------
    CheckResult
        With a :class:`Verdict`; ``result.agrees`` is True only for :attr:`Verdict.AGREES`;
        ``result.exponent``, ``result.extrapolated_error`` and ``result.next_order_coefficient`` give
        the measured scaling (:mod:`landau.analyses.contract`).

    Raises
    ------
    NoHopfError
        The law or system has no Hopf point at these parameters.
    InputError
        Bad arguments (eps2 out of range, V missing, unknown law).

    References
    ----------
    Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a
    spring–block system. J. Mech. Phys. Solids 58, 27–53, eqs (20)–(23).
    """
    from landau.laws.law import FrictionLaw
    from landau.systems.system import DynamicalSystem, SpringBlock

    eps2 = _eps2_request(eps2)
    if tolerance is not None and not (0 < tolerance < 1):
        raise InputError(f"tolerance must be in (0, 1), got {tolerance!r}")
    own = getattr(target, "amplitude_check", None)
    if callable(own):   # a model object with its own check by simulation (the non-smooth mode-coupling structure)
        return own(eps2, tolerance=tolerance)
    if isinstance(target, DynamicalSystem):
        return _check_system(target, dict(target.defaults, **(params or {})), bracket, eps2, tolerance, rtol)
    if isinstance(target, str):
        from landau.laws import get_law

        target = get_law(target)
    if isinstance(target, SpringBlock):
        target = target.law
    if not isinstance(target, FrictionLaw):
        raise InputError(f"check() takes a FrictionLaw, a law name, a SpringBlock or a DynamicalSystem, "
                         f"got {type(target).__name__}")
    if V is None:
        raise InputError("check() of a spring–block needs the driving velocity V [m/s]")
    from landau.derivation.linear import one_velocity

    V = one_velocity(V, "V", "a loop of check() calls, or `landau sweep check`")
    if not (V > 0 and math.isfinite(V)):
        raise InputError(f"V must be a positive velocity in m/s, got {V!r}")
    return _check_spring_block(target, V, eps2, params, tolerance, bistability)
