"""The derivation cache's key includes a fingerprint of the code that derives: every module it
names must exist, else an edit of a moved module would be served stale entries."""

from pathlib import Path

import landau
from landau.support import cache


def test_every_deriving_module_of_the_fingerprint_exists():
    package = Path(landau.__file__).resolve().parent
    missing = [name for name in cache.DERIVING_MODULES if not (package / name).is_file()]
    assert missing == []


def test_the_fingerprint_changes_with_the_deriving_code(tmp_path, monkeypatch):
    first = cache._version()
    monkeypatch.setattr(cache, "_FINGERPRINT", None)
    monkeypatch.setattr(cache, "DERIVING_MODULES", cache.DERIVING_MODULES[:-1])
    assert cache._version() != first
