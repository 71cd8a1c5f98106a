"""Velocity-only friction laws (landau.laws.velocity): values and slopes against closed forms."""

import math
import pickle

import numpy as np
import pytest

from landau.errors import InputError, ParseError
from landau.laws import Law, VelocityFriction, coulomb, get_law, regularised_coulomb


def test_every_law_kind_shares_the_base():
    assert isinstance(get_law("dieterich"), Law)
    assert isinstance(coulomb(), Law) and isinstance(regularised_coulomb(), Law)
    assert coulomb(0.3).defaults() == {"mu": 0.3}
    with pytest.raises(InputError, match="no parameter 'nope'"):
        coulomb().parameter("nope")


def test_coulomb_is_set_valued_with_its_coefficient_as_static_level():
    law = coulomb(0.42)
    assert law.is_set_valued() and law.static_level() == 0.42
    out = law.value([-2.0, 0.0, 3.0])
    assert out[0] == -0.42 and math.isnan(out[1]) and out[2] == 0.42
    assert law.slope(1.0) == 0.0


def test_regularised_law_matches_skurativskyi_eq1_closed_form():
    # F_R = c v + T v / sqrt(v^2 + eps^2), dF_R/dv = c + T eps^2 / (v^2 + eps^2)^{3/2}
    # (Skurativskyi et al. 2019, eq. 1), identified parameters of their Sec. 2
    c, T, eps = 6.6511, 0.63133, 1e-6
    law = regularised_coulomb()
    vs = np.array([-0.3, -2e-6, 0.0, 1e-7, 5e-6, 0.1])
    exact = c * vs + T * vs / np.sqrt(vs ** 2 + eps ** 2)
    slope = c + T * eps ** 2 / (vs ** 2 + eps ** 2) ** 1.5
    assert not law.is_set_valued()
    np.testing.assert_allclose(law.value(vs), exact, rtol=1e-14, atol=1e-300)
    np.testing.assert_allclose(law.slope(vs), slope, rtol=1e-12)
    assert law.units == "N"


def test_user_law_from_strings_with_odd_extension_and_derivatives():
    law = VelocityFriction.from_strings("stribeck", "mu_k + (mu_s - mu_k)*exp(-v/v_s)",
                                        params={"mu_k": 0.3, "mu_s": 0.42, "v_s": 0.5})
    v = np.array([0.2, 1.0, 3.0])
    exact = 0.3 + 0.12 * np.exp(-v / 0.5)
    np.testing.assert_allclose(law.value(v), exact, rtol=1e-15)
    np.testing.assert_allclose(law.value(-v), -exact, rtol=1e-15)          # odd extension
    np.testing.assert_allclose(law.slope(v), -0.12 / 0.5 * np.exp(-v / 0.5), rtol=1e-14)
    assert law.limits_at_zero() == pytest.approx((-0.42, 0.42), rel=1e-15)
    assert law.with_defaults(mu_s=0.5).static_level() == pytest.approx(0.5, rel=1e-15)
    again = pickle.loads(pickle.dumps(law))
    assert again.value(1.0) == law.value(1.0)


def test_explicit_negative_branch_is_used():
    law = VelocityFriction.from_strings("asym", "a + v", "-b + v", params={"a": 1.0, "b": 2.0})
    assert law.value(-0.5) == -2.5 and law.value(0.5) == 1.5
    assert law.limits_at_zero() == (-2.0, 1.0)


@pytest.mark.parametrize("text,params,match", [
    ("mu*v", {}, "unknown symbol"),
    ("__import__('os')", {}, "__import__"),
    ("v", {"v": 1.0}, "sliding velocity"),
    ("a*v", {"a": float("nan")}, "finite"),
])
def test_bad_input_is_named(text, params, match):
    with pytest.raises((InputError, ParseError), match=match):
        VelocityFriction.from_strings("bad", text, params=params)


def test_value_needs_known_parameters():
    with pytest.raises(InputError, match="no parameter"):
        coulomb().value(1.0, {"nu": 1.0})


def test_landau_hopf_spring_block_matches_the_linear_closed_form(capsys):
    import json

    from landau.cli import main
    from landau.derivation.linear import HopfLine
    from landau.systems.system import SpringBlock

    assert main(["hopf", "spring-block", "dieterich", "--V", "1e-4", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    block = SpringBlock(get_law("dieterich"))
    kc = HopfLine(block).points([1e-4], block.resolve({}))[0].kc
    assert doc["p_c"] == pytest.approx(kc, rel=1e-10)
    assert doc["criticality"] == "subcritical"
    assert main(["hopf", "no-such-model"]) == 2


def test_landau_laws_lists_velocity_laws(capsys):
    import json

    from landau.cli import main

    assert main(["laws", "regularised-coulomb", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)["laws"][0]
    assert doc["kind"] == "velocity" and doc["set_valued_at_zero"] is False
    assert {p["name"]: p["default"] for p in doc["parameters"]} == {"c": 6.6511, "T": 0.63133, "eps": 1e-6}
    assert main(["laws", "--json"]) == 0
    kinds = {d["name"]: d["kind"] for d in json.loads(capsys.readouterr().out)["laws"]}
    assert kinds["coulomb"] == "velocity" and kinds["dieterich"] == "rate-and-state"


def test_galvanetto_kinetic_law_is_on_the_same_base():
    from landau.laws.kinetic import KineticFriction

    k = KineticFriction()
    assert isinstance(k, Law) and k.name == "galvanetto-2004"
    assert k.defaults() == {"gamma": 3.0, "delta": 0.0}
    # eq. (7) of Galvanetto (2004) at r = -1 with gamma = 2, delta = 0.2: (1 - 0.2)/(1 + 2) + 0.2
    assert k.with_defaults(gamma=2.0, delta=0.2).neg(-1.0) == pytest.approx(0.8 / 3 + 0.2, rel=1e-15)
    with pytest.raises(InputError, match="no parameter"):
        k.with_defaults(mu=1.0)
