"""The compiled switching loop of landau.verify.skurativskyi.rk: its DOPRI5 steps are those of
the generic compiled DOPRI5 of the tests' oracle (support_dopri5) to the bit, and it returns owned
arrays.

The loop inlines the field and writes the DOPRI5 stages into preallocated buffers (speed only);
the published bifurcation values of Skurativskyi et al. (2019) were computed with the generic
step, and the period-doubling cascade near ω = 20.4 follows the last bit of the step sequence,
so the two must agree with ``==`` — here on random states and step lengths, in and out of
contact, for the 2-D field and the 4-D one with a tangent vector.
"""

from __future__ import annotations

import numpy as np
import pytest
from support_dopri5 import dopri5_method

from landau.verify.skurativskyi import rk as R
from landau.verify.skurativskyi.friction import quiet_first_class
from landau.verify.skurativskyi.model import Params, compiled_field
from landau.verify.skurativskyi.simulate import run


@pytest.mark.parametrize("n", [2, 4])
def test_loop_dopri5_step_equals_the_generic_compiled_step(n):
    prm = Params(omega=20.4)
    p = prm.packed()
    k = compiled_field(prm)
    generic, _ = dopri5_method(k.rhs)
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
        with quiet_first_class():
            R.dp5_step(p, t, y, k1, h, *b, *scratch, k.pointers)
        for u, w in zip(a, b, strict=True):
            assert np.array_equal(u, w)


def test_run_returns_owned_arrays():
    # the final state the loop returns must be owned by the result (a view of buffers reused
    # by the next run would be overwritten)
    r1 = run(Params(omega=16.0), 1, rtol=1e-6)
    y = r1.y_final.copy()
    r1.y_final[0] = 1.0
    r2 = run(Params(omega=16.0), 1, rtol=1e-6)
    assert np.array_equal(r2.y_final, y)
    assert r1.y_final[0] == 1.0
