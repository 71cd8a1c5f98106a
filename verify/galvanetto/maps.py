"""Event maps of the stick–slip models.

* Two blocks: the one-dimensional map d_{k+1} = f(d_k) of Galvanetto (2004) Sec. 2.2,
  d = X₂ − X₁ during a global stick phase (g.s.p.).  From d the start of the next slip is
  determined: block 1 leaves first iff (1 + 2α)d ≤ β − 1, at K₁ = 1 (X₁ = 1 + αd),
  otherwise block 2 leaves at K₂ = β (X₁ = β − (1 + α)d); both at velocity V.  The run
  stops when both blocks stick again (mode ``"ss"``).
* One block: the stick–slip cycle starts where the stick interval ends (X = F_s − cV,
  Ẋ = V) and runs to the next stick.

Every map evaluation returns a :class:`MapStep` (value, the run's events, whether a g.s.p.
was reached), so the bifurcation locators can read the events of the orbit they use.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from landau.errors import LandauError
from landau.verify.galvanetto.model import StickSlipParams, build_model
from landau.verify.hybrid import EngineOptions, EventLog, Status, simulate
from landau.verify.hybrid.dop853 import CompiledDOP853

#: map runs record no samples.  A stuck block whose spring force lands just outside its sticking
#: interval while moving into it is entered (``recover_tol``, larger than the model's landing band
#: ``CORNER_TOL``·F_s): at a sliding bifurcation itself the slip phase ends exactly at K = ±F_s, and
#: a smaller tolerance makes the Filippov rule alternate between slip and stick there.
FAST = EngineOptions(record=False, recover_tol=1e-5)


def default_stepper(rtol: float = 1e-11) -> CompiledDOP853:
    """DOP853 at ``rtol`` (atol = rtol/100, steps ≤ 1): the maps' default mode integrator, the
    compiled loop of :mod:`landau.verify.hybrid.dop853` (the same steps as scipy's ``DOP853``,
    with the quiet steps of a mode run in one compiled call)."""
    return CompiledDOP853(rtol=rtol, atol=rtol * 1e-2, max_step=1.0)


class MapUndefined(LandauError):
    """The orbit from this d never reaches another global stick phase (map undefined)."""


@dataclass(frozen=True)
class MapStep:
    d0: float
    d1: float
    events: EventLog
    duration: float

    def __repr__(self) -> str:
        return f"MapStep(d={self.d0:.12g} -> {self.d1:.12g}, {len(self.events)} events, T={self.duration:.6g})"


_MODEL_CACHE: dict = {}


def model_for(p: StickSlipParams, sections: bool = False, transparent: frozenset = frozenset()):
    key = (p, sections, transparent)
    m = _MODEL_CACHE.get(key)
    if m is None:
        if len(_MODEL_CACHE) > 64:
            _MODEL_CACHE.clear()
        m = _MODEL_CACHE[key] = build_model(p, sections, transparent)
    return m


def gsp_start(p: StickSlipParams, d: float) -> tuple[str, np.ndarray]:
    """Mode and state at the end of the g.s.p. labelled by d (Sec. 2.2)."""
    a, b, V = p.alpha, p.beta, p.V
    if (1 + 2 * a) * d <= b - 1:
        x1 = 1 + a * d
        return "ns", np.array([x1, x1 + d, V, V])
    x1 = b - (1 + a) * d
    return "sn", np.array([x1, x1 + d, V, V])


def d_range(p: StickSlipParams) -> tuple[float, float]:
    """Interval of definition [d_min, d_max] of the map: the g.s.p. parallelogram projected
    on d (points A and C of Fig. 2): |K₁| ≤ 1 and |K₂| ≤ β on a 45° line."""
    a, b = p.alpha, p.beta
    return (-(1 + b) / (1 + 2 * a), (1 + b) / (1 + 2 * a))


def two_block_map(p: StickSlipParams, d: float, stepper=None, sections: bool = False,
                  options: EngineOptions = FAST, t_max: float | None = None,
                  transparent: frozenset = frozenset(), stop=None) -> MapStep:
    """One application of the event map f(d); raises MapUndefined if no g.s.p. follows."""
    mode, y0 = gsp_start(p, d)
    t_max = t_max if t_max is not None else 200.0 + 20.0 / p.V
    sol = simulate(model_for(p, sections, transparent), mode, y0, (0.0, t_max), stepper or default_stepper(), options,
                   stop=stop or (lambda ev: ev.to_mode == "ss"))
    if sol.status is not Status.STOPPED:
        raise MapUndefined(f"no global stick phase within t={t_max:g} from d={d!r} ({sol.status.value})")
    y = sol.y_final
    return MapStep(d, float(y[1] - y[0]), sol.events, sol.t_final)


def f(p: StickSlipParams, d: float, stepper=None, transparent: frozenset = frozenset()) -> float:
    """d_{k+1} = f(d_k) (Galvanetto 2004, eq. 10)."""
    return two_block_map(p, d, stepper, transparent=transparent).d1


def f_n(p: StickSlipParams, d: float, n: int, stepper=None, transparent: frozenset = frozenset()) -> float:
    """n-th iterate fⁿ(d)."""
    for _ in range(n):
        d = f(p, d, stepper, transparent)
    return d


def iterate(p: StickSlipParams, d: float, n: int, stepper=None) -> np.ndarray:
    out = [d]
    for _ in range(n):
        out.append(f(p, out[-1], stepper))
    return np.array(out)


def one_block_cycle(p: StickSlipParams, stepper=None, sections: bool = False, max_events: int = 8,
                    options: EngineOptions = FAST, x0: float | None = None, v0: float | None = None,
                    transparent: frozenset = frozenset(), stop=None):
    """Run of the one-block model from the end of the stick interval until the next stick
    (or ``max_events`` switches): the stick–slip cycle of Figs 7 and 10."""
    x0 = (1.0 - p.c * p.V) if x0 is None else x0
    v0 = p.V if v0 is None else v0
    opts = EngineOptions(**{**options.__dict__, "max_events": max_events})
    return simulate(model_for(p, sections, transparent), "n", np.array([x0, v0]), (0.0, 200.0 + 20.0 / p.V),
                    stepper or default_stepper(), opts, stop=stop or (lambda ev: ev.to_mode == "s"))
