"""Every ``landau`` command shown in the README runs (exit code 0) on a fresh checkout.

The README is the front door: its commands are parsed from its ``bash`` blocks (continuation
lines joined, comments dropped) and run through the command-line entry point in a temporary
folder.  The heavier ones (whole-figure regeneration, simulation-backed verification,
transition sweeps) run in the opt-in slow suite.
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from landau.cli import main

README = Path(__file__).resolve().parents[2] / "README.md"
#: commands whose cost is minutes of CPU: the slow suite runs them
SLOW = ("landau verify", "landau figures", "landau transition", "landau scene run")


def readme_commands() -> list[str]:
    text = README.read_text(encoding="utf-8")
    cmds = []
    for block in re.findall(r"```bash\n(.*?)```", text, flags=re.S):
        joined = re.sub(r"\\\n\s*", " ", block)
        for line in joined.splitlines():
            line = line.strip()
            if line.startswith("landau "):
                cmds.append(line)
    return cmds


def _params():
    out = []
    for cmd in readme_commands():
        marks = [pytest.mark.slow] if cmd.startswith(SLOW) else []
        out.append(pytest.param(cmd, marks=marks, id=cmd[:70]))
    return out


def test_the_readme_shows_commands():
    cmds = readme_commands()
    assert len(cmds) >= 10 and any("--friction" in c for c in cmds) and any("landau hopf" in c for c in cmds)


@pytest.mark.parametrize("cmd", _params())
def test_readme_command_runs(cmd, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    argv = shlex.split(cmd, comments=True)[1:]
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 0, f"{cmd!r} exited {code}: {err.strip()[:400]}"
