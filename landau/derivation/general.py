"""Hopf points and their amplitude equation for any smooth system E(p)·ẏ = f(y; p).

The spring–block has closed forms; a general model (the slip mode of an impact oscillator, a
damped stick–slip block, Lorenz-84, a chemical reactor, …) has a numeric equilibrium and a Hopf
parameter that may move it.  :func:`hopf_normal_form` locates the Hopf point and runs the *same*
Fredholm code as the spring–block (:mod:`landau.derivation.fredholm`) on mpmath numbers:

1. the equilibrium is followed across the bracket (Newton from the declared equilibrium, which
   may be a closed form, constants, or a guess built from ``unknown_guess``);
2. a Hopf point is where a complex pair of the pencil (J, E) crosses the imaginary axis.  It is
   detected by the sign of the bialternate-product test function Π_{i<j}(λᵢ + λⱼ), which changes
   sign at *every* crossing — also when another pair is already unstable (the largest real part
   then never changes sign) — and located by bisection on it, then by Newton on
   det(iωE(p) − J(y₀(p), p)) = 0 at ``dps`` digits;
3. the derivatives of f at the point come from truncated Taylor arithmetic on the expression tree
   (:class:`landau.derivation.jets.TaylorJets`; ``jets="symbolic"`` uses sympy's derivatives instead — the
   same numbers, slower for large dense systems);
4. a full (non-diagonal) invertible mass matrix is handled by multiplying the system by E(p_c)⁻¹;
   a parameter-dependent E(p) adds −iω ψE_p q/δ to the linear coefficient.

Convention (:data:`landau.derivation.hopf.GENERAL`): dA/dT = a·(p − p_c)A + b·A|A|² with the critical
mode's ``normalise`` component equal to 1; a = dλ/dp, Λ = 2 Re b (Λ < 0: supercritical),
χ = 2 Im b.  The result also carries Kuznetsov's c₁ = b/⟨q, q⟩ and the first Lyapunov
coefficient l₁ = Re c₁/ω in Kuznetsov's normalisation (⟨q, q⟩ = 1, ⟨p, q⟩ = 1 for ẏ = E⁻¹f;
for a DAE, q is the full-state mode; Kuznetsov 2004, eq. 3.20).  MatCont (``nf_H.m``:
``real(p0'*h21)/2``) and BifurcationKit (its ``l1``) both print Re c₁ = ω·l₁, not divided by ω.

References
----------
Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, §3.5, §10.2.
Govaerts, W. (2000). Numerical Methods for Bifurcations of Dynamical Equilibria, SIAM (the
bialternate product test function).
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). J. Mech. Phys. Solids 58, 27–53 (eq. 20).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any, Mapping, Sequence

import mpmath
import numpy as np
import scipy.linalg
import scipy.optimize
import sympy as sp

from landau.derivation.fredholm import (
    _minor,
    _pencil,
    best_drop,
    cubic_coefficient,
    float64_drop,
    linear_coefficient,
    null_vectors,
    row_dot,
)
from landau.derivation.hopf import GENERAL, HopfResult
from landau.derivation.hopf_refine import refine_hopf
from landau.derivation.jets import Jets, TaylorJets
from landau.errors import InputError, NoHopfError, NonSimpleHopfError, SingularPointError
from landau.support.cx import Cx, as_expr
from landau.support.lambdify import lambdify_positional
from landau.systems.system import DynamicalSystem

#: default working precision of the located point and its coefficients (decimal digits)
DEFAULT_DPS = 50
#: samples of the bracket when looking for crossings
SCAN_SAMPLES = 40


#: largest ratio of eigenvalue moduli that float64 eigenvalues resolve to about 1e-7 relative
#: (beyond it :meth:`NumericSystem.eigenvalues` computes them again with mpmath)
SPREAD_FLOAT64 = 1e9


class NumericSystem:
    """A :class:`DynamicalSystem` with every parameter but the Hopf parameter p given a value.

    Evaluates f, its Jacobian, ∂f/∂p and E(p) in float64 (numpy) and at any mpmath precision,
    and finds equilibria by Newton's method.

    Parameters
    ----------
    system : DynamicalSystem
    params : mapping
        Values of ``system.parameters`` by name (extra names are ignored).
    y_guess : sequence of float, optional
        A starting guess of the equilibrium (else ``system.equilibrium`` with
        ``unknown_guess`` substituted for its unknowns).
    """

    def __init__(self, system: DynamicalSystem, params: Mapping[str, float], y_guess: Sequence[float] | None = None):
        self.sys = system
        self.n = len(system.states)
        missing = [s.name for s in system.parameters if s.name not in params]
        if missing:
            raise InputError(f"{system.name}: missing parameter(s) {', '.join(missing)}")
        try:
            self.params = {s: float(params[s.name]) for s in system.parameters}
        except (TypeError, ValueError):
            raise InputError(f"{system.name}: every parameter value must be a number") from None
        bad = [s.name for s, v in self.params.items() if not math.isfinite(v)]
        if bad:
            raise InputError(f"{system.name}: parameter(s) {', '.join(bad)} must be finite")
        norm = system.normalise
        if isinstance(norm, bool) or not isinstance(norm, (int, np.integer)) or not 0 <= norm < self.n:
            raise InputError(f"{system.name}: normalise must be the index (0 to {self.n - 1}) of a state of "
                             f"{', '.join(s.name for s in system.states)}, got {norm!r}")
        self.p = system.parameter
        Em = system.mass_matrix
        # f and its first derivatives (J, f_p) by Taylor arithmetic: no symbolic differentiation
        self.taylor1 = TaylorJets(system.rhs, [*system.states, self.p], 1)
        self._E = lambdify_positional([self.p, *self.params], Em.tolist(), "mpmath")
        self._Ep = lambdify_positional([self.p, *self.params], Em.diff(self.p).tolist(), "mpmath")
        self._Ef = lambdify_positional([self.p, *self.params], Em.tolist(), "numpy")
        self.mass_depends_on_p = self.p in Em.free_symbols
        self.diagonal_mass = system.mass_is_diagonal
        self._pv = list(self.params.values())
        if y_guess is not None:
            if len(y_guess) != self.n:
                raise InputError(f"{system.name}: the equilibrium guess needs {self.n} values")
            self._guess = lambda p: [float(x) for x in y_guess]
        else:
            eq = list(system.equilibrium)
            if system.unknowns:
                if len(system.unknown_guess) != len(system.unknowns):
                    raise InputError(f"{system.name}: the equilibrium has no closed form; give unknown_guess "
                                     "or an equilibrium guess")
                eq = [as_expr(e).xreplace(dict(zip(system.unknowns, system.unknown_guess, strict=True))) for e in eq]
            fn = lambdify_positional([self.p, *self.params], eq, "numpy")
            self._guess = lambda p: [float(x) for x in fn(p, *self._pv)]

    # --- float64 ------------------------------------------------------------------------------
    def first(self, y, p, as_float: bool):
        """(f, J = ∂f/∂y, f_p = ∂f/∂p) at (y, p), in float64 or at the working precision."""
        t = self.taylor1.at([*y, p], self.params, as_float=as_float)
        n = self.n
        # float64 arrays, or mpmath matrix and lists
        J: Any = np.zeros((n, n)) if as_float else mpmath.zeros(n, n)
        fp: Any = np.zeros(n) if as_float else [mpmath.mpf(0)] * n
        f: Any = np.zeros(n) if as_float else [mpmath.mpf(0)] * n
        for (i,), v in t[0].items():
            f[i] = v
        for (i, j), v in t[1].items():
            if j < n:
                J[i, j] = v
            else:
                fp[i] = v
        return f, J, fp

    def f_float(self, y, p) -> np.ndarray:
        return self.first([float(x) for x in y], float(p), True)[0]

    def J_float(self, y, p) -> np.ndarray:
        return self.first([float(x) for x in y], float(p), True)[1]

    def fp_float(self, y, p) -> np.ndarray:
        return self.first([float(x) for x in y], float(p), True)[2]

    def E_float(self, p) -> np.ndarray:
        return np.array(self._Ef(p, *self._pv), dtype=float).reshape(self.n, self.n)

    def equilibrium_float(self, p: float, guess=None, tol: float = 1e-12, maxit: int = 40) -> np.ndarray:
        """Newton's method on f(y, p) = 0 (float64) from ``guess`` (default: the declared equilibrium)."""
        y = np.array(self._guess(p) if guess is None else guess, dtype=float)
        for _ in range(maxit):
            F, J, _ = self.first(y, float(p), True)
            if not np.all(np.isfinite(F)):
                break
            try:
                dy = np.linalg.solve(J, -F)
            except np.linalg.LinAlgError:
                raise SingularPointError(f"{self.sys.name}: singular Jacobian at {self.p.name} = {p:g}") from None
            y = y + dy
            if np.max(np.abs(dy)) <= tol * (1 + np.max(np.abs(y))):
                if np.all(np.isfinite(y)):
                    return y
        raise SingularPointError(f"{self.sys.name}: no equilibrium found near the guess at {self.p.name} = {p:g}")

    def eigenvalues(self, y, p) -> np.ndarray:
        """Finite eigenvalues of the pencil J(y, p) v = λ E(p) v.

        float64 resolves an eigenvalue only to about eps·max|λ| in absolute terms: where the
        spectrum spans more than :data:`SPREAD_FLOAT64` (a fast eigenvalue −η/M beside a slow pair
        at 1e-7 rad/s: a quasi-dynamic fault cell at the plate rate), the eigenvalues of the same
        float64 matrix E⁻¹J are computed again with mpmath at 50 digits, which resolves the slow
        pair (its sensitivity to the matrix entries' own rounding is small for such graded matrices).
        """
        J, E = self.J_float(y, p), self.E_float(p)
        diagonal = np.count_nonzero(E - np.diag(np.diag(E))) == 0 and np.all(np.diag(E) != 0)
        if diagonal:
            A = J / np.diag(E)[:, None]
            lam = np.linalg.eigvals(A)
        else:
            lam = scipy.linalg.eigvals(J, E)
        lam = lam[np.isfinite(lam)]
        mag = np.abs(lam)
        if diagonal and len(mag) > 1 and np.all(np.isfinite(A)) and mag.max() > 0 \
                and np.min(mag[mag > 0], initial=np.inf) < mag.max() / SPREAD_FLOAT64:
            with mpmath.workdps(50):
                ev = mpmath.eig(mpmath.matrix(A.tolist()), left=False, right=False)
            lam = np.array([complex(e) for e in ev])
        return lam

    # --- mpmath ---------------------------------------------------------------------------------
    def equilibrium_mp(self, p, guess) -> list:
        """Newton's method at the working precision from a float or mp guess."""
        y = [mpmath.mpf(x) for x in guess]
        tol = mpmath.mpf(10) ** (-mpmath.mp.dps + 6)
        for _ in range(60):
            f, J, _ = self.first(y, p, False)
            F = mpmath.matrix(f)
            try:
                dy = mpmath.lu_solve(J, -F)
            except ZeroDivisionError:
                raise SingularPointError(f"{self.sys.name}: singular Jacobian at the equilibrium") from None
            y = [a + b for a, b in zip(y, dy, strict=True)]
            if mpmath.norm(dy, mpmath.inf) <= tol * (1 + max(abs(v) for v in y)):
                return y
        raise SingularPointError(f"{self.sys.name}: equilibrium Newton iteration did not converge at "
                                 f"{self.p.name} = {float(p):.10g}")

    def J_mp(self, y, p) -> mpmath.matrix:
        return self.first(y, p, False)[1]

    def E_mp(self, p) -> mpmath.matrix:
        return mpmath.matrix(self._E(p, *self._pv))

    def Ep_mp(self, p) -> mpmath.matrix:
        return mpmath.matrix(self._Ep(p, *self._pv))


