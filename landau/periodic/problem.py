"""The contract between a model and the cycle engine: a smooth vector field ẏ = f(y; p).

A :class:`CycleProblem` is what :mod:`landau.periodic` continues: a first-order system with
E⁻¹ already applied (a descriptor system with an invertible mass matrix is given as
ẏ = E⁻¹ f), its Jacobian, one continuation parameter ``p`` and the fixed values of the others.
It is numbers and compiled (or numpy-vectorised) callables only — no sympy — so that the engine
never needs to know which model it is following.

Calling conventions (the engine relies on them):

* ``rhs(y, p)``: ``y`` of shape (n,) gives (n,); ``y`` of shape (n, m) gives (n, m), column j
  being f(y[:, j]; p) (the collocation evaluates every mesh point in one call).
* ``jac(y, p)``: ∂f/∂y, (n, n) for ``y`` of shape (n,), (n, n, m) for (n, m).
* ``dfdp(y, p)`` (optional): ∂f/∂p, same shapes as ``rhs``; the engine differences ``rhs`` in p
  (central, step ``1e-6·max(1, |p|)``) where it is absent.
* ``multilinear`` (optional): ``(B, C)`` with ``B(y, p, u, v)`` = Σ ∂²f/∂y_j∂y_k u_j v_k and
  ``C(y, p, u, v, w)`` the third-order form, each vectorised like ``rhs`` over the columns of
  ``y, u, v, w`` (the normal-form coefficients of the bifurcations of cycles need them,
  Kuznetsov, Govaerts & Doedel 2005); where absent the engine takes directional differences of
  ``jac``.
* ``scales``: a typical magnitude of each state (for the tolerances and the mesh adaptation of
  systems whose states differ by orders of magnitude, e.g. slip 1e-7 m against φ ≈ 1).

References
----------
Kuznetsov, Y. A., Govaerts, W. & Doedel, E. J. (2005). Numerical periodic normalization for
codim 1 bifurcations of limit cycles. SIAM J. Numer. Anal. 43, 1407–1435.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Mapping

import numpy as np

from landau.errors import InputError


@dataclass(frozen=True)
class HopfStart:
    """The Hopf point a branch of cycles is born at, with the amplitude equation's prediction.

    Parameters
    ----------
    p_c : float
        Critical value of the continuation parameter.
    equilibrium : numpy.ndarray
        y₀ at p_c, shape (n,).
    omega : float
        ω_c, the angular frequency at onset (rad/s); the first cycle's period is 2π/ω_c.
    eigenvector : numpy.ndarray
        The critical eigenvector q (complex, shape (n,)) of J(y₀; p_c) for the eigenvalue iω_c,
        normalised with ``q[measure] = 1``.
    amplitude : float or None
        C of the amplitude equation: the cycle's half peak-to-peak of state ``measure`` is
        ≈ C·sqrt|p − p_c| on the side ``side`` (None where the coefficient is not known).
    side : int
        +1 or −1: the side of p_c on which the cycle exists to the first order (the sign of
        −Λ·dRe λ/dp); 0 where not known.
    Lambda, Lambda5 : float or None
        Landau coefficients Λ and Λ₅ (landau's convention), for the Bautin prediction of a fold
        of cycles near a degenerate Hopf point.
    """

    p_c: float
    equilibrium: np.ndarray
    omega: float
    eigenvector: np.ndarray
    amplitude: float | None = None
    side: int = 0
    Lambda: float | None = None
    Lambda5: float | None = None


@dataclass(frozen=True)
class CycleProblem:
    """ẏ = f(y; p): a smooth vector field, one continuation parameter, and how to measure a cycle.

    Parameters
    ----------
    name : str
        The system's name (in results and messages).
    states : tuple of str
        State names, in the order of ``y``.
    parameter : str
        The continuation parameter's name (the Hopf parameter of the model: ``k`` for the
        spring–block).
    params : mapping of str to float
        The other parameters' values (for the record: the callables already hold them).
    rhs, jac : callable
        f(y, p) and ∂f/∂y(y, p), vectorised as the module docstring says.
    dfdp : callable, optional
        ∂f/∂p(y, p).
    multilinear : tuple of callables, optional
        (B, C), the second- and third-order multilinear forms of f in y.
    scales : numpy.ndarray, optional
        Typical magnitude of each state (default: ones).
    measure : int
        Index of the state whose half peak-to-peak (max − min)/2 is the cycle's amplitude
        (the amplitude equation's C measure; the slip X for the spring–block).
    hopf : HopfStart, optional
        The Hopf point and the amplitude equation's prediction (to start a branch there).
    parameter_range : tuple of float
        Where the continuation parameter is meaningful (e.g. k > 0); the continuation stops at
        its ends.
    """

    name: str
    states: tuple[str, ...]
    parameter: str
    rhs: Callable[[np.ndarray, float], np.ndarray]
    jac: Callable[[np.ndarray, float], np.ndarray]
    params: Mapping[str, float] = field(default_factory=dict)
    dfdp: Callable[[np.ndarray, float], np.ndarray] | None = None
    multilinear: tuple[Callable[..., np.ndarray], Callable[..., np.ndarray]] | None = None
    scales: np.ndarray | None = None
    measure: int = 0
    hopf: HopfStart | None = None
    parameter_range: tuple[float, float] = (-np.inf, np.inf)

    def __post_init__(self) -> None:
        n = len(self.states)
        if n < 2:
            raise InputError(f"{self.name}: a periodic orbit needs at least 2 states, got {n}")
        if not 0 <= self.measure < n:
            raise InputError(f"{self.name}: measure index {self.measure} is not a state index (0…{n - 1})")
        if self.scales is not None:
            s = np.asarray(self.scales, dtype=float)
            if s.shape != (n,) or not np.all(np.isfinite(s)) or np.any(s <= 0):
                raise InputError(f"{self.name}: scales must be {n} positive finite numbers, got {self.scales!r}")
        lo, hi = self.parameter_range
        if not lo < hi:
            raise InputError(f"{self.name}: parameter_range must be increasing, got {self.parameter_range!r}")

    @classmethod
    def from_system(cls, system, params: Mapping[str, float] | None = None, **kwargs) -> "CycleProblem":
        """The problem of a :class:`landau.systems.system.DynamicalSystem` from the system's one numeric
        field builder (:mod:`landau.systems.numeric_field`: E⁻¹ applied, vectorised, exact ∂f/∂p and
        multilinear forms); keyword arguments ``hopf``, ``measure``, ``scales``, ``name``, ``unknowns``,
        ``parameter_range``. See :mod:`landau.periodic.from_system`."""
        from landau.periodic.from_system import build

        return build(system, params, **kwargs)

    @property
    def n(self) -> int:
        """The number of states."""
        return len(self.states)


@dataclass(frozen=True)
class CycleStart:
    """A cycle to start a branch from: states sampled on a time mesh over one period.

    Parameters
    ----------
    t : numpy.ndarray
        Times (m,), increasing, spanning one period from ``t[0]`` (the last sample may or may not
        repeat the first state at ``t[0] + period``).
    y : numpy.ndarray
        States (n, m) at ``t``.
    period : float
        T, or its guess.
    p : float
        The continuation parameter's value.
    exact : bool
        True for a computed cycle (a simulation's last period): the corrector starts from it
        as is; False for a rough guess (a few more damped Newton iterations are allowed).
    """

    t: np.ndarray
    y: np.ndarray
    period: float
    p: float
    exact: bool = True

    def __post_init__(self) -> None:
        t = np.asarray(self.t, dtype=float)
        y = np.asarray(self.y, dtype=float)
        if t.ndim != 1 or t.size < 4 or np.any(np.diff(t) <= 0):
            raise InputError(f"CycleStart: t must be at least 4 increasing times, got shape {t.shape}")
        if y.ndim != 2 or y.shape[1] != t.size:
            raise InputError(f"CycleStart: y must be (n, {t.size}) states at the times t, got shape {y.shape}")
        if not (np.isfinite(self.period) and self.period > 0):
            raise InputError(f"CycleStart: the period must be positive and finite, got {self.period!r}")
        if not (np.all(np.isfinite(y)) and np.isfinite(self.p)):
            raise InputError("CycleStart: the states and the parameter must be finite")
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "y", y)
