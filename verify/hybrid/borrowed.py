"""Array views that carry no reference count, for compiled loops that pass work arrays on.

numba counts the references of an array with an atomic instruction each time a compiled
function receives it, copies it or passes it on (a cfunc callback included); with a null
meminfo the count is a test and a jump.  A loop takes every work array it passes to a call
that is not inlined through :func:`borrowed` and keeps the owners alive until it returns
(:func:`keep_alive`).  Measured: the counting cost the Radau IIA loop of
:mod:`landau.verify.hybrid.radau` a tenth of its time on the spring–block cycle, and the
forced oscillator's loop of :mod:`landau.verify.skurativskyi.rk` (two arrays at each call of
its field) a third: 20 periods at ω = 16 took 3.57 → 2.43 ms at rtol 1e-5 and 5.78 → 4.31 ms at
1e-7 with borrowed stage vectors (the ``forced`` section of ``benchmarks/sections_solvers.py``).

The contract: a borrowed view must not outlive its owner, so it is never returned to Python
nor stored; the loop returns the owner where it returns the array.
"""

from __future__ import annotations

import numba as nb
from numba.core import cgutils
from numba.extending import intrinsic

from landau.verify.hybrid.callbacks import jit_enabled

__all__ = ["borrowed", "keep_alive"]


@intrinsic
def _borrowed_view(typingctx, arr):
    """A view of the array ``arr`` that records no owner (its meminfo is null)."""
    def codegen(context, builder, sig, args):
        src = context.make_array(sig.args[0])(context, builder, value=args[0])
        out = context.make_array(sig.return_type)(context, builder)
        out.meminfo = cgutils.get_null_value(out.meminfo.type)
        out.parent = cgutils.get_null_value(out.parent.type)
        out.nitems = src.nitems
        out.itemsize = src.itemsize
        out.data = src.data
        out.shape = src.shape
        out.strides = src.strides
        return out._getvalue()
    return arr(arr), codegen


def _same_array(arr):
    """:func:`borrowed` as plain Python (``NUMBA_DISABLE_JIT=1``): the array itself."""
    return arr


#: ``borrowed(arr)``: a view of ``arr`` without a reference count (the array itself as plain Python)
borrowed = _borrowed_view if jit_enabled() else _same_array


@nb.njit
def keep_alive(*owners):
    """A use of the owners of a loop's borrowed views at its end: numba frees an array after its
    last use, which must not come before the views' last use.  Compiled as part of the loop that
    calls it (no disk-cache entry of its own)."""
    return None
