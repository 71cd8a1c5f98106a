"""The first Lyapunov coefficient by Kuznetsov's projection formula — the independent check.

This route shares nothing with the Fredholm route (:mod:`landau.derivation.fredholm`,
:mod:`landau.derivation.multiscale`) except the exact symbolic jets of the right-hand side
(:class:`landau.derivation.jets.Jets`).  Everything else is done numerically with mpmath
(default 40 digits):

* the descriptor system E·ẏ = f(y; p) is turned into ẏ = E⁻¹f (needs every E_ii ≠ 0, i.e.
  M > 0 for the spring–block);
* the Hopf point is re-located from the eigenvalues of A(p) = E⁻¹ ∂f/∂y (secant on
  Re λ(p) = 0, starting from the caller's estimate);
* q and p come from mpmath's eigen-solver: A q = iω q, Aᵀ p = −iω p, ⟨p, q⟩ = p̄ᵀq = 1
  (not from the engine's structural null vectors);
* Kuznetsov, *Elements of Applied Bifurcation Theory* (3rd ed.), eqs (3.20)/(5.39):

      c₁ = ½ ⟨p, C(q,q,q̄) − 2 B(q, A⁻¹B(q,q̄)) + B(q̄, (2iω − A)⁻¹ B(q,q))⟩,   l₁ = Re c₁ / ω;

* the transversality μ'(p_c) = d Re λ / dp from eigenvalues at p_c ± h, p_c ± 2h
  (central differences with one Richardson step).

The normal form ż = (μ + iω) z + c₁ z|z|² has the cycle |z|² = −μ/Re c₁, and the state
y ≈ z q + c.c., so the amplitude of component ``normalise`` (the slip X of the
spring–block) per sqrt|p − p_c| is

    C_K = 2 |q_X| sqrt(|μ'| / |Re c₁|),

independent of how q is scaled.  l₁ < 0: supercritical (stable cycle for μ > 0);
l₁ > 0: subcritical.  For the spring–block, sign(l₁) must equal sign(Λ) and C_K must
equal the engine's C = 2 sqrt(2Γ̄/|Λ|) (Putelat et al. 2010, eq. 23).
"""

from __future__ import annotations

import itertools
import math
from typing import Any, Mapping, Sequence

import mpmath
import sympy as sp

from landau.derivation.hopf import GENERAL, HopfResult, spring_block_result
from landau.derivation.jets import Jets
from landau.errors import InputError, NoHopfError, SingularPointError
from landau.support.cx import as_expr
from landau.support.lambdify import lambdify_positional
from landau.systems.system import DynamicalSystem, SpringBlock

#: digits used when the caller does not say (≥ 30: far above the float64 engine it checks)
DEFAULT_DPS = 40


