"""det_by_sparsity (landau.derivation.sparse_det) against sympy's fraction-free elimination of the
same matrix: the same exact ring element, or None where the core is too large."""

import random

import sympy as sp
from sympy.polys.matrices import DomainMatrix

from landau.derivation.sparse_det import MAX_CORE, det_by_sparsity, independent_split


def _det_both(M: sp.Matrix):
    A = DomainMatrix.from_Matrix(M)
    K = A.domain
    return det_by_sparsity(A.to_list(), K.zero, K.one), A.det()


def test_arrow_matrix_with_symbols_equals_elimination():
    # λE − J of a spring–block with four independent state variables: X and the φᵢ couple only to u
    n = 4
    lam, k, M = sp.symbols("lambda k M")
    a = sp.symbols(f"a0:{n}")
    b = sp.symbols(f"b0:{n}")
    g = sp.symbols(f"g0:{n}")
    c = sp.Symbol("c")
    J = sp.zeros(n + 2, n + 2)
    J[0, 1], J[1, 0], J[1, 1] = 1, -k, c
    for i in range(n):
        J[1, 2 + i], J[2 + i, 1], J[2 + i, 2 + i] = a[i], b[i], g[i]
    E = sp.diag(1, M, *([1] * n))
    S, core = independent_split(DomainMatrix.from_Matrix(lam * E - J).to_list(), 0)
    assert core == [1] and S == [0, *range(2, n + 2)]
    fast, ref = _det_both(lam * E - J)
    assert fast == ref


def test_random_sparse_integer_matrices_equal_elimination():
    rng = random.Random(7)
    checked = 0
    for _ in range(60):
        n = rng.randint(3, 9)
        core = rng.sample(range(n), rng.randint(1, MAX_CORE))
        M = sp.zeros(n, n)
        for i in range(n):
            M[i, i] = rng.randint(-5, 5)
            for j in range(n):
                if i != j and (i in core or j in core) and rng.random() < 0.7:
                    M[i, j] = rng.randint(-5, 5)
        fast, ref = _det_both(M)
        if fast is not None:
            assert fast == ref, M
            checked += 1
    assert checked >= 40


def test_dense_matrix_left_to_elimination():
    M = sp.Matrix(6, 6, lambda i, j: i + 2 * j + 1 + (i == j))
    fast, _ = _det_both(M)
    assert fast is None
