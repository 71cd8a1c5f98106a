"""Exact sensitivities ∂q/∂p of the amplitude-equation quantities to the parameters.

Every quantity q of a :class:`~landau.derivation.multiscale.Derivation` — k_c, ω_c, Γ̄, Ω̄, Λ, χ
and C (Putelat, Dawes & Willis 2010, eqs 7–8, 15–23) — is a formula F(a, ω, k, p) in the law's
derivative atoms a(p) at steady sliding, the onset frequency ω and the stiffness k, evaluated on
the Hopf line k = k_c(p), ω = ω_c(p).  Its total derivative along a parameter p (V, a law
parameter, M, σ, an optional term) is the chain rule

    dq/dp = ∂F/∂p + Σₐ ∂F/∂a · da/dp + ∂F/∂ω · dω_c/dp + ∂F/∂k · dk_c/dp,

with, on a Hopf line in closed form (one state variable), dk_c/dp and dω_c/dp = (dω_c²/dp)/(2ω_c)
from the same rule on eqs (7)–(8); on a numerical Hopf line (several states), from the implicit
function theorem on the Hopf polynomial H(W) = 0, W = ω², and k_c = −Re(P Q̄)/|Q|² at W
(:mod:`landau.derivation.linear`); a steady state without closed form, R(φ₀; p) = 0, moves by
dφ₀/dp = −R_φ⁻¹ R_p.  C = 2 sqrt(2Γ̄/|Λ|) gives dC/dp = C (dΓ̄/dp / Γ̄ − dΛ/dp / Λ)/2.

The derivatives are computed as compiled code: each formula's straight-line program
(:class:`~landau.codegen.formula.Tape`) run in forward mode (:func:`landau.codegen.forward.forward`),
all parameters at once, vectorised over points (float64) or at any mpmath precision — exact up
to rounding, linear in the size of the formula's DAG.  Where the quantity has a closed form in V
and the parameters (Dieterich, Ruina: :meth:`Coefficient.closed_form`), :meth:`Sensitivity.closed_form`
differentiates it symbolically and :meth:`Sensitivity.latex` prints it.

References
----------
Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), "Regimes of frictional sliding of a
spring–block system", J. Mech. Phys. Solids 58(1), 27–53.
Griewank, A. & Walther, A. (2008), *Evaluating Derivatives*, 2nd ed., SIAM, ch. 3.
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Mapping, Sequence

import mpmath
import numpy as np
import sympy as sp

from landau.codegen.formula import Tape
from landau.codegen.forward import forward
from landau.derivation.coefficients import _GB, _LA, DERIVED, QUANTITIES, internal_name
from landau.derivation.linear import W, w
from landau.errors import InputError, NoHopfError

if TYPE_CHECKING:
    from landau.derivation.multiscale import Derivation

#: the quantities with a sensitivity (the user's names: k_c canonical, kc its deprecated alias)
SENSITIVE = tuple("k_c" if q == "kc" else q for q in QUANTITIES)


def parameters(d: "Derivation") -> tuple[str, ...]:
    """The parameters a quantity of ``d`` depends on: V, the law's, M, σ and the optional terms'.

    The gravity g is not one of them: it enters only through σ's default M·g, and every quantity
    is a function of σ itself.

    Parameters
    ----------
    d : Derivation

    Returns
    -------
    tuple of str
    """
    unknowns = set(d.system.unknowns)
    return tuple(s.name for s in d.args if s not in unknowns and s.name != "g")


def _hint(name: str, known: Sequence[str]) -> str:
    close = difflib.get_close_matches(name, list(known), n=1)
    return f"; did you mean {close[0]!r}?" if close else ""


def check_quantity(name: str) -> str:
    """The internal name of quantity ``name``; an :class:`InputError` (with "did you mean") otherwise."""
    if not isinstance(name, str) or internal_name(name) not in QUANTITIES:
        raise InputError(f"unknown quantity {name!r} for a sensitivity{_hint(str(name), SENSITIVE)} "
                         f"(known: {', '.join(SENSITIVE)})")
    return internal_name(name)


def check_parameter(d: "Derivation", name: str) -> str:
    """``name`` when it is a parameter of ``d`` (:func:`parameters`); an :class:`InputError` otherwise."""
    known = parameters(d)
    if name not in known:
        raise InputError(f"unknown parameter {name!r} for a sensitivity of law {d.block.law.name!r}"
                         f"{_hint(str(name), known)} (known: {', '.join(known)})")
    return name


def _expanded(expr: sp.Expr, atoms: Mapping[sp.Symbol, sp.Expr]) -> sp.Expr:
    """``expr`` with nested atoms replaced until none is left."""
    for _ in range(64):
        if not (expr.free_symbols & atoms.keys()):
            return expr
        expr = expr.xreplace(atoms)
    raise InputError("atom definitions refer to each other in a cycle")


class _Programs:
    """The straight-line programs of one derivation: its atoms over the arguments, the Hopf line,
    the numeric steady states' equations and each quantity's formula (built on first use)."""

    def __init__(self, d: "Derivation"):
        self.d = d
        self.args = tuple(d.args)
        self._formulas: dict[str, tuple[Tape, tuple[sp.Symbol, ...]]] = {}
        self._hopf: tuple[Tape, tuple[sp.Symbol, ...], int] | None = None
        self._atoms: dict[tuple[sp.Symbol, ...], Tape] = {}

    def atom_symbols(self, exprs: Sequence[sp.Expr]) -> list[sp.Symbol]:
        atoms = self.d.jets.atoms
        out: set[sp.Symbol] = set()
        for e in exprs:
            out |= {s for s in e.free_symbols if s in atoms}
        return sorted(out, key=lambda s: s.name)

    def formula(self, name: str) -> tuple[Tape, tuple[sp.Symbol, ...]]:
        """The tape of quantity ``name``'s formula over (its atoms, ω, k, args) and those atoms."""
        if name not in self._formulas:
            f = self.d.coefficient(name).formula
            syms = tuple(self.atom_symbols([f]))
            self._formulas[name] = (Tape(f, [*syms, w, self.d.k, *self.args]), syms)
        return self._formulas[name]

    def hopf(self) -> tuple[Tape, tuple[sp.Symbol, ...], int]:
        """The Hopf line's tape over (atoms, W, args): closed form: outputs (k_c, ω_c²) (W unused);
        numeric: the Hopf polynomial's coefficients c₀…cₙ, then Re(P Q̄) and |Q|² at W; and the
        number of polynomial coefficients (0 for the closed form)."""
        if self._hopf is not None:
            return self._hopf
        line = self.d.hopf
        if line.closed_form is not None:
            outs = list(line.closed_form)
            ncoef = 0
        else:
            H, re, q2 = line._hopf_polys
            coeffs = list(reversed(H.all_coeffs()))       # c₀, c₁, …, cₙ
            outs = [*coeffs, re, q2]
            ncoef = len(coeffs)
        syms = tuple(self.atom_symbols(outs))
        self._hopf = (Tape([sp.sympify(e) for e in outs], [*syms, W, *self.args]), syms, ncoef)
        return self._hopf

    def atoms(self, wanted: Sequence[sp.Symbol]) -> Tape:
        """One tape of the atoms ``wanted`` over the arguments."""
        key = tuple(wanted)
        if key not in self._atoms:
            atoms = self.d.jets.atoms
            self._atoms[key] = Tape([_expanded(atoms[s], atoms) for s in wanted], list(self.args))
        return self._atoms[key]


