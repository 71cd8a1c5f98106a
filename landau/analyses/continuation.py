"""Continuation of equilibria and of Hopf points — the MatCont / BifurcationKit workflow with landau's coefficients.

* :func:`equilibrium_branch` follows the equilibria of E(p)·ẏ = f(y; p) in the Hopf parameter p by
  pseudo-arclength continuation (so it passes folds), detects every Hopf point on the branch by
  the sign of the bialternate-product test function (:func:`landau.derivation.general.hopf_test_function`,
  which sees a crossing also when another pair is already unstable), locates each at ``dps``
  digits and attaches its amplitude equation and first Lyapunov coefficient l₁
  (:class:`landau.derivation.hopf.HopfResult`); folds are reported where the branch turns back in p.
* :func:`hopf_curve` follows a Hopf point in two parameters (the system's parameter p₁ and a second
  one p₂), with l₁ along the curve, and :func:`generalised_hopf` locates the generalised-Hopf
  (Bautin) points where l₁ = 0 (:class:`landau.analyses.codim2.GeneralisedHopfPoint`), with the second
  Lyapunov coefficient l₂ = Re c₂ from :func:`landau.derivation.lyapunov.lyapunov_coefficients`.

This module defines the two problems (residual and Jacobian); the pseudo-arclength continuation
(Keller 1977) in float64 is :func:`landau.analyses.arclength.continue_branch`.  Each located point is
refined at the working precision by :func:`landau.derivation.general.refine_hopf`.

References
----------
Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, ch. 10.
Dhooge, A., Govaerts, W., Kuznetsov, Yu. A. (2003). MATCONT: a MATLAB package for numerical
bifurcation analysis of ODEs. ACM Trans. Math. Softw. 29, 141–164.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, Mapping, Sequence

import mpmath
import numpy as np
import scipy.linalg
import scipy.optimize

from landau.analyses.arclength import StepControl, continue_branch
from landau.analyses.codim2 import GeneralisedHopfPoint
from landau.derivation.general import (
    DEFAULT_DPS,
    NumericSystem,
    hopf_test_function,
    locate_crossing,
    normal_form_at,
    refine_hopf,
    second_lyapunov,
)
from landau.derivation.hopf import HopfResult
from landau.errors import InputError, NoHopfError, SingularPointError
from landau.systems.system import DynamicalSystem


@dataclass(frozen=True)
class EquilibriumBranch:
    """A continued branch of equilibria with its Hopf points and folds.

    Parameters
    ----------
    system, parameter : str
        Names of the system and of the continuation parameter.
    p : ndarray
        Parameter values along the branch (in arclength order).
    y : ndarray, shape (m, n)
        The equilibria.
    n_unstable : ndarray of int
        Number of eigenvalues with positive real part at each point.
    hopf : tuple of HopfResult
        Every Hopf point on the branch, located at the working precision, with Λ and l₁.
    folds : tuple of float
        Parameter values of the folds (where the branch turns back in p), to the step accuracy
        refined by a quadratic fit.
    """

    system: str
    parameter: str
    p: np.ndarray
    y: np.ndarray
    n_unstable: np.ndarray
    hopf: tuple[HopfResult, ...] = ()
    folds: tuple[float, ...] = ()

    def as_dict(self) -> dict[str, Any]:
        return {"system": self.system, "parameter": self.parameter, "p": self.p.tolist(), "y": self.y.tolist(),
                "n_unstable": self.n_unstable.tolist(), "hopf": [h.as_dict() for h in self.hopf],
                "folds": list(self.folds)}

    def __repr__(self) -> str:
        hs = ", ".join(f"{h.p_c:.8g} (l1 = {h.l1:.4g})" for h in self.hopf) or "none"
        fs = ", ".join(f"{f:.6g}" for f in self.folds) or "none"
        return (f"EquilibriumBranch({self.system}: {len(self.p)} points, {self.parameter} in "
                f"[{self.p.min():.6g}, {self.p.max():.6g}]; Hopf at {hs}; folds at {fs})")


def _n_unstable(lam: np.ndarray) -> int:
    return int(np.sum(lam.real > 0))


def _start_tangent(J: np.ndarray, fp: np.ndarray) -> np.ndarray:
    """The starting unit tangent of the equilibrium branch, towards increasing p."""
    try:
        # J dy/dp = −f_p
        dy = np.linalg.solve(J, -fp)
    except np.linalg.LinAlgError:
        raise SingularPointError("continuation cannot start at a singular point") from None
    t = np.append(dy, 1.0)
    return t / np.linalg.norm(t)


def equilibrium_branch(system: DynamicalSystem, params: Mapping[str, float] | None, p_range: tuple[float, float], *,
                       start: float | None = None, equilibrium_guess: Sequence[float] | None = None,
                       step: float | None = None, max_step: float | None = None, max_points: int = 5000,
                       direction: int = 1, dps: int = DEFAULT_DPS, jets: str = "taylor",
                       locate_hopf: bool = True) -> EquilibriumBranch:
    """Continue equilibria in the system's parameter and locate every Hopf point (with l₁) on the branch.

    Parameters
    ----------
    system : DynamicalSystem
    params : mapping or None
        Values of the other parameters, by name.
    p_range : (float, float)
        The continuation stops when the parameter leaves this interval.
    start : float, optional
        Starting parameter value (default: the end of ``p_range`` the direction starts from).
    equilibrium_guess : sequence of float, optional
        Guess of the equilibrium at ``start`` (default: ``system.equilibrium``).
    step, max_step : float, optional
        Initial and largest pseudo-arclength step (default 1 % and 5 % of the range).
    max_points : int
        Safety bound on the number of points.
    direction : {1, −1, 0}
        Start towards increasing (1) or decreasing (−1) parameter; 0 continues both ways from
        ``start`` and joins the two halves.
    dps : int
        Working precision of the located Hopf points.
    jets : {"taylor", "symbolic"}
        Derivative route of the normal forms.
    locate_hopf : bool
        Locate and analyse the Hopf points (else only the branch and its stability).

    Returns
    -------
    EquilibriumBranch
    """
    lo, hi = sorted(map(float, p_range))
    if not (math.isfinite(lo) and math.isfinite(hi)) or lo == hi:
        raise InputError(f"p_range must be two different finite numbers, got {p_range!r}")
    if direction not in (1, -1, 0):
        raise InputError("direction must be 1, -1 or 0 (both ways)")
    if direction == 0:
        if start is None:
            raise InputError("direction=0 (both ways) needs a start value")
        kw: dict[str, Any] = dict(start=start, equilibrium_guess=equilibrium_guess, step=step, max_step=max_step,
                  max_points=max_points, dps=dps, jets=jets, locate_hopf=locate_hopf)
        down = equilibrium_branch(system, params, p_range, direction=-1, **kw)
        up = equilibrium_branch(system, params, p_range, direction=1, **kw)
        return EquilibriumBranch(system=up.system, parameter=up.parameter, p=np.concatenate([down.p[::-1], up.p[1:]]),
                                 y=np.concatenate([down.y[::-1], up.y[1:]]),
                                 n_unstable=np.concatenate([down.n_unstable[::-1], up.n_unstable[1:]]),
                                 hopf=tuple(down.hopf[::-1]) + up.hopf, folds=tuple(down.folds[::-1]) + up.folds)
    num = NumericSystem(system, params or {}, equilibrium_guess)
    n = num.n
    width = hi - lo
    p0 = (lo if direction == 1 else hi) if start is None else float(start)
    y0 = num.equilibrium_float(p0)
    _, J, fp = num.first(y0, p0, True)

    def F(x):  # G = f(y; p), DG = [J | f_p]
        f, Jx, fpx = num.first(x[:n], x[n], True)
        return f, np.column_stack([Jx, fpx]), None

    h = step or 0.01 * width
    ctl = StepControl(h0=h, h_max=max_step or 0.05 * width, h_min=1e-9 * width)
    br = continue_branch(F, np.append(y0, p0), ctl, tangent0=direction * _start_tangent(J, fp), tol=1e-11,
                         max_points=max_points, refine=False,
                         stop=lambda pt: None if lo <= pt.u[n] <= hi else "parameter range")
    if br.stopped.startswith("step size underflow"):
        raise SingularPointError(f"{system.name}: continuation stalled at {num.p.name} = {br.points[-1].u[n]:.8g}")
    P = np.array([pt.u[n] for pt in br.points])
    Y = np.array([pt.u[:n] for pt in br.points])
    tps = [pt.tangent[n] for pt in br.points]
    lams = [num.eigenvalues(y, p) for y, p in zip(Y, P, strict=True)]
    nus = [_n_unstable(lam) for lam in lams]
    tfs = [hopf_test_function(lam) for lam in lams]
    folds = [_refine_fold(num, Y, P, f.index) for f in br.folds]
    hopfs: list[HopfResult] = []
    if locate_hopf:
        cache: dict = {}
        for k in range(1, len(P)):
            if tfs[k - 1] * tfs[k] >= 0 or not (lo <= P[k] <= hi or lo <= P[k - 1] <= hi):
                continue
            if tps[k - 1] * tps[k] < 0:
                continue  # a fold in between: the branch is not a graph over p there
            pa, pb = sorted((P[k - 1], P[k]))
            ya = Y[k - 1] if P[k - 1] == pa else Y[k]
            hit = locate_crossing(num, pa, pb, ya)
            if hit is None:
                continue  # neutral saddle
            pc0, yc0, lamc = hit
            with mpmath.workdps(dps):
                pc, wc, yc = refine_hopf(num, pc0, abs(lamc.imag), yc0)
                hopfs.append(normal_form_at(num, pc, wc, yc, jets=jets, jets_cache=cache, params=params))
    return EquilibriumBranch(system=system.name, parameter=num.p.name, p=P, y=Y, n_unstable=np.array(nus),
                             hopf=tuple(hopfs), folds=tuple(folds))


def _refine_fold(num: NumericSystem, Y: np.ndarray, P: np.ndarray, index: int) -> float:
    """The extremal parameter of the branch at the fold detected between points ``index − 1`` and
    ``index`` (the tangent's p component changed sign there).

    The extremum may lie on either side of the branch point nearest to it: the bracket is the
    two neighbours of the most extreme of points ``index − 2 … index + 1`` (a maximum where p rises
    into the window, else a minimum).  Near a fold p is a smooth function of the state component
    that changes most across the bracket; p(s) comes from Newton's method with that component
    fixed and its extremum from Brent's method (p at a quadratic extremum is accurate to round-off).
    """
    n = num.n
    window = np.arange(max(index - 2, 0), min(index + 1, len(P) - 1) + 1)
    pw = P[window]
    is_max = (pw.max() - max(pw[0], pw[-1])) >= (min(pw[0], pw[-1]) - pw.min())
    m = int(window[np.argmax(pw) if is_max else np.argmin(pw)])
    ia, ib = max(m - 1, 0), min(m + 1, len(P) - 1)
    ya, yb = np.asarray(Y[ia], float), np.asarray(Y[ib], float)
    k = int(np.argmax(np.abs(yb - ya)))
    guess = {"y": ya.copy(), "p": float(P[ia])}

    def p_of(s):
        y, p = guess["y"].copy(), guess["p"]
        y[k] = s
        for _ in range(30):
            F, J, fp = num.first(y, p, True)
            A = np.column_stack([np.delete(J, k, axis=1), fp])
            # [J without column k | f_p] (δy_{≠k}, δp) = −f  (y_k fixed; least squares, square when regular)
            d = np.linalg.lstsq(A, -F, rcond=None)[0]
            y[np.arange(n) != k] += d[:-1]
            p += d[-1]
            if np.max(np.abs(d)) <= 1e-14 * (1 + np.max(np.abs(y)) + abs(p)):
                break
        guess["y"], guess["p"] = y, p
        return p

    sign = 1.0 if is_max else -1.0
    lo, hi = sorted((float(ya[k]), float(yb[k])))
    res = scipy.optimize.minimize_scalar(lambda s: -sign * p_of(s), bounds=(lo, hi), method="bounded",
                                         options={"xatol": 1e-10 * (1 + abs(hi))})
    pf = float(p_of(res.x))
    # verified before it is returned: at a fold of equilibria ∂f/∂y is singular (the derivative of
    # the branch's p vanishes); the extremum located to 1e-10 leaves σ_min(J) ~ 1e-10 |[J | f_p]|
    _, J, fp = num.first(guess["y"], pf, True)
    smin = np.linalg.svd(J, compute_uv=False)[-1]
    scale = np.linalg.norm(np.column_stack([J, fp]), 2)
    if not (smin <= FOLD_TOL * scale):
        raise SingularPointError(f"{num.sys.name}: the fold located at {num.p.name} = {pf:.10g} fails its check: "
                                 f"the Jacobian is regular there (smallest singular value {smin / scale:.2g} of "
                                 "|[J | f_p]|)")
    return pf


#: a located fold must make ∂f/∂y singular to this size relative to |[∂f/∂y | ∂f/∂p]| (its smallest singular value)
FOLD_TOL = 1e-6


# --- two-parameter continuation of a Hopf point -------------------------------------------------------

@dataclass(frozen=True)
class HopfCurve:
    """A curve of Hopf points in (p₁, p₂) with l₁ along it and its generalised-Hopf points."""

    system: str
    parameters: tuple[str, str]
    p1: np.ndarray
    p2: np.ndarray
    omega: np.ndarray
    l1: np.ndarray
    generalised_hopf: tuple[GeneralisedHopfPoint, ...] = ()

    def as_dict(self) -> dict[str, Any]:
        return {"system": self.system, "parameters": list(self.parameters), "p1": self.p1.tolist(),
                "p2": self.p2.tolist(), "omega": self.omega.tolist(), "l1": self.l1.tolist(),
                "generalised_hopf": [g.as_dict() for g in self.generalised_hopf]}

    def __repr__(self) -> str:
        gh = ", ".join(f"({g.p1:.8g}, {g.p2:.8g})" for g in self.generalised_hopf) or "none"
        return (f"HopfCurve({self.system}: {len(self.p1)} points, {self.parameters[1]} in "
                f"[{self.p2.min():.6g}, {self.p2.max():.6g}]; GH at {gh})")


class _HopfTracker:
    """Locates the Hopf point at a given p₂ by Newton from the last one found (natural continuation)."""

    def __init__(self, system: DynamicalSystem, params: Mapping[str, float], second: str, start: HopfResult,
                 dps: int, jets: str):
        if second not in {s.name for s in system.parameters}:
            raise InputError(f"{system.name}: {second!r} is not a parameter of the system "
                             f"(known: {', '.join(s.name for s in system.parameters)})")
        self.params = dict(params)
        self.second = second
        self.num = NumericSystem(system, self.params, start.equilibrium)
        self.sym2 = next(s for s in system.parameters if s.name == second)
        self.last = (start.p_c, start.omega_c, start.equilibrium)
        self.dps = dps
        self.jets = jets
        self.cache: dict = {}

    def set_p2(self, v: float) -> None:
        self.num.params[self.sym2] = float(v)
        self.num._pv = list(self.num.params.values())
        self.params[self.second] = float(v)

    def at(self, p2: float, dps: int | None = None) -> HopfResult:
        self.set_p2(p2)
        p1, om, y = self.last
        with mpmath.workdps(dps or self.dps):
            pc, wc, yc = refine_hopf(self.num, p1, om, y)
            res = normal_form_at(self.num, pc, wc, yc, jets=self.jets, jets_cache=self.cache, params=self.params)
        self.last = (res.p_c, res.omega_c, res.equilibrium)
        return res


def _hopf_residual(num: NumericSystem, sym2, X: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """[f(y; p₁, p₂), Re g, Im g] with g from the bordered system [[iωE − J, b], [cᴴ, 0]] (v, g) = (0, 1).

    g = 0 exactly at a Hopf point (Govaerts 2000, minimally augmented system); well conditioned
    when b and c approximate the left and right critical eigenvectors.
    """
    n = num.n
    y, p1, p2, om = X[:n], X[n], X[n + 1], X[n + 2]
    num.params[sym2] = float(p2)
    num._pv = list(num.params.values())
    f, J, _ = num.first(y, p1, True)
    M = np.zeros((n + 1, n + 1), complex)
    M[:n, :n] = 1j * om * num.E_float(p1) - J
    M[:n, n] = b
    M[n, :n] = c.conj()
    rhs = np.zeros(n + 1, complex)
    rhs[n] = 1.0
    # [[iωE − J, b], [cᴴ, 0]] (v, g) = (0, 1)
    g = np.linalg.solve(M, rhs)[n]
    return np.concatenate([f, [g.real, g.imag]])


def _hopf_borders(num: NumericSystem, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    n = num.n
    _, J, _ = num.first(X[:n], X[n], True)
    lam, vl, vr = scipy.linalg.eig(J, num.E_float(X[n]), left=True, right=True)
    i = int(np.argmin(np.abs(lam - 1j * X[n + 2])))
    return vl[:, i] / np.linalg.norm(vl[:, i]), vr[:, i] / np.linalg.norm(vr[:, i])


def _fd_jacobian(G, X: np.ndarray) -> np.ndarray:
    cols = []
    for i in range(len(X)):
        h = 1e-7 * (1 + abs(X[i]))
        e = np.zeros_like(X)
        e[i] = h
        cols.append((G(X + e) - G(X - e)) / (2 * h))
    return np.column_stack(cols)


def _trace_hopf_curve(num: NumericSystem, sym2, X0: np.ndarray, lo: float, hi: float, hmax: float,
                      max_points: int) -> list[np.ndarray]:
    """Pseudo-arclength continuation of the Hopf curve in (y, p₁, p₂, ω) both ways from X0 (float64)."""
    n = num.n
    out_both = []
    for direction in (1, -1):
        borders = list(_hopf_borders(num, X0))

        def F(Z, borders=borders):  # the minimally augmented system, its Jacobian by central differences
            G = lambda W: _hopf_residual(num, sym2, W, *borders)  # noqa: E731
            return G(Z), _fd_jacobian(G, Z), None

        def new_borders(pt, borders=borders):  # b, c follow the critical eigenvectors along the curve
            borders[:] = _hopf_borders(num, pt.u)

        orient = np.zeros(len(X0))
        orient[n + 1] = direction
        # the corrector counts iterations from 1: "≤ 4" is the three-correction rule of a 0-based count
        ctl = StepControl(h0=hmax / 4, h_max=hmax, h_min=1e-8 * hmax, fast=4)
        br = continue_branch(F, X0.copy(), ctl, orient=orient, tol=1e-10, max_points=max_points + 1,
                             fold_index=None, accept=lambda Z: Z[n + 2] > 0, on_point=new_borders,
                             stop=lambda pt: None if lo <= pt.u[n + 1] <= hi else "parameter range")
        out_both.append([pt.u for pt in br.points[1:]])
    return out_both[1][::-1] + [X0] + out_both[0]


def hopf_curve(system: DynamicalSystem, params: Mapping[str, float], second: str, p2_range: tuple[float, float],
               start: HopfResult, *, steps: int = 40, dps: int = 30, jets: str = "taylor",
               locate_gh: bool = True, l2: bool = True, max_points: int = 200) -> HopfCurve:
    """Follow a Hopf point in (p₁, p₂) while p₂ stays in ``p2_range`` and locate the generalised-Hopf points.

    The curve is traced by pseudo-arclength continuation of the minimally augmented system
    f(y; p₁, p₂) = 0, g(y, p₁, p₂, ω) = 0 (so it passes turning points in either parameter), both
    ways from ``start``; at each point the Hopf point is re-located at ``dps`` digits and l₁
    computed; a sign change of l₁ is bisected to the generalised-Hopf point.

    Parameters
    ----------
    system : DynamicalSystem
        Its ``parameter`` is p₁.
    params : mapping
        Values of the other parameters, including p₂'s value at ``start``.
    second : str
        Name of p₂.
    p2_range : (float, float)
        The continuation stops where p₂ leaves this interval.
    start : HopfResult
        A Hopf point at ``params`` (from :func:`landau.derivation.general.hopf_normal_form` or
        :func:`equilibrium_branch`).
    steps : int
        The largest arclength step is the width of ``p2_range`` divided by ``steps`` (at least 2 % of
        the norm of the starting point in (y, p₁, p₂, ω)).
    dps : int
        Working precision of the points and of l₁.
    locate_gh, l2 : bool
        Locate the points where l₁ changes sign, and compute l₂ there.
    max_points : int
        Safety bound on the number of points each way.

    Returns
    -------
    HopfCurve
        Points in arclength order.
    """
    if second not in params:
        raise InputError(f"params must give the starting value of {second!r}")
    p20 = float(params[second])
    lo, hi = sorted(map(float, p2_range))
    if not (lo <= p20 <= hi):
        raise InputError(f"the starting {second} = {p20:g} is outside {p2_range!r}")
    tracker = _HopfTracker(system, params, second, start, dps, jets)
    num = tracker.num
    X0 = np.array([*start.equilibrium, start.p_c, p20, start.omega_c], float)
    # the step bound acts on the whole arclength (states, p₁, p₂, ω): at least 2 % of |X₀|
    hmax = max((hi - lo) / steps, 0.02 * float(np.linalg.norm(X0)))
    path = _trace_hopf_curve(num, tracker.sym2, X0, lo, hi, hmax, max_points)
    n = num.n
    res: list[HopfResult] = []
    P2: list[float] = []
    for X in path:
        if not (lo <= X[n + 1] <= hi):
            continue
        tracker.last = (X[n], X[n + 2], tuple(X[:n]))
        try:
            res.append(tracker.at(X[n + 1]))
        except (SingularPointError, NoHopfError):
            continue  # a turning point in p₂: the point is not isolated at fixed p₂
        P2.append(float(X[n + 1]))
    L1 = np.array([r.l1 for r in res])
    ghs: list[GeneralisedHopfPoint] = []
    if locate_gh:
        for k in range(1, len(res)):
            if L1[k - 1] * L1[k] < 0:
                tracker.last = (res[k - 1].p_c, res[k - 1].omega_c, res[k - 1].equilibrium)
                ghs.append(_locate_gh(system, tracker, P2[k - 1], P2[k], l2))
    return HopfCurve(system=system.name, parameters=(system.parameter.name, second), p1=np.array([r.p_c for r in res]),
                     p2=np.array(P2), omega=np.array([r.omega_c for r in res]), l1=L1, generalised_hopf=tuple(ghs))


def _locate_gh(system: DynamicalSystem, tracker: _HopfTracker, a: float, b: float,
               with_l2: bool) -> GeneralisedHopfPoint:
    last = {}

    seen: dict[float, float] = {}

    def l1(v):
        r = tracker.at(v)
        last["r"] = r
        assert r.l1 is not None  # the normal form computes l1
        seen[v] = r.l1
        return r.l1

    xtol = 1e-14 * max(1.0, abs(a), abs(b))
    p2 = scipy.optimize.brentq(l1, a, b, xtol=xtol, rtol=1e-13)
    la, lb = seen.get(a, 0.0), seen.get(b, 0.0)
    r = tracker.at(p2, dps=max(tracker.dps, 40))
    # verified before it is returned: l₁ vanishes to the accuracy of the located p₂ (its slope
    # over the bracket times the bracket's tolerance, with a margin of 1e3); a Newton step of the
    # tracker that jumped to another branch of Hopf points leaves l₁ of order one there
    bound = max(1e3 * abs(lb - la) / abs(b - a) * (xtol + 1e-13 * abs(p2)), 1e-12 * max(abs(la), abs(lb)))
    if r.l1 is None or not (abs(r.l1) <= bound):
        raise NoHopfError(f"{system.name}: the point located at {tracker.second} = {p2:.10g} is not a "
                          f"generalised-Hopf point (l1 = {r.l1:.3g}, more than {bound:.2g} from 0): the Hopf point "
                          "jumped to another branch between the bracket's ends; narrow the bracket or follow the "
                          "curve with hopf_curve")
    l2v = second_lyapunov(system, tracker.params, r, max(tracker.dps, 40)) if with_l2 else None
    if l2v is not None:
        r = replace(r, l2=l2v)
    return GeneralisedHopfPoint(system=system.name, parameters=(system.parameter.name, tracker.second), p1=r.p_c,
                                p2=float(p2), omega=r.omega_c, equilibrium=r.equilibrium, l1=r.l1, l2=l2v, hopf=r)


def generalised_hopf(system: DynamicalSystem, params: Mapping[str, float], second: str,
                     p2_bracket: tuple[float, float], p1_bracket: tuple[float, float], *, dps: int = 40,
                     jets: str = "taylor", l2: bool = True, steps: int = 40) -> GeneralisedHopfPoint:
    """Locate the generalised-Hopf (Bautin) point — l₁ = 0 on the Hopf curve — with p₂ inside ``p2_bracket``.

    Parameters
    ----------
    system : DynamicalSystem
        Its ``parameter`` is p₁.
    params : mapping
        Values of the other parameters (the value of p₂ in it is ignored).
    second : str
        Name of p₂.
    p2_bracket : (float, float)
        Values of p₂ at which l₁ has opposite signs.
    p1_bracket : (float, float)
        A bracket of p₁ holding exactly one Hopf point at p₂ = p2_bracket[0].
    dps : int
        Working precision.
    jets : {"taylor", "symbolic"}
    l2 : bool
        Compute the second Lyapunov coefficient at the point by
        :func:`landau.derivation.lyapunov.lyapunov_coefficients` (Re c₂, as MatCont and BifurcationKit print it).
    steps : int
        The Hopf curve from p₂ = ``p2_bracket[0]`` is followed with arclength steps of at most the
        bracket's width over ``steps`` (:func:`hopf_curve`).

    Returns
    -------
    GeneralisedHopfPoint
        The first one met on the Hopf curve from p₂ = ``p2_bracket[0]``, verified: |l₁| there is
        within the accuracy of the located p₂.

    Raises
    ------
    NoHopfError
        l₁ does not change sign on the Hopf curve inside ``p2_bracket``, or the located point fails
        its check.
    """
    from landau.derivation.general import hopf_normal_form

    a, b = map(float, p2_bracket)
    if not (math.isfinite(a) and math.isfinite(b)) or a == b:
        raise InputError(f"{system.name}: p2_bracket must be two different finite numbers, got {p2_bracket!r}")
    prm = {**params, second: a}
    start = hopf_normal_form(system, prm, p1_bracket, dps=dps, jets=jets)
    # the Hopf curve followed by pseudo-arclength from p₂ = a (a Newton jump straight to p₂ = b can
    # land on another branch of Hopf points, whose l₁ has another sign)
    curve = hopf_curve(system, prm, second, (a, b), start, steps=steps, dps=dps, jets=jets, l2=l2)
    if not curve.generalised_hopf:
        l1s = curve.l1
        ends = f" ({l1s[0]:.3g} … {l1s[-1]:.3g} along the curve)" if len(l1s) else ""
        raise NoHopfError(f"{system.name}: l1 does not change sign on the Hopf curve from {second} = {a:g} "
                          f"towards {b:g}{ends}; no generalised-Hopf point bracketed")
    # the first one met from p₂ = a
    return min(curve.generalised_hopf, key=lambda g: abs(g.p2 - a))
