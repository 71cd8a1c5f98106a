"""A repeated command answers from the store of finished answers, without sympy; an entry that does
not verify is reported once and recomputed (landau.support.answers)."""

from __future__ import annotations

import json
import logging
import os
import subprocess
import sys

import pytest

from landau.cli import app
from landau.support import answers, cache, cachedir

HOPF = ["hopf", "spring-block", "dieterich", "--V", "1e-4", "--json"]
LINEAR = ["linear", "dieterich", "--V", "1e-4", "--json"]

#: runs the command line in-process and says on stderr whether sympy or numba were imported
PROBE = ("import sys\nfrom landau.cli.app import main\nrc = main(sys.argv[1:])\n"
         "sys.stderr.write('\\nLOADED ' + ' '.join(m for m in ('sympy', 'numba') if m in sys.modules) + '\\n')\n"
         "sys.exit(rc)\n")


@pytest.fixture
def store(tmp_path, monkeypatch):
    """An empty cache of the test's own, on, under a key of the test's own."""
    monkeypatch.setenv("LANDAU_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("LANDAU_CACHE_KEY", "5a" * 32)
    monkeypatch.delenv("LANDAU_CACHE", raising=False)
    cache.set_enabled(None)
    return tmp_path / "cache" / answers.KIND


def _probe(argv, env):
    return subprocess.run([sys.executable, "-c", PROBE, *argv], capture_output=True, text=True, env=env, timeout=300)


def test_a_repeated_hopf_prints_the_same_bytes_without_sympy(store):
    env = dict(os.environ)
    first = _probe(HOPF, env)
    assert first.returncode == 0, first.stderr
    assert "sympy" in first.stderr.rsplit("LOADED", 1)[1]          # the first call derives
    again = _probe(HOPF, env)
    assert again.returncode == 0, again.stderr
    assert again.stdout == first.stdout                            # byte for byte
    assert again.stderr.rsplit("LOADED", 1)[1].split() == []      # neither sympy nor numba
    assert json.loads(again.stdout)["criticality"] == "subcritical"


def _run(argv, capsys) -> tuple[int, str]:
    code = app.main(list(argv))
    return code, capsys.readouterr().out


def _entry(store):
    entries = list(store.glob("*.json"))
    assert len(entries) == 1
    return entries[0]


def _warnings(caplog) -> list[str]:
    return [r.getMessage() for r in caplog.records if r.name == answers.__name__ and r.levelno == logging.WARNING]


def test_a_corrupted_entry_is_reported_once_and_recomputed(store, capsys, caplog):
    code, first = _run(LINEAR, capsys)
    assert code == 0
    path = _entry(store)
    data = bytearray(path.read_bytes())
    at = data.index(b'"output"') + 12
    data[at] ^= 0x01                                              # one bit of the answer's text flipped
    path.write_bytes(bytes(data))
    with caplog.at_level(logging.WARNING, logger=answers.__name__):
        code, again = _run(LINEAR, capsys)
        assert code == 0 and again == first                       # recomputed, not the altered text
        assert len(_warnings(caplog)) == 1 and str(path) in _warnings(caplog)[0]
        assert "signature does not verify" in _warnings(caplog)[0]
        assert answers.load(LINEAR[0], LINEAR) == (0, first)      # the rewritten entry verifies
        _run(LINEAR, capsys)
        assert len(_warnings(caplog)) == 1                        # reported once


def test_a_truncated_entry_is_recomputed(store, capsys, caplog):
    _, first = _run(LINEAR, capsys)
    path = _entry(store)
    path.write_bytes(path.read_bytes()[:40])
    with caplog.at_level(logging.WARNING, logger=answers.__name__):
        assert _run(LINEAR, capsys) == (0, first)
    assert len(_warnings(caplog)) == 1


def test_an_entry_signed_under_another_key_is_reported_and_recomputed(store, capsys, caplog, monkeypatch):
    _, first = _run(LINEAR, capsys)
    path = _entry(store)
    monkeypatch.setenv("LANDAU_CACHE_KEY", "c3" * 32)             # another user's key
    answers.store(LINEAR[0], LINEAR, 0, "k_c = 1 N/m\n")          # a planted answer, validly signed by them
    monkeypatch.setenv("LANDAU_CACHE_KEY", "5a" * 32)
    with caplog.at_level(logging.WARNING, logger=answers.__name__):
        assert _run(LINEAR, capsys) == (0, first)
    assert len(_warnings(caplog)) == 1 and "signature" in _warnings(caplog)[0]
    assert b"k_c = 1 N/m" not in path.read_bytes()


def test_an_entry_of_another_command_is_refused(store, capsys, caplog):
    """An entry copied over another one's name fails its signature (the name is signed); one
    signed for its own name but holding other arguments (a forged document) is refused too."""
    _, first = _run(LINEAR, capsys)
    path = _entry(store)
    other = [*LINEAR[:-1], "--param", "a=0.011", "--json"]
    answers.store(other[0], other, 0, "another answer\n")
    copied = next(p for p in store.glob("*.json") if p != path)
    path.write_bytes(copied.read_bytes())
    with caplog.at_level(logging.WARNING, logger=answers.__name__):
        assert answers.load(LINEAR[0], LINEAR) is None
        name = answers.key(LINEAR[0], LINEAR)
        body = json.dumps({"command": "linear", "argv": other, "fingerprint": answers.fingerprint(),
                           "exit_code": 0, "output": "forged\n"}).encode()
        mac = cachedir.sign(answers.MAGIC, answers.KIND, name, body)
        path.write_bytes(f"{answers.MAGIC} {mac}\n".encode() + body)
        assert answers.load(LINEAR[0], LINEAR) is None
    assert len(_warnings(caplog)) == 2 and "another command" in _warnings(caplog)[1]
    assert _run(LINEAR, capsys) == (0, first)


def test_what_is_not_stored(store, capsys, tmp_path, monkeypatch):
    """A refused input, a file-writing option (or its abbreviation) and the cache turned off
    leave no answer behind."""
    assert app.main(["linear", "dieterich", "--V", "-1", "--json"]) == 2
    assert not list(store.glob("*.json"))
    assert not app._answerable(["derive", "dieterich", "--lat", "x.tex"])
    assert not app._answerable(["linear", "dieterich", "--latex=x.tex"])
    assert app._answerable(["derive", "dieterich", "--V", "1e-4"])
    # a verification simulates every time: its verdict is evidence produced by the run
    assert not app._answerable(["verify", "dieterich", "--V", "1e-4"])
    assert not app._answerable(["simulate", "spring-block", "dieterich"])
    monkeypatch.setenv("LANDAU_CACHE", "off")
    assert _run(LINEAR, capsys)[0] == 0
    assert not list(store.glob("*.json"))
    capsys.readouterr()
