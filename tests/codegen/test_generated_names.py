"""Numeric functions generated from expressions never confuse a user's symbol with a name of the
generated code (sympy's lambdify binds every symbol of the expression by its name, next to the
printed functions ``cos``, ``array``…): a parameter named ``cos`` or ``array`` gives the same numbers
as the same parameter under another name."""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from landau import DynamicalSystem, Verdict, check
from landau.laws.velocity import VelocityFriction
from landau.support.lambdify import lambdify_positional


@pytest.mark.parametrize("name", ["cos", "array", "exp", "select", "_a1"])
def test_lambdify_positional_with_function_names(name):
    """cos(x)/c + exp(c) with c named like a printed function: the closed form at (0.3, 2)."""
    x, c = sp.symbols(f"x {name}", real=True)
    expr = sp.cos(x) / c + sp.exp(c)
    want = math.cos(0.3) / 2 + math.exp(2)
    for modules in ("math", "numpy", "mpmath"):
        assert float(lambdify_positional([x, c], expr, modules)(0.3, 2.0)) == pytest.approx(want, rel=1e-15)
    J = lambdify_positional([x, c], sp.Matrix([expr]).jacobian([x, c]), "numpy")(0.3, 2.0)
    np.testing.assert_allclose(J, [[-math.sin(0.3) / 2, -math.cos(0.3) / 4 + math.exp(2)]], rtol=1e-15)
    # nested arguments, as for lambdify([states], ...)
    assert lambdify_positional([[x, c]], [expr], "math")([0.3, 2.0])[0] == pytest.approx(want, rel=1e-15)


def test_velocity_law_parameter_named_cos():
    """A velocity law c0*cos(v/cos): the branch function equals the closed form."""
    law = VelocityFriction.from_strings("w", "c0*cos(v/cos)", params={"c0": 0.4, "cos": 0.5})
    law2 = VelocityFriction.from_strings("w", "c0*cos(v/e1)", params={"c0": 0.4, "e1": 0.5})
    for vv in (0.01, 0.2):
        assert float(law(vv)) == pytest.approx(0.4 * math.cos(vv / 0.5), rel=1e-14)
        assert float(law(vv)) == float(law2(vv))


def test_impact_oscillator_hopf_with_a_parameter_named_cos():
    """The impact oscillator's slip Hopf point for mu*tanh(v/e) is the same with e named cos or array."""
    from landau.verify.lancioni.slip import slip_hopf

    def mu_c(name):
        law = VelocityFriction.from_strings("w", f"mu*tanh(v/{name})", params={"mu": 0.4, name: 0.05})
        return slip_hopf(friction=law).p_c

    ref = mu_c("e1")
    assert mu_c("cos") == pytest.approx(ref, rel=1e-12)
    assert mu_c("array") == pytest.approx(ref, rel=1e-12)


def test_general_system_with_a_parameter_named_cos():
    """ż = (μ + i)z + a z|z|² with a = −cos(c) and c named ``cos`` = 0: the cycle has radius sqrt(μ)
    exactly (Kuznetsov 2004, eq. 8.19 with ω = 1)."""
    x, y, mu, c = sp.symbols("x y mu cos", real=True)
    r2 = x * x + y * y
    a = -sp.cos(c)
    system = DynamicalSystem("polar", (x, y), (mu * x - y + a * r2 * x, x + mu * y + a * r2 * y),
                             (sp.Integer(1), sp.Integer(1)), mu, (sp.Integer(0), sp.Integer(0)),
                             defaults={"cos": 0.0})
    r = check(system, eps2=1e-2, bracket=(-0.5, 0.5))
    assert r.verdict is Verdict.AGREES
    assert r.amplitude_simulated == pytest.approx(math.sqrt(r.p), rel=1e-6)
