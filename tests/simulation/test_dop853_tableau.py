"""The DOP853 tableau (landau.verify.hybrid.dop853_tableau): consistency conditions of an explicit
Runge–Kutta method in closed form, and the same numbers as scipy's DOP853."""

import numpy as np
import pytest

from landau.verify.hybrid import dop853_tableau as T


def test_row_sums_are_the_nodes_and_the_weights_sum_to_one():
    # c_i = Σ_j a_ij for every stage (the method integrates t' = 1 exactly), Σ b_i = 1 (order ≥ 1)
    np.testing.assert_allclose(T.A.sum(axis=1), T.C, rtol=0, atol=1e-14)
    assert abs(T.B.sum() - 1.0) < 1e-14
    # explicit: strictly lower triangular
    assert np.all(np.triu(T.A) == 0.0)


def test_order_conditions_up_to_order_four():
    # Σ b_i c_i^{k-1} = 1/k for k = 1..8 (the quadrature conditions of an order-8 method)
    b, c = T.B, T.C[: T.N_STAGES]
    for k in range(1, 9):
        assert abs(np.dot(b, c ** (k - 1)) - 1.0 / k) < 1e-13, k
    # Σ b_i a_ij c_j = 1/6 (order 3), Σ b_i c_i a_ij c_j = 1/8 (order 4)
    a = T.A[: T.N_STAGES, : T.N_STAGES]
    assert abs(b @ a @ c - 1 / 6) < 1e-13
    assert abs((b * c) @ a @ c - 1 / 8) < 1e-13


def test_same_numbers_as_scipy():
    dc = pytest.importorskip("scipy.integrate._ivp.dop853_coefficients")
    for name in ("A", "B", "C", "D", "E3", "E5"):
        assert np.array_equal(getattr(T, name), getattr(dc, name)), name
