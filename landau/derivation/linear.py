"""Linear stability of steady sliding: the Hopf line k_c(V), ω_c(V).

For a system whose Hopf parameter p enters the Jacobian affinely (the spring–block's
stiffness k), det(λE − J) = P(λ) + p Q(λ).  A pair λ = ±iω crosses the axis where
P(iω) + p Q(iω) = 0 with p real, i.e. Im(P Q̄)(iω) = 0 and p = −Re(P Q̄)/|Q|².
Im(P Q̄)/ω is a polynomial in ω²: of degree one for a single state variable, which
gives Putelat et al.'s closed forms (7)–(8); for n states its roots are found
numerically and the critical stiffness is the largest positive root (steady sliding is
stable above it).  p may enter several entries of the Jacobian (the Linker–Dieterich state
response puts the stiffness in the state row too); the determinant stays affine in p there, and
:class:`~landau.derivation.parameter_jets.ParameterJets` keeps it polynomial in the atoms.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Any, Mapping, Sequence

import mpmath
import numpy as np
import sympy as sp
from sympy.polys.matrices import DomainMatrix

from landau.codegen.formula import CompiledFormula, compile_expr
from landau.derivation import hopf_roots
from landau.derivation.hopf_polynomial import hopf_polynomials
from landau.derivation.jets import Jets
from landau.derivation.parameter_jets import ParameterJets
from landau.derivation.sparse_det import det_by_sparsity
from landau.errors import InputError, NoHopfError, SingularPointError
from landau.systems.system import DynamicalSystem, SpringBlock, V

lam = sp.Symbol("lambda")
W = sp.Symbol("W", positive=True)       # ω²
w = sp.Symbol("omega", positive=True)   # ω

NO_HOPF_STABLE = "no Hopf bifurcation: steady sliding is stable for all k"


def _split_at_iw(poly: sp.Poly) -> tuple[sp.Poly, sp.Poly]:
    """(Re, Im) of a polynomial in λ evaluated at λ = iω, as polynomials in ω over the same
    coefficient domain."""
    re: dict[tuple[int], Any] = {}
    im: dict[tuple[int], Any] = {}
    for (m,), c in poly.rep.terms():
        sign = 1 if m % 4 in (0, 1) else -1
        (re if m % 2 == 0 else im)[(m,)] = c if sign == 1 else -c
    dom = poly.domain
    return sp.Poly.from_dict(re, w, domain=dom), sp.Poly.from_dict(im, w, domain=dom)


def _char_parts(det: Any, ring: Any, p: sp.Symbol) -> tuple[sp.Poly, sp.Poly]:
    """(P, Q) of det(λE − J) = P(λ) + p Q(λ), an element of the sparse polynomial ring ``ring`` over
    (atoms, λ, p), as polynomials in λ over the ring of the atoms: the terms sorted by their powers
    of p and λ (no dense multivariate conversion: one generator per atom)."""
    syms = ring.symbols
    ip, il = syms.index(p), syms.index(lam)
    keep = [i for i in range(len(syms)) if i not in (ip, il)]
    coef = ring.domain[tuple(syms[i] for i in keep)] if keep else ring.domain
    parts: tuple[dict, dict] = ({}, {})
    for mon, c in det.items():
        if mon[ip] > 1:
            raise InputError("the Hopf parameter enters the characteristic polynomial nonlinearly")
        parts[mon[ip]].setdefault(mon[il], {})[tuple(mon[i] for i in keep)] = c
    make = (lambda d: coef.ring.from_dict(d)) if keep else (lambda d: d[()])
    P, Q = (sp.Poly.from_dict({(m,): make(d) for m, d in part.items()} or {(0,): coef.zero}, lam, domain=coef)
            for part in parts)
    return P, Q


def _in_lambda(poly: sp.Poly) -> sp.Poly:
    """A polynomial in λ and other generators as a polynomial in λ over the ring of the others."""
    others = [g for g in poly.gens if g != lam]
    if lam not in poly.gens:
        return sp.Poly(poly.as_expr(), lam)
    return poly.reorder(lam, *others).eject(*others) if others else poly


@dataclass(frozen=True)
class HopfPoint:
    """Linear stability of steady sliding at one driving velocity V (SI units).

    k_c (eq. 7) is the critical stiffness: steady sliding is unstable for k < k_c;
    ω_c (eq. 8) the angular frequency at onset.  ``status`` is "ok" or "no-hopf".

    Parameters
    ----------
    V : float
        Driving velocity, m/s.
    status : str
        ``"ok"`` (a Hopf point) or ``"no-hopf"``.
    kc : float
        Critical stiffness k_c, N/m (NaN without a Hopf point); read it as the property ``k_c``
        (the canonical name; ``kc`` is a deprecated alias kept for one release, and ``as_dict``
        carries both keys).
    omega_c : float
        Angular frequency at onset ω_c, rad/s (NaN without a Hopf point).
    phi_ss : tuple of float
        The state variables at steady sliding.
    mu_ss, dmu_ss : float
        Steady-state friction coefficient μ_ss(V) and its slope dμ_ss/dV (s/m).
    reason : str
        Why there is no Hopf point (empty when there is one).
    weakening : str
        Where the law is velocity weakening, as a sentence.

    References
    ----------
    Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), "Regimes of frictional sliding of a
    spring–block system", J. Mech. Phys. Solids 58(1), 27–53, eqs (7)–(8).
    """

    V: float
    status: str
    kc: float = float("nan")
    omega_c: float = float("nan")
    phi_ss: tuple[float, ...] = ()
    mu_ss: float = float("nan")
    dmu_ss: float = float("nan")
    reason: str = ""
    #: where the law is velocity weakening (given with every "no Hopf point" answer)
    weakening: str = ""

    def as_dict(self) -> dict[str, Any]:
        """The point as JSON-ready fields.

        Returns
        -------
        dict
            V and status; k_c and ω_c, or the reason there is no Hopf point; the steady state.
        """
        d: dict[str, Any] = {"V": self.V, "status": self.status}
        if self.status == "ok":
            d.update(kc=self.kc, k_c=self.kc, omega_c=self.omega_c)
        else:
            d["reason"] = self.reason
            d["velocity_weakening"] = self.weakening
        d.update(phi_ss=list(self.phi_ss), mu_ss=self.mu_ss, dmu_ss_dV=self.dmu_ss)
        return d

    @property
    def k_c(self) -> float:
        """The critical stiffness k_c, N/m (canonical name of the deprecated ``kc``)."""
        return self.kc

    def __repr__(self) -> str:
        if self.status != "ok":
            return f"HopfPoint(V={self.V:.4g} m/s: {self.reason})"
        return f"HopfPoint(V={self.V:.4g} m/s, k_c={self.kc:.6g} N/m, ω_c={self.omega_c:.6g} rad/s)"

    def _repr_html_(self) -> str:
        from landau.report.display import html_record

        title = f"Linear stability at V = {self.V:.4g} m/s: " + ("Hopf point" if self.status == "ok" else self.reason)
        fields = {k: v for k, v in self.as_dict().items() if k != "kc"}
        return html_record(title, fields, units={"V": "m/s", "k_c": "N/m", "omega_c": "rad/s"})

    def _repr_latex_(self) -> str:
        if self.status != "ok":
            return rf"$V = {self.V:.4g}$: \text{{{self.reason}}}"
        return (rf"$V = {self.V:.4g}\,\mathrm{{m/s}},\ k_c = {self.kc:.6g}\,\mathrm{{N/m}},\ "
                rf"\omega_c = {self.omega_c:.6g}\,\mathrm{{rad/s}}$")


class HopfLine:
    """The Hopf line of a :class:`SpringBlock`: k_c(V) and ω_c(V), symbolic and compiled.

    Parameters
    ----------
    block : SpringBlock
        The mechanical system.
    jets : Jets, optional
        Derivatives of its vector field (shared with a :class:`Derivation`); built when omitted.

    References
    ----------
    Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), "Regimes of frictional sliding of a
    spring–block system", J. Mech. Phys. Solids 58(1), 27–53, eqs (7)–(8).
    """

    def __init__(self, block: SpringBlock, jets: Jets | None = None):
        self.block = block
        self.system: DynamicalSystem = block.system
        self.jets = jets or ParameterJets(self.system)
        self.args: tuple[sp.Symbol, ...] = block.args

    # --- symbolic ---------------------------------------------------------------------
    @cached_property
    def _char(self) -> tuple[sp.Poly, sp.Poly]:
        J = sp.Matrix(self.jets.jacobian())
        E = sp.diag(*self.system.mass)
        # the determinant in the polynomial ring of the entries (atoms, λ, p): exact, and far
        # cheaper than expanding a symbolic Berkowitz determinant for several state variables
        A = DomainMatrix.from_Matrix(lam * E - J)
        p = self.system.parameter
        ring = A.domain
        # the same exact element by the block-arrow sparsity of λE − J (one term per state
        # variable, no division), else by fraction-free elimination
        rows = A.to_list()
        det = det_by_sparsity(rows, ring.zero, ring.one)
        det = A.det() if det is None else det
        if ring.is_PolynomialRing and lam in ring.symbols and p in ring.symbols:
            return _char_parts(det, ring, p)
        char = sp.expand(ring.to_sympy(det))
        if sp.diff(char, p, 2) != 0:
            raise InputError("the Hopf parameter enters the characteristic polynomial nonlinearly")
        P = sp.Poly(char.subs(p, 0), lam)
        Q = sp.Poly(sp.diff(char, p), lam)
        return P, Q

    @cached_property
    def _hopf_polys(self) -> tuple[sp.Poly, sp.Expr, sp.Expr]:
        """(H(W) = Im(P Q̄)/ω as a polynomial in W = ω², Re(P Q̄), |Q|²)."""
        P, Q = self._char
        fast = hopf_polynomials(P, Q, W)     # exact products in ℤ[atoms] by FLINT
        if fast is not None:
            return fast
        # products of polynomials in ω over the coefficient ring; every product below is even
        # in ω (Im P(iω) is odd, Re P(iω) even), so ω² → W is a relabelling of the exponents
        Pr, Pi = _split_at_iw(P)
        Qr, Qi = _split_at_iw(Q)
        im = (Pi * Qr - Pr * Qi).exquo(sp.Poly(w, w, domain=Pr.domain))
        re = Pr * Qr + Pi * Qi
        q2 = Qr ** 2 + Qi ** 2

        def to_W(poly: sp.Poly) -> sp.Poly:
            terms = poly.terms()
            assert all(m % 2 == 0 for (m,), _ in terms)
            return sp.Poly.from_dict({(m // 2,): c for (m,), c in terms}, W, domain=poly.domain)

        return sp.Poly(to_W(im).as_expr(), W), sp.expand(to_W(re).as_expr()), sp.expand(to_W(q2).as_expr())

    @cached_property
    def closed_form(self) -> tuple[sp.Expr, sp.Expr] | None:
        """(k_c(V), ω_c²(V)) in closed form when the Hopf polynomial is linear in ω² (one state)."""
        H, re, q2 = self._hopf_polys
        if H.degree() != 1 or self.system.unknowns:
            return None
        c1, c0 = H.all_coeffs()
        W_c = sp.cancel(-c0 / c1)
        kc = sp.cancel((-re / q2).subs(W, W_c))
        return kc, W_c

    @property
    def kc_expr(self) -> sp.Expr:
        """k_c(V) in terms of the law (atoms substituted), eq. (7)."""
        cf = self.closed_form
        if cf is None:
            raise InputError(f"{self.system.name}: k_c has no closed form (more than one state); "
                             "use numeric evaluation")
        return self.jets.expand_atoms(cf[0])

    @property
    def omega2_expr(self) -> sp.Expr:
        """ω_c²(V) in terms of the law (atoms substituted), eq. (8)."""
        cf = self.closed_form
        if cf is None:
            raise InputError(f"{self.system.name}: ω_c² has no closed form (more than one state)")
        return self.jets.expand_atoms(cf[1])

    # --- numeric ------------------------------------------------------------------------
    def _argvals(self, Vs: np.ndarray, params: Mapping[str, float]) -> list:
        return self.block.argvals(Vs, params)

    @cached_property
    def _compiled_closed(self):
        kc, W_c = self.closed_form
        atoms = self.jets.atoms
        return CompiledFormula(kc, self.args, atoms), CompiledFormula(W_c, self.args, atoms)

    @cached_property
    def _compiled_closed_mp(self):
        kc, W_c = self.closed_form
        atoms = self.jets.atoms
        return CompiledFormula(kc, self.args, atoms, "mpmath"), CompiledFormula(W_c, self.args, atoms, "mpmath")

    def _rescue_closed(self, kc: np.ndarray, W_c: np.ndarray, vals) -> None:
        """In place: k_c, ω_c² where the float64 closed form overflowed, underflowed to 0 or gave NaN
        (σ = 1e300: k_c = 1.6e304 is representable, an intermediate is not), from mpmath (unbounded
        exponent); a value beyond float64's range stays non-finite."""
        lost = ~np.isfinite(kc) | ~np.isfinite(W_c) | (kc == 0) | (W_c == 0)
        if not lost.any():
            return
        fk, fW = self._compiled_closed_mp
        with mpmath.workdps(30):
            for i in map(tuple, np.argwhere(lost)):
                point = [mpmath.mpf(float(np.broadcast_to(v, kc.shape)[i])) for v in vals]
                with np.errstate(over="ignore"):
                    kc[i], W_c[i] = float(fk(*point)), float(fW(*point))

    @cached_property
    def _compiled_poly(self):
        H, re, q2 = self._hopf_polys
        atoms = self.jets.atoms
        coeffs = [CompiledFormula(c, self.args, atoms) for c in H.all_coeffs()]
        return coeffs, CompiledFormula(re, (W, *self.args), atoms), CompiledFormula(q2, (W, *self.args), atoms)

    @cached_property
    def _compiled_poly_mp(self):
        H, re, q2 = self._hopf_polys
        atoms = self.jets.atoms
        return ([CompiledFormula(c, self.args, atoms, "mpmath") for c in H.all_coeffs()],
                CompiledFormula(re, (W, *self.args), atoms, "mpmath"),
                CompiledFormula(q2, (W, *self.args), atoms, "mpmath"))

    def numeric_point_mp(self, vals: Sequence[Any]) -> tuple[Any, Any]:
        """(k_c, ω_c²) of the n-state route at the working mpmath precision.

        Parameters
        ----------
        vals : sequence of mpmath.mpf
            Values of :attr:`args` (the driving velocity and the parameters).

        Returns
        -------
        tuple of mpmath.mpf
            (k_c, ω_c²); (nan, nan) when there is no Hopf point.
        """
        import mpmath

        coeffs, fre, fq2 = self._compiled_poly_mp
        cs = [c(*vals) for c in coeffs]
        while cs and cs[0] == 0:
            cs = cs[1:]
        roots = mpmath.polyroots(cs, maxsteps=200, extraprec=2 * mpmath.mp.prec) if len(cs) > 1 else []
        return _stiffest_hopf_root([mpmath.mpc(r) for r in roots], lambda Wr: -fre(Wr, *vals) / fq2(Wr, *vals),
                                   mpmath.mpf(10) ** (-mpmath.mp.dps // 2), mpmath.nan)

    @cached_property
    def _mu_ss_exprs(self) -> tuple[sp.Expr, sp.Expr, tuple[sp.Expr, ...]]:
        """(μ_ss, dμ_ss/dV, φ_ss) in V, the parameters and — where the steady state has no closed
        form — the numeric steady-state symbols φᵢ,₀; then dφ_ss/dV = −(∂R/∂φ)⁻¹ ∂R/∂v (implicit
        function theorem on the rates R)."""
        from landau.laws.law import v as v_slip

        law = self.block.law
        ss = self.block.steady_state
        if ss is not None:
            mu = self.block.mu_ss()
            return mu, sp.diff(mu, V), tuple(ss)
        phi0 = self.block.phi0
        at = {v_slip: V, **dict(zip(law.states, phi0, strict=True))}
        R = sp.Matrix(law.rates)
        Rphi = R.jacobian(list(law.states)).xreplace(at)
        Rv = R.diff(v_slip).xreplace(at)
        dphi = -Rphi.LUsolve(Rv)
        mu = law.mu.xreplace(at)
        dmu = law.mu.diff(v_slip).xreplace(at) + sum(law.mu.diff(s).xreplace(at) * dphi[i]
                                                     for i, s in enumerate(law.states))
        return mu, dmu, tuple(phi0)

    @cached_property
    def _compiled_mu(self):
        mu, dmu, _ = self._mu_ss_exprs
        return compile_expr(mu, self.args), compile_expr(dmu, self.args)

    @cached_property
    def _compiled_phi(self):
        return [compile_expr(e, self.args) for e in self._mu_ss_exprs[2]]

    def evaluate(self, Vs: Sequence[float] | float | np.ndarray, params: Mapping[str, float] | None = None,
                 method: str = "auto", **overrides: float) -> tuple[np.ndarray, np.ndarray]:
        """Vectorised (k_c, ω_c) over velocities; NaN where there is no Hopf point.

        ``method="polynomial"`` forces the general n-state route (roots of the Hopf
        polynomial in ω²) even when a closed form exists.

        Parameters
        ----------
        Vs : float or sequence of float
            Driving velocities, m/s.
        params : mapping of str to float, optional
            Parameter overrides (defaults: :meth:`SpringBlock.resolve`); values may be arrays.
        method : {"auto", "polynomial"}
            The route (see above).
        **overrides : float
            Parameter values as keywords, merged with ``params`` (``evaluate(1e-4, M=1.2)``).

        Returns
        -------
        kc, omega_c : numpy.ndarray
            Critical stiffness (N/m) and onset angular frequency (rad/s), NaN where there is no
            Hopf point.
        """
        if method not in ("auto", "polynomial"):
            raise InputError(f"unknown method {method!r}")
        from landau.derivation.multiscale import _merged

        p = self.block.resolve(_merged(params, overrides))
        Vs = np.atleast_1d(np.asarray(Vs, dtype=float))
        if self.closed_form is not None and method == "auto":
            fk, fW = self._compiled_closed
            vals = self._argvals(Vs, p)
            with np.errstate(all="ignore"):
                kc = np.array(np.broadcast_to(np.asarray(fk(*vals), dtype=float), Vs.shape))
                W_c = np.array(np.broadcast_to(np.asarray(fW(*vals), dtype=float), Vs.shape))
            self._rescue_closed(kc, W_c, vals)
            ok = (W_c > 0) & (kc > 0) & np.isfinite(kc)
            return np.where(ok, kc, np.nan), np.where(ok, np.sqrt(np.where(ok, W_c, 1.0)), np.nan)
        # every argument at once (the numeric steady states are solved together)
        table = [np.broadcast_to(np.asarray(x, dtype=float), Vs.shape) for x in self._argvals(Vs, p)]
        return self.numeric_at(table)

    def numeric_at(self, table: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        """(k_c, ω_c) of the n-state route at argument values :attr:`args` broadcast to one shape
        (NaN where there is no Hopf point): the roots of every point's Hopf polynomial at once
        (:mod:`landau.derivation.hopf_roots`), the stiffest real positive one kept.

        Parameters
        ----------
        table : sequence of numpy.ndarray
            Values of :attr:`args` (the driving velocity and the parameters), all of one shape.

        Returns
        -------
        kc, omega_c : numpy.ndarray
            Of that shape.
        """
        coeffs, fre, fq2 = self._compiled_poly
        shape = np.shape(table[0])
        flat = [np.ravel(np.asarray(x, dtype=float)) for x in table]
        n = flat[0].size
        C = np.stack([np.broadcast_to(np.asarray(c(*flat), dtype=float), (n,)) for c in coeffs], axis=1)

        def stiffness(Wr: np.ndarray, rows: np.ndarray) -> np.ndarray:
            at = [x[rows] for x in flat]
            return -fre(Wr, *at) / fq2(Wr, *at)

        kcs, Ws = hopf_roots.stiffest(C, stiffness, 1e-9)
        return kcs.reshape(shape), np.sqrt(Ws).reshape(shape)

    def points(self, Vs: Sequence[float] | float | np.ndarray,
               params: Mapping[str, float] | None = None) -> list[HopfPoint]:
        """One :class:`HopfPoint` per velocity, with the steady state and μ_ss slope.

        Parameters
        ----------
        Vs : float or sequence of float
            Driving velocities, m/s.
        params : mapping of str to float, optional
            Parameter overrides (defaults: :meth:`SpringBlock.resolve`).

        Returns
        -------
        list of HopfPoint
        """
        Vs = _velocities(Vs)
        if np.any(~np.isfinite(Vs)) or np.any(Vs <= 0):
            bad = [x for x in Vs if not (np.isfinite(x) and x > 0)][0]
            raise InputError(f"driving velocity V must be > 0, got {bad!r}")
        p = self.block.resolve(params)
        kc, om = self.evaluate(Vs, p)
        vals = self._argvals(Vs, p)
        fmu, fdmu = self._compiled_mu
        mu = np.broadcast_to(fmu(*vals), Vs.shape)
        dmu = np.broadcast_to(fdmu(*vals), Vs.shape)
        phis = [np.broadcast_to(f(*vals), Vs.shape) for f in self._compiled_phi]
        out = []
        for i, Vi in enumerate(Vs):
            phi = tuple(float(ph[i]) for ph in phis)
            if not (np.isfinite(mu[i]) and np.isfinite(dmu[i])):
                raise SingularPointError(f"law {self.block.law.name!r} is not defined or not differentiable at its "
                                         f"steady state for V = {Vi:g} m/s (mu_ss = {mu[i]}, slope = {dmu[i]})")
            if not np.isfinite(kc[i]) and dmu[i] < 0 and self.closed_form is not None:
                fk, fW = self._compiled_closed
                raw = [float(np.ravel(f(*self._argvals(np.float64(Vi), p)))[0]) for f in (fk, fW)]
                if not all(np.isfinite(raw)) or 0.0 in raw:
                    raise SingularPointError(
                        f"law {self.block.law.name!r} at V = {Vi:g} m/s: k_c or omega_c^2 leaves the floating-point "
                        f"range (k_c = {raw[0]:g}, omega_c^2 = {raw[1]:g}): the parameters are out of range")
            if np.isfinite(kc[i]):
                out.append(HopfPoint(float(Vi), "ok", float(kc[i]), float(om[i]), phi, float(mu[i]), float(dmu[i])))
            else:
                reason = NO_HOPF_STABLE if dmu[i] >= 0 else \
                    ("no Hopf bifurcation: velocity weakening but no oscillatory instability "
                     "(check the direct effect mu_v > 0)")
                out.append(HopfPoint(float(Vi), "no-hopf", phi_ss=phi, mu_ss=float(mu[i]), dmu_ss=float(dmu[i]),
                                     reason=reason, weakening=self.weakening_range(p)))
        return out

    def weakening_range(self, params: Mapping[str, float] | None = None) -> str:
        """Where the law is velocity weakening (dμ_ss/dV < 0, the necessary condition for a Hopf
        point), read on a log grid of 301 velocities from 1e-12 to 1e3 m/s, as a sentence.

        Parameters
        ----------
        params : mapping of str to float, optional
            Parameter overrides.

        Returns
        -------
        str
        """
        from landau.errors import LandauError

        p = self.block.resolve(params)
        key = tuple(sorted(p.items()))
        cache = self.__dict__.setdefault("_weakening", {})
        if key in cache:
            return cache[key]
        grid = np.logspace(-12, 3, 301)
        try:
            _, fdmu = self._compiled_mu
            with np.errstate(all="ignore"):
                dmu = np.broadcast_to(np.asarray(fdmu(*self._argvals(grid, p)), dtype=float), grid.shape)
        except LandauError:
            cache[key] = "the velocity-weakening range could not be scanned"
            return cache[key]
        neg = np.isfinite(dmu) & (dmu < 0)
        if not neg.any():
            text = "the law is velocity strengthening (dmu_ss/dV >= 0) at every V from 1e-12 to 1e3 m/s"
        else:
            runs, start = [], None
            for i, flag in enumerate(neg):
                if flag and start is None:
                    start = i
                if start is not None and (not flag or i == grid.size - 1):
                    end = i if flag else i - 1
                    runs.append(f"{grid[start]:.3g} to {grid[end]:.3g}")
                    start = None
            text = "velocity weakening (dmu_ss/dV < 0) for V from " + " and from ".join(runs) + " m/s"
        cache[key] = text
        return text

    def point(self, V0: float, params: Mapping[str, float] | None = None) -> HopfPoint:
        """The :class:`HopfPoint` at one velocity.

        Parameters
        ----------
        V0 : float
            Driving velocity, m/s.
        params : mapping of str to float, optional
            Parameter overrides.

        Returns
        -------
        HopfPoint
            Its ``status`` is ``"no-hopf"`` where there is no Hopf point.
        """
        return self.points([one_velocity(V0, "V", "points(V)")], params)[0]

    def require(self, V0: float, params: Mapping[str, float] | None = None) -> HopfPoint:
        """The :class:`HopfPoint` at one velocity, which must exist.

        Parameters
        ----------
        V0 : float
            Driving velocity, m/s.
        params : mapping of str to float, optional
            Parameter overrides.

        Returns
        -------
        HopfPoint
            With ``status == "ok"``.

        Raises
        ------
        NoHopfError
            No Hopf point at ``V0`` (the message gives the velocity-weakening range).
        """
        pt = self.point(V0, params)
        if pt.status != "ok":
            raise NoHopfError(f"V = {V0:g} m/s: {pt.reason}; {pt.weakening}")
        return pt


def _velocities(Vs: Any) -> np.ndarray:
    """Velocities for a per-point function: a number or a 1-D sequence, as a 1-D float array."""
    try:
        arr = np.atleast_1d(np.asarray(Vs, dtype=float))
    except (TypeError, ValueError):
        raise InputError(f"V must be a number or a sequence of numbers (m/s), got {type(Vs).__name__}") from None
    if arr.ndim != 1:
        raise InputError(f"V must be a number or a 1-D sequence of velocities, got shape {arr.shape} "
                         "(evaluate(V) takes arrays of any shape)")
    return arr


def one_velocity(V: Any, what: str = "V", several: str = "points(V) or evaluate(V)") -> float:
    """A driving velocity given to a one-point function, as a float.

    Parameters
    ----------
    V : float
        The velocity (m/s).
    what : str
        Its name in the error message.
    several : str
        The functions that take several velocities, named in the error message.

    Returns
    -------
    float

    Raises
    ------
    InputError
        ``V`` is a sequence or an array of more than one value, not a number, not finite or not > 0.
    """
    if isinstance(V, (str, bytes)):
        raise InputError(f"{what} must be a number (m/s), got {V!r}")
    try:
        arr = np.asarray(V, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{what} must be a number (m/s), got {type(V).__name__}") from None
    if arr.ndim:
        raise InputError(f"{what} must be one velocity (a number), got {arr.size} value(s) of shape {arr.shape}: "
                         f"for several velocities use {several}")
    x = float(arr)
    if not (np.isfinite(x) and x > 0):
        raise InputError(f"{what}: driving velocity must be finite and > 0 m/s, got {x!r}")
    return x


def _stiffest_hopf_root(roots, stiffness, real_tol, nan) -> tuple[Any, Any]:
    """(k_c, ω_c²) from the roots W of the Hopf polynomial: among the real positive roots
    (|Im| ≤ real_tol·|W|), the one with the largest positive stiffness — steady sliding is
    unstable below the stiffest Hopf point; (nan, nan) when there is none."""
    best = (nan, nan)
    for r in roots:
        if abs(r.imag) > real_tol * abs(r) or r.real <= 0:
            continue
        kk = stiffness(r.real)
        if kk > 0 and not (kk <= best[0]):
            best = (kk, r.real)
    return best


def critical_stiffness(block: SpringBlock, V0, params: Mapping[str, float] | None = None):
    """k_c(V) of eq. (7) (vectorised; NaN where steady sliding is stable for all k).

    Parameters
    ----------
    block : SpringBlock
        The spring–block with its friction law.
    V0 : float or array_like
        Driving velocities (m/s).
    params : mapping, optional
        Parameter values overriding the defaults (law parameters, M, g, sigma).

    Returns
    -------
    numpy.ndarray
        The critical stiffness (N/m) at each velocity.

    References
    ----------
    Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). J. Mech. Phys. Solids 58, 27–53, eq. (7).
    """
    return HopfLine(block).evaluate(V0, params)[0]
