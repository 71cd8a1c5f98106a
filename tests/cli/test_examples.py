"""The notebooks in examples/ (jupytext percent scripts) execute headlessly and check their
own numbers (each asserts against a closed form or a published value).

Each notebook runs in this process, in a namespace of its own (``runpy.run_path`` as
``__main__``, matplotlib's Agg backend, a fresh working folder): a failed assert of the notebook
fails its test.  The first notebook also runs in a fresh interpreter, the way a reader runs it:
that checks that its own imports are enough (in this process the toolkit's modules are already
imported) and costs the interpreter's start-up once instead of six times.
"""

import os
import runpy
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

#: the categories Python's default warning filters never show
_HIDDEN = (PendingDeprecationWarning, ImportWarning, ResourceWarning)

EXAMPLES = sorted((Path(__file__).resolve().parent.parent.parent / "examples").glob("[0-9][0-9]_*.py"))


def test_the_six_notebooks_are_there():
    assert [p.stem[:2] for p in EXAMPLES] == ["01", "02", "03", "04", "05", "06"]


@pytest.mark.parametrize("script", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs_headless(script, tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    monkeypatch.chdir(tmp_path)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            runpy.run_path(str(script), run_name="__main__")
    finally:
        plt.close("all")
    # a notebook shows its reader no warning (each would be printed under a cell); what Python's
    # default filters hide is left out: deprecations raised inside libraries rather than by the
    # notebook's own lines, and pending-deprecation, import and resource warnings
    shown = [w for w in caught if not issubclass(w.category, _HIDDEN)
             and not (issubclass(w.category, DeprecationWarning) and w.filename != str(script))]
    assert not shown, [f"{w.category.__name__}: {w.message}" for w in shown]


def test_the_first_example_runs_in_a_fresh_interpreter(tmp_path):
    env = {**os.environ, "MPLBACKEND": "Agg"}
    proc = subprocess.run([sys.executable, str(EXAMPLES[0])], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
