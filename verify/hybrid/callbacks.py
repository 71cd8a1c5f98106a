"""A model's right-hand side and Jacobian as first-class functions of a compiled loop.

A compiled integrator that takes ``f(t, y, p, out)`` and ``jac(t, y, p, out)`` as arguments
of a ``numba.types.FunctionType`` is compiled once for every model.  :func:`make_pointers`
compiles each function as a ``numba.cfunc`` (cached on disk beside the function's source) and
hands it over as a :class:`FunctionPointer`, an object of numba's documented
``WrapperAddressProtocol`` whose address is the cfunc's ``address``.  Under
``NUMBA_DISABLE_JIT=1`` the Python functions are handed over as they are.

Calling a compiled function with such arguments from Python costs numba the typing and
unboxing of each pointer on every call.  numba's own unboxing of a ``FunctionType`` runs four
Python calls per pointer (it imports its module, asks ``_get_wrapper_address`` and
``_get_jit_address``, each checking the signature again): 11.3 µs for the pair against 0.4 µs
for two integers (an ``njit`` function returning its third argument, best of 7 × 2·10⁴ calls,
AMD EPYC, 2 cores).  A pointer is therefore typed :class:`AddressedFunctionType`, numba's
``FunctionType`` with the same data model and calls, whose unboxing reads the address the
:class:`FunctionPointer` holds (one attribute read), and the pointer carries that type as its
``_numba_type_``, which numba's dispatcher reads without running the typing registry: 1.5 µs
for the pair, measured the same way.  The 10 µs saved are a fifth of the fixed cost of
``springblock.integrate`` (a run over 10⁻⁹ s: 63 → 50 µs) and count where Python calls a loop
many times: the hybrid engine calls the DOP853 entries once or more per phase (Galvanetto's
fig. 12, 5512 maps: 13.0 → 12.4 CPU-s).  The unboxing builds numba's ``FunctionModel`` struct
(``c_addr``, ``py_addr``, ``jit_addr``, from ``numba.experimental.function_type``) with
``jit_addr`` null, as numba's own unboxing does for an object of the wrapper-address protocol;
``tests/simulation/test_callbacks.py`` checks that a loop calls the right machine code through
it.  Where a numba has no such model, pointers fall back to numba's own ``FunctionType``
(:data:`ADDRESSED`, :func:`pointer_type`), which the same tests run too.  :func:`call_pointer` runs such a function from
Python (a one-line compiled trampoline), so a model evaluates its field with the very machine
code the integrator calls instead of building the same function a second time.
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

__all__ = ["ADDRESSED", "AddressedFunctionType", "FunctionPointer", "call_pointer", "jit_enabled", "make_pointers",
           "pointer", "pointer_type", "warn_once"]

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


class AddressedFunctionType(types.FunctionType):
    """numba's first-class ``FunctionType`` of a :class:`FunctionPointer`: the same data model
    and the same calls, unboxed from the address the pointer holds (module docstring).

    A loop compiled for it takes only :class:`FunctionPointer` objects (their ``_numba_type_``);
    it is a type of its own, so machine code compiled for numba's ``FunctionType`` is never
    reused for it, nor the other way round.
    """


#: the struct numba's ``FunctionModel`` must have for :func:`_install_addressed_unboxing`
_FUNCTION_MODEL_FIELDS = ("c_addr", "py_addr", "jit_addr")


def _install_addressed_unboxing() -> bool:
    """Register the data model and the unboxing of :class:`AddressedFunctionType`.

    They build on numba's ``FunctionModel`` (``numba.experimental.function_type``) and its three
    fields.  When this numba has no such model, or its fields differ, nothing is registered and
    False is returned: pointers are then typed numba's own ``FunctionType`` (:func:`pointer_type`)
    and unboxed by numba, as before this type existed (slower by ~10 µs a call, the same results).
    """
    try:
        from numba.core import cgutils
        from numba.core.datamodel import default_manager
        from numba.experimental.function_type import FunctionModel
        from numba.extending import NativeValue, register_model, unbox

        fields = tuple(FunctionModel(default_manager, types.FunctionType(types.void()))._fields)
    except (ImportError, AttributeError, TypeError):
        return False
    if fields != _FUNCTION_MODEL_FIELDS:
        return False
    register_model(AddressedFunctionType)(FunctionModel)

    @unbox(AddressedFunctionType)
    def _unbox_addressed(typ, obj, c):
        # the FunctionModel struct numba's unboxing builds for a wrapper-address object: the C
        # address of the cfunc, the Python object, and no numba-convention entry (jit_addr null)
        voidptr = c.context.get_value_type(types.voidptr)
        fn = cgutils.create_struct_proxy(typ)(c.context, c.builder)
        fn.c_addr = cgutils.get_null_value(voidptr)
        fn.py_addr = c.builder.ptrtoint(obj, voidptr)
        fn.jit_addr = cgutils.get_null_value(voidptr)
        addr = c.pyapi.object_getattr_string(obj, "_address")
        failed = cgutils.is_null(c.builder, addr)       # not a FunctionPointer: the AttributeError is raised
        with c.builder.if_then(c.builder.not_(failed), likely=True):
            fn.c_addr = c.pyapi.long_as_voidptr(addr)
            c.pyapi.decref(addr)
        return NativeValue(fn._getvalue(), is_error=failed)

    return True


#: whether pointers are typed :class:`AddressedFunctionType` (False: numba's ``FunctionType``,
#: the tested fallback of :func:`_install_addressed_unboxing`)
ADDRESSED = _install_addressed_unboxing()


def pointer_type(signature):
    """The numba type of a :class:`FunctionPointer` of ``signature``, and of a compiled loop's
    argument that takes one: :class:`AddressedFunctionType`, or numba's ``FunctionType`` where
    :data:`ADDRESSED` is False."""
    return AddressedFunctionType(signature) if ADDRESSED else types.FunctionType(signature)


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
        self._ftype = self._numba_type_ = pointer_type(signature)
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
    # call from Python; the type of a pointer never changes, so it is made once (the dispatcher
    # reads it from ``_numba_type_``; this is the answer of numba.typeof)
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
