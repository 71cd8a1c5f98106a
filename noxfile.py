"""Development sessions: ``pip install nox`` then ``nox -s <session>`` (``nox -l`` lists them).

* ``tests`` — the default test selection (not ``slow``, not ``fuzz``) on each supported Python.
* ``numba_min`` — the integrator tests against the oldest numba the project declares
  (the lower bound of ``numba>=X,<Y`` in pyproject.toml, read from there), so the declared
  range is a tested one at both ends (the newest release inside it is what ``tests`` installs).
* ``lint`` — ruff and mypy with the configuration in pyproject.toml (mypy on an installed copy).
* ``docs`` — ``mkdocs build --strict``.
* ``bench`` — ``benchmarks/run.py --quick`` followed by ``benchmarks/report.py``.

Each session uses a landau cache folder of its own, inside its virtualenv.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import nox

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent
PYTHONS = ["3.10", "3.11", "3.12"]
nox.options.sessions = ["tests", "lint"]

#: the tests that compile and run the integrators, steppers and compiled loops: what a change
#: of numba (code generation, first-class functions, caching) can break
INTEGRATOR_TESTS = "radau or springblock or skurativskyi or steppers or hybrid or dop853 or jitcache or compile"


def _dependency(name: str) -> str:
    """The requirement string of ``name`` in pyproject's ``[project] dependencies``."""
    deps = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["dependencies"]
    for dep in deps:
        if re.match(rf"{re.escape(name)}\b", dep):
            return dep
    raise RuntimeError(f"{name} is not a dependency in pyproject.toml")


def numba_lower_bound() -> str:
    """X of ``numba>=X,<Y`` in pyproject.toml."""
    m = re.search(r">=\s*([0-9][0-9.]*)", _dependency("numba"))
    if m is None:
        raise RuntimeError("pyproject.toml gives numba no lower bound (numba>=X,<Y)")
    return m.group(1)


def _private_caches(session: nox.Session) -> dict[str, str]:
    """A landau cache of the session's own.  numba's cache stays where numba puts it by default
    (``__pycache__`` beside the sources; numba rewrites an entry written by another numba
    version): tests/test_jitcache.py looks for the cache files there."""
    return {"LANDAU_CACHE_DIR": str(Path(session.virtualenv.location) / "landau-cache")}


@nox.session(python=PYTHONS)
def tests(session: nox.Session) -> None:
    session.install("-e", ".[test]")
    session.run("pytest", "tests", "-x", "-q", *session.posargs, env=_private_caches(session))


@nox.session(python="3.11")
def numba_min(session: nox.Session) -> None:
    low = numba_lower_bound()
    session.install("-e", ".[test]")
    # pip picks the numpy and llvmlite that this numba accepts (numba pins both); pandas (a test
    # dependency, imported when the suite is collected) from 2.3 on needs numpy >= 2, which the
    # oldest numba does not accept, so the newest pandas that runs on numpy 1.x is taken with it
    session.install(f"numba=={low}", "pandas<2.3")
    session.run("python", "-c", "import numba, numpy, llvmlite; print('numba', numba.__version__, 'numpy', "
                "numpy.__version__, 'llvmlite', llvmlite.__version__)")
    session.run("pytest", "tests", "-x", "-q", "-k", INTEGRATOR_TESTS, *session.posargs,
                env=_private_caches(session))


@nox.session(python="3.11")
def lint(session: nox.Session) -> None:
    session.install(".", "ruff", "mypy")
    session.run("ruff", "check", ".")
    # mypy cannot follow the folder mapping of the install (laws/ -> landau.laws, verify/ ->
    # landau.verify, ...): it checks an installed copy of the package, as CI's import-linter step does
    copy = Path(session.create_tmp()) / "installed"
    session.run("python", "-m", "pip", "install", "-q", "--no-deps", "--upgrade", "--target", str(copy), ".")
    session.chdir(copy)
    session.run("mypy", "--config-file", str(ROOT / "pyproject.toml"), "-p", "landau", *session.posargs)


@nox.session(python="3.11")
def docs(session: nox.Session) -> None:
    session.install("-e", ".[docs]")
    session.run("python", "benchmarks/report.py", "--check")
    session.run("mkdocs", "build", "--strict")


@nox.session(python="3.11")
def bench(session: nox.Session) -> None:
    session.install("-e", ".[bench]")
    session.run("python", "benchmarks/run.py", "--quick", *session.posargs)
    session.run("python", "benchmarks/report.py")