class _NumericJets:
    """The jets of E·ẏ = f as mpmath numbers at fixed parameter values, as functions of p."""

    def __init__(self, system: DynamicalSystem, jets: Jets, values: Mapping[sp.Symbol, Any], max_order: int = 3):
        self.n = len(system.states)
        self.p = system.parameter
        self.max_order = max_order
        orders = {m: jets.order(m) for m in range(1, max_order + 1)}
        atoms = dict(jets.atoms)  # after building the orders: every atom they use is defined

        def expand(e: sp.Expr) -> sp.Expr:  # atoms written out in the model's symbols (may nest)
            for _ in range(10):
                if not (e.free_symbols & atoms.keys()):
                    return e
                e = e.xreplace(atoms)
            raise InputError("jets: atom definitions are circular")

        self._jets = jets

        self.keys = {m: list(t) for m, t in orders.items()}
        exprs = [as_expr(e) for e in system.mass]
        for m in range(1, max_order + 1):
            exprs += [expand(as_expr(orders[m][key])) for key in self.keys[m]]
        free = set().union(*(e.free_symbols for e in exprs)) - {self.p}
        missing = sorted(s.name for s in free if s not in values)
        if missing:
            raise InputError(f"{system.name}: no value for {', '.join(missing)}")
        syms = sorted(free, key=lambda s: s.name)
        self._fn = lambdify_positional([self.p, *syms], exprs, modules="mpmath")
        self._vals = [values[s] for s in syms]

    def expand(self, e: sp.Expr) -> sp.Expr:
        """``e`` with the jets' atoms (including any defined since construction) written out."""
        atoms = self._jets.atoms
        for _ in range(10):
            if not (e.free_symbols & atoms.keys()):
                return e
            e = e.xreplace(atoms)
        raise InputError("jets: atom definitions are circular")

    def raw(self, p) -> tuple[list, dict[int, dict[tuple, Any]]]:
        """(E diagonal, {order: {key: value}}) at parameter p, unscaled (E may have zeros)."""
        with mpmath.workdps(mpmath.mp.dps):
            out = self._fn(mpmath.mpf(p), *self._vals)
        n = self.n
        pos = n
        tens: dict[int, dict[tuple, Any]] = {}
        for m in range(1, self.max_order + 1):
            tens[m] = {}
            for key in self.keys[m]:
                tens[m][key] = mpmath.mpf(out[pos])
                pos += 1
        return [mpmath.mpf(x) for x in out[:n]], tens

    def at(self, p) -> tuple[mpmath.matrix, list, dict[int, dict[tuple, Any]]]:
        """(A = E⁻¹J, E diagonal, {order: {key: E⁻¹-scaled value}}) at parameter p."""
        with mpmath.workdps(mpmath.mp.dps):
            out = self._fn(mpmath.mpf(p), *self._vals)
        n = self.n
        E = [mpmath.mpf(x) for x in out[:n]]
        if any(e == 0 for e in E):
            raise InputError("Kuznetsov route needs an ODE: every mass entry must be non-zero (M > 0); "
                             "the quasi-static limit M = 0 is a DAE")
        pos = n
        tens: dict[int, dict[tuple, Any]] = {}
        for m in range(1, self.max_order + 1):
            tens[m] = {}
            for key in self.keys[m]:
                tens[m][key] = mpmath.mpf(out[pos]) / E[key[0]]
                pos += 1
        A = mpmath.matrix(n, n)
        for (i, j), val in tens[1].items():
            A[i, j] = val
        return A, E, tens


def _form(tensor: Mapping[tuple, Any], vecs: Sequence[Sequence[Any]], n: int) -> list:
    """Σ_{j₁…j_m} D_{i j₁…j_m} a¹_{j₁}…a^m_{j_m} over a symmetric tensor stored on sorted keys."""
    out = [mpmath.mpc(0)] * n
    for key, val in tensor.items():
        i, idx = key[0], key[1:]
        for perm in set(itertools.permutations(idx)):
            term = val
            for slot, j in enumerate(perm):
                term = term * vecs[slot][j]
            out[i] += term
    return out


def _solve(Amat: mpmath.matrix, rhs: Sequence[Any]) -> list:
    return list(mpmath.lu_solve(Amat, mpmath.matrix(list(rhs))))


def _critical_eig(A: mpmath.matrix, omega_hint: float | None):
    """The eigenvalue (with Im > 0) of the critical pair."""
    ev = mpmath.eig(A, left=False, right=False)
    upper = [lam for lam in ev if mpmath.im(lam) > 0]
    if not upper:
        raise NoHopfError("no complex eigenvalue pair: not a Hopf point")
    if omega_hint is not None:
        return min(upper, key=lambda lam: abs(lam - mpmath.mpc(0, omega_hint)))
    return max(upper, key=lambda lam: mpmath.re(lam))


def _relocate(nj: _NumericJets, p0, omega_hint, tol) -> Any:
    """Secant on Re λ(p) = 0 from the estimate p0 (the Hopf point, from the eigenvalues)."""
    g = lambda p: mpmath.re(_critical_eig(nj.at(p)[0], omega_hint))
    pa, pb = mpmath.mpf(p0), mpmath.mpf(p0) * (1 + mpmath.mpf("1e-7")) + mpmath.mpf("1e-30")
    ga, gb = g(pa), g(pb)
    for _ in range(60):
        if gb == ga:
            break
        pc = pb - gb * (pb - pa) / (gb - ga)
        pa, ga = pb, gb
        pb, gb = pc, g(pc)
        if abs(pb - pa) <= tol * abs(pb):
            return pb
    raise NoHopfError(f"Hopf point not found near p = {float(p0):.6g} (Re λ = {float(gb):.3g})")



