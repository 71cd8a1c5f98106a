"""Fuzzing the input paths: the law parser and the command line.

Every call must end within its time limit with a finite real result or with the named error
(:class:`ParseError` / :class:`InputError`; on the CLI exit 2 and one line on stderr, or exit 1
with a named toolkit error such as ``NoHopfError``) — never a traceback, a hang, an abort, a
complex or a NaN number.  The default run uses a fixed, derandomised budget; the long run
(``pytest -m fuzz``) draws 50,000 parser examples and 1,000 command lines.
"""

from __future__ import annotations

import contextlib
import json
import math
import signal
import string
from datetime import timedelta

import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from landau.cli import main
from landau.errors import InputError, ParseError
from landau.laws.law import RESERVED
from landau.laws.parse import FUNCTIONS, parse_expression

#: examples in the default run (the whole module stays well under a minute)
PARSER_EXAMPLES = 800
CLI_EXAMPLES = 30
#: examples in the opt-in long run
LONG_PARSER_EXAMPLES = 50_000
LONG_CLI_EXAMPLES = 1_000
#: wall-clock limit of one call (s): a hang becomes a failure instead of a stuck run
CALL_LIMIT = 60
#: wall-clock limit of one parse (s): every accepted or refused string parses in milliseconds to a
#: fraction of a second; the limit is loose for a loaded machine, a hang was minutes
PARSE_LIMIT = 10

NAMES = ["v", "phi", "a", "b", "L", "V_s", "a_v"]
SYMBOLS = {"v": sp.Symbol("v", positive=True), "phi": sp.Symbol("phi", positive=True),
           **{n: sp.Symbol(n, positive=True) for n in ("a", "b", "L", "V_s", "a_v")}}


@contextlib.contextmanager
def time_limit(seconds: int):
    """Raise TimeoutError in the main thread after ``seconds`` (SIGALRM)."""
    def handler(signum, frame):
        raise TimeoutError(f"call did not return within {seconds} s")
    old = signal.signal(signal.SIGALRM, handler)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


# --- strategies: expressions over the allowed grammar, plus hostile leaves ------------------------
numbers = st.one_of(
    st.integers(min_value=-10, max_value=10).map(str),
    st.integers(min_value=-10 ** 40, max_value=10 ** 40).map(str),
    st.floats(allow_nan=False, allow_infinity=False, width=64).map(repr),
    st.sampled_from(["1e400", "1e-400", "0", "0.0", "10**10**10", "2.0**1e20", "29**(7e12)", "9" * 400]),
)
#: short powers of numbers whose exact evaluation by sympy takes minutes (45**(-1/823543)), towers
#: of them, and the exp(c*log(x)) that sympy turns into a power
short_powers = st.one_of(
    st.tuples(st.integers(2, 10 ** 6), st.integers(1, 10), st.integers(2, 10 ** 7)).map(
        lambda t: f"{t[0]}**(-{t[1]}/{t[2]})"),
    st.tuples(st.integers(2, 10 ** 6), st.integers(2, 9), st.integers(2, 9)).map(lambda t: f"{t[0]}^(-{t[1]}^-{t[2]})"),
    st.tuples(st.integers(2, 10 ** 6), st.integers(2, 10 ** 7)).map(lambda t: f"exp(-log({t[0]})/{t[1]})"),
    st.tuples(st.integers(2, 10 ** 6), st.integers(2, 10 ** 7)).map(lambda t: f"({t[0]}*v)**(-1/{t[1]})"),
    st.sampled_from(["45**(-1/823543)", "970188^(-7^-7)", "(-1)**(1/3)", "(-1)**(1/3) - (-1)**(2/3)",
                     "sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(sqrt(45))))))))))**-1", "v # comment"]),
)
leaves = st.one_of(st.sampled_from(NAMES + ["pi", "E", "x", "__import__", "q"]), numbers, short_powers)


def _combine(children):
    binop = st.tuples(children, st.sampled_from(["+", "-", "*", "/", "**", "^", "%", "//", "@", "&"]),
                      children).map(lambda t: f"({t[0]} {t[1]} {t[2]})")
    unary = st.tuples(st.sampled_from(["-", "+", "~", "not "]), children).map(lambda t: f"{t[0]}({t[1]})")
    call = st.tuples(st.sampled_from(sorted(FUNCTIONS) + ["gamma", "eval", "getattr"]), children).map(
        lambda t: f"{t[0]}({t[1]})")
    return st.one_of(binop, unary, call)


expressions = st.recursive(leaves, _combine, max_leaves=25)
hostile_text = st.one_of(
    st.text(max_size=200),
    st.text(alphabet=string.printable, max_size=200),
    st.binary(max_size=200),
    st.integers(min_value=1, max_value=4000).map(lambda n: "(" * n + "v" + ")" * n),
    st.integers(min_value=1, max_value=4000).map(lambda n: "**".join(["v"] * n)),
    st.integers(min_value=1, max_value=40_000).map(lambda n: "+".join(["v"] * n)),
)


def check_parse(text) -> None:
    """parse_expression gives a finite real sympy expression over the declared symbols, or a ParseError."""
    with time_limit(PARSE_LIMIT):
        try:
            expr = parse_expression(text, SYMBOLS, what="mu")
        except ParseError:
            return
    assert isinstance(expr, sp.Expr)
    assert expr.free_symbols <= set(SYMBOLS.values())
    assert not expr.has(sp.I, sp.nan, sp.zoo, sp.oo, -sp.oo)
    assert expr.is_extended_real is not False


