"""Pseudo-arclength continuation: one predictor–corrector engine for every branch the toolkit follows.

A branch is the zero set of G: ℝⁿ⁺¹ → ℝⁿ, u = (x, λ), given by a problem as a function
``F(u) -> (G(u), DG(u), info)`` with DG the n × (n + 1) Jacobian (``info``: whatever the problem
wants back with each accepted point).  It serves

* equilibria of E·ẏ = f(y; p) in p (:func:`landau.analyses.continuation.equilibrium_branch`: G = f, DG = [J | f_p]);
* Hopf curves in two parameters (:func:`landau.analyses.continuation.hopf_curve`: the minimally augmented
  system of Govaerts 2000);
* periodic orbits of the spring–block in k or log V (:mod:`landau.verify.springblock.continuation`:
  G = P(z; λ) − z on a Poincaré section).

Keller's pseudo-arclength method (Keller 1977; Allgower & Georg 2003, ch. 2): from a point u with
unit tangent τ (DG τ = 0), predict u + h τ, correct by Newton's method on
[G(u); τ·(u − u_pred)] = 0 (:func:`newton_corrector`), take the new tangent from the bordered system
(:func:`tangent`), adapt h to Newton's effort (:class:`StepControl`).  A fold (turning point in the
parameter component ``fold_index``) is where that component of τ changes sign; it is refined by
bisection in the arclength (:func:`refine_fold`) or by the problem's own method.

References
----------
Keller, H. B. (1977). Numerical solution of bifurcation and nonlinear eigenvalue problems. In
Applications of Bifurcation Theory, Academic Press, 359–384.
Allgower, E. L., Georg, K. (2003). Introduction to Numerical Continuation Methods. SIAM.
Govaerts, W. (2000). Numerical Methods for Bifurcations of Dynamical Equilibria. SIAM.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np

#: a problem: u ↦ (G(u), DG(u) of shape (n, n + 1), info)
Residual = Callable[[np.ndarray], "tuple[np.ndarray, np.ndarray, Any]"]


class CorrectorError(ArithmeticError):
    """Newton's method did not converge from the predicted point (the caller shortens the step)."""


def _small(du: np.ndarray, u: np.ndarray, tol: float, norm: str) -> bool:
    """The Newton update is negligible: max|du| ≤ tol (1 + max|u|) or ‖du‖₂ ≤ tol max(1, ‖u‖₂)."""
    if norm == "max":
        return bool(np.max(np.abs(du)) <= tol * (1 + np.max(np.abs(u))))
    return bool(np.linalg.norm(du) <= tol * max(1.0, float(np.linalg.norm(u))))


def newton_corrector(F: Residual, u_pred: np.ndarray, tau: np.ndarray, tol: float, *, maxit: int = 8,
                     norm: str = "max") -> tuple[np.ndarray, int]:
    """Newton's method on the pseudo-arclength system [G(u); τ·(u − u_pred)] = 0.

    Parameters
    ----------
    F : callable
        u ↦ (G(u), DG(u), info).
    u_pred : ndarray
        The predicted point (start of the iteration).
    tau : ndarray
        The row of the arclength condition (the tangent at the last point; a unit vector e_i fixes
        component i at its predicted value).
    tol : float
        Relative size of the last update at convergence (see ``norm``).
    maxit : int
        Most iterations.
    norm : {"max", "2"}
        max|du| ≤ tol (1 + max|u|), or ‖du‖₂ ≤ tol max(1, ‖u‖₂).

    Returns
    -------
    (u, iterations)

    Raises
    ------
    CorrectorError
        No convergence in ``maxit`` iterations, a non-finite residual or a singular bordered matrix.
    """
    u = np.array(u_pred, dtype=float)
    for it in range(1, maxit + 1):
        G, DG, _ = F(u)
        if not np.all(np.isfinite(G)):
            raise CorrectorError(f"non-finite residual at iteration {it}")
        # [DG; τᵀ] du = −[G; τ·(u − u_pred)]  (the bordered Jacobian of the pseudo-arclength system)
        A = np.vstack([DG, tau])
        r = np.append(G, tau @ (u - u_pred))
        try:
            du = np.linalg.solve(A, -r)
        except np.linalg.LinAlgError:
            raise CorrectorError(f"singular bordered Jacobian at iteration {it}") from None
        u = u + du
        if _small(du, u, tol, norm):
            return u, it
    raise CorrectorError(f"no convergence in {maxit} iterations (last |du| = {np.max(np.abs(du)):.3g})")