@dataclass
class _Point:
    """The arguments at the evaluation points with their tangents along the chosen parameters."""

    values: list
    tangents: list
    n: int
    mp: bool

    def unit(self, i: int):
        """The tangent e_i (the direction of parameter i)."""
        if self.mp:
            t = np.array([mpmath.mpf(0)] * self.n, dtype=object)
            t[i] = mpmath.mpf(1)
            return t
        shape = np.broadcast(*[np.asarray(v) for v in self.values]).shape
        t = np.zeros((self.n, *shape))
        t[i] = 1.0
        return t


def _run(tape: Tape, inputs: Sequence[sp.Symbol], known: Mapping[sp.Symbol, tuple[Any, Any]], mp: bool):
    vals = [known[s][0] for s in inputs]
    tans = [known[s][1] for s in inputs]
    return forward(tape, vals, tans, "mpmath" if mp else "numpy")


class _Evaluation:
    """One forward pass: the arguments, atoms and Hopf line with their tangents, then the formulas."""

    def __init__(self, d: "Derivation", progs: _Programs, args: Sequence[Any], which: Sequence[str],
                 kc: Any, omega: Any, mp: bool, names: Sequence[str]):
        self.d, self.progs, self.mp = d, progs, mp
        # every formula first: deriving one adds the atoms it uses, evaluated below
        for name in names:
            for n in (*DERIVED.get(name, ()), name):
                if n not in ("kc", "omega_c") and n not in DERIVED:
                    progs.formula(n)
        progs.hopf()
        n = len(which)
        index = {s.name: i for i, s in enumerate(progs.args)}
        pt = _Point(list(args), [None] * len(args), n, mp)
        for i, name in enumerate(which):
            pt.tangents[index[name]] = pt.unit(i)
        self.point = pt
        self.known: dict[sp.Symbol, tuple[Any, Any]] = dict(zip(progs.args, zip(pt.values, pt.tangents, strict=True),
                                                                     strict=True))
        self._unknown_tangents()
        self._atom_values()
        self._hopf_tangents(kc, omega)

    def _unknown_tangents(self) -> None:
        """dφ₀/dp for the steady states solved numerically (implicit function theorem)."""
        system = self.d.system
        if not system.unknowns:
            return
        pt, m = self.point, len(system.unknowns)
        eqs = [sp.sympify(e) for e in system.unknown_equations]
        atoms = self.d.jets.atoms
        tape = Tape([_expanded(e, atoms) for e in eqs], list(self.progs.args))
        # directions: the parameters, then each unknown φ₀ⱼ
        ext = _Point(pt.values, [None if t is None else self._pad(t, m) for t in pt.tangents], pt.n + m, pt.mp)
        for j, u in enumerate(system.unknowns):
            ext.tangents[self.progs.args.index(u)] = ext.unit(pt.n + j)
        _, tans = forward(tape, ext.values, ext.tangents, "mpmath" if pt.mp else "numpy")
        R = [self._full(t, pt.n + m) for t in tans]
        # R(φ₀; p) = 0 along the parameters: dφ₀/dp = −R_φ⁻¹ R_p, one solve per point
        if pt.mp:
            Rphi = mpmath.matrix([[R[i][pt.n + j] for j in range(m)] for i in range(m)])
            Rp = mpmath.matrix([[R[i][c] for c in range(pt.n)] for i in range(m)])
            cols = [-mpmath.lu_solve(Rphi, Rp.column(c)) for c in range(pt.n)]
            dphi = [np.array([cols[c][j] for c in range(pt.n)], dtype=object) for j in range(m)]
        else:
            Rphi = np.moveaxis(np.stack([np.stack([R[i][pt.n + j] for j in range(m)]) for i in range(m)]),
                               (0, 1), (-2, -1))
            Rp = np.moveaxis(np.stack([np.stack([R[i][c] for c in range(pt.n)]) for i in range(m)]),
                             (0, 1), (-2, -1))
            sol = -np.linalg.solve(Rphi, Rp)
            dphi = [np.moveaxis(sol[..., j, :], -1, 0) for j in range(m)]
        for j, u in enumerate(system.unknowns):
            self.known[u] = (self.known[u][0], dphi[j])

    def _pad(self, t, m: int):
        if self.mp:
            return np.concatenate([t, np.array([mpmath.mpf(0)] * m, dtype=object)])
        return np.concatenate([t, np.zeros((m, *t.shape[1:]))])

    def _full(self, t, n: int):
        if t is not None:
            return t
        if self.mp:
            return np.array([mpmath.mpf(0)] * n, dtype=object)
        shape = np.broadcast(*[np.asarray(v) for v in self.point.values]).shape
        return np.zeros((n, *shape))

    def _atom_values(self) -> None:
        atoms = self.d.jets.atoms
        self.atom_syms = sorted(atoms, key=lambda s: s.name)
        tape = self.progs.atoms(self.atom_syms)
        vals = [self.known[s][0] for s in self.progs.args]
        tans = [self.known[s][1] for s in self.progs.args]
        av, at = forward(tape, vals, tans, "mpmath" if self.mp else "numpy")
        for s, v, t in zip(self.atom_syms, av, at, strict=True):
            self.known[s] = (v, t)

    def _hopf_tangents(self, kc: Any, omega: Any) -> None:
        tape, syms, ncoef = self.progs.hopf()
        Wc = omega * omega
        self.known[W] = (Wc, None)
        if ncoef == 0:
            _, (dk, dW) = _run(tape, [*syms, W, *self.progs.args], self.known, self.mp)
        else:
            # the W direction appended to the parameters' (∂/∂W of Re(P Q̄), |Q|²)
            n = self.point.n
            ext = {s: (v, None if t is None else self._pad(t, 1)) for s, (v, t) in self.known.items()}
            unit = _Point(self.point.values, [], n + 1, self.mp).unit(n)
            ext[W] = (Wc, unit)
            vals, tans = _run(tape, [*syms, W, *self.progs.args], ext, self.mp)
            tans = [self._full(t, n + 1) for t in tans]
            cs, dcs = vals[:ncoef], tans[:ncoef]
            # H(W) = Σ cᵢ Wⁱ = 0 on the line: dW/dp = −(Σ dcᵢ/dp Wⁱ)/H′(W)
            Hp = sum(dcs[i][:n] * Wc ** i for i in range(ncoef))
            HW = sum(i * cs[i] * Wc ** (i - 1) for i in range(1, ncoef))
            dW = -Hp / HW
            (re, q2), (tre, tq2) = vals[ncoef:], tans[ncoef:]
            dre = tre[:n] + tre[n] * dW
            dq2 = tq2[:n] + tq2[n] * dW
            # k_c = −Re(P Q̄)/|Q|² at W_c
            dk = -(dre * q2 - re * dq2) / (q2 * q2)
        self.known[self.d.k] = (kc, dk)
        # ω_c = sqrt(W_c): dω_c = dW/(2ω_c)
        self.known[w] = (omega, None if dW is None else dW / (2 * omega))

    def quantity(self, name: str) -> tuple[Any, Any]:
        """(value, tangent over the parameters) of quantity ``name``."""
        if name == "kc":
            return self.known[self.d.k][0], self._full(self.known[self.d.k][1], self.point.n)
        if name == "omega_c":
            return self.known[w][0], self._full(self.known[w][1], self.point.n)
        if name == "C":
            g, dg = self.quantity("Gamma_bar")
            lam, dlam = self.quantity("Lambda")
            C = 2 * (2 * g / abs(lam)) ** 0.5 if not self.mp else 2 * mpmath.sqrt(2 * g / abs(lam))
            # C = 2 sqrt(2Γ̄/|Λ|): dC = C (dΓ̄/Γ̄ − dΛ/Λ)/2
            return C, C * (dg / g - dlam / lam) / 2
        tape, syms = self.progs.formula(name)
        (v,), (t,) = _run(tape, [*syms, w, self.d.k, *self.progs.args], self.known, self.mp)
        return v, self._full(t, self.point.n)


