"""A large system as numbers: a sparse Jacobian affine in the Hopf parameter and local nonlinearities.

For a system of many states whose nonlinearity is local — each block of a chain, each contact of
a multi-degree-of-freedom model, depends on a few states of its own, and the couplings (springs,
dampers) are linear — the data of the weakly nonlinear analysis at a steady state y₀ are

* E, the (diagonal) mass: E·ẏ = f(y; p);
* J(p) = J₀ + p J₁, the Jacobian ∂f/∂y at y₀ (sparse), affine in the Hopf parameter p, with y₀
  independent of p (the chain: k multiplies the slips X_i, zero at steady sliding);
* the multilinear forms Dₘ[x¹, …, xᵐ] = Σ ∂ᵐf/∂y_{a₁}…∂y_{aₘ} x¹_{a₁}…xᵐ_{aₘ} (B = D₂, C = D₃ in
  Kuznetsov's notation), sums of :class:`LocalNonlinearity` terms, each the same small tensor
  applied to K copies of a few states.

:class:`SparseSystem` holds them; :mod:`landau.derivation.sparse_hopf` locates its Hopf point and
its amplitude equation with sparse LU factors, at a cost linear in the number of copies apart from
the eigenvalue scan.  :mod:`landau.systems.chain_forms` builds one for the spring–block chain.

References
----------
Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, §3.5
(eq. 3.4: the forms B, C) and §8.7 (their evaluation for large systems).
"""

from __future__ import annotations

import string
from dataclasses import dataclass
from typing import Mapping

import numpy as np
import scipy.sparse

from landau.errors import InputError


@dataclass(frozen=True, eq=False)
class LocalNonlinearity:
    """K copies of one local map: state indices ``inputs`` (K × a) feed the tensors, whose o outputs,
    each multiplied by ``scale`` (K × o), are added to the states ``outputs`` (K × o).

    ``tensors[m]`` has shape (o,) + (a,)·m: the m-th derivatives of the local map (full, symmetric in
    its last m indices), the same for every copy.
    """

    inputs: np.ndarray
    outputs: np.ndarray
    scale: np.ndarray
    tensors: Mapping[int, np.ndarray]

    def form(self, vectors: list[np.ndarray], out: np.ndarray) -> None:
        """Add Σ_copies scale·Dₘ[x¹…xᵐ] to ``out`` (m = len(vectors))."""
        m = len(vectors)
        D = self.tensors.get(m)
        if D is None:
            raise InputError(f"the local jets hold orders {sorted(self.tensors)}, not {m}")
        letters = string.ascii_lowercase[1:m + 1]
        # D[o, a, b, …] · x¹[k, a] · x²[k, b] … → [k, o], for every copy k at once
        spec = f"o{letters}," + ",".join(f"k{c}" for c in letters) + "->ko"
        local = np.einsum(spec, D, *(x[self.inputs] for x in vectors), optimize=True)
        np.add.at(out, self.outputs, self.scale * local)


@dataclass(frozen=True, eq=False)
class SparseSystem:
    """E·ẏ = f(y; p) near a steady state y₀ as numbers (see the module docstring).

    Parameters
    ----------
    name, parameter : str
        The system's and the Hopf parameter's names.
    states : tuple of str
        The state names (their order is that of the matrices).
    equilibrium : ndarray
        y₀ (independent of p).
    mass : ndarray
        The diagonal of E (a zero entry: an algebraic equation).
    J0, J1 : scipy.sparse matrices
        J(p) = J0 + p·J1.
    local : tuple of LocalNonlinearity
        The nonlinear terms of f.
    """

    name: str
    parameter: str
    states: tuple[str, ...]
    equilibrium: np.ndarray
    mass: np.ndarray
    J0: scipy.sparse.spmatrix
    J1: scipy.sparse.spmatrix
    local: tuple[LocalNonlinearity, ...]

    @property
    def n(self) -> int:
        return len(self.states)

    def jacobian(self, p: float) -> scipy.sparse.csc_matrix:
        """J(p) = J₀ + p J₁ (sparse, CSC)."""
        return scipy.sparse.csc_matrix(self.J0 + float(p) * self.J1)

    def form(self, *vectors: np.ndarray) -> np.ndarray:
        """Dₘ[x¹, …, xᵐ] (complex vectors; m = 2: B, m = 3: C)."""
        out = np.zeros(self.n, dtype=complex)
        vecs = [np.asarray(x, dtype=complex) for x in vectors]
        for term in self.local:
            term.form(vecs, out)
        return out


__all__ = ["LocalNonlinearity", "SparseSystem"]
