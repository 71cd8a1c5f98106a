"""The generated spring–block field does not depend on the names a law gives its symbols.

The field of Putelat et al. (2010), eq. (4), is written in internal symbols (the parameter
vector, the scaled states, the steady state φᵢ,₀, the derived parameters, the names of the
generated code).  A law whose parameters or states carry one of those names must give the same
field, the same Jacobian and the same verdict of the check as the law with its published names:
renaming is a change of notation, not of the model.  Each built-in law is renamed so that every
one of its parameters and states takes every internal name once (cyclic shifts of the list, so
that names are also swapped among themselves), and the compiled field and Jacobian are compared
at a few points with the original law's (the same arithmetic in the same order: equal to
rounding, 1e-12 relative).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import sympy as sp

from landau import check
from landau.cli import main
from landau.laws import BUILTIN, FrictionLaw, get_law
from landau.verify.springblock.model import SpringBlockModel

#: every name the spring–block generator and the kernel generator use for their own symbols
INTERNAL_NAMES = (
    [f"q{i}" for i in range(8)] + ["phi0_0", "phi0_1"] + [f"y{i}" for i in range(8)]
    + ["M_", "sigma_", "k_", "V_", "ell_", "mu0_", "hoisted0", "hoisted1", "s0", "s1", "s2", "c0", "c1", "t"]
)


def renamed(law: FrictionLaw, names: dict[str, str]) -> FrictionLaw:
    """``law`` with its parameters and states renamed by ``names`` (old -> new), all at once."""
    rep: dict[sp.Symbol, sp.Symbol] = {}
    params = []
    for p in law.parameters:
        q = dataclasses.replace(p, name=names.get(p.name, p.name))
        rep[p.symbol] = q.symbol
        params.append(q)
    states = []
    for s in law.states:
        t = sp.Symbol(names.get(s.name, s.name), **s.assumptions0)
        rep[s] = t
        states.append(t)
    ss = None if law.steady_state is None else tuple(e.xreplace(rep) for e in law.steady_state)
    return FrictionLaw(law.name, law.mu.xreplace(rep), tuple(states), tuple(r.xreplace(rep) for r in law.rates),
                       tuple(params), law.source, law.description, ss)


def _symbol_names(law: FrictionLaw) -> list[str]:
    return [p.name for p in law.parameters] + [s.name for s in law.states]


def _points(n: int) -> list[np.ndarray]:
    """Points off steady sliding (at the origin f is rounding noise of μ − μ₀, which depends on the
    order in which sympy adds the terms of μ, i.e. on the names)."""
    rng = np.random.default_rng(7)
    return [rng.normal(scale=0.4, size=n) for _ in range(3)]


#: the cyclic shifts the default suite builds: every 7th of the 32, so that each law's symbols take
#: names from each family (q*, phi0_*, y*, the scaled parameters, hoisted*/s*/c*/t) and are swapped
#: among themselves; the slow suite builds all 32 (each shift compiles one more model)
DEFAULT_SHIFTS = range(0, len(INTERNAL_NAMES), 7)


def _compare_renamed(name: str, shifts) -> None:
    law = get_law(name)
    old = _symbol_names(law)
    ref = SpringBlockModel.build(law, 1e-4, 1e5)
    pts = _points(ref.n)
    f_ref = [ref.f(y) for y in pts]
    J_ref = [ref.J(y) for y in pts]
    N = len(INTERNAL_NAMES)
    for shift in shifts:
        names = {o: INTERNAL_NAMES[(i + shift) % N] for i, o in enumerate(old)}
        # the length unit ℓ defaults to the parameter named L: given explicitly, the scaled variables agree
        m = SpringBlockModel.build(renamed(law, names), 1e-4, 1e5, length_scale=ref.ell)
        for y, f0, J0 in zip(pts, f_ref, J_ref, strict=True):
            np.testing.assert_allclose(m.f(y), f0, rtol=1e-12, atol=1e-12 * np.abs(f0).max(),
                                       err_msg=f"{name} renamed {names}")
            np.testing.assert_allclose(m.J(y), J0, rtol=1e-12, atol=1e-12 * np.abs(J0).max(),
                                       err_msg=f"{name} renamed {names}")


@pytest.mark.parametrize("name", sorted(BUILTIN))
def test_field_and_jacobian_do_not_depend_on_names(name):
    """The law's parameters and states take internal names of every family (every 7th cyclic shift)."""
    _compare_renamed(name, DEFAULT_SHIFTS)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(BUILTIN))
def test_field_and_jacobian_do_not_depend_on_names_every_shift(name):
    """Every parameter and state of the law takes every internal name (one model per cyclic shift)."""
    _compare_renamed(name, range(len(INTERNAL_NAMES)))


def test_check_verdict_does_not_depend_on_names():
    """landau.check on the Ruina law with its names swapped into the internal ones gives the same
    verdict and the same simulated amplitude (to the shooting tolerance, 1e-6 relative)."""
    law = get_law("ruina")
    names = {"a_v": "q1", "a": "q0", "b": "phi0_0", "L": "y2", "V_s": "q4", "phi": "q3"}
    r0 = check(law, V=1e-4, eps2=1e-3, bistability=False)
    r1 = check(renamed(law, names), V=1e-4, eps2=1e-3, bistability=False)
    assert r1.verdict is r0.verdict
    assert r1.amplitude_simulated == pytest.approx(r0.amplitude_simulated, rel=1e-6)
    assert r1.amplitude_predicted == pytest.approx(r0.amplitude_predicted, rel=1e-10)


def test_simulate_with_a_parameter_named_like_an_internal_symbol(capsys):
    """``landau simulate spring-block`` of the Dieterich law written with ``q1`` for ``a``: the same
    trajectory as with ``a`` (same field, same integrator: the final state agrees to 1e-9)."""
    import json

    def final(a: str) -> dict:
        code = main(["simulate", "spring-block", "x", "--mu", f"a_v + {a}*log(v/V_s) + b*log(V_s*phi/L)",
                     "--state", "phi=1 - v*phi/L", "--param", f"{a}=0.0349", "--t-end", "0.02", "--json"])
        out, _ = capsys.readouterr()
        assert code == 0
        return json.loads(out)["final_state"]

    ref, got = final("a"), final("q1")
    for key in ("X", "v", "phi"):
        assert got[key] == pytest.approx(ref[key], rel=1e-9), key
