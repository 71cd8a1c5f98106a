"""The flutter threshold of a structure in sliding contact: a mode-coupling collision or a Hopf point.

Complex eigenvalue analysis as brake engineers run it, on the matrices assembled about steady sliding
(:meth:`landau.systems.mode_coupling.ModeCoupling.linearised`): M, C_eff, K_eff with the non-symmetric
friction stiffness −μ N'(y*) e_t e_nᵀ.

* **Undamped** (C_eff = 0): the eigenvalues of M⁻¹K_eff are s = ω² (real and positive while stable);
  two of them merge and leave the real axis at the threshold — a collision of two imaginary pairs ±iω
  (a Krein, Hamiltonian–Hopf collision), not a transversal Hopf crossing.  It is located on the
  smooth test function min_{i<j} Re (s_i − s_j)², which changes sign there (for two modes it is the
  discriminant of the 2×2 eigenproblem), and returned as a :class:`ModeCouplingResult`
  (``kind = "mode-coupling"``).
* **Damped**: the threshold is a Hopf point, located on max Re λ of the first-order matrix; its
  amplitude equation is the general engine's (:func:`landau.derivation.general.hopf_normal_form`), with
  ``kind = "hopf"`` and the amplitude coefficient C of every coordinate.

For the undamped 2-DOF model of Hoffmann et al. (2002) with M = m I and contact stiffness k_N = N'(y*),
the discriminant (k₁₁ − k₂₂ − k_N)² + 4k₁₂(k₁₂ − μ k_N) of the 2×2 problem vanishes at

    μ_c = [(k₁₁ − k₂₂ − k_N)² + 4k₁₂²] / (4 k₁₂ k_N),   ω_c² = (k₁₁ + k₂₂ + k_N) / (2m)

(:func:`hoffmann_threshold`, :data:`THRESHOLD_LATEX`).

References
----------
Hoffmann, N., Fischer, M., Allgaier, R. & Gaul, L. (2002), Mech. Res. Commun. 29, 197–205.
Hoffmann, N. & Gaul, L. (2003), Effects of damping on mode-coupling instability in friction induced
oscillations, Z. Angew. Math. Mech. 83, 524–534.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, Callable, Mapping

import numpy as np
import scipy.optimize

from landau.errors import InputError, NoHopfError, NoSteadySlidingError
from landau.systems.mode_coupling import ModeCoupling, hoffmann_stiffness

#: samples of the bracket scanned for the first threshold
SCAN_SAMPLES = 200
#: the default search interval of the friction coefficient
MU_BRACKET = (0.0, 2.0)

THRESHOLD_LATEX = (r"\mu_c = \frac{(k_{11} - k_{22} - k_N)^2 + 4 k_{12}^2}{4\,k_{12}\,k_N}, \qquad "
                   r"\omega_c = \sqrt{\frac{k_{11} + k_{22} + k_N}{2m}}")


def hoffmann_threshold(m: float, k1: float, k2: float, alpha1: float, alpha2: float,
                       kN: float) -> tuple[float, float]:
    """(μ_c, ω_c) of the undamped 2-DOF model of Hoffmann et al. (2002) in closed form (module docstring).

    Parameters
    ----------
    m, k1, k2 : float
        Mass and spring stiffnesses.
    alpha1, alpha2 : float
        Spring angles (degrees).
    kN : float
        The contact's tangent stiffness N'(y*) (k_H for the linear contact).
    """
    k11, k12, k22 = hoffmann_stiffness(k1, k2, alpha1, alpha2)
    if k12 == 0:
        raise NoHopfError("hoffmann2002: k12 = 0, the friction does not couple the two modes")
    return ((k11 - k22 - kN) ** 2 + 4 * k12**2) / (4 * k12 * kN), math.sqrt((k11 + k22 + kN) / (2 * m))


def hoffmann_vanishing_damping_threshold(k1: float, k2: float, alpha1: float, alpha2: float, kN: float,
                                         c1: float, c2: float) -> float:
    """μ_c(ε → 0) of the 2-DOF model (M = m I) with damping ε diag(c₁, c₂), in closed form.

    The Routh–Hurwitz condition a₁a₂a₃ − a₀a₃² − a₁²a₄ > 0 of m²λ⁴ + mε(c₁ + c₂)λ³ + (m tr K + ε²c₁c₂)λ²
    + ε(c₁K₂₂ + c₂K₁₁)λ + det K at leading order in ε gives det K < (c₁K₂₂ + c₂K₁₁)(c₁K₁₁ + c₂K₂₂)/(c₁ + c₂)²,
    that is (K₁₁ = k₁₁, K₂₂ = k₂₂ + k_N, det K = K₁₁K₂₂ − k₁₂(k₁₂ − μk_N))

        μ_c(0⁺) = [c₁c₂/(c₁ + c₂)² (k₁₁ − k₂₂ − k_N)² + k₁₂²] / (k₁₂ k_N),

    the undamped μ_c where c₁ = c₂ (proportional damping) and below it otherwise, by
    (k₁₁ − k₂₂ − k_N)²/(4k₁₂k_N) · ((c₁ − c₂)/(c₁ + c₂))²: the destabilisation paradox (Hoffmann & Gaul 2003).
    """
    if not (c1 >= 0 and c2 >= 0 and c1 + c2 > 0):
        raise InputError(f"the damping c1, c2 must be >= 0 and not both 0, got {c1!r}, {c2!r}")
    k11, k12, k22 = hoffmann_stiffness(k1, k2, alpha1, alpha2)
    return (c1 * c2 / (c1 + c2) ** 2 * (k11 - k22 - kN) ** 2 + k12**2) / (k12 * kN)


def spectrum(mc: ModeCoupling) -> np.ndarray:
    """The 2n eigenvalues λ of the sliding motion's first-order matrix, sorted by Im λ, then Re λ."""
    lam = np.linalg.eigvals(mc.first_order())
    return lam[np.lexsort((lam.real, lam.imag))]