def hopf_test_function(lam: np.ndarray) -> float:
    """Bialternate-product test function Π_{i<j}(λᵢ + λⱼ) with each factor divided by 1 + |λᵢ| + |λⱼ|.

    Real for a real pencil; changes sign when a complex pair crosses the imaginary axis (and at
    neutral saddles λᵢ = −λⱼ real, which the callers reject).  The division keeps the sign and
    avoids overflow.
    """
    prod = 1.0 + 0j
    lam = np.asarray(lam)
    for i in range(len(lam)):
        for j in range(i + 1, len(lam)):
            prod *= (lam[i] + lam[j]) / (1 + abs(lam[i]) + abs(lam[j]))
    return float(prod.real)


def critical_pair(lam: np.ndarray) -> complex | None:
    """The eigenvalue with Im > 0 closest to the imaginary axis (None if all are real)."""
    upper = lam[lam.imag > 1e-10 * (1 + np.abs(lam.real))]
    if upper.size == 0:
        return None
    return complex(upper[np.argmin(np.abs(upper.real))])


def locate_crossing(num: NumericSystem, pa: float, pb: float, ya) -> tuple[float, np.ndarray, complex] | None:
    """Bisect the Hopf test function between pa and pb (float64); None at a neutral saddle."""
    cache = {}

    def g(p):
        y = num.equilibrium_float(p, ya)
        cache[p] = y
        return hopf_test_function(num.eigenvalues(y, p))

    ga, gb = g(pa), g(pb)
    if ga * gb >= 0:               # an end is the root to round-off (its sign is round-off)
        hits = [h for h in (_exact_crossing(num, end, cache[end]) for end in (pa, pb)) if h is not None]
        return min(hits, key=lambda h: abs(h[2].real)) if hits else None
    p0 = scipy.optimize.brentq(g, pa, pb, xtol=1e-13 * max(1.0, abs(pa), abs(pb)), rtol=1e-13)
    y0 = num.equilibrium_float(p0, cache.get(p0, ya))
    lam = critical_pair(num.eigenvalues(y0, p0))
    if lam is None or abs(lam.real) > 1e-6 * abs(lam):
        return None
    return p0, y0, lam


