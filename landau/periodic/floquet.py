"""Floquet multipliers of a cycle from its collocation system: the product of the condensed interval transfers.

The variational equation of the cycle in the rescaled time, v′ = T A(t) v with A = ∂f/∂y(y(t); p),
discretised exactly as the cycle is (:mod:`.collocation`), is on interval j the m·n linear equations

    Σ_k [ (D_ck / h_j) I − T A(ζ_jc) L_ck ] v_{j,k} = 0,   c = 1…m,                         (1)

in the m + 1 node values v_{j,0…m}. Condensing the m interior/end values gives the transfer
matrix v_{j,m} = M_j v_{j,0}; the monodromy is M = M_{N−1} ⋯ M_0 and its eigenvalues are the
Floquet multipliers (the approach of AUTO's condensation of parameters, Doedel et al. 1991;
Fairgrieve & Jepson 1991 discuss the product's conditioning). One multiplier is 1 in exact
arithmetic (the direction y′ of the flow): the multiplier nearest 1 is reported separately as the
*trivial* one, and its distance from 1 is an accuracy check of the discretisation.

Limitation: the explicit product loses the smallest multipliers' relative accuracy when the
spread |μ_max/μ_min| approaches 1/ε_machine (very strongly attracting or repelling cycles); the
largest ones, which decide stability, are unaffected.

References
----------
Fairgrieve, T. F. & Jepson, A. D. (1991). O.K. Floquet multipliers. SIAM J. Numer. Anal. 28, 1446–1462.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from landau.periodic.collocation import Mesh, _basis, at_points
from landau.periodic.problem import CycleProblem


def interval_systems(problem: CycleProblem, mesh: Mesh, Y: np.ndarray, T: float, p: float) -> np.ndarray:
    """The matrices G_j of (1), shape (N, m·n, (m+1)·n)."""
    n, N, m = problem.n, mesh.ntst, mesh.m
    _, _, L, D = _basis(m)
    yc, _ = at_points(mesh, Y)
    A = np.asarray(problem.jac(yc, p), dtype=float).reshape(n, n, N, m)   # A[a, b, j, c]
    eye = np.eye(n)
    G = (D[None, :, None, :, None] / mesh.h[:, None, None, None, None] * eye[None, None, :, None, :]
         - T * np.einsum("abjc,ck->jcakb", A, L))
    return G.reshape(N, m * n, (m + 1) * n)


def transfers(G: np.ndarray, n: int) -> np.ndarray:
    """The interval transfers: for each j the (m·n × n) matrix X_j with v_{j,1…m} = X_j v_{j,0}."""
    # (1) split as G0 v_{j,0} + G1 (v_{j,1}, …, v_{j,m}) = 0, so  G1 X_j = −G0  (one batched solve)
    G0, G1 = G[:, :, :n], G[:, :, n:]
    return np.linalg.solve(G1, -G0)


def monodromy(problem: CycleProblem, mesh: Mesh, Y: np.ndarray, T: float, p: float) -> np.ndarray:
    """M = M_{N−1} ⋯ M_0 (n × n)."""
    n = problem.n
    X = transfers(interval_systems(problem, mesh, Y, T, p), n)
    M = np.eye(n)
    for Mj in X[:, -n:, :]:
        M = Mj @ M
    return M


def propagate(problem: CycleProblem, mesh: Mesh, Y: np.ndarray, T: float, p: float, v0: np.ndarray) -> np.ndarray:
    """The solution of the discretised variational equation (1) from v(0) = v0: node values (n, N·m + 1)."""
    n, m = problem.n, mesh.m
    X = transfers(interval_systems(problem, mesh, Y, T, p), n)
    v0 = np.asarray(v0)
    out = [v0]
    v = v0
    for Xj in X:
        inner = (Xj @ v).reshape(m, n)
        out.extend(inner)
        v = inner[-1]
    return np.array(out).T


@dataclass(frozen=True)
class Multipliers:
    """The Floquet multipliers of one cycle.

    ``nontrivial`` holds the n − 1 multipliers other than the trivial one, sorted by decreasing
    modulus; ``trivial`` is the one nearest 1 (|trivial − 1| is an accuracy check).
    """

    all: np.ndarray
    trivial: complex
    nontrivial: np.ndarray

    @property
    def stable(self) -> bool:
        """True if every nontrivial multiplier lies inside the unit circle."""
        return bool(np.all(np.abs(self.nontrivial) < 1.0))

    @property
    def unstable_count(self) -> int:
        return int(np.sum(np.abs(self.nontrivial) > 1.0))


def multipliers_of(M: np.ndarray) -> Multipliers:
    """Split the eigenvalues of the monodromy into the trivial one and the others."""
    mu = np.linalg.eigvals(M).astype(complex)
    i = int(np.argmin(np.abs(mu - 1.0)))
    rest = np.delete(mu, i)
    rest = rest[np.argsort(-np.abs(rest), kind="stable")]
    return Multipliers(mu, complex(mu[i]), rest)


def floquet(problem: CycleProblem, mesh: Mesh, Y: np.ndarray, T: float, p: float) -> Multipliers:
    """The Floquet multipliers of the cycle (Y, T) at p."""
    return multipliers_of(monodromy(problem, mesh, Y, T, p))
