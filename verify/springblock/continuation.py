"""Pseudo-arclength continuation of spring–block limit cycles (what the paper did with AUTO).

A branch point is u = (z, λ): z a point of the Poincaré section Σ (:mod:`landau.verify.springblock.orbits`)
and λ the continuation parameter — ``"k"`` (stiffness, as k/k_ref, at fixed V; Figs 6) or
``"logV"`` (log₁₀ V at fixed k, i.e. fixed κ = kL/σ; Fig. 11).  G(u) = P(z; λ) − z = 0 with
DG = [DP − I | ∂P/∂λ] (DP from the variational equations, ∂P/∂λ by central differences).

* **Hopf start** — independent of the engine: the Hopf point of the steady state is located by
  the crossing of the leading eigenvalue pair (Brent on max Re λ(J)); the first cycle is solved
  with its slip amplitude ξ fixed small and λ free (the branch's amplitude² is linear in λ
  near the Hopf point, which gives the branch's own Hopf estimate).
* **Continuation** — :func:`landau.analyses.arclength.continue_branch` (predictor along the tangent,
  corrector by Newton on [G; τ·(u − u_pred)] = 0, step adapted to Newton's effort); this module
  defines the problem (G, DG) only.
* **Folds of cycles** (saddle-nodes) — sign changes of the λ-component of the tangent, refined
  by bisection in the arclength (:func:`landau.analyses.arclength.refine_fold`); a Floquet multiplier
  crosses +1 there.  Each is a :class:`landau.analyses.codim2.FoldOfCycles`; the velocity where the fold
  meets the Hopf line (:func:`codim2_velocity`) a :class:`landau.analyses.codim2.GeneralisedHopfPoint`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from landau.analyses import arclength as al
from landau.analyses.codim2 import SPRING_BLOCK_PARAMETERS, FoldOfCycles, GeneralisedHopfPoint
from landau.errors import IntegratorError
from landau.support.memo import FloatMemo
from landau.support.progress import progress as bar
from landau.verify.springblock.model import SpringBlockModel
from landau.verify.springblock.orbits import (
    PeriodicOrbit,
    ShootingError,
    describe,
    hopf_parameter,
    hopf_stiffness,
    return_map,
    section_point,
)


@dataclass(frozen=True)
class BranchPoint:
    parameter: float          # k [N/m] or V [m/s]
    orbit: PeriodicOrbit
    tangent_lambda: float


@dataclass(frozen=True)
class Branch:
    """A continued branch of limit cycles born at a Hopf point."""

    kind: str                  # "k" or "logV"
    fixed: dict
    hopf_equilibrium: float    # Hopf parameter from the steady state's eigenvalues
    hopf_extrapolated: float   # from the branch (amplitude² → 0)
    points: tuple[BranchPoint, ...] = field(repr=False)
    folds: tuple[FoldOfCycles, ...] = ()
    stopped: str = ""

    def __repr__(self) -> str:
        return (f"Branch({self.kind}, Hopf {self.hopf_equilibrium:.10g} (eigenvalues), "
                f"{self.hopf_extrapolated:.6g} (branch), {len(self.points)} points, folds="
                f"{[f'{f.p_fold:.6g}' for f in self.folds]}, stopped: {self.stopped})")


class _Problem:
    """Maps λ to a model and evaluates G, DG."""

    def __init__(self, make: Callable[[float], SpringBlockModel], rtol: float):
        self.make = make
        self.rtol = rtol
        # the model by λ: the corrector and the difference at λ ± h revisit the same values
        self.model: FloatMemo[SpringBlockModel] = FloatMemo(make, 9)

    def G(self, u: np.ndarray, jac: bool = True):
        z, lam = u[:-1], u[-1]
        m = self.model(lam)
        Pz, DP, T, run = return_map(m, z, rtol=self.rtol, monodromy=jac)
        if not jac:
            return Pz - z, None, T, DP
        h = 1e-6 * max(abs(lam), 1e-3)
        Pp = return_map(self.model(lam + h), z, rtol=self.rtol, monodromy=False)[0]
        Pm = return_map(self.model(lam - h), z, rtol=self.rtol, monodromy=False)[0]
        DG = np.hstack([DP - np.eye(len(z)), ((Pp - Pm) / (2 * h))[:, None]])
        return Pz - z, DG, T, DP

    def F(self, u: np.ndarray):
        """The engine's problem: G(u) = P(z; λ) − z, DG = [DP − I | ∂P/∂λ], info (T, DP)."""
        r, DG, T, DP = self.G(u)
        return r, DG, (T, DP)