def scan_hopf(num: NumericSystem, lo: float, hi: float, samples: int = SCAN_SAMPLES,
              y_start=None) -> list[tuple[float, np.ndarray, complex]]:
    """Every Hopf crossing in [lo, hi] (float64): (p, y₀, critical eigenvalue), in order of p.

    The equilibrium is followed from ``lo`` (which may be the larger end) by Newton's method
    from the previous sample.  Each pair's crossing changes the sign of the bialternate test
    function, so two crossings between neighbouring samples cancel (weakly coupled identical
    oscillators have nearly equal crossings): where the number of unstable complex pairs changes
    by two or more between samples, the interval is halved until each part holds one crossing
    (:func:`_split_crossings`), and crossings that still coincide are a double Hopf point
    (:class:`~landau.errors.NonSimpleHopfError`).
    """
    ps = np.linspace(lo, hi, samples + 1)
    ys = [num.equilibrium_float(ps[0], y_start)]
    for p in ps[1:]:
        ys.append(num.equilibrium_float(p, ys[-1]))
    lams = [num.eigenvalues(y, p) for y, p in zip(ys, ps, strict=True)]
    tfs = [hopf_test_function(lam) for lam in lams]
    zeros = sum(1 for t in tfs if t == 0)
    if zeros > 2:
        raise InputError(f"{num.sys.name}: the eigenvalues' real parts vanish to round-off at {zeros} of the "
                         f"{len(ps)} scanned values of {num.p.name} in [{min(lo, hi):g}, {max(lo, hi):g}], so no "
                         "isolated crossing can be told: the crossing is below float64's resolution at this scale "
                         "(bring the parameters nearer their physical scale), or the pair stays on the axis")
    found: list[tuple[float, np.ndarray, complex]] = []
    on_grid: set[int] = set()
    for i in range(len(ps)):
        # a grid point that is the crossing itself (the test function exactly 0 there, or, at an
        # end of the scan, the pair on the axis to round-off): the exact root, not a bracket
        end = i in (0, len(ps) - 1)
        if tfs[i] == 0 or (end and _end_on_axis(lams[i], lams[1 if i == 0 else i - 1])):
            hit = _exact_crossing(num, float(ps[i]), ys[i])
            if hit is not None:
                found.append(hit)
                on_grid.add(i)
    pairs = [unstable_pairs(lam) for lam in lams]
    for i in range(len(ps) - 1):
        if {i, i + 1} & on_grid:
            continue
        if abs(pairs[i] - pairs[i + 1]) >= 2:
            # several pairs cross between two samples: their sign changes cancel (an even number)
            # or add up in the test function, so the interval is halved until each part holds one
            found += _split_crossings(num, float(ps[i]), ys[i], pairs[i], float(ps[i + 1]), ys[i + 1], pairs[i + 1])
        elif tfs[i] * tfs[i + 1] < 0:
            hit = locate_crossing(num, min(ps[i], ps[i + 1]), max(ps[i], ps[i + 1]), ys[i])
            if hit is not None:
                found.append(hit)
    return sorted(found, key=lambda h: h[0] if lo <= hi else -h[0])


