"""A build that the address-space limit (ulimit -v) leaves no room for is refused by name: a cold
``landau simulate forced-oscillator`` under ``ulimit -v 900000`` ended in SIGABRT ("LLVM ERROR: Unable
to allocate section memory", exit 134) while compiling its integrator; it now exits 1 with a
BudgetError naming the limit, before LLVM starts."""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import textwrap

MB = 2**20


def _limit_to(extra: int) -> str:
    return textwrap.dedent(f"""
        import resource
        from landau.errors import BudgetError
        from landau.verify.compiling import _address_space_in_use, address_space_for_compiling
        used = _address_space_in_use()
        resource.setrlimit(resource.RLIMIT_AS, (used + {extra}, resource.getrlimit(resource.RLIMIT_AS)[1]))
        try:
            address_space_for_compiling("the probe")
        except BudgetError as exc:
            print(exc)
        else:
            print("room")
    """)


def test_the_guard_refuses_a_limit_without_room_and_passes_one_with_room():
    for extra, expected in ((64 * MB, "not enough address space to compile the probe"), (1024 * MB, "room")):
        out = subprocess.run([sys.executable, "-c", _limit_to(extra)], capture_output=True, text=True, timeout=120)
        assert out.returncode == 0, out.stderr
        assert out.stdout.startswith(expected), out.stdout


def _vm_at_the_build(tmp_path) -> int:
    """The process's address space where the integrator's build would start (a run stopped there)."""
    probe = textwrap.dedent("""
        import os, sys
        import landau.verify.compiling as compiling
        def stop(what):
            print(compiling._address_space_in_use()); sys.stdout.flush(); os._exit(0)
        compiling.address_space_for_compiling = stop
        from landau.cli import main
        main(["simulate", "forced-oscillator", "--json"])
    """)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba"), "LANDAU_CACHE_DIR": str(tmp_path / "landau")}
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=300, env=env)
    return int(out.stdout.split()[0])


def test_a_cold_forced_oscillator_under_a_tight_ulimit_is_refused_not_aborted(tmp_path):
    (tmp_path / "numba").mkdir(mode=0o700)
    limit = _vm_at_the_build(tmp_path) + 128 * MB      # room to run up to the build, not for the build

    def tight():
        resource.setrlimit(resource.RLIMIT_AS, (limit, resource.getrlimit(resource.RLIMIT_AS)[1]))

    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba"), "LANDAU_CACHE_DIR": str(tmp_path / "landau")}
    out = subprocess.run([sys.executable, "-m", "landau", "simulate", "forced-oscillator", "--json"],
                         capture_output=True, text=True, env=env, timeout=600, preexec_fn=tight)
    assert out.returncode == 1, (out.returncode, out.stderr[-400:])    # before: -6 (SIGABRT)
    assert "not enough address space to compile the forced-oscillator integrator" in out.stderr
    assert "LLVM ERROR" not in out.stderr
