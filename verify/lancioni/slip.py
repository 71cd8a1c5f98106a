"""The smooth slip mode of the frictional impact oscillator as a :class:`DynamicalSystem`.

Lancioni, Lenci & Galvanetto, eq. (1) (re-derived from the energies and virtual work):

    [m₁l²       m₁l sin φ] [φ̈]   [l sin φ  l cos φ] [λ_N]   [c_φφ̇ + k_φ(φ − φ₀) + m₁gl sin φ             ]
    [m₁l sin φ  m₁ + m₂  ] [ÿ] = [1        0      ] [λ_T] − [c_yẏ + k_y(y − y₀) + m₁lφ̇² cos φ + (m₁+m₂)g]

While the tip slides on the belt the gap g_N = y − l cos φ stays 0, so (Sec. 2.2 of the paper)
y = l cos φ, ẏ = −lφ̇ sin φ, ÿ = −lφ̇² cos φ − lφ̈ sin φ, and Coulomb friction gives
λ_T = −s μ λ_N with s = sign g_T, g_T = lφ̇ cos φ − v.  Substituting y, ÿ and λ_T, the two
rows of eq. (1) are linear in the two unknowns (φ̈, λ_N); eliminating λ_N leaves the planar
smooth ODE  φ̇ = ω,  ω̇ = F(φ, ω; μ)  (``slip_system``), which the landau engine
(:func:`landau.general.hopf_normal_form`) analyses with μ as the Hopf parameter.

Belt direction.  For a constant belt velocity v the slip equilibrium (ω = 0) has g_T = −v,
so s = −sign v and neither the equilibrium nor its linearisation depend on |v|.  Only one
direction has a Hopf point (see :func:`hopf_direction_scan`): with both parameter sets of
the paper it is v < 0 (s = +1, *positive slip* g_T > 0, friction λ_T = −μλ_N).  Why: the
c_y-damping of the reduced ODE is c_y l² sin φ (sin φ − sμ cos φ), which for s = +1
changes sign at μ ≈ tan φ_e (≈ tan π/8 = 0.414) — the Hopf point near μ ≈ 0.41; for
s = −1 it stays positive and the equilibrium stays stable for all μ in [0, 1].  The
denominator of F, l²(m₁cos²φ + m₂ sin φ (sin φ − sμ cos φ)) (the Painlevé coefficient
of :mod:`landau.verify.lancioni.contact`), stays positive on the slip branch for s = +1 only
while μ < (m₁ cot φ + m₂ tan φ)/m₂.

Equilibrium.  ω = 0, and φ_e solves the transcendental
    λ_N(φ)·l(sin φ − sμ cos φ) = k_φ(φ − φ₀) + m₁gl sin φ,  λ_N(φ) = k_y(l cos φ − y₀) + (m₁+m₂)g,
which has no closed form; the system declares one Newton step from φ₀ as its
(approximate) equilibrium expression and the engine refines it by Newton at 50 digits.

g.  The published Hopf values (μ = 0.40977, set 1; 0.353, set 2) are reproduced with
g = 10 m/s²; g = 9.81 moves them to ≈ 0.40986 and ≈ 0.3541.  g stays a parameter.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Mapping

import numpy as np
import sympy as sp

from landau.errors import InputError, NoHopfError
from landau.general import HopfNormalForm, hopf_normal_form
from landau.system import DynamicalSystem

phi, omega = sp.symbols("phi omega", real=True)
mu = sp.Symbol("mu", nonnegative=True)
m1, m2, l, k_y, k_phi, c_y, c_phi, phi0, y0, g = sp.symbols(
    "m1 m2 l k_y k_phi c_y c_phi phi0 y0 g", real=True)

#: paper's first parameter set (Sec. 3; Leine, Brogliato & Nijmeijer 2002) with g = 10 m/s²
SET1: dict[str, float] = {"m1": 0.1, "m2": 1.0, "l": 1.0, "k_y": 100.0, "k_phi": 100.0, "c_y": 10.0,
                          "c_phi": 0.0, "phi0": float(np.pi / 8), "y0": 1.0, "g": 10.0}
#: second set (Sec. 3, Figs 4–5): m₁ = 0.4 kg, k_φ = 25 N·m
SET2: dict[str, float] = {**SET1, "m1": 0.4, "k_phi": 25.0}
PARAM_NAMES = tuple(SET1)


@lru_cache(maxsize=4)
def slip_accelerations(s: int):
    """(φ̈, λ_N) in slip with λ_T = −sμλ_N, as sympy expressions of (φ, ω) and the parameters."""
    if s not in (-1, 1):
        raise InputError(f"slip sign must be +1 or -1, got {s!r}")
    ddphi, lamN = sp.symbols("ddphi lamN")
    sn, cs = sp.sin(phi), sp.cos(phi)
    y, yd = l * cs, -l * omega * sn
    ydd = -l * omega**2 * cs - l * ddphi * sn
    lamT = -s * mu * lamN
    row_phi = m1 * l**2 * ddphi + m1 * l * sn * ydd - (l * sn * lamN + l * cs * lamT) \
        + (c_phi * omega + k_phi * (phi - phi0) + m1 * g * l * sn)
    row_y = m1 * l * sn * ddphi + (m1 + m2) * ydd - lamN \
        + (c_y * yd + k_y * (y - y0) + m1 * l * omega**2 * cs + (m1 + m2) * g)
    # the rows are linear in (φ̈, λ_N): Cramer's rule (sympy's solve+simplify is ~10x slower)
    A, rhs = sp.linear_eq_to_matrix([sp.expand(row_phi), sp.expand(row_y)], [ddphi, lamN])
    det = sp.factor(A.det())
    x1 = (rhs[0] * A[1, 1] - A[0, 1] * rhs[1])
    x2 = (A[0, 0] * rhs[1] - A[1, 0] * rhs[0])
    return sp.collect(sp.expand(x1), omega) / det, sp.collect(sp.expand(x2), omega) / det


@lru_cache(maxsize=4)
def _numeric_slip(s: int):
    """Compiled F(φ, 0; μ, params) and the Jacobian of (ω, F) (for the direction scan)."""
    F, _ = slip_accelerations(s)
    names = [sp.Symbol(n, real=True) for n in PARAM_NAMES]
    f0 = sp.lambdify([phi, mu, *names], F.subs(omega, 0))
    J = sp.lambdify([phi, omega, mu, *names], sp.Matrix([omega, F]).jacobian([phi, omega]))
    return f0, J


@lru_cache(maxsize=4)
def slip_system(s: int = 1) -> DynamicalSystem:
    """The slip mode (g_N = 0, sign g_T = s) as φ̇ = ω, ω̇ = F(φ, ω; μ); Hopf parameter μ.

    ``s = +1`` (g_T > 0, belt velocity v < 0) is the direction with the Hopf point.
    """
    F, _ = slip_accelerations(s)
    # approximate equilibrium: one Newton step on F(φ, 0) = 0 from φ₀ (refined by the engine)
    F0 = F.subs(omega, 0)
    phi_e = phi0 - (F0 / sp.diff(F0, phi)).subs(phi, phi0)
    return DynamicalSystem(
        name=f"lancioni-slip[{'+' if s > 0 else '-'}]",
        states=(phi, omega),
        rhs=(omega, F),
        mass=(sp.Integer(1), sp.Integer(1)),
        parameter=mu,
        equilibrium=(phi_e, sp.Integer(0)),
        defaults=dict(SET1),
        normalise=0,
        description="Lancioni-Lenci-Galvanetto eq. (1) with g_N = 0 and lambda_T = -s mu lambda_N",
    )


def resolve(params: Mapping[str, float] | None = None) -> dict[str, float]:
    """SET1 updated by ``params`` (names of :data:`PARAM_NAMES`), checked."""
    p = dict(SET1)
    for k_, v_ in (params or {}).items():
        if k_ not in p:
            raise InputError(f"unknown parameter {k_!r} (known: {', '.join(PARAM_NAMES)})")
        v_ = float(v_)
        if not np.isfinite(v_):
            raise InputError(f"parameter {k_!r} must be finite")
        p[k_] = v_
    for k_ in ("m1", "m2", "l"):
        if p[k_] <= 0:
            raise InputError(f"parameter {k_!r} must be > 0, got {p[k_]!r}")
    return p


#: the scan for the Hopf point covers friction coefficients 0 < μ ≤ MU_SCAN_MAX (dry friction of
#: engineering materials stays below ~1.5; the slip mode is checked, not assumed, to be well posed)
MU_SCAN_MAX = 2.0


def hopf_bracket(params: Mapping[str, float] | None = None, s: int = 1, n: int = 201) -> tuple[float, float]:
    """A μ interval containing the first crossing of the slip equilibrium's complex pair.

    Scans max Re λ of the complex eigenvalue pair of the slip equilibrium over (0, MU_SCAN_MAX]
    (the physical range of a friction coefficient) and returns the first grid cell where it
    changes sign — derived from the model, not from a published value."""
    p = resolve(params)
    _, J = _numeric_slip(s)
    mus = np.linspace(MU_SCAN_MAX / n, MU_SCAN_MAX, n)
    prev = None
    for m_ in mus:
        try:
            pe = equilibrium_phi(p, m_, s)
            lam = np.linalg.eigvals(np.array(J(pe, 0.0, m_, *[p[k_] for k_ in PARAM_NAMES]), float))
        except (ValueError, RuntimeError, ZeroDivisionError):
            prev = None
            continue
        cplx = lam[np.abs(lam.imag) > 1e-12 * (1 + np.abs(lam.real))]
        r = float(np.max(cplx.real)) if cplx.size else None
        if r is not None and np.isfinite(r) and prev is not None and prev[1] * r < 0:
            return float(prev[0]), float(m_)
        prev = (m_, r) if r is not None and np.isfinite(r) else None
    raise NoHopfError(f"no Hopf point of the slip equilibrium (slip sign {s:+d}) for 0 < mu <= {MU_SCAN_MAX:g}")


def slip_hopf(params: Mapping[str, float] | None = None, bracket: tuple[float, float] | None = None,
              s: int = 1) -> HopfNormalForm:
    """Hopf point of the slip equilibrium in μ through the landau engine.

    Without ``bracket`` the interval comes from :func:`hopf_bracket` (a scan of the model).

    Parameters
    ----------
    params : mapping of str to float, optional
        Mechanical parameters (default: set 1).
    bracket : tuple of float, optional
        A μ interval containing the Hopf point.
    s : int, optional
        Slip sign (+1: positive slip, the belt direction with a Hopf point).

    Returns
    -------
    HopfNormalForm
        μ_c, ω_c, the Landau coefficient and the criticality.

    References
    ----------
    Kuznetsov, Y. A. (2004), *Elements of Applied Bifurcation Theory*, 3rd ed., Springer,
    Section 3.5.
    """
    if bracket is None:
        bracket = hopf_bracket(params, s)
    return hopf_normal_form(slip_system(s), resolve(params), bracket=bracket)


@dataclass(frozen=True)
class DirectionScan:
    """Max Re λ of the slip equilibrium over a μ grid for both belt directions."""

    mu: np.ndarray
    max_re: Mapping[int, np.ndarray]  # keyed by slip sign s (= −sign v)

    def hopf_sign(self) -> list[int]:
        return [s for s, r in self.max_re.items() if np.any(np.diff(np.sign(r[np.isfinite(r)])) != 0)]

    def __repr__(self) -> str:
        return f"DirectionScan(mu in [{self.mu[0]:g}, {self.mu[-1]:g}], Hopf for s = {self.hopf_sign()})"


def equilibrium_phi(p: Mapping[str, float], mu_val: float, s: int) -> float:
    """φ_e of the slip equilibrium (Newton on F(φ, 0) = 0 from φ₀)."""
    f, _ = _numeric_slip(s)
    from scipy.optimize import brentq, newton
    args = (mu_val, *[p[n] for n in PARAM_NAMES])
    try:
        return float(newton(lambda x: f(x, *args), p["phi0"], tol=1e-14, maxiter=100))
    except RuntimeError:
        return float(brentq(lambda x: f(x, *args), -np.pi / 2 + 1e-6, np.pi / 2 - 1e-6))


def hopf_direction_scan(params: Mapping[str, float] | None = None,
                        mus: np.ndarray = np.linspace(0.0, 1.0, 101)) -> DirectionScan:
    """Which belt direction has the Hopf point: max Re λ of the slip equilibrium for s = ±1."""
    p = resolve(params)
    out = {}
    for s in (-1, 1):
        _, J = _numeric_slip(s)
        vals = []
        for m_ in mus:
            try:
                pe = equilibrium_phi(p, m_, s)
                lam = np.linalg.eigvals(np.array(J(pe, 0.0, m_, *[p[n] for n in PARAM_NAMES]), float))
                vals.append(float(np.max(lam.real)))
            except (ValueError, RuntimeError):
                vals.append(np.nan)
        out[s] = np.array(vals)
    return DirectionScan(np.asarray(mus, float), out)
