"""The amplitude equation of the spring–block Hopf bifurcation (Putelat et al. 2010, Sec. 2.2).

``derive(block, quantities=[...])`` returns a lazy :class:`Derivation`: each requested
coefficient is derived through the Fredholm condition (:mod:`landau.derivation.fredholm`) on first
use and only from the derivative orders it needs — k_c and ω_c need first derivatives;
Γ̄, Ω̄ add ∂/∂k; Λ and χ add second and third derivatives.

Convention (eq. 20): d|A|/dT = (Γ|A| + Λ|A|³)/2, dθ/dT = (Ω + χ|A|²)/2 with the critical
mode normalised so that its slip (X) component is 1 (u₀ = (1, z)); Γ = −2Γ̄(k − k_c)/ε²,
Ω = 2Ω̄(k − k_c)/ε².  Λ < 0: supercritical Hopf; Λ > 0: subcritical.  The
normalisation-free slip amplitude is max|x − x₀| ≈ C·sqrt(k_c − k),
C = (4ω_c/|δ|)(F_V/|Λ|)^{1/2} = 2 sqrt(2Γ̄/|Λ|) (eq. 23; for a subcritical point, the
unstable cycle for k > k_c).
"""

from __future__ import annotations

import time
from functools import cached_property
from typing import Any, Iterable, Mapping, Sequence

import mpmath
import numpy as np
import sympy as sp

from landau.codegen.formula import AtomTable, CompiledFormula
from landau.derivation import precision, precision_numeric
from landau.derivation.coefficients import (  # noqa: F401
    _GB,
    _LA,
    ALL_QUANTITIES,
    CONVENTION,
    DERIVED,
    QUANTITIES,
    QUINTIC,
    UNITS,
    Coefficient,
    CoefficientTable,
    _with_bases,
    criticality,
    internal_name,
)
from landau.derivation.fredholm import cubic_coefficient, linear_coefficient, null_vectors, quintic_coefficient
from landau.derivation.hopf import spring_block_c1, spring_block_result
from landau.derivation.linear import HopfLine, w
from landau.derivation.parameter_jets import ParameterJets
from landau.derivation.precision import BLOCK as _BLOCK  # noqa: F401
from landau.errors import InputError, NoHopfError
from landau.support.cx import Cx, as_expr
from landau.systems.system import SpringBlock


