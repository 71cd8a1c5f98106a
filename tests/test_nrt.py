"""Reference-count-free views (landau.verify.hybrid.nrt) and the compiled Radau IIA core that uses them.

* A borrowed view shares its owner's data, shape and strides (writes through it are seen by
  the owner), and only arrays can be borrowed.
* The Radau IIA core works on borrowed views of its buffers and returns owned arrays: results
  stay valid and unchanged after further runs and allocations, share no memory with each
  other or with the inputs, and the inputs are not modified.  The runs are checked against a
  closed form (y' = −k y: y = y₀ e^{−kt}) on three states (the loop compiled with constant
  sizes), on two (the general loop) and with the 5-stage method.
"""

from __future__ import annotations

import gc

import numba as nb
import numpy as np
import pytest
import sympy as sp

from landau.codegen.kernels import generate_kernel
from landau.verify.hybrid.collocation import radau_tableau
from landau.verify.hybrid.fastcall import addresses, collocation_at, radau_at
from landau.verify.hybrid.nrt import borrowed, keep_alive
from landau.verify.hybrid.radau import A_RADAU, VINV


@nb.njit
def _write_through(a, value):
    v = borrowed(a)
    v[1, 0] = value
    s = 0.0
    for i in range(v.shape[0]):
        for j in range(v.shape[1]):
            s += v[i, j]
    keep_alive((a,))
    return s, v.shape[0], v.shape[1], v.strides[0], v.strides[1]


def test_borrowed_view_shares_data_shape_and_strides():
    own = np.arange(12.0).reshape(3, 4)
    a = own[:, ::2]                       # a strided (non-contiguous) array
    s, n0, n1, st0, st1 = _write_through(a, 100.0)
    assert own[1, 0] == 100.0             # the write went to the owner's memory
    assert (n0, n1) == a.shape and (st0, st1) == a.strides
    assert s == a.sum()


def test_only_arrays_can_be_borrowed():
    @nb.njit
    def f(x):
        return borrowed(x)

    with pytest.raises(nb.core.errors.TypingError):
        f(1.0)


@pytest.fixture(scope="module")
def decay():
    """y_i' = −k_i y_i for three and for two states (closed form y_i(t) = y_i(0) e^{−k_i t})."""
    out = {}
    for n in (2, 3):
        ys = sp.symbols(f"y0:{n}")
        rates = [1, 3, 7][:n]
        k = generate_kernel(list(ys), [-r * y for r, y in zip(rates, ys)], [], [], name=f"nrt_decay_{n}")
        out[n] = (k, addresses(k.fun, k.jac), np.array(rates, float))
    return out


def _radau5(k, af, aj, y0, t_end, rtol, rec_cap):
    n = len(y0)
    return radau_at(af, aj, 0.0, y0, t_end, k.p, rtol, np.full(n, rtol), 1e-4, np.inf, 10 ** 6, 0, 0.5, -1, 0,
                    rec_cap, A_RADAU, VINV, np.empty((10, n + 1)), np.zeros(10))


@pytest.mark.parametrize("n", [3, 2])
def test_radau_outputs_are_owned_and_match_the_closed_form(decay, n):
    k, (af, aj), rates = decay[n]
    y0 = np.ones(n)
    y0_before = y0.copy()
    r1 = _radau5(k, af, aj, y0, 2.0, 1e-10, 1000)
    st, t, y, cnt, ev_t, ev_y, rec_t, rec_y, h, Q = r1
    assert st == 0 and t == 2.0
    # rtol 1e-10 per step over ~100 steps: the global error stays below 1e-8 relative
    assert np.allclose(y, np.exp(-rates * 2.0), rtol=1e-8, atol=0)
    # the component y_0 = e^{−t} crosses 0.5 downwards once, at t = ln 2
    assert len(ev_t) == 1 and abs(ev_t[0] - np.log(2.0)) < 1e-8
    assert rec_t[0] == 0.0 and rec_t[-1] == 2.0 and len(rec_t) == cnt[7]
    assert np.allclose(rec_y, np.exp(-np.outer(rec_t, rates)), rtol=1e-8, atol=0)
    np.testing.assert_array_equal(y0, y0_before)             # the input is not modified
    arrays = [y, cnt, ev_t, ev_y, rec_t, rec_y, Q]
    for i, a in enumerate(arrays):
        assert a.flags.writeable
        assert not np.shares_memory(a, y0)
        for b in arrays[i + 1:]:
            assert not np.shares_memory(a, b)
    kept = [a.copy() for a in arrays]
    # further runs (other states, other sizes of buffers) and allocations leave the results intact
    for _ in range(3):
        _radau5(k, af, aj, 2.0 * y0, 1.0, 1e-6, 10)
        junk = [np.full(64, np.nan) for _ in range(100)]
        del junk
        gc.collect()
    for a, b in zip(arrays, kept):
        np.testing.assert_array_equal(a, b)


def test_five_stage_run_matches_the_closed_form(decay):
    k, (af, aj), rates = decay[3]
    tb = radau_tableau(5)
    st, t, y, cnt = collocation_at(af, aj, 0.0, np.ones(3), 2.0, k.p, 1e-10, np.full(3, 1e-10), 1e-4, np.inf,
                                   10 ** 6, tb.A, tb.c, tb.e, tb.mu, tb.vinv)
    assert st == 0 and t == 2.0
    assert np.allclose(y, np.exp(-rates * 2.0), rtol=1e-8, atol=0)
    assert not np.shares_memory(y, cnt)
