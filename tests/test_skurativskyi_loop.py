"""The compiled switching loop of landau.verify.skurativskyi.rk: its DOPRI5 steps are those of
the generic compiled DOPRI5 of landau.verify.hybrid.compiled to the bit, and its refcount-free
views (``rk.borrowed``) share their owner's data.

The loop inlines the field and writes the DOPRI5 stages into preallocated buffers (speed only);
the published bifurcation values of Skurativskyi et al. (2019) were computed with the generic
step, and the period-doubling cascade near ω = 20.4 follows the last bit of the step sequence,
so the two must agree with ``==`` — here on random states and step lengths, in and out of
contact, for the 2-D field and the 4-D one with a tangent vector.
"""

from __future__ import annotations

import sys

import numpy as np
import pytest
from numba import njit

from landau.verify.hybrid.compiled import dopri5_method
from landau.verify.skurativskyi import rk as R
from landau.verify.skurativskyi.model import Params, compiled_field
from landau.verify.skurativskyi.simulate import integrators, run


@njit(cache=True)
def _view_write(a):
    v = R.borrowed(a)
    v[0] = 7.0
    return v[1] + v.shape[0]


def _loop_module(params):
    """The specialised template module holding the loop built for ``params``."""
    _, mixed = integrators(params)
    return sys.modules[mixed.py_func.__module__]


@pytest.mark.parametrize("n", [2, 4])
def test_loop_dopri5_step_equals_the_generic_compiled_step(n):
    prm = Params(omega=20.4)
    p = prm.packed()
    k = compiled_field(prm)
    generic, _ = dopri5_method(k.rhs)
    mod = _loop_module(prm)
    rng = np.random.default_rng(3)
    for _ in range(300):
        # states on both sides of the obstacle x_I, velocities through the friction layer
        y = np.empty(n)
        y[0] = prm.xI + rng.uniform(-2e-4, 2e-4)
        y[1] = rng.choice([-1.0, 1.0]) * 10.0 ** rng.uniform(-9, -1)
        if n == 4:
            y[2:] = rng.normal(size=2)
        t = rng.uniform(0.0, 10.0)
        h = 10.0 ** rng.uniform(-7, -2)
        k1 = np.empty(n)
        k.rhs(t, y, p, k1)
        a = [np.empty(n) for _ in range(3)]
        b = [np.empty(n) for _ in range(3)]
        generic(p, t, y, k1, h, *a)
        scratch = [np.empty(n) for _ in range(6)]
        mod.dp5_step(p, t, y, k1, h, *b, *scratch)
        for u, w in zip(a, b):
            assert np.array_equal(u, w)


def test_borrowed_view_shares_the_owners_data():
    a = np.array([1.0, 2.0, 3.0])
    assert _view_write(a) == 2.0 + 3
    assert a[0] == 7.0


def test_run_returns_owned_arrays():
    # the loop works on borrowed views; the final state it returns must be an owned copy
    # (a view of freed buffers would be overwritten by the next run's allocations)
    r1 = run(Params(omega=16.0), 1, rtol=1e-6)
    y = r1.y.copy()
    r1.y[0] = 1.0
    r2 = run(Params(omega=16.0), 1, rtol=1e-6)
    assert np.array_equal(r2.y, y)
    assert r1.y[0] == 1.0
