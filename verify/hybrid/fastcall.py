"""Call the compiled integrators with kernels given by machine address (no per-call look-up).

Handing a first-class function (a numba dispatcher or a
:class:`~landau.verify.hybrid.radau.FunctionPointer`) to a compiled function from Python costs
numba a type look-up and an unboxing of each function argument at every call — about 20 µs
for the pair (f, J), a tenth of a loose-tolerance spring-block period.  The entry points here
take the two addresses as plain integers (resolved once, :func:`addresses`) and rebuild the
function values inside compiled code, so a call costs what its array arguments cost.

The addresses stay valid as long as the :class:`FunctionPointer` objects that produced them
are alive; :func:`addresses` returns them from the same cache as
:func:`landau.verify.hybrid.radau.pointers`, which keeps them for the life of the process.

The entry points are compiled on first use and cached on disk.  numba's cache of a function
is invalidated by changes to *its own* source file only: after editing a core these wrap
(:mod:`~landau.verify.hybrid.radau`, :mod:`~landau.verify.hybrid.rosenbrock`,
:mod:`~landau.verify.hybrid.collocation`) or the step loop they share
(:mod:`~landau.verify.hybrid.stiffdriver`), delete the cache files of this module and of the
cores (``__pycache__/*.nbi``, ``*.nbc``) in a development checkout.
"""

from __future__ import annotations

import numba as nb
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

from landau.verify.hybrid.collocation import collocation_core
from landau.verify.hybrid.radau import FUN_T, JAC_T, pointers, radau_core, radau_split_core
from landau.verify.hybrid.rosenbrock import rosenbrock_core

__all__ = ["addresses", "collocation_at", "radau_at", "rosenbrock_at"]


def _function_at(ftype):
    @intrinsic
    def at(typingctx, addr):
        if not isinstance(addr, types.Integer):
            return None

        def codegen(context, builder, signature, args):
            fn = cgutils.create_struct_proxy(ftype)(context, builder)
            fn.c_addr = builder.inttoptr(args[0], context.get_value_type(types.voidptr))
            return fn._getvalue()

        return ftype(addr), codegen

    return at


#: the first-class right-hand side / Jacobian at a machine address (compiled code only)
fun_at = _function_at(FUN_T)
jac_at = _function_at(JAC_T)


def addresses(fun, jac) -> tuple[int, int]:
    """Machine addresses of the C wrappers of ``fun(t, y, p, out)`` and ``jac(t, y, p, out)``.

    Parameters
    ----------
    fun, jac : numba dispatchers or FunctionPointer
        The kernel's right-hand side and Jacobian (signatures
        :data:`~landau.verify.hybrid.radau.SIG`, :data:`~landau.verify.hybrid.radau.SIG_JAC`).

    Returns
    -------
    (int, int)
        Valid while the process lives (the pointers are cached).
    """
    f, j = pointers(fun, jac)
    return f.__wrapper_address__(), j.__wrapper_address__()


@nb.njit(cache=True)
def radau_at(af, aj, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir, ev_stop,
             rec_cap, AR, VI, EVBUF, EVDIR):
    """:func:`~landau.verify.hybrid.radau.radau_core` with (f, J) given by address."""
    return radau_core(fun_at(af), jac_at(aj), t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx,
                      ev_val, ev_dir, ev_stop, rec_cap, AR, VI, EVBUF, EVDIR)


@nb.njit(cache=True)
def radau_split_at(af, aj, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir, ev_stop,
                   rec_cap, AR, VI, T, TI, gam, alp, bet, EVBUF, EVDIR):
    """:func:`~landau.verify.hybrid.radau.radau_split_core` with (f, J) given by address."""
    return radau_split_core(fun_at(af), jac_at(aj), t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx,
                            ev_val, ev_dir, ev_stop, rec_cap, AR, VI, T, TI, gam, alp, bet, EVBUF, EVDIR)


@nb.njit(cache=True)
def rosenbrock_at(af, aj, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir, ev_stop,
                  rec_cap, autonomous, one_step, RA, RC, RCN, RD, RM, RE, EVBUF, EVDIR):
    """:func:`~landau.verify.hybrid.rosenbrock.rosenbrock_core` with (f, J) given by address."""
    return rosenbrock_core(fun_at(af), jac_at(aj), t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx,
                           ev_val, ev_dir, ev_stop, rec_cap, autonomous, one_step, RA, RC, RCN, RD, RM, RE, EVBUF,
                           EVDIR)


@nb.njit(cache=True)
def collocation_at(af, aj, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, AR, CN, EE, mu, VI):
    """:func:`~landau.verify.hybrid.collocation.collocation_core` with (f, J) given by address."""
    return collocation_core(fun_at(af), jac_at(aj), t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, AR, CN,
                            EE, mu, VI)
