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
from typing import Any, Mapping

import numpy as np

from landau.codegen.names import lambdify_positional
from landau.derivation.hopf import Criticality, HopfResult
from landau.errors import InputError, IntegratorError, LandauError

#: relative amplitude tolerance at ε² = 1e-3 (the O(ε²) remainder of the amplitude equation)
SUPERCRITICAL_TOLERANCE = 0.02
#: the subcritical check also compares a bisection bracket, which has the bisection's width
SUBCRITICAL_TOLERANCE = 0.05
#: the tolerance scales with ε² above 1e-3 (the remainder is O(ε²)), but never beyond this
MAX_TOLERANCE = 0.2
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
            "agrees": "the simulated cycle matches the amplitude equation within the tolerance",
            "disagrees": "the simulated cycle differs from the prediction beyond the tolerance: check the law, "
                         "the parameters, or reduce eps2 (the remainder is O(eps2))",
            "outside-validity": "the amplitude equation does not apply at this distance from the Hopf point; "
                                "choose eps2 below eps2_max_valid",
            "failed": "the simulation could not locate the cycle (see reason); try a smaller eps2 or a tighter rtol",
        }[self.value]

    def __str__(self) -> str:
        return self.value

    def __format__(self, spec: str) -> str:
        return format(self.value, spec)


def default_tolerance(criticality: Criticality | str, eps2: float) -> float:
    """Relative tolerance at ε²: 2 % (supercritical) or 5 % (subcritical) at ε² ≤ 1e-3, growing ∝ ε²
    above it (the remainder of the amplitude equation is O(ε²)), capped at 20 %."""
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
    tolerance : float
        Relative tolerance applied to the amplitude.
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
        Route-specific data (Floquet multipliers, bisection bracket, ...).
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
    tolerance: float
    verdict: Verdict
    reason: str = ""
    eps2_max_valid: float | None = None
    bistable: bool | None = None
    cycle_stable: bool | None = None
    detail: Mapping[str, Any] = field(default_factory=dict, repr=False)

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
               "cycle_stable": self.cycle_stable}
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
        return (f"{self.system}: {self.criticality} Hopf at {self.parameter}_c = {self.prediction.p_c:.8g}; "
                f"eps2 = {self.eps2:.3g}: amplitude {_fmt(self.amplitude_simulated)} simulated vs "
                f"{_fmt(self.amplitude_predicted)} predicted "
                f"({_fmt(self.rel_error, '+.2%') if self.rel_error is not None else '—'}, "
                f"tolerance {self.tolerance:.1%}) -> {self.verdict.value}"
                + (f" ({self.reason})" if self.reason else ""))

    def __repr__(self) -> str:
        return f"CheckResult({self.summary()})"

    def _repr_html_(self) -> str:
        rows = "".join(f"<tr><th style='text-align:left'>{html.escape(k)}</th>"
                       f"<td>{html.escape(_fmt(v, '.6g'))}</td></tr>"
                       for k, v in self.as_dict().items() if not isinstance(v, (dict, list)))
        return (f"<div><b>check of {html.escape(self.system)}</b>: {html.escape(self.verdict.value)}"
                f"<table>{rows}</table></div>")


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


