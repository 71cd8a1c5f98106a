"""The forced cart with Hertz contact of Skurativskyi, Kudra, Witkowski & Awrejcewicz (2019) simulated
from plain values: :func:`simulate` (the model ``forced-oscillator``'s ``simulate`` offering).

The identified parameters of their Table 1, the paper's regularised Coulomb friction (c, T, eps)
or the user's law F_R(v) [N] (``friction`` options, or a
:class:`~landau.laws.velocity.VelocityFriction` as the setup's law), started at rest (at the static
equilibrium in contact where the obstacle is pressed, xI < 0), by the compiled loop
(:func:`~landau.verify.skurativskyi.simulate.record_run`).  The notes give the linearised grazing
estimate of their Sec. 5 for that law.

References
----------
Skurativskyi, S., Kudra, G., Witkowski, K. & Awrejcewicz, J. (2019), Nonlinear Dyn. 98, 1795–1806.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

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

NAME = "forced-oscillator"
#: the step budget of a run where none is given
MAX_STEPS = 5_000_000
#: recorded points kept (decimated past it)
MAX_POINTS = 200_000
#: the run's end where none is given (s)
T_END = 10.0
#: the state names and units of the series
STATE_UNITS = {"x": "m", "xdot": "m/s"}


def simulate(setup: Setup, *, t_end: float | None = None, y0=None, history=None, t_eval=None,
             max_steps: int | None = None, sections: bool = False):
    """The forced oscillator's run (module docstring): series x [m], xdot [m/s].

    Parameters
    ----------
    setup : Setup
        ``params``: Table 1's parameters (m, m0e, n1, n2, n3, k, kI, b, xI, omega) and the law's.
    t_end, y0, history, t_eval, max_steps, sections
        As :func:`landau.simulate` (no velocity history; the stroboscopic section at the forcing
        period is always available).

    Returns
    -------
    Simulation
    """
    from landau.laws.velocity import regularised_coulomb
    from landau.verify.lancioni.run import velocity_law
    from landau.verify.skurativskyi.approx import grazing_linear, static_equilibrium
    from landau.verify.skurativskyi.model import MECHANICAL, Params
    from landau.verify.skurativskyi.simulate import record_run

    no_history(history, NAME)
    t_end = end_time(t_end, T_END)
    over = dict(setup.params)
    # the friction F_R(v) [N]: the paper's regularised Coulomb law (c, T, eps) or the user's
    law = velocity_law(setup, regularised_coulomb(), over, quantity="force", model=NAME)
    unknown_parameters(over, list(MECHANICAL) + [q.name for q in law.parameters], NAME)
    p = Params(friction=law).with_(**over)
    if y0 is not None:
        y, note = initial_state(y0, tuple(STATE_UNITS)), "starts at the given y0 (--y0)"
    elif p.xI < 0:  # the springs press the cart on the obstacle: rest is the static equilibrium in contact
        y, note = None, "starts at rest at the static equilibrium (in contact)"
    else:  # the obstacle is not touched at rest
        y, note = np.zeros(2), "starts at rest at x = 0 (free of the obstacle)"
    sim = replace(record_run(p, t_end, y, max_steps=step_budget(max_steps, MAX_STEPS), max_points=MAX_POINTS),
                  model=NAME)
    sim = interpolated(sim, t_eval, t_end, "the integrator's step ends, with the field at each")
    used = {"friction": law.name, **p.values()}
    neg = "the odd extension -F(-v)" if law.negative is None else str(law.branch(-1))
    notes = [note, f"friction F_R(v) = {law.branch(1)} [N] for v > 0, {neg} for v < 0", *sim.notes]
    if p.xI < 0:
        # the Sec. 5 estimate of the first grazing, damped with the law's viscous coefficient
        try:
            notes.append(f"linearised grazing estimate (Skurativskyi et al. 2019, Sec. 5, eq. 4) with X0 = "
                         f"{static_equilibrium(p):.6g} m and the law's viscous coefficient "
                         f"{p.linear_damping:.6g} N s/m: omega = {grazing_linear(p):.6g} rad/s")
        except InputError as exc:
            notes.append(f"no linearised grazing estimate: {exc}")
    return replace(sim, law=law.name, units={"t": "s", **STATE_UNITS}, parameters=used, notes=tuple(notes),
                   plot_hints={"phase": (0, 1), "period": 2 * math.pi / p.omega})


__all__ = ["STATE_UNITS", "simulate"]
