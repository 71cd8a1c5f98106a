"""Bounded symbolic work: run a computation in a child process that is abandoned at a deadline.

sympy cannot be interrupted from another thread, and some of its routines (``solve`` on a
transcendental equation, ``simplify`` of a long expression) can run for hours and grow to
gigabytes.  :func:`run_bounded` runs such a call in a forked child with a time limit and an
address-space limit, returns its (pickled) result, and kills the child when the limit is
reached.  Where ``fork`` is not available the call runs in-process, unbounded.

The child never outlives its parent, whatever ends the parent (an exception, SIGTERM, SIGKILL):

* on Linux it asks the kernel for SIGKILL when its parent dies (``prctl(PR_SET_PDEATHSIG)``);
* everywhere, a watchdog thread in the child waits on a pipe whose only writer is the parent
  (end of file: the parent is gone) and checks the parent's process id every
  :data:`WATCH_PERIOD` seconds, and kills the child when either says the parent died;
* the child has its own deadline (``SIGALRM`` a little after the parent's, default action:
  termination), which ends it even inside a C routine that holds the interpreter lock.
"""

from __future__ import annotations

import math
import multiprocessing
import os
import pickle
import signal
import sys
import threading
from typing import Any, Callable

from landau.errors import BudgetError

#: address-space limit of the child process (bytes)
MEMORY_LIMIT = 4 * 1024 ** 3
#: how often (s) the child's watchdog checks that its parent is alive
WATCH_PERIOD = 0.5
#: seconds the child's own deadline lies past the parent's (the parent normally kills it first)
DEADLINE_GRACE = 5

_PR_SET_PDEATHSIG = 1


def _die_with_parent(parent: int) -> None:  # pragma: no cover - runs in the child
    """Linux: SIGKILL this process when the parent thread dies (prctl(2), PR_SET_PDEATHSIG);
    nothing elsewhere.  The parent may have died before the call: checked after it."""
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
        except (OSError, AttributeError, ValueError):
            pass
    if os.getppid() != parent:
        os._exit(1)


def _watchdog(parent: int, alive_fd: int) -> None:  # pragma: no cover - runs in the child
    """Kill this process when ``alive_fd`` (the read end of a pipe only the parent writes to)
    reaches end of file, or when the parent process id changes (re-parented: the parent died)."""
    import select

    while True:
        try:
            ready, _, _ = select.select([alive_fd], [], [], WATCH_PERIOD)
            gone = bool(ready) and os.read(alive_fd, 1) == b""
        except (OSError, ValueError):
            gone = True
        if gone or os.getppid() != parent:
            os.kill(os.getpid(), signal.SIGKILL)


def _child(conn, fn, args, memory, parent, alive, seconds) -> None:  # pragma: no cover - runs in the child
    alive_r, alive_w = alive
    os.close(alive_w)                       # the parent must be the pipe's only writer
    _die_with_parent(parent)
    threading.Thread(target=_watchdog, args=(parent, alive_r), daemon=True).start()
    if hasattr(signal, "alarm"):
        signal.signal(signal.SIGALRM, signal.SIG_DFL)
        signal.alarm(max(1, math.ceil(seconds)) + DEADLINE_GRACE)
    try:
        import resource

        if memory:
            soft, hard = resource.getrlimit(resource.RLIMIT_AS)
            limit = memory if hard == resource.RLIM_INFINITY else min(memory, hard)
            resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    except (ImportError, ValueError, OSError):
        pass
    try:
        result = fn(*args)
        payload = pickle.dumps((True, result))
    except BaseException as exc:  # noqa: BLE001 - every outcome goes back to the parent
        try:
            payload = pickle.dumps((False, exc))
        except Exception:  # noqa: BLE001
            payload = pickle.dumps((False, RuntimeError(f"{type(exc).__name__}: {exc}")))
    try:
        conn.send_bytes(payload)
    finally:
        conn.close()
        os._exit(0)


def fork_available() -> bool:
    return "fork" in multiprocessing.get_all_start_methods()


def run_bounded(fn: Callable[..., Any], args: tuple = (), *, seconds: float, what: str,
                hint: str = "", memory: int | None = MEMORY_LIMIT) -> Any:
    """``fn(*args)`` with at most ``seconds`` of wall time (and ``memory`` bytes of address space).

    The child process ends with the parent (see the module docstring): no computation outlives
    the command that asked for it.

    Parameters
    ----------
    fn, args : the call; ``fn``, its arguments and its result must be picklable (sympy
        expressions are).
    seconds : the time budget.
    what : what is being computed, for the error message.
    hint : what the user can do instead, appended to the error message.
    memory : address-space limit of the child in bytes (None: no limit).

    Returns
    -------
    The result of ``fn(*args)``; an exception raised by ``fn`` is re-raised.

    Raises
    ------
    BudgetError
        The call did not finish within ``seconds`` or ran out of memory.
    """
    if not fork_available():  # pragma: no cover - e.g. Windows
        return fn(*args)
    ctx = multiprocessing.get_context("fork")
    recv, send = ctx.Pipe(duplex=False)
    alive = os.pipe()
    proc = ctx.Process(target=_child, args=(send, fn, args, memory, os.getpid(), alive, seconds), daemon=True)
    try:
        proc.start()
    finally:
        os.close(alive[0])                  # the parent keeps only the write end, open until the child ends
        send.close()
    try:
        if not recv.poll(seconds):
            raise BudgetError(f"{what} did not finish within {seconds:g} s" + (f"; {hint}" if hint else ""))
        try:
            ok, result = pickle.loads(recv.recv_bytes())
        except (EOFError, OSError):
            raise BudgetError(f"{what} ran out of memory or crashed" + (f"; {hint}" if hint else "")) from None
    finally:
        if proc.is_alive():
            proc.kill()
        proc.join()
        recv.close()
        os.close(alive[1])
    if not ok:
        if isinstance(result, MemoryError):
            raise BudgetError(f"{what} ran out of memory" + (f"; {hint}" if hint else ""))
        raise result
    return result
