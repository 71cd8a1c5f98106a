"""The model registry: every model found through its entry point, looked up by name, and no model
reached by an import string outside the registry."""

from __future__ import annotations

import ast
from importlib.metadata import entry_points
from pathlib import Path

import pytest

import landau.models as models
from landau.errors import InputError

ROOT = Path(__file__).resolve().parents[2]
#: the rooms of the package (installed under landau)
SOURCES = ("landau", "laws", "verify", "paper_figures")
#: the one module allowed to turn names into code (the registry)
REGISTRY = {ROOT / "landau" / "models" / "__init__.py"}


def test_every_entry_point_gives_a_model_of_its_name():
    eps = {ep.name: ep for ep in entry_points(group=models.GROUP)}
    assert {"spring-block", "spring-block-chain", "system", "impact-oscillator", "galvanetto-one-block",
            "galvanetto-two-blocks", "forced-oscillator"} <= set(eps)
    for name in eps:
        m = models.get(name)
        assert isinstance(m, models.Model) and m.name == name
        assert m.parameters() or m.law_kind is models.LawKind.NONE   # a user system declares what it uses


def test_a_typo_names_the_closest_model():
    with pytest.raises(InputError, match="did you mean 'spring-block'"):
        models.get("spring-blok")


def test_a_runtime_model_is_found_and_a_name_is_not_taken_twice():
    m = models.Model("test-oscillator", "a test model", models.LawKind.NONE, lambda setup: ())
    models.register(m)
    try:
        assert models.get("test-oscillator") is m and "test-oscillator" in models.names()
        with pytest.raises(InputError, match="already registered"):
            models.register(m)
        with pytest.raises(InputError, match="already registered"):
            models.register(models.Model("spring-block", "", models.LawKind.NONE, lambda setup: ()))
    finally:
        models.unregister("test-oscillator")
    assert "test-oscillator" not in models.names()


def test_a_parameter_outside_its_domain_names_itself():
    p = models.get("spring-block").parameter("V")
    with pytest.raises(InputError, match=r"parameter 'V' \(driving \(load-point\) velocity\) must be > 0, got -1.0"):
        p.check(-1.0, "spring-block")
    assert p.check(1e-4) == 1e-4


def _string_imports(path: Path) -> list[str]:
    """The import strings in ``path``: ``import_module("landau...")`` and ``"landau.x.y:attr"`` constants."""
    import re

    tree = ast.parse(path.read_text(encoding="utf-8"))
    docstrings = {id(node.body[0].value) for node in ast.walk(tree)
                  if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
                  and node.body and isinstance(node.body[0], ast.Expr) and isinstance(node.body[0].value, ast.Constant)}
    hits = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and getattr(node.func, "attr", getattr(node.func, "id", "")) == "import_module":
            arg = node.args[0] if node.args else None
            if isinstance(arg, ast.Constant) and isinstance(arg.value, str) and arg.value.startswith("landau."):
                hits.append(f"{path.relative_to(ROOT)}:{node.lineno}: import_module({arg.value!r})")
        if (isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docstrings
                and re.fullmatch(r"landau(\.\w+)+:\w+", node.value)):
            hits.append(f"{path.relative_to(ROOT)}:{node.lineno}: {node.value!r}")
    return hits


def test_no_import_string_outside_the_registry():
    hits = [h for room in SOURCES for path in sorted((ROOT / room).rglob("*.py")) if path not in REGISTRY
            for h in _string_imports(path)]
    assert hits == [], "modules reached by an import string (declare an entry point instead):\n" + "\n".join(hits)


def test_the_string_check_can_fail(tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text('import importlib\nimportlib.import_module("landau.cli.hopf")\nREF = "landau.x.y:fn"\n')
    global ROOT
    old, ROOT = ROOT, tmp_path
    try:
        assert len(_string_imports(bad)) == 2
    finally:
        ROOT = old


def test_no_model_name_comparison_outside_the_models():
    """No ``== "spring-block"`` (or another model's name) in code: a model object answers instead."""
    import re

    names = "|".join(re.escape(n) for n in models.names())
    pattern = re.compile(rf"""[!=]=\s*["']({names})["']|["']({names})["']\s*[!=]=""")
    hits = [f"{path.relative_to(ROOT)}:{i}: {line.strip()}" for room in SOURCES
            for path in sorted((ROOT / room).rglob("*.py"))
            for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if pattern.search(line)]
    assert hits == [], "model-name comparisons:\n" + "\n".join(hits)