def numeric_values(system: DynamicalSystem, values: Mapping[sp.Symbol | str, Any]) -> dict[sp.Symbol, Any]:
    """``values`` (by symbol or name) as mpmath numbers keyed by the system's symbols; names the
    system does not use (e.g. g when σ is given) are dropped."""
    by_name = {s.name: s for s in (*system.parameters, *system.unknowns)}
    vals: dict[sp.Symbol, Any] = {}
    for key, val in values.items():
        sym = key if isinstance(key, sp.Symbol) else by_name.get(key)
        if sym is not None:
            vals[sym] = val if isinstance(val, mpmath.mpf) else mpmath.mpf(val)
    return vals


def equilibrium_floats(system: DynamicalSystem, pc, vals: Mapping[sp.Symbol, Any], dps: int) -> list[float]:
    """The declared equilibrium at p = p_c and the given values, as floats (NaN where it does not
    evaluate to a number)."""
    eq = []
    for e in system.equilibrium:
        e = as_expr(e).xreplace({system.parameter: sp.Float(str(pc), dps)})
        e = e.xreplace({s: sp.Float(str(v), dps) for s, v in vals.items()})
        try:
            eq.append(float(e))
        except TypeError:
            eq.append(float("nan"))
    return eq

def _check_dps(dps: int) -> None:
    if dps < 30:
        raise InputError(f"dps must be >= 30 for the Kuznetsov check, got {dps}")


