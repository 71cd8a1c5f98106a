"""Test-suite settings shared by every test module."""

import json
import os
import resource
import secrets
import shutil
import tempfile

import pytest


def pytest_configure(config):
    # The suite never reads or writes the user's disk cache.  By default it keeps one cache of its
    # own for the session, in a fresh temporary folder signed with a fresh key: the first test that
    # derives a law derives it (so every derivation the suite checks is computed in this run, from
    # an empty cache), and later tests and the commands they run in child processes read that
    # entry, verified, as a user's second command does.  LANDAU_TEST_CACHE=off derives in every
    # test instead (the cache switched off, as before).
    if os.environ.get("LANDAU_TEST_CACHE", "session").strip().lower() == "off":
        os.environ["LANDAU_CACHE"] = "off"
        return
    root = tempfile.mkdtemp(prefix="landau-test-cache-")
    config.add_cleanup(lambda: shutil.rmtree(root, ignore_errors=True))
    os.environ["LANDAU_CACHE"] = "on"
    os.environ["LANDAU_CACHE_DIR"] = root
    os.environ["LANDAU_CACHE_KEY"] = secrets.token_hex(32)


@pytest.fixture
def cache_off(monkeypatch):
    """The disk cache switched off for one test (and the commands it runs in child processes):
    for tests of what a derivation itself builds, which a cache hit would skip."""
    from landau.support import cache

    monkeypatch.setenv("LANDAU_CACHE", "off")
    cache.set_enabled(None)
    yield
    monkeypatch.undo()
    cache.set_enabled(None)


# --- CPU profile of the suite -------------------------------------------------------------------
# LANDAU_TEST_CPU_REPORT=path writes, at the end of the session, a JSON document with the user+sys
# CPU seconds of every test (setup, call and teardown, this process and the subprocesses it waited
# for), so that the suite's cost can be reported as CPU time, which a loaded machine does not
# inflate as it inflates wall-clock durations.

_CPU_REPORT = os.environ.get("LANDAU_TEST_CPU_REPORT")
_cpu_by_test: dict[str, float] = {}


def _cpu_now() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


if _CPU_REPORT:

    @pytest.hookimpl(hookwrapper=True)
    def pytest_runtest_protocol(item, nextitem):
        start = _cpu_now()
        yield
        _cpu_by_test[item.nodeid] = _cpu_by_test.get(item.nodeid, 0.0) + _cpu_now() - start

    def pytest_sessionfinish(session, exitstatus):
        by_file: dict[str, float] = {}
        for nodeid, cpu in _cpu_by_test.items():
            path = nodeid.split("::", 1)[0]
            by_file[path] = by_file.get(path, 0.0) + cpu
        report = {
            "total_cpu_s": _cpu_now(),
            "tests_cpu_s": sum(_cpu_by_test.values()),
            "n_tests": len(_cpu_by_test),
            "by_file": dict(sorted(by_file.items(), key=lambda kv: -kv[1])),
            "by_test": dict(sorted(_cpu_by_test.items(), key=lambda kv: -kv[1])),
        }
        with open(_CPU_REPORT, "w", encoding="utf-8") as handle:
            json.dump(report, handle, indent=1)


# --- assertion count of the selection -----------------------------------------------------------
# LANDAU_TEST_ASSERT_REPORT=path writes, after collection, the assertions the selected tests make:
# ``assert`` statements and calls of pytest.approx / pytest.raises / pytest.warns / numpy.testing
# in each test function and in the module-level helpers it calls (followed by name, transitively,
# within its module). ``sites`` counts each such line once; ``per_item`` counts them once per
# collected test (a parametrised test once per case). Compare two selections with these figures
# when tests are moved behind ``slow`` or merged: neither may shrink.

_ASSERT_REPORT = os.environ.get("LANDAU_TEST_ASSERT_REPORT")

if _ASSERT_REPORT:
    import ast
    import inspect

    _CHECK_CALLS = ("approx", "raises", "warns", "deprecated_call")

    def _is_check(node) -> bool:
        if isinstance(node, ast.Assert):
            return True
        if not isinstance(node, ast.Call):
            return False
        func = node.func
        name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")
        text = ast.unparse(func)
        return name in _CHECK_CALLS or name.startswith("assert_") or ".testing." in f".{text}"

    _module_index: dict[str, tuple[dict, str]] = {}

    def _functions_of(path: str):
        if path not in _module_index:
            tree = ast.parse(open(path, encoding="utf-8").read(), path)
            defs = {}
            for node in ast.walk(tree):
                if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    defs.setdefault(node.name, node)
            _module_index[path] = (defs, path)
        return _module_index[path][0]

    def _sites(path: str, name: str) -> set:
        defs = _functions_of(path)
        seen, todo, sites = set(), [name], set()
        while todo:
            fname = todo.pop()
            if fname in seen or fname not in defs:
                continue
            seen.add(fname)
            for node in ast.walk(defs[fname]):
                if _is_check(node):
                    sites.add((path, node.lineno, node.col_offset))
                if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
                    todo.append(node.func.id)
        return sites

    def pytest_collection_finish(session):
        all_sites: set = set()
        per_item = 0
        by_file: dict[str, int] = {}
        for item in session.items:
            function = getattr(item, "function", None)
            if function is None:
                continue
            try:
                path = inspect.getsourcefile(function)
            except TypeError:
                continue
            sites = _sites(path, function.__name__)
            all_sites |= sites
            per_item += len(sites)
            rel = os.path.relpath(path)
            by_file[rel] = by_file.get(rel, 0) + len(sites)
        report = {"n_tests": len(session.items), "sites": len(all_sites), "per_item": per_item,
                  "by_file": dict(sorted(by_file.items()))}
        with open(_ASSERT_REPORT, "w", encoding="utf-8") as handle:
            json.dump(report, handle, indent=1)
