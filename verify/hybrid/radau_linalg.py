"""The Newton matrices of a Radau IIA step, their LU factors and the solves (dense, real arithmetic).

The simplified Newton iteration of :mod:`landau.verify.hybrid.radau` solves, in the eigenbasis
of A⁻¹ (:mod:`landau.verify.hybrid.radau_tableau`), one real system with γ/h·I − J and one
complex system with (α + iβ)/h·I − J (Hairer & Wanner 1996, IV.8, eq. (8.18)):
:func:`factor_real` and :func:`factor_complex` form and factor them, :func:`solve` and
:func:`solve_complex` solve with the factors.  A step whose simplified iteration fails with a
fresh J is retried on the full 3n × 3n matrix I − h(A ⊗ I)·diag(J(Yᵢ)) with the stage
Jacobians (:func:`stage_jacobians`).  Systems are small (n is the number of states), so the LU
is a plain partial-pivoting loop written out for numba, the complex one in real arithmetic on
the real and imaginary parts (compiling real arithmetic only halves the loop's first build).

The functions the loop calls every step or every Newton sweep are :data:`inlined` into its IR:
compiled as part of the loop, they get no disk-cache entry of their own, and
:func:`landau.verify.compiling.compile_once` keys the loop's cache on this module's source too.

References
----------
Hairer, E., Wanner, G. (1996). Solving Ordinary Differential Equations II, 2nd ed., Springer,
Sec. IV.8.
Golub, G. H., Van Loan, C. F. (2013). Matrix Computations, 4th ed., Johns Hopkins, Sec. 3.4
(Gaussian elimination with partial pivoting).
"""

from __future__ import annotations

import numba as nb

from landau.verify.hybrid.radau_tableau import A_RADAU, ALPHA_SPLIT, BETA_SPLIT, GAMMA_SPLIT, NODES

__all__ = ["factor_complex", "factor_real", "inlined", "lu", "lu_complex", "solve", "solve_complex",
           "stage_jacobians"]

#: the decorator of the helpers the loop calls every step or every Newton sweep (the solves, the
#: factorisations, the dense output): numba inlines them into the loop's own IR, so that they
#: are optimised with it instead of being called through its calling convention (measured 1.6×
#: faster loop on the spring–block cycle of ``benchmarks/sections_solvers.py``; the first build
#: of the loop, 8–9 CPU-s on a loaded 2-core machine, is the same within its scatter with or
#: without it)
inlined = nb.njit(inline="always")


@inlined
def lu(a, piv, dinv):
    """In-place LU decomposition of the square ``a`` with partial pivoting (row swaps in ``piv``,
    the reciprocals of the pivots in ``dinv``: the solves multiply instead of dividing, which
    shortens their dependency chain); False when a pivot is exactly zero."""
    n = a.shape[0]
    for k in range(n):
        m = k
        big = abs(a[k, k])
        for i in range(k + 1, n):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                m = i
        piv[k] = m
        if big == 0.0:
            return False
        if m != k:
            for j in range(n):
                tmp = a[k, j]
                a[k, j] = a[m, j]
                a[m, j] = tmp
        inv = 1.0 / a[k, k]
        dinv[k] = inv
        for i in range(k + 1, n):
            a[i, k] *= inv
            f = a[i, k]
            if f != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= f * a[k, j]
    return True


@inlined
def solve(lu, piv, dinv, b):
    """Solve with the factors of :func:`lu`, in place in ``b``."""
    n = lu.shape[0]
    for k in range(n):
        m = piv[k]
        if m != k:
            tmp = b[k]
            b[k] = b[m]
            b[m] = tmp
    for i in range(n):
        s = b[i]
        for j in range(i):
            s -= lu[i, j] * b[j]
        b[i] = s
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= lu[i, j] * b[j]
        b[i] = s * dinv[i]


