"""Reference-count-free views (landau.verify.hybrid.nrt): a borrowed view shares its owner's
data, shape and strides (writes through it are seen by the owner), and only arrays can be
borrowed.  (The Radau IIA integrator no longer uses them; its owned outputs are checked in
tests/test_radau.py.)
"""

from __future__ import annotations

import numba as nb
import numpy as np
import pytest

from landau.verify.hybrid.nrt import borrowed, keep_alive


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
