"""The notebooks in examples/ (jupytext percent scripts) execute headlessly and check their
own numbers (each asserts against a closed form or a published value)."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = sorted((Path(__file__).resolve().parent.parent.parent / "examples").glob("[0-9][0-9]_*.py"))


def test_the_six_notebooks_are_there():
    assert [p.stem[:2] for p in EXAMPLES] == ["01", "02", "03", "04", "05", "06"]


@pytest.mark.parametrize("script", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs_headless(script, tmp_path):
    env = {**os.environ, "MPLBACKEND": "Agg"}
    # a generous wall-clock limit: about 30 s of CPU for all six on an idle machine
    proc = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
