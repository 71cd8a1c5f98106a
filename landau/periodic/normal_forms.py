"""First-order normal-form coefficients of the fold (LPC) and period doubling (PD) of cycles.

Periodic normalization (Iooss 1988; Kuznetsov, Govaerts & Doedel 2005, Sect. 4), computed on
the same collocation discretisation as the branch. Time is the model's time t ∈ [0, T];
A(t) = ∂f/∂y along the cycle x₀, f = f(x₀(t)), B and C the second- and third-order forms (the
contract's ``multilinear`` or directional differences of ``jac``). An integral ∫⟨φ*, g⟩ over
the period is the dot product of a left null vector of the collocation matrix with g at the
collocation points (a left null vector of the discretised operator is the quadrature-weighted
adjoint eigenfunction); every coefficient below is a ratio of two such integrals, so the
adjoint's scale cancels.

**LPC.** Centre manifold x = x₀(τ) + ξ v(τ) + ½ξ² h₂(τ) + …, normal form

    dτ/dt = 1 − ξ + a₁ξ² + …,   dξ/dt = b ξ² + …   (at the critical parameter),

with v̇ − A v = f, v T-periodic, ∫₀ᵀ⟨v, f⟩ dt = 0, and φ* the periodic adjoint null vector
(∫⟨φ*, f⟩ = 0). Solvability at order ξ² gives (KGD 2005, eq. 4.5)

    b = ∫₀ᵀ⟨φ*, B(v, v) + 2 A v⟩ dt / (2 ∫₀ᵀ⟨φ*, v⟩ dt).

The scale of v is fixed by v̇ − A v = f (b is a property of the cycle, not of a choice of scale).
v is the tangent's state part at the located fold rescaled by T/θ (θ its period component).

**PD.** x = x₀(τ) + ξ v(τ) + ½ξ² h₂(τ) + (1/6)ξ³ h₃(τ) + …, normal form dτ/dt = 1 + αξ² + …,
dξ/dt = c ξ³ + …, with v̇ = A v, v(T) = −v(0), ∫₀ᵀ⟨v, v⟩ dt = 1 (this normalisation fixes the
scale of c: c scales as |v|⁻²); φ₁* the periodic adjoint (∫⟨φ₁*, f⟩ = 1) and φ* the
anti-periodic one:

    α = ½ ∫⟨φ₁*, B(v, v)⟩,      ḣ₂ − A h₂ = B(v, v) − 2α f,  h₂ periodic, ∫⟨φ₁*, h₂⟩ = 0,
    c = ∫⟨φ*, C(v, v, v) + 3 B(v, h₂) − 6 α A v⟩ / (6 ∫⟨φ*, v⟩).

c < 0: the doubled cycle is born stable on the side where the cycle is unstable (supercritical);
c > 0 subcritical. KGD 2005 write c with ∫₀ᵀ normalisations in the rescaled time; their value and
this one have the same sign; the magnitude depends on the normalisation of v (MatCont's printed value for
its adaptive-control example is −0.04268, this one −0.3051). This c is checked independently against
the doubled cycle: with ν = ln(−μ)/T from the multiplier μ of the period-1 cycle and ξ its amplitude
along v, ξ² = −ν/c (tests/periodic/test_rossler.py).

**NS.** x = x₀(τ) + ξ v + ξ̄ v̄ + ½ξ² h₂₀ + ξξ̄ h₁₁ + …, normal form dτ/dt = 1 + a₁|ξ|² + …,
dξ/dt = (iθ/T) ξ + d ξ|ξ|² + … (KGD 2005, Sect. 4.3), e^{iθ} the critical multiplier (0 < θ < π),
v̇ − A v + (iθ/T) v = 0, v periodic, ∫₀ᵀ⟨v, v⟩ dt = 1 (Hermitian; fixes the scale of d, which scales
as |v|⁻²); φ₁* the periodic adjoint (∫⟨φ₁*, f⟩ = 1) and φ* the adjoint of v̇ − A v + (iθ/T) v:

    a₁ = ∫⟨φ₁*, B(v, v̄)⟩,   ḣ₁₁ − A h₁₁ = B(v, v̄) − a₁ f,  ∫⟨φ₁*, h₁₁⟩ = 0,
    ḣ₂₀ − A h₂₀ + (2iθ/T) h₂₀ = B(v, v),
    d = ∫⟨φ*, ½C(v, v, v̄) + B(v, h₁₁) + ½B(v̄, h₂₀) − a₁ A v⟩ / ∫⟨φ*, v⟩ + iθ a₁/T.

The reported coefficient is Re d: Re d < 0 a stable invariant torus on the side where the cycle is
unstable (supercritical), Re d > 0 subcritical. Checked against the closed form Re d = −2/T of a
cycle times a transverse Hopf normal form (tests/periodic/test_ns_coefficient.py). That system is
decoupled, so the check covers the cubic term, the normalisation and the adjoint ratio but not the
quadratic terms B(v, h₁₁), B(v̄, h₂₀), which vanish there.

References
----------
Iooss, G. (1988). Global characterization of the normal form for a vector field near a closed orbit.
J. Differential Equations 76, 47–76.
Kuznetsov, Y. A., Govaerts, W., Doedel, E. J. & Dhooge, A. (2005). Numerical periodic normalization
for codim 1 bifurcations of limit cycles. SIAM J. Numer. Anal. 43, 1407–1435.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import scipy.sparse as sps
import scipy.sparse.linalg as spla

from landau.periodic.collocation import Collocation, at_points
from landau.periodic.floquet import monodromy, propagate
from landau.periodic.problem import CycleProblem


def coefficient(problem: CycleProblem, kind: str, point: Any) -> tuple[float | None, str]:
    """The normal-form coefficient of a located special point, and a one-line message."""
    try:
        if kind == "LPC":
            b = lpc_coefficient(problem, point.coll, point.u, point.tau)
            return b, f"fold of cycles, normal-form coefficient b = {b:.6g} (dξ/dt = b ξ², KGD 2005)"
        if kind == "PD":
            c = pd_coefficient(problem, point.coll, point.u)
            side = "supercritical" if c < 0 else "subcritical"
            return c, f"period doubling, normal-form coefficient c = {c:.6g} ({side}; dξ/dt = c ξ³, KGD 2005)"
        if kind == "NS":
            d = ns_coefficient(problem, point.coll, point.u)
            side = "supercritical" if d.real < 0 else "subcritical"
            return float(d.real), (f"Neimark-Sacker, normal-form coefficient Re d = {d.real:.6g} ({side}; "
                                   f"dξ/dt = iθ/T ξ + d ξ|ξ|², KGD 2005)")
    except (np.linalg.LinAlgError, RuntimeError, ValueError) as exc:
        return None, f"{kind}: normal-form coefficient failed ({exc})"
    return None, f"{kind}: normal-form coefficient not computed (only LPC, PD and NS are)"


# ---- multilinear forms ---------------------------------------------------------------------------
def second(problem: CycleProblem, y: np.ndarray, p: float, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """B(y; u, v) at every column (the contract's form, or a central difference of ``jac`` along u)."""
    if problem.multilinear is not None:
        return np.asarray(problem.multilinear[0](y, p, u, v), dtype=float)
    h = 1e-4 * _size(y, u)
    Jp = np.asarray(problem.jac(y + h * u, p))
    Jm = np.asarray(problem.jac(y - h * u, p))
    return np.einsum("abm,bm->am", (Jp - Jm) / (2 * h), v)


def third(problem: CycleProblem, y: np.ndarray, p: float, u: np.ndarray, v: np.ndarray,
          w: np.ndarray) -> np.ndarray:
    """C(y; u, v, w) at every column (the contract's form, or a second difference of ``jac``)."""
    if problem.multilinear is not None:
        return np.asarray(problem.multilinear[1](y, p, u, v, w), dtype=float)
    if not np.array_equal(u, v):        # polarisation: C(u, v, w) from C(s, s, w) with s = u ± v
        return (third(problem, y, p, u + v, u + v, w) - third(problem, y, p, u - v, u - v, w)) / 4
    h = 2e-3 * _size(y, u)
    J = [np.asarray(problem.jac(y + s * h * u, p)) for s in (1, 0, -1)]
    return np.einsum("abm,bm->am", (J[0] - 2 * J[1] + J[2]) / h ** 2, w)


def _size(y: np.ndarray, u: np.ndarray) -> float:
    return float(max(1.0, np.max(np.abs(y)))) / float(max(1e-300, np.max(np.abs(u))))


# ---- linear algebra on the collocation matrix ----------------------------------------------------
def _operator(coll: Collocation, u: np.ndarray, sign: float) -> sps.csc_matrix:
    """The square collocation matrix of v′ − T A v in the node values, with the boundary rows
    v(0) − sign·v(1) (sign = +1 periodic, −1 anti-periodic)."""
    J = coll.jacobian(u, np.zeros(coll.nY)).tolil()
    ncol = coll.mesh.ntst * coll.mesh.m * coll.n
    n, nY = coll.n, coll.nY
    for a in range(n):
        J[ncol + a, nY - n + a] = -sign
    return J[: ncol + n, :nY].tocsc()


def _bordered(Msq: sps.csc_matrix, seed: int = 7) -> tuple[Any, np.ndarray, np.ndarray]:
    """LU of [M b; cᵀ 0] with fixed pseudo-random borders, nonsingular when M has a 1-d kernel."""
    rng = np.random.default_rng(seed)
    N = Msq.shape[0]
    b, c = rng.standard_normal(N), rng.standard_normal(N)
    E = sps.bmat([[Msq, sps.csc_matrix(b[:, None])], [sps.csr_matrix(c[None, :]), None]]).tocsc()
    return spla.splu(E), b, c


def _left_null(Msq: sps.csc_matrix) -> np.ndarray:
    """w with wᵀM ≈ 0: from [M b; cᵀ 0]ᵀ (w, s) = (0, 1)."""
    lu, _, _ = _bordered(Msq)
    e = np.zeros(Msq.shape[0] + 1)
    e[-1] = 1.0
    # the transposed bordered system [Mᵀ c; bᵀ 0] (w, s) = (0, 1)
    return lu.solve(e, trans="T")[:-1]


def _colloc_part(coll: Collocation, w: np.ndarray) -> np.ndarray:
    """The collocation rows of a left vector, as (n, N·m) at the collocation points."""
    ncol = coll.mesh.ntst * coll.mesh.m * coll.n
    return w[:ncol].reshape(-1, coll.n).T


def lpc_coefficient(problem: CycleProblem, coll: Collocation, u: np.ndarray, tau: np.ndarray) -> float:
    """b of the fold of cycles (module docstring) at the located fold (u, τ)."""
    Y, T, p = coll.unpack(u)
    V, theta, _ = coll.unpack(tau)
    if abs(theta) < 1e-14:
        raise ValueError("the tangent has no period component at the fold (a degenerate fold)")
    v = V * (T / theta)                                   # v̇ − A v = f in the time t
    f_nodes = np.asarray(problem.rhs(Y, p), dtype=float)
    yc, _ = at_points(coll.mesh, Y)
    vc, _ = at_points(coll.mesh, v)
    fc, _ = at_points(coll.mesh, f_nodes)
    wq = coll.w
    v = v - (np.sum(wq * np.sum(vc * fc, axis=0)) / np.sum(wq * np.sum(fc * fc, axis=0))) * f_nodes
    vc, _ = at_points(coll.mesh, v)
    # the adjoint: left null vector of the (Y, T) Jacobian at fixed p, [F_Y F_T; g 0]
    J = coll.jacobian(u, coll.phase_row(Y))[:, : coll.nY + 1].tocsc()
    phi = _colloc_part(coll, _left_null(J))
    A = np.asarray(problem.jac(yc, p), dtype=float)
    num = np.sum(phi * (second(problem, yc, p, vc, vc) + 2 * np.einsum("abm,bm->am", A, vc)))
    return float(num / (2 * np.sum(phi * vc)))


def _cycle_operators(problem: CycleProblem, coll: Collocation, u: np.ndarray, yc: np.ndarray, p: float):
    """``(A, f, L, φ₁*)`` of the cycle u at its collocation points yc: A(t) = f_y, f(t), the periodic
    operator L = d/dt − T·A(t) of the collocation, and its left null vector φ₁* (the adjoint of the
    phase direction) scaled so that ∫⟨φ₁*, f⟩ = 1 — the pieces every periodic normal form starts from
    (Kuznetsov, Govaerts & Doedel 2005, Sect. 2)."""
    A = np.asarray(problem.jac(yc, p), dtype=float)
    fc = np.asarray(problem.rhs(yc, p), dtype=float)
    Lper = _operator(coll, u, +1.0)
    phi1 = _colloc_part(coll, _left_null(Lper))
    return A, fc, Lper, phi1 / np.sum(phi1 * fc)                        # ∫⟨φ₁*, f⟩ = 1


def pd_coefficient(problem: CycleProblem, coll: Collocation, u: np.ndarray) -> float:
    """c of the period doubling (module docstring) at the located PD cycle u."""
    Y, T, p = coll.unpack(u)
    mesh = coll.mesh
    M = monodromy(problem, mesh, Y, T, p)
    lam, vecs = np.linalg.eig(M)
    i = int(np.argmin(np.abs(lam + 1.0)))
    v = np.real(propagate(problem, mesh, Y, T, p, np.real(vecs[:, i])))
    yc, _ = at_points(mesh, Y)
    vc, _ = at_points(mesh, v)
    scale = np.sqrt(T * np.sum(coll.w * np.sum(vc * vc, axis=0)))      # ∫₀ᵀ⟨v, v⟩ dt = 1
    v, vc = v / scale, vc / scale
    A, fc, Lper, phi1 = _cycle_operators(problem, coll, u, yc, p)
    Bvv = second(problem, yc, p, vc, vc)
    alpha = 0.5 * np.sum(phi1 * Bvv)
    h2c = _h2(coll, Lper, phi1, T * (Bvv - 2 * alpha * fc))
    phis = _colloc_part(coll, _left_null(_operator(coll, u, -1.0)))
    R = (third(problem, yc, p, vc, vc, vc) + 3 * second(problem, yc, p, vc, h2c)
         - 6 * alpha * np.einsum("abm,bm->am", A, vc))
    return float(np.sum(phis * R) / (6 * np.sum(phis * vc)))


def _h2(coll: Collocation, Lper: sps.csc_matrix, phi1: np.ndarray, rhs_c: np.ndarray) -> np.ndarray:
    """h₂ at the collocation points: the periodic solution of (v′ − T A v) = rhs with ∫⟨φ₁*, h₂⟩ = 0."""
    n = coll.n
    ic = coll.P.T @ phi1.T.ravel()                                     # row: Σ φ₁*·h₂ at the points
    rhs = np.concatenate([rhs_c.T.ravel(), np.zeros(n)])
    # the bordered system [L  w; icᵀ 0] (h₂, λ) = (rhs, 0), w the left null vector (λ absorbs the
    # O(h^{2m}) inconsistency of a singular L)
    w = _left_null(Lper)
    E = sps.bmat([[Lper, sps.csc_matrix(w[:, None])], [sps.csr_matrix(ic[None, :]), None]]).tocsc()
    sol = spla.splu(E).solve(np.concatenate([rhs, [0.0]]))
    h2 = sol[:-1].reshape(-1, n).T
    return at_points(coll.mesh, h2)[0]


# ---- Neimark–Sacker --------------------------------------------------------------------------------
def _bc(problem: CycleProblem, y: np.ndarray, p: float, u: np.ndarray, w: np.ndarray) -> np.ndarray:
    """B(u, w) for complex u, w (bilinear, from the real form :func:`second`)."""
    ur, ui, wr, wi = u.real, u.imag, w.real, w.imag
    return (second(problem, y, p, ur, wr) - second(problem, y, p, ui, wi)
            + 1j * (second(problem, y, p, ur, wi) + second(problem, y, p, ui, wr)))


def _cvvvbar(problem: CycleProblem, y: np.ndarray, p: float, v: np.ndarray) -> np.ndarray:
    """C(v, v, v̄) = C(a, a, v) + C(b, b, v) for v = a + ib (trilinear, from :func:`third`)."""
    a, b = v.real, v.imag
    out = np.zeros(v.shape, dtype=complex)
    for s in (a, b):
        out += third(problem, y, p, s, s, a) + 1j * third(problem, y, p, s, s, b)
    return out


def _shifted(coll: Collocation, Lper: sps.csc_matrix, shift: float) -> sps.csc_matrix:
    """The periodic collocation matrix of v′ − T A v + i·shift·v (collocation rows + boundary rows)."""
    ncol = coll.mesh.ntst * coll.mesh.m * coll.n
    Pz = sps.vstack([coll.P, sps.csr_matrix((Lper.shape[0] - ncol, coll.nY))])
    return (Lper.astype(complex) + 1j * shift * Pz).tocsc()


def ns_coefficient(problem: CycleProblem, coll: Collocation, u: np.ndarray) -> complex:
    """d of the Neimark–Sacker bifurcation (module docstring) at the located NS cycle u."""
    Y, T, p = coll.unpack(u)
    mesh = coll.mesh
    lam, vecs = np.linalg.eig(monodromy(problem, mesh, Y, T, p))
    cand = np.where(lam.imag > 1e-8)[0]
    if cand.size == 0:
        raise ValueError("no complex multiplier pair at the Neimark-Sacker point")
    i = int(cand[np.argmin(np.abs(np.abs(lam[cand]) - 1.0))])
    theta = float(np.angle(lam[i]))
    w = propagate(problem, mesh, Y, T, p, vecs[:, i].astype(complex))   # w(1) = e^{iθ} w(0)
    v = w * np.exp(-1j * theta * mesh.nodes)[None, :]                   # periodic
    yc, _ = at_points(mesh, Y)
    vc = at_points(mesh, v.real)[0] + 1j * at_points(mesh, v.imag)[0]
    scale = np.sqrt(T * np.sum(coll.w * np.sum(np.abs(vc) ** 2, axis=0)))   # ∫₀ᵀ⟨v, v⟩ dt = 1
    v, vc = v / scale, vc / scale
    A, fc, Lper, phi1 = _cycle_operators(problem, coll, u, yc, p)
    Bvvb = _bc(problem, yc, p, vc, np.conj(vc)).real
    a1 = float(np.sum(phi1 * Bvvb))
    h11 = _h2(coll, Lper, phi1, T * (Bvvb - a1 * fc))
    # h₂₀: the periodic solution of h′ − T A h + 2iθ h = T B(v, v) (nonsingular away from strong
    # resonance e^{iθ} ≠ e^{2πi k/3}, e^{2πi k/4})
    L20 = _shifted(coll, Lper, 2 * theta)
    rhs = np.concatenate([(T * _bc(problem, yc, p, vc, vc)).T.ravel(), np.zeros(coll.n)])
    h20 = spla.splu(L20).solve(rhs).reshape(-1, coll.n).T
    h20c = at_points(mesh, h20.real)[0] + 1j * at_points(mesh, h20.imag)[0]
    phis = _colloc_part(coll, _left_null(_shifted(coll, Lper, theta)))
    R = (0.5 * _cvvvbar(problem, yc, p, vc) + _bc(problem, yc, p, vc, h11.astype(complex))
         + 0.5 * _bc(problem, yc, p, np.conj(vc), h20c) - a1 * np.einsum("abm,bm->am", A, vc))
    return complex(np.sum(phis * R) / np.sum(phis * vc) + 1j * theta * a1 / T)
