"""Hybrid (non-smooth) simulation engine.

Compose a problem (:class:`HybridModel` of :class:`Mode` and :class:`Guard`), a mode
integrator (a stepper factory, :class:`ScipyStepper` or any object with scipy's
``OdeSolver`` members) and engine options, then call :func:`simulate`.  The result
(:class:`HybridSolution`) is the common result type of every model (:class:`Simulation`: recorded
time series, the event log :class:`EventLog`, a :class:`Status`) with the final mode, the recorded
segments and, if events accumulate, a :class:`ZenoDiagnosis`.
The compiled stepper over a :class:`Kernel` is in :mod:`landau.verify.hybrid.dop853`.  Analysis
tools (event maps, Poincaré sections) are in :mod:`landau.verify.hybrid.analysis`.
"""

from landau.verify.hybrid.kernel import Kernel
from landau.verify.hybrid.log import Event, EventLog
from landau.verify.hybrid.model import Guard, HybridModel, Jump, Mode
from landau.verify.hybrid.result import Simulation, Status
from landau.verify.hybrid.simulate import EngineOptions, HybridSolution, Segment, simulate
from landau.verify.hybrid.steppers import DOP853Stepper, RadauStepper, ScipyStepper
from landau.verify.hybrid.zeno import ZenoDiagnosis, ZenoMonitor

__all__ = ["Event", "EventLog", "Guard", "HybridModel", "Jump", "Mode", "EngineOptions",
           "HybridSolution", "Segment", "simulate", "DOP853Stepper", "RadauStepper",
           "ScipyStepper", "ZenoDiagnosis", "ZenoMonitor", "Kernel", "Simulation", "Status"]