def _correct(prob: _Problem, u_pred: np.ndarray, tau: np.ndarray, tol: float, maxiter: int = 8) -> np.ndarray:
    """The engine's Newton corrector on G (2-norm test) from ``u_pred`` with the row ``tau``: the cycle u."""
    try:
        return al.newton_corrector(prob.F, u_pred, tau, tol, maxit=maxiter, norm="2")[0]
    except al.CorrectorError as exc:
        raise ShootingError(f"corrector did not converge ({exc})") from None


def continue_branch(make: Callable[[float], SpringBlockModel], lam_hopf: float, *, direction: float,
                    xi_start: float = 0.05, ds: float = 0.05, ds_max: float = 2.0, steps: int = 60,
                    lam_bounds: tuple[float, float] = (-np.inf, np.inf), xi_max: float = np.inf,
                    rtol: float = 1e-10, tol: float = 1e-9, progress=None):
    """Continue cycles from the Hopf point at λ = ``lam_hopf`` (``direction`` = ±1 guesses the side).

    Returns (list of (λ, orbit, τ_λ), list of (λ, orbit, orbit) at the folds, stop reason); ``steps``
    bounds the predictor–corrector attempts."""
    prob = _Problem(make, rtol)
    m0 = prob.model(lam_hopf)
    z0 = section_point(m0, xi_start * m0.ell)
    # first cycle: ξ fixed, λ free (τ = e_ξ makes the corrector's extra row the amplitude constraint)
    u_pred = np.r_[z0, lam_hopf + direction * 1e-6 * max(abs(lam_hopf), 1.0)]
    e_xi = np.zeros(len(u_pred))
    e_xi[0] = 1.0
    u = _correct(prob, u_pred, e_xi, tol, maxiter=15)
    out = []

    def orbit(pt: al.BranchPoint):
        T, DP = pt.info
        return describe(prob.model(pt.u[-1]), pt.u[:-1], DP, T, None, pt.iterations, 0.0)

    def record(pt: al.BranchPoint) -> None:
        out.append((pt.u[-1], orbit(pt), pt.tangent[-1]))
        if progress:
            progress(out[-1])

    def stop(pt: al.BranchPoint) -> str | None:
        if not (lam_bounds[0] <= pt.u[-1] <= lam_bounds[1]):
            return "parameter bound"
        return "amplitude bound" if abs(pt.u[0]) > xi_max else None

    ctl = al.StepControl(h0=ds, h_max=ds_max, h_min=1e-6, grow=1.6, fast=3, keep=1.0, slow=5, shrink=0.5)
    with bar(total=steps, desc="continuation", unit="step") as pb:
        # move away from the Hopf point: growing amplitude (τ_ξ > 0)
        br = al.continue_branch(prob.F, u, ctl, orient=e_xi, tol=tol, norm="2", max_points=steps + 1,
                                max_attempts=steps, stop=stop, on_point=record,
                                failures=(ShootingError, IntegratorError), on_attempt=pb.update)
    stopped = "step limit" if br.stopped in ("step limit", "point limit") else br.stopped
    folds = []
    for f in br.folds:
        if f.point is None:  # no trial point converged: the point before the fold
            prev = br.points[f.index - 1]
            o = describe(prob.model(prev.u[-1]), prev.u[:-1], None, 0.0, None, 0, 0.0)
        else:
            o = orbit(al.BranchPoint(f.point.u, f.point.tangent, f.point.info, 0))
            prev = f.point
        folds.append((prev.u[-1], o, o))
    return out, folds, stopped


