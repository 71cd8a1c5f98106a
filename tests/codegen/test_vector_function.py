"""Generated vector functions with any number of components (landau/codegen/kernels.py
``generate_vector_function``, the route of a hybrid mode's compiled guards): values against the
expressions evaluated by sympy, and the refusals."""

import numpy as np
import pytest
import sympy as sp

from landau.codegen.kernels import generate_vector_function, kernel_source
from landau.errors import InputError


def test_components_equal_sympy_values():
    x, v, t, a = sp.symbols("x v t a", real=True)
    comps = [x - a * sp.cos(t), -v, x * v + sp.exp(-a * x)]
    g = generate_vector_function([x, v], comps, [a], [0.7], time=t, name="three")
    out = np.empty(3)
    for tt, xx, vv in ((0.0, 1.0, 2.0), (1.3, -0.4, 0.25)):
        g.fun(tt, np.array([xx, vv]), g.p, out)
        ref = [float(c.subs({x: xx, v: vv, t: tt, a: 0.7})) for c in comps]
        assert out == pytest.approx(ref, rel=1e-14, abs=1e-15)
    assert g.n == 2 and g.jac is None


def test_refusals():
    x, a = sp.symbols("x a")
    with pytest.raises(InputError, match="Jacobian"):
        kernel_source([x], [x, 2 * x], [], jacobian=True, square=False)
    with pytest.raises(InputError, match="at least one"):
        kernel_source([x], [], [], jacobian=False, square=False)
    with pytest.raises(InputError, match="values"):
        generate_vector_function([x], [x - a, a], [a], None)
    # a vector field still needs one component per state
    with pytest.raises(InputError, match="components"):
        kernel_source([x], [x, 2 * x], [], jacobian=False)