def unstable_pairs(lam: np.ndarray) -> int:
    """The number of complex pairs with Re λ > 0 (each counted once, by its member with Im > 0)."""
    lam = np.asarray(lam)
    upper = lam[lam.imag > 1e-10 * (1 + np.abs(lam.real))]
    return int(np.count_nonzero(upper.real > 0))


#: two pairs whose crossings lie closer than this fraction of the parameter cannot be told apart
#: by the float64 scan (nor refined apart from its starting points): the crossing is double
DOUBLE_CROSSING = 1e-11


def _split_crossings(num: NumericSystem, pa: float, ya, na: int, pb: float, yb,
                     nb: int) -> list[tuple[float, np.ndarray, complex]]:
    """The crossings between pa and pb, where the number of unstable pairs changes by ≥ 2.

    The interval is halved (the equilibrium followed from pa) until each part changes the count by
    at most one pair, then each such part is bisected by :func:`locate_crossing`.  Two pairs that
    still cross together in a part narrower than :data:`DOUBLE_CROSSING` of the parameter are a
    double, non-simple crossing (as for identical uncoupled oscillators): no single-mode amplitude
    equation applies there, and :class:`~landau.errors.NonSimpleHopfError` says so.
    """
    found: list[tuple[float, np.ndarray, complex]] = []
    stack = [(pa, ya, na, pb, yb, nb)]
    while stack:
        a, y_a, n_a, b, y_b, n_b = stack.pop()
        if abs(n_a - n_b) == 1:
            hit = locate_crossing(num, min(a, b), max(a, b), y_a)
            if hit is not None:
                found.append(hit)
            continue
        if n_a == n_b:
            continue
        if abs(b - a) <= DOUBLE_CROSSING * max(abs(a), abs(b)):
            m = 0.5 * (a + b)
            raise NonSimpleHopfError(
                f"{num.sys.name}: {abs(n_a - n_b)} complex pairs cross the imaginary axis together at "
                f"{num.p.name} = {m:.12g} (within {DOUBLE_CROSSING:g} of it): a double, non-simple Hopf "
                "crossing (e.g. identical uncoupled oscillators), where no single-mode amplitude equation applies")
        m = 0.5 * (a + b)
        y_m = num.equilibrium_float(m, y_a)
        n_m = unstable_pairs(num.eigenvalues(y_m, m))
        stack += [(m, y_m, n_m, b, y_b, n_b), (a, y_a, n_a, m, y_m, n_m)]
    return found


