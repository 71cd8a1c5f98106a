"""Deprecated path: ``landau.continuation`` is :mod:`landau.analyses.continuation` since the package was split into one
sub-package per pipeline stage; this alias warns and will be removed in the next release."""

import sys
import warnings

from landau.analyses import continuation as _moved

warnings.warn("landau.continuation is deprecated and will be removed in the next release; "
              "import landau.analyses.continuation", DeprecationWarning, stacklevel=2)
# the import system hands the importer what sys.modules holds under this name: the moved module itself
sys.modules[__name__] = _moved
