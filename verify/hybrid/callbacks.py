"""A model's right-hand side and Jacobian as first-class functions of a compiled loop.

A compiled integrator that takes ``f(t, y, p, out)`` and ``jac(t, y, p, out)`` as arguments
of a ``numba.types.FunctionType`` is compiled once for every model.  :func:`make_pointers`
compiles each function as a ``numba.cfunc`` (cached on disk beside the function's source) and
hands it over as a :class:`FunctionPointer`, an object of numba's documented
``WrapperAddressProtocol`` whose address is the cfunc's ``address``.  Under
``NUMBA_DISABLE_JIT=1`` the Python functions are handed over as they are.

Calling a compiled function with such arguments from Python costs numba the typing and
unboxing of each pointer on every call (measured about 35 µs for the pair on a loaded 2-core
machine, against about 15 µs for integer addresses turned back into functions inside
compiled code, which needs numba internals): cheap next to an integration, not next to a
single step.  :func:`call_pointer` runs such a function from Python (a one-line compiled
trampoline), so a model evaluates its field with the very machine code the integrator calls
instead of building the same function a second time.
"""

from __future__ import annotations

import types as _pytypes
import warnings

import numba as nb
import numpy as np
from numba import types
from numba.extending import typeof_impl

from landau.errors import InputError
from landau.verify.compiling import paused_gc

__all__ = ["FunctionPointer", "call_pointer", "jit_enabled", "make_pointers", "pointer", "warn_once"]

_WARNED: set[str] = set()


def warn_once(key: str, message: str) -> None:
    """A RuntimeWarning with ``message``, the first time ``key`` is seen in this process."""
    if key not in _WARNED:
        _WARNED.add(key)
        warnings.warn(message, RuntimeWarning, stacklevel=3)


@nb.njit
def _probe():                       # never compiled: only its type is looked at
    return 0


def jit_enabled() -> bool:
    """False under ``NUMBA_DISABLE_JIT=1`` (``njit`` then returns the Python function itself)."""
    return hasattr(_probe, "py_func")


class FunctionPointer(types.WrapperAddressProtocol):
    """A compiled ``f(t, y, p, out)`` (or Jacobian) handed to a compiled loop by its address.

    Made by :func:`make_pointers` from a ``numba.cfunc``; numba reads the address
    (:meth:`__wrapper_address__`) and the signature (:meth:`signature`) of this documented
    protocol.  The object keeps the cfunc alive, so the address stays valid.  Calling it from
    Python runs the Python function it was compiled from.
    """

    def __init__(self, cfunc, signature, python):
        self._cfunc = cfunc
        self._signature = signature
        self._ftype = types.FunctionType(signature)
        self._address = int(cfunc.address)
        self._python = python

    def __wrapper_address__(self) -> int:
        return self._address

    def signature(self):
        return self._signature

    def __call__(self, *args):
        return self._python(*args)


@typeof_impl.register(FunctionPointer)
def _typeof_pointer(val, c):
    # numba's own typing of a WrapperAddressProtocol object builds a new FunctionType at every
    # call from Python; the type of a pointer never changes, so it is made once
    return val._ftype


def _cfunc(fn, signature, tag):
    """``numba.cfunc(signature, cache=True)`` of the Python function behind ``fn``.

    The cfunc is made from a copy of the function under another qualified name, so that its
    disk-cache entry does not collide with that of an ``njit`` of the same function (both are
    keyed by the function's file, name and signature).
    """
    py = getattr(fn, "py_func", fn)
    if not isinstance(py, _pytypes.FunctionType):
        raise InputError(f"the integrator needs a Python or numba function for the {tag}, "
                         f"got {type(fn).__name__}")
    twin = _pytypes.FunctionType(py.__code__, py.__globals__, py.__name__, py.__defaults__, py.__closure__)
    twin.__qualname__ = f"{py.__qualname__}__cfunc"
    twin.__module__ = py.__module__
    with paused_gc():          # (a build with the collector running costs a sixth more)
        try:
            return nb.cfunc(signature, cache=True)(twin), py
        except Exception as exc:       # no file to cache it in (code made by exec), or dynamic globals
            warn_once(f"nocache:{py.__module__}.{py.__qualname__}",
                      f"landau: the {tag} {py.__qualname__!r} is compiled without numba's disk cache ({exc}); "
                      "it is compiled again in every process")
            return nb.cfunc(signature)(twin), py


_POINTERS: dict[tuple[int, str], tuple[object, FunctionPointer]] = {}


def pointer(f, sig, tag: str = "right-hand side"):
    """One function as a first-class function of a compiled loop (:func:`make_pointers` for a
    single function): a :class:`FunctionPointer`, or the Python function under
    ``NUMBA_DISABLE_JIT=1``."""
    jit = jit_enabled()
    if isinstance(f, FunctionPointer):
        return f if jit else f._python
    if not jit:
        return getattr(f, "py_func", f)
    key = (id(f), tag)
    hit = _POINTERS.get(key)
    if hit is None or hit[0] is not f:      # the entry keeps f alive: its id is not reused
        cf, py = _cfunc(f, sig, tag)
        hit = _POINTERS[key] = (f, FunctionPointer(cf, sig, py))
    return hit[1]


@nb.njit(cache=True)
def _call(f, t, y, p, out):
    f(t, y, p, out)


def call_pointer(f, t, y, p, out) -> None:
    """Evaluate ``f(t, y, p, out)`` for a function made by :func:`pointer`, running its compiled
    code (the machine code a compiled loop calls, so the values are the loop's to the last bit):
    a small trampoline, built once per signature, calls it by address.  Under
    ``NUMBA_DISABLE_JIT=1`` the Python function is called."""
    if isinstance(f, FunctionPointer) and jit_enabled():
        y = np.ascontiguousarray(y, dtype=np.float64)       # the pointer's argument types
        p = np.ascontiguousarray(p, dtype=np.float64)
        with paused_gc():       # the first call of each signature builds the trampoline
            _call(f, float(t), y, p, out)
    else:
        f(t, y, p, out)


def make_pointers(fun, jac, fun_sig, jac_sig):
    """(fun, jac) as first-class functions of a compiled loop, made once per function.

    Parameters
    ----------
    fun, jac : function, numba dispatcher or FunctionPointer
        ``fun(t, y, p, out)`` and ``jac(t, y, p, out)``: plain Python functions or
        ``numba.njit`` dispatchers are compiled as ``numba.cfunc`` (cached on disk).
    fun_sig, jac_sig : numba signature
        Their signatures.

    Returns
    -------
    tuple
        Two :class:`FunctionPointer` objects, or, under ``NUMBA_DISABLE_JIT=1``, the two Python
        functions.
    """
    return pointer(fun, fun_sig, "right-hand side"), pointer(jac, jac_sig, "Jacobian")
