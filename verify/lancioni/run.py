"""The frictional impact oscillator of Lancioni, Lenci & Galvanetto simulated from plain values:
:func:`simulate` (the model ``impact-oscillator``'s ``simulate`` offering).

A bar on a moving belt (their eq. 1), parameter set 1 of Sec. 3 (Leine, Brogliato & Nijmeijer 2002)
with the belt at ``v_belt`` (default −1 m/s) and Coulomb friction μ (default 0.42, above the Hopf
point 0.40978) or the user's law F(v) (``friction`` options, or a
:class:`~landau.laws.velocity.VelocityFriction` as the setup's law), started on the belt 1e-3 rad
off the slip equilibrium; integrated by the hybrid engine with the compiled DOP853 stepper.
"""

from __future__ import annotations

import math
from dataclasses import replace

from landau.errors import InputError
from landau.models import Setup
from landau.verify.hybrid.run_inputs import (
    end_time,
    initial_state,
    interpolated,
    no_history,
    step_budget,
    unknown_parameters,
)

NAME = "impact-oscillator"
#: the step budget of a run where none is given
MAX_STEPS = 300_000
#: events kept (the run ends with status max-events past it)
MAX_EVENTS = 200_000
#: recorded points kept (thinned past it)
MAX_POINTS = 200_000
#: the run's end where none is given (s)
T_END = 10.0
#: the state names and units of the series
STATE_UNITS = {"phi": "rad", "y": "m", "phidot": "rad/s", "ydot": "m/s"}


def velocity_law(setup: Setup, default, params: dict, *, quantity: str = "coefficient", model: str = NAME):
    """The setup's velocity law F(v): its ``law`` (a VelocityFriction, with any values of its
    parameters in ``params``), the ``friction`` options, or ``default``; the law's values are removed
    from ``params``."""
    from landau.laws.velocity import VelocityFriction, law_from_options

    if setup.law is not None:
        if not isinstance(setup.law, VelocityFriction):
            raise InputError(f"{model}: the law must be a velocity law F(v) (a VelocityFriction, or an expression "
                             f"in v), got {type(setup.law).__name__}")
        return law_from_options(None, None, None, setup.law, params, quantity=quantity)
    return law_from_options(setup.option("friction"), setup.option("friction_neg"), setup.option("friction_name"),
                            default, params, quantity=quantity)


def simulate(setup: Setup, *, t_end: float | None = None, y0=None, history=None, t_eval=None,
             max_steps: int | None = None, sections: bool = False):
    """The impact oscillator's run (module docstring): series phi [rad], y [m], phidot, ydot.

    Parameters
    ----------
    setup : Setup
        ``params``: set 1's parameters (m1, m2, l, k_y, k_phi, c_y, c_phi, phi0, y0, g), ``v_belt``,
        ``eN`` and ``mu`` or the user law's parameters.
    t_end, y0, history, t_eval, max_steps, sections
        As :func:`landau.simulate` (no velocity history; the impacts and switches are logged always).

    Returns
    -------
    Simulation
    """
    from landau.laws.velocity import coulomb
    from landau.verify.hybrid import simulate as run_hybrid
    from landau.verify.hybrid.dop853 import CompiledDOP853
    from landau.verify.lancioni import slip as S
    from landau.verify.lancioni.contact import default_options
    from landau.verify.lancioni.model import ConstantBelt, build, slip_state

    no_history(history, NAME)
    t_end = end_time(t_end, T_END)
    over = dict(setup.params)
    law = velocity_law(setup, coulomb(over.get("mu", 0.42)), over)
    unknown_parameters(over, ["eN", "v_belt"] + list(S.PARAM_NAMES), NAME)
    eN, v = over.pop("eN", 0.0), over.pop("v_belt", -1.0)
    if not (math.isfinite(v) and v != 0):
        raise InputError(f"{NAME}: v_belt must be a nonzero belt velocity (m/s), got {v!r}")
    p = S.resolve(over)
    cm = build(None, eN, p, ConstantBelt(v), friction=law)
    s = 1 if v < 0 else -1
    names = tuple(STATE_UNITS)
    if y0 is not None:
        y = initial_state(y0, names)
        start = "starts at the given y0 (--y0)"
    else:
        y = slip_state(cm.mech, S.equilibrium_phi(p, None, s, law, None, v) + 1e-3)
        start = "starts on the belt 1e-3 rad off the slip equilibrium"
    sol = run_hybrid(cm.model, cm.initial_mode(0.0, y), y, (0.0, t_end), CompiledDOP853(1e-10, 1e-12),
                     default_options(record=True, max_steps=step_budget(max_steps, MAX_STEPS), max_events=MAX_EVENTS,
                                     max_samples=MAX_POINTS))
    sim = replace(sol, model=NAME, state_names=names)
    sim = interpolated(sim, t_eval, t_end, "the engine's recorded samples")
    used = {**law.defaults(), "eN": eN, "v_belt": v, **p}
    if setup.law is not None or setup.option("friction") is not None:
        used["friction"] = f"{law.positive} (v > 0), {law.branch(-1)} (v < 0)"
    return replace(sim, law=law.name, units={"t": "s", **STATE_UNITS}, parameters=used,
                   notes=(start, *sim.notes), plot_hints={"phase": (0, 2)})


__all__ = ["STATE_UNITS", "simulate", "velocity_law"]
