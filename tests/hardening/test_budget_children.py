"""A budgeted child process (steady-state solve, ``--latex``) never outlives the command that
started it: SIGKILL or SIGTERM of the parent leaves no child alive 5 s later, and the child
ends at its own deadline even when the parent cannot kill it."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from landau.support import budget

pytestmark = pytest.mark.skipif(not budget.fork_available() or sys.platform == "win32",
                                reason="the budget runs in-process without fork")

PARENT = textwrap.dedent("""
    import os, sys, time
    from landau.support.budget import run_bounded

    def spin(path):
        with open(path, "w") as fh:
            fh.write(str(os.getpid()))
        while True:        # a computation that never ends (pure Python: holds the interpreter)
            sum(i * i for i in range(10_000))

    run_bounded(spin, (sys.argv[1],), seconds=600, what="spin")
""")


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    try:    # a zombie (ended, not yet reaped by init) counts as ended
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().split(")")[-1].split()[0] != "Z"
    except OSError:
        return True


def _start(tmp_path):
    path = tmp_path / "child.pid"
    proc = subprocess.Popen([sys.executable, "-c", PARENT, str(path)])
    for _ in range(600):
        if path.exists() and path.read_text():
            return proc, int(path.read_text())
        time.sleep(0.05)
    proc.kill()
    pytest.fail("the budgeted child did not start")


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM])
def test_child_dies_with_parent(tmp_path, sig):
    proc, child = _start(tmp_path)
    assert _alive(child)
    proc.send_signal(sig)
    proc.wait(10)
    deadline = time.monotonic() + 5
    while _alive(child) and time.monotonic() < deadline:
        time.sleep(0.1)
    try:
        assert not _alive(child), f"child {child} alive 5 s after its parent got {sig.name}"
    finally:
        if _alive(child):
            os.kill(child, signal.SIGKILL)


def test_watchdog_without_death_signal(tmp_path, monkeypatch):
    """The portable fallback alone (no PR_SET_PDEATHSIG): the watchdog pipe ends the child."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    path = tmp_path / "child.pid"
    code = "import landau.support.budget as b; b._PR_SET_PDEATHSIG = 0\n" + PARENT
    proc = subprocess.Popen([sys.executable, "-c", code, str(path)], env=env)
    for _ in range(600):
        if path.exists() and path.read_text():
            break
        time.sleep(0.05)
    child = int(path.read_text())
    proc.kill()
    proc.wait(10)
    deadline = time.monotonic() + 5
    while _alive(child) and time.monotonic() < deadline:
        time.sleep(0.1)
    try:
        assert not _alive(child)
    finally:
        if _alive(child):
            os.kill(child, signal.SIGKILL)


def test_budget_still_returns_and_times_out():
    assert budget.run_bounded(pow, (3, 4), seconds=30, what="pow") == 81
    with pytest.raises(budget.BudgetError, match="did not finish within 1 s"):
        budget.run_bounded(time.sleep, (30,), seconds=1, what="sleep")
