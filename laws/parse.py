"""Safe parsing of friction-law expressions given as strings.

The string is parsed by Python's :mod:`ast` into a syntax tree that is *walked*, never
executed: only numbers, declared names, the arithmetic operators and a whitelist of
functions are accepted, each translated to its sympy counterpart.  Anything else —
attribute access, subscripts, keywords, lambdas, ``__import__``, unknown functions or
symbols — is rejected with a :class:`~landau.errors.ParseError` that names the token.
``^`` is read as a power (``**``), as in most papers.
"""

from __future__ import annotations

import ast
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


def parse_expression(text: str, symbols: Mapping[str, sp.Symbol], *, what: str = "expression") -> sp.Expr:
    """Translate ``text`` into a sympy expression over ``symbols`` (name -> Symbol).

    Raises :class:`ParseError` naming the first offending token.
    """
    if not isinstance(text, str) or not text.strip():
        raise ParseError(f"{what} is empty")
    if len(text) > 10_000:
        raise ParseError(f"{what} is too long ({len(text)} characters)")
    # '^' means power in papers; Python would parse it as a low-precedence XOR
    text = text.replace("^", "**")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise ParseError(f"{what} {text!r} is not a valid expression: {exc.msg} at column {exc.offset}") from None

    def walk(node: ast.AST) -> sp.Expr:
        if isinstance(node, ast.Expression):
            return walk(node.body)
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise ParseError(f"{what}: literal {node.value!r} is not a number")
            return sp.Integer(node.value) if isinstance(node.value, int) else sp.Float(repr(node.value))
        if isinstance(node, ast.Name):
            if node.id in symbols:
                return symbols[node.id]
            if node.id in CONSTANTS:
                return CONSTANTS[node.id]
            if node.id in FUNCTIONS:
                raise ParseError(f"{what}: function {node.id!r} used without arguments")
            raise ParseError(f"{what}: unknown symbol {node.id!r} (declare it as a parameter or state)")
        if isinstance(node, ast.BinOp):
            op = _BINOPS.get(type(node.op))
            if op is None:
                raise ParseError(f"{what}: operator {type(node.op).__name__!r} is not allowed")
            return op(walk(node.left), walk(node.right))
        if isinstance(node, ast.UnaryOp):
            op = _UNARY.get(type(node.op))
            if op is None:
                raise ParseError(f"{what}: operator {type(node.op).__name__!r} is not allowed")
            return op(walk(node.operand))
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name):
                raise ParseError(f"{what}: only plain function calls are allowed, not {ast.unparse(node.func)!r}")
            name = node.func.id
            if name not in FUNCTIONS:
                raise ParseError(f"{what}: unknown function {name!r} (allowed: {', '.join(sorted(FUNCTIONS))})")
            if node.keywords:
                raise ParseError(f"{what}: keyword arguments are not allowed in {name}()")
            if len(node.args) != 1:
                raise ParseError(f"{what}: {name}() takes exactly one argument")
            return FUNCTIONS[name](walk(node.args[0]))
        if isinstance(node, ast.Attribute):
            raise ParseError(f"{what}: attribute access {ast.unparse(node)!r} is not allowed")
        if isinstance(node, ast.Subscript):
            raise ParseError(f"{what}: subscript {ast.unparse(node)!r} is not allowed")
        token = ast.unparse(node) if hasattr(ast, "unparse") else type(node).__name__
        raise ParseError(f"{what}: {type(node).__name__} {token!r} is not allowed")

    return walk(tree)
