"""Progress on a terminal, silence in --json mode and off a terminal (landau.support.progress)."""

import io
import json
import sys

import pytest

from landau.cli import main
from landau.support.progress import set_quiet


class _Terminal(io.StringIO):
    """A stand-in for an interactive stderr: ``landau.support.progress.shown`` asks ``sys.stderr.isatty()``."""

    def isatty(self) -> bool:
        return True


def _fake_terminal(monkeypatch) -> _Terminal:
    """Point sys.stderr at a fake terminal.  Called inside the test body: pytest's capture fixtures
    re-install their own sys.stderr between fixture set-up and the test call."""
    tty = _Terminal()
    monkeypatch.setattr(sys, "stderr", tty)
    monkeypatch.delenv("LANDAU_PROGRESS", raising=False)
    return tty


@pytest.fixture(autouse=True)
def _loud_again():
    yield
    set_quiet(False)   # --json silences the process; later tests start from the default


# Ruina law at V = 1e-5 m/s, eps2 = 1e-3: outside the range of validity (the predicted cycle would
# reverse the slip), so the point is decided from the prediction alone — cheap, no simulation.
VERIFY = ["verify", "ruina", "--V", "1e-5", "--eps2", "1e-3"]


def test_verify_shows_progress_on_a_terminal(monkeypatch, capsys):
    fake_terminal = _fake_terminal(monkeypatch)
    assert main(VERIFY) == 1   # outside validity: not an agreement
    err = fake_terminal.getvalue()
    assert "verify ruina" in err and "point" in err
    assert "outside-validity" in capsys.readouterr().out


def test_verify_json_writes_nothing_to_stderr(monkeypatch, capsys):
    fake_terminal = _fake_terminal(monkeypatch)
    assert main(VERIFY + ["--json"]) == 1
    assert fake_terminal.getvalue() == ""
    doc = json.loads(capsys.readouterr().out)
    assert [p["verdict"] for p in doc["points"]] == ["outside-validity"]


def test_verify_off_a_terminal_is_silent(monkeypatch, capsys):
    monkeypatch.delenv("LANDAU_PROGRESS", raising=False)
    assert main(VERIFY) == 1
    assert capsys.readouterr().err == ""


def test_closed_form_shows_a_status_line_on_a_terminal(monkeypatch):
    fake_terminal = _fake_terminal(monkeypatch)
    from landau import derive

    d = derive("dieterich", ["kc", "omega_c", "Gamma_bar"])
    d.coefficient("Gamma_bar").closed_form()
    assert "closed form of Gamma_bar" in fake_terminal.getvalue()


def test_simulate_shows_a_status_line_on_a_terminal_and_none_with_json(monkeypatch, capsys, tmp_path):
    fake_terminal = _fake_terminal(monkeypatch)
    argv = ["simulate", "galvanetto-one-block", "--t-end", "6", "--out", str(tmp_path / "run.csv")]
    assert main(argv) == 0
    assert "simulate galvanetto-one-block" in fake_terminal.getvalue()
    capsys.readouterr()
    fake_terminal.truncate(0)
    fake_terminal.seek(0)
    assert main(argv + ["--json"]) == 0
    assert fake_terminal.getvalue() == ""
    assert json.loads(capsys.readouterr().out)["status"] == "finished"