class Derivation:
    """Lazy multiple-scales derivation for a :class:`SpringBlock` (see module docstring).

    Each coefficient is derived on first request and kept; :func:`landau.derive` builds one.

    Parameters
    ----------
    block : SpringBlock or FrictionLaw or str
        The system (a law or a built-in law's name is wrapped in a :class:`SpringBlock`).

    References
    ----------
    Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), "Regimes of frictional sliding of a
    spring–block system", J. Mech. Phys. Solids 58(1), 27–53, eqs (23), (32)–(35).
    """

    def __init__(self, block: SpringBlock):
        block = _as_block(block)
        self.block = block
        self.system = block.system
        self.jets = ParameterJets(self.system)
        self.hopf = HopfLine(block, self.jets)
        self.k = self.system.parameter
        self.args = block.args
        self.timings: dict[str, float] = {}
        self._coefs: dict[str, Coefficient] = {}
        self._compiled: dict[tuple[str, str], CompiledFormula] = {}
        self._atom_table = AtomTable(self.jets.atoms, self.args)
        self._rational_cache: dict = {}

    # --- symbolic route ---------------------------------------------------------------
    def _structure(self) -> tuple[list, list, int, int]:
        J = self.jets.jacobian()
        E = list(self.system.mass)
        p = self.k
        n = len(E)
        entries = [(i, j) for i in range(n) for j in range(n) if p in as_expr(J[i][j]).free_symbols]
        if len(entries) > 1:
            # α_LD puts k in the state row too (dσ/dt = −γ_LD k u): drop the row of the entry in the
            # normalised (slip) column; the minor left, rows ≠ u and columns ≠ X, is det(iω − G_φ) ≠ 0
            entries = [(i, j) for i, j in entries if j == self.system.normalise]
        if len(entries) != 1:
            raise InputError("symbolic route needs the Hopf parameter in one Jacobian entry, or in one entry "
                             "of the normalised column")
        return J, E, entries[0][0], entries[0][1]

    @cached_property
    def vectors(self):
        """u₀ (q) and u₀* (ψ) of eq. (11) in atoms, with ω symbolic."""
        J, E, r, c = self._structure()
        return null_vectors(J, E, w, self.system.normalise, r, c)

    @cached_property
    def alpha_over_delta(self) -> Cx:
        """α/δ per unit k₂ (eqs 17–18)."""
        fp, Jp = self.jets.parameter_derivatives()
        J, _, _, _ = self._structure()
        B2 = self.jets.order(2) if any(f != 0 for f in fp) else {}
        return linear_coefficient(self.vectors, J, Jp, fp, B2)

    @cached_property
    def beta_over_delta(self) -> Cx:
        """β/δ (eqs 15–19)."""
        J, E, _, _ = self._structure()
        return cubic_coefficient(self.vectors, J, E, w, self.jets.order(2), self.jets.order(3), sp.Rational(1, 2))

    @cached_property
    def quintic(self):
        """b and c of dA/dT = b A|A|² + c A|A|⁴ at the Hopf point
        (:func:`landau.derivation.fredholm.quintic_coefficient`),
        in atoms with ω symbolic; builds the fourth and fifth derivatives (only when asked for)."""
        J, E, _, _ = self._structure()
        tensors = {m: self.jets.order(m) for m in (2, 3, 4, 5)}
        return quintic_coefficient(self.vectors, J, E, w, tensors, sp.Integer(1))

    def formula(self, name: str) -> sp.Expr:
        """The quantity ``name`` in the law's derivative atoms (ω and k as symbols).

        Parameters
        ----------
        name : str
            One of :data:`ALL_QUANTITIES`.

        Returns
        -------
        sympy.Expr

        Raises
        ------
        InputError
            An unknown quantity.
        """
        if name == "Lambda5":
            return 2 * self.quintic.c.re
        if name in ("kc", "k_c"):
            return self.k
        if name == "omega_c":
            return w
        if name == "Gamma_bar":
            return -self.alpha_over_delta.re
        if name == "Omega_bar":
            return self.alpha_over_delta.im
        if name == "Lambda":
            return 2 * self.beta_over_delta.re
        if name == "chi":
            return 2 * self.beta_over_delta.im
        if name == "C":
            # built from Γ̄ and Λ symbols: never ask sympy for |Λ| of the full expression
            return 2 * sp.sqrt(2 * _GB / sp.Abs(_LA))
        raise InputError(f"unknown quantity {name!r} (known: {', '.join(QUANTITIES)})")

    def coefficient(self, name: str) -> Coefficient:
        """The :class:`Coefficient` ``name``, derived on first request.

        Parameters
        ----------
        name : str
            One of :data:`ALL_QUANTITIES`.

        Returns
        -------
        Coefficient
        """
        name = internal_name(name)
        for base in DERIVED.get(name, ()):
            self.coefficient(base)
        if name not in ALL_QUANTITIES:
            raise InputError(f"unknown quantity {name!r} (known: {', '.join(ALL_QUANTITIES)})")
        if name not in self._coefs:
            t0 = time.perf_counter()
            self._coefs[name] = Coefficient(name, self._cached_formula(name), self)
            self.timings[name] = time.perf_counter() - t0
        return self._coefs[name]

    def _cached_formula(self, name: str) -> sp.Expr:
        """formula(name), from the disk cache (:mod:`landau.support.cache`) when this system was
        derived before; the atoms the formula uses are restored with it."""
        if name in ("kc", "omega_c") or name in DERIVED:
            return self.formula(name)
        from landau.support import cache

        key = cache.make_key("formula", cache.system_key(self.system), name)
        hit = cache.get("formula", key)
        if hit is not None:
            formula, atoms = hit
            for sym, value in atoms.items():
                self.jets.atoms.setdefault(sym, value)
            return formula
        formula = self.formula(name)
        cache.put("formula", key, (formula, dict(self.jets.atoms)))
        return formula

    # --- display (never derives, never simplifies: only reports what exists) -------------
    def _status(self) -> dict[str, str]:
        """quantity -> "closed form cached" / "derived" / "not built" (reads caches only)."""
        out = {}
        for n in QUANTITIES:
            c = self._coefs.get(n)
            if c is None:
                out[n] = "not built"
            elif "closed" in c._cache:
                out[n] = "derived, closed form cached"
            else:
                out[n] = "derived"
        return out

    def _hopf_status(self) -> str:
        if "closed_form" not in vars(self.hopf):
            return "not derived yet"
        return "closed form in V" if self.hopf.closed_form is not None else "numeric (no closed form)"

    def __repr__(self) -> str:
        law = self.block.law
        built = [n for n in QUANTITIES if n in self._coefs]
        states = ", ".join(s.name for s in self.system.states)
        return (f"Derivation(law {law.name!r} [{law.source}], system {self.system.name} with states ({states}), "
                f"Hopf parameter {self.k}; built: {', '.join(built) or 'nothing yet'}; "
                f"Hopf line: {self._hopf_status()})")

    def _repr_html_(self) -> str:
        import html

        from landau.report.display import html_table

        law = self.block.law
        esc = html.escape
        status = self._status()
        rows = [{"quantity": n, "symbol": QUANTITIES[n][0], "meaning": QUANTITIES[n][1], "source": QUANTITIES[n][2],
                 "units": UNITS[n], "status": status[n],
                 "derived in [s]": self.timings.get(n)} for n in QUANTITIES]
        states = ", ".join(s.name for s in self.system.states)
        params = ", ".join(f"{k} = {v:g}" for k, v in self.block.defaults.items())
        head = (f"<div class='landau-result'><b>Amplitude-equation derivation: law {esc(law.name)}</b>"
                f"<br><small>{esc(law.source)}</small>"
                f"<br>system: {esc(self.system.name)}, states ({esc(states)}), Hopf parameter {esc(str(self.k))}; "
                f"Hopf line: {esc(self._hopf_status())}<br>default parameters: {esc(params)}</div>")
        return head + html_table(rows, note=f"Convention: {CONVENTION}")

    def plot(self, V=(1e-6, 1e-2), params: Mapping[str, float] | None = None,
             names: Sequence[str] = ("kc", "Lambda", "C"), n: int = 200, *, fig=None):
        """Plot coefficients against the driving velocity with the criticality bands.

        Parameters
        ----------
        V : tuple (lo, hi) or array_like
            A velocity range given as a tuple (lo, hi) in m/s, sampled at ``n`` log-spaced
            points; a list or array gives the velocities themselves.
        params : mapping, optional
            Parameter overrides.
        names : sequence of str
            Quantities to plot, one panel each (default k_c, Λ, C).
        n : int
            Points of a (lo, hi) range.
        fig : matplotlib Figure, optional
            Draw into this figure.

        Returns
        -------
        matplotlib.figure.Figure
        """
        if isinstance(V, tuple) and len(V) == 2:
            lo, hi = map(float, V)
            if not (0 < lo < hi) or int(n) < 2:
                raise InputError(f"velocity range needs 0 < lo < hi and n >= 2, got {lo!r}:{hi!r}, n = {n!r}")
            Vs = np.logspace(np.log10(lo), np.log10(hi), int(n))
        else:
            Vs = np.asarray(V, dtype=float)
        table = self.evaluate(Vs, params, list(_with_bases(["kc", "omega_c", "Lambda", *names])))
        return table.plot(names, fig=fig)

    # --- numerics ---------------------------------------------------------------------
    def _compiled_formula(self, name: str, modules: str = "numpy") -> CompiledFormula:
        key = (name, modules)
        if key not in self._compiled:
            f = self.coefficient(name).formula
            self._compiled[key] = CompiledFormula(f, (w, self.k, *self.args), self.jets.atoms, modules)
        return self._compiled[key]

    @cached_property
    def _hopf_mp(self):
        kc, W_c = self.hopf.closed_form
        return (CompiledFormula(kc, self.args, self.jets.atoms, "mpmath"),
                CompiledFormula(W_c, self.args, self.jets.atoms, "mpmath"))

    def evaluate_mp(self, V0: float, params: Mapping[str, float], names: Iterable[str],
                    dps: int = 50) -> dict[str, Any]:
        """The same formulas evaluated at one point with mpmath at ``dps`` digits.

        Parameters
        ----------
        V0 : float
            Driving velocity, m/s.
        params : mapping of str to float
            Parameter values.
        names : iterable of str
            The quantities.
        dps : int, optional
            Decimal digits of working precision (default 50).

        Returns
        -------
        dict
            Quantity name -> mpmath value (NaN where there is no Hopf point).
        """
        from landau.derivation.linear import one_velocity

        V0 = one_velocity(V0, "V", "evaluate(V)") if not isinstance(V0, mpmath.mpf) else V0
        # a point read back from a table of argument values carries the numeric steady states φᵢ,₀
        # too: they are recomputed here, never taken as parameters
        unknowns = {s.name for s in self.block.phi0}   # names a law may not declare ("phi_0")
        p = self.block.resolve({k: x for k, x in params.items() if k not in unknowns})
        with mpmath.workdps(dps):
            vals = [mpmath.mpf(x) for x in self.block.argvals(V0, p)]
            if self.hopf.closed_form is None:
                kc, W_c = self.hopf.numeric_point_mp(vals)
            else:
                fk, fW = self._hopf_mp
                kc = fk(*vals)
                W_c = fW(*vals)
            if not (W_c > 0 and kc > 0):
                raise NoHopfError(f"V = {V0:g} m/s: no Hopf bifurcation")
            om = mpmath.sqrt(W_c)
            out = {"kc": kc, "omega_c": om}
            for n in _with_bases(names):
                if n not in out:
                    if n in DERIVED:
                        lam = out["Lambda"]
                        out[n] = mpmath.inf if lam == 0 else 2 * mpmath.sqrt(2 * out["Gamma_bar"] / abs(lam))
                    else:
                        out[n] = self._compiled_formula(n, "mpmath")(om, kc, *vals)
            return out

    def evaluate(self, Vs, params: Mapping[str, float] | None = None,
                 names: Sequence[str] = ("kc", "omega_c", "Gamma_bar", "Lambda"),
                 method: str = "auto", sign_only: bool = False, **overrides: Any) -> CoefficientTable:
        """Vectorised evaluation over velocities (any parameter may also be an array).

        NaN where there is no Hopf point.  Every value is accurate to 1e-10 relative or
        settled by a slower route (:mod:`landau.derivation.precision`): the exactly cancelled form when
        the law's derivatives are rational in V (:mod:`landau.derivation.rational`: Dieterich, Ruina,
        modified Dieterich); otherwise, for batches of 1000 points or more, float64 with a
        first-order error bound and the points it does not certify in double-double
        (:mod:`landau.codegen.bounded`; on a Hopf line without closed form the bound includes
        that of the numeric (ω_c, k_c), :mod:`landau.codegen.bounded_hopf`), for smaller ones
        float64 screened by float32 or long double; what is still doubtful from the exactly
        cancelled form where it exists, else
        with mpmath at 50 and 80 digits, and at up to 550 digits until two successive
        precisions agree (a tiny but genuine value, e.g. Λ ∝ M at M = 1e-50, keeps its value
        and sign).  A quantity that vanishes identically is returned as 0 and the point
        flagged ``degenerate``.

        ``method``: "general" (the float routes above), "rational" (every point from the
        exactly cancelled form, with error bounds and exact fallback; laws rational in V only)
        or "auto": "rational" for large batches (≥ 1e5 points) and once the cancelled form for
        these parameters exists, else "general".

        ``sign_only=True`` is for callers that use only the signs (a scan for sign changes): a
        point whose extended-precision value is certain in sign (its error, estimated from the
        float64–extended difference, below a tenth of its size) keeps that value and is not
        re-evaluated with mpmath; the values returned there may be off by more than 1e-10.

        Parameters
        ----------
        Vs : float or array_like
            Driving velocities, m/s.
        params : mapping of str to float, optional
            Parameter overrides (values may be arrays broadcasting against ``Vs``).
        names : sequence of str, optional
            The quantities (default k_c, ω_c, Γ̄, Λ).  The critical stiffness is ``"k_c"``
            (canonical) or ``"kc"`` (deprecated alias, kept for one release); the table carries it
            under the name asked for (``"kc"`` when neither is named) and answers ``table["k_c"]``
            and ``table["kc"]`` alike.
        method : {"auto", "general", "rational"}
            The evaluation route (see above).
        sign_only : bool, optional
            Whether only the signs are needed (see above).
        **overrides : float or array_like
            Parameter values as keywords, merged with ``params``:
            ``d.evaluate([1e-4, 1e-3], M=1.2, names=["k_c", "Lambda"])``.

        Returns
        -------
        CoefficientTable
            One array per quantity, shaped like the broadcast inputs.
        """
        if method not in ("auto", "general", "rational"):
            raise InputError(f"unknown evaluation method {method!r} (auto, general, rational)")
        if isinstance(names, str):  # evaluate(Vs, None, "Lambda"): one quantity, not its letters
            names = [names]
        asked = list(names)
        names = [internal_name(n) for n in asked]   # k_c (canonical) is built as kc (its deprecated alias)
        params = _merged(params, overrides)
        p = self.block.resolve({k: v for k, v in (params or {}).items() if np.ndim(v) == 0})
        arr = {k: np.asarray(v, dtype=float) for k, v in (params or {}).items() if np.ndim(v) > 0}
        Vs = np.asarray(Vs, dtype=float)
        if np.any(~np.isfinite(Vs)) or np.any(Vs <= 0):
            raise InputError("driving velocity V must be finite and > 0")
        vals = self.block.argvals(Vs, {**p, **arr})
        shape = np.broadcast(*[np.asarray(x) for x in vals]).shape
        vals = [np.broadcast_to(np.asarray(x, dtype=float), shape) for x in vals]
        bases = [n for n in _with_bases(names) if n not in ("kc", "omega_c") and n not in DERIVED]
        closed = self.hopf.closed_form is not None
        forms = raw = None
        if closed and not arr and method != "general" and (
                method == "rational" or Vs.size >= precision.RATIONAL_DIRECT or precision.has_rational(self, bases, p)):
            forms = precision.rational_forms(self, bases, p)
            if forms is None and method == "rational":
                raise InputError(f"{self.block.law.name}: the derivatives at steady sliding are not rational in V")
        if forms is None and closed and method == "auto":   # float64 with an error bound, double-double where needed
            raw = precision.bounded_route(self, Vs, vals, shape, bases, p, not arr, sign_only)
        if raw is not None:
            pass
        elif forms is not None:
            raw = precision.exact_rational_route(self, Vs, shape, bases, forms)
        elif closed:
            raw = precision.screened_route(self, Vs, vals, shape, bases, p, not arr, sign_only)
        else:
            if method == "auto":    # float64 with error bounds, double-double where needed
                raw = precision_numeric.bounded_numeric_route(self, Vs, vals, shape, bases, p, sign_only)
            if raw is None:
                raw = precision_numeric.numeric_hopf_route(self, Vs, vals, shape, bases, p, sign_only)
        table = precision.finish(self, Vs, vals, raw, names, bases, sign_only, {**p, **arr})
        if "k_c" in asked and "kc" not in asked:   # under the name asked for
            return CoefficientTable({("k_c" if k == "kc" else k): v for k, v in table.items()},
                                    law=table.law, params=table.params)
        return table

    # --- sensitivities (landau.derivation.sensitivity) -----------------------------------
    def sensitivity(self, quantity: str, parameter: str):
        """The exact sensitivity ∂q/∂p of a quantity to a parameter
        (:class:`~landau.derivation.sensitivity.Sensitivity`: call it, or ask its closed form and LaTeX).

        Parameters
        ----------
        quantity : str
            ``"k_c"``, ``"omega_c"``, ``"Gamma_bar"``, ``"Omega_bar"``, ``"Lambda"``, ``"chi"`` or ``"C"``.
        parameter : str
            ``"V"``, a law parameter, ``"M"``, ``"sigma"`` or an optional term's parameter.

        Returns
        -------
        Sensitivity

        Raises
        ------
        InputError
            An unknown quantity or parameter (with the closest known name).
        """
        from landau.derivation import sensitivity as sens

        return sens.Sensitivity(sens.check_quantity(quantity), sens.check_parameter(self, parameter), self)

    def sensitivities(self, Vs, params: Mapping[str, Any] | None = None,
                      quantities: Sequence[str] = ("k_c", "omega_c", "Gamma_bar", "Lambda", "C"),
                      parameters: Sequence[str] | None = None,
                      method: str = "auto") -> dict[str, dict[str, np.ndarray]]:
        """Every ∂q/∂p at once over velocities (one forward pass per quantity,
        :func:`landau.derivation.sensitivity.evaluate`: at 50 digits for a few points, float64 vectorised
        for many).

        Parameters
        ----------
        Vs : float or array_like
            Driving velocities, m/s.
        params : mapping, optional
            Parameter values.
        quantities : sequence of str, optional
            The quantities q.
        parameters : sequence of str, optional
            The parameters p (default: all of them).
        method : {"auto", "float64", "mpmath"}
            The arithmetic (:func:`landau.derivation.sensitivity.evaluate`).

        Returns
        -------
        dict
            quantity (the name as given) -> {parameter -> array}, and ``"value"`` -> {quantity -> array};
            NaN where there is no Hopf point.
        """
        from landau.derivation import sensitivity as sens

        res = sens.evaluate(self, Vs, params, list(quantities), parameters, method)
        rename = {internal_name(q): q for q in quantities}
        return {rename.get(k, k): v for k, v in res.items()} | {
            "value": {rename.get(k, k): v for k, v in res["value"].items()}}

    def _evaluate_mp_checked(self, V0: float, point: Mapping[str, float], names,
                             sign_estimate: Mapping[str, float] | None = None) -> tuple[dict, bool]:
        """Values at 50 digits, or more until two precisions agree (see
        :func:`landau.derivation.precision.evaluate_mp_checked`); returns them and whether Λ vanishes identically."""
        return precision.evaluate_mp_checked(self, V0, point, names, sign_estimate)

    def points(self, Vs, params: Mapping[str, float] | None = None,
               names: Sequence[str] = ("Gamma_bar", "Lambda", "C"), **overrides: float) -> list[Any]:
        """Per-velocity :class:`~landau.derivation.hopf.HopfResult` (or the linear :class:`HopfPoint` when
        there is no Hopf point).

        Each point is in the spring–block convention (Putelat et al. 2010, eq. 20): p = k,
        dλ/dk = −Γ̄ + iΩ̄, with ``V``, ``kc``, ``Gamma_bar``, ``Omega_bar`` as typed fields, and
        Kuznetsov's ``l1``, ``c1`` in the state coordinates (X, u = Ẋ, φ…)
        (:func:`~landau.derivation.hopf.spring_block_c1`; they depend on those coordinates, Λ and C do not).

        Parameters
        ----------
        Vs : float or sequence of float
            Driving velocities, m/s.
        params : mapping of str to float, optional
            Parameter overrides.
        names : sequence of str, optional
            The coefficients evaluated together (default Γ̄, Λ, C: their values are exactly
            those of :meth:`evaluate` with these names); Ω̄ and χ, which every point carries,
            are evaluated separately where not named.  Any other quantity named (``"Lambda5"``)
            is carried too.
        **overrides : float
            Parameter values as keywords, merged with ``params`` (``d.points(1e-4, M=1.2)``).

        Returns
        -------
        list of HopfResult or HopfPoint
            A :class:`~landau.report.display.ResultList` (one table in a notebook).
        """
        from landau.derivation.linear import _velocities

        Vs = _velocities(Vs)
        params = _merged(params, overrides)
        res = self.evaluate(Vs, params, ["kc", "omega_c", *names])
        rest = [n for n in ("Gamma_bar", "Omega_bar", "Lambda", "chi") if n not in names]
        more = self.evaluate(Vs, params, rest) if rest else {}
        resolved = self.block.resolve(params)
        equilibrium = self._equilibrium_function(resolved)
        lin = None
        out: list[Any] = []
        for i, Vi in enumerate(Vs):
            if not np.isfinite(res["kc"][i]):
                lin = lin or self.hopf.points(Vs, params)
                out.append(lin[i])
                continue
            values = {n: float(res[n][i]) for n in names}
            values.update({n: float(more[n][i]) for n in rest})
            if res["degenerate"][i] or (rest and more["degenerate"][i]):
                values["Lambda"] = 0.0            # vanishes identically: criticality degenerate, C infinite
            fields = {n: values.pop(n) for n in ("Gamma_bar", "Omega_bar", "Lambda", "chi")}
            values.pop("C", None)                 # a property of the result (the same formula)
            quintic = {"Lambda5": values.pop("Lambda5")} if "Lambda5" in values else {}
            kc = float(res["kc"][i])
            om = float(res["omega_c"][i])
            eq = equilibrium(float(Vi), kc)
            at = {**resolved, "V": float(Vi), **self._unknowns(float(Vi), resolved)}
            kuznetsov = spring_block_c1(self.system, at, kc, om, fields["Lambda"], fields["chi"], eq)
            out.append(self.block.name_terms(spring_block_result(
                self.block.law.name, float(Vi), kc, om, params={**resolved, "V": float(Vi)},
                equilibrium=eq, **fields, **quintic, **kuznetsov)))
        from landau.report.display import ResultList

        return ResultList(out, title=f"Hopf points of law {self.block.law.name}", units=UNITS)

    def _unknowns(self, V: float, resolved: Mapping[str, float]) -> dict[str, float]:
        """The steady states φᵢ,₀ at V by their symbols' names where they have no closed form (else {})."""
        unknowns = self.system.unknowns
        if not unknowns:
            return {}
        vals = self.block.argvals(np.array([V]), resolved)
        return {u.name: float(np.ravel(vals[self.args.index(u)])[0]) for u in unknowns}

    def _equilibrium_function(self, resolved: Mapping[str, float]):
        """(V, k) -> the steady sliding state (X, u, φ…) as floats; () where it has no closed form."""
        system = self.system
        if system.unknowns:
            return lambda V, k: ()
        by_name = {s.name: s for s in system.parameters}
        fixed = {by_name[n]: v for n, v in resolved.items() if n in by_name}
        V = by_name.get("V", sp.Dummy())
        exprs = [as_expr(e).xreplace(fixed) for e in system.equilibrium]
        if set().union(*(e.free_symbols for e in exprs)) - {V, self.k}:
            return lambda Vi, k: ()
        fn = sp.lambdify([V, self.k], exprs, modules="math")
        return lambda Vi, k: tuple(float(y) for y in fn(Vi, k))


