"""The amplitude-equation coefficients of the spring–block Hopf bifurcation (Putelat et al. 2010, Sec. 2.2):
their names, symbols and units, one :class:`Coefficient` (formula, closed form, LaTeX) and the
:class:`CoefficientTable` that :meth:`landau.derivation.multiscale.Derivation.evaluate` returns.

Convention (eq. 20): d|A|/dT = (Γ|A| + Λ|A|³)/2, dθ/dT = (Ω + χ|A|²)/2, critical mode normalised
with slip component 1; C = 2 sqrt(2Γ̄/|Λ|) (eq. 23).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Iterable, Mapping, Sequence

import numpy as np
import sympy as sp

from landau.derivation.hopf import SPRING_BLOCK_UNITS
from landau.derivation.linear import w
from landau.errors import InputError

if TYPE_CHECKING:
    from landau.derivation.multiscale import Derivation

CONVENTION = ("d|A|/dT = (Gamma |A| + Lambda |A|^3)/2, dtheta/dT = (Omega + chi |A|^2)/2 (Putelat et al. 2010 eq. 20); "
              "Gamma = -2 Gamma_bar (k - k_c)/eps^2, Omega = 2 Omega_bar (k - k_c)/eps^2; critical mode normalised "
              "with slip component 1; Lambda < 0: supercritical, Lambda > 0: subcritical; "
              "C = (half peak-to-peak swing of x - x0) / sqrt(|k_c - k|) = 2 sqrt(2 Gamma_bar/|Lambda|) (eq. 23; "
              "max|x - x0| differs from it at O(eps))")

#: SI units of the spring–block quantities (and of a spring–block :class:`~landau.derivation.hopf.HopfResult`'s fields)
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

#: deprecated quantity names, kept for one release -> their canonical names (``kc`` -> ``k_c``)
DEPRECATED_NAMES: dict[str, str] = {"kc": "k_c"}


def internal_name(name: str) -> str:
    """The name a :class:`Derivation` computes ``name`` under: the critical stiffness ``k_c`` (canonical)
    is built as ``kc`` (its deprecated alias); every other name is itself."""
    return "kc" if name == "k_c" else name


def with_canonical_names(doc: Mapping[str, Any]) -> dict[str, Any]:
    """``doc`` with the canonical key (``k_c``) placed after each deprecated one (``kc``) it carries.

    Parameters
    ----------
    doc : mapping
        A JSON record or a units dict.

    Returns
    -------
    dict
        The same entries, with ``k_c`` beside ``kc`` (same value) where only ``kc`` was present.
    """
    out: dict[str, Any] = {}
    for key, value in doc.items():
        out[key] = value
        new = DEPRECATED_NAMES.get(key)
        if new is not None and new not in doc:
            out[new] = value
    return out


_GB, _LA = sp.symbols("Gamma_bar Lambda", real=True)
#: quantities composed from others (name -> the base quantities they need)
DERIVED = {"C": ("Gamma_bar", "Lambda")}


@dataclass(frozen=True, eq=False)
class Coefficient:
    """One amplitude-equation coefficient: formula, closed form, LaTeX and compiled code.

    ``formula`` is in the derivative atoms of the law (see :mod:`landau.derivation.jets`) with the
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
        is re-derived in the field ℚ(V, parameters)(ω_c) (:func:`landau.derivation.rational.closed_form`:
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
                from landau.support.progress import progress

                # one status line while the closed form is (re-)derived: a terminal or notebook only
                with progress(total=1, desc=f"closed form of {self.name}", unit="form") as bar:
                    e = self.expr
                    if all(e.is_rational_function(s) for s in e.free_symbols):
                        e = sp.factor(sp.cancel(sp.together(e)))
                    elif self.name not in ("kc", "omega_c"):
                        from landau.derivation.rational import closed_form

                        e = closed_form(d, self.name) or e
                    bar.update()
            self._cache["closed"] = e
        return self._cache["closed"]

    def latex(self) -> str:
        """The coefficient as LaTeX (an ``aligned`` block, long lines split, paper symbols):
        the factored closed form in V and the parameters when the law's derivatives at steady
        sliding are rational (computed once, cached on disk), else the form in those
        derivatives (:func:`landau.derivation.latex.coefficient_latex`).

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
            from landau.derivation.latex import coefficient_latex

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
        meaning, symbol = ALL_QUANTITIES[self.name][1], ALL_QUANTITIES[self.name][2]
        return f"Coefficient({self.name}: {meaning}, {symbol}, [{self.units}])"

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

    def __init__(self, data: Mapping[str, Any] | None = None, law: str = "",
                 params: Mapping[str, Any] | None = None):
        super().__init__(data or {})
        self.law = law
        self.params = dict(params or {})

    def __missing__(self, key: str) -> Any:
        # the critical stiffness under either name: ``k_c`` (canonical) or ``kc`` (deprecated alias)
        other = {"k_c": "kc", "kc": "k_c"}.get(key)
        if other is not None and dict.__contains__(self, other):
            return dict.__getitem__(self, other)
        raise KeyError(key)

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
        kc = "kc" if "kc" in flat else "k_c"
        if "Lambda" in flat and kc in flat:
            lam = flat["Lambda"]
            flat["criticality"] = np.where(~np.isfinite(flat[kc]), "no Hopf point",
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
        from landau.report.display import require_pandas

        pd = require_pandas("CoefficientTable.to_dataframe()")
        units = self.units
        df = pd.DataFrame({(f"{c} [{units[c]}]" if c in units else c): v for c, v in self.columns().items()})
        df.attrs.update(units=units, law=self.law, params=dict(self.params))
        return df

    def plot(self, names: Sequence[str] | None = None, *, fig=None):
        """k_c, Λ, C, … against V with the super/subcritical bands shaded; returns the Figure
        (see :func:`landau.report.plotting.plot_coefficients`)."""
        from landau.report.plotting import plot_coefficients

        return plot_coefficients(self, names, fig=fig)

    def _size(self) -> int:
        return int(np.prod(np.broadcast(*[np.asarray(v) for v in self.values()]).shape)) if self else 0

    def _repr_html_(self) -> str:
        from landau.report.display import MAX_ROWS, html_table

        n = self._size()
        shown = "" if n <= MAX_ROWS else f", the first {MAX_ROWS} shown"
        title = f"Amplitude-equation coefficients, law {self.law}" if self.law else "Amplitude-equation coefficients"
        return html_table(self.rows(MAX_ROWS), units=self.units, title=title,
                          note=f"{n} point(s){shown}. Convention: {CONVENTION}")

    def __repr__(self) -> str:
        from landau.report.display import text_table

        n = self._size()
        names = ", ".join(k for k in self if k != "degenerate")
        more = f"\n… {n - 20} more points" if n > 20 else ""
        return (f"CoefficientTable(law {self.law!r}, {n} point(s): {names})\n"
                + text_table(self.rows(20), units=self.units) + more)


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
    """"supercritical" (Λ < 0), "subcritical" (Λ > 0) or "degenerate" (Λ not finite or |Λ| ≤ ``scale``)."""
    if not np.isfinite(lam) or abs(lam) <= scale:
        return "degenerate"
    return "supercritical" if lam < 0 else "subcritical"

