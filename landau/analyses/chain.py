"""The first Hopf point of a chain of spring–blocks as k decreases, with its critical mode shape.

The chain itself (its equations, parameters and steady sliding) is
:class:`landau.systems.chain.SpringBlockChain`; this module locates its first crossing as the
spring stiffness k decreases, through the general engine, and names the critical mode (in-phase,
anti-phase, mixed or travelling) from the slips X_i of the critical eigenvector.

References
----------
Burridge, R. & Knopoff, L. (1967). Model and theoretical seismicity. Bull. Seismol. Soc. Am. 57,
341–371 (the chain of blocks).
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a spring–block
system. J. Mech. Phys. Solids 58, 27–53, eq. (30) (the single block's k_c).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Mapping

import mpmath
import numpy as np

from landau.errors import InputError, NoHopfError, NonSimpleHopfError, SingularPointError
from landau.systems.chain import SYMBOLIC_MAX_BLOCKS, SpringBlockChain

#: the routes of :func:`chain_hopf`
ROUTES = ("auto", "symbolic", "numeric")
#: most blocks the automatic choice sends to the symbolic route (the measured crossover)
AUTO_SYMBOLIC_BLOCKS = 3
#: a numeric Hopf point whose Newton iteration stalled above this relative step (two crossings
#: nearly coincide: weakly coupled identical blocks) goes to the symbolic route where it runs
NEWTON_FLOOR = 1e-10


def _mode_shape(num, pc: float, wc: float, y0, slips: list[int]) -> np.ndarray:
    """The slips X_i of the critical eigenvector (iωE − J)q = 0, largest |X_i| = 1 and real positive."""
    J, E = num.J_float(y0, pc), num.E_float(pc)
    _, _, vh = np.linalg.svd(1j * wc * E - J)
    q = vh[-1].conj()
    x = q[slips]
    big = x[int(np.argmax(np.abs(x)))]
    x = x / big
    # the SVD of a float64 pencil gives the mode to ~1e-10: smaller parts are round-off
    x = np.where(np.abs(x.real) < 1e-8, 0.0, x.real) + 1j * np.where(np.abs(x.imag) < 1e-8, 0.0, x.imag)
    return x


def _mode_shape_mp(num, pc, wc, y, slips: list[int], j: int) -> np.ndarray:
    """The slips of the critical eigenvector at the working precision: (iωE − J)q = 0 with q_j = 1,
    solved with the row of least residual dropped."""
    n = num.n
    J, E = num.J_mp(y, pc), num.E_mp(pc)
    A = mpmath.matrix(n, n)
    for r in range(n):
        for c in range(n):
            A[r, c] = 1j * wc * E[r, c] - J[r, c]
    others = [c for c in range(n) if c != j]
    best = None
    for drop in range(n):
        rows = [r for r in range(n) if r != drop]
        M = mpmath.matrix([[A[r, c] for c in others] for r in rows])
        rhs = mpmath.matrix([-A[r, j] for r in rows])
        try:
            x = mpmath.lu_solve(M, rhs)
        except ZeroDivisionError:
            continue
        q = [mpmath.mpc(0)] * n
        q[j] = mpmath.mpc(1)
        for c, val in zip(others, x, strict=True):
            q[c] = val
        res = abs(sum(A[drop, c] * q[c] for c in range(n)))
        if best is None or res < best[0]:
            best = (res, q)
    assert best is not None, "no row of the pencil was dropped"
    x = np.array([complex(best[1][i]) for i in slips])
    return np.where(np.abs(x.real) < 1e-14, 0.0, x.real) + 1j * np.where(np.abs(x.imag) < 1e-14, 0.0, x.imag)


def chain_hopf(chain: SpringBlockChain, params: Mapping[str, float] | None = None,
               bracket: tuple[float, float] | None = None, dps: int = 50, route: str = "auto", l2: bool = False):
    """The first Hopf point of a chain as k decreases, with its amplitude equation and mode shape.

    Parameters
    ----------
    chain : SpringBlockChain
    params : mapping, optional
        Overrides of :attr:`SpringBlockChain.defaults` (resolved by :meth:`SpringBlockChain.resolve`).
    bracket : (float, float), optional
        Stiffnesses (N/m) to search, from the larger down (default: from a stiffness where sliding
        is stable, found by doubling, down by factors of 4 to 1e-12 of it).
    dps : int
        Working precision of the located point and its coefficients (symbolic route).
    route : {"auto", "symbolic", "numeric"}
        ``"symbolic"``: the general engine on the chain's sympy system at ``dps`` digits (up to
        :data:`SYMBOLIC_MAX_BLOCKS` blocks; its cost about doubles per block); ``"numeric"``: float64
        sparse linear algebra on the forms assembled from one block's law jets
        (:func:`landau.systems.chain_forms.chain_sparse_system`, :mod:`landau.derivation.sparse_hopf`;
        cost about linear in N beyond the O(N³) eigenvalue scan); ``"auto"``: symbolic up to
        :data:`AUTO_SYMBOLIC_BLOCKS` blocks, numeric beyond (and symbolic again, up to
        :data:`SYMBOLIC_MAX_BLOCKS`, where float64 cannot settle the point: crossings closer than
        its resolution, Λ ≈ 0; Newton stalled above :data:`NEWTON_FLOOR`).  The numeric route is
        faster at every N (measured: about 5× at one block, 55× at five, benchmarks/bench_chain.py);
        the symbolic one is kept for small chains for its 50 digits, Λ's round-off bound and the
        verdict at a degenerate point.
    l2 : bool
        Also compute the fifth order (``Lambda5`` and Kuznetsov's ``l2`` = Re c₂) where Λ does not
        vanish (where it does, both routes compute it anyway); the symbolic route gives ``l2`` only
        (:func:`landau.derivation.general.second_lyapunov`).

    Returns
    -------
    HopfResult
        Normalised on the slip of the block that moves most; ``extra`` holds ``route``, ``blocks``,
        ``mode_shape`` (the slips X_i of the critical mode as ``[re, im]`` pairs, largest 1),
        ``mode`` ("in-phase", "anti-phase", "mixed" or "travelling").  Symbolic route: from the
        general engine (:func:`landau.derivation.general.normal_form_at`) with Λ's round-off
        bound and, where Λ vanishes, the next order (:func:`landau.derivation.degenerate.with_verdict`).
        Numeric route: float64 values, with ``Lambda_scale`` (the size of the terms whose sum is Λ);
        where Λ is below 1e-12 of it (zero to round-off), Λ = 0 and the fifth order
        (:func:`landau.derivation.sparse_hopf.with_fifth_order`) with the same ``extra`` keys as
        the symbolic route's verdict.

    Raises
    ------
    NoHopfError
        No crossing in the bracket (e.g. velocity-strengthening friction).
    NonSimpleHopfError
        Several modes cross together (identical blocks with ``k_coupling`` = 0: a double crossing
        at the single block's k_c), where no single-mode amplitude equation applies.
    """
    if route not in ROUTES:
        raise InputError(f"route must be one of {', '.join(ROUTES)}, got {route!r}")
    p = chain.resolve(params)
    if route == "symbolic" and chain.blocks > SYMBOLIC_MAX_BLOCKS:
        raise InputError(f"the symbolic route takes at most {SYMBOLIC_MAX_BLOCKS} blocks (its cost about doubles per "
                         f"block), got {chain.blocks}: use the numeric route")
    if route == "numeric" or (route == "auto" and chain.blocks > AUTO_SYMBOLIC_BLOCKS):
        fallback = route == "auto" and chain.blocks <= SYMBOLIC_MAX_BLOCKS
        try:
            res = _numeric_chain_hopf(chain, p, bracket, fallback=fallback, l2=l2)
        except (SingularPointError, NonSimpleHopfError):
            # float64 cannot settle the point (crossings closer than its resolution, Λ not
            # resolved): the symbolic route can, where it runs
            if not fallback:
                raise
            res = None
        if res is not None:
            return res
    res = _symbolic_chain_hopf(chain, p, bracket, dps)
    if l2 and res.l2 is None:
        from landau.derivation.general import second_lyapunov

        # Re c₂ with ⟨q, q⟩ = 1: independent of the component the engine normalised on
        res = replace(res, l2=second_lyapunov(chain.system, p, res, max(dps, 40)))
    return res


def _first_stable_stiffness(p: Mapping[str, float], blocks: int, stable) -> float:
    """A stiffness where steady sliding is stable: from max σ_i/L, doubled until stable."""
    hi = max(p[f"sigma_{i}"] for i in range(1, blocks + 1)) / max(abs(float(x)) for x in (p.get("L", 1.0), 1e-300))
    for _ in range(200):
        if stable(hi):
            return hi
        hi *= 2.0
    raise NoHopfError(f"spring-block-chain: steady sliding is unstable at every stiffness tried (up to {hi:g} N/m)")


def _checked_bracket(bracket) -> tuple[float, float]:
    hi, lo = max(map(float, bracket)), min(map(float, bracket))
    if not (np.isfinite(lo) and np.isfinite(hi) and 0 < lo < hi):
        raise InputError(f"bracket: need 0 < lo < hi (stiffnesses in N/m), got {bracket!r}")
    return hi, lo


def _mode_name(shape: np.ndarray) -> str:
    if np.all(shape.imag == 0):
        return "in-phase" if np.all(shape.real > 0) else ("anti-phase" if np.all(shape.real != 0) else "mixed")
    return "travelling"


def _numeric_chain_hopf(chain: SpringBlockChain, p: dict, bracket, fallback: bool, l2: bool):
    """The numeric route (see :func:`chain_hopf`); None where ``fallback`` and float64 cannot settle Λ."""
    from landau.derivation.hopf import SPRING_BLOCK_UNITS
    from landau.derivation.sparse_hopf import _rightmost, resolution, sparse_hopf, with_fifth_order
    from landau.systems.chain_forms import chain_sparse_system

    sysm = chain_sparse_system(chain, p)
    if bracket is not None:
        hi, lo = _checked_bracket(bracket)
    else:
        hi = _first_stable_stiffness(p, chain.blocks, lambda kv: _rightmost(sysm, kv) < 0)
        lo = hi / 4.0 ** 20
    slips = np.array(chain.slip_indices())

    def biggest(q: np.ndarray) -> int:
        mag = np.abs(q[slips])
        return int(slips[np.flatnonzero(mag >= (1 - 1e-9) * mag.max())[0]])

    res, nf = sparse_hopf(sysm, hi, lo, choose_normalise=biggest, params=p)
    floor = float(res.extra["newton_floor"])
    if floor > NEWTON_FLOOR and fallback:
        return None         # a nearly double crossing: float64 holds the mode to `floor` only
    verdict = resolution(res.Lambda, 2 * nf.b_scale)
    if verdict == "unresolved":
        if fallback:
            return None
        raise SingularPointError(f"{sysm.name}: Λ = {res.Lambda:g} is not resolved in float64 (below 1e-8 of "
                                 f"its terms, {2 * nf.b_scale:g}); the symbolic route (route='symbolic', up to "
                                 f"{SYMBOLIC_MAX_BLOCKS} blocks) settles it")
    x = nf.q[slips]
    # float64 Newton and LU factors give the mode to ~1e-13 (to Newton's floor where two crossings
    # nearly coincide): smaller parts are round-off
    cut = max(1e-10, 100 * floor)
    x = np.where(np.abs(x.real) < cut, 0.0, x.real) + 1j * np.where(np.abs(x.imag) < cut, 0.0, x.imag)
    units = {key: val for key, val in SPRING_BLOCK_UNITS.items() if key in ("V", "p_c", "omega_c")}
    res = replace(res, units=units, at=("V",),
                  extra={"route": "numeric", "blocks": chain.blocks, "mode": _mode_name(x),
                         "mode_shape": [[float(z.real), float(z.imag)] for z in x],
                         "Lambda_scale": 2 * nf.b_scale, "newton_floor": floor})
    if verdict == "zero" or l2:
        # Λ zero to round-off (or l₂ asked for): the fifth order, from the law's jets to order 5
        res = with_fifth_order(res, nf, chain_sparse_system(chain, p, order=5), degenerate=verdict == "zero")
    return res


def _symbolic_chain_hopf(chain: SpringBlockChain, p: dict, bracket, dps: int):
    """The symbolic route (see :func:`chain_hopf`): the general engine on the chain's sympy system."""
    from landau.derivation.degenerate import with_verdict
    from landau.derivation.general import NumericSystem, normal_form_at, refine_hopf, scan_hopf
    from landau.derivation.hopf import SPRING_BLOCK_UNITS

    system = chain.system
    num = NumericSystem(system, p, chain.equilibrium_values(p))
    y_eq = np.array(chain.equilibrium_values(p))

    def stable(kv: float) -> bool:
        lam = num.eigenvalues(y_eq, kv)
        return bool(np.all(lam.real < 0))

    if bracket is not None:
        windows = [_checked_bracket(bracket)]
    else:
        hi = _first_stable_stiffness(p, chain.blocks, stable)
        windows = [(hi / 4.0 ** j, hi / 4.0 ** (j + 1)) for j in range(20)]
    for a, b in windows:
        hits = scan_hopf(num, a, b, samples=24, y_start=y_eq)
        if hits:
            break
    else:
        raise NoHopfError(f"{system.name}: no Hopf crossing of k below {windows[0][0]:g} N/m")
    p0, y0, lam = max(hits, key=lambda h: h[0])
    shape = _mode_shape(num, p0, abs(lam.imag), y0, chain.slip_indices())
    # normalise the amplitude equation on the block that moves most
    biggest = chain.slip_indices()[int(np.argmax(np.abs(shape)))]
    system_n = replace(system, normalise=biggest)
    num = NumericSystem(system_n, p, chain.equilibrium_values(p))
    jets_cache: dict = {}

    def at(digits: int):
        with mpmath.workdps(digits):
            pc, wc, y = refine_hopf(num, p0, abs(lam.imag), y0)
            return normal_form_at(num, pc, wc, y, jets_cache=jets_cache, params=p), (pc, wc, y)

    first, (pc, wc, y) = at(dps)
    with mpmath.workdps(dps):
        shape = _mode_shape_mp(num, pc, wc, y, chain.slip_indices(), biggest)
    # Λ with its round-off bound; where it vanishes, Λ = 0 (degenerate) and the next order
    res = with_verdict(system_n, p, first, dps, lambda d: at(d)[0])
    units = {key: val for key, val in SPRING_BLOCK_UNITS.items() if key in ("V", "p_c", "omega_c")}
    return replace(res, units=units, at=("V",),
                   extra={"route": "symbolic", "blocks": chain.blocks, "mode": _mode_name(shape),
                          "mode_shape": [[float(z.real), float(z.imag)] for z in shape], **res.extra})
