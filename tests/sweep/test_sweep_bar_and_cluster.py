"""A sweep's surroundings: its progress bar in a notebook (the widget where ipywidgets is installed,
the text bar without tqdm's warning where not) and a ``--dask local:N`` cluster closed without
killing its workers (landau.support.progress, landau.cli.sweep)."""

from __future__ import annotations

import argparse
import json
import logging
import sys
import textwrap
import time

import pytest

# ---------------------------------------------------------------------------------------------
# the progress bar in a real notebook kernel
# ---------------------------------------------------------------------------------------------
FAKE_WIDGETS = textwrap.dedent('''
    """A stand-in for ipywidgets: the three widgets tqdm.notebook builds, holding what it sets."""
    import types

    __version__ = "8.1.0"


    class _Widget:
        def __init__(self, **kw):
            self.layout, self.style = types.SimpleNamespace(), types.SimpleNamespace()
            self.value, self.bar_style, self.children = 0, "", ()
            for k, v in kw.items():
                setattr(self, k, v)

        def close(self):
            pass


    FloatProgress = HTML = HBox = _Widget
''')

CELL = textwrap.dedent("""
    import os
    os.environ["LANDAU_PROGRESS"] = "on"
    from landau.support.progress import progress
    bar = progress(total=3, desc="sweep demo", unit="pt")
    bar.update(3)
    bar.close()
    print("mro", " ".join(c.__module__ for c in type(bar).__mro__))
""")


def _run_kernel(tmp_path, monkeypatch, with_widgets: bool) -> list[dict]:
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    spec = tmp_path / "jupyter" / "kernels" / "landau-bar"
    spec.mkdir(parents=True)
    env = {}
    if with_widgets:
        pkg = tmp_path / "fake" / "ipywidgets"
        pkg.mkdir(parents=True)
        (pkg / "__init__.py").write_text(FAKE_WIDGETS)
        env["PYTHONPATH"] = str(tmp_path / "fake")
    (spec / "kernel.json").write_text(json.dumps({
        "argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
        "display_name": "landau bar", "language": "python", "env": env}))
    monkeypatch.setenv("JUPYTER_PATH", str(tmp_path / "jupyter"))
    monkeypatch.chdir(tmp_path)
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(CELL)])
    nbclient.NotebookClient(nb, kernel_name="landau-bar", timeout=120).execute()
    return nb.cells[0].outputs


def _text(outputs: list[dict]) -> str:
    parts = []
    for out in outputs:
        parts.append(out.get("text", ""))
        parts.extend(str(v) for v in out.get("data", {}).values())
    return "\n".join(parts)


@pytest.mark.parametrize("with_widgets", [False, True])
def test_a_notebook_gets_its_bar_without_tqdms_warning(tmp_path, monkeypatch, with_widgets):
    if with_widgets is False:
        import importlib.util

        if importlib.util.find_spec("ipywidgets") is not None:
            pytest.skip("ipywidgets is installed: the kernel would find it")
    text = _text(_run_kernel(tmp_path, monkeypatch, with_widgets))
    mro = next(line for line in text.splitlines() if line.startswith("mro "))
    # tqdm's own warnings: "IProgress not found" (no ipywidgets), the experimental autonotebook one
    assert "IProgress" not in text and "Warning" not in text, text
    if with_widgets:
        assert "tqdm.notebook" in mro.split()   # the widget
    else:
        assert "tqdm.notebook" not in mro.split() and "tqdm.std" in mro.split()
        assert "sweep demo:" in text and "| 0/3 " in text   # the text bar (cleared when closed: leave=False)


# ---------------------------------------------------------------------------------------------
# --dask local:N
# ---------------------------------------------------------------------------------------------
def _slow_exit() -> None:
    """In a dask worker: an exit handler of 5 s (more than the 4 s its nanny waits by default), as
    numba's cache signing can take on a loaded machine."""
    import atexit

    atexit.register(time.sleep, 5.0)


def test_a_local_cluster_is_closed_without_killing_its_workers():
    pytest.importorskip("distributed")
    from landau.cli.sweep import _executor

    records: list[logging.LogRecord] = []

    class Keep(logging.Handler):
        def emit(self, record):
            records.append(record)

    handler = Keep(level=logging.WARNING)
    loggers = [logging.getLogger(n) for n in ("distributed", "distributed.nanny", "distributed.worker",
                                               "distributed.scheduler", "distributed.core")]
    for lg in loggers:
        lg.addHandler(handler)
    try:
        executor, close = _executor(argparse.Namespace(dask="local:2", workers=None))
        client = executor._client
        pids = client.run(lambda: __import__("os").getpid())
        client.run(_slow_exit)
        start = time.monotonic()
        close()
        took = time.monotonic() - start
    finally:
        for lg in loggers:
            lg.removeHandler(handler)
    messages = [r.getMessage() for r in records]
    assert not any("still alive" in m or "killing" in m for m in messages), messages
    assert len(pids) == 2
    # the workers ran their 5 s exit handler to the end instead of being killed after 4 s
    assert took >= 5.0, took