def _end_on_axis(lam: np.ndarray, lam_next: np.ndarray) -> bool:
    """Whether the critical pair at a scan's end lies on the imaginary axis to round-off: its real
    part below :data:`ON_AXIS` of its modulus and below 1e-8 of its real part at the next sample
    (the pair moves across the bracket; round-off does not)."""
    pair, nxt = critical_pair(lam), critical_pair(lam_next)
    if pair is None or nxt is None:
        return False
    return abs(pair.real) <= ON_AXIS * abs(pair) and abs(pair.real) <= 1e-8 * abs(nxt.real)


#: a critical pair whose real part is below this fraction of its modulus lies on the imaginary
#: axis to round-off: the point is taken as the crossing itself
ON_AXIS = 1e-10


def _exact_crossing(num: NumericSystem, p: float, y) -> tuple[float, np.ndarray, complex] | None:
    """(p, y₀, λ) when a complex pair lies on the imaginary axis at p to round-off
    (|Re λ| ≤ :data:`ON_AXIS`·|λ|), else None."""
    lam = critical_pair(num.eigenvalues(y, p))
    if lam is None or abs(lam.real) > ON_AXIS * abs(lam):
        return None
    return p, np.asarray(y, dtype=float), lam


def _symbolic_tensors(num: NumericSystem, y0, pc, jets_cache: dict) -> dict[int, dict]:
    """Derivative tensors of f in (y, p) up to order 3 from sympy's derivatives (lambdified)."""
    sysm = num.sys
    key = "symbolic"
    if key not in jets_cache:
        y0s = tuple(sp.Symbol(f"{s.name}__eq", real=True) for s in sysm.states)
        probe = DynamicalSystem(sysm.name, sysm.states, sysm.rhs, sysm.mass, sysm.parameter, y0s)
        jets = Jets(probe)
        orders = {m: jets.order(m) for m in (1, 2, 3)}
        fp, Jp = jets.parameter_derivatives()
        n = num.n
        entries = []
        for m in (1, 2, 3):
            entries += [((m, k), v) for k, v in orders[m].items()]
        entries += [((1, (i, n)), fp[i]) for i in range(n)]
        entries += [((2, (i, j, n)), Jp[i][j]) for i in range(n) for j in range(n)]
        atoms = dict(jets.atoms)

        def expand(e):
            for _ in range(10):
                if not (as_expr(e).free_symbols & atoms.keys()):
                    return e
                e = as_expr(e).xreplace(atoms)
            return e
        fn = lambdify_positional([*y0s, sysm.parameter, *num.params], [expand(v) for _, v in entries], "mpmath")
        jets_cache[key] = ([k for k, _ in entries], fn)
    keys, fn = jets_cache[key]
    vals = fn(*y0, pc, *num._pv)
    tens: dict[int, dict] = {1: {}, 2: {}, 3: {}}
    for (m, k), v in zip(keys, vals, strict=True):
        v = mpmath.mpmathify(v)
        if v != 0:
            tens[m][k] = v
    return tens


def _taylor_tensors(num: NumericSystem, y0, pc, jets_cache: dict) -> dict[int, dict]:
    if "taylor" not in jets_cache:
        jets_cache["taylor"] = TaylorJets(num.sys.rhs, [*num.sys.states, num.p], 3)
    tj = jets_cache["taylor"]
    return tj.at([*y0, pc], num.params)


