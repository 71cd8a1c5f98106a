"""Array views without numba's reference counts, for the hot loops of the compiled integrators.

numba keeps an atomic reference count on every array it hands to a compiled function (the
callee takes a reference on entry and drops it after the last use) and on every local alias
or slice.  In a step loop over a 2- or 3-state system those locked updates can be a large part
of a step: in the forced-oscillator loop of :mod:`landau.verify.skurativskyi.rk` about half
of a run.  (The Radau IIA of :mod:`landau.verify.hybrid.radau` keeps its work arrays local and
does not use these views.)  :func:`borrowed` returns a view that shares the array's data,
shape and strides but carries no memory-info pointer, so numba's reference-count calls skip
it (a test for a null pointer instead of an atomic update); :func:`keep_alive` marks the
point up to which the owners of such views must live.

Rules for a borrowed view (compiled code only):

* it must not outlive its owner: the owner is used after the last use of the view
  (numba frees an array after its last use), e.g. by :func:`keep_alive`;
* it must never be returned to Python or stored in a container that outlives the owner —
  return the owner, or a copy.
"""

from __future__ import annotations

from numba.core import types
from numba.extending import intrinsic

__all__ = ["borrowed", "keep_alive"]


@intrinsic
def borrowed(typingctx, arr):
    """A view of the array ``arr`` without a reference count (numba intrinsic; compiled code only).

    The view shares ``arr``'s data, shape and strides and has no memory-info pointer.  It must
    not outlive ``arr`` and must not be returned to Python (module docstring).

    Parameters
    ----------
    arr : numba array

    Returns
    -------
    numba array
        The same type as ``arr``.
    """
    if not isinstance(arr, types.Array):
        return None

    def codegen(context, builder, sig, args):
        src = context.make_array(sig.args[0])(context, builder, args[0])
        out = context.make_array(sig.return_type)(context, builder)
        context.populate_array(out, data=src.data, shape=src.shape, strides=src.strides,
                               itemsize=src.itemsize, meminfo=None, parent=None)
        return out._getvalue()

    return arr(arr), codegen


@intrinsic
def keep_alive(typingctx, owners):
    """Use ``owners`` (a tuple of arrays) here, so that numba keeps them alive up to this point
    (it frees an array after its last use); generates no code (compiled code only).

    Parameters
    ----------
    owners : tuple
        The owners of :func:`borrowed` views used before this point.
    """
    if not isinstance(owners, types.BaseTuple):
        return None

    def codegen(context, builder, sig, args):
        return context.get_dummy_value()

    return types.none(owners), codegen
