"""Compiled loops built on first use (landau.verify.compiling.compile_once): nothing compiles at
import, a terminal line appears while a build takes time, and an edit of a module the loop calls
into is never served stale machine code from numba's disk cache (numba itself checks only the
file of the cached function)."""

import os
import subprocess
import sys
import textwrap

import pytest

pytestmark = pytest.mark.skipif(os.environ.get("NUMBA_DISABLE_JIT") == "1",
                                reason="numba's compiler is switched off: nothing is compiled or cached")

MAIN = """
    import numba as nb
    from numba import types
    from pkgtmp import dep

    @nb.njit(cache=True)
    def f(x):
        return dep.g(x)

    SIG = (types.float64,)
"""
DEP = """
    import numba as nb

    @nb.njit(cache=True)
    def g(x):
        return x + {inc}
"""
RUN = """
import sys
sys.path.insert(0, {root!r})
from pkgtmp import main
if {guarded}:
    from landau.verify.compiling import compile_once
    compile_once(main.f, main.SIG, "a test loop", watched=("pkgtmp.",))
print(main.f(1.0))
"""


def _write(root, inc):
    pkg = root / "pkgtmp"
    pkg.mkdir(exist_ok=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "main.py").write_text(textwrap.dedent(MAIN))
    (pkg / "dep.py").write_text(textwrap.dedent(DEP.format(inc=inc)))


def _run(root, env, guarded):
    code = RUN.format(root=str(root), guarded=guarded)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300)
    assert out.returncode == 0, out.stderr
    return float(out.stdout.strip().splitlines()[-1])


def test_edit_of_a_called_module_is_never_served_stale(tmp_path):
    # without compile_once, numba's cache keys on main.py alone and prints 2.0 after the edit
    # (numba 0.68: the old machine code is served); with it, the edit is seen
    guarded = True
    env = {**os.environ, "LANDAU_CACHE_DIR": str(tmp_path / "cache"), "NUMBA_CACHE_DIR": str(tmp_path / "nbc")}
    env.pop("NUMBA_DISABLE_JIT", None)
    _write(tmp_path, 1)
    assert _run(tmp_path, env, guarded) == 2.0
    _write(tmp_path, 2)                         # the callee changes; main.py does not
    assert _run(tmp_path, env, guarded) == 3.0


def _numba_files(root):
    """numba's files under ``root``, with the identity of each (a rebuilt file is a new file)."""
    return {f.name: (f.stat().st_ino, f.stat().st_mtime_ns) for f in root.rglob("*.nb[ic]")}


def test_the_build_stamp_travels_with_numbas_cache_not_the_landau_cache(tmp_path):
    # a CI that keeps numba's __pycache__ (a cached virtual environment) but starts with an
    # empty landau cache: the loop is loaded, not built again (its stamp lies beside numba's index)
    env = {**os.environ, "LANDAU_CACHE_DIR": str(tmp_path / "cache1")}
    for name in ("NUMBA_DISABLE_JIT", "NUMBA_CACHE_DIR"):
        env.pop(name, None)
    _write(tmp_path, 1)
    assert _run(tmp_path, env, True) == 2.0
    pycache = tmp_path / "pkgtmp" / "__pycache__"
    built = _numba_files(pycache)
    assert any(n.startswith("main.f-") for n in built), built
    env["LANDAU_CACHE_DIR"] = str(tmp_path / "cache2")        # a fresh landau cache
    assert _run(tmp_path, env, True) == 2.0
    assert _numba_files(pycache) == built                       # the same files: nothing rebuilt
    assert (pycache / "main.f.landau-stamp").is_file()
    # and the stamp still guards the edit of a callee
    _write(tmp_path, 2)
    assert _run(tmp_path, env, True) == 3.0
    assert _numba_files(pycache) != built


def test_nothing_compiles_at_import_of_the_simulation_layer():
    # importing every integrator module builds nothing: no dispatcher has a compiled signature
    code = textwrap.dedent("""
        import numba
        from numba.core.registry import CPUDispatcher
        import landau.verify.hybrid.radau, landau.verify.hybrid.dop853
        import landau.verify.skurativskyi.rk, landau.verify.skurativskyi.simulate
        import landau.verify.springblock.simulate, landau.verify.galvanetto.maps, landau.verify.lancioni.model
        import gc
        built = [o.py_func.__qualname__ for o in gc.get_objects()
                 if isinstance(o, CPUDispatcher) and o.signatures]
        print(len(built), built)
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.startswith("0 "), out.stdout


def test_the_radau_loop_s_stamp_covers_the_modules_it_inlines():
    """The Radau IIA loop inlines its factorisations and solves (radau_linalg), reads the method's
    coefficients (radau_tableau), builds the cubic scan (crossing) and takes its views without
    reference counts (borrowed) from other files: the stamp that keys its disk cache must hash each
    of them, or an edit there would be served stale; so must the forced oscillator's loop."""
    from landau.verify.compiling import WATCHED, _reachable_modules
    from landau.verify.hybrid import radau

    reached = _reachable_modules(sys.modules[radau._radau_loop.py_func.__module__], WATCHED)
    for part in ("radau", "radau_linalg", "radau_tableau", "crossing", "callbacks", "borrowed"):
        assert f"landau.verify.hybrid.{part}" in reached
    from landau.verify.skurativskyi import rk

    reached = _reachable_modules(sys.modules[rk.integrate_mixed.py_func.__module__], WATCHED)
    assert "landau.verify.hybrid.borrowed" in reached and "landau.verify.skurativskyi.field" in reached
