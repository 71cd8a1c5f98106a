"""Scenes: named, reproducible computations declared as data.

A scene names a model, its default parameters, the one quantity it computes and — for
a published fact — the published number and its source.  ``compute`` receives the full
parameter dict (defaults updated by the user's overrides) and returns either a float or
a dict with a ``"value"`` key plus any extra fields worth reporting.  A scene computes
only what its output needs: ``compute`` is called lazily, only by :func:`run_scene`.

Scene modules register themselves on import; they are declared as entry points of the
``landau.scenes`` group (landau's own in its ``pyproject.toml``; a plug-in package adds its own
the same way), loaded on the first use of the registry.
"""

from __future__ import annotations

import fnmatch
import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

from landau.errors import InputError, LandauError

#: the entry-point group of the modules that register scenes
GROUP = "landau.scenes"

_REGISTRY: dict[str, "Scene"] = {}
_loaded = False


@dataclass(frozen=True)
class Scene:
    """A named computation with its provenance.

    ``tolerance`` is the relative difference to the published value that still counts
    as agreement (it reflects the digits the paper prints).  A difference the project has
    traced to its cause is declared with ``explained``: the value the toolkit is known to give
    (``known_value``, within the relative ``known_tolerance``) and where the reason is written
    down.  Such a run is reported as "explained" (not "DISAGREES") and does not fail; a value
    that leaves the explained one still does.
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
    #: a documented discrepancy with the published value: why, and where it is written down
    explained: str = ""
    #: the value the toolkit is known to give where ``explained`` is set (at the defaults)
    known_value: float | None = None
    #: relative tolerance on ``known_value`` (the computation's own accuracy)
    known_tolerance: float | None = None
    #: parameters that steer the computation (brackets, tolerances, step counts) without changing
    #: the model: overriding them keeps the comparison with the published value (None: the
    #: names in NUMERICAL_SETTINGS)
    settings: frozenset[str] | None = None

    @property
    def numerical_settings(self) -> frozenset[str]:
        """The defaults that are numerical settings rather than model parameters."""
        names = NUMERICAL_SETTINGS if self.settings is None else self.settings
        return frozenset(k for k in self.defaults if k in names)

    def run(self, **overrides: float) -> "SceneResult":
        """Compute the scene (see :func:`run_scene`)."""
        return run_scene(self.name, overrides)

    def as_dict(self) -> dict[str, Any]:
        return {"scene": self.name, "parameter": self.parameter, "units": self.units, "published": self.published,
                "source": self.source, "params": dict(self.defaults), "description": self.description}

    def _display_row(self) -> dict[str, Any]:
        return {"scene": self.name, "parameter": self.parameter, "units": self.units,
                "published": self.published, "source": self.source}

    def __repr__(self) -> str:
        pub = "" if self.published is None else f", published={self.published:g}"
        return f"Scene({self.name!r}, {self.parameter} [{self.units}]{pub}, source={self.source!r})"

    def _repr_html_(self) -> str:
        from landau.report.display import html_record

        return html_record(f"Scene {self.name}", {**self._display_row(), "description": self.description,
                                                  **{f"param {k}": v for k, v in self.defaults.items()}})


#: default names of numerical settings (search brackets, tolerances, step counts)
NUMERICAL_SETTINGS = frozenset({"lo", "hi", "tol", "rtol", "atol", "n_steps", "orbit_omega", "gone_omega"})


def verdict(doc: Mapping[str, Any]) -> str:
    """One word for a scene result: "agrees", "explained" (a documented discrepancy, at the
    value the explanation gives), "DISAGREES", "not comparable" (parameters moved off those of
    the published value), "no tolerance" or "no published value"."""
    if doc.get("error"):
        return "ERROR"
    if doc.get("published") is None:
        return "no published value"
    if not doc.get("comparable", True):
        return "not comparable"
    if doc.get("agrees") is None:
        return "no tolerance"
    if doc["agrees"]:
        return "agrees"
    return "explained" if doc.get("explained") else "DISAGREES"


def failed(doc: Mapping[str, Any]) -> bool:
    """Whether a scene result fails a run (exit code 1 on the command line): an error, or a
    disagreement at the published parameters that no documented explanation accounts for."""
    return bool(doc.get("error")) or (verdict(doc) == "DISAGREES" and bool(doc.get("at_defaults")))


class SceneResult(dict):
    """The JSON-ready document of one scene run (a ``dict``) with a readable display."""

    def _display_row(self) -> dict[str, Any]:
        """The row of a summary table (:func:`run_scenes`, ``landau scene run --all``)."""
        return {"scene": self["scene"], "parameter": self["parameter"], "value": self.get("value"),
                "units": self["units"], "published": self.get("published"), "rel. diff.": self.get("rel_diff"),
                "verdict": verdict(self), "s": self.get("seconds")}

    def __repr__(self) -> str:
        if self.get("error"):
            return f"SceneResult({self['scene']}: {self['error']})"
        pub = "" if self.get("published") is None else f", published {self['published']:.10g}"
        return (f"SceneResult({self['scene']}: {self['parameter']} = {self['value']:.10g} {self['units']}"
                f"{pub}; {verdict(self)})")

    def _repr_html_(self) -> str:
        from landau.report.display import html_record

        return html_record(f"Scene {self['scene']}: {verdict(self)}",
                           {k: v for k, v in self.items() if k not in ("scene", "params")},
                           note="parameters: " + ", ".join(f"{k} = {v:g}" for k, v in self.get("params", {}).items()))


def register(scene: Scene) -> Scene:
    if scene.name in _REGISTRY:
        raise ValueError(f"scene {scene.name!r} registered twice")
    _REGISTRY[scene.name] = scene
    return scene


def _load() -> None:
    global _loaded
    if _loaded:
        return
    from importlib.metadata import entry_points

    eps = list(entry_points(group=GROUP))
    if not eps:
        raise InputError("no scenes are installed: the package's entry points are missing (reinstall it: "
                         "pip install -e . in the source tree)")
    for ep in eps:
        ep.load()   # the module registers its scenes
    _loaded = True


def all_scenes() -> list[Scene]:
    """Every registered scene in name order (a list that displays as one table)."""
    from landau.report.display import ResultList

    _load()
    return ResultList([_REGISTRY[k] for k in sorted(_REGISTRY)], title="Scenes")


def get_scene(name: str) -> Scene:
    _load()
    try:
        return _REGISTRY[name]
    except KeyError:
        raise InputError(f"unknown scene {name!r} (see 'landau scene list')") from None


def select_scenes(patterns: Sequence[str]) -> list[Scene]:
    """The scenes whose names match any of the shell-style ``patterns`` (``putelat2010/*``),
    in name order; an :class:`InputError` names a pattern that matches nothing."""
    scenes = all_scenes()
    chosen: list[Scene] = []
    for pat in patterns:
        hits = [s for s in scenes if fnmatch.fnmatchcase(s.name, pat)]
        if not hits:
            raise InputError(f"no scene matches {pat!r} (see 'landau scene list')")
        chosen += [s for s in hits if s not in chosen]
    return sorted(chosen, key=lambda s: s.name)


def run_scenes(patterns: Sequence[str] | None = None, overrides: Mapping[str, float] | None = None):
    """Run several scenes; returns a list of :class:`SceneResult` that displays as one table.

    Parameters
    ----------
    patterns : sequence of str, optional
        Scene names or shell-style patterns (``"putelat2010/*"``); None runs every scene.
    overrides : mapping, optional
        Parameter overrides, applied to each scene that has the parameter (an
        :class:`InputError` if none has it).

    Returns
    -------
    landau.report.display.ResultList
        One :class:`SceneResult` per scene, in name order; a scene whose computation fails
        with a toolkit error is reported with an ``"error"`` field instead of stopping the run.
    """
    from landau.errors import LandauError
    from landau.report.display import ResultList

    scenes = all_scenes() if patterns is None else select_scenes(patterns)
    overrides = dict(overrides or {})
    for key in overrides:
        if not any(key in s.defaults for s in scenes):
            raise InputError(f"--param {key}: none of the selected scenes has this parameter")
    results = ResultList(title="Scenes")
    for s in scenes:
        try:
            results.append(run_scene(s.name, {k: v for k, v in overrides.items() if k in s.defaults}))
        except LandauError as exc:
            results.append(SceneResult(scene=s.name, parameter=s.parameter, units=s.units, published=s.published,
                                       source=s.source, error=f"{type(exc).__name__}: {str(exc).splitlines()[0]}"))
    return results


def run_scene(name: str, overrides: Mapping[str, float] | None = None) -> SceneResult:
    """Run one scene; returns the JSON-ready document.

    The published value belongs to the scene's default model parameters.  When an override
    moves a model parameter (anything but a numerical setting such as a search bracket or a
    tolerance), the document says ``comparable: false`` and ``agrees`` is None: the relative
    difference to a value published for other parameters is reported, not judged."""
    scene = get_scene(name)
    params = dict(scene.defaults)
    for key, val in (overrides or {}).items():
        if key not in params:
            known = ", ".join(sorted(params)) or "none"
            raise InputError(f"scene {name!r} has no parameter {key!r} (known: {known})")
        params[key] = float(val)
    t0 = time.perf_counter()
    try:
        out = scene.compute(params)
    except (ArithmeticError, ValueError) as exc:
        if isinstance(exc, LandauError):
            raise
        # a formula of the scene undefined at the parameters given (M = 0 in sqrt(a σ L / M), a < 0 under a root)
        moved = ", ".join(f"{k} = {params[k]:g}" for k in sorted(overrides or {}))
        raise InputError(f"scene {name!r} is undefined for {moved or 'its parameters'} ({type(exc).__name__}: "
                         f"{exc}): give values in the scene's physical range") from None
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
    moved = sorted(k for k, v in scene.defaults.items()
                   if k not in scene.numerical_settings and float(params[k]) != float(v))
    if scene.published is not None:
        rel = abs(value - scene.published) / abs(scene.published)
        doc["rel_diff"] = rel
        doc["comparable"] = not moved
        if moved:
            doc["agrees"] = None
            doc["note"] = ("published value is for " + ", ".join(f"{k} = {scene.defaults[k]:g}" for k in moved)
                           + "; these parameters differ, so it is shown for reference only")
        elif scene.tolerance is not None:
            doc["agrees"] = bool(rel <= scene.tolerance)
            doc["tolerance"] = scene.tolerance
            if not doc["agrees"] and scene.explained and scene.known_value is not None:
                off = abs(value - scene.known_value) / abs(scene.known_value)
                doc["explained"] = bool(off <= (scene.known_tolerance or 0.0))
                doc["known_value"] = float(scene.known_value)
                doc["explanation"] = (scene.explained if doc["explained"] else
                                      f"the value left the explained one ({scene.known_value:.10g}, relative "
                                      f"difference {off:.2e} > {scene.known_tolerance:g}): {scene.explained}")
    doc.update(extra)
    doc["seconds"] = elapsed
    return SceneResult(doc)
