"""One generalised-Hopf point type and one fold-of-cycles type (landau.analyses.codim2), and typed HopfResult fields."""

import math

import pytest

from landau.analyses.bautin import fold_of_cycles
from landau.analyses.codim2 import FoldOfCycles, GeneralisedHopfPoint
from landau.derivation.hopf import HopfResult, spring_block_result


def _sb_point(**kw):
    base = dict(Lambda5=-2.0, l2=-1.0, sign_below=-1, sign_above=1, re_a=-3.0, dLambda_dp2=5.0)
    base.update(kw)
    return GeneralisedHopfPoint("dieterich", ("k", "V"), 1e4, 2e-4, 30.0, **base)


def test_expansion_fold_equals_the_quintic_fold_with_linear_Lambda():
    # Λ(V) = Λ'(V − V*) exactly: the expansion and fold_of_cycles (closed form) must agree
    g = _sb_point()
    V = 2.1e-4
    f = g.predicted_fold(V)
    ref = fold_of_cycles(5.0 * (V - 2e-4), -2.0, -3.0, 1e4, parameter="k")
    assert f.p_fold == pytest.approx(ref.p_fold, rel=1e-15)
    assert f.amplitude == pytest.approx(ref.amplitude, rel=1e-15)
    assert f.value("V") == V and g.predicted_fold(1.9e-4) is None
    assert g.fold_side == 1 and _sb_point(dLambda_dp2=-5.0).fold_side == -1
    assert _sb_point(Lambda5=None).fold_side == 0 and math.isnan(_sb_point(Lambda5=None).fold_p1_coefficient)


def test_spring_block_json_keys_and_names():
    g = _sb_point()
    assert (g.V, g.k_c, g.kc, g.k, g.omega_c, g.Gamma_bar) == (2e-4, 1e4, 1e4, 1e4, 30.0, 3.0)
    assert g.as_dict()["k_c"] == g.as_dict()["kc"] == 1e4      # k_c canonical, kc its deprecated alias
    assert list(g.as_dict()) == ["V", "k_c", "kc", "omega_c", "Lambda5", "l2", "Gamma_bar", "dLambda_dV", "sign_below",
                                 "sign_above", "fold_of_cycles"]
    bare = GeneralisedHopfPoint("dieterich", ("k", "V"), 1e4, 2e-4, 30.0, sign_below=1, sign_above=-1)
    assert bare.as_dict() == {"V": 2e-4, "k_c": 1e4, "kc": 1e4, "omega_c": 30.0, "sign_below": 1, "sign_above": -1}


def test_general_json_keys_and_missing_names():
    g = GeneralisedHopfPoint("bautin", ("a", "b"), 0.0, 1.0, 2.0, (0.0, 0.0), l1=1e-17, l2=None)
    assert g.as_dict() == {"system": "bautin", "parameters": ["a", "b"], "p1": 0.0, "p2": 1.0, "omega": 2.0,
                           "equilibrium": [0.0, 0.0], "l2": None, "l1": 1e-17}
    assert g.value("b") == 1.0
    with pytest.raises(AttributeError, match="no parameter 'V'"):
        _ = g.V
    assert "GeneralisedHopfPoint" in repr(g) and "not computed" in repr(g)


def test_fold_of_cycles_json():
    f = fold_of_cycles(1.0, -2.0, 0.5, 3.0)
    assert f.as_dict() == {"p_fold": 3.0 + 1 / (8 * -2.0 * 0.5), "p_c": 3.0, "offset": 1 / (8 * -2.0 * 0.5),
                           "amplitude": 1.0, "side": -1}
    g = FoldOfCycles("V", 1e-3, 0.01, fixed={"k": 5.0, "kappa": 1e-3})
    assert g.value("kappa") == 1e-3 and math.isnan(g.offset) and g.side == 0


def test_hopf_result_fields_are_typed():
    r = spring_block_result("dieterich", 1e-4, 2.0, 3.0, 0.5, 0.25, -1.0, 0.1, {"a": 1.0})
    assert (r.V, r.kc, r.Gamma_bar, r.Omega_bar) == (1e-4, 2.0, 0.5, 0.25)
    assert r.as_dict()["V"] == 1e-4 and r["Gamma_bar"] == 0.5
    assert "__getattr__" not in HopfResult.__dict__
    with pytest.raises(AttributeError):
        _ = r.nonexistent
    # an old-style call with route numbers in ``extra`` fills the typed fields; labels stay in extra
    old = HopfResult("s", "p", 1.0, 2.0, (), 1j, -1.0, 0.0, extra={"q_norm": 0.5, "c2_re": 4.0, "c2_im": 1.0,
                                                                    "dps": 30, "friction": "coulomb"})
    assert (old.q_norm, old.c2, old.dps, old.l2_over_omega) == (0.5, 4 + 1j, 30, 2.0)
    assert old.extra == {"friction": "coulomb"}
    d = old.as_dict()
    assert (d["c2_re"], d["c2_im"], d["l2_over_omega"], d["q_norm"], d["friction"]) == (4.0, 1.0, 2.0, 0.5, "coulomb")
