"""The module paths of the release before the split into one sub-package per stage still import, with a
DeprecationWarning naming the new path, and give the moved module itself (one object, not a copy)."""

from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

MOVED = {"landau.lyapunov": "landau.derivation.lyapunov", "landau.general": "landau.derivation.general",
         "landau.continuation": "landau.analyses.continuation", "landau.bautin": "landau.analyses.bautin",
         "landau.transition": "landau.analyses.transition"}


@pytest.mark.parametrize("old", sorted(MOVED))
def test_an_old_path_warns_and_is_the_moved_module(old):
    # in a fresh interpreter: the warning is raised on the first import only
    code = (f"import warnings; warnings.simplefilter('error', DeprecationWarning)\n"
            f"try:\n    import {old}\nexcept DeprecationWarning as w:\n    print(w)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == (f"{old} is deprecated and will be removed in the next release; "
                                  f"import {MOVED[old]}")
    with pytest.warns(DeprecationWarning, match=MOVED[old].replace(".", r"\.")):
        sys.modules.pop(old, None)
        mod = importlib.import_module(old)
    assert mod is importlib.import_module(MOVED[old])
