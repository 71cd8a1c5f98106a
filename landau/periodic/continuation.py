"""Pseudo-arclength continuation of a family of cycles in (y(·), T, p) (Keller 1977; Doedel et al. 1991).

Each new point u = (y(·), T, p) solves the collocation equations of :mod:`.collocation` (with
the phase condition against the previous cycle) bordered by Keller's pseudo-arclength equation

    ⟨u − u_k, τ_k⟩ = Δs,                                                                     (1)

τ_k the unit tangent at u_k in the inner product ⟨u, v⟩ = ∫₀¹⟨y_u, y_v⟩_s dt + T_u T_v + p_u p_v
(states divided by ``scales``). The predictor is u_k + Δs τ_k; Newton's method corrects on (1);
the step grows after fast convergence and halves on failure, down to ``ds_min``. The mesh is
adapted every ``adapt_every`` steps (:func:`.collocation.adapt`).

Starts: (a) a :class:`HopfStart` — the first cycle is the amplitude equation's prediction
y₀ + 2Re(ε q e^{2πit}), with 2ε = C√|p − p_c| the half peak-to-peak of state ``measure`` on the
side ``side`` (or a small ε at p = p_c when C is not known), corrected on the hyperplane through
it orthogonal to the eigenfunction direction 2Re(q e^{2πit}); (b)/(c) a :class:`CycleStart`
(a computed cycle or a guess), corrected at its fixed p.

The branch computed so far is always returned; :class:`.branch.EndReason` says why it ended.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sps
import scipy.sparse.linalg as spla

from landau.errors import InputError, IntegratorError
from landau.periodic import bifurcations as bif
from landau.periodic.branch import CycleBranch, EndReason, SpecialPoint
from landau.periodic.collocation import Collocation, Mesh, adapt, at_points, evaluate, remesh
from landau.periodic.floquet import Multipliers, floquet
from landau.periodic.problem import CycleProblem, CycleStart, HopfStart


class _NoConvergence(Exception):
    pass


@dataclass
class Point:
    """One converged point: the discretisation, the unknowns u, the unit tangent and the multipliers."""

    coll: Collocation
    u: np.ndarray
    tau: np.ndarray
    mu: Multipliers
    orient: float = 0.0         # sign of det [F_u; τ_prevᵀ] (branch points), 0 where not computed

    @property
    def Y(self) -> np.ndarray:
        return self.coll.unpack(self.u)[0]

    @property
    def T(self) -> float:
        return self.coll.unpack(self.u)[1]

    @property
    def p(self) -> float:
        return self.coll.unpack(self.u)[2]


def _border_row(coll: Collocation, tau: np.ndarray) -> np.ndarray:
    """The row r with r·u = ⟨τ, u⟩ (the inner product of the module docstring)."""
    return np.concatenate([coll.weight_vector(tau), tau[coll.nY:]])


def newton(coll: Collocation, u0: np.ndarray, phase: np.ndarray, row: np.ndarray, c: float, *,
           tol: float = 1e-10, maxit: int = 10, damped: bool = False,
           guard: bool = True) -> tuple[np.ndarray, int]:
    """Solve the collocation equations bordered by row·u = c, from u0; returns (u, iterations)."""
    u = u0.copy()
    s = np.concatenate([np.tile(coll.scales, coll.mesh.npts), [1.0, 1.0]])
    s[-2] = max(1.0, abs(u[-2]))
    s[-1] = max(1.0, abs(u[-1]))
    prev = np.inf
    for it in range(1, maxit + 1):
        F = np.concatenate([coll.residual(u, phase), [row @ u - c]])
        J = sps.vstack([coll.jacobian(u, phase), sps.csr_matrix(row)]).tocsc()
        # Newton step: [F_u; rᵀ] δ = −(F, rᵀu − c), the collocation Jacobian bordered by (1)
        try:
            du = spla.splu(J).solve(-F)
        except RuntimeError as exc:       # exactly singular
            raise _NoConvergence(str(exc)) from exc
        size = float(np.max(np.abs(du) / s))
        if not np.isfinite(size):
            raise _NoConvergence("non-finite Newton step")
        lam = 1.0
        if damped and size > 0.5:
            lam = 0.5 / size
        u = u + lam * du
        if size < tol:
            return u, it
        if guard and not damped and it > 2 and size > 2 * prev:
            raise _NoConvergence("Newton diverges")
        prev = size
    raise _NoConvergence(f"no convergence in {maxit} Newton iterations (last step {size:.2e})")


def tangent(coll: Collocation, u: np.ndarray, phase: np.ndarray, row: np.ndarray) -> np.ndarray:
    """The unit tangent τ at u: [F_u; rᵀ] τ = (0, 1), normalised in the inner product."""
    return tangent_and_sign(coll, u, phase, row)[0]


def tangent_and_sign(coll: Collocation, u: np.ndarray, phase: np.ndarray,
                     row: np.ndarray) -> tuple[np.ndarray, float]:
    """The unit tangent (:func:`tangent`) and the sign of det [F_u; rᵀ] from the same LU."""
    J = sps.vstack([coll.jacobian(u, phase), sps.csr_matrix(row)]).tocsc()
    rhs = np.zeros(J.shape[0])
    rhs[-1] = 1.0
    # the kernel direction of F_u: [F_u; rᵀ] τ = e_last (r the previous tangent's row)
    lu = spla.splu(J)
    t = lu.solve(rhs)
    return t / np.sqrt(coll.inner(t, t)), _lu_sign(lu)


def _lu_sign(lu) -> float:
    """The sign of the determinant of a matrix from its sparse LU (diag(U) and the permutations)."""
    d = np.sign(lu.U.diagonal()).prod()
    return float(d * _perm_sign(lu.perm_r) * _perm_sign(lu.perm_c))


def _perm_sign(perm: np.ndarray) -> int:
    seen = np.zeros(perm.size, dtype=bool)
    sign = 1
    for i in range(perm.size):
        if not seen[i]:
            j, length = i, 0
            while not seen[j]:
                seen[j] = True
                j = perm[j]
                length += 1
            if length % 2 == 0:
                sign = -sign
    return sign


# ---- first points ------------------------------------------------------------------------------
def _first_from_hopf(problem: CycleProblem, hopf: HopfStart, mesh: Mesh, amplitude0: float | None, tol: float):
    """The amplitude equation's first cycle, corrected orthogonally to the eigenfunction direction."""
    coll = Collocation(problem, mesh)
    t = mesh.nodes
    q = np.asarray(hopf.eigenvector, dtype=complex)
    phi = 2 * np.real(q[:, None] * np.exp(2j * np.pi * t)[None, :])
    y0 = np.asarray(hopf.equilibrium, dtype=float)
    s = coll.scales
    a0 = amplitude0 if amplitude0 is not None else 1e-3 * s[problem.measure]
    p = hopf.p_c
    if hopf.amplitude is not None and hopf.amplitude > 0 and hopf.side in (1, -1):
        p = hopf.p_c + hopf.side * (a0 / hopf.amplitude) ** 2
    return _first_along(problem, mesh, np.repeat(y0[:, None], t.size, axis=1), 2 * np.pi / hopf.omega, p,
                        phi, a0 / 2, tol)


