"""The data format of the derivation cache: JSON, with sympy expressions as ``srepr`` atoms and a
table of operations, read back without executing anything.

:mod:`landau.support.cache` stores results (formulas in the atoms of the law's jets, closed forms,
LaTeX text) that used to be pickled; unpickling a planted file runs arbitrary code.  This
format holds only JSON scalars, lists, tagged tuples and dictionaries, and a *node table* for
expressions:

* an atom (a symbol with its assumptions, an integer, a rational, a float with its precision,
  a named constant) is its ``sympy.srepr`` text, read back by :func:`parse_atom`, which accepts
  only calls of ``Symbol``, ``Dummy``, ``Integer``, ``Rational``, ``Float`` with literal arguments
  and the names of sympy's constants (it walks the syntax tree; nothing is evaluated);
* any other expression is ``[class name, [node numbers of its arguments]]``, the class taken from
  the fixed table :data:`CLASSES` (sympy's arithmetic, elementary and special functions,
  relations and conditions) and rebuilt as ``cls(*args, evaluate=False)``: the stored tree is the
  tree of the object that was written, rebuilt exactly as it was, without evaluating it again;
* each distinct sub-expression is written once (the formulas are DAGs whose tree form is
  exponentially larger), so the size is linear in the number of distinct operations.

Reading back never compares two expressions structurally.  sympy's constructors sit behind a
cache whose lookups compare a new call's arguments with those of earlier calls by ``==``, and
``==`` of two equal but distinct DAGs walks their *tree* form: a formula rebuilt in a process that
already holds an equal copy (a derivation, then a second command reading its entry, in one
notebook or test session) cost seconds there: the quintic coefficients of a law read back in 6.6
CPU-s instead of 0.21, and the walk grows exponentially with the formula's depth.  Two
things keep every such comparison an identity check: ``evaluate=False`` calls never meet the
evaluated calls of a derivation in that cache (their keyword is part of its key), and every node
read back is *interned* (:data:`_INTERNED`, keyed by its class and the identities of its
arguments), so equal sub-expressions of all the entries a process reads are one object.

A value the format cannot hold (another class, a numpy array) raises :class:`Unencodable`; the
cache then keeps nothing for it and the result is simply computed each time.
"""

from __future__ import annotations

import ast
import json
from typing import Any

import sympy as sp

#: version of this format (part of every entry)
FORMAT = "landau-cache-json/1"

_CLASS_NAMES = (
    "Add", "Mul", "Pow", "exp", "log", "sin", "cos", "tan", "cot", "sec", "csc", "asin", "acos", "atan",
    "acot", "atan2", "sinh", "cosh", "tanh", "coth", "asinh", "acosh", "atanh", "Abs", "sign", "re", "im",
    "arg", "conjugate", "floor", "ceiling", "Min", "Max", "Heaviside", "DiracDelta", "erf", "erfc", "gamma",
    "loggamma", "LambertW", "Piecewise", "ExprCondPair", "Tuple", "Equality", "Unequality", "StrictLessThan",
    "LessThan", "StrictGreaterThan", "GreaterThan", "And", "Or", "Not", "Derivative")
#: the classes an entry may name (everything else is refused)
CLASSES: dict[str, type] = {name: getattr(sp, name) for name in _CLASS_NAMES if name != "ExprCondPair"}
CLASSES["ExprCondPair"] = sp.functions.elementary.piecewise.ExprCondPair
_ATOM_CALLS = {"Symbol": sp.Symbol, "Dummy": sp.Dummy, "Integer": sp.Integer, "Rational": sp.Rational,
               "Float": sp.Float}
_ATOM_NAMES = {"pi": sp.pi, "E": sp.E, "I": sp.I, "oo": sp.oo, "zoo": sp.zoo, "nan": sp.nan,
               "true": sp.true, "false": sp.false, "EulerGamma": sp.EulerGamma, "Catalan": sp.Catalan,
               "GoldenRatio": sp.GoldenRatio}


class Unencodable(TypeError):
    """A value (or a part of it) that the cache format cannot hold."""


class Undecodable(ValueError):
    """An entry that is not in the cache format (corrupt, or naming something not allowed)."""


