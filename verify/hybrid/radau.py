"""Compiled Radau IIA (order 5) integrator for small stiff systems with an analytic Jacobian.

The three-stage Radau IIA collocation method (Hairer & Wanner, *Solving ODEs II*, Sec. IV.8)
solved by simplified Newton on the full 3n×3n stage system I − h(A⊗J) (:func:`radau_core`, the
default: one dense LU per step), or in the eigenbasis of A⁻¹ as in the classical code — one real
and one complex n×n system (:func:`radau_split_core`, the same steps at 1.3–1.5× less CPU per
step on the spring–block).  Error estimate and step-size control follow
the standard radau5 recipe (embedded estimate (μ/h·I − J)⁻¹(f₀ + Σ eᵢZᵢ/h), predictive
Gustafsson controller), dense output is the collocation polynomial.

The integrator is the s-stage Radau IIA of :mod:`landau.verify.hybrid.collocation` with this
module's closed-form coefficients; its set-up, step-size control, event location and recording
are the pieces shared by the compiled stiff integrators
(:mod:`landau.verify.hybrid.stiffdriver`).  What is particular to this method is here: its
coefficients, and the retry of a failed Newton iteration with the stage Jacobians before the
step is halved.

Everything runs inside one ``numba`` function compiled once (cached on disk) that calls
the right-hand side and Jacobian through first-class function pointers of signature
``f(t, y, p, out)`` / ``jac(t, y, p, out)`` — a new friction law compiles only its own
two small functions.

Crossings of ``y[ev_idx] = ev_val`` are located on the dense output (the collocation cubic,
by the compiled event locator of :mod:`landau.verify.hybrid.crossing`) and recorded; the run
can stop after a number of crossings in a chosen direction (Poincaré returns).  Accepted steps
may be recorded for plots.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np
from numba import types

from landau.verify.hybrid.collocation import NEWTON_MAXITER, _radau_iia, radau_iia_core  # noqa: F401
from landau.verify.hybrid.stiffdriver import STATUS, _lu, _poly, _rms, _solve  # noqa: F401  (re-exported)

SQ6 = math.sqrt(6.0)
#: collocation nodes c_i and Butcher matrix A of Radau IIA (order 5)
C_NODES = np.array([(4 - SQ6) / 10, (4 + SQ6) / 10, 1.0])
A_RADAU = np.array([
    [(88 - 7 * SQ6) / 360, (296 - 169 * SQ6) / 1800, (-2 + 3 * SQ6) / 225],
    [(296 + 169 * SQ6) / 1800, (88 + 7 * SQ6) / 360, (-2 - 3 * SQ6) / 225],
    [(16 - SQ6) / 36, (16 + SQ6) / 36, 1.0 / 9],
])
#: the real eigenvalue of A⁻¹ (γ₀⁻¹) and the embedded-error weights e_i (radau5)
MU_REAL = 3 + 3 ** (2 / 3) - 3 ** (1 / 3)
E_ERR = np.array([-13 - 7 * SQ6, -13 + 7 * SQ6, -1.0]) / 3
#: Z_i = Σ_j Q_j c_i^j  →  Q = VINV·Z (dense output y(t+xh) = y + Σ Q_j x^j)
VINV = np.linalg.inv(np.array([[c ** j for j in (1, 2, 3)] for c in C_NODES]))

#: the nodes the stage equations are evaluated at: C_NODES to 16 digits (the first differs from
#: (4 − √6)/10 in the last bit; the code has used these since its first version)
_NODES = np.array([0.1550510257216822, 0.6449489742783178, 1.0])

SIG = types.void(types.float64, types.float64[::1], types.float64[::1], types.float64[::1])
SIG_JAC = types.void(types.float64, types.float64[::1], types.float64[::1], types.float64[:, ::1])
FUN_T = types.FunctionType(SIG)
JAC_T = types.FunctionType(SIG_JAC)


class FunctionPointer(types.WrapperAddressProtocol):
    """A compiled function handed to :func:`radau_core` by its machine address.

    Passing a numba dispatcher where a first-class function type is expected makes numba look
    up (and possibly compile) its wrapper at *every* call — about 0.2 ms, more than a whole
    loose-tolerance run of a small system.  This object resolves the address once; numba then
    only reads it (:meth:`__wrapper_address__`).  It keeps the dispatcher alive, so the
    address stays valid.
    """

    def __init__(self, dispatcher, signature):
        from numba.experimental.function_type import _get_wrapper_address

        self._dispatcher = dispatcher
        self._signature = signature
        self._address = _get_wrapper_address(dispatcher, signature)

    def __wrapper_address__(self) -> int:
        return self._address

    def signature(self):
        return self._signature

    def __call__(self, *args):
        return self._dispatcher(*args)


_POINTERS: dict[tuple[int, str], FunctionPointer] = {}


def pointers(fun, jac) -> tuple[FunctionPointer, FunctionPointer]:
    """(fun, jac) as :class:`FunctionPointer` objects for :func:`radau_core` (made once per function).

    Parameters
    ----------
    fun, jac : numba dispatchers
        ``fun(t, y, p, out)`` and ``jac(t, y, p, out)`` (signatures :data:`SIG`, :data:`SIG_JAC`).

    Returns
    -------
    tuple of FunctionPointer
    """
    out = []
    for f, sig, tag in ((fun, SIG, "f"), (jac, SIG_JAC, "J")):
        if isinstance(f, FunctionPointer):
            out.append(f)
            continue
        key = (id(f), tag)
        ptr = _POINTERS.get(key)
        if ptr is None or ptr._dispatcher is not f:
            ptr = _POINTERS[key] = FunctionPointer(f, sig)
        out.append(ptr)
    return out[0], out[1]
F64 = types.float64
A1 = types.float64[::1]
A2 = types.float64[:, ::1]
I64 = types.int64


@nb.njit(types.Tuple((I64, F64, A1, I64[::1], A1, A2, A1, A2, F64, A2))(
    FUN_T, JAC_T, F64, A1, F64, A1, F64, A1, F64, F64, I64, I64, F64, I64, I64, I64, A2, A2, A2, A1), cache=True)
def radau_core(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps,
               ev_idx, ev_val, ev_dir, ev_stop, rec_cap, AR, VI, EVBUF, EVDIR):
    """Integrate from t0 to t_end.  Returns (status, t, y, counters, ev_t, ev_y, rec_t, rec_y, h, Q).

    counters = [accepted steps, rejected steps, f evaluations, Jacobians, LU decompositions,
    Newton failures, events, recorded steps].  ``EVBUF`` (m × n) / ``EVDIR`` (m) receive
    crossings; ``ev_idx < 0`` disables events; ``ev_stop > 0`` stops after that many
    crossings in direction ``ev_dir`` (±1, 0 = either).  ``h`` is the next step size and ``Q``
    the last accepted step's collocation polynomial (y(t_old + x h_old) = y_old + Σ_j Q_j x^{j+1}),
    so that a caller can drive the method one step at a time (``max_steps = 1``).  The step is
    :func:`landau.verify.hybrid.collocation.radau_iia_core` with this module's coefficients and
    a failed Newton iteration retried with the stage Jacobians.
    """
    if y0.shape[0] == 3:
        # the spring–block's three states: the loop compiled with constant sizes (same arithmetic)
        return _radau_iia(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir,
                          ev_stop, rec_cap, AR, _NODES, E_ERR, MU_REAL, VI, True, True, EVBUF, EVDIR, 3, 3)
    return radau_iia_core(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir,
                          ev_stop, rec_cap, AR, _NODES, E_ERR, MU_REAL, VI, True, True, EVBUF, EVDIR)


from landau.verify.hybrid.collocation import _radau_split, _radau_split_any, split_coefficients  # noqa: E402

#: A⁻¹ = T·diag(γ, [[α, −β], [β, α]])·T⁻¹, computed from :data:`A_RADAU` (:func:`split_coefficients`)
T_SPLIT, TI_SPLIT, GAMMA_SPLIT, ALPHA_SPLIT, BETA_SPLIT = split_coefficients(A_RADAU)


@nb.njit(types.Tuple((I64, F64, A1, I64[::1], A1, A2, A1, A2, F64, A2))(
    FUN_T, JAC_T, F64, A1, F64, A1, F64, A1, F64, F64, I64, I64, F64, I64, I64, I64, A2, A2, A2, A2, F64, F64, F64,
    A2, A1), cache=True)
def radau_split_core(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps,
                     ev_idx, ev_val, ev_dir, ev_stop, rec_cap, AR, VI, T, TI, gam, alp, bet, EVBUF, EVDIR):
    """:func:`radau_core` with the Newton system solved in the eigenbasis of A⁻¹: one real and
    one complex n × n LU per step instead of one 3n × 3n LU
    (:func:`landau.verify.hybrid.collocation._radau_split_body`; ``T``, ``TI``, ``gam``, ``alp``,
    ``bet`` from :func:`landau.verify.hybrid.collocation.split_coefficients`, e.g.
    :data:`T_SPLIT`…).  Same arguments and returned tuple as :func:`radau_core`; the results
    agree with it to the integration tolerance, not to the bit.
    """
    if y0.shape[0] == 3:
        return _radau_split(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir,
                            ev_stop, rec_cap, AR, _NODES, E_ERR, VI, T, TI, gam, alp, bet, EVBUF, EVDIR, 3)
    return _radau_split_any(fun, jac, t0, y0, t_end, p, rtol, atol, h0, max_step, max_steps, ev_idx, ev_val, ev_dir,
                            ev_stop, rec_cap, AR, _NODES, E_ERR, VI, T, TI, gam, alp, bet, EVBUF, EVDIR, y0.shape[0])
