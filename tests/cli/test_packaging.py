"""The install maps the repository's rooms under the one import namespace ``landau``."""

import pathlib

import tomllib

import landau

ROOT = pathlib.Path(__file__).resolve().parents[2]
ROOMS = {"landau": "landau", "laws": "landau.laws", "verify": "landau.verify", "paper_figures": "landau.paper_figures"}


def test_every_package_folder_is_listed_in_pyproject():
    """A folder with __init__.py that pyproject does not list would be missing from a wheel."""
    cfg = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    listed = set(cfg["packages"])
    found = set()
    for folder, name in ROOMS.items():
        for init in (ROOT / folder).rglob("__init__.py"):
            rel = init.parent.relative_to(ROOT / folder).parts
            found.add(".".join((name, *rel)))
    assert found == listed
    assert cfg["package-dir"] == {v: k for k, v in ROOMS.items()}


def test_version_is_the_distribution_version():
    from importlib.metadata import version

    assert landau.__version__ == version("landau-friction")
