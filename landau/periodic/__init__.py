"""Periodic orbits of any smooth system: continuation of cycles, Floquet multipliers and the
bifurcations of cycles (fold, period doubling, Neimark–Sacker).

The input is a :class:`~landau.periodic.problem.CycleProblem` (a vector field with its Jacobian,
one continuation parameter, and optionally the Hopf point the branch starts from); models build
one through their ``cycles`` declaration (:class:`landau.models.Model`), and
:func:`landau.cycles` is the front door by model name.
"""

from landau.periodic.branch import CycleBranch, EndReason, SpecialPoint
from landau.periodic.continuation import FixedCycle, continue_cycles, cycle_at
from landau.periodic.defect import Defect, periodicity_defect
from landau.periodic.problem import CycleProblem, CycleStart, HopfStart
from landau.periodic.switching import Cascade, follow_cascade

__all__ = ["CycleProblem", "HopfStart", "CycleStart", "CycleBranch", "EndReason", "SpecialPoint",
           "continue_cycles", "cycle_at", "FixedCycle", "follow_cascade", "Cascade", "periodicity_defect",
           "Defect"]
