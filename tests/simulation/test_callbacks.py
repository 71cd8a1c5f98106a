"""First-class functions handed to compiled loops (landau.verify.hybrid.callbacks).

A :class:`FunctionPointer` is typed :class:`AddressedFunctionType` and unboxed from the address
it holds, not by numba's generic unboxing of a ``FunctionType``.  These tests check that a
compiled loop called with two different pointers of one signature runs each one's own machine
code (so the address is read per call, not frozen into the loop), that the values are the
Python function's, and that an object claiming the type without an address raises instead of
calling a null pointer.  The fallback for a numba without the ``FunctionModel`` the unboxing
builds on (numba's own ``FunctionType``) is run the same way.
"""

from __future__ import annotations

import numba as nb
import numpy as np
import pytest

from landau.verify.hybrid import callbacks
from landau.verify.hybrid.callbacks import AddressedFunctionType, FunctionPointer, jit_enabled, pointer
from landau.verify.hybrid.radau import SIG

pytestmark = pytest.mark.skipif(not jit_enabled(), reason="NUMBA_DISABLE_JIT: no compiled loop to hand pointers to")


def _square(t, y, p, out):
    for i in range(y.shape[0]):
        out[i] = p[0] * y[i] * y[i] + t


def _shifted_exp(t, y, p, out):
    for i in range(y.shape[0]):
        out[i] = np.exp(y[i]) - p[0] * t


def _compose(f, g, t, y, p):
    """f(t, y) and then g(t, f(t, y)), both through the first-class functions."""
    a = np.empty_like(y)
    b = np.empty_like(y)
    f(t, y, p, a)
    g(t, a, p, b)
    return b


_apply_twice = nb.njit(_compose)


def test_a_pointer_is_typed_addressed_function_type_once():
    f = pointer(_square, SIG, "test square")
    assert isinstance(f, FunctionPointer)
    assert nb.typeof(f) is f._numba_type_
    assert nb.typeof(f) == AddressedFunctionType(SIG)
    assert nb.typeof(f) != nb.types.FunctionType(SIG)     # a type of its own: no machine code shared


def test_the_loop_runs_each_pointer_s_own_machine_code():
    f = pointer(_square, SIG, "test square")
    g = pointer(_shifted_exp, SIG, "test shifted exp")
    y = np.array([0.5, -1.25, 2.0])
    p = np.array([3.0])
    t = 0.75
    a = np.empty(3)
    b = np.empty(3)
    _square(t, y, p, a)
    _shifted_exp(t, a, p, b)           # the same formulas in Python (the libm exp numba calls too)
    np.testing.assert_allclose(_apply_twice(f, g, t, y, p), b, rtol=1e-15, atol=0)
    # the same compiled loop, the pointers swapped: the other composition
    _shifted_exp(t, y, p, a)
    _square(t, a, p, b)
    np.testing.assert_allclose(_apply_twice(g, f, t, y, p), b, rtol=1e-15, atol=0)
    assert len(_apply_twice.overloads) == 1


class _NoAddress:
    """Claims a pointer's numba type but holds no address."""

    def __init__(self):
        self._numba_type_ = AddressedFunctionType(SIG)


def test_an_object_without_an_address_raises_instead_of_calling_null():
    f = pointer(_square, SIG, "test square")
    with pytest.raises(AttributeError, match="_address"):
        _apply_twice(_NoAddress(), f, 0.0, np.ones(2), np.ones(1))


#: :func:`_compose` again, a dispatcher of its own for the fallback's argument type
_apply_twice_fallback = nb.njit(_compose)


def test_the_model_the_unboxing_builds_on_is_checked_and_the_fallback_runs(monkeypatch):
    assert callbacks.ADDRESSED                      # this numba has the FunctionModel of three fields
    monkeypatch.setattr(callbacks, "_FUNCTION_MODEL_FIELDS", ("c_addr", "jit_addr"))
    assert callbacks._install_addressed_unboxing() is False     # another layout: nothing registered
    monkeypatch.setattr(callbacks, "ADDRESSED", False)
    assert callbacks.pointer_type(SIG) == nb.types.FunctionType(SIG)
    pointers = []
    for fn in (_square, _shifted_exp):
        cf, py = callbacks._cfunc(fn, SIG, "test fallback")
        pointers.append(FunctionPointer(cf, SIG, py))
    f, g = pointers
    assert nb.typeof(f) == nb.types.FunctionType(SIG)       # numba's own type and unboxing
    y, p, t = np.array([0.5, -1.25, 2.0]), np.array([3.0]), 0.75
    a, b = np.empty(3), np.empty(3)
    _square(t, y, p, a)
    _shifted_exp(t, a, p, b)
    np.testing.assert_allclose(_apply_twice_fallback(f, g, t, y, p), b, rtol=1e-15, atol=0)
