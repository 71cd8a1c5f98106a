"""Deprecated path: ``landau.general`` is :mod:`landau.derivation.general` since the package was split into one
sub-package per pipeline stage; this alias warns and will be removed in the next release."""

import sys
import warnings

from landau.derivation import general as _moved

warnings.warn("landau.general is deprecated and will be removed in the next release; "
              "import landau.derivation.general", DeprecationWarning, stacklevel=2)
# the import system hands the importer what sys.modules holds under this name: the moved module itself
sys.modules[__name__] = _moved
