"""The spring–block chain as numbers: its sparse Jacobian in k and its forms from one block's jets.

At steady sliding (X_i = u_i = 0, φ_i = φ_ss(V)) block i of :class:`~landau.systems.chain.SpringBlockChain`
contributes, in y = (X_1, u_1, φ_1…, X_2, …) with E = diag(1, M_i, 1…),

    Ẋ_i = u_i,   M_i u̇_i = −k X_i + k_c (X_{i−1} − 2X_i + X_{i+1}) − σ_i (μ(V + u_i, φ_i) − μ_ss),
    φ̇_i = rate(V + u_i, φ_i)

(the terms of a missing neighbour left out).  The springs are linear, so the Jacobian is the
block-tridiagonal J(k) = J₀ + k J₁ (J₁ = −1 in each (u_i, X_i) entry) and every higher derivative
is local: the law's jets D_m of g = (μ, rate) in w = (v, φ) (:func:`landau.laws.local_jets.law_jets`,
one evaluation for all blocks) applied to each block's (u_i, φ_i), the μ output scaled by −σ_i.

References
----------
Burridge, R. & Knopoff, L. (1967). Model and theoretical seismicity. Bull. Seismol. Soc. Am. 57,
341–371 (the chain of blocks).
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). J. Mech. Phys. Solids 58, 27–53, eq. (4) (one block).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Mapping

import numpy as np
import scipy.sparse

from landau.laws.local_jets import law_jets
from landau.systems.sparse import LocalNonlinearity, SparseSystem

if TYPE_CHECKING:
    from landau.systems.chain import SpringBlockChain


def chain_sparse_system(chain: SpringBlockChain, params: Mapping[str, float], order: int = 3) -> SparseSystem:
    """The chain at steady sliding as a :class:`SparseSystem` in the Hopf parameter k.

    Parameters
    ----------
    chain : SpringBlockChain
    params : mapping
        Every parameter by name, as :meth:`SpringBlockChain.resolve` gives them.
    order : int
        The highest order of the forms (3: B and C).

    Returns
    -------
    SparseSystem
    """
    law, N = chain.law, chain.blocks
    m = len(law.states)
    per = 2 + m
    n = per * N
    y0 = np.array(chain.equilibrium_values(params), dtype=float)
    phis = y0[2:per]
    lp = {p.name: float(params[p.name]) for p in law.parameters}
    D = law_jets(law, float(params["V"]), phis, lp, order)
    D1 = D[1]
    kc = float(params["k_coupling"])
    M = np.array([float(params[f"M_{i}"]) for i in range(1, N + 1)])
    sigma = np.array([float(params[f"sigma_{i}"]) for i in range(1, N + 1)])
    base = per * np.arange(N)
    X, u = base, base + 1
    rows: list[np.ndarray] = []
    cols: list[np.ndarray] = []
    vals: list[np.ndarray] = []

    def put(r, c, v):
        r, c = np.broadcast_arrays(np.asarray(r), np.asarray(c))
        rows.append(r.ravel())
        cols.append(c.ravel())
        vals.append(np.broadcast_to(np.asarray(v, dtype=float), r.shape).ravel())

    put(X, u, 1.0)                                           # Ẋ_i = u_i
    neighbours = np.full(N, 2.0)
    if N > 1:
        neighbours[[0, -1]] = 1.0
        put(u[:-1], X[1:], kc)                               # k_c X_{i+1}
        put(u[1:], X[:-1], kc)                               # k_c X_{i−1}
    else:
        neighbours[:] = 0.0
    put(u, X, -kc * neighbours)
    w_idx = np.stack([u, *(base + 2 + j for j in range(m))], axis=1)   # (u_i, φ_i…): the law's w − w₀
    # the law's first derivatives: −σ_i ∂μ/∂w in the u row, ∂rate_j/∂w in the φ_j rows
    put(u[:, None], w_idx, -sigma[:, None] * D1[0][None, :])
    for j in range(m):
        put((base + 2 + j)[:, None], w_idx, np.broadcast_to(D1[1 + j][None, :], w_idx.shape))
    J0 = scipy.sparse.csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
    J1 = scipy.sparse.csc_matrix((-np.ones(N), (u, X)), shape=(n, n))   # ∂J/∂k: −k X_i in the u row
    mass = np.ones(n)
    mass[u] = M
    scale = np.concatenate([-sigma[:, None], np.ones((N, m))], axis=1)
    local = LocalNonlinearity(inputs=w_idx, outputs=w_idx, scale=scale,
                              tensors={o: D[o] for o in range(2, order + 1)})
    states = tuple(f"{s}_{i}" for i in range(1, N + 1) for s in ("X", "u", *(p.name for p in law.states)))
    return SparseSystem(name=f"spring-block-chain[{law.name}, N={N}]", parameter="k", states=states,
                        equilibrium=y0, mass=mass, J0=J0, J1=J1, local=(local,))


__all__ = ["chain_sparse_system"]
