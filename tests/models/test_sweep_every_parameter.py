"""Every registered model, every declared parameter: a two-point sweep equals the single-point calls.

For each model that offers a Hopf analysis, each parameter it declares (but its Hopf parameter, whose
critical value is what is computed) is swept over two values: its default and a value 1 % away (or
0.01 where the default is 0).  Each point's p_c and Λ must equal the model's own Hopf analysis at that
point (:attr:`landau.models.Model.hopf`, what ``landau hopf`` prints): to the last bit where the sweep
takes the same route, within 1e-9 relative where the spring–block's sweep evaluates a whole chunk
through the vectorised kernels (the single call evaluates one point of the same closed form; the
two differ by rounding, measured at most ~1e-13), and a point without a Hopf point must be ``no-hopf``
in both.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import landau
import landau.models as models
from landau.errors import NoHopfError

#: the law and options each model is swept with (a user system: the Brusselator, b_c = 1 + a^2)
SETUPS = {
    "spring-block": ("dieterich", {}),
    "spring-block-chain": ("dieterich", {"blocks": 2}),
    "system": (None, {"rhs": {"x": "a - (b + 1)*x + x^2*y", "y": "b*x - x^2*y"}, "parameter": "b",
                      "equilibrium": {"x": "a", "y": "b/a"}, "bracket": (1.0, 30.0)}),
    "impact-oscillator": (None, {}),
    "galvanetto-one-block": (None, {}),
    "mode-coupling": (None, {}),
}
#: the fixed values a model needs that have no default (the Brusselator's a)
FIXED = {"system": {"a": 1.5}}
#: the spring-block's vectorised chunk against its single-point evaluation (see the module docstring)
RTOL_VECTOR = 1e-9


def _cases():
    for name in models.names():
        m = models.get(name)
        if not m.offers("hopf"):
            continue
        law, options = SETUPS[name]
        setup = models.Setup(landau.laws.get_law(law) if law else None, FIXED.get(name, {}), options)
        hp = m.bifurcation_parameter(setup)
        for p in m.parameters(setup):
            if p.name == hp:
                continue
            yield pytest.param(name, p.name, id=f"{name}-{p.name}")


def test_every_hopf_model_is_covered():
    assert {n for n in models.names() if models.get(n).offers("hopf")} == set(SETUPS)


def _values(p, fixed):
    x0 = fixed.get(p.name, p.default)
    if x0 is None:
        pytest.fail(f"parameter {p.name!r} has no default: give it in FIXED")
    return [float(x0), float(x0 * 1.01) if x0 != 0 else 0.01]


def _single(model, law, params, options):
    try:
        res = model.hopf(models.Setup(law, params, options))
    except NoHopfError:
        return "no-hopf", math.nan, math.nan
    return ("degenerate" if res.criticality == "degenerate" else "ok"), float(res.p_c), float(res.Lambda)


@pytest.mark.parametrize("model_name,param", list(_cases()))
def test_two_point_sweep_equals_the_single_calls(model_name, param):
    import landau.laws

    m = models.get(model_name)
    law_name, options = SETUPS[model_name]
    law = landau.laws.get_law(law_name) if law_name else None
    fixed = dict(FIXED.get(model_name, {}))
    p = m.parameter(param, models.Setup(law, fixed, options))
    values = _values(p, fixed)
    fixed.pop(param, None)
    ds = landau.sweep("hopf", {param: values}, model=model_name, law=law_name, params=fixed, options=options,
                      workers=1, progress=False)
    vectorised = model_name == "spring-block" and param != "alpha_ld"
    for j, x in enumerate(values):
        status, pc, lam = _single(m, law, {**fixed, param: x}, options)
        assert str(ds.status.values[j]) == status, (param, x, str(ds.message.values[j]))
        if status == "no-hopf":
            continue
        got_pc, got_lam = float(ds.p_c.values[j]), float(ds.Lambda.values[j])
        if vectorised:
            np.testing.assert_allclose([got_pc, got_lam], [pc, lam], rtol=RTOL_VECTOR, err_msg=f"{param} = {x}")
        else:
            assert (got_pc, got_lam) == (pc, lam), (param, x)
