"""The compiled field and guards of the non-smooth mode-coupling model against the equations written out
here in numpy (Hoffmann, Fischer, Allgaier & Gaul 2002; the N-DOF family by a linear solve of M a = f)."""

import math

import numpy as np
import pytest

from landau.laws.velocity import VelocityFriction
from landau.verify.modecoupling.nonsmooth import (
    MODES,
    Contact,
    Structure,
    field_kernel,
    guard_kernel,
    hoffmann_structure,
    hybrid_model,
)


def hoffmann_numpy(mode, y, *, m=1.0, k1=1.0, k2=0.5, a1=30.0, a2=60.0, kH=1.0, kNL=0.0, P=1.0, c1=0.02, c2=0.04,
                   F=lambda v: 0.9, v0=1.0, law="linear"):
    """The paper's two equations, m x'' + c1 x' + k11 x + k12 y = F N, m y'' + c2 y' + k12 x + k22 y = P - N."""
    a1, a2 = math.radians(a1), math.radians(a2)
    k11 = k1 * math.cos(a1) ** 2 + k2 * math.cos(a2) ** 2
    k12 = k1 * math.sin(a1) * math.cos(a1) - k2 * math.sin(a2) * math.cos(a2)
    k22 = k1 * math.sin(a1) ** 2 + k2 * math.sin(a2) ** 2
    x, yy, xd, yd = y
    N = 0.0 if mode == "flight" else (kH * yy ** 1.5 if law == "hertz" else kH * yy + kNL * yy ** 3)
    fx = -c1 * xd - k11 * x - k12 * yy
    fy = -c2 * yd - k12 * x - k22 * yy + P - N
    if mode == "stick":
        return np.array([xd, yd, 0.0, fy / m]), -fx        # the holding force cancels the tangential force
    if mode.startswith("slip"):
        fx += F(v0 - xd) * N
    return np.array([xd, yd, fx / m, fy / m]), None


@pytest.mark.parametrize("law,kNL", [("linear", 0.0), ("cubic", -0.3), ("hertz", 0.0)])
@pytest.mark.parametrize("mode", MODES)
def test_hoffmann_field_against_numpy(mode, law, kNL):
    # Coulomb mu = 0.9; F(v) = -0.9 on the slip- side (the odd extension)
    s = hoffmann_structure(mu=0.9, contact=law, kNL=kNL, c1=0.02, c2=0.04)
    rng = np.random.default_rng(7)
    k = field_kernel(s, mode)
    for _ in range(5):
        y = np.array([rng.normal(), 0.2 + rng.random(), rng.normal(), rng.normal()])
        if mode == "slip-":
            y[2] = 1.0 + rng.random()          # x' > v0: the mass overtakes the belt
        if mode == "stick":
            y[2] = 1.0
        want, _ = hoffmann_numpy(mode, y, kNL=kNL, law=law, F=lambda v: 0.9 if v > 0 else -0.9)
        # the same arithmetic in another order: agreement to a few ulps of the largest term
        np.testing.assert_allclose(k(0.0, y), want, rtol=1e-13, atol=1e-14)


def test_velocity_law_field():
    # a Stribeck-like coefficient F(v) = mu_d + (mu_s - mu_d) exp(-v/vs) of v_rel = v0 - x'
    law = VelocityFriction.from_strings("stribeck", "md + (ms - md)*exp(-v/vs)", params={"md": 0.5, "ms": 0.9,
                                                                                            "vs": 0.3})
    s = hoffmann_structure(contact="cubic", kNL=0.2, friction=law, v0=1.3)
    y = np.array([0.1, 0.6, 0.4, -0.2])
    want, _ = hoffmann_numpy("slip+", y, kNL=0.2, law="cubic", v0=1.3,
                             F=lambda v: 0.5 + 0.4 * math.exp(-v / 0.3))
    np.testing.assert_allclose(field_kernel(s, "slip+")(0.0, y), want, rtol=1e-13, atol=1e-14)
    assert s.static == pytest.approx((0.9, 0.9), rel=1e-15)


def test_ndof_field_and_guards_against_a_linear_solve():
    # a 3-DOF structure with a full mass matrix: a = M^-1 f solved here by numpy, the stick force from
    # the constraint a[t] = 0 (two unknowns: the holding force and the other accelerations)
    rng = np.random.default_rng(3)
    B = rng.normal(size=(3, 3))
    M = B @ B.T + 3 * np.eye(3)
    K = np.array([[3.0, -1.0, 0.2], [-1.0, 2.5, -0.7], [0.2, -0.7, 2.0]])
    C = 0.05 * np.eye(3) + 0.01 * np.ones((3, 3))
    s = Structure(M, C, K, normal=2, tangential=0, preload=2.0, v0=0.8, contact=Contact("cubic", 1.5, 0.4), mu=0.6)
    y = np.array([0.3, -0.2, 0.5, 0.1, 0.05, -0.3])
    x, v = y[:3], y[3:]
    N = 1.5 * 0.5 + 0.4 * 0.5 ** 3
    base = -C @ v - K @ x + np.array([0.0, 0.0, 2.0 - N])
    slip = base + np.array([0.6 * N, 0.0, 0.0])
    np.testing.assert_allclose(field_kernel(s, "slip+")(0.0, y)[3:], np.linalg.solve(M, slip), rtol=1e-12, atol=1e-14)
    # stick: M a = base + lam e_0 with a_0 = 0  ->  [M e_0 ... ] unknowns (lam, a_1, a_2)
    A = np.column_stack([-np.eye(3)[:, 0], M[:, 1], M[:, 2]])
    lam, a1, a2 = np.linalg.solve(A, base)
    ys = y.copy()
    ys[3] = 0.8
    base_s = -C @ ys[3:] - K @ x + np.array([0.0, 0.0, 2.0 - N])
    lam, a1, a2 = np.linalg.solve(A, base_s)
    np.testing.assert_allclose(field_kernel(s, "stick")(0.0, ys)[3:], [0.0, a1, a2], rtol=1e-12, atol=1e-13)
    g = np.empty(3)
    gk = guard_kernel(s, "stick")
    gk.fun(0.0, ys, gk.p, g)
    np.testing.assert_allclose(g, [0.5, 0.6 * N - lam, 0.6 * N + lam], rtol=1e-12, atol=1e-13)
    # the Python guards of the hybrid model give the same numbers (the engine locates on them)
    py = [gd.fun(0.0, ys) for gd in hybrid_model(s).mode("stick").guards]
    np.testing.assert_allclose(py, g, rtol=1e-12, atol=1e-13)