def _programs(d: "Derivation") -> _Programs:
    progs = d.__dict__.get("_sensitivity_programs")
    if progs is None:
        progs = d.__dict__["_sensitivity_programs"] = _Programs(d)
    return progs


#: up to this many points :func:`evaluate`'s "auto" method works at 50 digits, point by point
MP_POINTS = 16


def evaluate(d: "Derivation", Vs, params: Mapping[str, Any] | None, quantities: Sequence[str],
             parameters_: Sequence[str] | None = None, method: str = "auto") -> dict[str, dict[str, np.ndarray]]:
    """∂q/∂p for each quantity q and parameter p over the points, as float64 arrays.

    ``method="float64"`` runs the programs in float64, vectorised: fast, and accurate to ~1e-8 of
    the natural scale |q/p| — a sensitivity that is itself a near-cancellation (dC/dσ =
    C(dΓ̄/Γ̄ − dΛ/Λ)/2 with the two terms equal to 1e-6) keeps that absolute accuracy, not its
    relative one.  ``method="mpmath"`` runs them at 50 digits point by point (:func:`evaluate_mp`);
    ``"auto"`` (default) does so up to :data:`MP_POINTS` points with scalar parameters, else float64.

    Parameters
    ----------
    d : Derivation
    Vs : float or array_like
        Driving velocities, m/s.
    params : mapping, optional
        Parameter values (arrays broadcasting against ``Vs`` accepted on a closed-form Hopf line).
    quantities : sequence of str
        Quantities (:data:`SENSITIVE`).
    parameters_ : sequence of str, optional
        Parameters (default: all, :func:`parameters`).
    method : {"auto", "float64", "mpmath"}
        The arithmetic (see above).

    Returns
    -------
    dict
        quantity -> {parameter -> array}; also ``"value"`` -> {quantity -> array}.  NaN where there
        is no Hopf point.
    """
    if method not in ("auto", "float64", "mpmath"):
        raise InputError(f"unknown sensitivity method {method!r} (auto, float64, mpmath)")
    arrays_given = any(np.ndim(v) > 0 for v in (params or {}).values())
    if method == "mpmath" or (method == "auto" and not arrays_given and np.size(Vs) <= MP_POINTS):
        if arrays_given:
            raise InputError("method 'mpmath' takes scalar parameters (one velocity array)")
        return _evaluate_points_mp(d, Vs, params, quantities, parameters_)
    names = [check_quantity(q) for q in quantities]
    which = [check_parameter(d, p) for p in (parameters_ if parameters_ is not None else parameters(d))]
    bases = [n for n in ("kc", "omega_c") if n not in names]
    base_names = list(dict.fromkeys([*bases, *names, *(b for n in names for b in DERIVED.get(n, ()))]))
    scalar = np.ndim(Vs) == 0
    Vs = np.atleast_1d(np.asarray(Vs, dtype=float))     # the precision routes want an array of velocities
    table = d.evaluate(Vs, params, base_names)
    scalars = {k: v for k, v in (params or {}).items() if np.ndim(v) == 0}
    arrays = {k: np.asarray(v, dtype=float) for k, v in (params or {}).items() if np.ndim(v) > 0}
    p = d.block.resolve(scalars)
    args = d.block.argvals(Vs, {**p, **arrays})
    shape = np.broadcast(*[np.asarray(x) for x in args]).shape
    args = [np.broadcast_to(np.asarray(x, dtype=float), shape) for x in args]
    kc = np.broadcast_to(np.asarray(table["kc"], dtype=float), shape)
    om = np.broadcast_to(np.asarray(table["omega_c"], dtype=float), shape)
    ev = _Evaluation(d, _programs(d), args, which, kc, om, False, names)
    out: dict[str, dict[str, np.ndarray]] = {"value": {}}
    final = () if scalar and shape == (1,) else shape
    for q in names:
        v, t = ev.quantity(q)
        t = np.broadcast_to(t, (len(which), *shape))
        out[q] = {pn: np.array(t[i]).reshape(final) for i, pn in enumerate(which)}
        out["value"][q] = np.broadcast_to(np.asarray(v, dtype=float), shape).reshape(final).copy()
    return out


