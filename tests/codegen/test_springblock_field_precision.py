"""The compiled spring–block field of Putelat et al. (2010), eq. (4) in scaled variables, against
the same field evaluated from the law at 30 significant digits (mpmath).

The kernels read a parameter vector extended by the field's parameter-only subexpressions (logs
of parameters, products, quotients: :func:`landau.codegen.kernels.hoist_parameters`), computed once
per model.  These tests check that the values they produce are those of eq. (4), to within
the rounding that double precision allows at each point:

    |f_kernel − f_exact| ≤ 16 ε S,   S = Σ_terms |term|  (ε = 2⁻⁵²),

the sum running over the terms of the fully expanded component (logarithms expanded, a log
counted as |ln x| + 1 because its argument carries a relative rounding error that becomes an
absolute one).  S is the condition scale of the sum: near steady sliding μ − μ₀ cancels to far
below its terms, and no evaluation order in double precision does better than ε times them.
The factor 16 covers the ≲ 10 roundings along a term (products, the libm exp/log to 1 ulp,
the once-evaluated parameter combinations); the measured errors are ≤ 1.8 ε S (the kernel of
the unhoisted field, evaluating the logarithms of parameters at every call, gives ≤ 2.6 ε S).
An error of 1e-12 in the first derived parameter (a logarithm of parameters for the
Dieterich law) exceeds the bound (≈ 48 ε S for Dieterich, more for the other laws).
"""

from __future__ import annotations

import ast

import mpmath
import numpy as np
import pytest
import sympy as sp

from landau.codegen.kernels import DerivedParameters, hoist_parameters
from landau.errors import InputError
from landau.laws import get_law
from landau.laws.law import v as v_slip
from landau.verify.springblock.model import SpringBlockModel, compile_variational

EPS = 2.0 ** -52
CASES = [("dieterich", {}), ("ruina", {}), ("spinodal", {}), ("nanoscale", {}), ("two-state-dieterich", {}),
         ("modified-dieterich", {"c": 3e-4})]


def _exact_field(model: SpringBlockModel):
    """Eq. (4) in (ξ, w = ln v/V, ψᵢ = ln φᵢ/φᵢ₀), written here from the law's μ and rates:
    (field, Jacobian, condition scales of both) as functions of the state at 30 digits, the
    model's parameter values taken as exact (mpf of the doubles).  The parameters stay symbols
    until evaluation, so that the expanded scale keeps a_v, a ln V, −a ln V_*, −μ₀ … as
    separate terms instead of one number in which they have already cancelled."""
    law, p = model.law, model.params
    ns = len(law.states)
    xi, w = sp.symbols("xi w", real=True)
    psi = sp.symbols(f"psi0:{ns}", real=True)
    V, k, ell, M, sig = sp.symbols("V_ k_ ell_ M_ sigma_", positive=True)
    mu0 = sp.Symbol("mu0_", real=True)
    phi0 = sp.symbols(f"phi0_0:{ns}", positive=True)
    lp = [prm.symbol for prm in law.parameters]
    psyms = [*lp, V, k, ell, M, sig, mu0, *phi0]
    pvals = [p[prm.name] for prm in law.parameters] + [model.V, model.k, model.ell, p["M"], p["sigma"],
                                                       model.mu0, *model.phi0]
    vv = V * sp.exp(w)
    phis = [p0 * sp.exp(s) for p0, s in zip(phi0, psi, strict=True)]
    sub = {v_slip: vv, **dict(zip(law.states, phis, strict=True))}
    mu = law.mu.xreplace(sub)
    f = [sp.exp(w) - 1, (ell / V) * sp.exp(-w) * (-k * ell * xi - sig * (mu - mu0)) / (M * V)]
    f += [(ell / V) * r.xreplace(sub) / ph for r, ph in zip(law.rates, phis, strict=True)]
    ys = [xi, w, *psi]
    J = sp.Matrix(f).jacobian(sp.Matrix(ys))

    def scale(e):
        e = sp.expand(sp.expand_log(sp.expand(e), force=True))
        terms = [t.replace(sp.log, lambda x: sp.Abs(sp.log(x)) + 1) for t in sp.Add.make_args(e)]
        return sp.Add(*[sp.Abs(t) for t in terms])

    args = [*ys, *psyms]
    fns = [sp.lambdify(args, list(f), "mpmath"), sp.lambdify(args, list(J), "mpmath"),
           sp.lambdify(args, [scale(e) for e in f], "mpmath"), sp.lambdify(args, [scale(e) for e in J], "mpmath")]
    exact = [mpmath.mpf(float(x)) for x in pvals]
    return [lambda *y, fn=fn: fn(*y, *exact) for fn in fns]