def _literal(node: ast.AST):
    if isinstance(node, ast.Constant) and isinstance(node.value, (str, int, bool)) and node.value is not None:
        return node.value
    if (isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub) and isinstance(node.operand, ast.Constant)
            and type(node.operand.value) is int):
        return -node.operand.value
    raise Undecodable(f"not a literal: {ast.dump(node)[:80]}")


def _atom(node: ast.AST) -> sp.Basic:
    if isinstance(node, ast.Name) and node.id in _ATOM_NAMES:
        return _ATOM_NAMES[node.id]
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub):
        value = _atom(node.operand)
        if not isinstance(value, sp.Number):
            raise Undecodable("a sign before something that is not a number")
        return -value
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in _ATOM_CALLS:
        args = [_literal(a) for a in node.args]
        kwargs = {}
        for k in node.keywords:
            if k.arg is None or not k.arg.isidentifier() or k.arg.startswith("_"):
                raise Undecodable("a keyword argument that is not a plain name")
            kwargs[k.arg] = _literal(k.value)
        try:
            return _ATOM_CALLS[node.func.id](*args, **kwargs)
        except Exception as exc:                # e.g. a malformed number: a corrupt entry
            raise Undecodable(f"bad atom ({exc})") from None
    raise Undecodable("not an atom of the cache format")


def parse_atom(text: str) -> sp.Basic:
    """The sympy atom whose ``srepr`` is ``text``, read through a whitelist (nothing is executed).

    Raises
    ------
    Undecodable
        ``text`` is anything but ``Symbol``/``Dummy``/``Integer``/``Rational``/``Float`` with
        literal arguments, or a name of a sympy constant.
    """
    if not isinstance(text, str) or len(text) > 10_000:
        raise Undecodable("an atom is not a short string")
    try:
        tree = ast.parse(text, mode="eval")
    except SyntaxError:
        raise Undecodable("an atom that does not parse") from None
    return _atom(tree.body)


def _exactly(node: sp.Basic, cls: type) -> bool:
    """Whether ``node`` is of class ``cls`` itself (a subclass may be another thing)."""
    return type(node) is cls


class _Nodes:
    """The node table of one entry, built while encoding."""

    def __init__(self):
        self.rows: list = []
        self.by_id: dict[int, int] = {}
        self.by_row: dict[str, int] = {}
        self.keep: list = []

    def add(self, row) -> int:
        text = json.dumps(row)
        n = self.by_row.get(text)
        if n is None:
            n = self.by_row[text] = len(self.rows)
            self.rows.append(row)
        return n

    def expr(self, root: sp.Basic) -> int:
        stack: list[tuple[sp.Basic, bool]] = [(root, False)]
        while stack:
            node, done = stack.pop()
            if id(node) in self.by_id:
                continue
            self.keep.append(node)
            if not node.args:
                text = sp.srepr(node)
                try:                            # only what reads back as itself is written
                    same = parse_atom(text) == node
                except Undecodable:
                    same = False
                if not same:
                    raise Unencodable(f"sympy atom {text[:60]}")
                self.by_id[id(node)] = self.add(["atom", text])
                continue
            name = type(node).__name__
            if name not in CLASSES or not _exactly(node, CLASSES[name]):
                raise Unencodable(f"sympy class {name}")
            if not done:
                stack.append((node, True))
                stack.extend((a, False) for a in reversed(node.args) if id(a) not in self.by_id)
                continue
            self.by_id[id(node)] = self.add([name, [self.by_id[id(a)] for a in node.args]])
        return self.by_id[id(root)]


def _encode(value: Any, nodes: _Nodes, depth: int = 0):
    if depth > 100:
        raise Unencodable("nested too deeply")
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, int):
        return value
    if isinstance(value, float):
        return {"float": repr(value)}
    if isinstance(value, sp.Basic):
        return {"sympy": nodes.expr(value)}
    if isinstance(value, tuple):
        return {"tuple": [_encode(v, nodes, depth + 1) for v in value]}
    if isinstance(value, list):
        return {"list": [_encode(v, nodes, depth + 1) for v in value]}
    if isinstance(value, dict):
        return {"dict": [[_encode(k, nodes, depth + 1), _encode(v, nodes, depth + 1)] for k, v in value.items()]}
    raise Unencodable(f"a value of type {type(value).__name__}")


