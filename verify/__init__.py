"""verify: the non-smooth models simulated, and the checks of the amplitude equation by simulation.

Imported before any of its compiled modules: numba's cache of them in ``$NUMBA_CACHE_DIR`` is made
private and verified first (:func:`landau.verify.compiling.secure_numba_cache`)."""

from landau.verify.compiling import secure_numba_cache as _secure_numba_cache

_secure_numba_cache()
