"""In a notebook every plotting call shows exactly one image.

A notebook is built here from cells and executed by a real kernel (nbclient, ipykernel, the
inline matplotlib backend, as in Jupyter); each cell's outputs are counted.  The convention
behind it is stated in :mod:`landau.report.plotting`: a figure made by the toolkit shows once
whether the call ends the cell or is assigned, and once more when displayed in a later cell.
"""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")

EXAMPLE_01 = Path(__file__).resolve().parents[2] / "examples" / "01_your_law_in_five_minutes.py"


def _percent_cells(path: Path) -> list[str]:
    """The code cells of a jupytext percent-format script."""
    parts = re.split(r"^# %%.*$", path.read_text(encoding="utf-8"), flags=re.M)
    heads = re.findall(r"^# %%.*$", path.read_text(encoding="utf-8"), flags=re.M)
    return [body.strip() for head, body in zip(heads, parts[1:], strict=True) if "[markdown]" not in head]


def _images(cell) -> int:
    return sum("image/png" in out.get("data", {}) for out in cell.outputs)


def _texts(cell) -> list[str]:
    return [out.get("data", {}).get("text/plain", "") for out in cell.outputs if "image/png" not in out.get("data", {})]


@pytest.fixture
def kernel(tmp_path, monkeypatch):
    """A kernel spec of this interpreter with the inline backend, whatever else is installed."""
    spec = tmp_path / "jupyter" / "kernels" / "landau-test"
    spec.mkdir(parents=True)
    (spec / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "landau test", "language": "python",
        "env": {"MPLBACKEND": "module://matplotlib_inline.backend_inline"}}))
    monkeypatch.setenv("JUPYTER_PATH", str(tmp_path / "jupyter"))
    monkeypatch.chdir(tmp_path)
    return "landau-test"


def test_each_plotting_call_shows_one_image(kernel):
    example = _percent_cells(EXAMPLE_01)
    setup_law = next(c for c in example if "FrictionLaw.from_strings(" in c)
    setup_derive = next(c for c in example if c.startswith("d = derive("))
    last_plot = example[-1]
    assert ".plot(" in last_plot
    cells = [
        # (source, images expected)
        ("import numpy as np\nimport landau\nfrom landau import SpringBlock, derive\n"
         "from landau.laws import FrictionLaw", 0),
        (setup_law, 0),
        (setup_derive, 0),
        ("d.plot((1e-6, 1e-3), n=30)", 1),                               # the cell's value
        ("fig = d.plot((1e-6, 1e-3), n=30)", 1),                         # assigned: the backend shows it
        ("fig", 1),                                                      # shown again when asked again
        ("d.evaluate(np.logspace(-6, -3, 20)).plot()", 1),
        ("landau.plotting.plot_check([1e-3, 4e-4, 1.6e-4], [1.0, 0.632, 0.4], [0.981, 0.6244, 0.3970])", 1),
        ("r = landau.plotting.plot_check([1e-3, 4e-4], [1.0, 0.632], [0.981, 0.6244])\nprint('drawn')", 1),
        (last_plot, 1),                                                  # examples/01, its last plot cell
    ]
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(src) for src, _ in cells])
    nbclient.NotebookClient(nb, timeout=600, kernel_name=kernel, allow_errors=False).execute()
    for cell, (src, want) in zip(nb.cells, cells, strict=True):
        got = _images(cell)
        assert got == want, f"cell {src!r} showed {got} image(s), expected {want}: {cell.outputs!r}"[:2000]
        # no figure shows as text instead of an image
        assert not any(t.startswith("<Figure") for t in _texts(cell)), src