def dumps(value: Any) -> bytes:
    """``value`` (None, bool, int, float, str, sympy expressions, tuples, lists and dictionaries
    of them) as the JSON text of this format.

    Raises
    ------
    Unencodable
        A part of ``value`` the format cannot hold.
    """
    nodes = _Nodes()
    doc = _encode(value, nodes)
    return json.dumps({"format": FORMAT, "nodes": nodes.rows, "value": doc}, separators=(",", ":")).encode()


#: every node read back in this process: ``("atom", srepr text)`` or ``(class name, identities of
#: the argument nodes)`` -> the node.  The table holds each node, and so its arguments, alive, so an
#: identity in a key is never reused by another object.
_INTERNED: dict[tuple, sp.Basic] = {}
#: above this many nodes the table starts afresh (memory of a long session that reads many
#: laws); nodes read after that are new objects, equal to the earlier ones
INTERN_LIMIT = 1_000_000
#: the classes whose constructor takes no ``evaluate`` keyword (it evaluates nothing)
_NO_EVALUATE_KEYWORD = frozenset({"ExprCondPair"})


def _node(head: str, args: tuple) -> sp.Basic:
    """The node ``head(*args)`` of an entry, interned (see the module docstring)."""
    key = (head, tuple(map(id, args)))
    node = _INTERNED.get(key)
    if node is None:
        cls = CLASSES[head]
        node = cls(*args) if head in _NO_EVALUATE_KEYWORD else cls(*args, evaluate=False)
        _INTERNED[key] = node
    return node


def _atom_node(text: str) -> sp.Basic:
    key = ("atom", text)
    node = _INTERNED.get(key)
    if node is None:
        node = _INTERNED[key] = parse_atom(text)
    return node


def _build(rows) -> list:
    if not isinstance(rows, list):
        raise Undecodable("the node table is not a list")
    if len(_INTERNED) + len(rows) > INTERN_LIMIT:
        _INTERNED.clear()
    out: list = []
    for row in rows:
        if not (isinstance(row, list) and len(row) == 2 and isinstance(row[0], str)):
            raise Undecodable("a malformed node")
        head, body = row
        if head == "atom":
            if not isinstance(body, str):
                raise Undecodable("an atom is not a short string")
            out.append(_atom_node(body))
            continue
        if head not in CLASSES:
            raise Undecodable(f"a node of class {head[:40]!r}, which the format does not allow")
        if not (isinstance(body, list) and all(type(i) is int and 0 <= i < len(out) for i in body)):
            raise Undecodable("a node refers to a node that is not before it")
        try:
            out.append(_node(head, tuple(out[i] for i in body)))
        except Exception as exc:
            raise Undecodable(f"a node cannot be rebuilt ({type(exc).__name__})") from None
    return out


def _decode(doc, built: list, depth: int = 0):
    if depth > 100:
        raise Undecodable("nested too deeply")
    if doc is None or isinstance(doc, (bool, str, int)):
        return doc
    if isinstance(doc, dict) and len(doc) == 1:
        (tag, body), = doc.items()
        if tag == "float" and isinstance(body, str):
            try:
                return float(body)
            except ValueError:
                raise Undecodable("a malformed float") from None
        if tag == "sympy" and type(body) is int and 0 <= body < len(built):
            return built[body]
        if tag in ("tuple", "list") and isinstance(body, list):
            items = [_decode(v, built, depth + 1) for v in body]
            return tuple(items) if tag == "tuple" else items
        if tag == "dict" and isinstance(body, list) and all(isinstance(p, list) and len(p) == 2 for p in body):
            return {_decode(k, built, depth + 1): _decode(v, built, depth + 1) for k, v in body}
    raise Undecodable("a value that is not in the cache format")


def loads(data: bytes) -> Any:
    """The value of :func:`dumps`' output ``data``.

    Raises
    ------
    Undecodable
        ``data`` is not an entry of this format, or names a class or atom outside the whitelist.
    """
    try:
        doc = json.loads(data)
    except (ValueError, RecursionError):
        raise Undecodable("not JSON") from None
    if not (isinstance(doc, dict) and doc.get("format") == FORMAT and set(doc) == {"format", "nodes", "value"}):
        raise Undecodable("not an entry of this format")
    try:
        return _decode(doc["value"], _build(doc["nodes"]))
    except (TypeError, RecursionError):         # e.g. an unhashable dictionary key
        raise Undecodable("a malformed value") from None
