"""The model registry: every mechanical model of landau, and of any installed plug-in, by name.

``landau.models.get("spring-block")`` returns the :class:`~landau.models.model.Model`; a typo is an
:class:`~landau.errors.InputError` that names the closest model.  Models are found through the
``landau.models`` entry-point group (:mod:`importlib.metadata`), so that a third-party package adds
one without touching landau, in its own ``pyproject.toml``::

    [project.entry-points."landau.models"]
    my-brake = "my_package.brake:MODEL"     # a landau.models.Model object

landau's own models are declared the same way (its ``pyproject.toml``).  An entry point is loaded
on the first :func:`get` of its name (or the first listing), so that looking up one model does not
import every other; this module is the one place that turns a name into a model — the command
line, the sweep, the simulation front door and the paper figures all ask it.

:func:`register` adds a model at run time (a notebook, a test); it takes precedence over an entry
point of the same name only with ``replace=True``.
"""

from __future__ import annotations

import difflib
from importlib.metadata import entry_points

from landau.errors import InputError
from landau.models.model import LawKind, Model, Option, Parameter, Setup

#: the entry-point group models are declared in
GROUP = "landau.models"

_LOADED: dict[str, Model] = {}
_RUNTIME: dict[str, Model] = {}


def _entry_points() -> dict:
    eps = {ep.name: ep for ep in entry_points(group=GROUP)}
    if not eps and not _RUNTIME:
        raise InputError("no landau models are installed: the package's entry points are missing (reinstall it: "
                         "pip install -e . in the source tree)")
    return eps


def names() -> tuple[str, ...]:
    """The names of every registered model (entry points and run-time registrations), sorted."""
    return tuple(sorted(set(_entry_points()) | set(_RUNTIME)))


def get(name: str) -> Model:
    """The model registered as ``name``.

    Raises
    ------
    InputError
        No model of that name (the message lists the known ones and the closest), or an entry
        point that does not give a :class:`Model`.
    """
    if not isinstance(name, str):
        raise InputError(f"a model is named by a string, got {type(name).__name__}")
    if name in _RUNTIME:
        return _RUNTIME[name]
    if name in _LOADED:
        return _LOADED[name]
    eps = _entry_points()
    if name not in eps:
        known = sorted(set(eps) | set(_RUNTIME))
        close = difflib.get_close_matches(name, known, n=1)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise InputError(f"unknown model {name!r} (known: {', '.join(known)}){hint}")
    model = eps[name].load()
    if not isinstance(model, Model):
        raise InputError(f"the entry point {name!r} of group {GROUP!r} ({eps[name].value}) gives a "
                         f"{type(model).__name__}, not a landau.models.Model")
    if model.name != name:
        raise InputError(f"the entry point {name!r} gives the model {model.name!r}: the names must agree")
    _LOADED[name] = model
    return model


def all_models() -> tuple[Model, ...]:
    """Every registered model (loads every entry point)."""
    return tuple(get(n) for n in names())


def offering(task: str) -> tuple[str, ...]:
    """The names of the models that run the sweep task ``task``."""
    return tuple(m.name for m in all_models() if m.offers(task))


def register(model: Model, *, replace: bool = False) -> Model:
    """Register ``model`` at run time (a notebook, a test); returns it.

    Raises
    ------
    InputError
        A name already registered (unless ``replace``).
    """
    if not isinstance(model, Model):
        raise InputError(f"register: expected a landau.models.Model, got {type(model).__name__}")
    if not replace and (model.name in _RUNTIME or model.name in {ep.name for ep in entry_points(group=GROUP)}):
        raise InputError(f"a model named {model.name!r} is already registered (register(..., replace=True) to "
                         "replace it)")
    _RUNTIME[model.name] = model
    return model


def unregister(name: str) -> None:
    """Remove a run-time registration (entry points stay)."""
    _RUNTIME.pop(name, None)


__all__ = ["GROUP", "LawKind", "Model", "Option", "Parameter", "Setup", "all_models", "get", "names", "offering",
           "register", "unregister"]
