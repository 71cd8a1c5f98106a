"""The public API has numpydoc docstrings: Parameters (and Returns) sections the API reference renders."""

import enum
import importlib
import inspect
import re

import pytest

import landau
import landau.laws
from landau.analyses.checking import check
from landau.testing import assert_prediction


def _has_section(doc: str, title: str) -> bool:
    """A numpydoc section: the title on its own line, underlined with dashes."""
    return re.search(rf"^\s*{title}\s*\n\s*-{{3,}}\s*$", doc or "", re.MULTILINE) is not None


VERIFY_ENTRY_POINTS = (
    "landau.verify.springblock.checks.predict",
    "landau.verify.springblock.checks.supercritical_check",
    "landau.verify.springblock.checks.subcritical_check",
    "landau.verify.springblock.integrate",
    "landau.verify.hybrid.simulate",
    "landau.verify.galvanetto.model.one_block",
    "landau.verify.galvanetto.model.two_blocks",
    "landau.verify.galvanetto.model.build_model",
    "landau.verify.lancioni.model.build",
    "landau.verify.lancioni.slip.slip_hopf",
    "landau.verify.skurativskyi.simulate.run",
)


def _public_api():
    names = [(f"landau.{n}", getattr(landau, n)) for n in landau.__all__ if not n.startswith("_")]
    names += [(f"landau.laws.{n}", getattr(landau.laws, n)) for n in getattr(landau.laws, "__all__", ())]
    names += [("landau.analyses.checking.check", check), ("landau.testing.assert_prediction", assert_prediction)]
    # the simulation and check entry points of the API reference (docs/api/verify.md)
    for path in VERIFY_ENTRY_POINTS:
        module, _, attr = path.rpartition(".")
        names.append((path, getattr(importlib.import_module(module), attr)))
    out = []
    for qual, obj in names:
        if inspect.isclass(obj):
            # exceptions and enumerations are documented by their members, not constructor parameters
            if issubclass(obj, (BaseException, enum.Enum)):
                continue
            out.append((qual, obj))
        elif inspect.isfunction(obj):
            out.append((qual, obj))
    return out


API = _public_api()


def _arguments(func) -> list[str]:
    return [p for p in inspect.signature(func).parameters if p not in ("self", "cls")]


@pytest.mark.parametrize("qual, obj", API, ids=[q for q, _ in API])
def test_public_name_has_a_parameters_section(qual, obj):
    doc = inspect.getdoc(obj)
    assert _has_section(doc, "Parameters"), f"{qual}: no numpydoc 'Parameters' section"
    if inspect.isfunction(obj):
        assert _has_section(doc, "Returns"), f"{qual}: no numpydoc 'Returns' section"


@pytest.mark.parametrize("qual, cls", [(q, o) for q, o in API if inspect.isclass(o)],
                         ids=[q for q, o in API if inspect.isclass(o)])
def test_public_methods_document_arguments_and_result(qual, cls):
    missing = []
    for name, member in vars(cls).items():
        member = getattr(member, "__func__", member)   # classmethod / staticmethod
        if name.startswith("_") or not inspect.isfunction(member):
            continue
        doc = inspect.getdoc(member)
        if not _has_section(doc, "Returns") or (_arguments(member) and not _has_section(doc, "Parameters")):
            missing.append(name)
    assert not missing, f"{qual}: methods without Parameters/Returns sections: {missing}"


def test_the_walk_covers_the_front_door():
    # the walk above must not silently become empty (a renamed __all__, a filter too broad)
    quals = {q for q, _ in API}
    assert {"landau.derive", "landau.check", "landau.SpringBlock", "landau.Derivation",
            "landau.laws.get_law", "landau.laws.FrictionLaw", "landau.testing.assert_prediction"} <= quals