def tangent(DG: np.ndarray, prev: np.ndarray | None = None) -> np.ndarray:
    """The unit tangent τ of the branch (DG τ = 0), oriented along ``prev`` when given.

    With a previous tangent the bordered system below is solved (it stays regular through folds);
    without one, or where it is singular, τ is the right singular vector of DG's smallest singular
    value.
    """
    n = DG.shape[0]
    t = None
    if prev is not None:
        # [DG; τ_prevᵀ] τ = e_{n+1}: the null vector of DG normalised by τ_prev·τ = 1
        A = np.vstack([DG, prev])
        rhs = np.zeros(n + 1)
        rhs[n] = 1.0
        try:
            t = np.linalg.solve(A, rhs)
        except np.linalg.LinAlgError:
            t = None
        if t is not None and not np.all(np.isfinite(t)):
            t = None
    if t is None:
        t = np.linalg.svd(DG)[2][-1]
    t = t / np.linalg.norm(t)
    if prev is not None and t @ prev < 0:
        t = -t
    return t


@dataclass(frozen=True)
class StepControl:
    """Pseudo-arclength step h: halved after a failed correction, scaled after a success by
    ``grow`` (Newton needed ≤ ``fast`` iterations), ``keep`` (≤ ``slow``) or ``shrink`` (more),
    never above ``h_max``; the continuation stops when a halving goes below ``h_min``."""

    h0: float
    h_max: float
    h_min: float
    grow: float = 1.3
    fast: int = 3
    keep: float = 1.0
    slow: int = 5
    shrink: float = 1.0

    def after(self, h: float, iterations: int) -> float:
        """The step after a success that took ``iterations`` Newton steps."""
        if iterations <= self.fast:
            return min(self.grow * h, self.h_max)
        return min(h * (self.keep if iterations <= self.slow else self.shrink), self.h_max)


@dataclass(frozen=True)
class BranchPoint:
    """One point of a continued branch: u = (x, λ), its unit tangent, the problem's info, Newton's iterations."""

    u: np.ndarray
    tangent: np.ndarray
    info: Any = field(default=None, repr=False)
    iterations: int = 0


@dataclass(frozen=True)
class Fold:
    """A fold found between points ``index − 1`` and ``index`` of a branch, refined to ``point`` (or None)."""

    index: int
    point: BranchPoint | None = None


@dataclass(frozen=True)
class Continued:
    """A continued branch: its points (the start first), folds and why it stopped."""

    points: tuple[BranchPoint, ...]
    folds: tuple[Fold, ...] = ()
    stopped: str = ""


def refine_fold(F: Residual, start: BranchPoint, h: float, tol: float, *, fold_index: int = -1, iters: int = 12,
                maxit: int = 8, norm: str = "max",
                failures: tuple[type[BaseException], ...] = ()) -> BranchPoint | None:
    """Bisection in the arclength s ∈ (0, h) from ``start`` for the zero of the tangent's
    ``fold_index`` component (each trial point corrected onto the branch); None if no trial converged."""
    u, tau = start.u, start.tangent
    lo, hi = 0.0, h
    best = None
    caught: tuple[type[BaseException], ...] = (CorrectorError, *failures)
    for _ in range(iters):
        s = 0.5 * (lo + hi)
        try:
            us, _ = newton_corrector(F, u + s * tau, tau, tol, maxit=maxit, norm=norm)
            _, DG, info = F(us)
        except caught:
            break
        ts = tangent(DG, tau)
        best = BranchPoint(us, ts, info)
        if np.sign(ts[fold_index]) == np.sign(tau[fold_index]):
            lo = s
        else:
            hi = s
    return best