def _parser_test(n: int):
    @settings(max_examples=n, deadline=timedelta(seconds=CALL_LIMIT), derandomize=True, database=None,
              suppress_health_check=list(HealthCheck))
    @given(st.one_of(expressions, hostile_text, short_powers))
    def test(text):
        check_parse(text)
    return test


test_parser_fuzz = _parser_test(PARSER_EXAMPLES)
test_parser_fuzz_long = pytest.mark.fuzz(_parser_test(LONG_PARSER_EXAMPLES))


# --- the command line --------------------------------------------------------------------------------
identifiers = st.one_of(
    st.sampled_from(sorted(RESERVED) + ["phi", "psi", "theta", "x0", "log", "exp", "phi_0", "d1_u_phi", "lambda",
                                        "__class__", "a b", "", "1x", "é"]),
    st.from_regex(r"[A-Za-z][A-Za-z0-9_]{0,8}", fullmatch=True),
)
velocities = st.one_of(
    st.lists(st.floats(min_value=1e-9, max_value=1e-1), min_size=1, max_size=3).map(
        lambda xs: ",".join(repr(x) for x in xs)),
    st.sampled_from(["1e-4", "0", "-1e-4", "nan", "inf", "1e-300", "1e300", "", ",", "abc", "1e-4,1e-3"]),
)


@st.composite
def command_lines(draw):
    state = draw(identifiers)
    # a Dieterich-like law with random perturbations of mu and of the rate
    mu = draw(st.one_of(
        st.just(f"a_v + a*log(v/V_s) + b*log(V_s*{state}/L)"),
        expressions.map(lambda e: f"a_v + a*log(v/V_s) + b*log(V_s*{state}/L) + 0.001*({e})"),
        expressions,
    ))
    rate = draw(st.one_of(
        st.just(f"1 - v*{state}/L"),
        expressions.map(lambda e: f"1 - v*{state}/L + 0.01*({e})"),
        st.just(f"1 - v*{state}/L - 0.01*tanh({state})"),
    )).replace("phi", state)
    argv = [draw(st.sampled_from(["linear", "derive"])), draw(st.sampled_from(["x", "dieterich", "ruina"]))]
    argv += ["--mu", mu, "--state", f"{state}={rate}", "--V", draw(velocities)]
    if argv[0] == "derive":
        argv += ["--quantities", draw(st.sampled_from(["kc,omega_c,Gamma_bar", "kc", "Gamma_bar,Omega_bar"]))]
    for _ in range(draw(st.integers(0, 2))):
        argv += ["--param", draw(st.one_of(
            st.tuples(identifiers, st.sampled_from(["1", "0", "-1", "1e-3", "nan", "1e300", "x"])).map(
                lambda t: f"{t[0]}={t[1]}"),
            st.sampled_from(["M=2", "M=0", "sigma=5", "a=0.01", "V=1", "k=3", "=", "M"]),
        ))]
    return argv + ["--json"]


def check_cli(argv, capsys) -> None:
    with time_limit(CALL_LIMIT):
        code = main(argv)
    out, err = capsys.readouterr()
    assert "Traceback" not in err and "internal error" not in err, (argv, err)
    if code == 0:
        doc = json.loads(out)
        for pt in doc["points"]:
            if pt["status"] == "ok":
                for key, val in pt.items():
                    if key not in ("V", "status", "criticality", "phi_ss"):
                        assert isinstance(val, float) and math.isfinite(val), (argv, key, val)
            else:
                assert pt["reason"] and pt.get("velocity_weakening"), (argv, pt)
        return
    assert code in (1, 2), (argv, code, err)
    assert err.count("\n") == 1 and err.startswith("landau: "), (argv, err)
    if code == 1:   # a named toolkit error, not bad input
        assert err.split(":")[1].strip().endswith("Error"), (argv, err)


def _cli_test(n: int):
    @settings(max_examples=n, deadline=timedelta(seconds=CALL_LIMIT), derandomize=True, database=None,
              suppress_health_check=list(HealthCheck))
    @given(argv=command_lines())
    def test(argv, capsys):
        check_cli(argv, capsys)
    return test


test_cli_fuzz = _cli_test(CLI_EXAMPLES)
test_cli_fuzz_long = pytest.mark.fuzz(_cli_test(LONG_CLI_EXAMPLES))


def test_reserved_names_never_reach_a_result(capsys):
    """Every reserved name, as a state: refused with exit 2 (never a wrong number)."""
    for name in sorted(RESERVED):
        if name == "v" or not name.isidentifier():
            continue
        code = main(["linear", "x", "--mu", f"a_v + a*log(v/V_s) + b*log(V_s*{name}/L)", "--state",
                     f"{name}=1 - v*{name}/L", "--V", "1e-4"])
        _, err = capsys.readouterr()
        assert code == 2 and ("reserved" in err or "cannot" in err or "not" in err), (name, err)
    with pytest.raises(InputError):
        from landau.laws import FrictionLaw

        FrictionLaw.from_strings("x", mu="a*log(v)", state={"phi": "1 - v*phi/L"}, params={"Lambda": 1.0})
