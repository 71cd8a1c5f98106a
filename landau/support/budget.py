"""Bounded symbolic work: run a computation in a child process that is abandoned at a deadline.

sympy cannot be interrupted from another thread, and some of its routines (``solve`` on a
transcendental equation, ``simplify`` of a long expression) can run for hours and grow to
gigabytes.  :func:`run_bounded` runs such a call in a forked child with a time limit and an
address-space limit, returns its (pickled) result, and kills the child when the limit is
reached.  Where ``fork`` is not available the call runs in-process, unbounded.
"""

from __future__ import annotations

import multiprocessing
import os
import pickle
from typing import Any, Callable

from landau.errors import BudgetError

#: address-space limit of the child process (bytes)
MEMORY_LIMIT = 4 * 1024 ** 3


def _child(conn, fn, args, memory) -> None:  # pragma: no cover - runs in the child
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
    proc = ctx.Process(target=_child, args=(send, fn, args, memory), daemon=True)
    proc.start()
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
    if not ok:
        if isinstance(result, MemoryError):
            raise BudgetError(f"{what} ran out of memory" + (f"; {hint}" if hint else ""))
        raise result
    return result