def _first_along(problem: CycleProblem, mesh: Mesh, Ybase: np.ndarray, T: float, p: float, phi: np.ndarray,
                 eps: float, tol: float):
    """The cycle near Ybase + ε φ, corrected on the hyperplane through it orthogonal to (φ, 0, 0);
    the tangent there oriented along +φ (away from the Hopf or PD point the branch starts at)."""
    coll = Collocation(problem, mesh)
    Y = Ybase + eps * phi
    u0 = coll.pack(Y, T, p)
    d = coll.pack(phi, 0.0, 0.0)
    d /= np.sqrt(coll.inner(d, d))
    row = _border_row(coll, d)
    g = coll.set_reference(Y)
    u, _ = newton(coll, u0, g, row, row @ u0, tol=tol, maxit=20, damped=True)
    g = coll.set_reference(coll.unpack(u)[0])
    tau = tangent(coll, u, g, row)
    if coll.inner(tau, d) < 0:
        tau = -tau
    return coll, u, tau


def _first_from_cycle(problem: CycleProblem, start: CycleStart, mesh: Mesh, tol: float):
    """A sampled cycle interpolated onto the mesh and corrected at its fixed p."""
    if start.y.shape[0] != problem.n:
        raise InputError(f"CycleStart: y has {start.y.shape[0]} states, the problem {problem.n}")
    coll = Collocation(problem, mesh)
    s = (start.t - start.t[0]) / start.period
    keep = s < 1 - 1e-12
    s, y = s[keep], start.y[:, keep]
    Y = np.array([np.interp(mesh.nodes, s, yi, period=1.0) for yi in y])
    Y[:, -1] = Y[:, 0]
    u0 = coll.pack(Y, start.period, start.p)
    row = np.zeros(coll.size)
    row[-1] = 1.0
    g = coll.set_reference(Y)
    u = u0
    for _ in range(1 if start.exact else 4):    # a guess: re-anchor the phase after each solve
        u, _ = newton(coll, u, g, row, start.p, tol=tol, maxit=30, damped=True)
        g = coll.set_reference(coll.unpack(u)[0])
    # the tangent with dp = 1, scaled to unit length
    tau = tangent(coll, u, g, row)
    return coll, u, tau