def continue_branch(F: Residual, u0: np.ndarray, step: StepControl, *, tangent0: np.ndarray | None = None,
                    orient: np.ndarray | None = None, tol: float = 1e-10, norm: str = "max", maxit: int = 8,
                    max_points: int = 1000, max_attempts: int | None = None, fold_index: int | None = -1,
                    refine: bool = True, accept: Callable[[np.ndarray], bool] | None = None,
                    stop: Callable[[BranchPoint], str | None] | None = None,
                    on_point: Callable[[BranchPoint], None] | None = None,
                    on_attempt: Callable[[], Any] | None = None,
                    failures: tuple[type[BaseException], ...] = ()) -> Continued:
    """Follow the branch G(u) = 0 from the point ``u0`` on it.

    Parameters
    ----------
    F : callable
        u ↦ (G(u), DG(u), info), DG of shape (n, n + 1).
    u0 : ndarray
        A point of the branch (already corrected).
    step : StepControl
    tangent0 : ndarray, optional
        The starting tangent (default: the null vector of DG(u0), oriented by ``orient``).
    orient : ndarray, optional
        The starting tangent is turned so that τ·orient > 0.
    tol, norm, maxit : see :func:`newton_corrector`.
    max_points : int
        Most points (the start included).
    max_attempts : int, optional
        Most predictor–corrector attempts, failed ones included (default: unbounded).
    fold_index : int or None
        Component whose tangent sign change marks a fold (default the last, λ); None: no fold detection.
    refine : bool
        Refine each fold by :func:`refine_fold`.
    accept : callable, optional
        u ↦ bool; a corrected point it rejects counts as a failed correction.
    stop : callable, optional
        Called with each accepted point: a reason (str) ends the continuation after that point.
    on_point : callable, optional
        Called with each point (the start included).
    on_attempt : callable, optional
        Called before each predictor–corrector attempt (e.g. a progress bar's ``update``).
    failures : tuple of exception types
        Exceptions of F that count as a failed correction (besides :class:`CorrectorError`).

    Returns
    -------
    Continued
    """
    u = np.array(u0, dtype=float)
    _, DG, info = F(u)
    t = tangent0 if tangent0 is not None else tangent(DG)
    t = t / np.linalg.norm(t)
    if orient is not None and t @ orient < 0:
        t = -t
    pts = [BranchPoint(u, t, info, 0)]
    if on_point:
        on_point(pts[0])
    folds: list[Fold] = []
    h = step.h0
    attempts = 0
    stopped = "point limit"
    caught: tuple[type[BaseException], ...] = (CorrectorError, np.linalg.LinAlgError, *failures)
    while len(pts) < max_points:
        if max_attempts is not None and attempts >= max_attempts:
            stopped = "step limit"
            break
        attempts += 1
        if on_attempt:
            on_attempt()
        last = pts[-1]
        try:
            u_new, its = newton_corrector(F, last.u + h * last.tangent, last.tangent, tol, maxit=maxit, norm=norm)
            if accept is not None and not accept(u_new):
                raise CorrectorError("corrected point rejected")
            _, DG, info = F(u_new)
            t_new = tangent(DG, last.tangent)
        except caught as exc:
            h *= 0.5
            if h < step.h_min:
                stopped = f"step size underflow ({exc})"
                break
            continue
        new = BranchPoint(u_new, t_new, info, its)
        if fold_index is not None and np.sign(t_new[fold_index]) != np.sign(last.tangent[fold_index]) \
                and last.tangent[fold_index] != 0:
            at = (refine_fold(F, last, h, tol, fold_index=fold_index, maxit=maxit, norm=norm, failures=failures)
                  if refine else None)
            folds.append(Fold(len(pts), at))
        pts.append(new)
        if on_point:
            on_point(new)
        h = step.after(h, its)
        reason = stop(new) if stop else None
        if reason:
            stopped = reason
            break
    return Continued(tuple(pts), tuple(folds), stopped)
