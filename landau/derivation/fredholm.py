"""The multiple-scales expansion and its Fredholm solvability condition (field-generic).

For E·ẏ = f(y; p) with a Hopf point (p_c, ±iω) write p = p_c + ε²p₂, T = ε²t,
y = y₀ + εy₁ + ε²y₂ + ε³y₃ + … (Putelat et al. 2010, eqs 9–10).  With
A = iωE − J and the multilinear forms B, C of the second and third derivatives:

* O(ε):  y₁ = A(T) e^{iωt} q + c.c.,  A q = 0,  q_normalise = 1  (u₀ = (1, z), eq. 11)
* O(ε²): y₂ = A² e^{2iωt} W₂ + c.c. + |A|² W₀,
         (2iωE − J) W₂ = ½ B(q, q),  −J W₀ = B(q, q̄)           (eq. 12)
* O(ε³): resonant forcing e^{iωt}[−E q A_T + p₂ A (J_p q − B(q, J⁻¹f_p)) + A|A|² R],
         R = B(q̄, W₂) + B(q, W₀) + ½ C(q, q, q̄)                (eqs 13–16)
  Fredholm: ψ·(forcing) = 0 with ψ A = 0 (left null vector u₀*), hence
         δ A_T = α A + β A|A|²,  δ = ψEq, α = p₂ ψ(J_p q − …), β = ψR   (eqs 17–19)

* O(ε⁴), O(ε⁵) (:func:`quintic_coefficient`): the same condition one order further gives
  dA/dT = … + c A|A|⁴; landau reports Λ₅ = 2 Re c with the critical mode's ``normalise``
  component equal to 1 (Kuznetsov's l₂ = Re c₂ with ⟨q, q⟩ = 1 is Λ₅|q_n|⁴/2).

The functions here work on :class:`~landau.support.cx.Cx` numbers over any real field, so the
same code gives closed forms (sympy atoms) and 50-digit numbers (mpmath).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable, Mapping, Sequence

from landau.derivation.jets import multilinear
from landau.support.cx import Cx, as_cx, cx_is_zero, solve


@dataclass(frozen=True)
class FredholmVectors:
    """Right null vector q (q[normalise] = 1) and left null vector ψ of A = iωE − J."""

    q: list[Cx]
    psi: list[Cx]
    delta: Cx  # ψ E q
    normalise: int = -1  # the component of q fixed to 1
    drop_row: int = -1  # the redundant row of iωE − J (ψ[drop_row] = 1)


def _pencil(J: Sequence[Sequence[Any]], E: Sequence[Any], s: Any) -> list[list[Cx]]:
    """s·iE − J as a Cx matrix (s real: the multiple of iω)."""
    n = len(E)
    return [[Cx(-J[i][j], (s * E[i]) if i == j else 0 * s) for j in range(n)] for i in range(n)]


def _minor(A, drop_row: int, drop_col: int):
    n = len(A)
    return [[A[i][j] for j in range(n) if j != drop_col] for i in range(n) if i != drop_row]


def null_vectors(J, E, w, normalise: int, drop_row: int, drop_col: int) -> FredholmVectors:
    """q with (iωE − J)q = 0, q[normalise] = 1 (row ``drop_row`` is the redundant one);
    ψ with ψ(iωE − J) = 0, ψ[drop_row] = 1 (column ``drop_col`` is the redundant one)."""
    n = len(E)
    A = _pencil(J, E, w)
    rows = [i for i in range(n) if i != drop_row]
    cols = [j for j in range(n) if j != normalise]
    q_rest = solve([[A[i][j] for j in cols] for i in rows], [-A[i][normalise] for i in rows]) if cols else []
    q: list[Cx] = [Cx(0, 0)] * n
    q[normalise] = as_cx(1 + 0 * w)
    for j, val in zip(cols, q_rest, strict=True):
        q[j] = val
    # ψ A = 0  ⇔  Aᵀ ψᵀ = 0 (no conjugation: ψ is a row vector, ⟨p, ·⟩ = ψ·)
    prow = [i for i in range(n) if i != drop_row]
    pcol = [j for j in range(n) if j != drop_col]
    psi_rest = solve([[A[i][j] for i in prow] for j in pcol], [-A[drop_row][j] for j in pcol]) if prow else []
    psi: list[Cx] = [Cx(0, 0)] * n
    psi[drop_row] = as_cx(1 + 0 * w)
    for i, val in zip(prow, psi_rest, strict=True):
        psi[i] = val
    delta = Cx(0, 0)
    for i in range(n):
        if not cx_is_zero(psi[i]) and not cx_is_zero(q[i]) and E[i] != 0:
            delta = delta + psi[i] * q[i] * E[i]
    return FredholmVectors(q, psi, delta, normalise, drop_row)


def row_dot(psi: Sequence[Cx], x: Sequence[Cx]) -> Cx:
    out = Cx(0, 0)
    for a, b in zip(psi, x, strict=True):
        if not (cx_is_zero(a) or cx_is_zero(b)):
            out = out + a * b
    return out


def linear_coefficient(vec: FredholmVectors, J, Jp, fp, B2) -> Cx:
    """α/δ per unit p₂ (eq. 18 generalised): ψ(J_p q − B(q, J⁻¹ f_p)) / δ."""
    n = len(vec.q)
    Jpq = [Cx(0, 0)] * n
    for i in range(n):
        for j in range(n):
            if Jp[i][j] != 0 and not cx_is_zero(vec.q[j]):
                Jpq[i] = Jpq[i] + vec.q[j] * Jp[i][j]
    if any(f != 0 for f in fp):
        # the equilibrium moves with p: y₀(p_c + ε²p₂) = y₀ − ε² p₂ J⁻¹ f_p
        shift = solve([[as_cx(J[i][j]) for j in range(n)] for i in range(n)], [as_cx(f) for f in fp])
        Bq = multilinear(B2, [vec.q, shift], n)
        Jpq = [a - b for a, b in zip(Jpq, Bq, strict=True)]
    return row_dot(vec.psi, Jpq) / vec.delta


def cubic_coefficient(vec: FredholmVectors, J, E, w, B2, C3, half) -> Cx:
    """β/δ (eqs 15–19): ψ[B(q̄, W₂) + B(q, W₀) + ½C(q, q, q̄)] / δ."""
    n = len(vec.q)
    q = vec.q
    qb = [z.conj() for z in q]
    Bqq = multilinear(B2, [q, q], n)
    Bqqb = multilinear(B2, [q, qb], n)
    A2 = _pencil(J, E, 2 * w)
    W2 = solve(A2, [z * half for z in Bqq])
    W0 = solve([[Cx(-J[i][j], 0 * w) for j in range(n)] for i in range(n)], Bqqb)
    R1 = multilinear(B2, [qb, W2], n)
    R2 = multilinear(B2, [q, W0], n)
    R3 = multilinear(C3, [q, q, qb], n)
    R = [a + b + c * half for a, b, c in zip(R1, R2, R3, strict=True)]
    return row_dot(vec.psi, R) / vec.delta


def float64_drop(A, normalise: int) -> tuple[int, int] | None:
    """Numeric mode, from float64: the (row, column) of :func:`best_drop` without its 2n determinants at
    the working precision, or None where float64 cannot tell (then :func:`best_drop`).

    For A = iωE − J of rank n − 1, adj A = c q pᵀ (pᴴA = 0, Aq = 0), so |minor(A, i, j)| ∝ |p_i||q_j|:
    the best-conditioned minors are those of the largest |p_i| and |q_j| (ties to the first index),
    read from the SVD of A in float64 (O(n³)).  None where A does not fit float64, where its smallest
    singular value is not below 1e-6 of the next (no clear one-dimensional null space), or where
    |q_normalise| ≤ 1e-8 max|q| (the working precision decides whether q can be scaled there).  For a
    chain of a dozen blocks the determinants took minutes.
    """
    import numpy as np

    try:
        a = np.array([[complex(float(z.re), float(z.im)) for z in row] for row in A])
        if not np.all(np.isfinite(a)):
            return None
        # the null vectors: the left and right singular vectors of the smallest singular value
        u, sv, vh = np.linalg.svd(a)
    except (np.linalg.LinAlgError, OverflowError, ValueError):
        return None
    if len(sv) < 2 or not sv[-1] < 1e-6 * sv[-2]:
        return None
    p, q = np.abs(u[:, -1]), np.abs(vh[-1])
    if not q[normalise] > 1e-8 * q.max():
        return None
    r, c = (int(np.flatnonzero(m >= (1 - 1e-8) * m.max())[0]) for m in (p, q))
    return r, c


def best_drop(A: Sequence[Sequence[Cx]], normalise: int, det: Callable[[list], float]) -> tuple[int, int]:
    """Numeric mode: the (row, column) whose removal leaves the best-conditioned minors."""
    n = len(A)
    r = max(range(n), key=lambda i: det(_minor(A, i, normalise)))
    c = max(range(n), key=lambda j: det(_minor(A, r, j)))
    return r, c


# --------------------------------------------------------------------------------------
# fifth order
@dataclass(frozen=True)
class QuinticCoefficients:
    """Cubic and quintic coefficients of dA/dT = b A|A|² + c A|A|⁴ at the Hopf point.

    ``b`` equals :func:`cubic_coefficient` (β/δ); ``c`` is the quintic coefficient with the
    critical mode's ``normalise`` component equal to 1 and the gauge choice that the
    first-harmonic correction h₂₁ (the e^{iωt}A|A|² part of y₃) has that component zero.
    Re c does not depend on that choice (a near-identity change A → A + κA|A|² changes c
    by 2b Re κ − 2κ Re b, whose real part is zero); Im c does.
    """

    b: Cx
    c: Cx


def _faa_terms(target: tuple[int, int], monomials: Sequence[tuple[int, int]], max_order: int):
    """Multisets of ≥ 2 monomials (from ``monomials``) whose exponents add up to ``target``.

    Yields (multiset, 1/Π multiplicity!) — the weight of the multiset in (1/m!)·Dₘ[H, …, H]
    with H = Σ h_{jk} z^j z̄^k (no factorials in H)."""
    mons = sorted(monomials)

    def rec(start, remaining, chosen):
        if remaining == (0, 0):
            if len(chosen) >= 2:
                yield list(chosen)
            return
        if len(chosen) == max_order:
            return
        for i in range(start, len(mons)):
            a, b = mons[i]
            if a <= remaining[0] and b <= remaining[1]:
                chosen.append(mons[i])
                yield from rec(i, (remaining[0] - a, remaining[1] - b), chosen)
                chosen.pop()

    for ms in rec(0, target, []):
        weight = 1
        for mon in set(ms):
            weight *= math.factorial(ms.count(mon))
        yield ms, weight


def quintic_coefficient(vec: FredholmVectors, J, E, w, tensors: Mapping[int, Mapping[tuple, Any]],
                        one) -> QuinticCoefficients:
    """b and c of the amplitude equation to fifth order, by the Fredholm condition order by order.

    With p = p_c, y = Σ h_{jk} z^j z̄^k (z = εA e^{iωt}, h₁₀ = q, h₀₁ = q̄) and
    dA/dt = b A|A|² + c A|A|⁴ (physical amplitude, i.e. ε absorbed), E·ẏ = f(y) gives at each
    monomial z^j z̄^k (j ≥ k, the others are complex conjugates)

        (i(j − k)ωE − J) h_{jk} = [F(H)]_{jk} − E [H_z ż + H_z̄ dz̄/dt]_{jk, nonlinear},

    F(y) = Σₘ Dₘ[y, …, y]/m! (``tensors[m]`` the m-th derivative tensor, m = 2…5).  At the
    resonant monomials z²z̄ and z³z̄² the right-hand side contains E q b (resp. E q c):
    the Fredholm condition ψ·(rhs) = 0 (ψ the left null vector) fixes b = ψ·R₂₁/δ and
    c = ψ·R₃₂/δ, δ = ψEq; h₂₁ is then the solution with the ``normalise`` component zero.

    The functions work over any real field (``one`` is its unit: sympy Integer(1) for
    closed forms, mpmath.mpf(1) for numbers).
    """
    n = len(vec.q)
    q = vec.q
    if vec.drop_row < 0:
        raise ValueError("quintic_coefficient needs the vectors of null_vectors (drop_row unknown)")
    h: dict[tuple[int, int], list[Cx]] = {(1, 0): q, (0, 1): [z.conj() for z in q]}
    coef: dict[tuple[int, int], Cx] = {}          # {(m+1, m): normal-form coefficient}
    zero = Cx(0 * one, 0 * one)
    order = [(2, 0), (1, 1), (3, 0), (2, 1), (3, 1), (2, 2), (3, 2)]
    for (j, k) in order:
        rhs = [zero] * n
        for ms, weight in _faa_terms((j, k), [m for m in h if m[0] <= j and m[1] <= k], 5):
            tens = tensors.get(len(ms), {})
            if not tens:
                continue
            term = multilinear(tens, [h[m] for m in ms], n)
            scale = one / weight
            rhs = [r + t * scale for r, t in zip(rhs, term, strict=True)]
        # nonlinear part of H_z ż + H_z̄ dz̄/dt: a·h_{ab} c_m z^{a-1+m+1} z̄^{b+m} + b·h_{ab} c̄_m z^{a+m} z̄^{b-1+m+1}
        corr = [zero] * n
        for (mm1, mm), cm in coef.items():
            for (a, b), vecab in h.items():
                if (a, b) in ((1, 0), (0, 1)):
                    continue
                if a > 0 and (a + mm1 - 1, b + mm) == (j, k):
                    corr = [x + y * cm * a for x, y in zip(corr, vecab, strict=True)]
                if b > 0 and (a + mm, b + mm1 - 1) == (j, k):
                    corr = [x + y * cm.conj() * b for x, y in zip(corr, vecab, strict=True)]
        rhs = [r - x * E[i] if E[i] != 0 else r for i, (r, x) in enumerate(zip(rhs, corr, strict=True))]
        l = j - k
        if l == 1:
            cval = row_dot(vec.psi, rhs) / vec.delta
            coef[(j, k)] = cval
            if (j, k) == (3, 2):
                break
            rhs = [r - q[i] * cval * E[i] if E[i] != 0 else r for i, r in enumerate(rhs)]
            A = _pencil(J, E, w)
            rows = [i for i in range(n) if i != vec.drop_row]
            cols = [c for c in range(n) if c != vec.normalise]
            part = solve([[A[i][c] for c in cols] for i in rows], [rhs[i] for i in rows]) if cols else []
            sol = [zero] * n
            for c, val in zip(cols, part, strict=True):
                sol[c] = val
        else:
            sol = solve(_pencil(J, E, l * w), rhs)
        h[(j, k)] = sol
        if j != k:
            h[(k, j)] = [z.conj() for z in sol]
    return QuinticCoefficients(coef[(2, 1)], coef[(3, 2)])
