"""Safe parsing of friction-law expressions given as strings.

The string is parsed by Python's :mod:`ast` into a syntax tree that is *walked*, never
executed: only numbers, declared names, the arithmetic operators and a whitelist of
functions are accepted, each translated to its sympy counterpart.  Anything else —
attribute access, subscripts, keywords, lambdas, ``__import__``, unknown functions or
symbols — is rejected with a :class:`~landau.errors.ParseError` that names the token.
``^`` is read as a power (``**``), as in most papers; a ``#`` is refused (Python would read
the rest as a comment).

The cost of what is built is bounded, not only the size of its values: a power of exact
numbers is kept exact only for an integer exponent or a root of denominator at most
:data:`MAX_ROOT`, at a bit cost below :data:`MAX_EXACT_COST`; otherwise it is evaluated as a
30-digit float (sympy's exact simplification of ``45**(-1/823543)`` took minutes).  ``exp`` of
``c*log(x)``, which sympy turns into ``x**c``, takes the same route.
"""

from __future__ import annotations

import ast
import io
import tokenize
from typing import Callable, Mapping

import sympy as sp

from landau.errors import ParseError

#: function name -> sympy constructor
FUNCTIONS: dict[str, Callable[..., sp.Expr]] = {
    "log": sp.log, "ln": sp.log, "exp": sp.exp, "sqrt": sp.sqrt,
    "sin": sp.sin, "cos": sp.cos, "tan": sp.tan,
    "sinh": sp.sinh, "cosh": sp.cosh, "tanh": sp.tanh,
    "asinh": sp.asinh, "arcsinh": sp.asinh, "acosh": sp.acosh, "atanh": sp.atanh,
    "atan": sp.atan, "arctan": sp.atan,
    "abs": sp.Abs, "Abs": sp.Abs, "sign": sp.sign,
    "log10": lambda x: sp.log(x, 10),
}

#: constants always available
CONSTANTS: dict[str, sp.Expr] = {"pi": sp.pi, "E": sp.E}

_BINOPS = {
    ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b,
    ast.Mult: lambda a, b: a * b, ast.Div: lambda a, b: a / b,
    ast.Pow: lambda a, b: a ** b,
}
_UNARY = {ast.USub: lambda a: -a, ast.UAdd: lambda a: a}


#: longest accepted expression (characters); checked before anything parses the text
MAX_LENGTH = 2_000
#: deepest accepted syntax tree (a 300-term sum written a+b+... is 300 deep)
MAX_DEPTH = 60
#: most accepted syntax-tree nodes
MAX_NODES = 600
#: largest |numeric exponent| of a power whose base contains a symbol (v**e, (1+phi)**e)
MAX_EXPONENT = 100
#: largest decimal exponent of any number built while parsing (|x| <= 1e300, or 0)
MAX_DECADES = 300.0
#: largest argument of exp/sinh/cosh of a pure number (exp(700) ~ 1e304)
MAX_EXP_ARG = 690.0
#: largest denominator of an exponent kept exact on an exact number (2**(1/3) stays a radical;
#: 45**(1/823543) is evaluated as a float: sympy's radical simplification of b**(p/q) costs
#: work that grows with q and the size of b, minutes for 45**(-1/823543))
MAX_ROOT = 4
#: largest work allowed for an exact power of an exact number: bits of the number times the size
#: of the exponent (max(|p|, q) of p/q); beyond it the power is evaluated as a float
MAX_EXACT_COST = 2 ** 16


def _number_decades(x: sp.Expr) -> float | None:
    """log10|x| of a sympy number computed without evaluating it (None for 0 or a non-number)."""
    import math

    if not x.is_Number or x == 0:
        return None
    if x.is_Integer:
        return (abs(int(x)).bit_length() - 1) * math.log10(2)
    if x.is_Rational:
        return (abs(int(x.p)).bit_length() - abs(int(x.q)).bit_length()) * math.log10(2)
    if x.is_Float:
        sign, man, exp, bc = x._mpf_
        if man == 0:
            return None
        return (exp + bc) * math.log10(2)
    return None


