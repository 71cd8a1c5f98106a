"""Griffe extension: show Sphinx cross-reference roles as plain code in the API reference.

Some docstrings use reStructuredText roles (``:class:`SpringBlock```, ``:func:`~a.b.c```),
which Markdown would print literally.  This extension rewrites them to code spans
(``SpringBlock``, ``c``) before mkdocstrings renders the docstring.
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


def to_markdown(text: str) -> str:
    """Replace every Sphinx role in ``text`` by a Markdown code span."""
    return _ROLE.sub(_plain, text)


class SphinxRolesToCode(griffe.Extension):
    """Rewrite Sphinx roles in every docstring griffe loads."""

    def on_instance(self, *, node: Any, obj: griffe.Object, agent: Any, **kwargs: Any) -> None:
        if obj.docstring is not None:
            obj.docstring.value = to_markdown(obj.docstring.value)