def _critical_pair(system: DynamicalSystem, values, jets, p_c, omega_c, dps: int, relocate: bool, max_order: int):
    """At the working precision: the numeric parameter values, the jets to ``max_order``, the
    (re-located) Hopf parameter p_c, the Jacobian A and derivative tensors there, ω and
    Kuznetsov's critical eigenvectors q (⟨q, q⟩ = 1) and p̄ (⟨p, q⟩ = p̄ᵀq = 1).  Raises
    NoHopfError where the critical eigenvalue is not on the imaginary axis."""
    vals = numeric_values(system, values)
    nj = _NumericJets(system, jets or Jets(system), vals, max_order=max_order)
    n = nj.n
    pc = _relocate(nj, p_c, omega_c, mpmath.mpf(10) ** (-(dps - 8))) if relocate else mpmath.mpf(p_c)
    A, _, tens = nj.at(pc)
    ev, EL, ER = mpmath.eig(A, left=True, right=True)
    lam_c = _critical_eig(A, omega_c)
    i_c = min(range(n), key=lambda i: abs(ev[i] - lam_c))
    lam = ev[i_c]
    if abs(mpmath.re(lam)) > mpmath.mpf(10) ** (-(dps // 2)) * abs(lam):
        raise NoHopfError(f"not a Hopf point: critical eigenvalue {complex(lam)} at p = {float(pc):.10g}")
    q = [ER[i, i_c] for i in range(n)]
    qn = mpmath.sqrt(sum(abs(z) ** 2 for z in q))
    q = [z / qn for z in q]                       # ⟨q, q⟩ = 1
    wl = [EL[i_c, j] for j in range(n)]           # w A = iω w, i.e. p̄ᵀ ∝ w
    wq = sum(a * b for a, b in zip(wl, q, strict=True))
    pbar = [a / wq for a in wl]                   # ⟨p, q⟩ = p̄ᵀ q = 1
    return vals, nj, pc, A, tens, mpmath.im(lam), q, pbar


def first_lyapunov(system: DynamicalSystem, values: Mapping[sp.Symbol | str, Any], p_c: float, *,
                   omega_c: float | None = None, jets: Jets | None = None, dps: int = DEFAULT_DPS,
                   relocate: bool = True, rel_step: float = 1e-5) -> HopfResult:
    """l₁ and C_K of the Hopf point of ``system`` near ``p_c`` (generic entry point).

    Parameters
    ----------
    system : DynamicalSystem
        E·ẏ = f(y; p) with every mass entry non-zero.
    values : mapping
        Every parameter of the system (by symbol or name) and, where the equilibrium has no
        closed form, its ``unknowns`` (the numeric equilibrium).
    p_c : float
        Estimate of the Hopf parameter (re-located from the eigenvalues unless
        ``relocate=False``).
    omega_c : float, optional
        Estimate of the frequency, used only to pick the critical eigenvalue pair.
    jets : Jets, optional
        The system's symbolic jets (built if not given).
    dps : int
        Working precision (≥ 30).
    relocate : bool
        Whether to re-locate p_c from the eigenvalues.
    rel_step : float
        Relative step of the finite differences of λ(p).

    Returns
    -------
    HopfResult
        In the general convention (critical mode with ``normalise`` component 1):
        ``l1`` = Re c₁/ω, ``c1`` (⟨q, q⟩ = 1, ⟨p, q⟩ = 1), ``dlambda_dp`` from eigenvalues at
        p_c ± h, p_c ± 2h (``dmu_dp`` its real part), Λ = 2 Re c₁/|q_n|², χ = 2 Im c₁/|q_n|²,
        so ``C`` = 2|q_n| sqrt(|μ'|/|Re c₁|); fields ``q_norm`` = |q_n| and ``dps``.

    References
    ----------
    Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer,
    eqs (3.20), (5.39).
    """
    _check_dps(dps)
    with mpmath.workdps(dps):
        vals, nj, pc, A, tens, om, q, pbar = _critical_pair(system, values, jets, p_c, omega_c, dps, relocate, 3)
        n = nj.n
        # residual checks: the eigen-solver, not an assumption, supplies q and p
        res_q = max(abs(sum(A[i, j] * q[j] for j in range(n)) - 1j * om * q[i]) for i in range(n))
        res_p = max(abs(sum(pbar[i] * A[i, j] for i in range(n)) - 1j * om * pbar[j]) for j in range(n))
        scale = mpmath.mnorm(A, 1)
        small = mpmath.mpf(10) ** (-(dps // 2)) * scale
        if res_q > small or res_p > small * max(abs(z) for z in pbar):
            raise SingularPointError(f"eigenvectors inaccurate at p = {float(pc):.10g} (residuals {float(res_q):.2g}, "
                                     f"{float(res_p):.2g})")
        qb = [mpmath.conj(z) for z in q]
        B, C3 = tens[2], tens[3]
        Bqq = _form(B, [q, q], n)
        Bqqb = _form(B, [q, qb], n)
        h11 = _solve(A, Bqqb)                                        # A⁻¹ B(q, q̄)
        M2 = mpmath.matrix(n, n)
        for i in range(n):
            for j in range(n):
                M2[i, j] = (2j * om if i == j else 0) - A[i, j]
        h20 = _solve(M2, Bqq)                                        # (2iω − A)⁻¹ B(q, q)
        Cqqqb = _form(C3, [q, q, qb], n)
        Bq_h11 = _form(B, [q, h11], n)
        Bqb_h20 = _form(B, [qb, h20], n)
        vec = [c - 2 * b1 + b2 for c, b1, b2 in zip(Cqqqb, Bq_h11, Bqb_h20, strict=True)]
        c1 = sum(a * b for a, b in zip(pbar, vec, strict=True)) / 2
        l1 = mpmath.re(c1) / om
        # transversality dλ/dp: central differences at h and 2h, one Richardson step
        h = abs(pc) * mpmath.mpf(rel_step) if pc != 0 else mpmath.mpf(rel_step)
        eig = {s: _critical_eig(nj.at(pc + s * h)[0], float(om)) for s in (1, -1, 2, -2)}

        def richardson(part):
            d1 = (part(eig[1]) - part(eig[-1])) / (2 * h)
            d2 = (part(eig[2]) - part(eig[-2])) / (4 * h)
            return (4 * d1 - d2) / 3

        dmu, dom = richardson(mpmath.re), richardson(mpmath.im)      # d Re λ/dp, d Im λ/dp
        qx = abs(q[system.normalise])
        eq = equilibrium_floats(system, pc, vals, dps)
        return HopfResult(
            system=system.name, parameter=system.parameter.name, p_c=float(pc), omega_c=float(om),
            equilibrium=tuple(eq), dlambda_dp=complex(float(dmu), float(dom)),
            Lambda=float(2 * mpmath.re(c1) / qx ** 2), chi=float(2 * mpmath.im(c1) / qx ** 2), convention=GENERAL,
            normalise=system.states[system.normalise].name, l1=float(l1), c1=complex(c1),
            params={s.name: float(v) for s, v in vals.items()}, q_norm=float(qx), dps=dps,
        )


def spring_block_lyapunov(block: SpringBlock, V: float, params: Mapping[str, float] | None = None, *,
                          kc_guess: float | None = None, jets: Jets | None = None,
                          dps: int = DEFAULT_DPS) -> HopfResult:
    """Kuznetsov's l₁ and C_K for the spring–block (Putelat et al. 2010, eq. 4) at driving velocity V.

    The starting estimate of k_c is ``kc_guess`` or the linear Hopf line (eq. 7); it is
    re-located from the eigenvalues.  Needs M > 0.

    Parameters
    ----------
    block : SpringBlock
        The spring–block with its friction law (closed-form steady state).
    V : float
        Driving velocity, m/s.
    params : mapping, optional
        Parameter overrides.
    kc_guess : float, optional
        Starting estimate of k_c (default: the linear Hopf line).
    jets : Jets, optional
        The system's symbolic jets.
    dps : int
        Working precision (≥ 30).

    Returns
    -------
    HopfResult
        As :func:`first_lyapunov`, in the spring–block convention (p = k, slip component X of
        the mode 1, so Λ, χ and C are comparable with :meth:`landau.derivation.multiscale.Derivation.points`;
        Γ̄ = −d Re λ/dk and Ω̄ = d Im λ/dk by finite differences), located at V.

    References
    ----------
    Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a
    spring–block system. J. Mech. Phys. Solids 58, 27–53.
    """
    p = block.resolve(params)
    if p["M"] <= 0:
        raise InputError("Kuznetsov route needs M > 0 (E·ẏ = f must be an ODE)")
    values: dict[str, Any] = dict(p)
    values["V"] = V
    system = block.system
    if system.unknowns:
        raise InputError("spring_block_lyapunov: the law needs a closed-form steady state; "
                         "use first_lyapunov with the numeric equilibrium")
    if kc_guess is None:
        from landau.derivation.linear import HopfLine

        kc, om = HopfLine(block, jets).evaluate([V], p)
        if not (kc[0] > 0):
            raise NoHopfError(f"V = {V:g} m/s: no Hopf bifurcation")
        kc_guess, om_guess = float(kc[0]), float(om[0])
    else:
        om_guess = None
    res = first_lyapunov(system, values, kc_guess, omega_c=om_guess, jets=jets, dps=dps)
    a = res.dlambda_dp
    return spring_block_result(block.law.name, float(V), res.p_c, res.omega_c, -a.real, a.imag, res.Lambda,
                               res.chi, {**p, "V": float(V)}, equilibrium=res.equilibrium, l1=res.l1, c1=res.c1,
                               q_norm=res.q_norm, dps=res.dps)


# --------------------------------------------------------------------------------------
# second Lyapunov coefficient
def _set_partitions(items: list) -> list[list[list]]:
    """Every partition of ``items`` (labelled) into non-empty blocks."""
    if not items:
        return [[]]
    first, rest = items[0], items[1:]
    out = []
    for part in _set_partitions(rest):
        out.append([[first], *part])
        for i in range(len(part)):
            out.append([*part[:i], [first, *part[i]], *part[i + 1:]])
    return out


def _kuznetsov_c1_c2(A: mpmath.matrix, tens: Mapping[int, Mapping[tuple, Any]], q: list, pbar: list, om):
    """c₁ and c₂ of ż = iωz + c₁z|z|² + c₂z|z|⁴ by Kuznetsov's homological equation.

    ẋ = Ax + F(x), F = Σₘ Dₘ[x, …, x]/m!; x = H(z, z̄) = zq + z̄q̄ + Σ h_{jk} z^j z̄^k/(j! k!).
    The coefficient of z^j z̄^k/(j! k!) in F(H) is the Faà di Bruno sum over the partitions of
    j labelled z's and k labelled z̄'s into m ≥ 2 blocks of Dₘ(h_{block}, …), and the
    nonlinear part of H_z ż + H_z̄ dz̄/dt contributes at z^{j+m}z̄^{k+m} the terms
    [(j+m)!(k+m)!/((j−1)! k!)] c_m h_{jk} and [(j+m)!(k+m)!/(j!(k−1)!)] c̄_m h_{jk}
    (in the factorial-scaled basis).  Resonant orders (j = k + 1) are solved with the
    bordered system ⟨p, h_{jk}⟩ = 0; then c₁ = ⟨p, H₂₁⟩/2 and c₂ = ⟨p, H₃₂⟩/12 (Kuznetsov
    1999, §7; the sum of the terms of MatCont's nf_GH with the c₁-terms kept).
    """
    n = A.rows
    fact = math.factorial
    h: dict[tuple[int, int], list] = {(1, 0): list(q), (0, 1): [mpmath.conj(z) for z in q]}
    coef: dict[int, Any] = {}
    pdot = lambda x: sum(a * b for a, b in zip(pbar, x, strict=True))

    def shifted(s):
        M = mpmath.matrix(n, n)
        for i in range(n):
            for j in range(n):
                M[i, j] = (s if i == j else 0) - A[i, j]
        return M

    for (j, k) in [(2, 0), (1, 1), (3, 0), (2, 1), (3, 1), (2, 2), (3, 2)]:
        labels = ["z"] * j + ["w"] * k
        rhs = [mpmath.mpc(0)] * n
        for part in _set_partitions(list(range(j + k))):
            m = len(part)
            if m < 2 or m not in tens:
                continue
            vecs = []
            for block in part:
                nz = sum(1 for i in block if labels[i] == "z")
                vecs.append(h[(nz, len(block) - nz)])
            rhs = [r + t for r, t in zip(rhs, _form(tens[m], vecs, n), strict=True)]
        for mm, cm in coef.items():               # ż ∋ c_m z^{m+1} z̄^m
            for (a, b), vec in h.items():
                if (a, b) in ((1, 0), (0, 1)) or (a + mm, b + mm) != (j, k):
                    continue
                if a > 0:
                    f = fact(j) * fact(k) / (fact(a - 1) * fact(b))
                    rhs = [r - f * cm * x for r, x in zip(rhs, vec, strict=True)]
                if b > 0:
                    f = fact(j) * fact(k) / (fact(a) * fact(b - 1))
                    rhs = [r - f * mpmath.conj(cm) * x for r, x in zip(rhs, vec, strict=True)]
        if j - k == 1:
            mm = k
            cval = pdot(rhs) / (fact(j) * fact(k))
            coef[mm] = cval
            if mm == 2:
                break
            rhs = [r - fact(j) * fact(k) * cval * qi for r, qi in zip(rhs, q, strict=True)]
            big = mpmath.matrix(n + 1, n + 1)
            M = shifted(1j * om)
            for i in range(n):
                for c in range(n):
                    big[i, c] = M[i, c]
                big[i, n] = q[i]
                big[n, i] = pbar[i]
            sol = _solve(big, [*rhs, 0])[:n]
        else:
            sol = _solve(shifted(1j * (j - k) * om), rhs)
        h[(j, k)] = sol
        if j != k:
            h[(k, j)] = [mpmath.conj(z) for z in sol]
    return coef[1], coef[2]


def lyapunov_coefficients(system: DynamicalSystem, values: Mapping[sp.Symbol | str, Any], p_c: float, *,
                          dps: int = DEFAULT_DPS, omega_c: float | None = None, jets: Jets | None = None,
                          relocate: bool = True, rel_step: float = 1e-5) -> HopfResult:
    """First and second Lyapunov coefficients of a Hopf point by Kuznetsov's projection method.

    Independent of the Fredholm route (it shares only the symbolic jets): the ODE ẏ = E⁻¹f,
    q and p from mpmath's eigen-solver with ⟨q, q⟩ = 1, ⟨p, q⟩ = 1, and the normal form
    ż = iωz + c₁z|z|² + c₂z|z|⁴ computed from multilinear forms up to fifth order (see
    :func:`_kuznetsov_c1_c2`) at ``dps`` digits.

    Parameters
    ----------
    system : DynamicalSystem
        E·ẏ = f(y; p) with every mass entry non-zero.
    values : mapping
        Every parameter (by symbol or name) and, where the equilibrium has no closed form,
        its ``unknowns``.
    p_c : float
        Estimate of the Hopf parameter (re-located from the eigenvalues unless
        ``relocate=False``).
    dps : int
        Working precision (≥ 30).
    omega_c : float, optional
        Estimate of the frequency, used only to pick the critical pair.

    Returns
    -------
    HopfResult
        ``l1`` = Re c₁/ω (as :func:`first_lyapunov`); ``c1``; ``l2`` = Re c₂ — the number
        MatCont (``nf_GH.m``: ``real(p0'*h32/12)``) and BifurcationKit
        (``NormalForms.jl``: ``l2 = real(G32)/12``) print at a generalised-Hopf point, *not*
        divided by ω; ``c2`` and ``l2_over_omega`` = Re c₂/ω.  In landau's convention
        (critical mode with ``normalise`` component 1): Λ = 2 Re c₁/|q_n|²,
        χ = 2 Im c₁/|q_n|², Λ₅ = 2 Re c₂/|q_n|⁴ with q_n that component of Kuznetsov's q.
        Re c₂ does not depend on the choice ⟨p, h₂₁⟩ = 0; away from l₁ = 0 it is the
        coefficient of the normal form without time rescaling.

    References
    ----------
    Kuznetsov, Yu. A. (1999). Numerical normalization techniques for all codim 2 bifurcations
    of equilibria in ODE's. SIAM J. Numer. Anal. 36, 1104–1124, §7 (generalised Hopf).
    """
    _check_dps(dps)
    with mpmath.workdps(dps):
        vals, nj, pc, A, tens, om, q, pbar = _critical_pair(system, values, jets, p_c, omega_c, dps, relocate, 5)
        c1, c2 = _kuznetsov_c1_c2(A, {m: tens[m] for m in (2, 3, 4, 5)}, q, pbar, om)
        # dλ/dp (complex) from the eigenvalues: central differences at h and 2h, one Richardson step
        h = abs(pc) * mpmath.mpf(rel_step) if pc != 0 else mpmath.mpf(rel_step)
        lam = lambda p: _critical_eig(nj.at(p)[0], float(om))
        d1 = (lam(pc + h) - lam(pc - h)) / (2 * h)
        d2 = (lam(pc + 2 * h) - lam(pc - 2 * h)) / (4 * h)
        dlam = (4 * d1 - d2) / 3
        qx2 = abs(q[system.normalise]) ** 2
        eq = equilibrium_floats(system, pc, vals, dps)
        return HopfResult(
            system=system.name, parameter=system.parameter.name, p_c=float(pc), omega_c=float(om),
            equilibrium=tuple(eq), dlambda_dp=complex(dlam), Lambda=float(2 * mpmath.re(c1) / qx2),
            chi=float(2 * mpmath.im(c1) / qx2), convention=GENERAL, normalise=system.states[system.normalise].name,
            l1=float(mpmath.re(c1) / om), c1=complex(c1), Lambda5=float(2 * mpmath.re(c2) / qx2 ** 2),
            l2=float(mpmath.re(c2)), params={s.name: float(v) for s, v in vals.items()},
            c2=complex(c2), q_norm=float(mpmath.sqrt(qx2)), dps=dps,
        )
