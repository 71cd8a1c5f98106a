"""Deprecated path: ``landau.lyapunov`` is :mod:`landau.derivation.lyapunov` since the package was split into one
sub-package per pipeline stage; this alias warns and will be removed in the next release."""

import sys
import warnings

from landau.derivation import lyapunov as _moved

warnings.warn("landau.lyapunov is deprecated and will be removed in the next release; "
              "import landau.derivation.lyapunov", DeprecationWarning, stacklevel=2)
# the import system hands the importer what sys.modules holds under this name: the moved module itself
sys.modules[__name__] = _moved
