"""The amplitude equation of the spring–block Hopf bifurcation (Putelat et al. 2010, Sec. 2.2).

``derive(block, quantities=[...])`` returns a lazy :class:`Derivation`: each requested
coefficient is derived through the Fredholm condition (:mod:`landau.fredholm`) on first
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

import logging
import os
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Iterable, Mapping, Sequence

import mpmath
import numpy as np
import sympy as sp

from landau.codegen import AtomTable, CompiledFormula
from landau.cx import Cx, as_expr
from landau.errors import InputError, NoHopfError, SingularPointError
from landau.fredholm import cubic_coefficient, linear_coefficient, null_vectors, quintic_coefficient
from landau.hopf import SPRING_BLOCK_UNITS, spring_block_result
from landau.jets import Jets
from landau.linear import HopfLine, w
from landau.system import SpringBlock

logger = logging.getLogger(__name__)

CONVENTION = ("d|A|/dT = (Gamma |A| + Lambda |A|^3)/2, dtheta/dT = (Omega + chi |A|^2)/2 (Putelat et al. 2010 eq. 20); "
              "Gamma = -2 Gamma_bar (k - kc)/eps^2, Omega = 2 Omega_bar (k - kc)/eps^2; critical mode normalised "
              "with slip component 1; Lambda < 0: supercritical, Lambda > 0: subcritical; "
              "C = max|x - x0| / sqrt(|kc - k|) = 2 sqrt(2 Gamma_bar/|Lambda|) (eq. 23)")
#: smallest grid on which Derivation.evaluate compiles the bounded program (landau.bounded) when
#: it is not compiled already: below, the compile (0.4–0.9 s) costs more than it saves
BOUNDED_MIN_POINTS = 20_000

#: SI units of the spring–block quantities (and of a spring–block :class:`~landau.hopf.HopfResult`'s fields)
UNITS = SPRING_BLOCK_UNITS

#: quantity -> (LaTeX symbol, description, equation)
QUANTITIES: dict[str, tuple[str, str, str]] = {
    "kc": (r"k_c", "critical stiffness", "eq. (7)"),
    "omega_c": (r"\omega_c", "angular frequency at onset", "eq. (8)"),
    "Gamma_bar": (r"\bar\Gamma", "linear growth rate per unit k_c - k", "eqs (18), (21)"),
    "Omega_bar": (r"\bar\Omega", "linear frequency shift per unit k - k_c", "eqs (18), (21)"),
    "Lambda": (r"\Lambda", "Landau coefficient", "eqs (15)-(21)"),
    "chi": (r"\chi", "nonlinear frequency coefficient", "eqs (15)-(21)"),
    "C": (r"C", "slip amplitude per sqrt(k_c - k)", "eq. (23)"),
}

#: fifth-order quantities: built only when asked for by name (never by ``derive(block)``'s default)
QUINTIC: dict[str, tuple[str, str, str]] = {
    "Lambda5": (r"\Lambda_5", "quintic coefficient 2 Re c of dA/dT = ... + c A|A|^4 (slip component of the mode 1)",
                "Fredholm condition at O(eps^5)"),
}
#: every quantity a :class:`Derivation` can build
ALL_QUANTITIES = {**QUANTITIES, **QUINTIC}

_GB, _LA = sp.symbols("Gamma_bar Lambda", real=True)
#: quantities composed from others (name -> the base quantities they need)
DERIVED = {"C": ("Gamma_bar", "Lambda")}

#: accuracy every returned value must have (relative)
_REL_GOOD = 1e-10
#: doubtful points from which deriving the exactly cancelled form beats mpmath point by point
_RATIONAL_MIN = 500
#: points from which the exactly cancelled form (~0.2 s to derive per parameter set) beats the
#: general formula for all of them (float64 + float32 screen + extended pass, ~1e6 points/s)
_RATIONAL_DIRECT = 100_000
#: points per block of the vectorised evaluation (working set of a formula stays in cache)
_BLOCK = 16_384
#: threads for the blocks (numpy's elementwise loops release the GIL)
_WORKERS = max(1, min(8, os.cpu_count() or 1))
#: float32 vs float64 disagreement above which float64 may miss _REL_GOOD.  The eps ratio is
#: ~5e8, but the float64 error was measured up to ~200x larger than that ratio predicts from
#: the float32 disagreement (spinodal law at V ~ 3e-8 m/s: 1.2e-10 behind a 0.5 % disagreement),
#: hence 2e-4 rather than 2e-2
_REL_SCREEN = 2e-4
#: digits of the successive mpmath evaluations that decide whether a tiny value is genuine
_MP_LADDER = (50, 80, 120, 200, 330, 550)
#: extended precision available (x86 80-bit long double: eps 1.1e-19, ~1000x float64)
_EXTENDED = np.finfo(np.longdouble).eps < 1e-18
_EXT_GAIN = float(np.finfo(np.float64).eps / np.finfo(np.longdouble).eps) / 4


@dataclass(frozen=True, eq=False)
class Coefficient:
    """One amplitude-equation coefficient: formula, closed form, LaTeX and compiled code.

    ``formula`` is in the derivative atoms of the law (see :mod:`landau.jets`) with the
    onset frequency ``omega`` and stiffness ``k`` as symbols; :attr:`expr` is the same
    quantity in terms of V and the parameters; ``coef(V, **params)`` evaluates it
    vectorised (float64, with a 50-digit fallback where ω_c² suffers cancellation).

    Parameters
    ----------
    name : str
        The quantity, one of :data:`ALL_QUANTITIES` (``"kc"``, ``"omega_c"``, ``"Gamma_bar"``,
        ``"Omega_bar"``, ``"Lambda"``, ``"chi"``, ``"C"``, ``"Lambda5"``).
    formula : sympy.Expr
        The formula in the law's derivative atoms.
    derivation : Derivation
        The derivation it belongs to (obtain coefficients with :meth:`Derivation.coefficient`).

    References
    ----------
    Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), "Regimes of frictional sliding of a
    spring–block system", J. Mech. Phys. Solids 58(1), 27–53, eqs (23), (32)–(35), (44)–(45).
    """

    name: str
    formula: sp.Expr
    derivation: "Derivation" = field(repr=False)
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def symbol(self) -> str:
        """The LaTeX symbol (e.g. ``\\Lambda``)."""
        return ALL_QUANTITIES[self.name][0]

    @property
    def units(self) -> str:
        """SI units of the coefficient."""
        return UNITS[self.name]

    @property
    def expr(self) -> sp.Expr:
        """The coefficient in terms of V and the parameters (atoms substituted, ω = sqrt(ω_c²))."""
        if "expr" not in self._cache:
            d = self.derivation
            kc, W_c = d.hopf.closed_form or (None, None)
            if kc is None:
                raise InputError(f"{d.block.law.name}: no closed form (the Hopf line is numeric)")
            if self.name in DERIVED:
                e = self.formula.xreplace({_GB: d.coefficient("Gamma_bar").expr, _LA: d.coefficient("Lambda").expr})
            else:
                e = d.jets.expand_atoms(self.formula.xreplace({d.k: kc}).xreplace({w: sp.sqrt(W_c)}))
            self._cache["expr"] = e
        return self._cache["expr"]

    def closed_form(self) -> sp.Expr:
        """A simplified closed form (e.g. eqs 32–35, 44–45).

        An expression rational after ω_c = sqrt(ω_c²) is cancelled and factored; a law whose
        derivatives at steady sliding are rational in V and the parameters (Dieterich, Ruina)
        is re-derived in the field ℚ(V, parameters)(ω_c) (:func:`landau.rational.closed_form`:
        FLINT polynomials, well under a second; cached on disk); otherwise the unsimplified
        :attr:`expr` is returned.

        Returns
        -------
        sympy.Expr
            The coefficient in V and the law's parameters.

        Raises
        ------
        InputError
            The Hopf line has no closed form (a numeric Hopf line).
        """
        if "closed" not in self._cache:
            d = self.derivation
            if self.name in DERIVED:
                e = self.formula.xreplace({_GB: d.coefficient("Gamma_bar").closed_form(),
                                           _LA: d.coefficient("Lambda").closed_form()})
            elif self.name in QUINTIC:
                e = self.expr  # fifth order: too large for cancellation and factoring (seconds become hours)
            else:
                from landau.progress import progress

                # one status line while the closed form is (re-)derived: a terminal or notebook only
                with progress(total=1, desc=f"closed form of {self.name}", unit="form") as bar:
                    e = self.expr
                    if all(e.is_rational_function(s) for s in e.free_symbols):
                        e = sp.factor(sp.cancel(sp.together(e)))
                    elif self.name not in ("kc", "omega_c"):
                        from landau.rational import closed_form

                        e = closed_form(d, self.name) or e
                    bar.update()
            self._cache["closed"] = e
        return self._cache["closed"]

    def latex(self) -> str:
        """The coefficient as LaTeX (an ``aligned`` block, long lines split, paper symbols):
        the factored closed form in V and the parameters when the law's derivatives at steady
        sliding are rational (computed once, cached on disk), else the form in those
        derivatives (:func:`landau.latex.coefficient_latex`).

        Returns
        -------
        str
            LaTeX for a math environment.

        Raises
        ------
        InputError
            For the quintic coefficient (too large to print).
        """
        if self.name in QUINTIC:
            raise InputError(f"{self.name}: the fifth-order closed form is too large to print; "
                             "evaluate it (Derivation.evaluate) or use .formula (in the law's derivatives)")
        if "latex" not in self._cache:
            from landau.latex import coefficient_latex

            self._cache["latex"] = coefficient_latex(self)
        return self._cache["latex"]

    def _repr_latex_(self) -> str:
        # display never computes: the LaTeX already made by latex(), else a one-line summary
        if "latex" in self._cache:
            return f"$\\displaystyle {self._cache['latex']}$"
        desc = QUANTITIES[self.name][1].replace("_", r"\_")
        return (f"${self.symbol}$: {desc} (Putelat et al. 2010, {QUANTITIES[self.name][2]}), "
                f"units {self.units.replace('^', '')}; .latex() gives the formula")

    def __repr__(self) -> str:
        return f"Coefficient({self.name}: {ALL_QUANTITIES[self.name][1]}, {ALL_QUANTITIES[self.name][2]}, [{self.units}])"

    def __call__(self, Vs, **params) -> np.ndarray:
        return self.derivation.evaluate(Vs, params, [self.name])[self.name]


class CoefficientTable(dict):
    """Evaluated amplitude-equation coefficients: a dict of arrays (name -> values over V).

    What :meth:`Derivation.evaluate` returns.  It is a plain ``dict`` for every existing use
    (``table["Lambda"]``), and adds what a notebook user expects: :attr:`units`,
    :meth:`to_dataframe` (pandas, units in the column names and in ``df.attrs``),
    :meth:`plot` (the coefficients against V with the criticality bands) and an HTML table.

    Parameters
    ----------
    data : mapping
        Quantity name -> array (``"V"``, ``"kc"``, ``"omega_c"``, …, ``"degenerate"``).
    law : str
        Name of the friction law.
    params : mapping
        The parameter values the table was evaluated at.
    """

    def __init__(self, data: Mapping[str, Any] = (), law: str = "", params: Mapping[str, Any] | None = None):
        super().__init__(data)
        self.law = law
        self.params = dict(params or {})

    @property
    def units(self) -> dict[str, str]:
        """Quantity -> SI unit for the quantities in the table."""
        return {k: UNITS[k] for k in self if k in UNITS}

    def columns(self, limit: int | None = None) -> dict[str, np.ndarray]:
        """Flat columns (arrays broadcast together and flattened in C order; the first
        ``limit`` points if given), with the criticality of each point as a string column
        when Λ is in the table."""
        if not self:
            return {}
        shape = np.broadcast(*[np.asarray(v) for v in self.values()]).shape
        if limit is None:
            flat = {k: np.ravel(np.broadcast_to(np.asarray(v), shape)) for k, v in self.items()}
        else:
            flat = {k: np.broadcast_to(np.asarray(v), shape).flat[:limit] for k, v in self.items()}
        degenerate = flat.pop("degenerate", np.zeros(flat[next(iter(flat))].shape, dtype=bool))
        if "Lambda" in flat and "kc" in flat:
            lam = flat["Lambda"]
            flat["criticality"] = np.where(~np.isfinite(flat["kc"]), "no Hopf point",
                                           np.where(degenerate | ~np.isfinite(lam) | (lam == 0), "degenerate",
                                                    np.where(lam < 0, "supercritical", "subcritical")))
        return flat

    def rows(self, limit: int | None = None) -> list[dict[str, Any]]:
        """One mapping per point (the first ``limit`` points if given), see :meth:`columns`."""
        cols = self.columns(limit)
        n = len(next(iter(cols.values()))) if cols else 0
        return [{k: c[i].item() for k, c in cols.items()} for i in range(n)]

    def to_dataframe(self):
        """The table as a pandas DataFrame.

        Returns
        -------
        pandas.DataFrame
            One row per point; units in the column names (``"kc [N/m]"``) and in
            ``df.attrs["units"]``; ``df.attrs`` also holds the law and the parameters.

        Raises
        ------
        ImportError
            When pandas is missing (``pip install 'landau-friction[notebook]'``).
        """
        from landau.display import require_pandas

        pd = require_pandas("CoefficientTable.to_dataframe()")
        units = self.units
        df = pd.DataFrame({(f"{c} [{units[c]}]" if c in units else c): v for c, v in self.columns().items()})
        df.attrs.update(units=units, law=self.law, params=dict(self.params))
        return df

    def plot(self, names: Sequence[str] | None = None, *, fig=None):
        """k_c, Λ, C, … against V with the super/subcritical bands shaded; returns the Figure
        (see :func:`landau.plotting.plot_coefficients`)."""
        from landau.plotting import plot_coefficients

        return plot_coefficients(self, names, fig=fig)

    def _size(self) -> int:
        return int(np.prod(np.broadcast(*[np.asarray(v) for v in self.values()]).shape)) if self else 0

    def _repr_html_(self) -> str:
        from landau.display import MAX_ROWS, html_table

        n = self._size()
        shown = "" if n <= MAX_ROWS else f", the first {MAX_ROWS} shown"
        title = f"Amplitude-equation coefficients, law {self.law}" if self.law else "Amplitude-equation coefficients"
        return html_table(self.rows(MAX_ROWS), units=self.units, title=title,
                          note=f"{n} point(s){shown}. Convention: {CONVENTION}")

    def __repr__(self) -> str:
        from landau.display import text_table

        n = self._size()
        names = ", ".join(k for k in self if k != "degenerate")
        more = f"\n… {n - 20} more points" if n > 20 else ""
        return (f"CoefficientTable(law {self.law!r}, {n} point(s): {names})\n"
                + text_table(self.rows(20), units=self.units) + more)


def _agree(x: np.ndarray, y: np.ndarray, rel: float) -> np.ndarray:
    """|x − y| ≤ rel·|y| elementwise; two NaNs agree (no Hopf point in either precision)."""
    with np.errstate(all="ignore"):
        return (np.abs(x - y) <= rel * np.abs(y)) | (np.isnan(x) & np.isnan(y))


def _sign_settled(x64: np.ndarray, x80: np.ndarray) -> np.ndarray:
    """Where the extended-precision value is certain in sign: non-zero, and its error — the
    float64 error |x64 − x80| scaled down by the precision gain — below a tenth of its size."""
    with np.errstate(all="ignore"):
        return (x80 != 0) & np.isfinite(x80) & (np.abs(x64 - x80) <= 0.1 * _EXT_GAIN * np.abs(x80))


def _with_bases(names: Iterable[str]) -> list[str]:
    """names with the base quantities of derived ones placed before them."""
    out: list[str] = []
    for n in names:
        for b in DERIVED.get(n, ()):
            if b not in out:
                out.append(b)
        if n not in out:
            out.append(n)
    return out


def criticality(lam: float, scale: float = 0.0) -> str:
    if not np.isfinite(lam) or abs(lam) <= scale:
        return "degenerate"
    return "supercritical" if lam < 0 else "subcritical"


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
        self.jets = Jets(self.system)
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
        rows = [i for i in range(len(E)) if any(p in as_expr(J[i][j]).free_symbols for j in range(len(E)))]
        cols = [j for j in range(len(E)) if any(p in as_expr(J[i][j]).free_symbols for i in range(len(E)))]
        if len(rows) != 1 or len(cols) != 1:
            raise InputError("symbolic route needs the Hopf parameter in exactly one Jacobian entry")
        return J, E, rows[0], cols[0]

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
        """b and c of dA/dT = b A|A|² + c A|A|⁴ at the Hopf point (:func:`landau.fredholm.quintic_coefficient`),
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
        if name == "kc":
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
        """formula(name), from the disk cache (:mod:`landau.cache`) when this system was
        derived before; the atoms the formula uses are restored with it."""
        if name in ("kc", "omega_c") or name in DERIVED:
            return self.formula(name)
        from landau import cache

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

        from landau.display import html_table

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

    def _bounded_kernel(self, bases: Sequence[str], n_points: int = BOUNDED_MIN_POINTS):
        """k_c, ω_c² and the coefficients ``bases`` as one compiled program with a round-off
        bound (:class:`landau.bounded.BoundedKernel`); None where it cannot be built (an
        operation it does not know, an llvmlite without LLVM 16 IR), and the float32-screened
        route is used.

        Compiling the program costs 0.4–0.9 s per law and set of coefficients, which only pays
        off on large grids: below :data:`BOUNDED_MIN_POINTS` points it is used only when it is
        already compiled (in this process, or its object files are in the disk cache)."""
        key = ("bounded", tuple(bases))
        if key in self._compiled:
            return self._compiled[key]
        from landau.bounded import EXTENDED, BoundedKernel

        varying = [True] + [False] * (len(self.args) - 1)
        draft_key = ("bounded-draft", tuple(bases))
        if draft_key not in self._compiled:
            kc, W_c = self.hopf.closed_form
            defs = {**self.jets.atoms, w: sp.sqrt(W_c), self.k: kc}
            try:
                draft = BoundedKernel([kc, W_c, *(self.coefficient(n).formula for n in bases)], self.args, defs)
                cheap = draft.ready(varying)
            except Exception as exc:  # an unknown operation: the old route, for good
                logger.info("%s: no bounded kernel (%s)", self.block.law.name, exc)
                self._compiled[key] = None
                return None
            self._compiled[draft_key] = (draft, cheap)
        kernel, cheap = self._compiled[draft_key]
        if n_points < BOUNDED_MIN_POINTS and not cheap:
            return None
        try:
            kernel.compiled(varying)
            if EXTENDED:
                kernel.compiled_extended()
        except Exception as exc:  # an llvmlite too old for the IR: old route
            logger.info("%s: no bounded kernel (%s)", self.block.law.name, exc)
            kernel = None
        self._compiled[key] = kernel
        return kernel

    @cached_property
    def _hopf_mp(self):
        kc, W_c = self.hopf.closed_form
        return (CompiledFormula(kc, self.args, self.jets.atoms, "mpmath"),
                CompiledFormula(W_c, self.args, self.jets.atoms, "mpmath"))

    def evaluate_mp(self, V0: float, params: Mapping[str, float], names: Iterable[str], dps: int = 50) -> dict[str, Any]:
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
        p = self.block.resolve(params)
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
                 method: str = "auto", sign_only: bool = False) -> dict[str, np.ndarray]:
        """Vectorised evaluation over velocities (any parameter may also be an array).

        NaN where there is no Hopf point.  Every value is checked for round-off: with a
        closed-form Hopf line, k_c, ω_c² and the coefficients are one compiled program that
        computes a first-order bound of its own round-off at every point
        (:mod:`landau.bounded`); where the bound exceeds 1e-10 (cancellation near an extremum
        of μ_ss, inertia-free limits, Λ ≡ 0 at M = 0) the rounding errors of the program are
        computed and added back (compensated float64, with its own bound), then what is still
        unproven runs again in 80-bit extended precision with its own bound; a value is used
        where it is proven to 1e-10 (laws
        whose formulas the program cannot express use a float32 screen instead).  What is still doubtful is taken from
        the exactly cancelled form when the law's derivatives are rational in V
        (:mod:`landau.rational`: Dieterich, Ruina, modified Dieterich), else re-evaluated at 50
        and 80 digits with mpmath, and at up to 550 digits until two successive precisions
        agree (a tiny but genuine value, e.g. Λ ∝ M at M = 1e-50, keeps its value and sign).
        A quantity that vanishes identically is returned as 0 and the point flagged
        ``degenerate``.

        ``method``: "general" (the route above), "rational" (every point from the exactly
        cancelled form, with error bounds and exact fallback; laws rational in V only) or
        "auto": "rational" for large batches (≥ 1e5 points) and once the cancelled form for
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
            The quantities (default k_c, ω_c, Γ̄, Λ).
        method : {"auto", "general", "rational"}
            The evaluation route (see above).
        sign_only : bool, optional
            Whether only the signs are needed (see above).

        Returns
        -------
        dict of str to numpy.ndarray
            One array per quantity, shaped like the broadcast inputs.
        """
        if method not in ("auto", "general", "rational"):
            raise InputError(f"unknown evaluation method {method!r} (auto, general, rational)")
        if isinstance(names, str):  # evaluate(Vs, None, "Lambda"): one quantity, not its letters
            names = [names]
        p = self.block.resolve({k: v for k, v in (params or {}).items() if np.ndim(v) == 0})
        arr = {k: np.asarray(v, dtype=float) for k, v in (params or {}).items() if np.ndim(v) > 0}
        Vs = np.asarray(Vs, dtype=float)
        if np.any(~np.isfinite(Vs)) or np.any(Vs <= 0):
            raise InputError("driving velocity V must be finite and > 0")
        vals = self.block.argvals(Vs, {**p, **arr})
        shape = np.broadcast(*[np.asarray(x) for x in vals]).shape
        vals = [np.broadcast_to(np.asarray(x, dtype=float), shape) for x in vals]
        bases = [n for n in _with_bases(names) if n not in ("kc", "omega_c") and n not in DERIVED]
        forms = None
        if self.hopf.closed_form is not None and not arr and method != "general" and (
                method == "rational" or Vs.size >= _RATIONAL_DIRECT or self._has_rational(bases, p)):
            forms = self._rational_forms(bases, p)
            if forms is None and method == "rational":
                raise InputError(f"{self.block.law.name}: the derivatives at steady sliding are not rational in V")
        if forms is not None:
            raw = forms.evaluate(np.broadcast_to(Vs, shape), bases, _REL_GOOD)
            need_mp = np.zeros(shape, dtype=bool)
            exact_zero = np.full(shape, "Lambda" in forms and forms["Lambda"].identically_zero)
        elif self.hopf.closed_form is None:
            if arr:
                raise InputError("array-valued parameters need a closed-form Hopf line (one state variable)")
            kc, om = self.hopf.evaluate(Vs.ravel(), p)
            raw = {"kc": kc.reshape(shape), "W": om.reshape(shape) ** 2}
            raw.update(self._raw(vals, shape, bases, np.float64, raw["kc"], np.sqrt(raw["W"])))
            # screen: the same formulas in extended precision at the same (k_c, ω_c); where
            # float64 loses more than _REL_GOOD to round-off, the point goes to mpmath
            need_mp = np.zeros(shape, dtype=bool)
            if _EXTENDED and bases:
                ld = np.longdouble
                ext = self._raw([v.astype(ld) for v in vals], shape, bases, ld, raw["kc"].astype(ld),
                                np.sqrt(raw["W"]).astype(ld))
                for n in bases:
                    x80 = ext[n].astype(float)
                    doubtful = ~_agree(raw[n], x80, _REL_GOOD)
                    if sign_only:
                        doubtful &= ~_sign_settled(raw[n], x80)
                        raw[n] = np.where(doubtful, raw[n], x80)
                    need_mp |= doubtful
            elif bases:
                need_mp[...] = True
            need_mp &= np.isfinite(raw["kc"])
            exact_zero = np.zeros(shape, dtype=bool)
        else:
            kernel = self._bounded_kernel(bases, int(np.prod(shape)))
            if kernel is not None:
                # compiled, with a first-order round-off bound at every point: proven values
                # are kept, the rest refined in long double (landau.bounded), then below
                from landau.bounded import evaluate_proven

                flat, unproven = evaluate_proven(kernel, vals, _REL_GOOD, _WORKERS, sign_only)
                keys = ["kc", "W", *bases]
                raw = {key: flat[j].reshape(shape) for j, key in enumerate(keys)}
                bad = {key: unproven[j].reshape(shape) for j, key in enumerate(keys)}
            else:
                raw = self._raw(vals, shape, bases, np.float64)
                # cheap screen: the same code in float32; where it disagrees by more than 2 % the
                # float64 value may be off by more than ~1e-10 (errors scale with the unit round-off)
                r32 = self._raw([v.astype(np.float32) for v in vals], shape, bases, np.float32)
                suspect = np.zeros(shape, dtype=bool)
                for key in raw:
                    suspect |= ~_agree(raw[key], r32[key].astype(float), _REL_SCREEN)
                bad = {key: suspect.copy() for key in raw}
                if _EXTENDED and suspect.any():
                    # the suspects again in extended precision: keep the value where float64 and it
                    # agree; take the extended value where it is itself good enough; else mpmath
                    sub = [v[suspect].astype(np.longdouble) for v in vals]
                    ext = self._raw(sub, sub[0].shape, bases, np.longdouble)
                    for key in raw:
                        x64, x80 = raw[key][suspect], ext[key].astype(float)
                        good64 = _agree(x64, x80, _REL_GOOD)
                        raw[key][suspect] = np.where(good64, x64, x80)
                        bad[key][suspect] = ~_agree(x64, x80, _REL_GOOD * _EXT_GAIN)
                        if sign_only:
                            bad[key][suspect] &= ~_sign_settled(x64, x80)
            need_mp = np.zeros(shape, dtype=bool)
            for key in raw:
                need_mp |= bad[key]
            hopf_ok = ~(bad["kc"] | bad["W"])
            rest = need_mp & hopf_ok & (raw["kc"] > 0) & (raw["W"] > 0)
            exact_zero = np.zeros(shape, dtype=bool)
            # the exact route costs ~1 s to derive per parameter set: worth it for many points
            if bases and not arr and (rest.sum() >= _RATIONAL_MIN or (rest.any() and self._has_rational(bases, p))):
                resolved, exact_zero = self._exact_rational(Vs, vals, raw, rest, bases, p)
                need_mp &= ~resolved
        kc, W_c = raw["kc"], raw["W"]
        ok = (kc > 0) & (W_c > 0)
        out: dict[str, np.ndarray] = {"V": Vs * np.ones(shape), "kc": np.where(ok, kc, np.nan),
                                      "omega_c": np.sqrt(np.where(ok, W_c, np.nan))}
        for n in bases:
            out[n] = raw[n]
        out["degenerate"] = exact_zero & ok
        extra = [n for n in _with_bases(names) if n not in ("kc", "omega_c")]
        if np.any(need_mp & ok):
            logger.info("%s: 50-digit fallback at %d points", self.block.law.name, int(np.sum(need_mp & ok)))
        for idx in map(tuple, np.argwhere(need_mp & ok)):
            point = {s.name: float(vals[i + 1][idx]) for i, s in enumerate(self.args[1:])}
            estimate = {n: float(out[n][idx]) for n in extra if n in out} if sign_only else None
            mp, degenerate = self._evaluate_mp_checked(float(vals[0][idx]), point, extra, estimate)
            for n in ("kc", "omega_c", *extra):
                if n not in DERIVED:
                    out[n][idx] = float(mp[n])
            out["degenerate"][idx] = degenerate
        if "C" in names:
            with np.errstate(all="ignore"):
                out["C"] = 2 * np.sqrt(2 * out["Gamma_bar"] / np.abs(out["Lambda"]))
        for n in bases:
            singular = np.isfinite(out["kc"]) & ~np.isfinite(out[n])
            if np.any(singular):
                i = tuple(np.argwhere(singular)[0])
                raise SingularPointError(
                    f"{self.block.law.name}: {n} is not finite at V = {float(out['V'][i]):g} m/s although a Hopf "
                    "point exists there: the law's derivatives are singular at this steady state")
        return CoefficientTable(out, law=self.block.law.name, params={**p, **arr})

    def _has_rational(self, bases, params) -> bool:
        return (tuple(bases), tuple(sorted(params.items()))) in self._rational_cache

    def _rational_forms(self, bases, params):
        """The exactly cancelled forms (:mod:`landau.rational`) for these parameters, cached;
        None when the law's derivatives at steady state are not rational in V."""
        from landau.rational import rational_forms

        key = (tuple(bases), tuple(sorted(params.items())))
        if key not in self._rational_cache:
            self._rational_cache[key] = rational_forms(self, bases, params)
        return self._rational_cache[key]

    def _exact_rational(self, Vs, vals, raw, where, bases, params) -> tuple[np.ndarray, np.ndarray]:
        """Points of ``where`` settled by the exactly cancelled form when every derivative at
        steady state is rational in V; returns the settled mask and the points where Λ
        vanishes identically."""
        settled = np.zeros(where.shape, dtype=bool)
        forms = self._rational_forms(bases, params)
        if forms is None:
            return settled, settled
        sub = forms.evaluate(np.broadcast_to(Vs, where.shape)[where], bases, _REL_GOOD)
        for n in bases:
            raw[n][where] = sub[n]
        settled[where] = True
        degenerate = settled & bool("Lambda" in forms and forms["Lambda"].identically_zero)
        return settled, degenerate

    def _raw(self, vals, shape, bases, dtype, kc=None, om=None) -> dict[str, np.ndarray]:
        """k_c, ω_c² and the requested coefficients in one precision, atoms shared.

        Large batches go through in blocks of _BLOCK points, on _WORKERS threads: the formulas
        are long chains of elementwise operations; blocks that fit in cache run them faster and
        numpy releases the GIL inside each operation."""
        size = int(np.prod(shape))
        if size <= _BLOCK:
            return self._raw_block(vals, shape, bases, dtype, kc, om)
        flat = [np.ravel(v) for v in vals]
        kcf = None if kc is None else np.ravel(kc)
        omf = None if om is None else np.ravel(om)
        self._raw_block([v[:1] for v in flat], (1,), bases, dtype, None if kcf is None else kcf[:1],
                        None if omf is None else omf[:1])          # compile once, outside the threads

        def block(i: int) -> tuple[slice, dict[str, np.ndarray]]:
            sl = slice(i, min(i + _BLOCK, size))
            return sl, self._raw_block([v[sl] for v in flat], (sl.stop - sl.start,), bases, dtype,
                                       None if kcf is None else kcf[sl], None if omf is None else omf[sl])

        out: dict[str, np.ndarray] = {}
        # numpy releases the GIL inside each elementwise operation: blocks run on all cores
        with ThreadPoolExecutor(max_workers=_WORKERS) as pool:
            for sl, part in pool.map(block, range(0, size, _BLOCK)):
                for key, val in part.items():
                    out.setdefault(key, np.empty(size, dtype=val.dtype))[sl] = val
        return {key: val.reshape(shape) for key, val in out.items()}

    def _raw_block(self, vals, shape, bases, dtype, kc=None, om=None) -> dict[str, np.ndarray]:
        formulas = [self._compiled_formula(n) for n in bases]
        hopf = self.hopf._compiled_closed if kc is None else ()
        atoms = self._atom_table.evaluate(
            sorted(set().union(*(f.atom_syms for f in [*formulas, *hopf])), key=str), *vals)
        res: dict[str, np.ndarray] = {}
        if kc is None:
            fk, fW = hopf
            res["kc"] = np.asarray(fk.call_with_atoms(atoms, *vals), dtype=dtype) * np.ones(shape, dtype)
            res["W"] = np.asarray(fW.call_with_atoms(atoms, *vals), dtype=dtype) * np.ones(shape, dtype)
            with np.errstate(all="ignore"):
                om = np.sqrt(np.where(res["W"] > 0, res["W"], np.nan))
            kc = res["kc"]
        for n, f in zip(bases, formulas):
            res[n] = np.asarray(f.call_with_atoms(atoms, om, kc, *vals), dtype=dtype) * np.ones(shape, dtype)
        return res

    def _evaluate_mp_checked(self, V0: float, point: Mapping[str, float], names,
                             sign_estimate: Mapping[str, float] | None = None) -> tuple[dict, bool]:
        """Values at 50 digits, or more where needed.  A coefficient whose values at two
        successive precisions (50, 80, 120, 200, 330, 550 digits) agree to 1e-20 relative is
        settled at the finer one: a tiny but genuine value (e.g. Λ ∝ M at M = 1e-50) is
        cancellation-free once the precision exceeds the orders it lies below its terms.  A
        coefficient that never settles is round-off of an identically vanishing quantity
        (its value keeps shrinking with the precision): it is returned as 0 and flagged.

        ``sign_estimate`` (a sign scan's float values at this point): round-off grows with the
        unit round-off times the same condition number at every precision, so a 50-digit value
        h whose float estimate f (unit round-off ≥ 5e-20) is off by |h − f| is itself off by
        about |h − f|·1e-30.  Where |h − f| ≤ 1e20·|h| (f non-zero) that is below 1e-10·|h|:
        the sign is certain and the 50-digit values are returned without climbing the ladder.
        Round-off of a quantity that vanishes identically, or a genuine value far below its
        terms (|h − f| ~ 1e34·|h|), still climbs it."""
        ladder = _MP_LADDER
        hi = self.evaluate_mp(V0, point, names, dps=ladder[0])
        if sign_estimate is not None and all(
                n in DERIVED or (hi[n] != 0 and sign_estimate.get(n, 0.0) != 0
                                 and abs(hi[n] - sign_estimate.get(n, float("nan"))) <= 1e20 * abs(hi[n]))
                for n in names):
            return dict(hi), False
        ref = self.evaluate_mp(V0, point, names, dps=ladder[1])
        degenerate = False
        res = dict(hi)
        tol = mpmath.mpf("1e-20")
        for n in names:
            if n in DERIVED:
                continue
            if abs(hi[n] - ref[n]) <= tol * abs(ref[n]):
                continue
            prev, settled = ref[n], None
            for dps in ladder[2:]:
                cur = self.evaluate_mp(V0, point, [n], dps=dps)[n]
                if abs(cur - prev) <= tol * abs(cur):
                    settled = cur
                    break
                prev = cur
            if settled is not None:
                res[n] = settled
            else:
                res[n] = mpmath.mpf(0)
                degenerate = degenerate or n == "Lambda"
        if degenerate and "C" in res:
            res["C"] = mpmath.inf
        return res, degenerate

    def points(self, Vs, params: Mapping[str, float] | None = None,
               names: Sequence[str] = ("Gamma_bar", "Lambda", "C")) -> list[Any]:
        """Per-velocity :class:`~landau.hopf.HopfResult` (or the linear :class:`HopfPoint` when
        there is no Hopf point).

        Each point is in the spring–block convention (Putelat et al. 2010, eq. 20): p = k,
        dλ/dk = −Γ̄ + iΩ̄, with ``V``, ``kc``, ``Gamma_bar``, ``Omega_bar`` in ``extra``.

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

        Returns
        -------
        list of HopfResult or HopfPoint
            A :class:`~landau.display.ResultList` (one table in a notebook).
        """
        Vs = np.atleast_1d(np.asarray(Vs, dtype=float))
        res = self.evaluate(Vs, params, ["kc", "omega_c", *names])
        rest = [n for n in ("Gamma_bar", "Omega_bar", "Lambda", "chi") if n not in names]
        more = self.evaluate(Vs, params, rest) if rest else {}
        resolved = self.block.resolve(params)
        equilibrium = self._equilibrium_function(resolved)
        lin = None
        out = []
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
            out.append(spring_block_result(self.block.law.name, float(Vi), kc, float(res["omega_c"][i]),
                                           params={**resolved, "V": float(Vi)}, extra=values,
                                           equilibrium=equilibrium(float(Vi), kc), **fields, **quintic))
        from landau.display import ResultList

        return ResultList(out, title=f"Hopf points of law {self.block.law.name}", units=UNITS)

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


def _as_block(block) -> SpringBlock:
    """A :class:`SpringBlock` from a block, a :class:`FrictionLaw` or a built-in law's name."""
    if isinstance(block, SpringBlock):
        return block
    from landau.laws import FrictionLaw

    if isinstance(block, (FrictionLaw, str)):
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
        Any of ``"kc"``, ``"omega_c"``, ``"Gamma_bar"``, ``"Omega_bar"``, ``"Lambda"``,
        ``"chi"``, ``"C"`` (default: all).

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
