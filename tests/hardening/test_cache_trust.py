"""What the cache trusts and why (landau.support.cachedir, landau.support.cachecodec,
landau.support.cache): a per-user key kept outside the cache, entries signed under it, folders that
must be the user's own, a data format that executes nothing, versions in every key."""

import os
import stat
import warnings

import pytest
import sympy as sp

from landau.support import cache, cachecodec, cachedir


@pytest.fixture()
def root(tmp_path, monkeypatch):
    monkeypatch.setenv("LANDAU_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("XDG_CONFIG_HOME", str(tmp_path / "config"))
    monkeypatch.delenv("LANDAU_CACHE_KEY", raising=False)
    monkeypatch.delenv("LANDAU_CACHE", raising=False)
    cache.set_enabled(None)
    return tmp_path / "cache"


def _mode(path):
    return stat.S_IMODE(os.stat(path).st_mode)


def test_folders_and_key_are_private(root, tmp_path):
    cache.put("test", cache.make_key("test", "a"), {"x": 1})
    assert _mode(root) == 0o700 and _mode(root / "test") == 0o700
    key = tmp_path / "config" / "landau" / "cache.key"
    assert key.stat().st_size == cachedir.KEY_BYTES and _mode(key) == 0o600 and _mode(key.parent) == 0o700
    assert not any(p.name == "cache.key" for p in root.rglob("*"))      # the key is not in the cache


def test_an_entry_signed_under_another_key_is_rebuilt(root, monkeypatch):
    """A cache copied from elsewhere (a CI cache restored from another branch, another user's
    folder): its entries carry HMACs under a key this user does not hold."""
    calls = []
    build = lambda: calls.append(1) or sp.Symbol("V", positive=True) ** 2     # noqa: E731
    key = cache.make_key("test", "restored")
    monkeypatch.setenv("LANDAU_CACHE_KEY", "ab" * 32)
    cache.cached("test", key, build)
    assert cache.cached("test", key, build) == sp.Symbol("V", positive=True) ** 2 and len(calls) == 1
    monkeypatch.setenv("LANDAU_CACHE_KEY", "cd" * 32)
    assert cache.cached("test", key, build) == sp.Symbol("V", positive=True) ** 2 and len(calls) == 2


def test_an_edited_entry_is_rebuilt(root):
    key = cache.make_key("test", "edited")
    cache.put("test", key, {"Lambda": sp.Integer(-3)})
    (path,) = (root / "test").glob("*.json")
    path.write_bytes(path.read_bytes().replace(b"Integer(-3)", b"Integer(3)"))    # the sign of Λ
    assert cache.get("test", key) is None and not path.exists()


def test_a_key_file_others_may_read_is_refused(root, tmp_path):
    keyfile = tmp_path / "config" / "landau" / "cache.key"
    keyfile.parent.mkdir(parents=True, mode=0o700)
    keyfile.write_bytes(b"k" * cachedir.KEY_BYTES)
    os.chmod(keyfile, 0o644)
    with pytest.warns(cachedir.CacheWarning, match="cache key"):
        cache.put("test", cache.make_key("test", "b"), 1)
    assert cache.get("test", cache.make_key("test", "b")) is None
    assert not (root / "test").exists()                                  # bypassed: nothing written


def test_a_malformed_key_in_the_environment_is_refused(root, monkeypatch):
    monkeypatch.setenv("LANDAU_CACHE_KEY", "not hex")
    with pytest.warns(cachedir.CacheWarning, match="LANDAU_CACHE_KEY"):
        assert cachedir.cache_key() is None


def test_a_file_in_place_of_the_root_is_refused_once(tmp_path, monkeypatch, root):
    monkeypatch.setenv("LANDAU_CACHE_DIR", str(tmp_path / "file"))
    (tmp_path / "file").write_text("not a folder")
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        for _ in range(3):
            cache.put("test", cache.make_key("test", "c"), 1)
            assert cache.get("test", cache.make_key("test", "c")) is None
    assert len([w for w in seen if issubclass(w.category, cachedir.CacheWarning)]) == 1


def test_versions_are_part_of_every_key(monkeypatch):
    import importlib.metadata as md

    first = cache._version()
    real = md.version
    monkeypatch.setattr(cache, "_FINGERPRINT", None)
    monkeypatch.setattr(md, "version", lambda name: "0.0.1" if name == "sympy" else real(name))
    assert cache._version() != first
    monkeypatch.setattr(cache, "_FINGERPRINT", None)
    monkeypatch.setattr(md, "version", lambda name: "0.0.1" if name == "numba" else real(name))
    assert cache._version() != first


# --- the data format ---------------------------------------------------------------------------
V, a = sp.Symbol("V", positive=True), sp.Symbol("a", real=True)


@pytest.mark.parametrize("value", [
    {"kc": a * sp.log(V / 3) ** 2, "W": (V + sp.Rational(-1, 7)) / (a - sp.pi)},
    (sp.exp(-V) * sp.Float("0.1", 40), {a: sp.sqrt(V), V: sp.Integer(10) ** 40}),
    [None, True, 2, 2.5, float("inf"), "x", sp.Piecewise((V, V < 1), (sp.oo, True)), sp.zoo, -sp.oo],
    sp.Dummy("d") * sp.Abs(a) + sp.sign(a) * sp.tanh(V) - sp.Heaviside(a - 1),
])
def test_values_read_back_as_they_were(value):
    back = cachecodec.loads(cachecodec.dumps(value))
    assert back == value and type(back) is type(value)
    if isinstance(value, dict) and "kc" in value:      # assumptions survive
        assert back["kc"].free_symbols == {a, V} and next(iter(back["W"].atoms(sp.Symbol) - {a})).is_positive


def test_shared_subexpressions_are_written_once():
    e = V
    for _ in range(300):               # 2**300 tree nodes, 600 distinct ones
        e = sp.Add(e, e * a, evaluate=False)
    assert len(cachecodec.dumps(e)) < 40_000


def _same_dag(x, y, seen=None) -> bool:
    """Structural equality of two expressions that visits each pair of distinct nodes once
    (``==`` walks the tree form, 2**40 nodes below)."""
    seen = set() if seen is None else seen
    if x is y or (id(x), id(y)) in seen:
        return True
    seen.add((id(x), id(y)))
    if not x.args or not y.args:
        return x == y
    return (type(x) is type(y) and len(x.args) == len(y.args)
            and all(_same_dag(p, q, seen) for p, q in zip(x.args, y.args, strict=True)))


def test_reading_back_never_compares_formulas_by_structure(monkeypatch):
    """A formula read back in a process that already holds an equal copy (a derivation, then a
    command that reads its entry) is rebuilt without one structural comparison with that copy.
    sympy's constructor cache compares a new call's arguments with an earlier call's by ``==``,
    which for a DAG walks the tree form: before the fix this read-back stopped at the budget
    below (the unbounded walk over 2**40 nodes would never end); the second of two
    ``landau derive … --codim2`` commands for the atan state law in one process took 6.6 CPU-s
    instead of 0.21."""
    from sympy.core.cache import clear_cache

    x = sp.Symbol("x", positive=True)
    e = x
    for _ in range(40):                               # 2**40 tree nodes, 120 distinct ones
        e = (e + 1) * (e + 2)
    data = cachecodec.dumps(e)
    clear_cache()
    sp.Mul(*e.args)               # the top call of the derivation, as sympy's cache keeps it
    calls = 0
    structural_eq = sp.Basic.__eq__

    class Budget(Exception):
        pass

    def counting_eq(self, other):
        nonlocal calls
        calls += 1
        if calls > 10_000:
            raise Budget
        return structural_eq(self, other)

    monkeypatch.setattr(sp.Basic, "__eq__", counting_eq)
    back = cachecodec.loads(data)
    again = cachecodec.loads(data)
    monkeypatch.undo()
    assert calls < 100
    assert back is not e and _same_dag(back, e) and hash(back) == hash(e)
    assert again is back                              # equal nodes read back are one object


@pytest.mark.parametrize("atom", [
    "__import__('os').system('true')", "Symbol('x').__class__", "Symbol(*['x'])", "Symbol('x', **{})",
    "Function('f')", "eval('1')", "Integer(1) + Integer(2)", "Symbol('x', _assumptions=1)", "(lambda: 0)()"])
def test_an_atom_outside_the_whitelist_is_refused(atom):
    with pytest.raises(cachecodec.Undecodable):
        cachecodec.parse_atom(atom)


@pytest.mark.parametrize("doc", [
    '{"format":"landau-cache-json/1","nodes":[["Function",[]]],"value":{"sympy":0}}',          # a class not allowed
    '{"format":"landau-cache-json/1","nodes":[["Add",[1]],["atom","Integer(1)"]],"value":{"sympy":0}}',  # forward
    '{"format":"landau-cache-json/1","nodes":[],"value":{"sympy":0}}',
    '{"format":"landau-cache-json/1","nodes":[],"value":{"dict":[[{"list":[]},1]]}}',          # unhashable key
    '{"format":"other","nodes":[],"value":1}', "\x80\x04K\x01.", "",
])
def test_a_malformed_entry_is_refused(doc):
    with pytest.raises(cachecodec.Undecodable):
        cachecodec.loads(doc.encode("latin-1"))


def test_a_value_the_format_cannot_hold_is_not_cached(root):
    import numpy as np

    key = cache.make_key("test", "array")
    cache.put("test", key, np.arange(3))
    assert cache.get("test", key) is None
    assert cache.cached("test", key, lambda: np.arange(3)).tolist() == [0, 1, 2]


def test_signatures_nobody_used_for_a_month_are_pruned(root):
    import time

    from landau.verify import jitcache

    sigdir = root / "jit" / "signatures"
    sigdir.mkdir(parents=True, mode=0o700)
    os.chmod(root, 0o700)
    os.chmod(root / "jit", 0o700)
    stale, recent = sigdir / ("a" * 64), sigdir / ("b" * 64)
    for f, age_days in ((stale, jitcache.SIGNATURE_DAYS + 1), (recent, jitcache.SIGNATURE_DAYS - 1)):
        f.touch()
        t = time.time() - age_days * 86400
        os.utime(f, (t, t))
    assert jitcache._signature_dir() == sigdir
    assert not stale.exists() and recent.exists()
