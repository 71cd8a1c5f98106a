"""The exact determinant of a sparse matrix over a ring, by its sparsity: det(λE − J) of a spring–block.

The linear operator λE − J of a spring–block with n state variables is block-arrow shaped: the
rates of the state variables φᵢ depend on the slip rate u and on φᵢ itself (the Dieterich family
of n independent state variables), the slip X only on u, and only the momentum row u sees every
variable.  The indices S = {X, φ₁, …, φₙ} form an independent set of the off-diagonal sparsity
graph (no entry couples two of them); the core m = {u} is what is left.  In a permutation σ of
the Leibniz sum every index of S is either fixed (it contributes its diagonal entry dᵢ) or sent
into the core (its row and column have no other entry), so at most |m| indices of S move, and

    det B = Σ_{T ⊆ S, |T| ≤ |m|}  Π_{i ∈ S∖T} dᵢ · det B̃[m ∪ T],

where B̃[m ∪ T] is the principal submatrix on m ∪ T with the diagonal entries of T set to zero
(they would be fixed points).  For the arrow (|m| = 1) this is the Schur complement on the core,
det B = Π dᵢ · (B_uu − Σᵢ B_ui B_iu / dᵢ) with the division carried out exactly:

    det B = B_uu Π_{i ∈ S} dᵢ − Σ_{i ∈ S} B_ui B_iu Π_{j ∈ S, j ≠ i} dⱼ.

Only additions and multiplications of ring elements are used, so the result is the same exact
element that fraction-free (Bareiss) elimination returns; Bareiss's exact divisions of
multivariate polynomials in many atoms (one generator per derivative) were the cost of the
derivation for several state variables (21 CPU-s of the 8-state Dieterich law's 39).
"""

from __future__ import annotations

import itertools
from typing import Any, Sequence

#: the largest core for which the expansion over subsets is used (above it, fraction-free elimination)
MAX_CORE = 3


def independent_split(B: Sequence[Sequence[Any]], zero: Any) -> tuple[list[int], list[int]]:
    """(S, m): a maximal set S of indices no off-diagonal entry of ``B`` couples (greedy, fewest
    couplings first, ties by index), and the core m of the others."""
    n = len(B)
    adj = [{j for j in range(n) if j != i and (B[i][j] != zero or B[j][i] != zero)} for i in range(n)]
    S: list[int] = []
    for i in sorted(range(n), key=lambda i: (len(adj[i]), i)):
        if not adj[i] & set(S):
            S.append(i)
    S.sort()
    return S, [i for i in range(n) if i not in S]


def _leibniz(M: Sequence[Sequence[Any]], zero: Any, one: Any) -> Any:
    """det M by cofactor expansion along the first row (M small: at most 2·MAX_CORE rows), zero
    entries skipped; additions and multiplications only."""
    n = len(M)
    if n == 0:
        return one
    if n == 1:
        return M[0][0]
    out = zero
    for j in range(n):
        if M[0][j] == zero:
            continue
        minor = [[row[c] for c in range(n) if c != j] for row in M[1:]]
        term = M[0][j] * _leibniz(minor, zero, one)
        out = out + term if j % 2 == 0 else out - term
    return out


def _product(items: Sequence[Any], one: Any) -> Any:
    out = one
    for x in items:
        out = out * x
    return out


def det_by_sparsity(B: Sequence[Sequence[Any]], zero: Any, one: Any) -> Any | None:
    """det B exactly by the expansion over subsets of the independent set (module docstring), or
    None where the core is larger than :data:`MAX_CORE` or nothing is independent (the caller then
    eliminates).

    Parameters
    ----------
    B : sequence of sequences of ring elements
        A square matrix (rows of elements of one ring: sympy polynomial-ring elements, integers).
    zero, one : ring elements
        The ring's zero and unit.

    Returns
    -------
    ring element or None
    """
    S, m = independent_split(B, zero)
    if len(m) > MAX_CORE or len(S) < 2:
        return None
    # an index of S can move only when it couples to the core both ways
    movable = [i for i in S if any(B[i][c] != zero for c in m) and any(B[c][i] != zero for c in m)]
    out = zero
    for t in range(min(len(m), len(movable)) + 1):
        for T in itertools.combinations(movable, t):
            idx = [*m, *T]
            sub = [[zero if (r == c and r in T) else B[r][c] for c in idx] for r in idx]
            minor = _leibniz(sub, zero, one)
            if minor == zero:
                continue
            out = out + _product([B[i][i] for i in S if i not in T], one) * minor
    return out


__all__ = ["MAX_CORE", "det_by_sparsity", "independent_split"]
