"""Scenes: named, reproducible computations declared as data.

A scene names a model, its default parameters, the one quantity it computes and — for
a published fact — the published number and its source.  ``compute`` receives the full
parameter dict (defaults updated by the user's overrides) and returns either a float or
a dict with a ``"value"`` key plus any extra fields worth reporting.  A scene computes
only what its output needs: ``compute`` is called lazily, only by :func:`run_scene`.

Scene modules register themselves on import; the modules are listed in
:data:`SCENE_MODULES` so that ``landau scene list`` imports nothing it does not need
until asked.
"""

from __future__ import annotations

import importlib
import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping

from landau.errors import InputError

#: Modules that register scenes (imported on first use of the registry).
SCENE_MODULES: list[str] = [
    "landau.scenes.putelat2010",
    "landau.verify.galvanetto.scenes",
    "landau.scenes.putelat2010_transitions",
    "landau.verify.lancioni.scenes",
    "landau.verify.skurativskyi.scenes",
]

_REGISTRY: dict[str, "Scene"] = {}
_loaded = False


@dataclass(frozen=True)
class Scene:
    """A named computation with its provenance.

    ``tolerance`` is the relative difference to the published value that still counts
    as agreement (it reflects the digits the paper prints).
    """

    name: str
    parameter: str
    units: str
    source: str
    compute: Callable[[dict[str, float]], Any]
    defaults: Mapping[str, float] = field(default_factory=dict)
    published: float | None = None
    tolerance: float | None = None
    description: str = ""

    def __repr__(self) -> str:
        pub = "" if self.published is None else f", published={self.published:g}"
        return f"Scene({self.name!r}, {self.parameter} [{self.units}]{pub}, source={self.source!r})"


def register(scene: Scene) -> Scene:
    if scene.name in _REGISTRY:
        raise ValueError(f"scene {scene.name!r} registered twice")
    _REGISTRY[scene.name] = scene
    return scene


def _load() -> None:
    global _loaded
    if _loaded:
        return
    for mod in SCENE_MODULES:
        importlib.import_module(mod)
    _loaded = True


def all_scenes() -> list[Scene]:
    _load()
    return [ _REGISTRY[k] for k in sorted(_REGISTRY) ]


def get_scene(name: str) -> Scene:
    _load()
    try:
        return _REGISTRY[name]
    except KeyError:
        raise InputError(f"unknown scene {name!r} (see 'landau scene list')") from None


def run_scene(name: str, overrides: Mapping[str, float] | None = None) -> dict[str, Any]:
    """Run one scene; returns the JSON-ready document."""
    scene = get_scene(name)
    params = dict(scene.defaults)
    for key, val in (overrides or {}).items():
        if key not in params:
            known = ", ".join(sorted(params)) or "none"
            raise InputError(f"scene {name!r} has no parameter {key!r} (known: {known})")
        params[key] = float(val)
    t0 = time.perf_counter()
    out = scene.compute(params)
    elapsed = time.perf_counter() - t0
    extra: dict[str, Any] = {}
    if isinstance(out, Mapping):
        extra = {k: v for k, v in out.items() if k != "value"}
        value = out["value"]
    else:
        value = out
    value = float(value)
    if not math.isfinite(value):
        raise InputError(f"scene {name!r} produced a non-finite value for these parameters")
    doc: dict[str, Any] = {
        "scene": scene.name,
        "parameter": scene.parameter,
        "value": value,
        "units": scene.units,
        "published": None if scene.published is None else float(scene.published),
        "source": scene.source,
        "params": {k: float(v) for k, v in params.items()},
        "at_defaults": all(float(params[k]) == float(v) for k, v in scene.defaults.items()),
    }
    if scene.published is not None:
        rel = abs(value - scene.published) / abs(scene.published)
        doc["rel_diff"] = rel
        if scene.tolerance is not None:
            doc["agrees"] = bool(rel <= scene.tolerance)
            doc["tolerance"] = scene.tolerance
    doc.update(extra)
    doc["seconds"] = elapsed
    return doc
