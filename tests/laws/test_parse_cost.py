"""The law parser bounds the cost of what it builds, not only the size of its values.

Powers of numbers are evaluated exactly only while that is cheap (an exact number to an integer
power or a root of denominator at most 4, at bounded bit cost); otherwise as a 30-digit float.
sympy's exact radical simplification of 45**(-1/823543) alone took minutes; exp(c*log(x)) is
x**c for sympy, so exp goes through the same bound.  Every value below is checked against an
independent float computation.  A hang (minutes before the fix) becomes a failure after 30 s
(SIGALRM): a hang detector, not a speed goal.
"""

from __future__ import annotations

import math
import signal

import pytest
import sympy as sp

from landau.cli import main
from landau.errors import ParseError
from landau.laws.parse import parse_expression

v = sp.Symbol("v", positive=True)
SYMBOLS = {"v": v, "a": sp.Symbol("a", positive=True)}
#: seconds after which a parse counts as hung (each case here takes milliseconds)
HANG = 30


def parse(text: str) -> sp.Expr:
    def hung(signum, frame):
        raise TimeoutError(f"parsing {text!r} did not end within {HANG} s")

    old = signal.signal(signal.SIGALRM, hung)
    signal.alarm(HANG)
    try:
        return parse_expression(text, SYMBOLS, what="mu")
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


@pytest.mark.parametrize("text,value", [
    ("45**(-1/823543)", 45.0 ** (-1 / 823543)),
    ("970188^(-7^-7)", 970188.0 ** (-(7.0 ** -7))),
    ("45**(1/1000003)", 45.0 ** (1 / 1000003)),
    ("45**(-1/1000003)", 45.0 ** (-1 / 1000003)),
    ("exp(-log(45)/823543)", 45.0 ** (-1 / 823543)),
    ("1/sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(45))))))))))))))))))",
     45.0 ** (-(0.5 ** 18))),
    ("45**(1/61)*45**(1/59)*45**(1/53)*45**(1/47)*45**(-1/43)",
     45.0 ** (1 / 61 + 1 / 59 + 1 / 53 + 1 / 47 - 1 / 43)),
    ("(1000001/1000000)**100000", math.exp(100000 * math.log1p(1e-6))),
    ("2**pi", 2.0 ** math.pi),
])
def test_powers_of_numbers_are_bounded_in_cost(text, value):
    """Values to 1e-14 (the float reference's own rounding; the parser works with 30 digits)."""
    assert float(parse(text)) == pytest.approx(value, rel=1e-14)


@pytest.mark.parametrize("text,expect", [
    ("2**(1/2)", sp.sqrt(2)), ("8**(1/3)", sp.Integer(2)), ("sqrt(8)", 2 * sp.sqrt(2)), ("(-2)**2", sp.Integer(4)),
    ("v**(-1/2)", 1 / sp.sqrt(v)), ("exp(2*log(v))", v ** 2), ("(45*v)**(1/3)", sp.Integer(45) ** sp.Rational(1, 3)
                                                                 * v ** sp.Rational(1, 3)),
])
def test_small_exact_powers_stay_exact(text, expect):
    assert parse(text) == expect


@pytest.mark.parametrize("text", ["(45*v)**(-1/823543)", "exp(v - log(45*v)/823543)", "E**(-log(45*v)/823543)",
                                  "((45*v)**(1/3))**(1/3)"])
def test_symbolic_powers_with_large_roots_are_bounded(text):
    """The numbers are raised as floats: the result at v = 2 equals the float computation."""
    e = parse(text)
    x = 2.0
    ref = {"(45*v)**(-1/823543)": (45 * x) ** (-1 / 823543),
           "exp(v - log(45*v)/823543)": math.exp(x) * (45 * x) ** (-1 / 823543),
           "E**(-log(45*v)/823543)": (45 * x) ** (-1 / 823543),
           "((45*v)**(1/3))**(1/3)": (45 * x) ** (1 / 9)}[text]
    assert float(e.subs(v, x)) == pytest.approx(ref, rel=1e-14)


@pytest.mark.parametrize("text,match", [
    ("(-1)**(1/3)", "not real"), ("0.001*((-1)**(1/3) - (-1)**(2/3))", "not real"), ("(-2)**0.5", "not real"),
    ("(-1)**v", "not real"), ("sqrt(-v)", "not real"), ("(-v)**(1/3)", "not real"),
    ("((2*v)**100)**100", "out of range"), ("(1e-300*v)**2", "out of range"), ("0**(-1)", "divides by zero"),
    ("a*log(v/V_s) # + b*log(phi)", "'#'"), ("v#", "'#'"),
])
def test_refusals_are_named(text, match):
    with pytest.raises(ParseError, match=match):
        parse(text)


def test_cli_refuses_a_non_real_rate_in_one_line(capsys):
    """A (-1)**(1/3) term in a rate was an internal error (exit 1) in the engine: now exit 2, one line."""
    code = main(["linear", "x", "--mu", "a_v + a*log(v/V_s) + b*log(V_s*phi/L)", "--state",
                 "phi=1 - v*phi/L + 0.001*((-1)**(1/3) - (-1)**(2/3))", "--V", "1e-4"])
    _, err = capsys.readouterr()
    assert code == 2 and err.count("\n") == 1 and "not real" in err, err


def test_cli_refuses_a_comment(capsys):
    """A '#' dropped the rest of the law silently."""
    code = main(["linear", "x", "--mu", "a_v + a*log(v/V_s) # + b*log(V_s*phi/L)", "--state", "phi=1 - v*phi/L",
                 "--V", "1e-4"])
    _, err = capsys.readouterr()
    assert code == 2 and err.count("\n") == 1 and "'#'" in err, err


def test_cli_impact_oscillator_refuses_an_imaginary_friction(capsys):
    """sqrt(-v) on the branch v > 0 was an internal error of the equilibrium solver: exit 2, one line."""
    code = main(["simulate", "impact-oscillator", "--friction", "sqrt(-v)", "--t-end", "1"])
    _, err = capsys.readouterr()
    assert code == 2 and err.count("\n") == 1 and "not real for v > 0" in err, err


@pytest.mark.parametrize("name", ["", " "])
def test_laws_with_an_empty_name_is_refused(name, capsys):
    """`landau laws ""` listed every law: an empty filter is an error naming the fix."""
    code = main(["laws", name])
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and err.count("\n") == 1 and "empty" in err, err