def normal_form_at(num: NumericSystem, pc, wc, y0, *, jets: str = "taylor", jets_cache: dict | None = None,
                   params: Mapping[str, float] | None = None) -> HopfResult:
    """The amplitude equation at a located Hopf point (p_c, ω_c, y₀) — mpmath numbers at the working precision.

    Parameters
    ----------
    num : NumericSystem
    pc, wc : mpmath numbers
        The Hopf parameter and angular frequency (ω_c > 0).
    y0 : list of mpmath numbers
        The equilibrium at p_c.
    jets : {"taylor", "symbolic"}
        How the derivatives of f are computed.
    jets_cache : dict, optional
        Reused between calls on the same system (continuation).

    Returns
    -------
    HopfResult
    """
    n = num.n
    cache = {} if jets_cache is None else jets_cache
    if jets == "taylor":
        tens = _taylor_tensors(num, y0, pc, cache)
    elif jets == "symbolic":
        tens = _symbolic_tensors(num, y0, pc, cache)
    else:
        raise InputError(f"jets must be 'taylor' or 'symbolic', got {jets!r}")
    J = [[mpmath.mpf(0)] * n for _ in range(n)]
    fp = [mpmath.mpf(0)] * n
    Jp = [[mpmath.mpf(0)] * n for _ in range(n)]
    B2: dict = {}
    C3: dict = {}
    for (i, j), v in tens[1].items():
        if j < n:
            J[i][j] = v
        else:
            fp[i] = v
    for k, v in tens[2].items():
        if k[2] == n:
            if k[1] < n:
                Jp[k[0]][k[1]] = v
        else:
            B2[k] = v
    for k, v in tens[3].items():
        if k[-1] < n:
            C3[k] = v
    Em = num.E_mp(pc)
    Ep = num.Ep_mp(pc) if num.mass_depends_on_p else None
    if num.diagonal_mass:
        E = [Em[i, i] for i in range(n)]
    else:
        # E·ẏ = f  ⇔  ẏ = E⁻¹f: every tensor, f_p and J_p are multiplied by E⁻¹ (f = 0 at y₀)
        try:
            Einv = Em ** -1
        except ZeroDivisionError:
            raise InputError(f"{num.sys.name}: a non-diagonal mass matrix must be invertible "
                             "(write a DAE with a diagonal E)") from None
        L = lambda vec: [sum(Einv[i, k] * vec[k] for k in range(n)) for i in range(n)]
        J = [list(col) for col in zip(*[L([J[i][j] for i in range(n)]) for j in range(n)], strict=True)]
        Jp = [list(col) for col in zip(*[L([Jp[i][j] for i in range(n)]) for j in range(n)], strict=True)]
        fp = L(fp)

        def left(t):
            out: dict = {}
            for key, v in t.items():
                for i in range(n):
                    if Einv[i, key[0]] != 0:
                        k2 = (i, *key[1:])
                        out[k2] = out.get(k2, 0) + Einv[i, key[0]] * v
            return out
        B2, C3 = left(B2), left(C3)
        if Ep is not None:
            Ep = Einv * Ep
        E = [mpmath.mpf(1)] * n
    A = _pencil(J, E, wc)

    def absdet(rows):
        if not rows:
            return 1.0
        m = mpmath.matrix([[mpmath.mpc(z.re, z.im) for z in r] for r in rows])
        try:
            return float(abs(mpmath.det(m)))
        except (ZeroDivisionError, TypeError):  # mpmath's LU fails on an exactly zero column
            return 0.0

    normalise = num.sys.normalise
    drop = float64_drop(A, normalise)
    if drop is not None:
        r, c = drop
    else:   # no clear float64 null space, or q[normalise] small: n determinants each at the working precision
        r, c = best_drop(A, normalise, absdet)
        _check_normalise(num, A, r, normalise, absdet)
    vec = null_vectors(J, E, wc, normalise, r, c)
    try:
        a = linear_coefficient(vec, J, Jp, fp, B2)
    except ZeroDivisionError:
        raise SingularPointError(f"{num.sys.name}: ψ·E·q = 0 at {num.p.name} = {float(pc):.10g}: the critical "
                                 "eigenvalue is not simple (no amplitude equation of a simple Hopf point)") from None
    if Ep is not None:
        # E(p_c + ε²p₂)·ẏ adds −p₂ iω E_p q A to the resonant forcing at O(ε³)
        Epq = [Cx(0, 0)] * n
        for i in range(n):
            for j in range(n):
                if Ep[i, j] != 0:
                    Epq[i] = Epq[i] + vec.q[j] * Ep[i, j]
        a = a - row_dot(vec.psi, Epq) / vec.delta * Cx(0, wc)
    b = cubic_coefficient(vec, J, E, wc, B2, C3, mpmath.mpf(1) / 2)
    qq = sum(z.re ** 2 + z.im ** 2 for z in vec.q)
    c1 = complex(float(b.re / qq), float(b.im / qq))
    Lam = float(2 * b.re)
    _verify_crossing(num, pc, wc, y0, complex(float(a.re), float(a.im)))
    return HopfResult(
        system=num.sys.name, parameter=num.p.name, p_c=float(pc), omega_c=float(wc),
        equilibrium=tuple(float(x) for x in y0), dlambda_dp=complex(float(a.re), float(a.im)),
        Lambda=Lam, chi=float(2 * b.im), convention=GENERAL, normalise=num.sys.states[normalise].name,
        l1=float(b.re / qq / wc), c1=c1, params={s.name: v for s, v in num.params.items()} if params is None
        else dict(params),
    )