# ---- the continuation ----------------------------------------------------------------------------
def continue_cycles(problem: CycleProblem, start: HopfStart | CycleStart | SpecialPoint | None = None, *,
                    steps: int = 100,
                    ds: float = 0.01, ds_min: float = 1e-7, ds_max: float = 0.5, direction: int = 1,
                    detect: bool = True, normal_forms: bool = True, ntst: int = 40, ncol: int = 4,
                    adapt_every: int = 3, max_period: float = np.inf, tol: float = 1e-10,
                    amplitude0: float | None = None, collapse: float | None = None,
                    strict: bool = False, stop_at: tuple[str, ...] = ()) -> CycleBranch:
    """Continue the branch of cycles of ``problem`` from ``start`` (default: ``problem.hopf``).

    Parameters
    ----------
    problem : CycleProblem
        The vector field and the continuation parameter.
    start : HopfStart, CycleStart, SpecialPoint or None
        Where the branch starts (None: ``problem.hopf``); a located period doubling (a
        ``SpecialPoint`` of kind "PD") switches onto the period-doubled branch
        (:mod:`.switching`).
    steps : int
        The number of continuation steps after the first cycle.
    ds, ds_min, ds_max : float
        The initial, smallest and largest pseudo-arclength step (1).
    direction : int
        +1 or −1: from a Hopf point +1 moves away from it (growing cycles); from a cycle, +1
        makes p increase first.
    detect, normal_forms : bool
        Locate LPC, PD, NS (and BP) points; compute their normal-form coefficients.
    ntst, ncol : int
        Mesh intervals N and collocation points per interval m.
    adapt_every : int
        Adapt the mesh every this many steps (0: never).
    max_period : float
        Stop when T exceeds it.
    tol : float
        Newton tolerance on the scaled step (states / scales, T and p relative to max(1, |·|)).
    amplitude0 : float, optional
        The first cycle's half peak-to-peak of state ``measure`` from a Hopf start
        (default 1e-3 × its scale).
    collapse : float, optional
        Stop (COLLAPSE) when the amplitude falls below it (default 1e-6 × the scale of ``measure``).
    stop_at : tuple of str
        Stop (SPECIAL_POINT) after locating a special point of one of these kinds ("LPC", "PD", "NS").
    strict : bool
        Raise :class:`landau.errors.IntegratorError` (carrying ``.branch``) when the continuation
        ends on a failure (no convergence, collapse, period beyond ``max_period``) instead of
        returning the branch with its end reason.

    Returns
    -------
    CycleBranch
    """
    if direction not in (1, -1):
        raise InputError(f"direction must be +1 or -1, got {direction!r}")
    if steps < 0 or ntst < 2 or ncol < 1 or not ds > 0:
        raise InputError(f"steps >= 0, ntst >= 2, ncol >= 1 and ds > 0 needed, got {steps}, {ntst}, {ncol}, {ds}")
    start = start if start is not None else problem.hopf
    if start is None:
        raise InputError(f"{problem.name}: no start given and the problem has no Hopf point (problem.hopf)")
    mesh = Mesh.uniform(ntst, ncol)
    route = ("hopf" if isinstance(start, HopfStart) else "period-doubling" if isinstance(start, SpecialPoint)
             else "cycle" if start.exact else "guess")
    branch = CycleBranch(problem, route, settings={
        "discretisation": f"orthogonal collocation, Gauss-Legendre, ncol={ncol}", "ntst": ntst, "ncol": ncol,
        "newton_tol": tol, "ds": ds, "ds_max": ds_max, "adapt_every": adapt_every})
    try:
        if isinstance(start, HopfStart):
            coll, u, tau = _first_from_hopf(problem, start, mesh, amplitude0, tol)
            tau = direction * tau
        elif isinstance(start, SpecialPoint) and start.kind == "PD":
            from landau.periodic.switching import doubled_start
            mesh2, Yb, T2, p2, phi, eps = doubled_start(problem, start, amplitude0)
            coll, u, tau = _first_along(problem, mesh2, Yb, T2, p2, phi, eps, tol)
        elif isinstance(start, CycleStart):
            coll, u, tau = _first_from_cycle(problem, start, mesh, tol)
            tau = direction * tau
        else:
            raise InputError(f"start must be a HopfStart, a CycleStart or a PD SpecialPoint, got {start!r}")
    except _NoConvergence as exc:
        branch.end, branch.message = EndReason.FIRST_POINT, str(exc)
        err = IntegratorError(f"{problem.name}: the first cycle did not converge ({exc}); "
                              "give a better guess, a smaller amplitude0, or more mesh intervals (ntst)")
        err.branch = branch  # type: ignore[attr-defined]
        raise err from exc
    return _run(problem, branch, Point(coll, u, tau, floquet(problem, coll.mesh, *coll.unpack(u))),
               steps=steps, ds=ds, ds_min=ds_min, ds_max=ds_max, detect=detect, normal_forms=normal_forms,
               adapt_every=adapt_every, max_period=max_period, tol=tol, collapse=collapse, strict=strict,
               stop_at=tuple(stop_at))


