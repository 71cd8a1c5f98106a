"""A continued branch of cycles: arrays along the branch, its special points, and why it ended.

:class:`CycleBranch` is what :func:`landau.periodic.continue_cycles` returns. Along the branch
(index ``i``, the dimension ``point`` of :meth:`CycleBranch.to_dataset`) it holds the parameter,
the period T, the amplitude (half peak-to-peak (max − min)/2 of state ``measure`` — the amplitude
equation's C measure), the max and min of every state, the n Floquet multipliers (complex), the
trivial multiplier's distance from 1, and the stability flag; each cycle's mesh and node values
(:meth:`CycleBranch.cycle`). The special points (fold LPC, period doubling PD, Neimark–Sacker NS,
branch point BP) are :class:`SpecialPoint` records with their located parameter and period and the
normal-form coefficient; :class:`EndReason` says why the continuation stopped.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from landau.periodic.collocation import Mesh, evaluate
from landau.periodic.problem import CycleProblem


def _peak(vals: np.ndarray) -> np.ndarray:
    """The maximum of each row of periodic samples (last = first), refined by the parabola through
    the largest sample and its neighbours (error O(Δ⁴) instead of O(Δ²))."""
    y = vals[:, :-1]
    i = np.argmax(y, axis=1)
    r = np.arange(y.shape[0])
    y0, ym, yp = y[r, i], y[r, i - 1], y[r, (i + 1) % y.shape[1]]
    curv = 2 * y0 - ym - yp
    with np.errstate(divide="ignore", invalid="ignore"):
        corr = np.where(curv > 0, (yp - ym) ** 2 / (8 * curv), 0.0)
    return y0 + corr


class EndReason(enum.Enum):
    """Why a continuation stopped (the branch computed so far is always kept)."""

    STEPS = "the requested number of steps was reached"
    PARAMETER_RANGE = "the parameter left parameter_range"
    MAX_PERIOD = "the period exceeded max_period (approach to a homoclinic orbit?)"
    COLLAPSE = "the cycle collapsed onto an equilibrium (a Hopf point was reached)"
    NO_CONVERGENCE = "Newton's method did not converge even at the smallest step ds_min"
    FIRST_POINT = "the first cycle could not be corrected"
    SPECIAL_POINT = "a special point named in stop_at was located"


@dataclass(frozen=True)
class SpecialPoint:
    """A located bifurcation of cycles on the branch.

    ``kind`` is "LPC", "PD", "NS" or "BP"; ``index`` the branch point just before it; ``parameter``
    and ``period`` the located values; ``coefficient`` the first-order normal-form coefficient
    (None where not computed; :mod:`landau.periodic.normal_forms` states each normalisation);
    ``multipliers`` the multipliers at the located point; ``message`` a one-line description.
    """

    kind: str
    index: int
    parameter: float
    period: float
    coefficient: float | None = None
    multipliers: np.ndarray | None = None
    message: str = ""
    cycle: tuple[Mesh, np.ndarray] | None = field(default=None, repr=False)


@dataclass
class CycleBranch:
    """A branch of cycles of one :class:`CycleProblem` (see the module docstring)."""

    problem: CycleProblem
    route: str
    parameter: list[float] = field(default_factory=list)
    period: list[float] = field(default_factory=list)
    meshes: list[Mesh] = field(default_factory=list, repr=False)
    nodes: list[np.ndarray] = field(default_factory=list, repr=False)
    multipliers: list[np.ndarray] = field(default_factory=list, repr=False)
    trivial: list[complex] = field(default_factory=list, repr=False)
    special: list[SpecialPoint] = field(default_factory=list)
    end: EndReason = EndReason.STEPS
    message: str = ""
    settings: dict[str, Any] = field(default_factory=dict)

    def append(self, mesh: Mesh, Y: np.ndarray, T: float, p: float, mu: np.ndarray, trivial: complex) -> None:
        self.meshes.append(mesh)
        self.nodes.append(np.array(Y))
        self.period.append(float(T))
        self.parameter.append(float(p))
        self.multipliers.append(np.asarray(mu, dtype=complex))
        self.trivial.append(complex(trivial))

    def __len__(self) -> int:
        return len(self.parameter)

    # ---- arrays ----------------------------------------------------------------------------
    def _dense(self, i: int, k: int = 8) -> np.ndarray:
        """State values on a fine grid (k per node interval) for max/min."""
        mesh = self.meshes[i]
        t = np.linspace(0.0, 1.0, k * (mesh.npts - 1) + 1)
        return evaluate(mesh, self.nodes[i], t)

    @property
    def maxima(self) -> np.ndarray:
        """max over the cycle of every state, (points, n)."""
        return np.array([_peak(self._dense(i)) for i in range(len(self))]).reshape(len(self), self.problem.n)

    @property
    def minima(self) -> np.ndarray:
        """min over the cycle of every state, (points, n)."""
        return np.array([-_peak(-self._dense(i)) for i in range(len(self))]).reshape(len(self), self.problem.n)

    @property
    def amplitude(self) -> np.ndarray:
        """(max − min)/2 of state ``measure``: the amplitude equation's C measure."""
        j = self.problem.measure
        return (self.maxima[:, j] - self.minima[:, j]) / 2

    @property
    def floquet(self) -> np.ndarray:
        """The n multipliers per point (trivial one included), (points, n) complex."""
        return np.array(self.multipliers).reshape(len(self), self.problem.n)

    @property
    def stable(self) -> np.ndarray:
        """True where every nontrivial multiplier is inside the unit circle."""
        out = []
        for mu, tr in zip(self.multipliers, self.trivial, strict=True):
            i = int(np.argmin(np.abs(mu - tr)))
            out.append(bool(np.all(np.abs(np.delete(mu, i)) < 1.0)))
        return np.array(out, dtype=bool)

    def cycle(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        """The i-th cycle: times (in units of the model's time, 0…T) and states (n, len(t))."""
        mesh = self.meshes[i]
        return mesh.nodes * self.period[i], np.array(self.nodes[i])

    def points(self, kind: str) -> list[SpecialPoint]:
        return [s for s in self.special if s.kind == kind]

    def to_dataset(self) -> Any:
        """An xarray Dataset along dimension ``point`` (attrs: route, discretisation, tolerances)."""
        import xarray as xr

        n = self.problem.n
        mu = self.floquet
        ds = xr.Dataset(
            {
                "parameter": ("point", np.array(self.parameter)),
                "period": ("point", np.array(self.period)),
                "amplitude": ("point", self.amplitude),
                "maximum": (("point", "state"), self.maxima),
                "minimum": (("point", "state"), self.minima),
                "multiplier_real": (("point", "multiplier"), mu.real),
                "multiplier_imag": (("point", "multiplier"), mu.imag),
                "trivial_error": ("point", np.abs(np.array(self.trivial) - 1.0)),
                "stable": ("point", self.stable),
            },
            coords={"point": np.arange(len(self)), "state": list(self.problem.states),
                    "multiplier": np.arange(n)},
        )
        ds.attrs.update({
            "system": self.problem.name, "parameter_name": self.problem.parameter, "route": self.route,
            "end_reason": self.end.name, "end_message": self.message,
            "special_points": "; ".join(f"{s.kind} at {self.problem.parameter} = {s.parameter:.10g} "
                                        f"(T = {s.period:.10g}, coefficient {s.coefficient})" for s in self.special),
        })
        ds.attrs.update({k: v for k, v in self.settings.items() if isinstance(v, (int, float, str))})
        return ds

    def __repr__(self) -> str:
        p = self.parameter
        rng = f"{p[0]:.6g}…{p[-1]:.6g}" if p else "empty"
        kinds = ", ".join(f"{s.kind}@{s.parameter:.6g}" for s in self.special) or "none"
        return (f"CycleBranch({self.problem.name}: {len(self)} cycles, {self.problem.parameter} {rng}, "
                f"special: {kinds}, end: {self.end.name})")
