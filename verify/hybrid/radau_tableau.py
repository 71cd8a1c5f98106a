"""The coefficients of the three-stage Radau IIA method (order 5) and their eigen-split.

The collocation nodes, the Butcher matrix A, the embedded-error weights of radau5 and the dense
output's inverse Vandermonde matrix (Hairer & Wanner 1996, *Solving ODEs II*, Sec. IV.5 and
IV.8), and the transformation A⁻¹ = T·diag(γ, [[α, −β], [β, α]])·T⁻¹ that splits the Newton
system of a step into one real and one complex n × n system (:func:`split_coefficients`,
eq. (8.15)–(8.18)).  The loop of :mod:`landau.verify.hybrid.radau` reads them as constants; like
:mod:`landau.verify.hybrid.dop853_tableau` for DOP853, this module holds numbers, not steps.

References
----------
Hairer, E., Wanner, G. (1996). Solving Ordinary Differential Equations II, 2nd ed., Springer,
Sec. IV.5 (Radau IIA) and IV.8 (implementation).
"""

from __future__ import annotations

import math

import numpy as np

from landau.errors import InputError

__all__ = ["A_RADAU", "ALPHA_SPLIT", "BETA_SPLIT", "C_NODES", "E_ERR", "GAMMA_SPLIT", "MU_REAL", "NODES", "SQ6",
           "TI_ROWS", "TI_SPLIT", "T_ROWS", "T_SPLIT", "VINV", "split_coefficients"]

SQ6 = math.sqrt(6.0)
#: collocation nodes c_i and Butcher matrix A of Radau IIA (order 5)
C_NODES = np.array([(4 - SQ6) / 10, (4 + SQ6) / 10, 1.0])
A_RADAU = np.array([
    [(88 - 7 * SQ6) / 360, (296 - 169 * SQ6) / 1800, (-2 + 3 * SQ6) / 225],
    [(296 + 169 * SQ6) / 1800, (88 + 7 * SQ6) / 360, (-2 - 3 * SQ6) / 225],
    [(16 - SQ6) / 36, (16 + SQ6) / 36, 1.0 / 9],
])
#: the real eigenvalue of A⁻¹ (γ₀⁻¹) and the embedded-error weights e_i (radau5)
MU_REAL = 3 + 3 ** (2 / 3) - 3 ** (1 / 3)
E_ERR = np.array([-13 - 7 * SQ6, -13 + 7 * SQ6, -1.0]) / 3
#: Z_i = Σ_j Q_j c_i^j  →  Q = VINV·Z (dense output y(t+xh) = y + Σ Q_j x^j)
VINV = np.linalg.inv(np.array([[c ** j for j in (1, 2, 3)] for c in C_NODES]))

#: the nodes the stage equations are evaluated at: C_NODES to 16 digits (the first differs from
#: (4 − √6)/10 in the last bit; the code has used these since its first version)
NODES = np.array([0.1550510257216822, 0.6449489742783178, 1.0])


def split_coefficients(A):
    """The transformation of the 3-stage Newton system to one real and one complex n × n system.

    A⁻¹ = T·Λ·T⁻¹ with Λ = diag(γ, [[α, −β], [β, α]]): γ the real eigenvalue of A⁻¹ and
    α ± iβ (β > 0) its complex pair (Hairer & Wanner 1996, IV.8, eq. (8.15)–(8.18)).  With
    W = T⁻¹Z the stage equations Z = h(A ⊗ I)F decouple, for a constant Jacobian, into
    (γ/h·I − J)·ΔW₁ = … and ((α + iβ)/h·I − J)·(ΔW₂ + iΔW₃) = ….

    Parameters
    ----------
    A : ndarray, shape (3, 3)
        Butcher matrix of a 3-stage method whose A⁻¹ has one real eigenvalue and a complex pair.

    Returns
    -------
    (T, TI, gamma, alpha, beta) : (ndarray, ndarray, float, float, float)
    """
    A = np.asarray(A, dtype=float)
    if A.shape != (3, 3):
        raise InputError(f"split_coefficients: a 3 x 3 Butcher matrix is needed, got shape {A.shape}")
    AI = np.linalg.inv(A)
    lam, vec = np.linalg.eig(AI)
    ir = int(np.argmin(np.abs(np.imag(lam))))
    ic = int(np.argmin(np.imag(lam)))          # the eigenvalue α − iβ of the pair
    if ic == ir or abs(np.imag(lam[ic])) == 0.0:
        raise InputError("split_coefficients: A⁻¹ has no complex eigenvalue pair")
    gamma = float(np.real(lam[ir]))
    alpha, beta = float(np.real(lam[ic])), float(-np.imag(lam[ic]))
    u = vec[:, ic]
    T = np.column_stack([np.real(vec[:, ir]), np.real(u), np.imag(u)])
    TI = np.linalg.inv(T)
    Lam = np.array([[gamma, 0.0, 0.0], [0.0, alpha, -beta], [0.0, beta, alpha]])
    if not np.allclose(T @ Lam @ TI, AI, rtol=1e-12, atol=1e-12 * np.abs(AI).max()):
        raise InputError("split_coefficients: the eigen-decomposition of A⁻¹ does not reproduce it")
    return T, TI, gamma, alpha, beta


#: A⁻¹ = T·diag(γ, [[α, −β], [β, α]])·T⁻¹, computed from :data:`A_RADAU` (:func:`split_coefficients`)
T_SPLIT, TI_SPLIT, GAMMA_SPLIT, ALPHA_SPLIT, BETA_SPLIT = split_coefficients(A_RADAU)

#: T and T⁻¹ as tuples of rows: the loop reads them as constants (an element of a constant array
#: costs numba an indexing operation to type and lower at the first build)
T_ROWS = tuple(tuple(float(v) for v in row) for row in T_SPLIT)
TI_ROWS = tuple(tuple(float(v) for v in row) for row in TI_SPLIT)