def half_amplitude(coll: Collocation, Y: np.ndarray, j: int) -> float:
    """(max − min)/2 of state j over the cycle, on a grid 4× finer than the nodes."""
    t = np.linspace(0.0, 1.0, 4 * (coll.mesh.npts - 1) + 1)
    yj = evaluate(coll.mesh, Y, t)[j]
    return float((yj.max() - yj.min()) / 2)


def _correct(problem: CycleProblem, prev: Point, s: float, tol: float, near_singular: bool = False
             ) -> tuple[Point, int]:
    """The point at pseudo-arclength step s from ``prev`` (predictor prev.u + s τ, corrector on (1))."""
    coll = prev.coll
    row = _border_row(coll, prev.tau)
    g = coll.set_reference(prev.Y)
    # near a branch point Newton converges linearly: more iterations, no divergence guard
    u, it = newton(coll, prev.u + s * prev.tau, g, row, row @ prev.u + s, tol=tol,
                   maxit=40 if near_singular else 10, guard=not near_singular)
    tau, sign = tangent_and_sign(coll, u, g, row)
    return Point(coll, u, tau, floquet(problem, coll.mesh, *coll.unpack(u)), sign), it


def _adapted(problem: CycleProblem, pt: Point, tol: float) -> Point:
    """The point on a mesh equidistributing the error (:func:`.collocation.adapt`), re-corrected."""
    old = pt.coll
    mesh = adapt(old.mesh, pt.Y, scales=old.scales)
    coll = Collocation(problem, mesh)
    Y, T, p = old.unpack(pt.u)
    tY = old.unpack(pt.tau)[0]
    u0 = coll.pack(remesh(old.mesh, Y, mesh), T, p)
    tau = coll.pack(remesh(old.mesh, tY, mesh), *pt.tau[old.nY:])
    tau /= np.sqrt(coll.inner(tau, tau))
    row = _border_row(coll, tau)
    g = coll.set_reference(coll.unpack(u0)[0])
    u, _ = newton(coll, u0, g, row, row @ u0, tol=tol)
    _, sign = tangent_and_sign(coll, u, g, row)     # the orientation on the new mesh
    return Point(coll, u, tau, floquet(problem, mesh, *coll.unpack(u)), sign)