def _evaluate_points_mp(d: "Derivation", Vs, params, quantities, parameters_) -> dict[str, dict[str, np.ndarray]]:
    """:func:`evaluate_mp` at each velocity, gathered into float64 arrays (NaN without a Hopf point)."""
    names = [check_quantity(q) for q in quantities]
    which = [check_parameter(d, p) for p in (parameters_ if parameters_ is not None else parameters(d))]
    V = np.asarray(Vs, dtype=float)
    if np.any(~np.isfinite(V)) or np.any(V <= 0):
        raise InputError("driving velocity V must be finite and > 0")
    flat = np.ravel(V)
    out: dict[str, dict[str, np.ndarray]] = {"value": {q: np.full(flat.shape, np.nan) for q in names}}
    for q in names:
        out[q] = {pn: np.full(flat.shape, np.nan) for pn in which}
    for i, Vi in enumerate(flat):
        try:
            res = evaluate_mp(d, float(Vi), params, names, which)
        except NoHopfError:
            continue
        for q in names:
            out["value"][q][i] = float(res["value"][q])
            for pn in which:
                out[q][pn][i] = float(res[q][pn])
    return {key: {k: v.reshape(V.shape) for k, v in table.items()} for key, table in out.items()}


def evaluate_mp(d: "Derivation", V0: float, params: Mapping[str, float] | None, quantities: Sequence[str],
                parameters_: Sequence[str] | None = None, dps: int = 50) -> dict[str, dict[str, Any]]:
    """∂q/∂p at one point with mpmath at ``dps`` digits (see :func:`evaluate`).

    Raises
    ------
    NoHopfError
        There is no Hopf point at V0.
    """
    names = [check_quantity(q) for q in quantities]
    which = [check_parameter(d, p) for p in (parameters_ if parameters_ is not None else parameters(d))]
    p = d.block.resolve(params)
    with mpmath.workdps(dps):
        base = d.evaluate_mp(V0, p, ["kc", "omega_c"], dps=dps)
        vals = [mpmath.mpf(x) for x in d.block.argvals(V0, p)]
        if d.system.unknowns:
            # the numeric steady states at the working precision (a float64 root would limit dps)
            vals = _refine_unknowns(d, vals)
        ev = _Evaluation(d, _programs(d), vals, which, base["kc"], base["omega_c"], True, names)
        out: dict[str, dict[str, Any]] = {"value": {}}
        for q in names:
            v, t = ev.quantity(q)
            out[q] = {pn: t[i] for i, pn in enumerate(which)}
            out["value"][q] = v
    return out