def _check_spring_block(law, V: float, eps2: float, params, tolerance, bistability: bool) -> CheckResult:
    from landau.verify.springblock.checks import predict, subcritical_check, supercritical_check

    pr = predict(law, V, params)
    crit = pr.criticality
    tol = tolerance if tolerance is not None else default_tolerance(crit, eps2)
    sub = crit == Criticality.SUBCRITICAL
    k = pr.p_c * (1 + eps2) if sub else pr.p_c * (1 - eps2)
    inside, reason, eps2_max = spring_block_validity(pr, eps2)
    common = dict(system=law.name, parameter="k", p=k, eps2=eps2, prediction=pr, tolerance=tol, eps2_max_valid=eps2_max)
    if not inside:
        return CheckResult(amplitude_predicted=pr.amplitude(k) if crit != Criticality.DEGENERATE else None,
                           amplitude_simulated=None, rel_error=None,
                           frequency_predicted=pr.frequency(k) if crit != Criticality.DEGENERATE else None,
                           frequency_simulated=None, frequency_rel_error=None,
                           verdict=Verdict.OUTSIDE_VALIDITY, reason=reason, **common)
    try:
        if sub:
            pc = subcritical_check(law, V, eps2, params, tolerance=tol, prediction=pr,
                                   bisections=7 if bistability else 0, test_bistability=bistability)
        else:
            pc = supercritical_check(law, V, eps2, params, tolerance=tol, prediction=pr)
    except LandauError as exc:
        return CheckResult(amplitude_predicted=pr.amplitude(k), amplitude_simulated=None, rel_error=None,
                           frequency_predicted=pr.frequency(k), frequency_simulated=None, frequency_rel_error=None,
                           verdict=Verdict.FAILED, reason=f"{type(exc).__name__}: {exc}", **common)
    stable = pc.detail.get("stable")
    if stable is None and "unstable_cycle" in pc.detail and "floquet_multipliers" in pc.detail["unstable_cycle"]:
        stable = max(pc.detail["unstable_cycle"]["floquet_multipliers"]) < 1
    if pc.agrees:
        verdict, why = Verdict.AGREES, ""
    elif pc.amplitude_simulated is None or pc.rel_error is None:
        verdict, why = Verdict.FAILED, "no cycle found by shooting"
    else:
        verdict = Verdict.DISAGREES
        why = (f"amplitude off by {pc.rel_error:+.2%}" if abs(pc.rel_error) > tol else
               ("no bistability shown" if sub and bistability and not pc.bistable else
                "the cycle has the wrong stability" if stable is not None and stable == sub else
                "the bisection bracket does not match the cycle"))
    return CheckResult(amplitude_predicted=pc.amplitude_predicted, amplitude_simulated=pc.amplitude_simulated,
                       rel_error=pc.rel_error, frequency_predicted=pc.frequency_predicted,
                       frequency_simulated=pc.frequency_simulated, frequency_rel_error=pc.frequency_rel_error,
                       verdict=verdict, reason=why, bistable=pc.bistable, cycle_stable=stable,
                       detail=dict(pc.detail, max_abs_slip=pc.max_abs_slip), **common)


# ---------------------------------------------------------------------------------------------
# general smooth systems
# ---------------------------------------------------------------------------------------------

def _numeric_field(system, params: Mapping[str, float]):
    import sympy as sp

    missing = [s.name for s in system.parameters if s.name not in params]
    if missing:
        raise InputError(f"{system.name}: missing parameter(s) {', '.join(missing)}")
    vals = [float(params[s.name]) for s in system.parameters]
    args = [*system.states, system.parameter, *system.parameters]
    f = lambdify_positional(args, list(system.rhs), "numpy")
    J = lambdify_positional(args, sp.Matrix(system.rhs).jacobian(system.states), "numpy")
    E_of = lambdify_positional([system.parameter, *system.parameters], system.mass_matrix, "numpy")

    def E_inverse(p: float) -> np.ndarray:
        E = np.asarray(E_of(p, *vals), dtype=float)
        if not np.all(np.isfinite(E)) or abs(np.linalg.det(E)) < 1e-300 or np.linalg.cond(E) > 1e14:
            raise InputError(f"{system.name}: direct simulation needs an invertible mass matrix E; a "
                             "differential-algebraic system (singular E) is not supported by the generic check")
        return np.linalg.inv(E)

    return f, J, E_inverse, vals


