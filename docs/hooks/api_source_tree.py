"""MkDocs hook: lay out the ``landau`` import namespace for the API reference.

The repository installs its top-level folders ``laws/``, ``verify/`` and ``paper_figures/``
as ``landau.laws``, ``landau.verify`` and ``landau.paper_figures`` (a setuptools
``package-dir`` mapping).  The API reference reads the sources statically (griffe) and
cannot follow that mapping, so this hook builds ``build/docs-src/landau`` — symbolic links
to the files of ``landau/`` plus the three mapped folders — and mkdocstrings reads from
there.  Nothing is imported and nothing is fetched.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TREE = ROOT / "build" / "docs-src"
MAPPED = {"laws": "laws", "verify": "verify", "paper_figures": "paper_figures"}


def build_tree() -> Path:
    """(Re)create the linked source tree and return its root."""
    pkg = TREE / "landau"
    if TREE.exists():
        shutil.rmtree(TREE)
    pkg.mkdir(parents=True)
    for entry in (ROOT / "landau").iterdir():
        if entry.name != "__pycache__":
            os.symlink(entry, pkg / entry.name)
    for name, folder in MAPPED.items():
        os.symlink(ROOT / folder, pkg / name)
    return TREE


build_tree()
