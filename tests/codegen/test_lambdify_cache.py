"""Lambdified formulas cached across processes (landau.codegen.formula.lambdify): keyed by the formula's
structure, stored atomically in the one code folder, corrupt entries rebuilt, concurrent
processes safe; and one rule for where every landau cache lives (landau.support.cachedir)."""

import os
import subprocess
import sys

import mpmath
import numpy as np
import pytest
import sympy as sp

from landau.codegen import formula as codegen
from landau.support import cache as dcache
from landau.support import cachedir
from landau.verify import jitcache

x, y = sp.symbols("x y", real=True)
#: shared subexpressions, a log and a rational constant: what cse and the printers must handle
FORMULA = [sp.exp(x) * y + sp.exp(x) / (1 + y ** 2), sp.log(x) * sp.Rational(1, 3)]


def _reference(xv, yv):
    """The formula evaluated by hand (an independent computation)."""
    return [np.exp(xv) * yv + np.exp(xv) / (1 + yv ** 2), np.log(xv) / 3]


@pytest.fixture()
def code(tmp_path, monkeypatch):
    monkeypatch.setenv("LANDAU_CACHE_DIR", str(tmp_path))
    return tmp_path / "jit"


def _entries(folder):
    return sorted(folder.glob("landau_lambdify_*.py"))


def test_structure_text_compares_structure_not_sympy_equality():
    a = codegen.structure_text
    assert a([x ** 2, x + 1]) == a([x ** 2, x + 1])                   # rebuilt alike: same key
    assert a(x ** 2) != a(x ** sp.Float(2.0))                       # printed differently by lambdify
    assert a(sp.Symbol("x")) != a(sp.Symbol("x", real=True))        # assumptions are part of a symbol
    assert a(x - y) != a(y - x)


def test_structure_text_is_linear_in_the_dag():
    e = x
    for _ in range(200):            # 2**200 tree nodes, 400 distinct ones: a tree walk would never end
        e = sp.Add(e, e * y, evaluate=False)
    assert len(codegen.structure_text(e).splitlines()) < 1000


def test_second_use_executes_the_stored_source(code):
    xs, ys = np.array([0.5, 1.5]), np.array([-1.0, 2.0])
    first = codegen.lambdify([x, y], FORMULA, "numpy")
    (path,) = _entries(code)
    second = codegen.lambdify([x, y], FORMULA, "numpy")
    assert second.__code__.co_filename == str(path)         # not lambdified again
    for f in (first, second):
        # the same arithmetic in another order: agreement to a few ulps
        np.testing.assert_allclose(f(xs, ys), _reference(xs, ys), rtol=1e-14)


def test_mpmath_functions_are_cached_and_keep_their_precision(code):
    codegen.lambdify([x, y], FORMULA, "mpmath")
    f = codegen.lambdify([x, y], FORMULA, "mpmath")
    assert str(code) in f.__code__.co_filename
    with mpmath.workdps(50):
        got = f(mpmath.mpf("0.5"), mpmath.mpf(2))
        # log(1/2)/3 at 50 digits: a 1/3 printed as a float would be wrong after ~16 digits
        assert abs(got[1] - mpmath.log(mpmath.mpf("0.5")) / 3) < mpmath.mpf(10) ** -48


def test_other_arguments_or_modules_are_other_entries(code):
    codegen.lambdify([x, y], FORMULA, "numpy")
    codegen.lambdify([y, x], FORMULA, "numpy")
    codegen.lambdify([x, y], FORMULA, "mpmath")
    assert len(_entries(code)) == 3
    assert codegen.lambdify([y, x], FORMULA, "numpy")(2.0, 0.5)[1] == pytest.approx(np.log(0.5) / 3, rel=1e-15)


@pytest.mark.parametrize("damage", [b"", b"def _lambdifygenerated(x, y):\n    return (", b"\xff\xfe garbage"])
def test_a_damaged_entry_is_rebuilt(code, damage):
    codegen.lambdify([x, y], FORMULA, "numpy")
    (path,) = _entries(code)
    good = path.read_bytes()
    path.write_bytes(damage)                  # truncated, foreign or not text: never executed
    f = codegen.lambdify([x, y], FORMULA, "numpy")
    np.testing.assert_allclose(f(0.5, 2.0), _reference(0.5, 2.0), rtol=1e-14)
    assert path.read_bytes() == good          # rewritten whole


