"""``landau.simulate``: the run that ``landau simulate`` makes, from Python.

::

    import landau
    sim = landau.simulate("spring-block", "dieterich", params={"V": 1e-4}, t_end=5)
    sim.plot()                      # units on the axes, log v, stick phases shaded
    sim.to_csv("run.csv")           # header t [s], X [m], v [m/s], phi [s]

The model is found by name in the registry (:func:`landau.models.get`); its parameters are checked
against its declaration (:meth:`~landau.models.Model.check_params`: an unknown name is an
:class:`~landau.errors.InputError` that names the closest); the law is checked against the kind the
model takes (:class:`~landau.models.LawKind`); then the model's own ``simulate`` offering assembles
the run.  The result is the toolkit's one :class:`~landau.verify.hybrid.result.Simulation`, which
carries the unit of each series, every parameter used (defaults completed), the notes, the model's
and the law's names and how to draw it (:meth:`~landau.verify.hybrid.result.Simulation.plot`).

Output times: by default the integrator's own points (accepted steps or dense samples);
``t_eval`` gives them at chosen times, ``dt`` on a uniform grid 0, dt, 2 dt, … ≤ t_end and
``samples`` on that many points spanning [0, t_end] — computed at those times where the model
can (a load-point history: each time the end of a compiled Radau IIA run), else interpolated from
the record (cubic Hermite where the field is recorded, linear otherwise); the notes say which.
"""

from __future__ import annotations

import math
from typing import Any, Mapping

import numpy as np

from landau.errors import InputError


def _model(model):
    from landau import models

    if isinstance(model, models.Model):
        return model
    return models.get(model)


def _law_and_options(m, law, options: dict):
    """The setup's law for the model's kind: a rate-and-state law by name or object; a velocity or kinetic
    law as an expression (the ``friction`` / ``kinetic`` option) or an object."""
    from landau.models import LawKind

    kind = m.law_kind
    if law is None:
        if kind is LawKind.RATE_AND_STATE and m.default_law is not None:
            from landau.laws import get_law

            return get_law(m.default_law)
        return None
    if kind is LawKind.RATE_AND_STATE:
        from landau.laws import FrictionLaw, get_law

        if isinstance(law, str):
            return get_law(law)
        if isinstance(law, FrictionLaw):
            return law
        want = "a rate-and-state law (a built-in law's name or a landau.laws.FrictionLaw)"
    elif kind is LawKind.VELOCITY:
        from landau.laws.velocity import VelocityFriction

        if isinstance(law, str):
            _as_option(options, "friction", law)
            return None
        if isinstance(law, VelocityFriction):
            return law
        want = "a velocity law F(v) (an expression in v, or a landau.laws.velocity.VelocityFriction)"
    elif kind is LawKind.KINETIC:
        from landau.laws.kinetic import KineticFriction

        if isinstance(law, str):
            _as_option(options, "kinetic", law)
            return None
        if isinstance(law, KineticFriction):
            return law
        want = "a kinetic law of r = Xdot - V (an expression in r, or a landau.laws.kinetic.KineticFriction)"
    else:
        want = "no friction law"
    got = getattr(law, "name", None)
    raise InputError(f"{m.name} takes {want}, got {type(law).__name__}" + (f" {got!r}" if got else ""))


def _as_option(options: dict, name: str, text: str) -> None:
    if options.get(name) not in (None, text):
        raise InputError(f"two laws given: {text!r} and the option {name}={options[name]!r}")
    options[name] = text


def _checked_options(m, options: Mapping[str, Any] | None) -> dict:
    known = [o.name for o in m.options] + list(m.defaults.get("simulate_options", ()))
    out = dict(options or {})
    for name in out:
        if name not in known:
            raise InputError(f"{m.name}: unknown option {name!r} (known: {', '.join(known) or 'none'})")
    return out


def _params(m, params: Mapping[str, Any] | None, law, options: dict) -> dict[str, float]:
    """The given parameter values as floats, every name declared by the model for this law and these
    options (the declaration may depend on the values: a user law's parameters)."""
    from landau.models import Setup
    from landau.models.model import finite

    given = {str(k): finite(v, f"{m.name}: parameter {k!r}") for k, v in dict(params or {}).items()}
    m.check_params(list(given), Setup(law, dict(given), options))
    return given


