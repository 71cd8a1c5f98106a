"""The Hopf point and the amplitude equation of a large sparse system, in float64 with sparse LU factors.

The numeric route for systems of many states (:class:`~landau.systems.sparse.SparseSystem`: a chain
of a hundred blocks, a multi-degree-of-freedom model), whose cost is polynomial in the size where
the general engine (:mod:`landau.derivation.general`, 50-digit determinants and minors) grows about
twofold per block of a chain:

1. **first crossing** (:func:`first_crossing`): from a parameter value where the steady state is
   stable, the parameter is lowered geometrically until the rightmost eigenvalue of the pencil
   (J(p), E) has Re λ > 0 (halving p), and the bracket is bisected (in log p) to 2e-2 — about
   fifteen dense spectra, O(n³) each, the only dense step; the rightmost eigenvalue there and its
   eigenvector by inverse iteration (sparse LU) start
2. **Newton on the extended system** (:func:`newton_hopf`) in (q, ω, p), q = q_r + i q_i with
   q_c = 1 (Kuznetsov 2004, §10.3.1, the standard augmented system of a Hopf point):

       (J(p) − iωE) q = 0,   q_c − 1 = 0,

   2n + 2 real equations in 2n + 2 unknowns, each step one sparse LU (``scipy.sparse.linalg.splu``);
   where it lands on a pair other than the first to cross (other pairs unstable at p_c: two
   crossings in the bracket), the bracket is narrowed and Newton started again;
3. **the amplitude equation** (:func:`sparse_normal_form`) by the same Fredholm condition as the
   general engine (:mod:`landau.derivation.fredholm`, Putelat et al. 2010, eqs 12–19), each solve
   a sparse LU of an n × n (or bordered (n+1) × (n+1)) matrix:

       q, ψ:  [[iωE − J, Eq], [e_cᵀ, 0]] (q, s) = (0, 1),  its transpose for ψ (ψEq = 1)
       a  = ψ J₁ q                          (dλ/dp; J₁ = ∂J/∂p, y₀ independent of p)
       W₂ = (2iωE − J)⁻¹ ½B(q, q),   W₀ = (−J)⁻¹ B(q, q̄)
       b  = ψ [B(q̄, W₂) + B(q, W₀) + ½C(q, q, q̄)]

   (Kuznetsov 2004 eq. (3.20) writes the same with h₂₀ = 2W₂, h₁₁ = W₀.)

The numbers are those of the general engine's convention (:data:`landau.derivation.hopf.GENERAL`):
dA/dT = a(p − p_c)A + bA|A|² with q_normalise = 1, Λ = 2 Re b, χ = 2 Im b, c₁ = b/⟨q, q⟩,
l₁ = Re c₁/ω.

References
----------
Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, §3.5 (eq. 3.20),
§8.7 (the fifth-order coefficient) and §10.2–10.3 (locating a Hopf point; its defining systems).
Govaerts, W. (2000). Numerical Methods for Bifurcations of Dynamical Equilibria, SIAM, §4.4
(bordered systems).
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). J. Mech. Phys. Solids 58, 27–53, eqs 12–19.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg
import scipy.sparse
import scipy.sparse.linalg

from landau.derivation.hopf import GENERAL, HopfResult
from landau.errors import NoHopfError, NonSimpleHopfError, SingularPointError
from landau.support.blas_threads import one_blas_thread
from landau.systems.sparse import SparseSystem

#: the ratio between the samples of the scan for the first crossing
SCAN_RATIO = 0.5
#: relative width to which the bracket of the first crossing is bisected before Newton (first try)
BRACKET_REL = 2e-2
#: two eigenvalues of the pencil this close (relative to ω) at the located point: a non-simple crossing
DOUBLE_REL = 1e-10
#: a coefficient below this fraction of the size of the terms it sums is zero to float64's round-off
ZERO_REL = 1e-12
#: a coefficient above :data:`ZERO_REL` but below this fraction of its terms is not resolved in float64
RESOLVED_REL = 1e-8


def spectrum(system: SparseSystem, p: float) -> np.ndarray:
    """The finite eigenvalues of J(p) v = λ E v, dense (O(n³): the only dense step of the route)."""
    J = system.jacobian(p).toarray()
    E = system.mass
    with one_blas_thread():      # a few hundred states: BLAS threads only spin (landau.support.blas_threads)
        lam = np.linalg.eigvals(J / E[:, None]) if np.all(E != 0) else scipy.linalg.eigvals(J, np.diag(E))
    return lam[np.isfinite(lam)]


def _rightmost(system: SparseSystem, p: float) -> float:
    lam = spectrum(system, p)
    return float(np.max(lam.real)) if lam.size else -np.inf


def eigenvector(system: SparseSystem, p: float, lam: complex, steps: int = 3) -> np.ndarray:
    """The right eigenvector of λ (a float64 eigenvalue of the pencil) by inverse iteration."""
    E = scipy.sparse.diags(system.mass).tocsc()
    # (J − λ̃E) v_{j+1} = E v_j with λ̃ the eigenvalue moved by 1e-10 of itself (J − λE is singular to round-off)
    shift = lam * (1 + 1e-10) + 1e-300
    lu = scipy.sparse.linalg.splu((system.jacobian(p) - shift * E).astype(complex).tocsc())
    v = np.random.default_rng(0).standard_normal(system.n) + 0j
    for _ in range(steps):
        v = lu.solve(E @ v if np.any(system.mass != 1) else v)
        v = v / v[np.argmax(np.abs(v))]
    return v


def first_crossing(system: SparseSystem, hi: float, lo: float, rel: float = BRACKET_REL) -> tuple[float, float]:
    """(a, b): a bracket hi ≥ a > b ≥ lo of the first crossing as p decreases, stable at a, unstable at
    b, a − b ≤ ``rel``·a (geometric scan by :data:`SCAN_RATIO`, then bisection in log p).

    Raises
    ------
    NoHopfError
        The steady state is unstable at ``hi``, or stays stable down to ``lo``.
    """
    a = float(hi)
    if _rightmost(system, a) >= 0:
        raise NoHopfError(f"{system.name}: the steady state is not stable at {system.parameter} = {a:g}")
    while True:
        b = max(a * SCAN_RATIO, lo)
        if _rightmost(system, b) >= 0:
            break
        if b <= lo:
            raise NoHopfError(f"{system.name}: no Hopf crossing of {system.parameter} below {hi:g} "
                              f"(down to {lo:g})")
        a = b
    return _bisect(system, a, b, rel)


def _bisect(system: SparseSystem, a: float, b: float, rel: float) -> tuple[float, float]:
    """Bisection in log p on the sign of the rightmost real part: stable at a, unstable at b."""
    while a - b > rel * a:
        c = float(np.sqrt(a * b))
        if _rightmost(system, c) >= 0:
            b = c
        else:
            a = c
    return a, b


def _start(system: SparseSystem, b: float) -> tuple[float, np.ndarray]:
    """(ω₀, q₀) of the rightmost eigenvalue at b (just past the crossing)."""
    lam = spectrum(system, b)
    i = int(np.argmax(lam.real))
    if abs(lam[i].imag) <= 1e-10 * (1 + abs(lam[i].real)):
        raise SingularPointError(f"{system.name}: a real eigenvalue crosses first near {system.parameter} = "
                                 f"{b:.8g} (a fold, not a Hopf point)")
    lam_i = complex(lam[i].real, abs(lam[i].imag))
    return lam_i.imag, eigenvector(system, b, lam_i)


def newton_hopf(system: SparseSystem, p0: float, omega0: float, q0: np.ndarray, c: int | None = None,
                tol: float = 1e-14, maxit: int = 30) -> tuple[float, float, np.ndarray, float]:
    """(p_c, ω_c, q, floor) by Newton's method on (J(p) − iωE) q = 0, q_c = 1 (the module docstring,
    step 2); ``floor`` is the relative size of the last step (≤ ``tol``, or the round-off floor the
    iteration stalled at: about the relative accuracy of q where two crossings nearly coincide).

    ``c`` is the normalised component (default: the largest of q₀).
    """
    n = system.n
    E = scipy.sparse.diags(system.mass)
    c = int(np.argmax(np.abs(q0))) if c is None else int(c)
    q = np.asarray(q0, dtype=complex) / q0[c]
    p, w = float(p0), float(omega0)
    ec = scipy.sparse.csc_matrix(([1.0], ([0], [c])), shape=(1, n))
    last = np.inf
    for _ in range(maxit):
        J = system.jacobian(p)
        qr, qi = q.real, q.imag
        F = np.concatenate([J @ qr + w * (E @ qi), J @ qi - w * (E @ qr), [qr[c] - 1.0, qi[c]]])
        col_w = np.concatenate([E @ qi, -(E @ qr), [0.0, 0.0]])[:, None]
        col_p = np.concatenate([system.J1 @ qr, system.J1 @ qi, [0.0, 0.0]])[:, None]
        top = scipy.sparse.bmat([[J, w * E], [-w * E, J], [ec, None], [None, ec]])
        K = scipy.sparse.hstack([top, scipy.sparse.csc_matrix(col_w), scipy.sparse.csc_matrix(col_p)]).tocsc()
        try:
            # the Newton step of the extended system: K (δq_r, δq_i, δω, δp) = −F
            step = scipy.sparse.linalg.splu(K).solve(-F)
        except RuntimeError:
            raise SingularPointError(f"{system.name}: the extended Hopf system is singular near "
                                     f"{system.parameter} = {p:.10g}") from None
        q = q + step[:n] + 1j * step[n:2 * n]
        w += step[2 * n]
        p += step[2 * n + 1]
        size = max(abs(step[2 * n + 1]) / abs(p), abs(step[2 * n]) / abs(w),
                   float(np.max(np.abs(step[:2 * n]))) / float(np.max(np.abs(q))))
        # converged: the step at the tolerance, or at round-off — small (1e-8) and no longer
        # shrinking quadratically, as where nearly coincident crossings make the extended system
        # ill-conditioned, with the residual of (J − iωE)q at round-off of its terms
        if size <= tol:
            break
        if size <= 1e-8 and size > 0.1 * last:
            J = system.jacobian(p)
            r = J @ q - 1j * w * (E @ q)
            terms = abs(J) @ np.abs(q) + w * np.abs(E @ q)
            if np.max(np.abs(r) / np.maximum(terms, 1e-300)) <= 1e-12:
                break
        last = size
    else:
        raise SingularPointError(f"{system.name}: Newton's method on the Hopf point did not converge "
                                 f"(last {system.parameter} = {p:.10g})")
    if not w > 0:
        raise SingularPointError(f"{system.name}: Newton's method reached ω = {w:g} (no Hopf point)")
    return p, w, q, size


@dataclass(frozen=True)
class SparseNormalForm:
    """The numbers of the amplitude equation at a Hopf point (the module docstring, step 3)."""

    q: np.ndarray          # (iωE − J)q = 0, q[normalise] = 1
    psi: np.ndarray        # ψ(iωE − J) = 0, ψEq = 1
    a: complex             # dλ/dp = ψ J₁ q
    b: complex             # the cubic coefficient
    b_scale: float         # Σ|ψ_i R_i|: the size of the terms whose sum is b (|b| ≪ b_scale: cancellation)


def sparse_normal_form(system: SparseSystem, pc: float, wc: float, q0: np.ndarray, normalise: int) -> SparseNormalForm:
    """q, ψ, a = dλ/dp and b at (p_c, ω_c) with q[normalise] = 1, by sparse LU factors."""
    n = system.n
    E = scipy.sparse.diags(system.mass).tocsc()
    J = system.jacobian(pc)
    A = (1j * wc * E - J).tocsc()
    Eq = E @ np.asarray(q0, dtype=complex)
    en = scipy.sparse.csc_matrix(([1.0], ([0], [normalise])), shape=(1, n))
    M = scipy.sparse.bmat([[A, scipy.sparse.csc_matrix(Eq[:, None])], [en, None]]).tocsc()
    rhs = np.zeros(n + 1, dtype=complex)
    rhs[-1] = 1.0
    try:
        lu = scipy.sparse.linalg.splu(M)
    except RuntimeError:
        raise SingularPointError(f"{system.name}: the bordered pencil is singular at {system.parameter} = "
                                 f"{pc:.10g}: the critical eigenvalue is not simple, or q[{normalise}] = 0") from None
    # [[iωE − J, E q₀], [e_nᵀ, 0]] (q, s) = (0, 1): the right null vector with q_n = 1 (s = 0)
    q = lu.solve(rhs)[:n]
    # its transpose (ψ, t) = (0, 1): ψ(iωE − J) = 0 with ψ E q₀ = 1 (t = 0)
    psi = lu.solve(rhs, trans="T")[:n]
    delta = psi @ (E @ q)
    psi = psi / delta
    a = complex(psi @ (system.J1 @ q))
    qb = q.conj()
    try:
        # (2iωE − J) W₂ = ½ B(q, q)   (Kuznetsov 2004 eq. 3.20: h₂₀ = 2W₂)
        W2 = scipy.sparse.linalg.splu((2j * wc * E - J).tocsc()).solve(0.5 * system.form(q, q))
        # −J W₀ = B(q, q̄)   (h₁₁ = W₀; J is invertible at a Hopf point)
        W0 = scipy.sparse.linalg.splu((-J).astype(complex).tocsc()).solve(system.form(q, qb))
    except RuntimeError:
        raise SingularPointError(f"{system.name}: J or 2iωE − J is singular at the Hopf point "
                                 f"{system.parameter} = {pc:.10g} (a resonance)") from None
    R = system.form(qb, W2) + system.form(q, W0) + 0.5 * system.form(q, q, qb)
    b = complex(psi @ R)
    return SparseNormalForm(q=q, psi=psi, a=a, b=b, b_scale=float(np.sum(np.abs(psi * R))))


def sparse_quintic(system: SparseSystem, pc: float, wc: float, nf: SparseNormalForm,
                   normalise: int) -> tuple[complex, float]:
    """(c, Σ|ψ_i r_i|): the quintic coefficient c of dA/dT = … + bA|A|² + cA|A|⁴ (q[normalise] = 1;
    Λ₅ = 2 Re c, Kuznetsov's l₂ = Re c/⟨q, q⟩²) and the size of the terms whose sum it is.

    The recursion of :func:`landau.derivation.fredholm.quintic_coefficient` (the Fredholm condition
    at each monomial z^j z̄^k up to z³z̄², h₂₁ with its ``normalise`` component zero) with the forms
    D₂…D₅ of the system and sparse LU solves:

        (i(j − k)ωE − J) h_{jk} = [F(H)]_{jk} − E [H_z ż + H_z̄ dz̄/dt]_{jk, nonlinear}

    (Kuznetsov 2004 §8.7, the generalised-Hopf coefficients; the singular systems at j − k = 1
    bordered as for q: [[iωE − J, Eq], [e_nᵀ, 0]]).  Needs the forms to fifth order.
    """
    from landau.derivation.fredholm import _faa_terms

    n = system.n
    E = scipy.sparse.diags(system.mass).tocsc()
    J = system.jacobian(pc)
    q, psi = nf.q, nf.psi
    en = scipy.sparse.csc_matrix(([1.0], ([0], [normalise])), shape=(1, n))
    bordered = scipy.sparse.linalg.splu(scipy.sparse.bmat(
        [[(1j * wc * E - J).tocsc(), scipy.sparse.csc_matrix((E @ q)[:, None])], [en, None]]).tocsc())
    lus: dict[int, Any] = {}
    h: dict[tuple[int, int], np.ndarray] = {(1, 0): q, (0, 1): q.conj()}
    coef: dict[tuple[int, int], complex] = {}
    for (j, k) in [(2, 0), (1, 1), (3, 0), (2, 1), (3, 1), (2, 2), (3, 2)]:
        rhs = np.zeros(n, dtype=complex)
        for ms, weight in _faa_terms((j, k), [m for m in h if m[0] <= j and m[1] <= k], 5):
            rhs += system.form(*(h[m] for m in ms)) / weight
        corr = np.zeros(n, dtype=complex)
        for (mm1, mm), cm in coef.items():
            for (a, b), vec in h.items():
                if (a, b) in ((1, 0), (0, 1)):
                    continue
                if a > 0 and (a + mm1 - 1, b + mm) == (j, k):
                    corr += vec * cm * a
                if b > 0 and (a + mm, b + mm1 - 1) == (j, k):
                    corr += vec * np.conj(cm) * b
        rhs -= E @ corr
        m = j - k
        if m == 1:
            c = complex(psi @ rhs)          # ψ E q = 1
            coef[(j, k)] = c
            if (j, k) == (3, 2):
                return c, float(np.sum(np.abs(psi * rhs)))
            # [[iωE − J, Eq], [e_nᵀ, 0]] (h, s) = (rhs − c E q, 0): h₂₁ with h[normalise] = 0
            sol = bordered.solve(np.concatenate([rhs - c * (E @ q), [0.0]]))[:n]
        else:
            if m not in lus:
                lus[m] = scipy.sparse.linalg.splu((1j * m * wc * E - J).astype(complex).tocsc())
            # (i(j − k)ωE − J) h_{jk} = rhs
            sol = lus[m].solve(rhs)
        h[(j, k)] = sol
        if j != k:
            h[(k, j)] = sol.conj()
    raise AssertionError("the recursion ends at z³z̄²")


def resolution(value: float, scale: float) -> str:
    """"zero" (|value| ≤ :data:`ZERO_REL`·scale: round-off), "unresolved" (below :data:`RESOLVED_REL`·scale)
    or "resolved": the float64 verdict on a coefficient summed from terms of total size ``scale``."""
    if not abs(value) > ZERO_REL * scale:
        return "zero"
    return "unresolved" if not abs(value) > RESOLVED_REL * scale else "resolved"


def with_fifth_order(res: HopfResult, nf: SparseNormalForm, system5: SparseSystem, degenerate: bool) -> HopfResult:
    """``res`` with Λ₅ = 2 Re c and l₂ = Re c/⟨q, q⟩² (:func:`sparse_quintic`, forms to fifth order in
    ``system5``); where ``degenerate`` (Λ zero to round-off), Λ = l₁ = Re c₁ = 0 and the verdict of
    the next order in ``extra`` as the general engine gives it (``criticality_next_order``,
    ``degenerate_at_every_order_computed``)."""
    from dataclasses import replace

    from landau.derivation.hopf import Criticality

    idx = system5.states.index(res.normalise)
    c, scale = sparse_quintic(system5, res.p_c, res.omega_c, nf, idx)
    qq = float(np.sum(np.abs(nf.q) ** 2))
    verdict = resolution(2 * c.real, 2 * scale)
    lam5 = 0.0 if verdict == "zero" else 2 * c.real
    extra = dict(res.extra)
    extra["Lambda5_scale"] = 2 * scale
    out = replace(res, Lambda5=lam5, l2=lam5 / 2 / qq ** 2, extra=extra)
    if not degenerate:
        return out
    extra["criticality_next_order"] = Criticality.from_sign(lam5).value if verdict == "resolved" else "degenerate"
    extra["degenerate_at_every_order_computed"] = verdict != "resolved"
    c1 = None if res.c1 is None else complex(0.0, res.c1.imag)
    return replace(out, Lambda=0.0, l1=0.0, c1=c1, extra=extra)


def _check_double(system: SparseSystem, a: float, b: float) -> None:
    """Where Newton fails: a double crossing (two rightmost eigenvalues equal to round-off at the
    bracket's end, e.g. identical uncoupled blocks) is named as such."""
    a, b = _bisect(system, a, b, 1e-12)
    lam = spectrum(system, b)
    i = int(np.argmax(lam.real * (lam.imag > 0)))
    near = np.count_nonzero((np.abs(lam - lam[i]) <= 1e-8 * abs(lam[i])) & (lam.imag > 0))
    if near >= 2:
        raise NonSimpleHopfError(f"{system.name}: {near} complex pairs cross the imaginary axis together at "
                                 f"{system.parameter} = {b:.12g} (to float64's resolution): a double, non-simple Hopf "
                                 "crossing, where no single-mode amplitude equation applies")


def _check_first(system: SparseSystem, pc: float, wc: float) -> bool:
    """Whether the located pair is the only one on or right of the imaginary axis at p_c; refuse a
    non-simple crossing (a second eigenvalue at iω_c: e.g. identical uncoupled blocks), where no
    single-mode amplitude equation applies."""
    lam = spectrum(system, pc)
    on = (np.abs(lam - 1j * wc) <= DOUBLE_REL * wc) | (np.abs(lam + 1j * wc) <= DOUBLE_REL * wc)
    near = np.count_nonzero(np.abs(lam - 1j * wc) <= DOUBLE_REL * wc)
    if near >= 2:
        raise NonSimpleHopfError(f"{system.name}: {near} eigenvalues cross the imaginary axis together at "
                                 f"{system.parameter} = {pc:.12g}: a double, non-simple Hopf crossing, where no "
                                 "single-mode amplitude equation applies")
    # float64 eigenvalues carry an absolute error of about eps·‖J‖
    tol = 1e-12 * float(np.max(np.abs(lam)))
    return not np.any(lam[~on].real > tol)


def sparse_hopf(system: SparseSystem, hi: float, lo: float, choose_normalise=None,
                params: dict | None = None) -> tuple[HopfResult, SparseNormalForm]:
    """The first Hopf point as p decreases from ``hi`` and its amplitude equation (the numeric route).

    Parameters
    ----------
    system : SparseSystem
    hi, lo : float
        The scan: from ``hi`` (steady state stable) down to ``lo``.
    choose_normalise : callable, optional
        ``choose_normalise(q) -> index`` of the component of the critical mode normalised to 1
        (default: the largest).
    params : dict, optional
        The parameters reported with the result.

    Returns
    -------
    (HopfResult, SparseNormalForm)
        The result in the general engine's convention, ``extra["route"] = "numeric"``.
    """
    a, b = first_crossing(system, hi, lo)
    rel = BRACKET_REL
    while True:
        w0, q0 = _start(system, b)
        try:
            pc, wc, q, floor = newton_hopf(system, b, w0, q0)
        except SingularPointError:
            _check_double(system, a, b)
            raise
        # Newton from the rightmost pair just past the crossing: where another pair crossed in the
        # bracket too, it may find that one (unstable pairs remain at p_c): the bracket is narrowed
        if b * (1 - 1e-9) <= pc <= a * (1 + 1e-9) and _check_first(system, pc, wc):
            break
        if rel < 1e-9:
            raise SingularPointError(f"{system.name}: Newton's method from the first crossing in "
                                     f"[{b:.12g}, {a:.12g}] found {system.parameter} = {pc:.12g} with another pair "
                                     "unstable there")
        rel *= 1e-3
        a, b = _bisect(system, a, b, rel)
    idx = int(np.argmax(np.abs(q))) if choose_normalise is None else int(choose_normalise(q))
    nf = sparse_normal_form(system, pc, wc, q / q[idx], idx)
    a, b = nf.a, nf.b
    if not abs(a.real) > 1e-12 * abs(a):
        raise SingularPointError(f"{system.name}: at {system.parameter} = {pc:.10g} the pair ±i·{wc:.6g} touches "
                                 "the imaginary axis without crossing it (Re dλ/dp = 0): not a Hopf bifurcation")
    qq = float(np.sum(np.abs(nf.q) ** 2))
    res = HopfResult(system=system.name, parameter=system.parameter, p_c=pc, omega_c=wc,
                     equilibrium=tuple(float(x) for x in system.equilibrium), dlambda_dp=a,
                     Lambda=2 * b.real, chi=2 * b.imag, convention=GENERAL, normalise=system.states[idx],
                     l1=b.real / qq / wc, c1=b / qq, params=dict(params or {}),
                     extra={"route": "numeric", "newton_floor": floor})
    return res, nf


__all__ = ["SparseNormalForm", "eigenvector", "first_crossing", "newton_hopf", "sparse_hopf", "sparse_normal_form",
           "resolution", "sparse_quintic", "spectrum", "with_fifth_order"]