def continue_in_k(model: SpringBlockModel, k_lo: float, k_hi: float, **kw) -> Branch:
    """Fig. 6: cycles vs stiffness at fixed V, from the Hopf point in [k_lo, k_hi]."""
    k_h = hopf_stiffness(model, k_lo, k_hi)
    make = lambda lam: model.with_(k=lam * k_h)  # noqa: E731
    # side: supercritical cycles exist for k < k_c; try that first, else the other side
    pts = folds = stop = None
    for direction in (-1.0, 1.0):
        try:
            pts, folds, stop = continue_branch(make, 1.0, direction=direction, **kw)
            break
        except (ShootingError, IntegratorError):
            continue
    if pts is None or folds is None:
        raise ShootingError("no cycle branch could be started at the Hopf point")
    return _branch("k", {"V": model.V}, k_h, [(lam * k_h, o, t) for lam, o, t in pts],
                   [(lam * k_h, a, b) for lam, a, b in folds], stop)


def continue_in_logV(model: SpringBlockModel, V_lo: float, V_hi: float, **kw) -> Branch:
    """Fig. 11: cycles vs log₁₀ V at fixed k (fixed κ), from the Hopf point in [V_lo, V_hi]."""
    lv_h = hopf_parameter(lambda lv: model.with_(V=10 ** lv), np.log10(V_lo), np.log10(V_hi), xtol=1e-14,
                          rtol=1e-14)
    make = lambda lam: model.with_(V=10 ** lam)  # noqa: E731
    pts = None
    for direction in (-1.0, 1.0):
        try:
            pts, folds, stop = continue_branch(make, lv_h, direction=direction, **kw)
            break
        except (ShootingError, IntegratorError):
            continue
    if pts is None:
        raise ShootingError("no cycle branch could be started at the Hopf point")
    return _branch("logV", {"k": model.k, "kappa": model.kappa}, 10 ** lv_h,
                   [(10 ** lam, o, t) for lam, o, t in pts], [(10 ** lam, a, b) for lam, a, b in folds], stop)


def _branch(kind, fixed, hopf, pts, folds, stop) -> Branch:
    bp = tuple(BranchPoint(p, o, t) for p, o, t in pts)
    # branch's own Hopf estimate: half peak-to-peak² is linear in the parameter near the Hopf point
    hp = np.array([0.5 * (b.orbit.x_max - b.orbit.x_min) for b in bp[:3]])
    par = np.array([b.parameter for b in bp[:3]])
    if kind == "logV":
        par = np.log10(par)
    c = np.polyfit(hp ** 2, par, 1) if len(bp) >= 2 else [0, par[0]]
    h_ext = float(c[-1]) if kind == "k" else float(10 ** c[-1])
    name = "k" if kind == "k" else "V"
    fl = tuple(FoldOfCycles(name, lam, 0.5 * (a.amplitude + b.amplitude), p_c=hopf, fixed=dict(fixed),
                            half_peak_to_peak=0.25 * (a.x_max - a.x_min + b.x_max - b.x_min), z=a.z)
               for lam, a, b in folds)
    return Branch(kind, fixed, hopf, h_ext, bp, fl, stop)