def _merged(params: Mapping[str, Any] | None, overrides: Mapping[str, Any]) -> dict[str, Any] | None:
    """``params`` with the keyword ``overrides`` added; a name given both ways is an InputError."""
    if not overrides:
        return params if params is None else dict(params)
    if params is not None and not isinstance(params, Mapping):
        raise InputError(f"params must be a mapping of parameter names to values, got {type(params).__name__}")
    both = sorted(set(params or {}) & set(overrides))
    if both:
        raise InputError(f"parameter {both[0]!r} is given twice (in params and as a keyword)")
    return {**(params or {}), **overrides}


def _as_block(block) -> SpringBlock:
    """A :class:`SpringBlock` from a block, a :class:`FrictionLaw` or a built-in law's name."""
    if isinstance(block, SpringBlock):
        return block
    from landau.laws import FrictionLaw

    if isinstance(block, str):
        from landau.laws import get_law

        return SpringBlock(get_law(block))
    if isinstance(block, FrictionLaw):
        return SpringBlock(block)
    raise InputError(f"derive needs a SpringBlock, a FrictionLaw or a built-in law's name, got {type(block).__name__}")


def derive(block: SpringBlock, quantities: Sequence[str] | None = None) -> Derivation:
    """Derive the requested amplitude-equation coefficients (default: all) — lazily.

    Only the derivative orders the requested quantities need are built; the rest are
    derived on first use.

    Parameters
    ----------
    block : SpringBlock
        The spring–block with its friction law.
    quantities : sequence of str, optional
        Any of ``"k_c"`` (or its deprecated alias ``"kc"``), ``"omega_c"``, ``"Gamma_bar"``,
        ``"Omega_bar"``, ``"Lambda"``, ``"chi"``, ``"C"`` (default: all).

    Returns
    -------
    Derivation
        Evaluate it with :meth:`Derivation.evaluate` or :meth:`Derivation.points`; get one
        coefficient's formula, closed form and LaTeX with :meth:`Derivation.coefficient`.

    References
    ----------
    Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a
    spring–block system. J. Mech. Phys. Solids 58, 27–53, Sec. 2.2, eqs (7)–(23).
    """
    d = Derivation(block)
    if isinstance(quantities, str):
        quantities = [quantities]
    for q in quantities or QUANTITIES:
        d.coefficient(q)
    return d