def _run(problem: CycleProblem, branch: CycleBranch, pt: Point, *, steps: int, ds: float, ds_min: float,
         ds_max: float, detect: bool, normal_forms: bool, adapt_every: int, max_period: float, tol: float,
         collapse: float | None, strict: bool, stop_at: tuple[str, ...]) -> CycleBranch:
    """The continuation loop: step, check the stops, detect and locate special points, adapt."""
    j = problem.measure
    s_meas = pt.coll.scales[j]
    collapse = 1e-6 * s_meas if collapse is None else collapse
    lo, hi = problem.parameter_range
    branch.append(pt.coll.mesh, pt.Y, pt.T, pt.p, pt.mu.all, pt.mu.trivial)
    psi = bif.test_values(pt.tau[-1], pt.mu)
    failure = None
    for k in range(steps):
        while True:
            try:
                new, it = _correct(problem, pt, ds, tol)
                break
            except _NoConvergence as exc:
                ds /= 2
                if ds < ds_min:
                    failure = (EndReason.NO_CONVERGENCE, f"at {problem.parameter} = {pt.p:.10g}: {exc}; "
                               "try a smaller ds_min, more mesh intervals (ntst) or a smaller tol")
                    break
        if failure:
            break
        psi_new = bif.test_values(new.tau[-1], new.mu)
        if detect and pt.coll is new.coll and pt.orient * new.orient < 0 and "LPC" not in bif.changes(psi, psi_new):
            bp = _locate_bp(problem, pt, ds, new.orient, len(branch) - 1, tol)
            if bp is not None:
                branch.special.append(bp)
        if detect:
            for kind in bif.changes(psi, psi_new):
                sp_ = _locate(problem, pt, ds, kind, psi[kind], psi_new[kind], len(branch) - 1, tol, normal_forms)
                if sp_ is not None:
                    branch.special.append(sp_)
        if not lo <= new.p <= hi:
            last = _on_bound(problem, new, lo if new.p < lo else hi, tol)
            if last is not None:
                branch.append(last.coll.mesh, last.Y, last.T, last.p, last.mu.all, last.mu.trivial)
            branch.end, branch.message = EndReason.PARAMETER_RANGE, f"{problem.parameter} reached the end of {lo, hi}"
            return branch
        prev_pt, pt, psi = pt, new, psi_new
        branch.append(pt.coll.mesh, pt.Y, pt.T, pt.p, pt.mu.all, pt.mu.trivial)
        if any(sp_.kind in stop_at for sp_ in branch.special):
            branch.end, branch.message = EndReason.SPECIAL_POINT, "stopped after " + ", ".join(stop_at)
            return branch
        if pt.T > max_period:
            failure = (EndReason.MAX_PERIOD, f"T = {pt.T:.6g} > max_period = {max_period:.6g} at "
                       f"{problem.parameter} = {pt.p:.10g}; raise max_period to go on")
            break
        if half_amplitude(pt.coll, pt.Y, j) < collapse or _inverted(prev_pt, pt):
            failure = (EndReason.COLLAPSE, f"the cycle collapsed onto an equilibrium (a Hopf point) near "
                       f"{problem.parameter} = {pt.p:.10g}; start there from the HopfStart to follow the other side")
            break
        ds = min(ds * 1.3, ds_max) if it <= 3 else (ds * 0.7 if it >= 6 else ds)
        if adapt_every and (k + 1) % adapt_every == 0:
            try:
                pt = _adapted(problem, pt, tol)
            except _NoConvergence:
                pass                           # keep the old mesh
    if failure:
        branch.end, branch.message = failure
        if strict:
            err = IntegratorError(f"{problem.name}: {failure[0].value}: {failure[1]}")
            err.branch = branch  # type: ignore[attr-defined]
            raise err
    return branch


def _inverted(a: Point, b: Point) -> bool:
    """True if the cycle's deviation from its mean reversed sign between two points: the branch
    went through the equilibrium (a Hopf point), ⟨y_b − ȳ_b, y_a − ȳ_a⟩ < 0 at the same phase."""
    if a.coll.mesh is not b.coll.mesh:
        return False
    ya, _ = at_points(a.coll.mesh, a.Y)
    yb, _ = at_points(b.coll.mesh, b.Y)
    w = a.coll.w / a.coll.scales[:, None] ** 2
    da = ya - (ya * a.coll.w).sum(axis=1, keepdims=True)
    db = yb - (yb * b.coll.w).sum(axis=1, keepdims=True)
    return bool(np.sum(w * da * db) < 0)


def _on_bound(problem: CycleProblem, pt: Point, bound: float, tol: float) -> Point | None:
    """The cycle of pt corrected at p = bound (the end of parameter_range), or None if that fails."""
    coll = pt.coll
    row = np.zeros(coll.size)
    row[-1] = 1.0
    g = coll.set_reference(pt.Y)
    try:
        u, _ = newton(coll, pt.u, g, row, bound, tol=tol)
    except _NoConvergence:
        return None
    return Point(coll, u, pt.tau, floquet(problem, coll.mesh, *coll.unpack(u)))