def _refine_unknowns(d: "Derivation", vals: list) -> list:
    system = d.system
    idx = [d.args.index(u) for u in system.unknowns]
    fn = sp.lambdify([*d.args], [sp.sympify(e) for e in system.unknown_equations], "mpmath")

    def eqs(*phis):
        v = list(vals)
        for i, ph in zip(idx, phis, strict=True):
            v[i] = ph
        out = fn(*v)
        return out if len(idx) > 1 else out[0]

    root = mpmath.findroot(eqs, [vals[i] for i in idx])
    root = [root] if len(idx) == 1 else list(root)
    out = list(vals)
    for i, r in zip(idx, root, strict=True):
        out[i] = r
    return out


@dataclass(eq=False)
class Sensitivity:
    """∂q/∂p of one amplitude-equation quantity q along one parameter p (module docstring).

    Obtain it with :meth:`landau.derivation.multiscale.Derivation.sensitivity`; call it like a
    coefficient: ``d.sensitivity("k_c", "a")(1e-4, b=0.02)``.

    Parameters
    ----------
    quantity : str
        The quantity (internal name: ``kc`` for k_c).
    parameter : str
        The parameter.
    derivation : Derivation
    """

    quantity: str
    parameter: str
    derivation: "Derivation" = field(repr=False)
    _cache: dict = field(default_factory=dict, repr=False)

    @property
    def name(self) -> str:
        """``d(k_c)/d(a)``: the key under which the CLI reports it."""
        q = "k_c" if self.quantity == "kc" else self.quantity
        return f"d({q})/d({self.parameter})"

    @property
    def units(self) -> str:
        """The SI unit: the quantity's per the parameter's."""
        from landau.derivation.coefficients import UNITS

        d = self.derivation
        law_units = {prm.name: prm.units for prm in d.block.law.parameters}
        pu = {"V": "m/s", **law_units, **d.block.units}.get(self.parameter) or "1"
        return UNITS[self.quantity] if pu == "1" else f"({UNITS[self.quantity]})/({pu})"

    def __call__(self, Vs, params: Mapping[str, Any] | None = None, **overrides: Any) -> np.ndarray:
        """∂q/∂p in float64 over velocities (NaN where there is no Hopf point)."""
        from landau.derivation.multiscale import _merged

        res = evaluate(self.derivation, Vs, _merged(params, overrides), [self.quantity], [self.parameter])
        return res[self.quantity][self.parameter]

    def evaluate_mp(self, V0: float, params: Mapping[str, float] | None = None, dps: int = 50):
        """∂q/∂p at one point with mpmath at ``dps`` digits."""
        res = evaluate_mp(self.derivation, V0, params, [self.quantity], [self.parameter], dps)
        return res[self.quantity][self.parameter]

    def closed_form(self) -> sp.Expr:
        """∂q/∂p in closed form: the derivative of :meth:`Coefficient.closed_form` in V and the
        parameters, cancelled and factored when it is rational.

        Raises
        ------
        InputError
            The Hopf line has no closed form (several state variables).
        """
        if "closed" not in self._cache:
            d = self.derivation
            if d.hopf.closed_form is None:
                raise InputError(f"{d.block.law.name}: no closed form (the Hopf line is numeric); "
                                 "evaluate the sensitivity instead")
            p = next(s for s in d.args if s.name == self.parameter)
            if self.quantity in DERIVED:
                gb = d.coefficient("Gamma_bar").closed_form()
                la = d.coefficient("Lambda").closed_form()
                C = d.coefficient("C").formula.xreplace({_GB: gb, _LA: la})
                # C = 2 sqrt(2Γ̄/|Λ|): dC = C (dΓ̄/Γ̄ − dΛ/Λ)/2
                e = C * (sp.diff(gb, p) / gb - sp.diff(la, p) / la) / 2
            else:
                e = sp.diff(d.coefficient(self.quantity).closed_form(), p)
                if all(e.is_rational_function(s) for s in e.free_symbols):
                    e = sp.factor(sp.cancel(sp.together(e)))
            self._cache["closed"] = e
        return self._cache["closed"]

    def latex(self) -> str:
        """``\\partial q/\\partial p = …`` of :meth:`closed_form` as an ``align*`` block (long lines split,
        the paper's symbols)."""
        if "latex" not in self._cache:
            from landau.derivation.coefficients import ALL_QUANTITIES
            from landau.report.latex import align_block, equation_lines, symbol_latex

            lhs = (rf"\frac{{\partial {ALL_QUANTITIES[self.quantity][0]}}}"
                   rf"{{\partial {symbol_latex(self.parameter)}}}")
            self._cache["latex"] = align_block(equation_lines(lhs, self.closed_form(), {}, letter="S"))
        return self._cache["latex"]

    def __repr__(self) -> str:
        return f"Sensitivity({self.name} of law {self.derivation.block.law.name!r}, [{self.units}])"


