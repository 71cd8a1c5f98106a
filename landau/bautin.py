"""Deprecated path: ``landau.bautin`` is :mod:`landau.analyses.bautin` since the package was split into one
sub-package per pipeline stage; this alias warns and will be removed in the next release."""

import sys
import warnings

from landau.analyses import bautin as _moved

warnings.warn("landau.bautin is deprecated and will be removed in the next release; "
              "import landau.analyses.bautin", DeprecationWarning, stacklevel=2)
# the import system hands the importer what sys.modules holds under this name: the moved module itself
sys.modules[__name__] = _moved
