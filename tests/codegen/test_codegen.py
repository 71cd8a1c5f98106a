"""landau.codegen.formula: the straight-line program (Tape) against lambdify on the same expression."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import sympy as sp

from landau.codegen.formula import Tape, dag_free_symbols, tree_size

# plain symbols: assumption queries would walk the tree at every construction step
x, y, z = sp.symbols("x y z")


def _shared_dag(depth: int = 12) -> sp.Expr:
    """An expression whose subexpressions are reused at every level (tree size ~2^depth)."""
    e = x / 3 + sp.log(1 + y) + sp.sqrt(z) * sp.Rational(7, 5)
    for i in range(depth):
        e = e * y / (e + z) + e ** 2 / (e ** 2 + sp.exp(-x)) + sp.Rational(1, 3 + i)   # stays O(1), > 0
    return e


def test_tree_size_and_free_symbols_on_the_dag():
    e = _shared_dag(3)
    assert tree_size(e) == sum(1 for _ in sp.preorder_traversal(e))   # sympy's own tree walk
    assert dag_free_symbols(e) == e.free_symbols


@pytest.mark.parametrize("dtype", [np.float64, np.longdouble])
def test_tape_matches_lambdify(dtype):
    e = _shared_dag(6)                 # small enough for lambdify + cse (a second implementation)
    tape = Tape(e, [x, y, z])
    f = sp.lambdify([x, y, z], e, "numpy", cse=True)
    rng = np.random.default_rng(3)
    X, Y, Z = (rng.uniform(0.5, 2.0, 200).astype(dtype) for _ in range(3))
    got, want = tape(X, Y, Z), f(X, Y, Z)
    assert got.dtype == dtype
    # the same well-conditioned operations, possibly in another order: a few ulps per level
    assert np.allclose(got.astype(float), want.astype(float), rtol=1e-13, atol=0)


def test_tape_of_a_large_dag_is_small_and_right():
    e = _shared_dag(16)
    assert tree_size(e) > 1e5          # what lambdify/cse would walk
    tape = Tape(e, [x, y, z])
    assert len(tape.ops) < 300         # 16 levels × ~12 distinct operations
    pts = [(0.7, 1.3, 0.9), (1.9, 0.6, 1.4)]
    got = tape(*(np.array(c) for c in zip(*pts, strict=True)))
    with mpmath.workdps(40):
        ref = [tape(*map(mpmath.mpf, p), modules="mpmath") for p in pts]
    # float64 vs 40 digits on a well-conditioned rational recursion: ~1e-15 per level
    assert np.allclose(got, [float(r) for r in ref], rtol=1e-12, atol=0)


def test_tape_mpmath_matches_sympy_at_50_digits():
    e = _shared_dag(3)                 # sympy's evalf walks the tree: keep it small
    tape = Tape(e, [x, y, z])
    pt = {x: sp.Rational(3, 4), y: sp.Rational(5, 3), z: sp.Rational(9, 7)}
    with mpmath.workdps(50):
        got = tape(*(mpmath.mpf(v.p) / v.q for v in pt.values()), modules="mpmath")
        want = e.xreplace(pt).evalf(50)
        assert abs(got - mpmath.mpf(str(want))) <= mpmath.mpf("1e-45") * abs(got)


def test_tape_refuses_unknown_operations_and_symbols():
    with pytest.raises(ValueError):
        Tape(sp.gamma(x), [x])
    with pytest.raises(ValueError):
        Tape(x + y, [x])
