"""Direct simulation of the rate-and-state spring–block (Putelat et al. 2010, eq. 4/5) and checks of
the amplitude-equation engine against it.

* :mod:`.model` — eq. (4) in log variables, right-hand side and exact Jacobian generated from the
  symbolic law and compiled with numba; dimensional or dimensionless (m, κ) construction.
* :mod:`.radau` — compiled Radau IIA (order 5) integrator with dense output and section crossings.
* :mod:`.simulate` — :func:`integrate`, returning a :class:`RadauRecord` (the common ``Simulation``
  with the integrator's counters and located crossings; raises ``IntegratorError`` with time and
  state on failure) and ``record_run`` (bounded steps and memory, a named status at its limit).
* :mod:`.history` — the load point driven by a velocity history (velocity steps, slide-hold-slide).
* :mod:`.units` — the units of a law's states by dimensional analysis.
* :mod:`.orbits` — shooting on the Poincaré section, monodromy, Floquet multipliers, Hopf points.
* :mod:`.checks` — supercritical / subcritical prediction checks (``landau verify``).
* :mod:`.continuation` — pseudo-arclength continuation, folds of cycles, codimension-two points.
* :mod:`.workprecision`, :mod:`.benchmark`, :mod:`.reproductions` — Fig. 3 work–precision, speed,
  Figs 6/11/12.
"""

from landau.support.deprecation import former_names
from landau.verify.springblock.model import SpringBlockModel
from landau.verify.springblock.simulate import RadauRecord, integrate

__all__ = ["SpringBlockModel", "RadauRecord", "integrate"]


# the former name of the record, kept for one release
_RENAMED = {"Run": (lambda: RadauRecord,
                "use RadauRecord (the record of one Radau IIA integration, a Simulation)")}
__getattr__ = former_names(__name__, _RENAMED)
