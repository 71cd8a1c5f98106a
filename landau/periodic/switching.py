"""Branch switching at a period doubling onto the doubled cycle, and a cascade of doublings followed.

At a period doubling of the cycle x₀ (period T) the monodromy has the multiplier −1 with
eigenvector v₀; the solution v of the variational equation from v₀ is anti-periodic,
v(T) = −v(0). The doubled cycle (period 2T) is, to first order in its amplitude ε,

    x(t) ≈ x₀(t) + ε v(t)   on [0, T],    x₀(t) − ε v(t − T)   on [T, 2T]

(continuous and 2T-periodic because v is anti-periodic; Doedel et al. 1991, Sect. 6). The
continuation starts from the PD cycle traversed twice, on the mesh of [0, 2T] made of the PD
mesh halved and repeated, corrected on the hyperplane orthogonal to (v on [0, T], −v on [T, 2T]).

:func:`follow_cascade` continues a branch until its first PD, switches, continues the doubled
branch until its PD, and so on; the Feigenbaum ratios δ_n = (p_n − p_{n−1})/(p_{n+1} − p_n) of
the located PD values tend to 4.6692… (Feigenbaum 1978) along a cascade.

References
----------
Feigenbaum, M. J. (1978). Quantitative universality for a class of nonlinear transformations.
J. Stat. Phys. 19, 25–52.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from landau.errors import InputError
from landau.periodic.branch import CycleBranch, SpecialPoint
from landau.periodic.collocation import Mesh
from landau.periodic.floquet import monodromy, propagate
from landau.periodic.problem import CycleProblem


def doubled_start(problem: CycleProblem, pd: SpecialPoint, amplitude: float | None = None):
    """(mesh, base nodes, 2T, p, direction φ, ε) of the doubled cycle at the period doubling ``pd``."""
    if pd.kind != "PD" or pd.cycle is None:
        raise InputError(f"branch switching needs a located period doubling, got {pd.kind}")
    mesh, Y = pd.cycle
    T, p = pd.period, pd.parameter
    M = monodromy(problem, mesh, Y, T, p)
    lam, vecs = np.linalg.eig(M)
    i = int(np.argmin(np.abs(lam + 1.0)))
    v = np.real(propagate(problem, mesh, Y, T, p, np.real(vecs[:, i])))
    s = np.ones(problem.n) if problem.scales is None else np.asarray(problem.scales, dtype=float)
    v = v / np.max(np.abs(v) / s[:, None])
    tau2 = np.concatenate([mesh.tau / 2, 0.5 + mesh.tau[1:] / 2])
    Yb = np.concatenate([Y, Y[:, 1:]], axis=1)
    phi = np.concatenate([v, -v[:, 1:]], axis=1)
    eps = amplitude if amplitude is not None else 1e-3 * float(s[problem.measure])
    return Mesh(tau2, mesh.m), Yb, 2 * T, p, phi, eps


@dataclass
class Cascade:
    """The branches of a period-doubling cascade and its located PD parameter values."""

    branches: list[CycleBranch] = field(default_factory=list)
    points: list[SpecialPoint] = field(default_factory=list)

    @property
    def parameters(self) -> np.ndarray:
        """p_1, p_2, …: the located period doublings, in cascade order."""
        return np.array([s.parameter for s in self.points])

    @property
    def feigenbaum(self) -> np.ndarray:
        """δ_n = (p_n − p_{n−1})/(p_{n+1} − p_n), n = 2… (empty below three doublings)."""
        p = self.parameters
        return (p[1:-1] - p[:-2]) / (p[2:] - p[1:-1]) if p.size >= 3 else np.array([])

    def __repr__(self) -> str:
        return f"Cascade(PD at {list(np.round(self.parameters, 10))}, δ = {list(np.round(self.feigenbaum, 6))})"


def follow_cascade(problem: CycleProblem, start: Any = None, *, doublings: int = 3, steps: int = 200,
                   ds: float = 0.05, ntst: int = 40, amplitude: float | None = None,
                   **continue_kwargs: Any) -> Cascade:
    """Follow a period-doubling cascade through ``doublings`` doublings.

    Each branch is continued (:func:`landau.periodic.continue_cycles`, ``stop_at=("PD",)``)
    until its first period doubling; the doubled branch starts there. The mesh of a doubled
    branch has twice the intervals of its parent (``ntst`` for the first branch).

    Returns
    -------
    Cascade
        The branches, the located PD points and the Feigenbaum ratios.
    """
    from landau.periodic.continuation import continue_cycles

    if doublings < 1:
        raise InputError(f"doublings must be at least 1, got {doublings}")
    out = Cascade()
    br = continue_cycles(problem, start, steps=steps, ds=ds, ntst=ntst, stop_at=("PD",), **continue_kwargs)
    out.branches.append(br)
    for _ in range(doublings):
        pds = br.points("PD")
        if not pds:
            break
        out.points.append(pds[0])
        if len(out.points) == doublings:
            break
        br = continue_cycles(problem, pds[0], steps=steps, ds=ds, stop_at=("PD",), amplitude0=amplitude,
                             **continue_kwargs)
        out.branches.append(br)
    return out