def _shoot(rhs, jac, y0: np.ndarray, T0: float, anchor_f: np.ndarray, rtol: float):
    """Periodic orbit by Newton on (y(T; z) − z, (z − y0)·f(y0)) with the unknowns (z, T)."""
    import scipy.integrate
    import scipy.optimize

    n = y0.size

    def flow(z, T):
        sol = scipy.integrate.solve_ivp(rhs, (0.0, T), z, method="Radau", jac=jac, rtol=rtol,
                                        atol=rtol * max(1e-12, float(np.max(np.abs(z)))), dense_output=True)
        if sol.status != 0:
            raise IntegratorError(f"integration failed while shooting: {sol.message}")
        return sol

    def residual(u):
        z, T = u[:n], u[n]
        return np.append(flow(z, T).y[:, -1] - z, np.dot(z - y0, anchor_f))

    res = scipy.optimize.root(residual, np.append(y0, T0), method="hybr", options={"xtol": 1e-11})
    if not res.success or np.max(np.abs(res.fun[:n])) > 1e-7 * max(1.0, float(np.max(np.abs(res.x[:n])))):
        raise IntegratorError(f"shooting did not converge: {res.message}")
    z, T = res.x[:n], float(res.x[n])
    sol = flow(z, T)
    # monodromy by central differences (small systems)
    h = 1e-6 * max(1.0, float(np.max(np.abs(z))))
    Mono = np.empty((n, n))
    for j in range(n):
        d = np.zeros(n)
        d[j] = h
        Mono[:, j] = (flow(z + d, T).y[:, -1] - flow(z - d, T).y[:, -1]) / (2 * h)
    mult = np.linalg.eigvals(Mono)
    # drop the trivial multiplier (closest to 1)
    mult = np.delete(mult, int(np.argmin(np.abs(mult - 1.0))))
    return z, T, sol, mult


def _check_system(system, params: Mapping[str, float], bracket, eps2: float, tolerance, rtol: float) -> CheckResult:
    from landau.derivation.general import hopf_normal_form

    if bracket is None:
        raise InputError(f"{system.name}: give bracket=(lo, hi) around the Hopf value of {system.parameter.name}")
    pr = hopf_normal_form(system, params, bracket)
    crit = Criticality(str(pr.criticality))
    tol = tolerance if tolerance is not None else default_tolerance(crit, eps2)
    scale = abs(pr.p_c) if abs(pr.p_c) > P_C_ZERO else 1.0   # a Hopf point at p = 0: absolute distance
    common = dict(system=system.name, parameter=pr.parameter, eps2=eps2, prediction=pr, tolerance=tol)
    if crit == Criticality.DEGENERATE or pr.cycle_side == 0:
        return CheckResult(p=pr.p_c, amplitude_predicted=None, amplitude_simulated=None, rel_error=None,
                           frequency_predicted=None, frequency_simulated=None, frequency_rel_error=None,
                           verdict=Verdict.OUTSIDE_VALIDITY,
                           reason="Lambda = 0 (codimension-two point): the cubic amplitude equation predicts no "
                                  "amplitude",
                           **common)
    p = pr.p_c + pr.cycle_side * eps2 * scale
    A = pr.amplitude(p)
    w = pr.frequency(p)
    if not w > 0:
        return CheckResult(p=p, amplitude_predicted=A, amplitude_simulated=None, rel_error=None, frequency_predicted=w,
                           frequency_simulated=None, frequency_rel_error=None, verdict=Verdict.OUTSIDE_VALIDITY,
                           reason=f"the predicted frequency {w:.3g} rad/s is not positive at eps2 = {eps2:g}", **common)
    f, J, E_inverse, vals = _numeric_field(system, params)
    Einv = E_inverse(p)

    def rhs(t, y):
        return Einv @ np.asarray(f(*y, p, *vals), dtype=float)

    def jac(t, y):
        return Einv @ np.asarray(J(*y, p, *vals), dtype=float)

    import scipy.optimize

    y0 = np.asarray(pr.equilibrium, dtype=float)
    y0 = scipy.optimize.fsolve(lambda y: rhs(0.0, y), y0, xtol=1e-13)
    lam, vecs = np.linalg.eig(jac(0.0, y0))
    i = int(np.argmin(np.abs(lam.imag - pr.omega_c) + np.abs(lam.real)))
    q = vecs[:, i] / vecs[system.normalise, i]        # normalised component = 1
    start = y0 + A * np.real(q)                       # on the critical mode, normalised component at its max
    try:
        z, T, sol, mult = _shoot(rhs, jac, start, 2 * np.pi / w, rhs(0.0, start), rtol)
    except (IntegratorError, ValueError, np.linalg.LinAlgError) as exc:
        return CheckResult(p=p, amplitude_predicted=A, amplitude_simulated=None, rel_error=None, frequency_predicted=w,
                           frequency_simulated=None, frequency_rel_error=None, verdict=Verdict.FAILED,
                           reason=str(exc), **common)
    ts = np.linspace(0.0, T, 2001)
    yn = sol.sol(ts)[system.normalise]
    amp = 0.5 * float(yn.max() - yn.min())
    rel = amp / A - 1.0
    wsim = 2 * np.pi / T
    stable = bool(np.max(np.abs(mult)) < 1.0)
    ok_stab = stable == (crit == Criticality.SUPERCRITICAL)
    agrees = abs(rel) <= tol and ok_stab
    reason = "" if agrees else (f"amplitude off by {rel:+.2%}" if abs(rel) > tol else "the cycle has the wrong "
                                                                                      "stability")
    return CheckResult(p=p, amplitude_predicted=A, amplitude_simulated=amp, rel_error=rel, frequency_predicted=w,
                       frequency_simulated=wsim, frequency_rel_error=wsim / w - 1.0,
                       verdict=Verdict.AGREES if agrees else Verdict.DISAGREES, reason=reason, cycle_stable=stable,
                       detail={"floquet_multipliers": [float(abs(m)) for m in mult], "period": T,
                               "mean_shift": 0.5 * float(yn.max() + yn.min()) - float(y0[system.normalise])},
                       **common)


