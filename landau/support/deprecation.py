"""Former public names kept for one release: a module ``__getattr__`` (PEP 562) that warns.

A module whose public name changed keeps the old one importable with

    __getattr__ = former_names(__name__, {"Run": (lambda: RadauRecord, "use RadauRecord (...)")})

``from module import Run`` and ``module.Run`` then return the new object with a
:class:`DeprecationWarning` that names the replacement; any other unknown name raises
:class:`AttributeError` as usual.  One mechanism, so every renamed name warns alike.
"""

from __future__ import annotations

import warnings
from typing import Callable, Mapping


def former_names(module: str, names: Mapping[str, tuple[Callable[[], object], str]]) -> Callable[[str], object]:
    """The module ``__getattr__`` that serves the former ``names`` of ``module`` with a warning.

    Parameters
    ----------
    module : str
        The module's ``__name__``.
    names : mapping of str to (callable, str)
        Former name → (a function of no arguments returning the object it now stands for, imported
        on use where the import must wait; the advice after "is deprecated: ").

    Returns
    -------
    callable
        ``__getattr__(name)`` for the module namespace.
    """

    def __getattr__(name: str) -> object:
        if name in names:
            get, advice = names[name]
            warnings.warn(f"{module}.{name} is deprecated: {advice}", DeprecationWarning, stacklevel=2)
            return get()
        raise AttributeError(f"module {module!r} has no attribute {name!r}")

    return __getattr__


__all__ = ["former_names"]