def _finite_real(x: sp.Expr) -> float | None:
    """float(x) for a symbol-free bounded expression; None when it is not a finite real number."""
    import math

    try:
        z = complex(x.evalf(20))
    except (TypeError, ValueError, OverflowError, ArithmeticError):
        return None
    if z.imag != 0 or not math.isfinite(z.real):
        return None
    return z.real


def _bits(x: sp.Rational) -> int:
    return int(x.p).bit_length() + int(x.q).bit_length()


def _exact_factors(base: sp.Expr) -> list[tuple[sp.Rational, sp.Rational]]:
    """(c, r) for each factor c**r of ``base`` with c an exact number and r rational (r = 1 for a
    plain number): the numbers that ``base**e`` raises exactly to c**(r*e)."""
    out = []
    for f in sp.Mul.make_args(base):
        if f.is_Rational:
            out.append((f, sp.Integer(1)))
        elif f.is_Pow and f.base.is_Rational and f.exp.is_Rational:
            out.append((f.base, f.exp))
    return out


def _exact_ok(base: sp.Expr, ex: sp.Rational) -> bool:
    """Whether sympy may raise ``base`` to the rational ``ex`` exactly at a bounded cost: every exact
    number it raises gets an exponent with a denominator of at most :data:`MAX_ROOT`, a positive
    base if that exponent is not an integer, and work (bits × exponent size) below
    :data:`MAX_EXACT_COST`."""
    for c, r in _exact_factors(base):
        e = r * ex
        if not e.is_Integer and (e.q > MAX_ROOT or c < 0):
            return False
        if _bits(c) * max(abs(int(e.p)), int(e.q)) > MAX_EXACT_COST:
            return False
    return True


def _checked_text(text, what: str) -> str:
    """The text after the checks that come before any parsing: type, encoding, length."""
    if isinstance(text, bytes):
        try:
            text = text.decode("utf-8")
        except UnicodeDecodeError:
            raise ParseError(f"{what} is not valid UTF-8 text") from None
    if not isinstance(text, str) or not text.strip():
        raise ParseError(f"{what} is empty")
    if len(text) > MAX_LENGTH:
        raise ParseError(f"{what} is too long ({len(text)} characters, at most {MAX_LENGTH})")
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        raise ParseError(f"{what} contains bytes that are not valid UTF-8 text") from None
    if not text.isprintable():
        raise ParseError(f"{what} contains control characters")
    if "#" in text:   # Python would read the rest of the line as a comment and drop it silently
        raise ParseError(f"{what}: '#' is not part of the expression language (at column {text.index('#') + 1})")
    return text


#: operator tokens that each make at least one syntax-tree node (comparisons, which chain into one
#: node, and brackets and commas, which make none, are not counted)
_NODE_OPERATORS = frozenset({"+", "-", "*", "/", "**", "//", "%", "@", "&", "|", "^", "~", "<<", ">>"})


def _too_many_operators(text: str) -> bool:
    """True where ``text`` has more operator tokens than :data:`MAX_NODES`: its syntax tree would be
    refused by :func:`_bound_tree`, so it is refused before :func:`ast.parse` builds it (a sum of
    hundreds of terms is a tree hundreds of levels deep, whose construction in CPython can end in a
    RecursionError or a SystemError, "AST constructor recursion depth mismatch").  Counted by
    :mod:`tokenize`, which does not recurse; a text it cannot tokenize is left to the parser's message."""
    count = 0
    try:
        for tok in tokenize.generate_tokens(io.StringIO(text).readline):
            if tok.type == tokenize.OP and tok.string in _NODE_OPERATORS:
                count += 1
                if count > MAX_NODES:
                    return True
    except (tokenize.TokenError, SyntaxError):
        return False
    return False


