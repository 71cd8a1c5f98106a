"""A single velocity whose float64 value is a suspect (screened by float32, settled in long double):
the vectorised evaluation at one point (shape ()) wrote the settled value into a numpy scalar and
raised TypeError ("'numpy.float64' object does not support item assignment"); it now gives the value
the 50-digit evaluation gives."""

from __future__ import annotations

import numpy as np
import pytest

import landau
from landau.laws import get_law


def test_one_suspect_point_is_settled_like_an_array_of_one():
    d = landau.derive(landau.SpringBlock(get_law("dieterich")))
    one = d.evaluate(1e-6, None, ["Lambda"])["Lambda"]
    arr = d.evaluate(np.array([1e-6]), None, ["Lambda"])["Lambda"]
    exact = float(d.evaluate_mp(1e-6, {}, ["Lambda"])["Lambda"])
    assert np.shape(one) == () and float(one) == float(arr[0])
    assert float(one) == pytest.approx(exact, rel=1e-10)   # the evaluation's stated accuracy