def _points(n, rng):
    """States over a stick–slip cycle and beyond: slip ξ up to ±200 memory lengths, v from
    e⁻³⁰ V (deep stick) to e⁵ V, φ from e⁻⁵ to e³⁰ φ₀, and points near steady sliding."""
    far = rng.uniform([-200, -30, -5, -5], [200, 5, 30, 30], (12, 4))[:, :n]
    near = rng.normal(scale=1e-6, size=(4, n))
    return np.vstack([far, near])


@pytest.mark.parametrize("name,params", CASES, ids=[c[0] for c in CASES])
def test_kernel_field_and_jacobian_match_eq4_at_30_digits(name, params):
    law = get_law(name)
    model = SpringBlockModel.build(law, 1e-4, 1.3e5, params)
    f_ex, J_ex, f_sc, J_sc = _exact_field(model)
    rng = np.random.default_rng(7)
    worst = 0.0
    with mpmath.workdps(30):
        for y in _points(model.n, rng):
            args = [mpmath.mpf(float(x)) for x in y]
            f, J = model.f(y), model.J(y).ravel()
            for got, ex, sc in ((f, f_ex(*args), f_sc(*args)), (J, J_ex(*args), J_sc(*args))):
                for g, e, s in zip(got, ex, sc, strict=True):
                    if not np.isfinite(float(e)):
                        continue                         # e^{±w} beyond double range: not compared
                    err = abs(mpmath.mpf(float(g)) - e)
                    assert err <= 16 * EPS * s, (name, y, float(g), float(e), float(s))
                    if s > 0:
                        worst = max(worst, float(err / (EPS * s)))
    assert worst < 16


def test_variational_kernel_reads_the_same_parameter_vector():
    """The augmented system Φ' = J Φ (shooting, monodromy) takes ``model.p`` as the plain kernel
    does: with Φ = I its field is (f, J) of the plain kernel, bit for bit (same expressions)."""
    model = SpringBlockModel.build(get_law("dieterich"), 1e-4, 1.3e5)
    c = compile_variational(model.law)
    y = np.array([3.0, -12.0, 9.0])
    n = model.n
    out = np.empty(n + n * n)
    c.rhs(0.0, np.concatenate([y, np.eye(n).ravel()]), model.p, out)
    np.testing.assert_array_equal(out[:n], model.f(y))
    np.testing.assert_allclose(out[n:].reshape(n, n), model.J(y), rtol=4 * EPS, atol=0.0)


def test_kernel_evaluates_no_function_of_parameters_alone():
    """Every exp/log the generated field calls has a state in its argument: the logarithms of
    parameters that expanding ln(v/V_*) and ln(V_*φ/L) produces are in the parameter vector."""
    src = SpringBlockModel.build(get_law("dieterich"), 1e-4, 1.3e5).compiled.source
    fun = next(n for n in ast.parse(src).body if isinstance(n, ast.FunctionDef) and n.name == "fun")
    assigned = {}
    for st in fun.body:
        if isinstance(st, ast.Assign) and isinstance(st.targets[0], ast.Name):
            assigned[st.targets[0].id] = st.value

    def depends_on_state(node):
        for nm in (x.id for x in ast.walk(node) if isinstance(x, ast.Name)):
            if nm.startswith("s") or (nm.startswith("c") and depends_on_state(assigned[nm])):
                return True
        return False

    calls = [c for c in ast.walk(fun) if isinstance(c, ast.Call)]
    assert calls and all(depends_on_state(a) for c in calls for a in c.args)


def test_hoisted_field_equals_the_original_expression():
    """Substituting the derived parameters' definitions back gives the original field (sympy)."""
    x, w, a, b, c = sp.symbols("x w a b c", positive=True)
    field = [sp.exp(-w) * (a * sp.log(b) + sp.log(c) * w - a / b * x), sp.log(c + a * b * sp.exp(x)) / (a * b)]
    h = hoist_parameters(field, [a, b, c])
    back = [e.xreplace(dict(zip(h.derived, h.values, strict=True))) for e in h.field]
    assert all(sp.simplify(u - v) == 0 for u, v in zip(back, field, strict=True))
    assert all(not (e.free_symbols <= {a, b, c}) for d in h.field for e in sp.preorder_traversal(d)
               if isinstance(e, (sp.log, sp.exp, sp.Pow)))


@pytest.mark.parametrize("value", [-1.0, 0.0])
def test_derived_parameter_out_of_domain_is_a_named_error(value):
    a, x = sp.symbols("a x")
    h = hoist_parameters([x * sp.log(a)], [a])
    dp = DerivedParameters([a], h.values)
    assert dp([2.0])[1] == pytest.approx(np.log(2.0), rel=1e-15)
    with pytest.raises(InputError, match="parameter"):
        dp([value])
