"""``landau ... --help`` prints plain text: no reStructuredText markup from the docstrings, and
every help string formats (argparse %-formats them: a lone ``%`` prints the action's internals)."""

from __future__ import annotations

import argparse
import re

import pytest

from landau.cli import main
from landau.cli.app import COMMANDS, build_parser, plain_text

#: what a docstring's markup looks like once printed
MARKUP = {
    "a Sphinx role": re.compile(r":(?:py:)?[a-z]+:`"),
    "an inline literal": re.compile(r"``"),
    "a substitution": re.compile(r"(?<![\w|])\|\w[\w-]*\|(?![\w|])"),
    "a literal-block marker": re.compile(r"\S ?::$", re.M),
}


def _help(argv: list[str], capsys) -> str:
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 0
    return capsys.readouterr().out


@pytest.mark.parametrize("argv", [["--help"], *[[name, "--help"] for name in COMMANDS]],
                         ids=["landau", *COMMANDS])
def test_help_has_no_markup(argv, capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "1000")  # one line per help text: no markup cut in two by the wrapping
    out = _help(argv, capsys)
    assert "usage: landau" in out
    found = {what: pat.findall(out) for what, pat in MARKUP.items() if pat.search(out)}
    assert not found, f"landau {' '.join(argv)} prints documentation markup: {found}"


def test_markup_is_found_where_it_is():
    """The patterns above catch what the docstrings of the commands hold."""
    text = "see :func:`landau.check` and ``--json``; |sub| here; Examples::"
    assert all(pat.search(text) for pat in MARKUP.values())
    assert not any(pat.search("NAME|GLOB... up|down {list,run} a: b") for pat in MARKUP.values())


@pytest.mark.parametrize("doc, plain", [
    (":func:`landau.check`", "landau.check"),
    (":class:`~landau.derivation.hopf.HopfResult` prints", "HopfResult prints"),
    (":py:meth:`a.b.c`, :mod:`landau.cli.hopf_chain`", "a.b.c, landau.cli.hopf_chain"),
    (":ref:`the contract <contract>`", "the contract"),
    ("``--param gamma=... --param\ndelta=...``", "--param gamma=... --param\ndelta=..."),
    ("|sub| and up|down|both", "sub and up|down|both"),
    ("Examples::\n\n    landau x", "Examples:\n\n    landau x"),
    ("Examples: ::\n\n    landau x", "Examples:\n\n    landau x"),
    ("text\n\n::\n\n    landau x", "text\n\n\n    landau x"),
    ("NAME|GLOB... [--all] (a | b)", "NAME|GLOB... [--all] (a | b)"),
])
def test_plain_text(doc, plain):
    assert plain_text(doc) == plain


def _parsers():
    parser, _ = build_parser()
    [sub] = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return [parser, *sub.choices.values()]


def test_every_help_string_formats():
    """A "%" in a help string is "%%" or a "%(name)s" of the action (as argparse documents)."""
    bad = []
    for parser in _parsers():
        for action in parser._actions:
            text = action.help if isinstance(action.help, str) else ""
            if "%" in re.sub(r"%%|%\((\w+)\)[sdrfg]", "", text):
                bad.append(f"{parser.prog} {'/'.join(action.option_strings) or action.dest}: {text!r}")
            for name in re.findall(r"%\((\w+)\)", text):
                assert name in vars(action) or name == "prog", f"{parser.prog}: %({name}) is no attribute"
    assert not bad, "help strings with a lone %: " + "; ".join(bad)