def parse_pairs(d: "Derivation", spec: str, quantities: Sequence[str]) -> list[tuple[str, str]]:
    """(quantity, parameter) pairs from ``"k_c:a,Lambda:b"``; ``Q:*`` is every parameter,
    ``*:P`` every quantity of ``quantities``, ``all`` every pair.

    Raises
    ------
    InputError
        A malformed item, an unknown quantity or parameter (with the closest known name).
    """
    out: list[tuple[str, str]] = []
    items = [x.strip() for x in str(spec).split(",") if x.strip()]
    if not items:
        raise InputError("--sensitivity: no QUANTITY:PARAMETER pair given (e.g. k_c:a)")
    for item in items:
        if item == "all":
            q_part, p_part = "*", "*"
        elif item.count(":") != 1:
            raise InputError(f"--sensitivity: {item!r} is not QUANTITY:PARAMETER (e.g. k_c:a, Lambda:*, all)")
        else:
            q_part, p_part = (x.strip() for x in item.split(":"))
        qs = list(quantities) if q_part == "*" else [q_part]
        ps = list(parameters(d)) if p_part == "*" else [p_part]
        for q in qs:
            check_quantity(q)
            for p in ps:
                check_parameter(d, p)
                if (q, p) not in out:
                    out.append((q, p))
    return out


__all__ = ["SENSITIVE", "Sensitivity", "evaluate", "evaluate_mp", "parameters"]