# ---------------------------------------------------------------------------------------------
# the entry point
# ---------------------------------------------------------------------------------------------

def check(target, V: float | None = None, eps2: float = 1e-3, params: Mapping[str, float] | None = None, *,
          bracket: tuple[float, float] | None = None, tolerance: float | None = None, bistability: bool = True,
          rtol: float = 1e-10) -> CheckResult:
    """Check the predicted Hopf bifurcation of a law or system by direct simulation.

    Parameters
    ----------
    target : FrictionLaw, str, SpringBlock or DynamicalSystem
        A friction law (or the name of a built-in law) is put in the default spring–block of
        Putelat et al. (2010) eq. (4); a general system is simulated as E·ẏ = f(y; p).
    V : float
        Driving velocity [m/s] (spring–block only).
    eps2 : float
        Relative distance from the Hopf point, ε² = |p − p_c|/|p_c|, in (0, 0.5) (absolute distance
        |p − p_c| for a general system whose Hopf point is at p_c = 0, |p_c| < 1e-9).  The side is chosen
        from the prediction: where the stable (supercritical) or unstable (subcritical) cycle exists.
    params : mapping, optional
        Parameter values (overrides of the law's and system's defaults).
    bracket : (float, float), optional
        General systems: an interval of the bifurcation parameter containing one Hopf point.
    tolerance : float, optional
        Relative amplitude tolerance (default: :func:`default_tolerance`).
    bistability : bool
        Subcritical spring–block points: also show bistability by bisection (slower).
    rtol : float
        Integration tolerance of the general route.

    Returns
    -------
    CheckResult
        With a :class:`Verdict`; ``result.agrees`` is True only for :attr:`Verdict.AGREES`.

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

    try:
        eps2 = float(eps2)
    except (TypeError, ValueError):
        raise InputError(f"eps2 must be a number, got {eps2!r}") from None
    if not (0 < eps2 < 0.5) or not math.isfinite(eps2):
        raise InputError(f"eps2 must be in (0, 0.5), got {eps2!r}")
    if tolerance is not None and not (0 < tolerance < 1):
        raise InputError(f"tolerance must be in (0, 1), got {tolerance!r}")
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
    V = float(V)
    if not (V > 0 and math.isfinite(V)):
        raise InputError(f"V must be a positive velocity in m/s, got {V!r}")
    return _check_spring_block(target, V, eps2, params, tolerance, bistability)
