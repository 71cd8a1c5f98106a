"""The ``landau`` command line: one module per sub-command, wired up by :mod:`landau.cli.app`.

Each sub-command module exposes ``configure(parser)``, ``run(args) -> dict`` (the JSON document)
and ``render(doc) -> str`` (the human table).  Importing this package imports nothing else, so
``landau --help`` stays cheap.
"""

from __future__ import annotations

from typing import Sequence


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line (see :func:`landau.cli.app.main`)."""
    from landau.cli.app import main as _main

    return _main(argv)