def uniform_times(dt: float | None = None, samples: int | None = None):
    """The uniform output grid as a function of the run's end time: 0, dt, 2 dt, … ≤ t_end, or
    ``samples`` points spanning [0, t_end] (None when neither is given)."""
    if dt is not None and samples is not None:
        raise InputError("give dt or samples, not both")
    if dt is not None:
        try:
            step = float(dt)
        except (TypeError, ValueError):
            raise InputError(f"dt must be a number, got {dt!r}") from None
        if not (math.isfinite(step) and step > 0):
            raise InputError(f"dt must be a finite number > 0, got {dt!r}")

        def grid(t_end: float) -> np.ndarray:
            n = int(math.floor(t_end / step * (1 + 1e-12)))
            if n > 10_000_000:
                raise InputError(f"dt = {step:g} gives {n + 1} output times over [0, {t_end:g}]: more than 1e7")
            return step * np.arange(n + 1)

        return grid
    if samples is not None:
        try:
            count = float(samples)
        except (TypeError, ValueError):
            count = float("nan")
        if not (math.isfinite(count) and count == int(count) and 2 <= count <= 10_000_000):
            raise InputError(f"samples must be a whole number from 2 to 1e7, got {samples!r}")
        return lambda t_end: np.linspace(0.0, t_end, int(count))
    return None


def _title(m, sim, setup) -> str:
    units = {p.name: p.unit for p in m.parameters(setup)}
    parts = []
    for name in m.defaults.get("key_parameters", ()):
        if name in sim.parameters:
            val = sim.parameters[name]
            unit = units.get(name, "1")
            parts.append(f"{name} = {val:.4g}" + (f" {unit}" if unit not in ("", "1") else "")
                         if isinstance(val, (int, float)) else f"{name} = {val}")
    if "V_history" in sim.parameters:
        parts.insert(0, f"V(t) = {sim.parameters['V_history']} m/s @ s")
    law = f", {sim.law}" if sim.law else ""
    return f"{m.name}{law}" + (": " + ", ".join(parts) if parts else "")


def simulate(model, law=None, *, params: Mapping[str, Any] | None = None, t_end: float | None = None, y0=None,
             history=None, t_eval=None, dt: float | None = None, samples: int | None = None,
             options: Mapping[str, Any] | None = None, max_steps: int | None = None, sections: bool = False):
    """Simulate a registered model (module docstring).

    Parameters
    ----------
    model : str or landau.models.Model
        The model's name (``landau.models.names()``: spring-block, galvanetto-one-block, …).
    law : str or law object, optional
        The friction law, of the kind the model takes: a rate-and-state law's name or
        :class:`~landau.laws.FrictionLaw` (spring-block; default the model's, dieterich); a velocity
        law's expression in ``v`` or :class:`~landau.laws.velocity.VelocityFriction` (impact and forced
        oscillators; default their published laws); a kinetic law's expression in r or
        :class:`~landau.laws.kinetic.KineticFriction` (the Galvanetto blocks; default eq. 7).
    params : mapping, optional
        Parameter values by declared name (``landau.models.get(name).parameters()``); the others
        take their defaults.  The spring-block's V [m/s] and k [N/m] are parameters here.
    t_end : float, optional
        End of the run (default the model's ``defaults["t_end"]``).
    y0 : sequence, optional
        Initial state in the order and units of the series.
    history : str or sequence of (V_i, t_i), optional
        A load-point velocity history (spring-block): ``"1e-5@0,1e-4@5"`` or ``[(1e-5, 0), (1e-4, 5)]``.
    t_eval : array_like, optional
        Output times in [0, t_end].
    dt : float, optional
        Uniform output step.
    samples : int, optional
        Number of uniform output times spanning [0, t_end].
    options : mapping, optional
        The model's options (:attr:`~landau.models.Model.options`, e.g. ``{"friction_neg": ...}``)
        and its simulation's (``{"hopf": True}`` for galvanetto-one-block).
    max_steps : int, optional
        Step budget (default the model's); at it the run ends with status ``max-steps``.
    sections : bool, optional
        Log the Poincaré-section crossings the model defines (spring-block: v = V rising).

    Returns
    -------
    Simulation
        With ``units``, ``parameters``, ``notes``, ``law`` and ``plot_hints`` (the title).

    Raises
    ------
    InputError
        An unknown model (with the closest name), a model without a simulation, a law of the wrong
        kind, an unknown parameter or option, bad output times.
    """
    from dataclasses import replace

    from landau.models import Setup

    m = _model(model)
    if m.simulate is None:
        from landau import models

        have = [n for n in models.names() if models.get(n).simulate is not None]
        raise InputError(f"model {m.name!r} has no simulation (models with one: {', '.join(have)})")
    opts = _checked_options(m, options)
    the_law = _law_and_options(m, law, opts)
    setup = Setup(the_law, _params(m, params, the_law, opts), opts)
    if sum(x is not None for x in (t_eval, dt, samples)) > 1:
        raise InputError("give one of t_eval, dt and samples")
    grid = t_eval if t_eval is not None else uniform_times(dt, samples)
    sim = m.simulate(setup, t_end=t_end, y0=y0, history=history, t_eval=grid, max_steps=max_steps,
                     sections=bool(sections))
    hints = {**sim.plot_hints, "title": _title(m, sim, setup)}
    return replace(sim, plot_hints=hints)


__all__ = ["simulate", "uniform_times"]