def squared_frequencies(mc: ModeCoupling) -> np.ndarray:
    """The eigenvalues s = ω² of M⁻¹K_eff (undamped), sorted by real part."""
    M, _, K = mc.linearised()
    # s: eigenvalues of M⁻¹K_eff, from one solve of M X = K_eff
    s = np.linalg.eigvals(np.linalg.solve(M, K))
    return s[np.argsort(s.real)]


def collision_function(mc: ModeCoupling) -> float:
    """min_{i<j} Re (s_i − s_j)² over the eigenvalues s = ω² of M⁻¹K_eff: > 0 while they are real and
    distinct, < 0 once two have merged into a complex pair (smooth in the parameters)."""
    s = squared_frequencies(mc)
    d = s[:, None] - s[None, :]
    iu = np.triu_indices(len(s), 1)
    return float(np.min((d[iu] ** 2).real))


def growth_function(mc: ModeCoupling) -> float:
    """max Re λ of the first-order matrix (> 0: unstable)."""
    return float(np.max(np.linalg.eigvals(mc.first_order()).real))


@dataclass(frozen=True)
class Threshold:
    """The first flutter threshold of a parameter in a bracket (from :func:`flutter_threshold`).

    ``kind`` is ``"mode-coupling"`` (undamped: two imaginary pairs collide) or ``"hopf"`` (damped).
    """

    kind: str
    parameter: str
    p_c: float
    omega_c: float
    bracket: tuple[float, float]
    system: ModeCoupling
    #: the interval searched (``bracket`` is the scan step holding the threshold)
    search: tuple[float, float] = (math.nan, math.nan)


