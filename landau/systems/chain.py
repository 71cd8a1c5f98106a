"""A chain of N spring–blocks with rate-and-state friction (Burridge–Knopoff with a state).

Block i (mass M_i, normal load σ_i, default M_i·g) is pulled by a spring of stiffness k to the load
point moving at V and coupled to its neighbours by springs ``k_coupling`` (free ends):

    M_i ẍ_i = k(Vt − x_i) + k_c (x_{i+1} − 2x_i + x_{i−1}) − σ_i μ(ẋ_i, φ_i),   dφ_i/dt = rate(ẋ_i, φ_i),

with the terms of a missing neighbour left out.  Every block slides steadily at V with the law's
steady state; in X_i = x_i − x_{i,0}(t), u_i = ẋ_i − V that sliding is the origin of the
mechanical part, as for the single block (:class:`~landau.systems.system.SpringBlock`).  The Hopf
parameter is k; the Hopf point reported is the first crossing met as k decreases from a stiffness
where sliding is stable, with the critical mode shape (the slips X_i of the critical eigenvector).
Identical blocks have the single block's k_c in the in-phase mode (the coupling springs are then
not stretched), and every other mode is more stable (Putelat et al. 2010 eq. (30) for the single
block).  Built as a :class:`~landau.systems.system.DynamicalSystem` (:attr:`SpringBlockChain.system`), it
goes through the general engine; as numbers (a sparse Jacobian and one block's law jets,
:func:`landau.systems.chain_forms.chain_sparse_system`) through the numeric route of
:mod:`landau.derivation.sparse_hopf`; its first Hopf point and mode shape are
:func:`landau.analyses.chain.chain_hopf`.

References
----------
Burridge, R. & Knopoff, L. (1967). Model and theoretical seismicity. Bull. Seismol. Soc. Am. 57,
341–371 (the chain of blocks).
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a spring–block
system. J. Mech. Phys. Solids 58, 27–53, eq. (4) (one block) and eq. (30) (its k_c).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Mapping

import numpy as np
import sympy as sp

from landau.errors import InputError
from landau.laws.law import FrictionLaw
from landau.laws.law import v as v_slip
from landau.systems.system import (
    G_DEFAULT,
    M_DEFAULT,
    DynamicalSystem,
    SpringBlock,
    V,
    default_normal_load,
    finite_parameter,
    k,
)

#: the coupling stiffness between neighbours [N/m]
k_coupling = sp.Symbol("k_coupling", nonnegative=True)
#: default coupling stiffness [N/m]: of the order of the single block's k_c at the defaults
K_COUPLING_DEFAULT = 1.0e5
#: most blocks accepted (the state has 2 + (law states) entries per block; the numeric route's
#: dense eigenvalue scan costs O(N³), about 1 CPU-s at 100 blocks)
MAX_BLOCKS = 100
#: most blocks the symbolic route (the general engine on :attr:`SpringBlockChain.system`) takes:
#: its cost about doubles per block
SYMBOLIC_MAX_BLOCKS = 12


@dataclass(frozen=True, eq=False)
class SpringBlockChain:
    """N spring–blocks with the same rate-and-state law, each pulled by k, coupled by ``k_coupling``.

    Parameters
    ----------
    law : FrictionLaw or str
        The friction law of every block, or a built-in law's name.
    blocks : int
        The number of blocks N (1 to :data:`MAX_BLOCKS`).

    Notes
    -----
    Parameters: the law's, ``V`` (driving velocity, m/s), ``k_coupling`` (N/m), ``M_i`` (kg,
    default 1.2) and ``sigma_i`` (N), i = 1…N, whose default is the single block's σ
    (:meth:`SpringBlock.resolve`): 1.2 kg × 9.81 m/s² whatever M_i (a mass alone changes the inertia
    only), and M_i·g (1.2 kg × g for M_i = 0) where ``g`` is given.
    """

    law: FrictionLaw
    blocks: int = 2

    def __post_init__(self) -> None:
        if isinstance(self.law, str):
            from landau.laws import get_law

            object.__setattr__(self, "law", get_law(self.law))
        if not isinstance(self.law, FrictionLaw):
            raise InputError(f"SpringBlockChain needs a FrictionLaw or a built-in law's name, "
                             f"got {type(self.law).__name__}")
        if isinstance(self.blocks, bool) or not isinstance(self.blocks, (int, np.integer)) \
                or not 1 <= int(self.blocks) <= MAX_BLOCKS:
            raise InputError(f"the number of blocks must be an integer from 1 to {MAX_BLOCKS}, got {self.blocks!r}")
        object.__setattr__(self, "blocks", int(self.blocks))
        names = {s.name for s in self.law.states} | {p.name for p in self.law.parameters}
        clash = sorted(names & {"k_coupling", "g", *self._block_names()})
        if clash:
            raise InputError(f"law {self.law.name!r}: name {clash[0]!r} is a parameter of the chain; rename it")

    def _block_names(self) -> list[str]:
        return [f"{n}_{i}" for i in range(1, self.blocks + 1) for n in ("M", "sigma")]

    @cached_property
    def single(self) -> SpringBlock:
        """The single block with the same law (its steady state and argument checks)."""
        return SpringBlock(self.law)

    @cached_property
    def defaults(self) -> dict[str, float]:
        d = {key: val for key, val in self.single.defaults.items() if key not in ("M", "sigma")}
        d["V"] = 1e-4
        d["k_coupling"] = K_COUPLING_DEFAULT
        for i in range(1, self.blocks + 1):
            d[f"M_{i}"] = M_DEFAULT
            d[f"sigma_{i}"] = M_DEFAULT * G_DEFAULT
        return d

    def resolve(self, overrides: Mapping[str, float] | None = None) -> dict[str, float]:
        """Every parameter value (law, V, k_coupling, M_i, sigma_i) with ``overrides`` applied and checked.

        Parameters
        ----------
        overrides : mapping of str to float, optional
            Values by name; ``g`` sets the default loads σ_i = M_i·g.

        Returns
        -------
        dict of str to float

        Raises
        ------
        InputError
            An unknown name (``M`` and ``sigma`` name the blocks' ``M_i``, ``sigma_i``), a value
            that is not a finite number, M_i < 0, σ_i ≤ 0, k_coupling < 0, V ≤ 0.
        """
        over = dict(overrides or {})
        for key in ("M", "sigma"):
            if key in over:
                raise InputError(f"a chain has one {key} per block: give {key}_1 ... {key}_{self.blocks}")
        g = over.pop("g", G_DEFAULT)
        law_over = {key: val for key, val in over.items() if key in {p.name for p in self.law.parameters}}
        p = {key: val for key, val in self.single.resolve({**law_over, "g": g}).items()
             if key not in ("M", "sigma", "g")}
        p.update(V=1e-4, k_coupling=K_COUPLING_DEFAULT)
        known = set(p) | set(self._block_names())
        for key, val in over.items():
            if key not in known:
                raise InputError(f"unknown parameter {key!r} for the chain of {self.blocks} blocks with law "
                                 f"{self.law.name!r} (known: {', '.join(sorted(known))}, g)")
            p[key] = finite_parameter(key, val)
        g_given = "g" in (overrides or {})
        g = float(g)
        for i in range(1, self.blocks + 1):
            m = p.setdefault(f"M_{i}", M_DEFAULT)
            if m < 0:
                raise InputError(f"parameter 'M_{i}' must be >= 0, got {m!r}")
            # one default for one thing: σ_i as the single block's σ (SpringBlock.resolve): M_DEFAULT·g,
            # following M_i only where g is given (changing a mass alone changes the inertia only)
            s = p.setdefault(f"sigma_{i}", float(default_normal_load(m, g)) if g_given else M_DEFAULT * G_DEFAULT)
            if not s > 0:
                raise InputError(f"parameter 'sigma_{i}' must be > 0, got {s!r}")
        if p["k_coupling"] < 0:
            raise InputError(f"parameter 'k_coupling' must be >= 0, got {p['k_coupling']!r}")
        if not p["V"] > 0:
            raise InputError(f"parameter 'V' (driving velocity) must be > 0 m/s, got {p['V']!r}")
        return p

    @cached_property
    def system(self) -> DynamicalSystem:
        """The chain as E·ẏ = f(y; k): y = (X_1, u_1, φ_1…, X_2, …), E = diag(1, M_i, 1…)."""
        law = self.law
        ss = self.single.steady_state
        eq_phi = ss if ss is not None else self.single.phi0
        mu_0 = law.mu.subs({v_slip: V, **dict(zip(law.states, eq_phi, strict=True))})
        Xs = [sp.Symbol(f"X_{i}", real=True) for i in range(1, self.blocks + 1)]
        states, rhs, mass, eq = [], [], [], []
        for i in range(self.blocks):
            X, u = Xs[i], sp.Symbol(f"u_{i + 1}", real=True)
            phis = [sp.Symbol(f"{s.name}_{i + 1}", positive=True) for s in law.states]
            at = {v_slip: V + u, **dict(zip(law.states, phis, strict=True))}
            Mi, si = sp.Symbol(f"M_{i + 1}", nonnegative=True), sp.Symbol(f"sigma_{i + 1}", positive=True)
            spring = -k * X
            if i > 0:
                spring += k_coupling * (Xs[i - 1] - X)
            if i < self.blocks - 1:
                spring += k_coupling * (Xs[i + 1] - X)
            states += [X, u, *phis]
            rhs += [u, spring - si * (law.mu.xreplace(at) - mu_0), *(r.xreplace(at) for r in law.rates)]
            mass += [sp.Integer(1), Mi, *([sp.Integer(1)] * len(phis))]
            eq += [sp.Integer(0), sp.Integer(0), *eq_phi]
        unknowns: tuple = ()
        eqs: tuple = ()
        guess: tuple = ()
        if ss is None:
            unknowns = self.single.phi0
            eqs = tuple(r.subs({v_slip: V, **dict(zip(law.states, unknowns, strict=True))}) for r in law.rates)
        return DynamicalSystem(
            name=f"spring-block-chain[{law.name}, N={self.blocks}]", states=tuple(states), rhs=tuple(rhs),
            mass=tuple(mass), parameter=k, equilibrium=tuple(eq), defaults=self.defaults, normalise=0,
            unknowns=unknowns, unknown_equations=eqs, unknown_guess=guess,
            description="N spring-blocks pulled by k, coupled by k_coupling, in X_i = x_i - x_i0(t), u_i = dx_i/dt - V")

    def slip_indices(self) -> list[int]:
        """Positions of X_1 … X_N in the state."""
        per = 2 + len(self.law.states)
        return [i * per for i in range(self.blocks)]

    def equilibrium_values(self, params: Mapping[str, float]) -> list[float]:
        """The steady sliding state (X_i = u_i = 0, φ_i = φ_ss(V)) as floats."""
        lp = {p.name: np.asarray(params[p.name], dtype=float) for p in self.law.parameters}
        Vv = np.asarray(params["V"], dtype=float)
        phis = [float(x) for x in self.law.steady_state_values(Vv, lp)]
        self.law.check_real(Vv, [np.asarray(x) for x in phis], lp)
        return [x for _ in range(self.blocks) for x in (0.0, 0.0, *phis)]
