"""A cycle of a branch checked by a separate integrator: one period integrated from its first node.

Collocation solves a discretised boundary-value problem. Where the mesh does not resolve the cycle
— a slip spike of relative width 1e-6 on 80 intervals, as in a quasi-static rate-and-state block
near its runaway — Newton's method still converges, to a solution of the discretisation that is
not a cycle of the field, and nothing in the collocation residual shows it. Integrating the field
over one period T from the cycle's first node y(0), with scipy's Radau IIA (a stepper independent
of the collocation, the problem's Jacobian, rtol 1e-10 by default), tells the two apart:

* ``closure`` = maxᵢ |yᵢ(T) − yᵢ(0)| / sᵢ, the scaled periodicity defect;
* ``path`` = the largest scaled distance between the integrated path and the collocated cycle at
  the mesh nodes;
* ``amplification`` = the largest |μ| of the cycle's Floquet multipliers (at least 1): an exact
  cycle's closure is the collocation error of y(0) carried once around the cycle, so up to this
  factor larger for an unstable cycle.

``ok`` is ``closure ≤ tol · amplification``. For a resolved cycle the closure is of the order of the
collocation error (1e-9 … 1e-12 of the scales on the engine's test systems); for an unresolved one it
is of order one.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from landau.errors import InputError
from landau.periodic.branch import CycleBranch


@dataclass(frozen=True)
class Defect:
    """The check of one cycle (see the module docstring): scaled closure and path distance, the
    multipliers' amplification, the tolerance and the verdict."""

    closure: float
    path: float
    amplification: float
    tol: float
    ok: bool

    def __str__(self) -> str:
        verdict = "a cycle of the field" if self.ok else "NOT a cycle of the field (refine the mesh: more ntst)"
        return (f"one period integrated (Radau IIA): closure {self.closure:.3g}, path {self.path:.3g} "
                f"(scaled; amplification {self.amplification:.3g}, tol {self.tol:g}): {verdict}")


def periodicity_defect(branch: CycleBranch, i: int, *, rtol: float = 1e-10, tol: float = 1e-6) -> Defect:
    """Check cycle ``i`` of ``branch`` by integrating one period from its first node.

    Parameters
    ----------
    branch : CycleBranch
        A continued branch.
    i : int
        The index of the cycle on the branch (negative counts from the end).
    rtol : float
        The integrator's relative tolerance (absolute: ``rtol`` × the scales).
    tol : float
        The largest scaled closure accepted, multiplied by the amplification.

    Raises
    ------
    InputError
        An index off the branch, or a non-positive ``rtol`` or ``tol``.
    """
    from scipy.integrate import solve_ivp

    if not -len(branch) <= i < len(branch):
        raise InputError(f"periodicity_defect: cycle {i} is not on the branch ({len(branch)} cycles)")
    if not (rtol > 0 and tol > 0):
        raise InputError(f"periodicity_defect: rtol and tol must be positive, got {rtol!r} and {tol!r}")
    pr = branch.problem
    mesh, Y = branch.meshes[i], np.asarray(branch.nodes[i], dtype=float)
    T, p = float(branch.period[i]), float(branch.parameter[i])
    if pr.scales is not None:
        s = np.asarray(pr.scales, dtype=float)
    else:
        s = np.maximum(np.max(np.abs(Y), axis=1), np.finfo(float).tiny)

    def f(t, y):
        return np.asarray(pr.rhs(y, p), dtype=float)

    def jac(t, y):
        return np.asarray(pr.jac(y, p), dtype=float)

    t_nodes = mesh.nodes * T
    sol = solve_ivp(f, (0.0, T), Y[:, 0], method="Radau", jac=jac, rtol=rtol, atol=rtol * s,
                    t_eval=t_nodes)
    if sol.status != 0 or sol.y.shape[1] != t_nodes.size:
        # the integration itself failed (a blow-up off the cycle): as far from a cycle as can be
        return Defect(np.inf, np.inf, 1.0, tol, False)
    closure = float(np.max(np.abs(sol.y[:, -1] - Y[:, 0]) / s))
    path = float(np.max(np.abs(sol.y - Y) / s[:, None]))
    mu = np.asarray(branch.multipliers[i])
    amp = max(1.0, float(np.max(np.abs(mu)))) if mu.size else 1.0
    return Defect(closure, path, amp, tol, bool(closure <= tol * amp))
