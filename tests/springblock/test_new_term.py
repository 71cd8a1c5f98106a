"""A spring–block term written in one place (a test) reaches every stage.

The term: a dashpot of coefficient c_dash in parallel with the spring, force c_dash (V_lp − v) on the
block.  Without a term that loads the block it acts on the linearisation exactly as radiation damping
η does (both add −c u to the force balance in u = v − V; η's steady force ηV is carried by the spring
and changes nothing else while σ is constant), so every number of the block with c_dash = c equals
that with η = c: the independent computation each stage is checked against (for the aging law the
closed form k_c = [σ(b − a) − ηV]/L · [1 + MV²/(L(σa + ηV))] of radiation damping, Rice 1993 and
Putelat et al. 2010 eq. 30 with a → a + ηV/σ, with η → c_dash).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import sympy as sp

from landau.laws import get_law
from landau.systems import springblock_terms as T

C = 150.0    # N s/m
V = 1e-4


@pytest.fixture
def dashpot():
    c = sp.Symbol("c_dash", nonnegative=True)
    T.register_term("c_dash", T.Term(c, "N s/m", "dashpot in parallel with the spring, force c_dash (V_lp - v)",
                                     "a test", True, force=lambda b: b.symbol["c_dash"] * (b.V_lp - b.v)))
    try:
        yield "c_dash"
    finally:
        T.unregister_term("c_dash")


def test_the_derivation_and_its_latex(dashpot):
    from landau.derivation.multiscale import derive
    from landau.systems.system import SpringBlock

    law = get_law("dieterich")
    d = derive(SpringBlock(law, (dashpot,)))
    ref = derive(SpringBlock(law, ("eta",)))
    names = ["kc", "omega_c", "Lambda", "C"]
    got = d.evaluate(np.array([V]), {dashpot: C}, names)
    want = ref.evaluate(np.array([V]), {"eta": C}, names)
    for n in names:
        np.testing.assert_allclose(np.ravel(got[n]), np.ravel(want[n]), rtol=1e-12, err_msg=n)
    tex = d.coefficient("k_c").latex()
    assert r"V c_{\mathrm{dash}} + a \sigma - b \sigma" in tex, tex   # σ(b − a) − c V, as η's closed form


def test_landau_hopf_and_a_sweep(dashpot, capsys):
    import landau
    from landau.cli import main

    assert main(["hopf", "spring-block", "dieterich", "--V", str(V), "--param", f"{dashpot}={C}", "--json"]) == 0
    ours = json.loads(capsys.readouterr().out)
    assert main(["hopf", "spring-block", "dieterich", "--V", str(V), "--param", f"eta={C}", "--json"]) == 0
    eta = json.loads(capsys.readouterr().out)
    assert ours["p_c"] == pytest.approx(eta["p_c"], rel=1e-12)
    assert ours["Lambda"] == pytest.approx(eta["Lambda"], rel=1e-10)
    ds = landau.sweep("hopf", {dashpot: [0.0, C]}, law="dieterich", params={"V": V}, workers=1, progress=False)
    assert list(ds.status.values) == ["ok", "ok"]
    assert float(ds.k_c.values[1]) == pytest.approx(eta["p_c"], rel=1e-10)
    assert float(ds.k_c.values[0]) != pytest.approx(eta["p_c"], rel=1e-3)   # the term acts


def test_the_compiled_field(dashpot):
    """The compiled scaled field of the simulation (landau simulate) with the dashpot equals that with η at
    the same state, but for η's steady force (which only moves the steady state the field is written about)."""
    from landau.verify.springblock.model import SpringBlockModel

    law = get_law("dieterich")
    ours = SpringBlockModel.build(law, V, 1.5e5, {dashpot: C})
    eta = SpringBlockModel.build(law, V, 1.5e5, {"eta": C})
    y = np.array([0.3, -0.2, 0.1])
    np.testing.assert_allclose(ours.f(y), eta.f(y), rtol=1e-13, atol=1e-15)
    assert not np.allclose(ours.f(y), SpringBlockModel.build(law, V, 1.5e5).f(y))


def test_landau_check(dashpot):
    from landau.analyses.checking import check

    law = get_law("dieterich")
    ours = check(law, V=V, eps2=1e-3, params={dashpot: C}, bistability=False)
    eta = check(law, V=V, eps2=1e-3, params={"eta": C}, bistability=False)
    assert ours.p == pytest.approx(eta.p, rel=1e-12)   # the stiffness simulated, (1 - eps2) k_c or so
    assert ours.verdict == eta.verdict
    assert ours.amplitude_simulated == pytest.approx(eta.amplitude_simulated, rel=1e-6)


def test_the_quasi_dynamic_cell(dashpot):
    """M = 0: the cell's force residual and field with (η, c_dash) equal those with η + c_dash alone (both
    add −c u in the force balance written about steady sliding)."""
    from landau.verify.springblock.quasidynamic import QuasiDynamicCell

    law = get_law("dieterich")
    ours = QuasiDynamicCell.build(law, V, 1.5e5, {"M": 0.0, "eta": 1e3, dashpot: C})
    ref = QuasiDynamicCell.build(law, V, 1.5e5, {"M": 0.0, "eta": 1e3 + C})
    for state in ((0.0, 0.0, 0.0), (0.2, -0.4, 0.3)):
        got, want = ours._fn(*state), ref._fn(*state)
        np.testing.assert_allclose(got[0], want[0], rtol=1e-12, atol=1e-15)        # R
        np.testing.assert_allclose(got[2], want[2], rtol=1e-12, atol=1e-15)        # the field


def test_a_load_history(dashpot):
    """A velocity step with the dashpot: it carries no force at steady sliding (v = V_lp), so the new
    steady friction is μ₁ + (a − b) ln(V₂/V₁) (Dieterich 1979; Putelat et al. 2010 eq. 28), and the spring
    force column follows k u as without it."""
    from landau.verify.springblock.history import simulate_history

    law = get_law("dieterich")
    p = law.defaults()
    sim = simulate_history(law, "1e-5@0,1e-4@20", 2e5, {dashpot: C}, t_end=400.0)
    names = list(sim.state_names)
    mu = sim.y[names.index("mu")]
    mu1 = p["a_v"] + (p["a"] - p["b"]) * np.log(1e-5 / p["V_s"])
    assert mu[0] == pytest.approx(mu1, rel=1e-9)
    assert mu[-1] == pytest.approx(mu1 + (p["a"] - p["b"]) * np.log(10.0), rel=1e-6)
    assert "F" in names and "sigma" not in names   # a force term, no load term


def test_landau_simulate(dashpot):
    """The front door runs the block with the term (the compiled model above) and reports its value."""
    import landau

    sim = landau.simulate("spring-block", "dieterich", params={"V": V, "k": 1.5e5, dashpot: C}, t_end=2.0)
    assert sim.parameters[dashpot] == C and sim.status.value == "finished"
    ref = landau.simulate("spring-block", "dieterich", params={"V": V, "k": 1.5e5, "eta": C}, t_end=2.0)
    # η's steady force ηV moves the steady state both start from (the field about it is the dashpot's)
    np.testing.assert_allclose(sim.y_final[1:], ref.y_final[1:], rtol=1e-6)
