"""One result type for a Hopf point and its amplitude equation, for any system.

Every route of the toolkit — the spring–block closed forms (Putelat et al. 2010), the general
Fredholm engine for E·ẏ = f(y; p), Kuznetsov's projection formula — returns a
:class:`HopfResult`.  The result carries its :class:`Convention` (the amplitude equation it
refers to, the normalisation of the critical mode, the source), so numbers from different
routes and tools can be compared without guessing factors of 2 or ω.

Amplitude equation (landau's convention, Putelat et al. 2010 eq. 20 written for a general
parameter p)::

    dA/dT = a (p − p_c) A + b A|A|² (+ c A|A|⁴),     a = dλ/dp,  Λ = 2 Re b,  χ = 2 Im b,
    Λ₅ = 2 Re c,

with the critical mode's ``normalise`` component equal to 1.  Λ < 0: supercritical, Λ > 0:
subcritical.  The normalisation-free number to compare with a simulation is
C = 2 sqrt(2|Re a|/|Λ|): the cycle's amplitude in the normalised coordinate is
max|y − y₀| ≈ C sqrt|p − p_c|.

Kuznetsov's normalisation (MatCont, BifurcationKit): ⟨q, q⟩ = 1, ⟨p, q⟩ = 1, normal form
ż = iω z + c₁ z|z|² + c₂ z|z|⁴; the first Lyapunov coefficient ``l1`` = Re c₁ / ω (Kuznetsov
2004, eq. 3.20; MatCont's ``nf_H.m`` returns ``real(p0'*h21)/2`` and BifurcationKit its ``l1``,
both Re c₁ = ω·l1, so compare their number with ``c1.real``) and the second ``l2`` = Re c₂, not divided by ω
(MatCont's ``nf_GH.m`` returns ``real(p0'*h32/12)``, BifurcationKit's ``NormalForms.jl``
``l2 = real(G32)/12``; both with ⟨q, q⟩ = 1).

References
----------
Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a
spring–block system. J. Mech. Phys. Solids 58, 27–53.
Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, §3.5, §8.3.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import Any, Mapping


class Criticality(str, enum.Enum):
    """Type of a Hopf bifurcation, from the sign of the Landau coefficient Λ (or l₁).

    A ``str`` enum: ``Criticality.SUBCRITICAL == "subcritical"`` and it serialises to JSON as its value.
    """

    SUPERCRITICAL = "supercritical"
    SUBCRITICAL = "subcritical"
    DEGENERATE = "degenerate"

    @classmethod
    def from_sign(cls, value: float | None, scale: float = 0.0) -> "Criticality":
        """Λ < 0 → supercritical, Λ > 0 → subcritical; |Λ| ≤ scale, NaN or None → degenerate."""
        if value is None or not math.isfinite(value) or abs(value) <= scale:
            return cls.DEGENERATE
        return cls.SUPERCRITICAL if value < 0 else cls.SUBCRITICAL

    def __str__(self) -> str:
        return self.value

    def __format__(self, spec: str) -> str:
        return format(self.value, spec)


@dataclass(frozen=True)
class Convention:
    """How the coefficients of a :class:`HopfResult` are normalised.

    Parameters
    ----------
    name : str
        Short identifier (``"putelat2010"``, ``"general"``).
    equation : str
        The amplitude equation in plain text.
    latex : str
        The same in LaTeX.
    normalisation : str
        How the critical mode is normalised.
    source : str
        Where the convention comes from (paper and equation).
    """

    name: str
    equation: str
    latex: str
    normalisation: str
    source: str

    def __str__(self) -> str:
        return f"{self.equation}; {self.normalisation} ({self.source})"


#: the general convention (any parameter p, the ``normalise`` component of the mode is 1)
GENERAL = Convention(
    name="general",
    equation="dA/dT = a (p - p_c) A + b A|A|^2 + c A|A|^4; Lambda = 2 Re b, chi = 2 Im b, Lambda5 = 2 Re c",
    latex=r"\frac{dA}{dT} = a\,(p-p_c)\,A + b\,A|A|^2 + c\,A|A|^4,\quad \Lambda = 2\,\mathrm{Re}\,b,"
          r"\ \chi = 2\,\mathrm{Im}\,b,\ \Lambda_5 = 2\,\mathrm{Re}\,c",
    normalisation="critical mode with its normalised component equal to 1",
    source="Putelat et al. (2010) eq. (20), written for a general parameter p",
)

#: the spring–block convention of Putelat et al. (2010): p = k, a = −Γ̄ + iΩ̄
SPRING_BLOCK = Convention(
    name="putelat2010",
    equation="d|A|/dT = (Gamma |A| + Lambda |A|^3)/2, dtheta/dT = (Omega + chi |A|^2)/2, "
             "Gamma = -2 Gamma_bar (k - k_c)/eps^2, Omega = 2 Omega_bar (k - k_c)/eps^2",
    latex=r"\frac{d|A|}{dT} = \tfrac12\left(\Gamma|A| + \Lambda|A|^3\right),\ "
          r"\frac{d\theta}{dT} = \tfrac12\left(\Omega + \chi|A|^2\right)",
    normalisation="critical mode with slip component X equal to 1 (u0 = (1, z))",
    source="Putelat et al. (2010) eqs (15)-(23)",
)


#: units of the fields of a spring–block result (SI; ``as_dict`` names)
SPRING_BLOCK_UNITS: dict[str, str] = {
    "V": "m/s", "p_c": "N/m", "k_c": "N/m", "kc": "N/m", "omega_c": "rad/s", "dRe_lambda_dp": "1/(N s)",
    "dIm_lambda_dp": "1/(N s)", "Gamma_bar": "1/(N s)", "Omega_bar": "1/(N s)", "Lambda": "1/(m^2 s)",
    "chi": "1/(m^2 s)", "C": "m/sqrt(N/m)", "Lambda5": "1/(m^4 s)",
}


def _fmt(x: Any, digits: int = 6) -> str:
    if x is None:
        return "—"
    if isinstance(x, complex):
        return f"{x.real:.{digits}g}{x.imag:+.{digits}g}i"
    try:
        return f"{float(x):.{digits}g}"
    except (TypeError, ValueError):
        return str(x)


#: the route-specific typed fields of a :class:`HopfResult`, in their :meth:`~HopfResult.as_dict` order
_ROUTE_FIELDS = ("V", "kc", "Gamma_bar", "Omega_bar", "q_norm", "dps", "c2", "Im_c")


@dataclass(frozen=True)
class HopfResult:
    """A located Hopf point with its amplitude-equation coefficients (SI units of the system).

    Parameters
    ----------
    system : str
        Name of the system (or law, for the spring–block).
    parameter : str
        Name of the bifurcation parameter p (``"k"`` for the spring–block).
    p_c : float
        Critical value of p.
    omega_c : float
        Angular frequency at onset (rad/s).
    equilibrium : tuple of float
        The equilibrium y₀ at p_c.
    dlambda_dp : complex
        a = dλ/dp, the speed of the critical eigenvalue across the imaginary axis
        (spring–block: a = −Γ̄ + iΩ̄).
    Lambda : float
        Landau coefficient Λ = 2 Re b (Λ < 0: supercritical).
    chi : float
        Nonlinear frequency coefficient χ = 2 Im b.
    convention : Convention
        Normalisation of a, b, c.
    normalise : str
        The state component of the critical mode that is normalised to 1.
    l1 : float, optional
        First Lyapunov coefficient in Kuznetsov's normalisation, Re c₁/ω.  It depends on the
        declared state coordinates (and their units); C, Λ and the criticality do not.  For the
        spring–block, c₁ = (Λ + iχ)/(2‖q‖²) with q = (1, iω_c, φ₁…) in (X, u = Ẋ, φ…)
        (:func:`spring_block_c1`).
    c1 : complex, optional
        Kuznetsov's c₁(0) (⟨q, q⟩ = 1, ⟨p, q⟩ = 1); MatCont and BifurcationKit print its real part.
    Lambda5 : float, optional
        Quintic coefficient Λ₅ = 2 Re c in landau's convention.
    l2 : float, optional
        Second Lyapunov coefficient in Kuznetsov's normalisation, Re c₂ (not divided by ω: the
        number MatCont and BifurcationKit print at a generalised-Hopf point).
    params : mapping
        The other parameters' values.
    extra : mapping
        Free-form labels added to :meth:`as_dict` (e.g. the name of a friction law); never read as
        attributes.  A number of a known route given here (an old-style call) is moved to its typed
        field below.
    units : mapping
        Unit of each field by its :meth:`as_dict` name (empty: the system's own units, unstated).
    at : tuple of str
        Names of fields (or ``params`` entries) that locate the point on a family, shown first in
        the repr and in tables (``("V",)`` for a spring–block point at driving velocity V).
    V, kc : float, optional
        Spring–block: the driving velocity V (m/s) and the critical stiffness k_c (= ``p_c``, N/m;
        read it as the property ``k_c``, the canonical name: ``kc`` is a deprecated alias kept for
        one release, and JSON carries both keys)
        (Putelat et al. 2010, eq. 7).
    Gamma_bar, Omega_bar : float, optional
        Spring–block: Γ̄ and Ω̄ of dλ/dk = −Γ̄ + iΩ̄ (Putelat et al. 2010, eqs 18, 21).
    q_norm : float, optional
        Kuznetsov route: |q_n| of the critical eigenvector with ⟨q, q⟩ = 1 (the factor between the
        two normalisations: Λ = 2 Re c₁/|q_n|², Λ₅ = 2 Re c₂/|q_n|⁴).
    dps : int, optional
        Kuznetsov route: the working precision (digits).
    c2 : complex, optional
        Kuznetsov's c₂(0) (⟨q, q⟩ = 1), written to JSON as ``c2_re``, ``c2_im``.
    Im_c : float, optional
        Fredholm route at fifth order: Im c (gauge-dependent: h₂₁'s normalised component is 0).

    Notes
    -----
    Names kept from the former result types: ``omega`` (= ``omega_c``), ``dmu_dp``
    (= Re ``dlambda_dp``), ``sign`` (of Λ), ``result["Lambda"]`` (any :meth:`as_dict` entry by name).
    """

    system: str
    parameter: str
    p_c: float
    omega_c: float
    equilibrium: tuple[float, ...]
    dlambda_dp: complex
    Lambda: float
    chi: float
    convention: Convention = GENERAL
    normalise: str = ""
    l1: float | None = None
    c1: complex | None = None
    Lambda5: float | None = None
    l2: float | None = None
    params: Mapping[str, float] = field(default_factory=dict)
    extra: Mapping[str, Any] = field(default_factory=dict)
    units: Mapping[str, str] = field(default_factory=dict)
    at: tuple[str, ...] = ()
    V: float | None = None
    kc: float | None = None
    Gamma_bar: float | None = None
    Omega_bar: float | None = None
    q_norm: float | None = None
    dps: int | None = None
    c2: complex | None = None
    Im_c: float | None = None

    def __post_init__(self) -> None:
        # an old-style call with route numbers in ``extra``: move them to their typed fields
        extra = dict(self.extra)
        if "c2_re" in extra or "c2_im" in extra:
            object.__setattr__(self, "c2", complex(extra.pop("c2_re", 0.0), extra.pop("c2_im", 0.0)))
        extra.pop("l2_over_omega", None)        # a property (Re c₂/ω)
        if "omega_c" in extra and extra["omega_c"] == self.omega_c:
            extra.pop("omega_c")
        for name in _ROUTE_FIELDS:
            if name in extra:
                object.__setattr__(self, name, extra.pop(name))
        if len(extra) != len(self.extra):
            object.__setattr__(self, "extra", extra)
        self._check_finite()

    #: the fields a Hopf result must carry as finite numbers (None: not computed)
    _FINITE = ("p_c", "omega_c", "dlambda_dp", "Lambda", "chi", "l1", "c1", "Lambda5", "l2", "kc", "Gamma_bar",
               "Omega_bar", "c2")

    def _check_finite(self) -> None:
        """No NaN or infinity passes as a result: a field that is not finite raises
        :class:`~landau.errors.SingularPointError` naming it, the point and the parameters."""
        for name in self._FINITE:
            v = getattr(self, name)
            if v is None:
                continue
            try:
                finite = math.isfinite(v.real) and math.isfinite(v.imag) if isinstance(v, complex) \
                    else math.isfinite(float(v))
            except (TypeError, ValueError, OverflowError):
                finite = False
            if not finite:
                from landau.errors import SingularPointError

                where = f"{self.parameter} = {self.p_c:g}" if name != "p_c" else "the Hopf point"
                params = ", ".join(f"{k} = {x:g}" if isinstance(x, (int, float)) else f"{k} = {x}"
                                   for k, x in dict(self.params).items())
                raise SingularPointError(
                    f"{self.system}: {name} = {v} is not finite at {where}" + (f" ({params})" if params else "")
                    + ": the computation leaves float64's range there or the point is singular")

    def route_fields(self) -> dict[str, Any]:
        """The route-specific entries that are set, by their :meth:`as_dict` names.

        Returns
        -------
        dict
            ``V``, ``kc`` with ``k_c``, ``Gamma_bar``, ``Omega_bar``, ``q_norm``, ``dps``, ``c2_re``, ``c2_im``,
            ``l2_over_omega`` and ``Im_c``, those that are not None.
        """
        out: dict[str, Any] = {}
        for name in _ROUTE_FIELDS:
            v = getattr(self, name)
            if v is None:
                continue
            if name == "c2":
                out.update(c2_re=v.real, c2_im=v.imag, l2_over_omega=self.l2_over_omega)
            elif name == "kc":
                out.update(kc=v, k_c=v)         # k_c canonical; kc its deprecated alias (one release)
            else:
                out[name] = v
        return out

    @property
    def k_c(self) -> float | None:
        """Spring–block: the critical stiffness k_c (N/m, = ``p_c``); the canonical name of the
        deprecated ``kc`` (None for other models: see ``p_c``)."""
        return self.kc

    @property
    def l2_over_omega(self) -> float | None:
        """Re c₂/ω (Kuznetsov route; None where c₂ was not computed)."""
        return None if self.c2 is None else self.c2.real / self.omega_c

    def __getitem__(self, key: str) -> Any:
        """``result["Lambda"]``: any entry of :meth:`as_dict` by name."""
        fields = self.as_dict()
        if key not in fields:
            raise KeyError(f"{key!r} (known: {', '.join(fields)})")
        return fields[key]

    def _located(self) -> dict[str, Any]:
        """The entries named by ``at``, from the typed fields or ``params``."""
        out: dict[str, Any] = {}
        for name in self.at:
            if name in _ROUTE_FIELDS and getattr(self, name) is not None:
                out[name] = getattr(self, name)
            elif name in self.params:
                out[name] = self.params[name]
        return out

    # --- derived quantities -------------------------------------------------------------
    @property
    def criticality(self) -> Criticality:
        """Super/subcritical from the sign of Λ (degenerate where Λ is zero or not finite)."""
        return Criticality.from_sign(self.Lambda)

    @property
    def sign(self) -> int:
        """Sign of Λ: −1 supercritical, +1 subcritical, 0 degenerate."""
        return {Criticality.SUPERCRITICAL: -1, Criticality.SUBCRITICAL: 1}.get(self.criticality, 0)

    @property
    def omega(self) -> float:
        """The angular frequency at onset, ``omega_c`` (rad/s)."""
        return self.omega_c

    @property
    def dmu_dp(self) -> float:
        """The transversality d Re λ/dp = Re ``dlambda_dp``."""
        return self.dlambda_dp.real

    @property
    def C(self) -> float:
        """Amplitude per sqrt|p − p_c| of the normalised component, 2 sqrt(2|Re a|/|Λ|) (inf at Λ = 0)."""
        if self.Lambda == 0 or not math.isfinite(self.Lambda):
            return math.inf
        return 2.0 * math.sqrt(2.0 * abs(self.dlambda_dp.real) / abs(self.Lambda))

    @property
    def cycle_side(self) -> int:
        """+1 if the (stable or unstable) cycle exists for p > p_c, −1 for p < p_c, 0 if Λ = 0."""
        s = self.dlambda_dp.real * self.Lambda
        return 0 if s == 0 or not math.isfinite(s) else (-1 if s > 0 else 1)

    def amplitude(self, p: float) -> float:
        """Predicted cycle amplitude at p: the half peak-to-peak swing (max y_n − min y_n)/2 of the normalised
        component (NaN on the side without a cycle).  max|y_n − y₀,n| differs from it by the cycle's O(ε²)
        mean shift, i.e. by O(ε) relative.

        Parameters
        ----------
        p : float
            Value of the bifurcation parameter.

        Returns
        -------
        float
            C·sqrt(|p − p_c|) on the side where the cycle exists, else NaN.

        References
        ----------
        Kuznetsov, Y. A. (2004), *Elements of Applied Bifurcation Theory*, 3rd ed., Springer,
        Section 3.5.
        """
        d = p - self.p_c
        if self.cycle_side == 0 or d == 0 or (d > 0) != (self.cycle_side > 0):
            return math.nan
        return self.C * math.sqrt(abs(d))

    def frequency(self, p: float) -> float:
        """Predicted cycle angular frequency ω_c + (Im a − χ Re a/Λ)(p − p_c).

        Parameters
        ----------
        p : float
            Value of the bifurcation parameter.

        Returns
        -------
        float
            Angular frequency, rad/s (NaN when Λ = 0).
        """
        a = self.dlambda_dp
        if self.Lambda == 0:
            return math.nan
        return self.omega_c + (a.imag - self.chi * a.real / self.Lambda) * (p - self.p_c)

    # --- rendering ----------------------------------------------------------------------
    def amplitude_equation(self) -> str:
        """The amplitude equation with this result's numbers, its criticality and convention.

        Returns
        -------
        str
        """
        a, b = self.dlambda_dp, complex(self.Lambda / 2, self.chi / 2)
        eq = f"dA/dT = ({_fmt(a)})({self.parameter} - {_fmt(self.p_c, 10)}) A + ({_fmt(b)}) A|A|^2"
        if self.Lambda5 is not None:
            eq += f" + c A|A|^4 (Re c = {_fmt(self.Lambda5 / 2)})"
        return f"{eq}   [{self.criticality}; {self.convention.normalisation}]"

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready fields (complex numbers split into real and imaginary parts).

        Returns
        -------
        dict
        """
        out: dict[str, Any] = {
            "system": self.system, "parameter": self.parameter, **self._located(), "p_c": self.p_c,
            "omega_c": self.omega_c,
            "equilibrium": list(self.equilibrium), "dRe_lambda_dp": self.dlambda_dp.real,
            "dIm_lambda_dp": self.dlambda_dp.imag, "Lambda": self.Lambda, "chi": self.chi, "C": self.C,
            "criticality": self.criticality.value, "normalise": self.normalise, "convention": self.convention.name,
        }
        for name in ("l1", "Lambda5", "l2"):
            if getattr(self, name) is not None:
                out[name] = getattr(self, name)
        if self.c1 is not None:
            out["c1"] = [self.c1.real, self.c1.imag]
        out.update(self.route_fields())
        out.update(self.extra)
        return out

    def _unit(self, name: str) -> str:
        u = self.units.get(name)
        return f" {u}" if u else ""

    def _where(self) -> str:
        return ", ".join(f"{k} = {_fmt(v, 4)}{self._unit(k)}" for k, v in self._located().items())

    def __repr__(self) -> str:
        parts = [f"{self.parameter}_c = {_fmt(self.p_c, 10)}{self._unit('p_c')}",
                 f"ω_c = {_fmt(self.omega_c)}{self._unit('omega_c')}",
                 f"Λ = {_fmt(self.Lambda)}{self._unit('Lambda')} ({self.criticality})",
                 f"C = {_fmt(self.C)}{self._unit('C')}"]
        for name in ("l1", "Lambda5", "l2"):
            if getattr(self, name) is not None:
                parts.append(f"{name} = {_fmt(getattr(self, name))}{self._unit(name)}")
        where = self._where()
        return f"HopfResult({self.system}{' at ' + where if where else ''}: " + ", ".join(parts) + ")"

    def _display_row(self) -> dict[str, Any]:
        # one row of a table of results (ResultList): where, the Hopf point, Λ, C, criticality
        row: dict[str, Any] = {**self._located(), f"{self.parameter}_c": self.p_c, "omega_c": self.omega_c,
                               "Lambda": self.Lambda, "C": self.C}
        for name in ("l1", "Lambda5", "l2"):
            if getattr(self, name) is not None:
                row[name] = getattr(self, name)
        row["criticality"] = self.criticality.value
        return row

    def _repr_latex_(self) -> str:
        where = "".join(rf"{k} = {_fmt(v, 4)},\ " for k, v in self._located().items())
        return (rf"${where}{self.parameter}_c = {_fmt(self.p_c, 10)},\ \omega_c = {_fmt(self.omega_c)},\ "
                rf"\Lambda = {_fmt(self.Lambda)}$ ({self.criticality})")

    def _repr_html_(self) -> str:
        from landau.report.display import html_record

        fields = {k: v for k, v in self.as_dict().items() if k not in ("system", "convention", "kc")}
        where = self._where()
        return html_record(f"Hopf point of {self.system}{' at ' + where if where else ''}: {self.criticality}",
                           fields, units=self.units, note=f"Convention: {self.convention}")


#: system -> compiled (J(y, k, params…), E(k, params…), y₀(k, params…)); one entry per system built
_LINEARISATIONS: dict[int, tuple[Any, tuple]] = {}


def _linearisation(system: Any) -> tuple:
    """The Jacobian ∂f/∂y, the mass matrix E and the equilibrium of ``system`` as float functions
    (built once per system: sympy's derivative of f, compiled by lambdify)."""
    hit = _LINEARISATIONS.get(id(system))
    if hit is not None and hit[0] is system:
        return hit[1]
    import sympy as sp

    from landau.support.cx import as_expr
    from landau.support.lambdify import lambdify_positional

    states, k, pars = list(system.states), system.parameter, [*system.parameters, *system.unknowns]
    J = sp.Matrix([as_expr(f) for f in system.rhs]).jacobian(states)
    fns = (lambdify_positional([*states, k, *pars], J.tolist(), "numpy"),
           lambdify_positional([k, *pars], system.mass_matrix.tolist(), "numpy"),
           lambdify_positional([k, *pars], [as_expr(e) for e in system.equilibrium], "numpy"))
    _LINEARISATIONS[id(system)] = (system, fns)
    return fns


def spring_block_c1(system: Any, params: Mapping[str, float], k_c: float, omega_c: float, Lambda: float,
                    chi: float, equilibrium: tuple[float, ...] = ()) -> dict[str, Any]:
    """Kuznetsov's first Lyapunov coefficient of a spring–block Hopf point from its Λ and χ.

    With the critical eigenvector q = (1, iω_c, φ₁…φₙ) of E·ẏ = f(y; k) in the state coordinates
    y = (X, u = Ẋ, φ…), normalised with slip component 1 (Putelat et al. 2010), and
    ‖q‖² = Σ|qᵢ|², Kuznetsov's normalisation ⟨q, q⟩ = 1 gives

        c₁ = (Λ + iχ)/(2‖q‖²),     l₁ = Re c₁/ω_c.

    The state components solve (iω_c E − ∂f/∂y) q = 0 (for one state φ:
    (iω_c − ∂G/∂φ) φ₁ = iω_c ∂G/∂v).  l₁ and c₁ depend on the state coordinates and their units
    (‖q‖² mixes m, m/s and the state's unit); Λ, χ's sign, C and the criticality do not.

    Parameters
    ----------
    system : DynamicalSystem
        The spring–block system (:attr:`landau.systems.system.SpringBlock.system`).
    params : mapping
        Values of every parameter but k (the driving velocity ``V`` included), and of the
        steady states φᵢ,₀ by their symbols' names where they have no closed form.
    k_c, omega_c, Lambda, chi : float
        The Hopf point and its cubic coefficients in the slip-normalised convention.
    equilibrium : tuple of float, optional
        The steady state (X, u, φ…) at k_c; solved by Newton's method when empty.

    Returns
    -------
    dict
        ``{"l1": float, "c1": complex}``, or ``{}`` where the eigenvector cannot be computed.

    References
    ----------
    Kuznetsov, Yu. A. (2004). Elements of Applied Bifurcation Theory, 3rd ed., Springer, §3.5.
    """
    import numpy as np

    from landau.derivation.general import NumericSystem
    from landau.errors import LandauError

    try:
        if system.unknowns and not all(u.name in params for u in system.unknowns):
            # a numerically solved steady state not given: the general engine's Newton solve
            num = NumericSystem(system, dict(params))
            y = np.asarray(equilibrium, dtype=float) if len(equilibrium) else num.equilibrium_float(float(k_c))
            A = num.J_float(y, float(k_c)) - 1j * float(omega_c) * num.E_float(float(k_c))
        else:
            fJ, fE, fy = _linearisation(system)
            pv = [float(params[s.name]) for s in (*system.parameters, *system.unknowns)]
            y = np.asarray(fy(float(k_c), *pv), dtype=float).ravel()
            J = np.asarray(fJ(*y, float(k_c), *pv), dtype=float).reshape(len(y), len(y))
            E = np.asarray(fE(float(k_c), *pv), dtype=float).reshape(len(y), len(y))
            A = J - 1j * float(omega_c) * E
        q = np.ones(len(y), dtype=complex)
        q[1:] = np.linalg.solve(A[1:, 1:], -A[1:, 0])
        c1 = complex(Lambda, chi) / (2.0 * float(np.sum(np.abs(q) ** 2)))
    except (LandauError, np.linalg.LinAlgError, KeyError, ValueError, TypeError, ArithmeticError):
        return {}
    if not (math.isfinite(c1.real) and math.isfinite(c1.imag)):
        return {}
    return {"l1": c1.real / float(omega_c), "c1": c1}


def spring_block_result(law: str, V: float, kc: float, omega_c: float, Gamma_bar: float, Omega_bar: float,
                        Lambda: float, chi: float, params: Mapping[str, float], **fields: Any) -> HopfResult:
    """A spring–block Hopf point at driving velocity V as a :class:`HopfResult`.

    Spring–block convention (Putelat et al. 2010, eq. 20): p = k, dλ/dk = −Γ̄ + iΩ̄, the critical
    mode normalised with slip component X = 1; SI units.

    Parameters
    ----------
    law : str
        Name of the friction law.
    V : float
        Driving velocity, m/s.
    kc, omega_c : float
        Critical stiffness (N/m) and angular frequency at onset (rad/s).
    Gamma_bar, Omega_bar : float
        Γ̄ and Ω̄ (1/(N s)): dλ/dk = −Γ̄ + iΩ̄.
    Lambda, chi : float
        Landau coefficient Λ and nonlinear frequency coefficient χ (1/(m² s)).
    params : mapping
        The other parameters' values.
    **fields
        Further :class:`HopfResult` fields (``equilibrium``, ``Lambda5``, ``l1``, ``c1``, ``q_norm``, …).

    Returns
    -------
    HopfResult
        With the fields V, kc, Gamma_bar, Omega_bar set, located at V.

    References
    ----------
    Putelat, T., Dawes, J. H. P., Willis, J. R. (2010). Regimes of frictional sliding of a
    spring–block system. J. Mech. Phys. Solids 58, 27–53, eqs (7), (8), (18)–(23).
    """
    fields.setdefault("equilibrium", ())
    return HopfResult(system=law, parameter="k", p_c=float(kc), omega_c=float(omega_c),
                      dlambda_dp=complex(-Gamma_bar, Omega_bar), Lambda=float(Lambda), chi=float(chi),
                      convention=SPRING_BLOCK, normalise="X", params=dict(params), units=SPRING_BLOCK_UNITS,
                      at=("V",), V=float(V), kc=float(kc), Gamma_bar=float(Gamma_bar),
                      Omega_bar=float(Omega_bar), **fields)
