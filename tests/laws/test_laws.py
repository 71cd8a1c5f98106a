"""Friction laws as data: the safe parser, from_strings, the built-in library (Putelat et al. 2010)."""

import pytest
import sympy as sp

from landau.errors import InputError, ParseError
from landau.laws import BUILTIN, TABLE1, FrictionLaw, get_law, v
from landau.laws.parse import parse_expression

X = sp.Symbol("x")


@pytest.mark.parametrize("text, token", [
    ("__import__('os').system('ls')", "__import__"),
    ("x.__class__", "x.__class__"),
    ("x[0]", "x[0]"),
    ("foo(x)", "foo"),
    ("y + 1", "'y'"),
    ("lambda: 1", "Lambda"),
    ("log(x, 2)", "exactly one argument"),
    ("'abc'", "'abc'"),
    ("exp(x=1)", "keyword"),
    ("x if x else 1", "IfExp"),
    ("x +", "not a valid expression"),
])
def test_parser_rejects_and_names_the_token(text, token):
    with pytest.raises(ParseError) as err:
        parse_expression(text, {"x": X})
    assert token in str(err.value)


def test_parser_builds_sympy_without_eval():
    e = parse_expression("a*log(x/2)^2 + asinh(x) - sqrt(x)/3", {"x": X, "a": sp.Symbol("a")})
    a = sp.Symbol("a")
    assert sp.simplify(e - (a * sp.log(X / 2) ** 2 + sp.asinh(X) - sp.sqrt(X) / 3)) == 0


def test_from_strings_takes_table1_values_and_matches_builtin_dieterich():
    law = FrictionLaw.from_strings("mine", mu="a_v + a*log(v/V_s) + b*log(V_s*phi/L)", state={"phi": "1 - v*phi/L"})
    ref = get_law("dieterich")
    assert law.defaults() == {k: TABLE1[k].default for k in ("a_v", "a", "b", "L", "V_s")}
    assert sp.simplify(law.mu - ref.mu) == 0
    assert law.steady_state_closed_form == (TABLE1["L"].symbol / v,)


def test_from_strings_unknown_symbol_is_an_error_naming_it():
    with pytest.raises(ParseError, match="unknown symbol 'c'"):
        FrictionLaw.from_strings("x", mu="a*log(v/V_s) + c", state={"phi": "1 - v*phi/L"})
    law = FrictionLaw.from_strings("x", mu="a*log(v/V_s) + c", state={"phi": "1 - v*phi/L"}, params={"c": 0.1})
    assert law.defaults()["c"] == 0.1


def test_law_without_velocity_dependence_is_rejected():
    with pytest.raises(InputError, match="does not depend on the slip rate"):
        FrictionLaw.from_strings("x", mu="a_v + b*log(phi)", state={"phi": "1 - v*phi/L"})


@pytest.mark.parametrize("name", [n for n in BUILTIN])
def test_builtin_steady_states_zero_the_rates(name):
    law = get_law(name)
    ss = law.steady_state_closed_form
    assert ss is not None
    for r in law.rates:
        assert sp.simplify(r.subs(dict(zip(law.states, ss, strict=True)))) == 0
    assert law.source and all(p.source for p in law.parameters)


def test_two_state_steady_state_solved_by_sympy_when_not_declared():
    law = FrictionLaw.from_strings("two", mu="a*log(v/V_s) + b*log(V_s*p/L) + b*log(V_s*q/L)",
                                   state={"p": "1 - v*p/L", "q": "-(v*q/L)*log(v*q/L)"})
    L = TABLE1["L"].symbol
    assert law.steady_state_closed_form == (L / v, L / v)


@pytest.mark.parametrize("name", ["__import__", "_x", "lambda", "a-b"])
def test_declared_names_must_be_plain_identifiers(name):
    with pytest.raises(InputError, match="plain identifier"):
        FrictionLaw.from_strings("x", mu="a*log(v/V_s)", state={"phi": "1 - v*phi/L"}, params={name: 1.0})
