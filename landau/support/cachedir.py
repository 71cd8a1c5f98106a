"""Where landau keeps its disk caches: one rule, defined here only.

Every cache of the toolkit lives under one root folder:

* the root is ``$LANDAU_CACHE_DIR`` when that is set, else the per-user cache folder of landau
  (``platformdirs.user_cache_dir("landau")``, e.g. ``~/.cache/landau`` on Linux);
* derivations and closed forms (:mod:`landau.support.cache`) are kept in sub-folders of the root named
  by their kind;
* generated code (:mod:`landau.verify.jitcache`: kernels, lambdified
  formulas, and numba's cache of them) is kept in ``<root>/jit``; ``$LANDAU_JIT_DIR`` names
  that folder directly when ``LANDAU_CACHE_DIR`` is not set (an older setting, still accepted).

This module imports neither sympy nor numba: the simulation layer uses it too.
"""

from __future__ import annotations

import os
from pathlib import Path

#: the root of every landau cache
ENV_ROOT = "LANDAU_CACHE_DIR"
#: the generated-code folder alone (older setting; ``LANDAU_CACHE_DIR`` wins when both are set)
ENV_JIT = "LANDAU_JIT_DIR"


def cache_root() -> Path:
    """The root folder of every landau cache (not created here).

    Returns
    -------
    pathlib.Path
        ``$LANDAU_CACHE_DIR``, else ``platformdirs.user_cache_dir("landau")``.
    """
    env = os.environ.get(ENV_ROOT)
    if env:
        return Path(env)
    import platformdirs

    return Path(platformdirs.user_cache_dir("landau", appauthor=False))


def code_dir() -> Path:
    """The folder of generated code and numba's cache of it (not created here).

    Returns
    -------
    pathlib.Path
        ``$LANDAU_CACHE_DIR/jit``, else ``$LANDAU_JIT_DIR``, else ``jit`` in :func:`cache_root`.
    """
    if not os.environ.get(ENV_ROOT):
        jit = os.environ.get(ENV_JIT)
        if jit:
            return Path(jit)
    return cache_root() / "jit"
