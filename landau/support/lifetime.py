"""Worker processes that die with their parent, and SIGTERM handled as an interrupt.

Two guarantees for the processes a long computation starts (the sweep's local pool):

* **No orphans.**  A pool worker is an ordinary child process: if its parent is killed
  (``SIGKILL``, the out-of-memory killer) nobody tells it, and it keeps its memory and waits
  forever for work on a queue whose other end it holds itself (forked, it inherited both ends).
  :func:`die_with_parent`, run as the pool's initializer, makes each worker end when the parent
  does: on Linux with ``prctl(PR_SET_PDEATHSIG, SIGKILL)`` (the kernel sends the signal the moment
  the parent's thread that started the worker ends; the worker then re-checks ``os.getppid()``
  since the parent may have died before the call), elsewhere (or where prctl is refused) with a
  daemon thread that polls ``os.getppid()`` every :data:`POLL_S` seconds and ends the process when
  it changes (the worker is re-parented to init or a sub-reaper).
* **SIGTERM is Ctrl-C.**  :func:`terminate_as_interrupt` turns ``SIGTERM`` (``kill PID``, a batch
  scheduler's time limit, ``docker stop``) into :class:`Terminated`, a :class:`KeyboardInterrupt`,
  for the duration of a ``with`` block: the code in between then unwinds as after Ctrl-C (its
  ``finally`` clauses write what is done and remove temporary files) instead of the process
  vanishing mid-write.  Only the main thread can receive Python signal handlers, and a handler
  someone else installed (a notebook, a dask worker) is kept: the block then changes nothing.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
from typing import Iterator

#: seconds between two checks of the parent in the portable fallback of :func:`die_with_parent`
POLL_S = 0.5
#: ``PR_SET_PDEATHSIG`` of <linux/prctl.h>
_PR_SET_PDEATHSIG = 1


class Terminated(KeyboardInterrupt):
    """The process received SIGTERM inside :func:`terminate_as_interrupt` (unwinds as Ctrl-C does)."""


def _kernel_death_signal() -> bool:
    """Ask Linux to SIGKILL this process when its parent ends; whether the kernel accepted."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        return libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0) == 0
    except (OSError, AttributeError, ValueError):
        return False


def _watch_parent(parent: int) -> None:
    stop = threading.Event()
    while not stop.wait(POLL_S):
        if os.getppid() != parent:
            os._exit(1)   # the parent is gone: nobody is left to take the results


def die_with_parent(parent: int) -> None:
    """End this process when the process ``parent`` ends (a pool initializer; see the module docstring).

    Parameters
    ----------
    parent : int
        The parent's pid as the parent saw it (``os.getpid()`` there), to detect a parent that
        died before this call.
    """
    # a worker ends with SIGTERM plainly: the parent's Terminated handler (inherited on fork) is not its own
    if threading.current_thread() is threading.main_thread():
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if not _kernel_death_signal():
        threading.Thread(target=_watch_parent, args=(parent,), name="landau-parent-watch", daemon=True).start()
    if os.getppid() != parent:  # the parent died before the kernel (or the thread) was watching
        os._exit(1)


def _raise_terminated(signum, frame) -> None:
    raise Terminated(f"terminated by signal {signum}")


@contextlib.contextmanager
def terminate_as_interrupt() -> Iterator[bool]:
    """SIGTERM raises :class:`Terminated` inside the block (see the module docstring); yields whether
    the handler was installed (False off the main thread or where another handler was set)."""
    if threading.current_thread() is not threading.main_thread():
        yield False
        return
    try:
        previous = signal.getsignal(signal.SIGTERM)
    except (ValueError, OSError):
        yield False
        return
    if previous not in (signal.SIG_DFL, None):
        yield False
        return
    signal.signal(signal.SIGTERM, _raise_terminated)
    try:
        yield True
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
