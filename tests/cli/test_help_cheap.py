"""``landau --help`` and ``landau --version`` are cheap: they import no part of the engine.

Their CPU cost is a benchmark (``benchmarks/run.py --only help``); here, in a fresh
interpreter, the modules they leave in ``sys.modules`` — the engine's heavy dependencies must
not be among them — and the summaries that ``--help`` prints without importing a command.
"""

from __future__ import annotations

import importlib
import json
import subprocess
import sys

import pytest

from landau.cli.app import COMMANDS, SUMMARIES

HEAVY = ("sympy", "numba", "scipy", "numpy", "matplotlib")

PROBE = """
import contextlib, io, json, sys
from landau.cli import main
out = io.StringIO()
with contextlib.redirect_stdout(out):
    try:
        code = main({argv!r})
    except SystemExit as exc:
        code = exc.code
print(json.dumps({{"code": code, "out": out.getvalue(),
                   "heavy": sorted({{m.split(".")[0] for m in sys.modules}} & set({heavy!r}))}}))
"""


def _probe(argv: list[str]) -> dict:
    proc = subprocess.run([sys.executable, "-c", PROBE.format(argv=argv, heavy=HEAVY)], capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return json.loads(proc.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("argv", [["--help"], ["-h"], ["--version"]])
def test_help_and_version_import_no_engine(argv):
    res = _probe(argv)
    assert res["code"] in (0, None)
    assert res["heavy"] == [], f"landau {' '.join(argv)} imported {res['heavy']}"


def test_help_lists_every_command_with_its_summary():
    out = _probe(["--help"])["out"]
    flat = " ".join(out.split())
    for name in COMMANDS:
        assert name in out
        assert " ".join(SUMMARIES[name].split()) in flat, name


@pytest.mark.parametrize("name", list(COMMANDS))
def test_summary_is_the_first_line_of_the_command_docstring(name):
    """The summary ``--help`` prints without importing a command is the one its module states
    (a new command adds its line to ``landau.cli.app.SUMMARIES``)."""
    assert name in SUMMARIES, f"landau.cli.app.SUMMARIES has no summary for the command {name!r}"
    doc = (importlib.import_module(COMMANDS[name]).__doc__ or "").strip()
    assert SUMMARIES[name] == doc.splitlines()[0]


def test_a_command_help_still_documents_its_options(capsys):
    from landau.cli import main

    with pytest.raises(SystemExit) as exc:
        main(["derive", "--help"])
    assert exc.value.code == 0
    assert "--codim2" in capsys.readouterr().out
