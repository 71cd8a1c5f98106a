"""docs/cli.md lists every command and every option of the parser ``landau`` uses, and nothing else.

The page's reference part is generated (``python -m landau.cli.reference docs/cli.md``); here it
is compared with the parser three ways: it is what the generator prints now (no drift), every
command and argument the parser has appears in its command's section with its metavar and default
(read from the argparse actions, not from the generator), and no option the page names anywhere,
prose included, is unknown to the parser.  Every command takes ``--json`` (the CLI contract).
"""

from __future__ import annotations

import argparse
import difflib
import html
import re
from pathlib import Path

import pytest

from landau.cli import reference
from landau.cli.app import COMMANDS, build_parser
from landau.errors import InputError

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "cli.md"
REGENERATE = ".venv/bin/python -m landau.cli.reference docs/cli.md"


@pytest.fixture(scope="module")
def parser() -> argparse.ArgumentParser:
    return build_parser()[0]


@pytest.fixture(scope="module")
def commands(parser) -> dict[str, argparse.ArgumentParser]:
    [sub] = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return dict(sub.choices)


@pytest.fixture(scope="module")
def sections() -> dict[str, str]:
    """The generated part of the page, cut at its ``### landau NAME`` headings ("" for ``landau``)."""
    part = reference.generated_part(PAGE.read_text(encoding="utf-8"))
    pieces = re.split(r"^### landau\b ?(\S*)\n", part, flags=re.M)
    return dict(zip(pieces[1::2], pieces[2::2], strict=True))


def test_page_is_the_generated_reference(parser):
    committed = reference.generated_part(PAGE.read_text(encoding="utf-8"))
    generated = reference.render(parser)
    if committed != generated:
        diff = "".join(list(difflib.unified_diff(committed.splitlines(True), generated.splitlines(True),
                                                 "docs/cli.md (committed)", "generated from the parser"))[:60])
        pytest.fail(f"docs/cli.md is out of date with the command line; regenerate it with `{REGENERATE}`\n{diff}")


def test_every_command_has_a_section(commands, sections):
    assert set(commands) == set(COMMANDS), "a command's module could not be imported"
    assert sorted(sections) == sorted(["", *commands])


#: a row of an argument table: names (code spans), value, default, help
_ROW = re.compile(r"^\| (?P<names>`[^`]*`(?:, `[^`]*`)*) \| (?P<value>(?:`[^`]*`)?) \| "
                  r"(?P<default>(?:`[^`]*`)?) \| (?P<help>.*) \|$", re.M)


def _rows(section: str) -> list[re.Match]:
    return list(_ROW.finditer(section))


def _names(row: re.Match) -> list[str]:
    """The names of a row: ``--opt`` for each option string, ``law`` for ``[law]``, ``NAME`` for ``[NAME ...]``."""
    return [re.sub(r"^\[(.*)\]$", r"\1", s).removesuffix(" ...") for s in re.findall(r"`([^`]*)`", row["names"])]


def _row_of(rows: list[re.Match], token: str, where: str) -> re.Match:
    found = [row for row in rows if token in _names(row)]
    assert len(found) == 1, f"{where}: {token} is in {len(found)} rows of its command's table, not 1"
    return found[0]


def _shown(cell: str) -> str:
    """What a Markdown cell shows: escapes and entities undone."""
    return html.unescape(re.sub(r"\\(.)", r"\1", cell))


def test_every_option_is_in_its_command_section(commands, sections):
    for name, sub in commands.items():
        rows = _rows(sections[name])
        shown = [a for a in sub._actions if not isinstance(a, argparse._HelpAction) and a.help != argparse.SUPPRESS]
        for action in shown:
            where = f"landau {name} {'/'.join(action.option_strings) or action.dest}"
            if action.option_strings:
                row = _row_of(rows, action.option_strings[0], where)
                assert _names(row) == action.option_strings, where
            else:  # a positional argument: under its metavar, its choices or its name
                token = action.metavar or ("{" + ",".join(action.choices) + "}" if action.choices else action.dest)
                row = _row_of(rows, token, where)
            if action.option_strings and isinstance(action.metavar, str):
                assert row["value"] == f"`{action.metavar}`", where
            for choice in action.choices or ():
                assert str(choice) in row["names"] + row["value"], where
            if action.default not in (None, False, [], argparse.SUPPRESS):
                assert row["default"] == f"`{action.default}`", where
            else:
                assert row["default"] == "", where
            text = action.help or ""
            if "%(" not in text:  # (one with %(default)s and the like is compared with the generated page)
                assert _shown(row["help"]) == " ".join(text.replace("%%", "%").split()), where
        assert len(rows) == len(shown), f"landau {name}: the table has rows the parser lacks"


def test_the_top_level_lists_every_command_and_option(parser, commands, sections):
    top = sections[""]
    for name in commands:
        assert f"[`{name}`](#landau-{name})" in top
    assert "`--version`" in top and "`--help`" in reference.generated_part(PAGE.read_text(encoding="utf-8"))


def _all_options(parser: argparse.ArgumentParser, commands) -> set[str]:
    opts = {o for a in parser._actions for o in a.option_strings}
    for sub in commands.values():
        opts |= {o for a in sub._actions for o in a.option_strings}
    return opts


def test_page_names_no_option_or_command_the_parser_lacks(parser, commands):
    text = PAGE.read_text(encoding="utf-8")
    named = set(re.findall(r"(?<![\w-])--[A-Za-z][\w-]*", text))
    assert named, "the page names no option at all"
    unknown = named - _all_options(parser, commands)
    assert not unknown, f"docs/cli.md names options no command has: {sorted(unknown)}"
    used = set(re.findall(r"(?:^|`)landau ([a-z][\w-]*)", text, flags=re.M))
    assert used - set(commands) == set(), f"docs/cli.md names unknown commands: {sorted(used - set(commands))}"


def test_the_unknown_option_check_can_fail(parser, commands):
    """The regular expression of the check above does pick up an option that does not exist."""
    named = set(re.findall(r"(?<![\w-])--[A-Za-z][\w-]*", "run `landau derive --no-such-flag` or --V=1"))
    assert named - _all_options(parser, commands) == {"--no-such-flag"}


@pytest.mark.parametrize("name", list(COMMANDS))
def test_every_command_takes_json(commands, name):
    [action] = [a for a in commands[name]._actions if "--json" in a.option_strings]
    assert isinstance(action, argparse._StoreTrueAction) and action.dest == "json" and action.default is False
    assert action.option_strings == ["--json"]


def test_rewrite_replaces_only_the_generated_part(tmp_path, parser):
    page = tmp_path / "cli.md"
    prose = "# Command line\n\nHand-written prose, `--mu` and all.\n\n"
    page.write_text(prose + reference.BEGIN + "\nstale\n" + reference.END + "\n\nA closing line.\n")
    assert reference.rewrite(page, parser) is True
    text = page.read_text()
    assert text == prose + reference.render(parser) + "\nA closing line.\n"
    assert reference.rewrite(page, parser) is False


def test_a_page_without_the_markers_is_refused(tmp_path, capsys):
    page = tmp_path / "cli.md"
    page.write_text("# Command line\n")
    with pytest.raises(InputError, match="no generated reference"):
        reference.rewrite(page)
    assert reference.main([str(page)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "no generated reference" in err
    assert page.read_text() == "# Command line\n"