def _bracket_of(mc: ModeCoupling, parameter: str, bracket) -> tuple[float, float]:
    values = mc.parameter_values()
    if parameter not in values:
        raise InputError(f"mode-coupling: unknown bifurcation parameter {parameter!r} "
                         f"(known: {', '.join(sorted(values))})")
    if bracket is None:
        if parameter == "mu":
            return MU_BRACKET
        v = values[parameter]
        if v == 0:
            raise InputError(f"mode-coupling: give the interval of {parameter!r} to search (--bracket LO:HI)")
        return tuple(sorted((v / 10, v * 10)))  # type: ignore[return-value]
    try:
        lo, hi = (float(b) for b in bracket)
    except (TypeError, ValueError):
        raise InputError(f"mode-coupling: the bracket must be two numbers, got {bracket!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise InputError(f"mode-coupling: the bracket needs LO < HI, both finite, got {bracket!r}")
    return lo, hi


def flutter_threshold(mc: ModeCoupling, parameter: str = "mu", bracket: tuple[float, float] | None = None,
                      samples: int = SCAN_SAMPLES) -> Threshold:
    """The first value of ``parameter`` in ``bracket`` where steady sliding loses stability by flutter.

    The bracket is scanned in ``samples`` steps (points where the contact opens at equilibrium are
    skipped); the first sign change of the test function (module docstring) is refined by Brent's
    method to machine precision.

    Raises
    ------
    NoHopfError
        No threshold in the bracket.
    """
    lo, hi = _bracket_of(mc, parameter, bracket)
    grid = np.linspace(lo, hi, int(samples) + 1)
    prev: tuple[float, float, bool] | None = None
    opened: NoSteadySlidingError | None = None
    valid = 0
    for p in grid:
        try:
            sys_p = mc.with_value(parameter, p)
            undamped = sys_p.undamped()
            g = collision_function(sys_p) if undamped else -growth_function(sys_p)
        except NoSteadySlidingError as exc:
            prev, opened = None, exc
            continue
        valid += 1
        if prev is not None and prev[2] == undamped and prev[1] > 0 >= g:
            return replace(_refine(mc, parameter, prev[0], p, undamped), search=(lo, hi))
        prev = (p, g, undamped)
    if not valid and opened is not None:   # no steady sliding anywhere in the bracket: say why
        raise opened
    what = "collision of two modes" if mc.undamped() else "flutter (Hopf) threshold"
    raise NoHopfError(f"mode-coupling: no {what} of {parameter} in [{lo:g}, {hi:g}] (steady sliding stays "
                      "stable there, or is unstable at its lower end already)")


def _refine(mc: ModeCoupling, parameter: str, a: float, b: float, undamped: bool) -> Threshold:
    def g(p: float) -> float:
        s = mc.with_value(parameter, p)
        return collision_function(s) if undamped else -growth_function(s)

    pc = b if g(b) == 0 else float(scipy.optimize.brentq(g, a, b, xtol=1e-15 * max(1.0, abs(a), abs(b)),
                                                         rtol=4 * np.finfo(float).eps, maxiter=200))
    at = mc.with_value(parameter, pc)
    if undamped:
        s = squared_frequencies(at)
        i = int(np.argmin(np.abs(np.diff(s.real))))
        omega = math.sqrt(max(0.5 * float((s[i] + s[i + 1]).real), 0.0))
        kind = "mode-coupling"
    else:
        lam = spectrum(at)
        omega = abs(float(lam[np.argmax(lam.real)].imag))
        kind = "hopf"
    return Threshold(kind, parameter, pc, omega, (a, b), mc)


@dataclass(frozen=True)
class ModeCouplingResult:
    """A mode-coupling (Krein) collision: the undamped flutter threshold, which is not a Hopf point.

    Parameters
    ----------
    parameter : str
        The bifurcation parameter (μ by default).
    p_c : float
        Its critical value μ_c, where two imaginary pairs ±iω collide.
    omega_c : float
        The merging frequency (rad/s).
    equilibrium : tuple of float
        The steady sliding state at p_c (positions, then velocities 0).
    modes : tuple of dict
        The two merging modes: their index by ascending frequency, their frequency at the lower end
        of the bracket and their (real) mode shape there, normalised on the tangential coordinate.
    shape : tuple of complex
        The one (defective) mode shape they merge into at p_c, normalised on the tangential coordinate.
    params : mapping
        The other parameters' values.
    """

    system: str
    parameter: str
    p_c: float
    omega_c: float
    equilibrium: tuple[float, ...]
    modes: tuple[Mapping[str, Any], ...]
    shape: tuple[complex, ...]
    states: tuple[str, ...]
    params: Mapping[str, float] = field(default_factory=dict)
    kind: str = "mode-coupling"
    #: no Landau coefficient: a Krein collision has no Hopf normal form
    Lambda: float = math.nan
    criticality: str = "undetermined"

    def as_dict(self) -> dict[str, Any]:
        return {"system": self.system, "kind": self.kind, "parameter": self.parameter, "p_c": self.p_c,
                "omega_c": self.omega_c, "frequency_hz": self.omega_c / (2 * math.pi),
                "equilibrium": list(self.equilibrium), "Lambda": None, "criticality": self.criticality,
                "modes": [dict(m) for m in self.modes],
                "shape_re": [z.real for z in self.shape], "shape_im": [z.imag for z in self.shape],
                "note": "undamped: the threshold is a collision of two imaginary pairs (mode coupling, a Krein "
                        "collision), not a Hopf point; give damping (c1, c2) for the Hopf point and Lambda"}

    def __str__(self) -> str:
        a, b = (m["index"] for m in self.modes)
        return (f"mode coupling: {self.parameter}_c = {self.p_c:.10g}, modes {a} and {b} merge at "
                f"omega_c = {self.omega_c:.6g} rad/s ({self.omega_c / (2 * math.pi):.6g} Hz); undamped, "
                "no Hopf normal form (give damping for Lambda)")

    __repr__ = __str__


def _modes_at(mc: ModeCoupling, merging: tuple[int, int]) -> tuple[dict[str, Any], ...]:
    M, _, K = mc.linearised()
    # the undamped modes: eigenpairs of M⁻¹K_eff, from one solve of M X = K_eff
    s, vec = np.linalg.eig(np.linalg.solve(M, K))
    order = np.argsort(s.real)
    out = []
    for i in merging:
        j = order[i]
        v = vec[:, j] / vec[mc.tangential, j]
        out.append({"index": i + 1, "omega": math.sqrt(max(float(s[j].real), 0.0)),
                    "shape": [float(x) for x in v.real]})
    return tuple(out)


def mode_coupling_result(th: Threshold) -> ModeCouplingResult:
    """The named result of an undamped threshold: μ_c, the merging frequency and the two modes."""
    mc = th.system
    at = mc.with_value(th.parameter, th.p_c)
    s = squared_frequencies(at)
    i = int(np.argmin(np.abs(np.diff(s.real))))
    base = mc.with_value(th.parameter, th.search[0])
    try:
        modes = _modes_at(base, (i, i + 1))
    except NoSteadySlidingError:
        modes = _modes_at(at, (i, i + 1))
    M, _, K = at.linearised()
    # the merged shape: the null vector of K_eff − ω_c² M (its last right singular vector)
    _, _, vh = np.linalg.svd(K - th.omega_c**2 * M)
    shape = vh[-1].conj()
    shape = shape / shape[mc.tangential]
    x0 = at.equilibrium()
    params = {k: v for k, v in at.parameter_values().items() if k != th.parameter}
    return ModeCouplingResult("mode-coupling", th.parameter, th.p_c, th.omega_c, (*map(float, x0), *([0.0] * mc.n)),
                              modes, tuple(complex(z) for z in shape), mc.state_names(), params)


def amplitudes(mc: ModeCoupling, result) -> dict[str, float]:
    """C of every coordinate: C·|q_j| with the critical mode q of the first-order matrix at p_c normalised
    on the tangential position (the engine's normalised component)."""
    A = mc.with_value(result.parameter, result.p_c).first_order()
    lam, vec = np.linalg.eig(A)
    j = int(np.argmin(np.abs(lam - 1j * result.omega_c)))
    q = vec[:, j] / vec[mc.tangential, j]
    return {f"C_{name}": float(result.C * abs(z)) for name, z in zip(mc.state_names(), q, strict=True)}


def flutter_hopf(mc: ModeCoupling, parameter: str = "mu", bracket: tuple[float, float] | None = None, *,
                 l2: bool = False):
    """The flutter onset of ``mc`` in ``parameter``: a :class:`ModeCouplingResult` where undamped, else the
    Hopf point with its amplitude equation (a :class:`~landau.derivation.hopf.HopfResult` with
    ``kind = "hopf"`` and ``C_<state>`` for every state in ``extra``).

    Raises
    ------
    NoHopfError
        No threshold in the bracket.
    """
    from landau.derivation.general import hopf_normal_form

    th = flutter_threshold(mc, parameter, bracket)
    if th.kind != "hopf":   # undamped: a collision of two imaginary pairs
        return mode_coupling_result(th)
    system = mc.with_value(parameter, th.p_c).sliding_system(parameter)
    lo, hi = _bracket_of(mc, parameter, bracket)
    d = 1e-3 * (hi - lo)
    params = dict(system.defaults)
    res = hopf_normal_form(system, params, (max(lo, th.p_c - d), min(hi, th.p_c + d)), samples=4, l2=l2)
    extra = {**res.extra, "kind": "hopf", **amplitudes(mc, res)}
    return replace(res, extra=extra)


def paradox_scaled(mc: ModeCoupling, scale: float) -> ModeCoupling:
    """``mc`` with its damping matrix multiplied by ``scale`` (c₁, c₂ of the 2-DOF model)."""
    if mc.params is not None:
        return mc.with_value("c1", mc.params["c1"] * scale).with_value("c2", mc.params["c2"] * scale)
    return replace(mc, C=mc.C * scale)


@dataclass(frozen=True)
class Paradox:
    """The destabilisation paradox of Hoffmann & Gaul (2003): μ_c of the damping scaled by ``scales``
    (→ 0) beside the undamped μ_c."""

    parameter: str
    scales: np.ndarray
    p_c: np.ndarray
    p_c_undamped: float

    @property
    def limit(self) -> float:
        """μ_c at the smallest damping scale (the limit c → 0)."""
        return float(self.p_c[np.argmin(self.scales)])


def destabilisation_paradox(mc: ModeCoupling, scales=None, parameter: str = "mu",
                            bracket: tuple[float, float] | None = None) -> Paradox:
    """μ_c(ε C) for damping scales ε → 0 and μ_c(C = 0): for damping that is not proportional, the limit
    differs from (lies below) the undamped threshold (Hoffmann & Gaul 2003)."""
    eps = np.geomspace(1.0, 1e-4, 9) if scales is None else np.asarray(scales, dtype=float)
    if eps.ndim != 1 or not np.all(eps > 0):
        raise InputError("destabilisation_paradox: the damping scales must be > 0")
    pcs = np.array([flutter_threshold(paradox_scaled(mc, e), parameter, bracket).p_c for e in eps])
    undamped = flutter_threshold(paradox_scaled(mc, 0.0), parameter, bracket).p_c
    return Paradox(parameter, eps, pcs, undamped)


def vanishing_damping_thresholds(mc: ModeCoupling, ratios, scale: float = 1e-4,
                                 bracket: tuple[float, float] | None = None) -> np.ndarray:
    """μ_c(c → 0) of the 2-DOF model against the damping ratio c₂/c₁: the damping diag(c₁, r c₁) scaled to
    ``scale`` × c₁ of ``mc``.  At r = 1 (damping proportional to M = m I) it is the undamped μ_c; elsewhere
    below it — the destabilisation paradox as a damping-ratio sweep (Hoffmann & Gaul 2003)."""
    if mc.params is None:
        raise InputError("vanishing_damping_thresholds: the damping ratio c2/c1 is a parameter of the 2-DOF model "
                         "(for matrices use destabilisation_paradox)")
    c1 = mc.params["c1"] if mc.params["c1"] > 0 else 1.0
    out = []
    for r in np.asarray(ratios, dtype=float):
        if not (math.isfinite(r) and r > 0):
            raise InputError(f"vanishing_damping_thresholds: a damping ratio must be > 0, got {r!r}")
        damped = mc.with_value("c1", c1 * scale).with_value("c2", c1 * scale * r)
        out.append(flutter_threshold(damped, "mu", bracket).p_c)
    return np.array(out)


def scan(mc: ModeCoupling, parameter: str, values, fn: Callable[[ModeCoupling], Any]) -> list[Any]:
    """``fn`` of the system at each value of ``parameter`` (None where the contact opens)."""
    out: list[Any] = []
    for p in values:
        try:
            out.append(fn(mc.with_value(parameter, float(p))))
        except NoSteadySlidingError:
            out.append(None)
    return out


__all__ = ["MU_BRACKET", "THRESHOLD_LATEX", "ModeCouplingResult", "Paradox", "Threshold", "amplitudes",
           "collision_function", "destabilisation_paradox", "flutter_hopf", "flutter_threshold", "growth_function",
           "hoffmann_threshold", "hoffmann_vanishing_damping_threshold", "mode_coupling_result", "spectrum",
           "squared_frequencies", "vanishing_damping_thresholds"]
