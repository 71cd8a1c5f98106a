"""Griffe extension: show Sphinx cross-reference roles as plain code in the API reference.

Some docstrings use reStructuredText roles (``:class:`SpringBlock```, ``:func:`~a.b.c```),
which Markdown would print literally.  This extension rewrites them to code spans
(``SpringBlock``, ``c``) before mkdocstrings renders the docstring, and ends a paragraph
that introduces a literal block with one colon instead of two.
"""

from __future__ import annotations

import re
from typing import Any

import griffe

_ROLE = re.compile(r":(?:py:)?(?:class|func|meth|mod|data|attr|exc|obj|const|term|ref):`(~?)([^`]+)`")


def _plain(match: re.Match) -> str:
    short, target = match.group(1), match.group(2)
    if "<" in target and target.endswith(">"):  # :ref:`text <target>`
        target = target[: target.index("<")].strip()
    if short:
        target = target.rsplit(".", 1)[-1]
    return f"`{target}`"


#: reStructuredText "paragraph::" introducing a literal block (Markdown: the indented block alone)
_LITERAL = re.compile(r"(\S)::\n\n")
_LITERAL_ALONE = re.compile(r"(^|\n)\s*::\n\n")


def to_markdown(text: str) -> str:
    """Replace every Sphinx role in ``text`` by a Markdown code span, and ``text::`` by ``text:``."""
    text = _LITERAL_ALONE.sub(r"\1\n", text)
    text = _LITERAL.sub(r"\1:\n\n", text)
    return _ROLE.sub(_plain, text)


class SphinxRolesToCode(griffe.Extension):
    """Rewrite Sphinx roles in every docstring griffe loads."""

    def on_instance(self, *, node: Any, obj: griffe.Object, agent: Any, **kwargs: Any) -> None:
        if obj.docstring is not None:
            obj.docstring.value = to_markdown(obj.docstring.value)