@inlined
def lu_complex(ar, ai, piv, dr, di):
    """In-place LU decomposition of the complex square matrix ``ar + i·ai`` with partial pivoting
    (largest |Re| + |Im|; row swaps in ``piv``, reciprocals of the pivots in ``dr + i·di``), in
    real arithmetic; False when a pivot is exactly zero.

    The complex n × n system of the simplified Newton iteration costs a quarter of the flops of
    the real 2n × 2n form of the same matrix and half its dependency chain in the solves."""
    n = ar.shape[0]
    for k in range(n):
        m = k
        big = abs(ar[k, k]) + abs(ai[k, k])
        for i in range(k + 1, n):
            v = abs(ar[i, k]) + abs(ai[i, k])
            if v > big:
                big = v
                m = i
        piv[k] = m
        if big == 0.0:
            return False
        if m != k:
            for j in range(n):
                tr = ar[k, j]
                ar[k, j] = ar[m, j]
                ar[m, j] = tr
                ti = ai[k, j]
                ai[k, j] = ai[m, j]
                ai[m, j] = ti
        # 1/(pr + i·pi) by Smith's division (no overflow of pr² + pi²)
        pr = ar[k, k]
        pi = ai[k, k]
        if abs(pr) >= abs(pi):
            r = pi / pr
            ir = 1.0 / (pr + pi * r)
            ii = -r * ir
        else:
            r = pr / pi
            ii = -1.0 / (pr * r + pi)
            ir = -r * ii
        dr[k] = ir
        di[k] = ii
        for i in range(k + 1, n):
            xr = ar[i, k]
            xi = ai[i, k]
            lr = xr * ir - xi * ii
            li = xr * ii + xi * ir
            ar[i, k] = lr
            ai[i, k] = li
            if lr != 0.0 or li != 0.0:
                for j in range(k + 1, n):
                    ur = ar[k, j]
                    ui = ai[k, j]
                    ar[i, j] -= lr * ur - li * ui
                    ai[i, j] -= lr * ui + li * ur
    return True


@inlined
def solve_complex(ar, ai, piv, dr, di, br, bi):
    """Solve with the factors of :func:`lu_complex`, in place in ``br + i·bi``."""
    n = ar.shape[0]
    for k in range(n):
        m = piv[k]
        if m != k:
            tr = br[k]
            br[k] = br[m]
            br[m] = tr
            ti = bi[k]
            bi[k] = bi[m]
            bi[m] = ti
    for i in range(n):
        sr = br[i]
        si = bi[i]
        for j in range(i):
            sr -= ar[i, j] * br[j] - ai[i, j] * bi[j]
            si -= ar[i, j] * bi[j] + ai[i, j] * br[j]
        br[i] = sr
        bi[i] = si
    for i in range(n - 1, -1, -1):
        sr = br[i]
        si = bi[i]
        for j in range(i + 1, n):
            sr -= ar[i, j] * br[j] - ai[i, j] * bi[j]
            si -= ar[i, j] * bi[j] + ai[i, j] * br[j]
        br[i] = sr * dr[i] - si * di[i]
        bi[i] = sr * di[i] + si * dr[i]


@inlined
def factor_real(J, h, Mr, pivR, dinvR):
    """LU of γ/h·I − J in place in ``Mr`` (the matrix of the first decoupled system and of the
    error estimate, Hairer & Wanner 1996, eq. (8.18)); False when singular."""
    n = J.shape[0]
    gh = GAMMA_SPLIT / h
    for i in range(n):
        for j in range(n):
            Mr[i, j] = -J[i, j]
        Mr[i, i] += gh
    return lu(Mr, pivR, dinvR)


@inlined
def factor_complex(J, h, Mcr, Mci, pivC, dcr, dci):
    """LU of the complex (α + iβ)/h·I − J (eq. (8.18)), real part in ``Mcr`` and imaginary part in
    ``Mci`` (:func:`lu_complex`); False when singular."""
    n = J.shape[0]
    ah = ALPHA_SPLIT / h
    bh = BETA_SPLIT / h
    for i in range(n):
        for j in range(n):
            Mcr[i, j] = -J[i, j]
            Mci[i, j] = 0.0
        Mcr[i, i] += ah
        Mci[i, i] = bh
    return lu_complex(Mcr, Mci, pivC, dcr, dci)


# compiled as part of the loop that calls it (no disk-cache entry of its own), not inlined: it runs
# only when a step is retried
@nb.njit
def stage_jacobians(jac, t, h, y, Z, p, JB, ytmp, Mf, pivF, dinvF, cnt):
    """The full-Newton matrix I − h(A ⊗ I)·diag(J(Y_b)) with the stage Jacobians at the current
    iterate, factorised in place; False when it is singular."""
    s, n = Z.shape
    for b in range(s):
        for i in range(n):
            ytmp[i] = y[i] + Z[b, i]
        jac(t + NODES[b] * h, ytmp, p, JB[b])
        cnt[3] += 1
    for a in range(s):
        for b in range(s):
            hab = -h * A_RADAU[a, b]
            for i in range(n):
                for j in range(n):
                    Mf[a * n + i, b * n + j] = hab * JB[b, i, j]
    for i in range(s * n):
        Mf[i, i] += 1.0
    if not lu(Mf, pivF, dinvF):
        return False
    cnt[4] += 1
    return True