def _python_tree(text: str) -> ast.Expression:
    """Python's syntax tree of ``text`` as one expression (the one call of :func:`ast.parse`)."""
    return ast.parse(text, mode="eval")


def referenced_names(text: str, *, what: str = "expression") -> set[str]:
    """Every name an expression mentions (symbols and functions), after the same bounds as
    :func:`parse_expression`; an unparsable text gives the empty set (the parse reports it)."""
    text = _checked_text(text, what).replace("^", "**").strip()
    if _too_many_operators(text):
        return set()
    try:
        tree = _python_tree(text)
    except (SyntaxError, RecursionError, MemoryError, ValueError, OverflowError, SystemError):
        return set()
    return {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)}


def parse_expression(text: str, symbols: Mapping[str, sp.Symbol], *, what: str = "expression") -> sp.Expr:
    """Translate ``text`` into a sympy expression over ``symbols`` (name -> Symbol).

    Every cost is bounded before sympy sees the text: its length (:data:`MAX_LENGTH`,
    checked first), the depth and size of the syntax tree, the size of every number built
    (|x| <= 1e300), numeric exponents of symbolic bases (|e| <= :data:`MAX_EXPONENT`) and
    arguments of exp of pure numbers, and the work of every power of numbers (exact only while
    cheap, else a 30-digit float).  The result must be real where the symbols are (v > 0,
    states > 0): an expression that sympy shows complex (``sqrt(-v)``, ``log(-1)``), a negative
    number or base to a non-integer power (``(-1)**(1/3)``) or a value that is not finite
    (``0/0``, ``log(0)``) is refused.

    Parameters
    ----------
    text : the expression, Python syntax, ``^`` read as a power.
    symbols : the names that may appear, mapped to their sympy symbols.
    what : how the expression is named in error messages (e.g. "mu").

    Returns
    -------
    sympy.Expr

    Raises
    ------
    ParseError
        Naming the first offending token or the bound that was exceeded; every failure of
        the parser (including recursion, memory and overflow errors) is reported as this.
    """
    text = _checked_text(text, what)
    try:
        return _parse(text, symbols, what)
    except ParseError:
        raise
    except (RecursionError, MemoryError):
        raise ParseError(f"{what} is too deeply nested or too large") from None
    except (ValueError, OverflowError, TypeError, ArithmeticError, AttributeError) as exc:
        raise ParseError(f"{what} cannot be parsed: {type(exc).__name__}: "
                         f"{str(exc).splitlines()[0][:120] if str(exc) else ''}") from None


def _parse(text: str, symbols: Mapping[str, sp.Symbol], what: str) -> sp.Expr:
    """The whitelist walk behind :func:`parse_expression`, in three phases: the syntax tree of
    ``text`` (``^`` read as a power; :func:`_syntax_tree`), bounded in size and depth before any
    sympy object is built (:func:`_bound_tree`), then walked node by node into sympy, each node
    kind accepted or refused by name (:class:`_Walker`, never executed); the result must be
    real."""
    tree = _syntax_tree(text, what)
    _bound_tree(tree, what)
    expr = _Walker(symbols, what).walk(tree)
    if expr.has(sp.I) or expr.is_extended_real is False:
        raise ParseError(f"{what} = {str(expr)[:80]} is not real for positive slip rate, states and parameters")
    return expr


def _syntax_tree(text: str, what: str) -> ast.Expression:
    """The syntax tree of ``text`` as one Python expression, ``^`` read as a power; a
    :class:`~landau.errors.ParseError` with the parser's message and column when it is not one."""
    # '^' means power in papers; Python would parse it as a low-precedence XOR
    text = text.replace("^", "**")
    if _too_many_operators(text.strip()):
        raise ParseError(f"{what} is too large (more than {MAX_NODES} operators, so more than {MAX_NODES} "
                         "syntax nodes)")
    try:
        return _python_tree(text.strip())
    except SyntaxError as exc:
        raise ParseError(f"{what} {text!r} is not a valid expression: {exc.msg} at column {exc.offset}") from None
    except SystemError:   # CPython's AST construction on a tree too deep for the stack left
        raise ParseError(f"{what} is too deeply nested or too large") from None


