"""Λ on a Hopf line without closed form (two state variables): the float64 (k_c, ω_c) it is evaluated
at carry a rounding error that a sensitive Λ amplifies past 1e-10, although float64 and long double
agree at those inputs. Independent reference: 40-digit mpmath (k_c, ω_c and Λ all in mpmath)."""

from __future__ import annotations

import numpy as np

from landau.derivation.multiscale import derive
from landau.laws import get_law
from landau.systems.system import SpringBlock


def test_lambda_where_it_amplifies_the_error_of_k_c():
    d = derive(SpringBlock(get_law("two-state-dieterich")), ["Lambda"])
    # V where |d ln Λ / d ln k_c| ~ 1e6 (Λ ≈ 2.9e5 over k_c ≈ 26512 N/m barely moving): one ulp of
    # k_c moved Λ by up to 1.1e-10 here (found on the benchmark's 1000 log-spaced points)
    Vs = np.array([2.5728259674479322e-06, 2.9749075472144434e-06, 3.0724688427090035e-06,
                   3.1224428230928577e-06, 3.913745601980384e-06])
    got = d.evaluate(Vs, {}, ["Lambda"])["Lambda"]
    for V, g in zip(Vs, got, strict=True):
        want = float(d.evaluate_mp(float(V), {}, ["Lambda"], dps=40)["Lambda"])
        assert abs(g - want) <= 1e-10 * abs(want), (V, g, want)
