"""The one numeric field builder of a system as the cycle engine reads it: ∂f/∂p and the multilinear
forms B, C of ẏ = E(p)⁻¹ f against central differences of the field and its Jacobian (an independent
route), on a system whose mass matrix depends on the parameter."""

from __future__ import annotations

import numpy as np
import pytest

from landau.errors import InputError
from landau.periodic import CycleProblem
from landau.systems.system import DynamicalSystem


def _system() -> DynamicalSystem:
    # E = diag(1, 1 + p²): a mass that depends on the continuation parameter, so ∂ẏ/∂p has the
    # product-rule term −E⁻¹(∂E/∂p)E⁻¹f that a plain ∂f/∂p misses
    return DynamicalSystem.from_strings(
        {"x": "p*x - y + a*x^2*y - x^3", "y": "x + p*y + sin(x*y)"}, "p", {"a": 0.7},
        mass={"y": "1 + p^2"}, equilibrium={"x": "0", "y": "0"}, name="massive")


def test_dfdp_and_forms_equal_differences_of_the_field():
    pr = CycleProblem.from_system(_system())
    rng = np.random.default_rng(3)
    y = rng.normal(size=(2, 5))
    u, v, w = (rng.normal(size=(2, 5)) for _ in range(3))
    p, h = 0.4, 1e-5
    # central differences: O(h²) ≈ 1e-10 truncation, round-off ~1e-11/h ≈ 1e-6 relative for the
    # second difference of the Jacobian (C), so 1e-8 for ∂f/∂p and B, 1e-5 for C
    fd_p = (pr.rhs(y, p + h) - pr.rhs(y, p - h)) / (2 * h)
    assert np.max(np.abs(pr.dfdp(y, p) - fd_p)) < 1e-8
    Jd = (pr.jac(y + h * v, p) - pr.jac(y - h * v, p)) / (2 * h)
    B = pr.multilinear[0](y, p, u, v)
    assert np.max(np.abs(B - np.einsum("abm,bm->am", Jd, u))) < 1e-8
    J2 = (pr.jac(y + h * w + h * v, p) - pr.jac(y + h * w - h * v, p)
          - pr.jac(y - h * w + h * v, p) + pr.jac(y - h * w - h * v, p)) / (4 * h * h)
    C = pr.multilinear[1](y, p, u, v, w)
    assert np.max(np.abs(C - np.einsum("abm,bm->am", J2, u))) < 1e-5
    assert B.shape == C.shape == (2, 5)


def test_an_algebraic_row_is_refused_at_build():
    system = DynamicalSystem.from_strings({"x": "p*x - y", "y": "x + y^3"}, "p", mass={"y": "0"},
                                          equilibrium={"x": "0", "y": "0"}, name="dae")
    with pytest.raises(InputError, match="mass matrix is singular"):
        CycleProblem.from_system(system)