def plot_branch(branch: Branch, path, title: str = ""):
    """Fig. 6/11-style panels: spring force, slip rate, slip and stress drop (max/min) along the branch."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from landau.support.io import atomic_savefig

    par = np.array([b.parameter for b in branch.points])
    o = [b.orbit for b in branch.points]
    st = np.array([b.orbit.stable for b in branch.points])
    k = np.array([x.k for x in o])
    xmax, xmin = np.array([x.x_max for x in o]), np.array([x.x_min for x in o])
    vmax, vmin = np.array([x.v_max for x in o]), np.array([x.v_min for x in o])
    panels = [("spring-force excess -k X [N]", -k * xmin, -k * xmax), ("slip rate v [m/s]", vmax, vmin),
              ("slip x - x0 [m]", xmax, xmin), ("stress drop k(Xmax - Xmin) [N]", k * (xmax - xmin), None)]
    fig, axes = plt.subplots(2, 2, figsize=(9, 7))
    for ax, (lab, hi, lo) in zip(axes.ravel(), panels, strict=True):
        for arr in (hi, lo):
            if arr is None:
                continue
            ax.plot(np.where(st, par, np.nan), np.where(st, arr, np.nan), "k-")
            ax.plot(np.where(~st, par, np.nan), np.where(~st, arr, np.nan), "k:")
        ax.axvline(branch.hopf_equilibrium, color="r", lw=0.6)
        for f in branch.folds:
            ax.axvline(f.p_fold, color="b", lw=0.6, ls="--")
        ax.set_ylabel(lab, fontsize=8)
        ax.set_xlabel("k [N/m]" if branch.kind == "k" else "V [m/s]", fontsize=8)
        if branch.kind == "logV":
            ax.set_xscale("log")
        if "slip rate" in lab:
            ax.set_yscale("log")
    fig.suptitle(title or f"limit cycles, continuation in {branch.kind} (solid stable, dotted unstable; "
                 "red: Hopf, blue dashed: fold)", fontsize=9)
    fig.tight_layout()
    out = atomic_savefig(fig, path)
    plt.close(fig)
    return out


def branch_curvature(model: SpringBlockModel, k_hopf: float, xis=(0.02, 0.04), rtol: float = 1e-11) -> float:
    """c₂ in k(ξ) = k_H + c₂ξ² + c₄ξ⁴ along the cycle branch at fixed V (ξ = max slip / ℓ):
    c₂ < 0 ⇔ cycles for k < k_H (supercritical), c₂ > 0 ⇔ subcritical.  The fold of cycles
    approaches the Hopf point where c₂ = 0 (its amplitude² ∝ −c₂/c₄)."""
    make = lambda lam: model.with_(k=lam * k_hopf)  # noqa: E731
    prob = _Problem(make, rtol)
    lams = []
    for xi in xis:
        m0 = prob.model(1.0)
        z0 = section_point(m0, xi * m0.ell)
        u_pred = np.r_[z0, 1.0]
        e_xi = np.zeros(len(u_pred))
        e_xi[0] = 1.0
        u = _correct(prob, u_pred, e_xi, 1e-11, maxiter=15)
        lams.append(u[-1] - 1.0)
    x2 = np.array(xis) ** 2
    # two amplitudes: eliminate the ξ⁴ term (Richardson)
    A = np.column_stack([x2, x2 ** 2])
    # [ξ² ξ⁴] (c₂, c₄) = k(ξ)/k_H − 1 at the two amplitudes
    c2, c4 = np.linalg.solve(A, np.array(lams))
    return float(c2 * k_hopf)


def codim2_velocity(make_model: Callable[[float], SpringBlockModel], hopf_k: Callable[[float], float],
                    V_lo: float, V_hi: float, tol: float = 1e-4, maxiter: int = 30) -> GeneralisedHopfPoint:
    """The velocity where the branch curvature c₂ (fold-of-cycles ↔ Hopf) changes sign, by the
    Illinois (regula falsi) method in log V on c₂(V) computed from periodic orbits alone
    (Hopf stiffness from the steady state's eigenvalues, cycles by shooting).

    Returns a :class:`~landau.analyses.codim2.GeneralisedHopfPoint` with p₁ = k (the Hopf stiffness there),
    p₂ = V, the Illinois ``iterations`` and the ``history`` of (V, c₂); ω is not computed (NaN)."""
    law = make_model(V_lo).law.name

    def point(V, k, it, hist):
        return GeneralisedHopfPoint(law, SPRING_BLOCK_PARAMETERS, float(k), float(V), math.nan, iterations=it,
                                    history=tuple(hist))

    def c2(V):
        m = make_model(V)
        kh = hopf_k(V)
        return branch_curvature(m.with_(k=kh), kh), kh

    a, b = np.log10(V_lo), np.log10(V_hi)
    fa, _ = c2(V_lo)
    fb, _ = c2(V_hi)
    hist = [(V_lo, fa), (V_hi, fb)]
    if np.sign(fa) == np.sign(fb):
        raise ShootingError(f"no sign change of the branch curvature on [{V_lo:g}, {V_hi:g}] m/s")
    side = 0
    kh = np.nan
    for it in range(1, maxiter + 1):
        c = (a * fb - b * fa) / (fb - fa)
        fc, kh = c2(10 ** c)
        hist.append((10 ** c, fc))
        if abs(b - a) < tol / np.log(10) or fc == 0:
            return point(10 ** c, kh, it, hist)
        if np.sign(fc) == np.sign(fb):
            b, fb = c, fc
            if side == -1:
                fa /= 2
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb /= 2
            side = 1
        if abs(b - a) < tol / np.log(10):
            return point(10 ** c, kh, it, hist)
    return point(10 ** c, kh, maxiter, hist)


def _fold_residual(make_V, lv: float, z: np.ndarray, rtol: float):
    m = make_V(10 ** lv)
    Pz, DP, T, _ = return_map(m, z, rtol=rtol)
    return np.r_[Pz - z, np.linalg.det(DP - np.eye(len(z)))], m


def fold_point(make_V: Callable[[float], SpringBlockModel], V_guess: float, z_guess, *, rtol: float = 1e-11,
               tol: float = 1e-10, maxiter: int = 12, parameter: str = "V") -> FoldOfCycles:
    """Solve P(z; V) = z, det(DP − I) = 0 for (z, log V) at fixed k (Newton, finite-difference Jacobian).

    ``make_V`` maps the positive unknown (V by default; its name is ``parameter``) to a model; the fold
    is a :class:`~landau.analyses.codim2.FoldOfCycles` with the model's V, k and κ (those not the unknown) in
    ``fixed`` and the slip amplitude in m."""
    u = np.r_[np.asarray(z_guess, dtype=float), np.log10(V_guess)]
    for _ in range(maxiter):
        r, m = _fold_residual(make_V, u[-1], u[:-1], rtol)
        J = np.empty((len(u), len(u)))
        for j in range(len(u)):
            h = 1e-6 * max(abs(u[j]), 1e-2)
            up, um = u.copy(), u.copy()
            up[j] += h
            um[j] -= h
            J[:, j] = (_fold_residual(make_V, up[-1], up[:-1], rtol)[0]
                       - _fold_residual(make_V, um[-1], um[:-1], rtol)[0]) / (2 * h)
        # D[P(z) − z; det(DP − I)] du = −[P(z) − z; det(DP − I)]  (Newton, central-difference Jacobian)
        du = np.linalg.solve(J, -r)
        u = u + du
        if np.linalg.norm(du) < tol * max(1.0, float(np.linalg.norm(u))):
            m = make_V(10 ** u[-1])
            fixed = {n: float(v) for n, v in (("V", m.V), ("k", m.k), ("kappa", m.kappa)) if n != parameter}
            return FoldOfCycles(parameter, float(10 ** u[-1]), float(u[0] * m.ell), fixed=fixed, z=u[:-1].copy())
    raise ShootingError(f"fold-of-cycles Newton did not converge (last |du| = {np.linalg.norm(du):.3g})")


def fold_curve(base: SpringBlockModel, V_fold: float, z_fold, kappas, **kw) -> list[FoldOfCycles]:
    """Two-parameter continuation of the fold of cycles in (V, κ) (Fig. 12): natural continuation in
    κ (list ``kappas`` ordered away from the starting κ), each point by :func:`fold_point` seeded by the
    previous one (secant extrapolation in log V and z).  Stops when Newton fails — near the
    codimension-two point the fold's amplitude → 0 and the condition det(DP − I) = 0 degenerates."""
    pts: list[FoldOfCycles] = []
    V, z = V_fold, np.asarray(z_fold, dtype=float)
    sigma, L = base.params["sigma"], base.params["L"]
    for kap in kappas:
        k = kap * sigma / L
        make_V = lambda VV, k=k: base.with_(V=VV, k=k)  # noqa: E731
        if len(pts) >= 2:
            a, b = pts[-2], pts[-1]
            assert a.z is not None and b.z is not None  # points of a continued fold curve carry their state
            w = (np.log(kap) - np.log(b.value("kappa"))) / (np.log(b.value("kappa")) - np.log(a.value("kappa")))
            V = 10 ** (np.log10(b.p_fold) + w * (np.log10(b.p_fold) - np.log10(a.p_fold)))
            z = b.z + w * (b.z - a.z)
        try:
            fp = fold_point(make_V, V, z, **kw)
        except (ShootingError, IntegratorError, np.linalg.LinAlgError):
            break
        pts.append(fp)
        V, z = fp.p_fold, fp.z
    return pts
