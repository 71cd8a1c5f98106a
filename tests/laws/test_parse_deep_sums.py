"""A sum of hundreds of terms is refused before CPython builds its syntax tree: the tree of
``v+v+…+v`` (787 terms) is 787 levels deep, and its construction could end in a raw
``SystemError: AST constructor recursion depth mismatch`` under the fuzz run's deep stack (issue seen
with ``pytest -m fuzz``); every such text is beyond :data:`MAX_NODES` anyway."""

from __future__ import annotations

import pytest
import sympy as sp

from landau.errors import ParseError
from landau.laws import parse as parse_module
from landau.laws.parse import MAX_NODES, parse_expression, referenced_names

V = {"v": sp.Symbol("v", positive=True)}


def _no_tree(*args, **kwargs):
    raise AssertionError("the syntax tree was built")


@pytest.mark.parametrize("text", ["+".join(["v"] * 787), "-" * 1500 + "v", "**".join(["v"] * (MAX_NODES + 2))])
def test_a_text_with_more_operators_than_nodes_allowed_never_reaches_ast_parse(text, monkeypatch):
    monkeypatch.setattr(parse_module, "_python_tree", _no_tree)
    with pytest.raises(ParseError, match=rf"mu is too large \(more than {MAX_NODES} operators"):
        parse_expression(text, V, what="mu")
    assert referenced_names(text) == set()


def test_the_bound_counts_operators_not_characters_of_numbers():
    # 1e-5 has a '-' that is no operator: 300 such numbers summed are 299 operators, within the bound
    # (the tree is then refused for its depth, by the tree's own bound, after ast.parse)
    text = "+".join(["1e-5*v"] * 100)
    assert len(text) < 2000
    with pytest.raises(ParseError, match="too deeply nested"):
        parse_expression(text, V)
    assert parse_expression("1e-5*v + 2e-3", V) == sp.Float(1e-5) * V["v"] + sp.Float(2e-3)


def test_a_systemerror_of_the_ast_construction_is_a_parse_error(monkeypatch):
    def broken(*args, **kwargs):
        raise SystemError("AST constructor recursion depth mismatch (before=37, after=39)")

    monkeypatch.setattr(parse_module, "_python_tree", broken)
    with pytest.raises(ParseError, match="mu is too deeply nested or too large"):
        parse_expression("v + 1", V, what="mu")
    assert referenced_names("v + 1") == set()