def test_an_entry_that_does_not_compile_is_rebuilt(code, caplog):
    codegen.lambdify([x, y], FORMULA, "numpy")
    (path,) = _entries(code)
    header = path.read_text().splitlines()[0]
    path.write_text(header + "\ndef _lambdifygenerated(x, y):\n    return (\n")   # right header, broken body
    f = codegen.lambdify([x, y], FORMULA, "numpy")
    np.testing.assert_allclose(f(0.5, 2.0), _reference(0.5, 2.0), rtol=1e-14)
    assert "signature does not verify" in caplog.text             # refused before it is compiled
    assert codegen.lambdify([x, y], FORMULA, "numpy").__code__.co_filename == str(path)   # and stored again


def test_unwritable_folder_runs_from_memory(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("LANDAU_CACHE_DIR", str(blocker))           # <file>/jit cannot be created
    from landau.support.cachedir import CacheWarning

    with pytest.warns(CacheWarning, match="it is not a folder") as caught:   # said once, with the fix
        f = codegen.lambdify([x, y], FORMULA, "numpy")
    assert len(caught) == 1 and "LANDAU_CACHE_DIR" in str(caught[0].message)
    np.testing.assert_allclose(f(0.5, 2.0), _reference(0.5, 2.0), rtol=1e-14)


_WORKER = """
import sympy as sp
from landau.codegen import formula as codegen
x, y = sp.symbols("x y", real=True)
f = codegen.lambdify([x, y], [sp.exp(x) * y + sp.exp(x) / (1 + y ** 2) + sp.sqrt(x)], "numpy")
print(repr(float(f(0.25, 3.0)[0])))
"""


def test_concurrent_processes_share_one_entry(code):
    procs = [subprocess.Popen([sys.executable, "-c", _WORKER], stdout=subprocess.PIPE, text=True,
                              env=dict(os.environ)) for _ in range(3)]
    outs = [p.communicate(timeout=300)[0] for p in procs]
    assert all(p.returncode == 0 for p in procs)
    want = np.exp(0.25) * 3.0 + np.exp(0.25) / 10.0 + 0.5
    assert all(float(o) == pytest.approx(want, rel=1e-15) for o in outs)
    (path,) = _entries(code)                                  # one complete file, whoever wrote it last
    assert path.read_text().startswith("# landau generated code: lambdify ")


def test_compiled_formula_uses_the_cache(code):
    a = sp.Symbol("a", real=True)
    atoms = {a: sp.exp(x)}
    f1 = codegen.CompiledFormula(a * y + a ** 2, (x, y), atoms)
    n = len(_entries(code))
    assert n == 2                                             # the atoms and the formula
    f2 = codegen.CompiledFormula(a * y + a ** 2, (x, y), atoms)
    assert len(_entries(code)) == n
    xs = np.linspace(0.1, 1.0, 5)
    np.testing.assert_allclose(f2(xs, 2.0), np.exp(xs) * 2.0 + np.exp(2 * xs), rtol=1e-14)
    np.testing.assert_array_equal(f1(xs, 2.0), f2(xs, 2.0))


def test_one_rule_for_every_cache_folder(tmp_path, monkeypatch):
    monkeypatch.setenv("LANDAU_CACHE_DIR", str(tmp_path / "root"))
    monkeypatch.setenv("LANDAU_JIT_DIR", str(tmp_path / "old"))
    assert dcache.cache_dir() == cachedir.cache_root() == tmp_path / "root"
    assert jitcache.cache_dir() == cachedir.code_dir() == tmp_path / "root" / "jit"
    monkeypatch.delenv("LANDAU_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    assert dcache.cache_dir() == tmp_path / "xdg" / "landau"
    assert jitcache.cache_dir() == tmp_path / "old"               # the older setting, when the root is not set


def test_mpmath_formulas_are_straight_line_programs_that_agree_with_lambdify(code):
    a, b = sp.symbols("a b", real=True)
    atoms = {a: sp.exp(x) / (1 + y), b: sp.log(a + 2)}         # b defined through a: nested atoms
    formula = (a - b) ** 3 * sp.Float(0.1) + sp.pi * a * b - sp.sqrt(x) * sp.Rational(2, 7)
    f = codegen.CompiledFormula(formula, (x, y), atoms, "mpmath")
    assert _entries(code) == []                                  # nothing lambdified
    g = sp.lambdify([x, y], formula.subs(b, sp.log(a + 2)).subs(a, sp.exp(x) / (1 + y)), "mpmath")
    with mpmath.workdps(50):
        for xv, yv in ((0.5, 2.0), (3.0, -0.25)):
            want = g(mpmath.mpf(xv), mpmath.mpf(yv))
            # both at 50 digits, in a different order of operations: agreement to ~1e-45
            assert abs(f(mpmath.mpf(xv), mpmath.mpf(yv)) - want) <= mpmath.mpf(10) ** -45 * abs(want)