def _locate_bp(problem: CycleProblem, pt: Point, ds: float, sign1: float, index: int,
               tol: float) -> SpecialPoint | None:
    """A branch point of cycles between pt and the step ds: bisection on the sign of det [F_u; τᵀ]."""
    a, b = 0.0, ds
    q = None
    while b - a > 1e-7 * max(1.0, ds):
        m = (a + b) / 2
        try:
            trial, _ = _correct(problem, pt, m, tol, near_singular=True)
        except _NoConvergence:          # at the branch point itself the bordered system is singular
            break
        q = trial
        if q.orient * sign1 > 0:
            b = m
        else:
            a = m
    if q is None:
        return None
    return SpecialPoint("BP", index, q.p, q.T, None, q.mu.all,
                        "branch point of cycles (the orientation det [F_u; τᵀ] changes sign); no normal form",
                        (q.coll.mesh, q.Y))


def _locate(problem: CycleProblem, pt: Point, ds: float, kind: str, f0: float, f1: float, index: int,
            tol: float, normal_forms: bool) -> SpecialPoint | None:
    """Locate the zero of test function ``kind`` between pt and the step ds from it."""
    cache: dict[float, Point] = {}

    def psi(s: float) -> float:
        q, _ = _correct(problem, pt, s, tol)
        cache[s] = q
        return bif.test_values(q.tau[-1], q.mu)[kind]

    try:
        s = bif.locate(psi, 0.0, ds, f0, f1, tol=1e-12)
        q = cache.get(s) or _correct(problem, pt, s, tol)[0]
    except _NoConvergence:
        return None
    if kind == "NS" and not bif.is_neimark_sacker(q.mu):
        return None
    coef, msg = None, ""
    if normal_forms:
        from landau.periodic import normal_forms as nf
        coef, msg = nf.coefficient(problem, kind, q)
    return SpecialPoint(kind, index, q.p, q.T, coef, q.mu.all, msg, (q.coll.mesh, q.Y))


# ---- a cycle at a given parameter value ----------------------------------------------------------
@dataclass(frozen=True)
class FixedCycle:
    """The cycle at one parameter value: mesh, node values Y (n, npts), period T, p, multipliers."""

    mesh: Mesh
    Y: np.ndarray
    T: float
    p: float
    multipliers: Multipliers


def cycle_at(branch: CycleBranch, p: float, near: int | None = None, *, tol: float = 1e-10) -> FixedCycle:
    """The cycle of ``branch`` at the parameter value ``p``, with its Floquet multipliers.

    Newton's method on the collocation equations at fixed p (the border row picks p), on the mesh of
    branch point ``near`` and from its cycle (default: the point whose parameter is nearest p).
    Where the branch folds, the parameter does not fix the cycle: pass ``near`` on the wanted side,
    close enough to p for Newton's method (the conditioning grows as 1/|μ_c − 1| toward the fold).
    ``tol`` is Newton's tolerance on the scaled step, as in :func:`continue_cycles`.

    Raises InputError for an empty branch, a non-finite p or a ``near`` off the branch, and
    IntegratorError when Newton's method does not converge.
    """
    if not len(branch):
        raise InputError("cycle_at: the branch has no cycles")
    if not np.isfinite(p):
        raise InputError(f"cycle_at: p must be finite, got {p}")
    i = int(np.argmin(np.abs(np.asarray(branch.parameter) - p))) if near is None else int(near)
    if not -len(branch) <= i < len(branch):
        raise InputError(f"cycle_at: near = {near} is not a point of the branch ({len(branch)} cycles)")
    coll = Collocation(branch.problem, branch.meshes[i])
    Y0 = np.array(branch.nodes[i])
    row = np.zeros(coll.size)
    row[-1] = 1.0
    g = coll.set_reference(Y0)
    try:
        # Newton step: [F_u; e_pᵀ] δ = −(F, p_k − p), the collocation Jacobian bordered by p = const
        u, _ = newton(coll, coll.pack(Y0, branch.period[i], p), g, row, p, tol=tol, maxit=30, damped=True)
    except _NoConvergence as exc:
        raise IntegratorError(f"cycle_at: no cycle found at {branch.problem.parameter} = {p} from branch "
                              f"point {i} ({exc}); start nearer (near=) or refine the branch") from exc
    Y, T, pv = coll.unpack(u)
    return FixedCycle(coll.mesh, Y, T, pv, floquet(branch.problem, coll.mesh, Y, T, pv))