def _check_normalise(num: NumericSystem, A, r: int, normalise: int, absdet) -> None:
    """Refuse by name a ``normalise`` state whose component of the critical mode q is 0 (q cannot
    be scaled to q[normalise] = 1).  The cofactors of a row of A = iωE − J are proportional to q,
    so the cofactor in the ``normalise`` column is compared with the largest one."""
    n = len(A)
    if n < 2:
        return
    tiny = 10.0 ** (-(mpmath.mp.dps // 2))
    m_n = absdet(_minor(A, r, normalise))
    entries = [abs(complex(float(z.re), float(z.im))) for row in A for z in row]
    scale = max(entries) ** (n - 1) if entries else 1.0
    if m_n > tiny * scale:
        return
    cof = [[absdet(_minor(A, i, j)) for j in range(n)] for i in range(n)]
    best_row = max(range(n), key=lambda i: max(cof[i]))
    top = max(cof[best_row])
    if top == 0 or m_n > tiny * top:
        return
    names = [s.name for s in num.sys.states]
    carried = [names[j] for j in range(n) if cof[best_row][j] > tiny * top]
    raise InputError(f"{num.sys.name}: the state {names[normalise]!r} chosen to normalise the critical mode "
                     f"(normalise={normalise}) has no component in it at the Hopf point; normalise on one of "
                     f"{', '.join(carried)} (DynamicalSystem(..., normalise=INDEX))")


def _verify_crossing(num: NumericSystem, pc, wc, y0, dlambda_dp: complex) -> None:
    """A Hopf point is verified before it is returned: the pencil has the pair ±iω_c at (y₀, p_c)
    (to 1e-6 of the spectrum's scale, in float64) and the pair crosses, Re dλ/dp ≠ 0; else
    :class:`~landau.errors.SingularPointError`."""
    p, w = float(pc), float(wc)
    y = np.array([float(v) for v in y0])
    try:
        lam = num.eigenvalues(y, p)
    except (np.linalg.LinAlgError, ValueError):
        return                     # the float64 pencil cannot be formed: the mpmath refinement stands
    scale = max(w, float(np.max(np.abs(lam))) if lam.size else 0.0, 1e-300)
    if not (w > 0 and lam.size and np.min(np.abs(lam - 1j * w)) <= 1e-6 * scale):
        near = complex(lam[np.argmin(np.abs(lam - 1j * w))]) if lam.size else None
        raise SingularPointError(f"{num.sys.name}: the point {num.p.name} = {p:.10g} is not a Hopf point: no "
                                 f"eigenvalue pair ±i·{w:.6g} (nearest eigenvalue {near})")
    if not (abs(dlambda_dp.real) > 1e-12 * abs(dlambda_dp)):
        raise SingularPointError(f"{num.sys.name}: at {num.p.name} = {p:.10g} the pair ±i·{w:.6g} touches the "
                                 "imaginary axis without crossing it (Re dλ/dp = 0): not a Hopf bifurcation")


def hopf_normal_form(system: DynamicalSystem, params: Mapping[str, float] | None, bracket: tuple[float, float],
                     dps: int = DEFAULT_DPS, *, equilibrium_guess: Sequence[float] | None = None,
                     jets: str = "taylor", samples: int = SCAN_SAMPLES, l2: bool = False) -> HopfResult:
    """Locate the Hopf point of ``system`` in its parameter inside ``bracket`` and derive its amplitude equation.

    Parameters
    ----------
    system : DynamicalSystem
        E(p)·ẏ = f(y; p); E diagonal (possibly singular: a DAE) or a full invertible matrix.
    params : mapping or None
        Values of every other parameter, by name (None or {} if the Hopf parameter is the only one).
    bracket : (float, float)
        Interval of the Hopf parameter holding exactly one Hopf point (other eigenvalue pairs may
        be unstable anywhere in it: the crossing pair is followed).  The equilibrium is followed
        from ``bracket[0]`` to ``bracket[1]`` (either order).
    dps : int
        Working precision (decimal digits) of the located point and its coefficients.
    equilibrium_guess : sequence of float, optional
        Starting guess of the equilibrium at ``bracket[0]`` (default: ``system.equilibrium``,
        which may be a closed form, constants, or contain ``unknowns`` with ``unknown_guess``).
    jets : {"taylor", "symbolic"}
        Derivatives by Taylor arithmetic (default; fast for large dense systems) or by sympy.
    samples : int
        Number of intervals the bracket is scanned in for crossings.
    l2 : bool
        Also compute the second Lyapunov coefficient (:func:`second_lyapunov`; wanted at or near
        Λ = 0, where l₁ says nothing).

    Returns
    -------
    HopfResult
        With ``l1`` and ``c1`` in Kuznetsov's normalisation (l₁ = Re c₁/ω; MatCont and
        BifurcationKit print Re c₁), and ``l2`` = Re c₂ if asked for.

    Raises
    ------
    NoHopfError
        No complex pair crosses the imaginary axis in the bracket.
    InputError
        Bad parameters, or several Hopf points in the bracket (the message lists them).
    SingularPointError
        If the Newton refinement of the Hopf point fails.
    NonSimpleHopfError
        Two pairs cross together (a double, non-simple Hopf point).

    References
    ----------
    Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, §3.5.
    Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). J. Mech. Phys. Solids 58, 27–53,
    Sec. 2.2 (the Fredholm route, written here for a general parameter).
    """
    num = NumericSystem(system, params or {}, equilibrium_guess)
    try:
        first, last = map(float, bracket)
    except (TypeError, ValueError):
        raise InputError(f"{system.name}: bracket must be two numbers, got {bracket!r}") from None
    lo, hi = sorted((first, last))
    if not (math.isfinite(lo) and math.isfinite(hi)) or lo == hi:
        raise InputError(f"{system.name}: bracket must be two different finite numbers, got {bracket!r}")
    hits = scan_hopf(num, first, last, samples)
    if not hits:
        raise NoHopfError(f"{system.name}: no Hopf crossing of {system.parameter.name} in [{lo:g}, {hi:g}]")
    if len(hits) > 1:
        raise InputError(f"{system.name}: {len(hits)} Hopf points in [{lo:g}, {hi:g}] (at "
                         + ", ".join(f"{h[0]:.8g}" for h in hits) + "); narrow the bracket or use "
                         "landau.analyses.continuation.equilibrium_branch")
    p0, y0, lam = hits[0]
    jets_cache: dict = {}

    def at(digits: int) -> HopfResult:
        with mpmath.workdps(digits):
            pc, wc, y = refine_hopf(num, p0, abs(lam.imag), y0)
            return normal_form_at(num, pc, wc, y, jets=jets, jets_cache=jets_cache, params=params)

    from landau.derivation.degenerate import with_verdict

    # Λ with its round-off bound; where it vanishes, Λ = 0 (degenerate) and the next order (l₂)
    res = with_verdict(system, params, at(dps), dps, at)
    if l2 and res.l2 is None:
        res = replace(res, l2=second_lyapunov(system, params, res, max(dps, 40)))
    return res


def _frozen_equilibrium(system: DynamicalSystem, params: Mapping[str, float] | None, result: HopfResult):
    """(probe system, values, p_c) for the symbolic-jet routes of :mod:`landau.derivation.lyapunov` at a located point.

    The probe's equilibrium is a set of fresh unknowns whose values are the numeric equilibrium
    at p_c (refined at the working precision), so those routes need no closed form.
    """
    y0s = tuple(sp.Symbol(f"{s.name}__eq", real=True) for s in system.states)
    at = dict(zip(system.states, y0s, strict=True))
    probe = DynamicalSystem(system.name, system.states, system.rhs, system.mass, system.parameter, y0s,
                            normalise=system.normalise, unknowns=y0s,
                            unknown_equations=tuple(as_expr(f).xreplace(at) for f in system.rhs))
    values: dict[str, Any] = dict(params or {})
    num = NumericSystem(system, params or {}, result.equilibrium)
    pc, _, y = refine_hopf(num, result.p_c, result.omega_c, result.equilibrium)
    values.update({s.name: v for s, v in zip(y0s, y, strict=True)})
    return probe, values, pc


def kuznetsov_check(system: DynamicalSystem, params: Mapping[str, float] | None, result: HopfResult,
                    dps: int = 40) -> HopfResult:
    """Kuznetsov's projection formula (:func:`landau.derivation.lyapunov.first_lyapunov`) at a located Hopf point.

    Works without a closed-form equilibrium: the numeric equilibrium of ``result`` is passed to
    the projection route as the values of fresh unknowns, at the exact p_c (no re-location), and
    the transversality is taken from ``result`` (the projection route would move p with the
    equilibrium frozen).  Needs a diagonal, invertible E.

    Parameters
    ----------
    system : DynamicalSystem
    params : mapping or None
        The other parameters' values, by name.
    result : HopfResult
        The point, from :func:`hopf_normal_form` or :func:`landau.analyses.continuation.equilibrium_branch`.
    dps : int
        Working precision (≥ 30).

    Returns
    -------
    HopfResult
        l₁, c₁, Λ = 2 Re c₁/|q_n|², χ = 2 Im c₁/|q_n|² and a = dλ/dp from ``result``, so that
        C = 2|q_n| sqrt(|Re a|/|Re c₁|).

    References
    ----------
    Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, eq. (3.20).
    """
    from landau.derivation.lyapunov import first_lyapunov

    with mpmath.workdps(dps):
        probe, values, pc = _frozen_equilibrium(system, params, result)
        res = first_lyapunov(probe, values, pc, omega_c=result.omega_c, dps=dps, relocate=False)
    return replace(res, dlambda_dp=result.dlambda_dp)


def second_lyapunov(system: DynamicalSystem, params: Mapping[str, float] | None, result: HopfResult,
                    dps: int = 40) -> float | None:
    """l₂ = Re c₂ (Kuznetsov's normalisation, not divided by ω) at a located Hopf point by
    :func:`landau.derivation.lyapunov.lyapunov_coefficients`.

    The numeric equilibrium is passed as the values of fresh unknowns (as in
    :func:`kuznetsov_check`), so no closed form is needed; the point is not re-located (the
    equilibrium is frozen at p_c, as in :func:`kuznetsov_check`).
    """
    from landau.derivation.degenerate import ode_on_constraint
    from landau.derivation.lyapunov import lyapunov_coefficients

    # a DAE (zero mass entry) as the ODE with the same flow on its constraint manifold
    system = ode_on_constraint(system, dict(params or {}), result.p_c, max(abs(result.omega_c), 1e-300))
    with mpmath.workdps(dps):
        probe, values, pc = _frozen_equilibrium(system, params, result)
        out = lyapunov_coefficients(probe, values, pc, dps=dps, omega_c=result.omega_c, relocate=False)
    return None if out.l2 is None else float(out.l2)