def _bound_tree(tree: ast.AST, what: str) -> None:
    """Refuse a tree with more than :data:`MAX_NODES` nodes or deeper than :data:`MAX_DEPTH`
    (walked without recursion, before any sympy object is built)."""
    nodes = 0
    stack: list[tuple[ast.AST, int]] = [(tree, 0)]
    while stack:
        node, depth = stack.pop()
        nodes += 1
        if nodes > MAX_NODES:
            raise ParseError(f"{what} is too large (more than {MAX_NODES} syntax nodes)")
        if depth > MAX_DEPTH:
            raise ParseError(f"{what} is too deeply nested (more than {MAX_DEPTH} levels)")
        stack.extend((child, depth + 1) for child in ast.iter_child_nodes(node))


class _Walker:
    """The translation of a bounded syntax tree into sympy over ``symbols``: :meth:`walk` accepts
    numbers, declared names and constants, the arithmetic operators and calls of
    :data:`FUNCTIONS`, and refuses every other node with a :class:`~landau.errors.ParseError`
    naming it; powers, ``exp`` and the results' sizes are built under the module's cost bounds.
    ``what`` names the expression in the messages."""

    def __init__(self, symbols: Mapping[str, sp.Symbol], what: str) -> None:
        self.symbols, self.what = symbols, what

    # -- the bounds on what is built
    def bounded(self, result: sp.Expr, token: str) -> sp.Expr:
        """``result``, refused when it is not finite or a number outside 1e-300 ≤ |x| ≤ 1e300."""
        if result.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
            raise ParseError(f"{self.what}: {token!r} is not finite")
        if result.is_Number:
            dec = _number_decades(result)
            if dec is not None and abs(dec) > MAX_DECADES:
                raise ParseError(f"{self.what}: {token!r} is out of range (|x| must lie between 1e-300 and 1e300)")
        return result

    def out_of_range(self, token: str) -> ParseError:
        """The error of a number outside 1e-300 ≤ |x| ≤ 1e300."""
        return ParseError(f"{self.what}: {token!r} is out of range (|x| must lie between 1e-300 and 1e300)")

    def not_real(self, token: str, why: str) -> ParseError:
        """The error of a value that is not real, with the reason."""
        return ParseError(f"{self.what}: {token!r} is not real ({why})")

    # -- powers, exp and calls
    def number_power(self, base: sp.Expr, ex: sp.Expr, token: str) -> sp.Expr:
        """base**ex for symbol-free base and exponent: exact while that is cheap (an exact number
        to a small integer or a small root), else a float computed by mpmath (30 digits)."""
        import math

        what = self.what
        b, e = _finite_real(base), _finite_real(ex)
        if b is None or e is None:
            raise ParseError(f"{what}: {token!r} is not a finite real number")
        if b == 0:
            if e <= 0:
                raise ParseError(f"{what}: {token!r} divides by zero (not finite)")
            return sp.Integer(0)
        if e * math.log10(abs(b)) > MAX_DECADES or e * math.log10(abs(b)) < -MAX_DECADES:
            raise self.out_of_range(token)
        integral = ex.is_Integer or (ex.is_Float and float(ex).is_integer())
        if b < 0 and not integral:
            raise self.not_real(token, "a negative number to a non-integer power")
        if ex.is_Rational and (base.is_Rational or (not base.is_Number and abs(e) <= MAX_EXPONENT)) \
                and _exact_ok(base, ex):
            return base ** ex
        if base.is_Float and ex.is_Number:
            return base ** ex                       # mpmath arithmetic: no exact work
        if integral and abs(e) <= 2 ** 31:
            return sp.Float(base.evalf(30), 30) ** int(e)
        return sp.Float(base.evalf(30), 30) ** sp.Float(ex.evalf(30), 30)

    def power(self, base: sp.Expr, ex: sp.Expr, token: str) -> sp.Expr:
        """base**ex under the bounds: numbers by :meth:`number_power`, a number to a symbolic power
        only for a nonnegative base, a symbolic base to a numeric exponent of magnitude at most
        :data:`MAX_EXPONENT` (the numbers sympy distributes it over bounded in size and cost)."""
        what = self.what
        if not base.free_symbols:
            if not ex.free_symbols:
                return self.number_power(base, ex, token)
            b = _finite_real(base)
            if b is None or b < 0:
                raise self.not_real(token, "a negative number to a symbolic power")
            return self.exp_of(ex, token) if base == sp.E else base ** ex
        if ex.is_Number:
            if abs(float(ex)) > MAX_EXPONENT:
                raise ParseError(f"{what}: exponent in {token!r} exceeds {MAX_EXPONENT} in magnitude")
        elif not ex.free_symbols:
            ev = _finite_real(ex)
            if ev is None:
                raise ParseError(f"{what}: exponent in {token!r} is not a finite real number")
            if abs(ev) > MAX_EXPONENT:
                raise ParseError(f"{what}: exponent in {token!r} exceeds {MAX_EXPONENT} in magnitude")
        if ex.is_Number and not ex.is_Integer and base.is_extended_negative:
            raise self.not_real(token, "a negative base to a non-integer power")
        if ex.is_Number:
            # sympy distributes a numeric power over the numbers of a product: bound their size and cost
            numbers = _exact_factors(base) + [(f, sp.Integer(1)) for f in sp.Mul.make_args(base) if f.is_Float]
            for c, r in numbers:
                dec = _number_decades(c)
                if dec is not None and abs(float(r * ex)) * abs(dec) > MAX_DECADES:
                    raise self.out_of_range(token)
            if ex.is_Rational and not _exact_ok(base, ex):
                ex = sp.Float(ex, 30)
        return base ** ex

    def exp_of(self, arg: sp.Expr, token: str) -> sp.Expr:
        """exp(arg) with the powers sympy makes of it (exp(c*log(x)) is x**c) built by :meth:`power`,
        under its cost bound."""
        powers, rest = [], []
        for t in sp.Add.make_args(arg):
            c, m = t.as_coeff_Mul()
            # as sympy's exp does: a factor that logcombine makes a log (log(2) + log(3)) counts as one
            fs = [sp.logcombine(f) if not isinstance(f, sp.log) and f.has(sp.log) else f for f in sp.Mul.make_args(m)]
            logs = [f for f in fs if isinstance(f, sp.log)]
            if len(logs) == 1 and all(f.is_comparable for f in fs if f is not logs[0]):
                powers.append(self.power(logs[0].args[0], c * sp.Mul(*[f for f in fs if f is not logs[0]]), token))
            else:
                rest.append(t)
        return sp.Mul(*powers) * sp.exp(sp.Add(*rest))

    def call(self, name: str, arg: sp.Expr, token: str) -> sp.Expr:
        """The whitelisted function ``name`` of ``arg`` (exp, sinh, cosh of a number at most
        :data:`MAX_EXP_ARG`; sqrt and exp through :meth:`power` and :meth:`exp_of`)."""
        if name in ("exp", "sinh", "cosh") and not arg.free_symbols:
            x = _finite_real(arg)
            if x is not None and abs(x) > MAX_EXP_ARG:
                raise ParseError(f"{self.what}: {token!r} is out of range (argument above {MAX_EXP_ARG:g})")
        if name == "sqrt":
            return self.power(arg, sp.Rational(1, 2), token)
        if name == "exp":
            return self.exp_of(arg, token)
        return FUNCTIONS[name](arg)

    # -- the walk: one method per accepted node kind, everything else refused by name
    def walk(self, node: ast.AST) -> sp.Expr:
        """The sympy expression of ``node``; a :class:`~landau.errors.ParseError` naming the first
        node that is not on the whitelist."""
        what = self.what
        token = ast.unparse(node)[:60] if not isinstance(node, ast.Expression) else ""
        if isinstance(node, ast.Expression):
            return self.walk(node.body)
        if isinstance(node, ast.Constant):
            return self._constant(node, token)
        if isinstance(node, ast.Name):
            return self._name(node)
        if isinstance(node, ast.BinOp):
            return self._binop(node, token)
        if isinstance(node, ast.UnaryOp):
            uop = _UNARY.get(type(node.op))
            if uop is None:
                raise ParseError(f"{what}: operator {type(node.op).__name__!r} is not allowed")
            return uop(self.walk(node.operand))
        if isinstance(node, ast.Call):
            return self._call(node, token)
        if isinstance(node, ast.Attribute):
            raise ParseError(f"{what}: attribute access {ast.unparse(node)!r} is not allowed")
        if isinstance(node, ast.Subscript):
            raise ParseError(f"{what}: subscript {ast.unparse(node)!r} is not allowed")
        raise ParseError(f"{what}: {type(node).__name__} {token!r} is not allowed")

    def _constant(self, node: ast.Constant, token: str) -> sp.Expr:
        """A literal: a finite int or float (exact integer, float from its repr), within range."""
        what = self.what
        if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
            raise ParseError(f"{what}: literal {node.value!r} is not a number")
        if (isinstance(node.value, float) and node.value != node.value
                or node.value in (float("inf"), float("-inf"))):
            raise ParseError(f"{what}: literal {token!r} is not a finite number")
        val = sp.Integer(node.value) if isinstance(node.value, int) else sp.Float(repr(node.value))
        return self.bounded(val, token)

    def _name(self, node: ast.Name) -> sp.Expr:
        """A declared symbol or a constant (:data:`CONSTANTS`); a function name without its call
        and an undeclared name are refused."""
        what = self.what
        if node.id in self.symbols:
            return self.symbols[node.id]
        if node.id in CONSTANTS:
            return CONSTANTS[node.id]
        if node.id in FUNCTIONS:
            raise ParseError(f"{what}: function {node.id!r} used without arguments")
        raise ParseError(f"{what}: unknown symbol {node.id!r} (declare it as a parameter or state)")

    def _binop(self, node: ast.BinOp, token: str) -> sp.Expr:
        """An arithmetic operation of :data:`_BINOPS` (a power through :meth:`power`, a division
        by an exact zero refused)."""
        what = self.what
        op = _BINOPS.get(type(node.op))
        if op is None:
            raise ParseError(f"{what}: operator {type(node.op).__name__!r} is not allowed")
        left, right = self.walk(node.left), self.walk(node.right)
        if isinstance(node.op, ast.Pow):
            return self.bounded(self.power(left, right, token), token)
        if isinstance(node.op, ast.Div) and right == 0:
            raise ParseError(f"{what}: {token!r} divides by zero (not finite)")
        return self.bounded(op(left, right), token)

    def _call(self, node: ast.Call, token: str) -> sp.Expr:
        """A plain call of a whitelisted function with one positional argument."""
        what = self.what
        if not isinstance(node.func, ast.Name):
            raise ParseError(f"{what}: only plain function calls are allowed, not {ast.unparse(node.func)!r}")
        name = node.func.id
        if name not in FUNCTIONS:
            raise ParseError(f"{what}: unknown function {name!r} (allowed: {', '.join(sorted(FUNCTIONS))})")
        if node.keywords:
            raise ParseError(f"{what}: keyword arguments are not allowed in {name}()")
        if len(node.args) != 1:
            raise ParseError(f"{what}: {name}() takes exactly one argument")
        return self.bounded(self.call(name, self.walk(node.args[0]), token), token)
