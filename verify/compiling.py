"""Compile a numba function on first use, and say so on the terminal when that takes a while.

Nothing in landau compiles at import: a compiled loop is built the first time a call needs it,
for the one signature that call uses, and numba's disk cache (``cache=True``) keeps the machine
code for every later process.  The first build on a fresh machine (or a fresh CI runner) can
take several seconds; :func:`compile_once` prints one line on standard error while it does, so
a user is never left in front of a silent terminal.  A build loaded from the disk cache is
quick and prints nothing (the line appears only after :data:`NOTICE_AFTER` seconds).

Which folders to keep between CI runs so that the build happens once: the landau cache root
(``$LANDAU_CACHE_DIR``, else the per-user cache folder, see :mod:`landau.support.cachedir`) and numba's
cache (``$NUMBA_CACHE_DIR`` when set, else the ``__pycache__`` folders of the installed package).

This module imports numba only when a function is compiled.
"""

from __future__ import annotations

import os
import sys
import threading
from typing import Any

__all__ = ["NOTICE_AFTER", "compile_once"]

#: seconds a first build may take before the terminal line is printed
NOTICE_AFTER = 0.5
#: set to "0" to silence the line (e.g. in a notebook that shows its own progress)
ENV_NOTICE = "LANDAU_COMPILE_NOTICE"


def _notice(what: str) -> None:
    print(f"landau: compiling {what} (once for this machine; cached afterwards)...",
          file=sys.stderr, flush=True)


def compile_once(dispatcher: Any, signature: Any, what: str) -> Any:
    """Make sure ``dispatcher`` holds machine code for ``signature``; say so if building takes time.

    Parameters
    ----------
    dispatcher : numba dispatcher
        A function decorated with ``numba.njit(cache=True)`` and *no* explicit signature (so
        importing its module compiles nothing).
    signature : numba signature or tuple of numba types
        The argument types of the call about to be made.
    what : str
        What is being compiled, for the terminal line (e.g. ``"the Radau IIA integrator"``).

    Returns
    -------
    numba dispatcher
        ``dispatcher``, now compiled (or loaded from numba's disk cache) for ``signature``.
    """
    args = tuple(signature.args) if hasattr(signature, "args") else tuple(signature)
    overloads = getattr(dispatcher, "overloads", None)
    if overloads is None or args in overloads:      # NUMBA_DISABLE_JIT=1: a Python function
        return dispatcher
    timer = None
    if os.environ.get(ENV_NOTICE, "1") != "0":
        timer = threading.Timer(NOTICE_AFTER, _notice, args=(what,))
        timer.daemon = True
        timer.start()
    try:
        dispatcher.compile(args)
    finally:
        if timer is not None:
            timer.cancel()
    return dispatcher
