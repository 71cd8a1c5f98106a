"""Reproductions of internal errors and a wrong exit 0 reported by users: each is now one named line, exit 2.

Before: the impact oscillator with ``e = 1e-300`` ended in an internal OverflowError (exit 1); a
constant negative kinetic law ``--kinetic -1`` (friction pushing along the slip) simulated and exited
0; a load history starting at 1e-300 m/s ended in an internal ZeroDivisionError (exit 1)."""

from __future__ import annotations

import pytest

from landau.cli import main


@pytest.mark.parametrize("argv, needle", [
    (["hopf", "impact-oscillator", "--friction", "mu*tanh(v/e)", "--param", "mu=0.4", "--param", "e=1e-300"],
     "leaves the float64 range"),
    (["simulate", "galvanetto-one-block", "--kinetic", "-1", "--t-end", "5"], "must be > 0"),
    (["simulate", "galvanetto-two-blocks", "--kinetic", "1", "--kinetic-pos", "1", "--t-end", "5"], "must be < 0"),
    (["simulate", "spring-block", "dieterich", "--V-history", "1e-300@0,1e-5@10", "--t-end", "20"],
     "below 1e-20 m/s"),
])
def test_named_and_exit_2(argv, needle, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and needle in err[0] and "internal error" not in err[0], err


def test_a_plate_rate_history_still_runs(capsys, tmp_path, monkeypatch):
    """The bound is far below plate rates (~1e-9 m/s): a step from 1e-9 to 1e-8 m/s runs."""
    monkeypatch.chdir(tmp_path)
    assert main(["simulate", "spring-block", "dieterich", "--V-history", "1e-9@0,1e-8@100", "--t-end", "300"]) == 0
