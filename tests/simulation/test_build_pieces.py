"""The pieces that keep the first build of a simulation short: the garbage collector paused during
a numba build (landau.verify.compiling.paused_gc), and the spring–block model's f and J evaluated
through the law's C callbacks (the integrator's own machine code) instead of a second build."""

import gc
import os

import numpy as np
import pytest

from landau.laws import get_law
from landau.verify.compiling import paused_gc
from landau.verify.springblock.model import SpringBlockModel


def test_paused_gc_restores_the_collector_state():
    """The collector is off inside, back on after (also after an exception, and when nested), and
    left off when it was off before."""
    was = gc.isenabled()
    try:
        gc.enable()
        with paused_gc():
            assert not gc.isenabled()
            with paused_gc():
                assert not gc.isenabled()
            assert not gc.isenabled()       # only the outermost resumes collection
        assert gc.isenabled()
        with pytest.raises(RuntimeError):
            with paused_gc():
                raise RuntimeError("a failed build")
        assert gc.isenabled()
        gc.disable()
        with paused_gc():
            pass
        assert not gc.isenabled()
    finally:
        (gc.enable if was else gc.disable)()


def test_model_field_is_the_compiled_kernel_to_the_last_bit():
    """model.f and model.J (C callbacks called through a trampoline) equal the same generated
    kernel called as a numba function (an independent build) bit for bit, and the Python kernel
    to rounding."""
    model = SpringBlockModel.build(get_law("ruina"), 1e-4, 1.8e5)
    c = model.compiled
    rng = np.random.default_rng(7)
    for y in rng.normal(scale=0.5, size=(5, model.n)):
        f_ref = np.empty(model.n)
        J_ref = np.empty((model.n, model.n))
        c.rhs(0.0, y, model.p, f_ref)
        c.jac(0.0, y, model.p, J_ref)
        f, J = model.f(y), model.J(y)
        if os.environ.get("NUMBA_DISABLE_JIT") != "1":
            assert np.array_equal(f, f_ref) and np.array_equal(J, J_ref)
        f_py = np.empty(model.n)
        c.rhs_py(0.0, y, model.p, f_py)
        assert np.allclose(f, f_py, rtol=1e-13, atol=1e-15)
