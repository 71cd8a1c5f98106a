"""Contact mechanics shared by the stick–slip and impact models: one unilateral frictional
contact on the hybrid engine — Coulomb contact element (flight / slip± / stick modes), the
contact problem (LCP, Painlevé situations detected), Poisson impacts with Coulomb friction.

Any mechanical system with generalised coordinates q (n of them), mass matrix M(q) and
one contact point — normal gap g_N(q) ≥ 0, relative tangential velocity γ_T = w_T·q̇ − v(t)
— is written as

    M q̈ = f(t, q, q̇) + w_N λ_N + w_T λ_T,     g̈_N = w_N·q̈ + ŵ_N,  γ̇_T = w_T·q̇̇ + ŵ_T.

A *mechanics* object (:class:`ContactMechanics`) supplies, vectorised over trailing
sample axes, the free acceleration a₀ = M⁻¹f, the columns M⁻¹W (W = [w_N w_T]), the
Delassus matrix G = WᵀM⁻¹W and b = Wᵀa₀ + ŵ, so that the contact accelerations are
affine in the forces:  (g̈_N, γ̇_T) = G λ + b.

Modes (state y = (q, q̇) in every mode)
---------------------------------------
* ``flight``  (g_N > 0): λ = 0.  Guard ``impact`` (g_N → 0) applies the impact law.
* ``slip+`` / ``slip-`` (g_N = 0, sign γ_T = s = ±1): λ_T = −sμλ_N and g̈_N = 0 give
  λ_N = −b_N / D_s,  D_s = G_NN − sμ G_NT.  Guards ``lift-off`` (λ_N → 0) and ``stop``
  (sγ_T → 0: slip→stick if the stick condition holds, else slip reversal).
* ``stick`` (g_N = 0, γ_T = 0): G λ = −b.  Guards ``lift-off`` (λ_N → 0) and
  ``slip+ onset`` / ``slip- onset`` (|λ_T| → μλ_N; λ_T → −μλ_N starts positive slip).

Contact problem and Painlevé situations
----------------------------------------
Whenever the contact state is decided (after an impact, at lift-off-free grazing, at the
end of a slip phase) :func:`contact_problem` enumerates *every* solution of the
complementarity problem (flight: λ = 0 with g̈_N = b_N ≥ 0; slip s: λ_N = −b_N/D_s > 0 with
sγ̇_T > 0 when γ_T = 0; stick: |λ_T| ≤ μλ_N, λ_N > 0).  With D_s > 0 exactly one
solution exists.  If D_s ≤ 0 — the Painlevé situation of frictional impact oscillators
(Leine, Brogliato & Nijmeijer 2002) — there may be none ("inconsistent") or two
("indeterminate", flight and slip both admissible).  These raise :class:`PainleveError`
(kind, state, the candidate list); they are never resolved silently.  A slip phase that
reaches D_s = 0 is stopped by the guard ``painleve`` (D_s → 0) with the same error.

Poisson impact law with Coulomb friction (Pfeiffer & Glocker 1996)
------------------------------------------------------------------
Integrating M q̈ = f + Wλ over the impact [t_A, t_E] (f bounded, so ∫f dt → 0):
M(q̇⁺ − q̇⁻) = W Λ,  hence  γ⁺ = γ⁻ + G Λ (γ = (γ_N, γ_T) = Wᵀq̇ − (0, v)).  For eq. (1)
of Lancioni et al. G = WᵀM⁻¹W with M⁻¹ = [[m₁+m₂, −m₁l sin φ], [−m₁l sin φ, m₁l²]]
/ (m₁l²(m₂ + m₁cos²φ)), W = [[l sin φ, l cos φ], [1, 0]].
The impact is split into

* compression [t_A, t_C]: impulses Λ_C = (Λ_NC, Λ_TC) with γ_N,C = 0 at its end and
  Coulomb on the end-of-phase sliding velocity, Λ_TC ∈ −μΛ_NC Sign(γ_T,C):
    - stick:  G Λ_C = −γ⁻  (γ_C = 0), admissible if Λ_NC ≥ 0 and |Λ_TC| ≤ μΛ_NC;
    - slip σ = ±1:  Λ_NC = −γ_N⁻ / (G_NN − σμG_NT),  Λ_TC = −σμΛ_NC,
      γ_T,C = γ_T⁻ + (G_TN − σμG_TT)Λ_NC, admissible if Λ_NC > 0 and σγ_T,C > 0;
  exactly one candidate must be admissible, otherwise a :class:`PainleveError` (kind
  ``"impact"``) is raised;
* expansion [t_C, t_E]: Poisson's law Λ_NE = e_N Λ_NC, and Coulomb again,
  Λ_TE = clip(−(γ_T,C + G_TN Λ_NE)/G_TT, −μΛ_NE, μΛ_NE) (unique because G_TT > 0);
  γ⁺ = γ_C + G Λ_E.  (γ_N⁺ < 0, an expansion pushed back into the surface by friction,
  would violate Pfeiffer–Glocker's inequality form; it is reported as PainleveError
  kind ``"expansion"``.)

After the impact the state is projected onto g_N = 0; γ_N⁺ > ``v_tol`` → flight (a bounce),
otherwise the contact problem picks stick / slip (or flight).  e_N = 0 is the perfectly
plastic impact of Leine et al.

Chattering.  With e_N > 0 the bounces accumulate; as in the paper, chattering is ended
when the time between consecutive impacts falls below a tolerance: the engine's Zeno
monitor (``EngineOptions.zeno_interval``, ``zeno_relative=False``) calls the flight mode's
``on_zeno``, which removes the remaining normal velocity (a plastic normal impulse
q̇ ← q̇ − M⁻¹w_N γ_N/G_NN) and decides the contact mode; the engine logs it as a
``"zeno"`` event "chattering ended".  A bounce whose normal velocity after the impact is
below ``v_tol`` (1e-10 m/s) is treated as plastic as well (logged as an impact "→ stick/slip"):
with e_N = 0.2 this velocity rule, not the time rule, ends the chattering once the chatter
tolerance is ≤ 1e-6 s (see verify/benchmarks/results/lancioni_chatter.md).
Velocity-dependent friction.  The friction coefficient need not be a constant: the
mechanics object gives its magnitude in slip s at the current relative velocity,
``slip_mu(s, γ_T)`` (λ_T = −s·slip_mu·λ_N), and its one-sided limits at γ_T = 0,
``static_mu() = (μ₊, μ₋)``: stick holds while −μ₊λ_N ≤ λ_T ≤ μ₋λ_N and slip s starts when
λ_T reaches the edge of that cone.  The impulsive friction of an impact (a vanishing time in
which the sliding velocity is not defined) takes the one-sided limit of the sliding
direction, μ_σ.  Plain Coulomb friction is slip_mu = μ₊ = μ₋ = μ (the default of
:class:`ContactMechanics`).  This module only receives these numbers; the model evaluates
its friction law.
Stick tolerance (off by default).  ``ContactModel(stick_tol=η)`` imitates simulation codes
that treat |γ_T| < η as stick: a slip phase ends when it enters the band |γ_T| ≤ η while
stick is admissible (|λ_T| ≤ μλ_N, λ_N > 0 for the stick forces at that state), not only at
γ_T = 0.  ``stick_tol_reset="project"`` then sets γ_T = 0 (a velocity jump ≤ η);
``"hold"`` keeps the entry value during the stick phase (stick forces keep γ̇_T = 0, a
Karnopp-like band) and into the following slip phase.  Impacts and the contact problem
after them are unchanged.  The exact model (η = 0) is the reference; the tolerance exists
to explain differences from published tolerance-based simulations
(verify/lancioni/period_adding.py), never to tune results.
The slip guard ``stop`` carries its rate s·γ̇_T so that a slip phase that starts a rounding
error behind γ_T = 0 (the engine takes roots on the new side) is entered, not re-fired.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Generic, Sequence, TypeVar

import numpy as np

from landau.errors import InputError, IntegratorError
from landau.verify.hybrid.model import Guard, HybridModel, Jump, Mode
from landau.verify.hybrid.simulate import EngineOptions


class PainleveError(IntegratorError):
    """The contact problem has no solution or several (Painlevé situation); never resolved silently."""

    def __init__(self, kind: str, message: str, t: float | None = None, state=None,
                 candidates: Sequence[str] = ()):
        super().__init__(f"Painlevé situation ({kind}): {message}", t=t, state=state)
        self.kind = kind
        self.candidates = tuple(candidates)


def check_contact_coefficients(mu: float, eN: float) -> None:
    """Refuse a Coulomb coefficient or a restitution coefficient outside its domain.

    Parameters
    ----------
    mu : float
        Coulomb friction coefficient; must be finite and >= 0.
    eN : float
        Newton restitution coefficient; must be in [0, 1].

    Raises
    ------
    InputError
        Naming the parameter, its domain and the value given (NaN included).
    """
    if not (np.isfinite(mu) and mu >= 0):
        raise InputError(f"friction coefficient mu must be a finite number >= 0, got {mu!r}")
    if not (0 <= eN <= 1):
        raise InputError(f"restitution eN must be in [0, 1], got {eN!r}")


class ContactMechanics:
    """Subclass contract: one frictional unilateral contact of an n-DOF system.

    Attributes ``n`` (DOF), ``mu`` (Coulomb coefficient), ``eN`` (restitution).  Methods,
    all vectorised over trailing axes of ``q``/``qd`` (shape (n,) or (n, m)):

    * ``terms(t, q, qd) -> (a0, MiW, G, b)`` with shapes (n,…), (n, 2,…), (2, 2,…), (2,…);
    * ``gap(q)`` (g_N), ``gammas(t, q, qd) -> (γ_N, γ_T)``;
    * ``project(t, y) -> y`` onto g_N = 0 (exactly), γ_N = 0 (only the position by default);
    * ``slip_mu(s, gT)`` and ``static_mu()`` — the friction coefficient in slip s at relative
      velocity γ_T and its one-sided limits (μ₊, μ₋) at γ_T = 0; by default the constant
      ``mu`` (plain Coulomb friction).  ``velocity_dependent`` says whether ``slip_mu``
      depends on γ_T (if not, γ_T is not evaluated for it);
    * ``mode_kernel(mode)`` (optional) — a function building the mode's compiled field (a
      :class:`~landau.verify.hybrid.kernel.Kernel`) for the compiled steppers, or None.
    """

    n: int = 1
    mu: float = 0.0
    eN: float = 0.0
    velocity_dependent: bool = False

    def slip_mu(self, s: int, gT):
        """Magnitude of the friction coefficient in slip ``s`` (±1) at relative velocity ``gT``:
        λ_T = −s·slip_mu·λ_N (vectorised over ``gT``).  Default: the constant ``mu``."""
        return self.mu

    def static_mu(self) -> tuple[float, float]:
        """(μ₊, μ₋): the coefficient's one-sided limits at γ_T = 0⁺ and 0⁻ (magnitudes); stick holds
        while −μ₊λ_N ≤ λ_T ≤ μ₋λ_N.  Default: (``mu``, ``mu``)."""
        return self.mu, self.mu

    def terms(self, t, q, qd):  # pragma: no cover - interface
        raise NotImplementedError

    def gap(self, q):  # pragma: no cover - interface
        raise NotImplementedError

    def gammas(self, t, q, qd):  # pragma: no cover - interface
        raise NotImplementedError

    def project(self, t, y, normal_velocity: bool = False):
        return np.array(y, dtype=float)

    def project_stick(self, t, y):
        """State with γ_T = 0 exactly (and γ_N = 0): entering or leaving stick.  Default: unchanged."""
        return np.array(y, dtype=float)

    def mode_kernel(self, mode: str):
        """A function of no arguments building the compiled field of ``mode`` (a
        :class:`~landau.verify.hybrid.kernel.Kernel`, for the compiled steppers), or None (the
        default: the engine integrates the Python field)."""
        return None

    def guard_kernel(self, mode: str, sections: Sequence["Section"]):
        """A function of no arguments building the guards of ``mode`` (in the order of
        :class:`ContactModel`: flight ``impact``; slip ``lift-off``, ``stop``, ``painleve``; stick
        ``lift-off``, ``slip+ onset``, ``slip- onset``; then ``sections``) as one compiled vector
        function (:attr:`landau.verify.hybrid.model.Mode.guard_kernel`), or None (the default: the
        engine evaluates the Python guards)."""
        return None


# --------------------------------------------------------------------------- contact algebra
def _mu_pair(mu) -> tuple[float, float]:
    """(μ₊, μ₋) from one coefficient (plain Coulomb) or a pair."""
    if isinstance(mu, (tuple, list)):
        return float(mu[0]), float(mu[1])
    return float(mu), float(mu)


def slip_forces(G, b, mu: float, s: int):
    """(λ_N, λ_T, D_s) in slip with sign s: λ_N = −b_N/D_s, λ_T = −sμλ_N."""
    D = G[0, 0] - s * mu * G[0, 1]
    lamN = -b[0] / D
    return lamN, -s * mu * lamN, D


def stick_forces(G, b):
    """λ solving G λ = −b (2×2, vectorised)."""
    det = G[0, 0] * G[1, 1] - G[0, 1] * G[1, 0]
    lamN = -(G[1, 1] * b[0] - G[0, 1] * b[1]) / det
    lamT = -(-G[1, 0] * b[0] + G[0, 0] * b[1]) / det
    return lamN, lamT


@dataclass(frozen=True)
class ContactSolution:
    """The mode chosen by the contact problem and its forces."""

    mode: str
    lamN: float
    lamT: float


def contact_problem(G, b, mu, gT: float, v_tol: float = 1e-10, flight_allowed: bool = True,
                    t: float | None = None, state=None) -> ContactSolution:
    """Every admissible contact mode at g_N = 0, γ_N = 0; exactly one or a :class:`PainleveError`.

    ``mu`` is the friction coefficient at the current relative velocity γ_T = ``gT``: one number
    (plain Coulomb friction, or the coefficient of the slip direction at γ_T), or the pair
    (μ₊, μ₋) of magnitudes for slip+ and slip− (at γ_T = 0: the one-sided limits, which bound
    the stick cone −μ₊λ_N ≤ λ_T ≤ μ₋λ_N).
    """
    mu_p, mu_m = _mu_pair(mu)
    sols: list[ContactSolution] = []
    scale = max(abs(float(b[0])), abs(float(b[1])), 1e-300)
    tiny = 1e-12 * scale
    if flight_allowed and b[0] >= -tiny:
        sols.append(ContactSolution("flight", 0.0, 0.0))
    if abs(gT) > v_tol:
        s = 1 if gT > 0 else -1
        lamN, lamT, D = slip_forces(G, b, mu_p if s > 0 else mu_m, s)
        if lamN > 0 and not (flight_allowed and abs(b[0]) <= tiny):
            sols.append(ContactSolution("slip+" if s > 0 else "slip-", float(lamN), float(lamT)))
    else:
        lamN, lamT = stick_forces(G, b)
        if lamN > 0 and -mu_p * lamN * (1 + 1e-12) <= lamT <= mu_m * lamN * (1 + 1e-12) \
                and not (flight_allowed and abs(b[0]) <= tiny):
            sols.append(ContactSolution("stick", float(lamN), float(lamT)))
        else:
            for s in (1, -1):
                lamN, lamT, D = slip_forces(G, b, mu_p if s > 0 else mu_m, s)
                gTdot = b[1] + G[1, 0] * lamN + G[1, 1] * lamT
                if lamN > 0 and s * gTdot > 0:
                    sols.append(ContactSolution("slip+" if s > 0 else "slip-", float(lamN), float(lamT)))
    if len(sols) == 1:
        return sols[0]
    D = {s: float(G[0, 0] - s * (mu_p if s > 0 else mu_m) * G[0, 1]) for s in (1, -1)}
    if not sols:
        raise PainleveError("inconsistent", f"no admissible contact mode (b_N = {float(b[0]):.6g}, "
                            f"D± = {D[1]:.6g}, {D[-1]:.6g}, γ_T = {gT:.6g})", t=t, state=state)
    raise PainleveError("indeterminate", f"{len(sols)} admissible modes {[x.mode for x in sols]} "
                        f"(b_N = {float(b[0]):.6g}, D± = {D[1]:.6g}, {D[-1]:.6g})", t=t, state=state,
                        candidates=[x.mode for x in sols])


@dataclass(frozen=True)
class ImpactResult:
    """Impulses of the compression (C) and expansion (E) phases and the velocities after each."""

    compression: str          # "stick", "slip+" or "slip-" (end-of-phase sliding state)
    Lambda_C: np.ndarray
    Lambda_E: np.ndarray
    gamma_C: np.ndarray
    gamma_plus: np.ndarray

    @property
    def Lambda(self) -> np.ndarray:
        return self.Lambda_C + self.Lambda_E

    def __repr__(self) -> str:
        return (f"ImpactResult({self.compression}, Λ_C={np.round(self.Lambda_C, 8)}, "
                f"Λ_E={np.round(self.Lambda_E, 8)}, γ⁺={np.round(self.gamma_plus, 8)})")


def poisson_impact(G, gamma_minus, mu, eN: float, t: float | None = None, state=None) -> ImpactResult:
    """Poisson impact with Coulomb friction (compression + expansion); see the module docstring.

    ``mu`` is the Coulomb coefficient, or the pair (μ₊, μ₋) of the friction's one-sided limits
    at zero sliding velocity (the impulsive friction in sliding direction σ is μ_σ).
    """
    mu_p, mu_m = _mu_pair(mu)
    G = np.asarray(G, float)
    gm = np.asarray(gamma_minus, float)
    if gm[0] >= 0:
        raise ValueError("poisson_impact needs an approaching contact (γ_N⁻ < 0)")
    cands = []
    det = G[0, 0] * G[1, 1] - G[0, 1] * G[1, 0]
    L = np.array([-(G[1, 1] * gm[0] - G[0, 1] * gm[1]) / det, -(-G[1, 0] * gm[0] + G[0, 0] * gm[1]) / det])
    if L[0] >= 0 and -mu_p * L[0] * (1 + 1e-12) <= L[1] <= mu_m * L[0] * (1 + 1e-12):
        cands.append(("stick", L, np.zeros(2)))
    for sig in (1, -1):
        mu_s = mu_p if sig > 0 else mu_m
        D = G[0, 0] - sig * mu_s * G[0, 1]
        if D <= 0:
            continue
        LN = -gm[0] / D
        LC = np.array([LN, -sig * mu_s * LN])
        gC = gm + G @ LC
        if sig * gC[1] > 0:
            cands.append(("slip+" if sig > 0 else "slip-", LC, np.array([0.0, gC[1]])))
    if len(cands) != 1:
        kind = "no" if not cands else f"{len(cands)}"
        raise PainleveError("impact", f"{kind} admissible compression phases {[c[0] for c in cands]} "
                            f"(γ⁻ = {gm}, D± = {G[0, 0] - mu_p * G[0, 1]:.6g}, {G[0, 0] + mu_m * G[0, 1]:.6g})",
                            t=t, state=state, candidates=[c[0] for c in cands])
    mode, LC, gC = cands[0]
    LNE = eN * LC[0]
    LTE = float(np.clip(-(gC[1] + G[1, 0] * LNE) / G[1, 1], -mu_p * LNE, mu_m * LNE))
    LE = np.array([LNE, LTE])
    gp = gC + G @ LE
    if gp[0] < -1e-12 * max(1.0, abs(gm[0])):
        raise PainleveError("expansion", f"expansion impulse drives the contact inwards (γ_N⁺ = {gp[0]:.3g})",
                            t=t, state=state)
    return ImpactResult(mode, LC, LE, gC, gp)


# --------------------------------------------------------------------------- hybrid model
MODES = ("flight", "slip+", "slip-", "stick")


@dataclass(frozen=True)
class Section:
    """A section guard added to every mode: ``fun(t, y, acc)`` with acc = q̈ of the mode (vectorised).

    ``symbolic`` (optional): the same function of sympy symbols and expressions (t, the state
    components, the components of q̈), returning a sympy expression; a mechanics whose guards
    are compiled (:meth:`ContactMechanics.guard_kernel`) compiles it with them.  Without it the
    modes' guards stay in Python.
    """

    name: str
    fun: Callable
    symbolic: Callable | None = None


_Mech = TypeVar("_Mech", bound="ContactMechanics")


@dataclass
class ContactModel(Generic[_Mech]):
    """The hybrid model of a :class:`ContactMechanics` (modes flight, slip±, stick) and helpers."""

    mech: _Mech
    sections: Sequence[Section] = ()
    v_tol: float = 1e-10
    #: numerical stick tolerance η (velocity units; 0 = exact, the default).  See
    #: "Stick tolerance" in the module docstring: a slip phase with |γ_T| ≤ η where
    #: stick is admissible is treated as stick.  Only for reproducing tolerance-based codes.
    stick_tol: float = 0.0
    #: what happens to γ_T at a tolerance stick: "project" (set to 0, a jump ≤ η) or
    #: "hold" (kept, Karnopp-like band: the stick phase keeps the entry value of γ_T)
    stick_tol_reset: str = "project"
    model: HybridModel = field(init=False)

    def __post_init__(self):
        check_contact_coefficients(self.mech.mu, self.mech.eN)
        mu_p, mu_m = self.mech.static_mu()
        if not (np.isfinite(mu_p) and np.isfinite(mu_m) and mu_p >= 0 and mu_m >= 0):
            raise InputError(f"the friction's limits at zero sliding velocity must be finite with "
                             f"F(0+) >= 0 >= F(0-) (a stick cone), got F(0+) = {mu_p!r}, F(0-) = {-mu_m!r}")
        if not (self.stick_tol >= 0 and np.isfinite(self.stick_tol)):
            raise InputError(f"stick_tol must be a finite number >= 0, got {self.stick_tol!r}")
        if self.stick_tol_reset not in ("project", "hold"):
            raise InputError(f"stick_tol_reset must be 'project' or 'hold', got {self.stick_tol_reset!r}")
        self.model = self._build()

    def _hold(self) -> bool:
        return self.stick_tol > 0 and self.stick_tol_reset == "hold"

    def _to_stick(self, t, y):
        """State put into stick: γ_T = 0 exactly, or (tolerance "hold") only γ_N = 0."""
        if self._hold():
            return self.mech.project(t, y, normal_velocity=True)
        return self.mech.project_stick(t, y)

    def _leave_stick(self, t, y, s: int):
        """State leaving stick into slip s: as :meth:`_to_stick`; a held γ_T of the wrong sign is zeroed."""
        if self._hold():
            n = self.mech.n
            gT = float(self.mech.gammas(t, y[:n], y[n:])[1])
            if s * gT >= 0:
                return self.mech.project(t, y, normal_velocity=True)
        return self.mech.project_stick(t, y)

    def stick_margin(self, t, y):
        """min(μ₊λ_N + λ_T, μ₋λ_N − λ_T, λ_N) of the stick forces at y (for plain Coulomb friction
        min(μλ_N − |λ_T|, λ_N)): ≥ 0 where stick is admissible (vectorised)."""
        _, lamN, lamT, _ = self.forces("stick", t, y)
        mu_p, mu_m = self.mech.static_mu()
        if mu_p == mu_m:
            return np.minimum(mu_p * lamN - np.abs(lamT), lamN)
        return np.minimum(np.minimum(mu_p * lamN + lamT, mu_m * lamN - lamT), lamN)

    def slip_mu(self, s: int, t, y):
        """The mechanics' friction coefficient in slip ``s`` at the state y (vectorised)."""
        mech = self.mech
        if not mech.velocity_dependent:
            return mech.slip_mu(s, 0.0)
        n = mech.n
        return mech.slip_mu(s, mech.gammas(t, y[:n], y[n:])[1])

    # ---- dynamics of each mode (vectorised over sample axes)
    def forces(self, mode: str, t, y):
        n = self.mech.n
        q, qd = y[:n], y[n:]
        a0, MiW, G, b = self.mech.terms(t, q, qd)
        if mode == "flight":
            z = np.zeros_like(b[0])
            return a0, z, z, (G, b)
        if mode == "stick":
            lamN, lamT = stick_forces(G, b)
        else:
            s = 1 if mode == "slip+" else -1
            lamN, lamT, _ = slip_forces(G, b, self.slip_mu(s, t, y), s)
        acc = a0 + MiW[:, 0] * lamN + MiW[:, 1] * lamT
        return acc, lamN, lamT, (G, b)

    def rhs(self, mode: str):
        n = self.mech.n

        def f(t, y):
            acc = self.forces(mode, t, y)[0]
            return np.concatenate([y[n:], acc])
        return f

    def accel(self, mode: str, t, y):
        return self.forces(mode, t, y)[0]

    # ---- transitions
    def decide(self, t, y, note: str, flight_allowed: bool = True) -> Jump:
        """On the surface with γ_N = 0: solve the contact problem, project, jump."""
        y = self.mech.project(t, y, normal_velocity=True)
        n = self.mech.n
        a0, MiW, G, b = self.mech.terms(t, y[:n], y[n:])
        gT = float(self.mech.gammas(t, y[:n], y[n:])[1])
        mu: float | tuple[float, float]   # the slip coefficient, or the stick cone (μ₊, μ₋)
        if abs(gT) > self.v_tol:
            mu = float(self.mech.slip_mu(1 if gT > 0 else -1, gT))
        else:
            mu = self.mech.static_mu()
        sol = contact_problem(G, b, mu, gT, self.v_tol, flight_allowed, t=t, state=y)
        return Jump(sol.mode, y, f"{note} → {sol.mode}")

    def impact(self, t, y) -> Jump:
        n = self.mech.n
        q, qd = y[:n], y[n:]
        gN_dot, gT = (float(x) for x in self.mech.gammas(t, q, qd))
        if gN_dot >= -self.v_tol:  # grazing touch: no impulse, the contact problem decides
            return self.decide(t, y, "grazing contact")
        a0, MiW, G, b = self.mech.terms(t, q, qd)
        res = poisson_impact(G, [gN_dot, gT], self.mech.static_mu(), self.mech.eN, t=t, state=y)
        y2 = np.array(y, float)
        y2[n:] = qd + MiW @ res.Lambda
        y2 = self.mech.project(t, y2)
        note = f"impact ({res.compression} compression, Λ_N={res.Lambda[0]:.4g})"
        if res.gamma_plus[0] > self.v_tol:
            return Jump("flight", y2, note + " → bounce")
        return self.decide(t, y2, note)

    def end_chattering(self, t, y) -> Jump:
        n = self.mech.n
        q, qd = y[:n], y[n:]
        gN_dot = float(self.mech.gammas(t, q, qd)[0])
        a0, MiW, G, b = self.mech.terms(t, q, qd)
        y2 = np.array(y, float)
        y2[n:] = qd - MiW[:, 0] * gN_dot / G[0, 0]
        return self.decide(t, y2, "chattering ended (plastic normal impulse)", flight_allowed=True)

    def _build(self) -> HybridModel:
        mech, n = self.mech, self.mech.n
        modes = {}
        for mode in MODES:
            gs = []
            if mode == "flight":
                gs.append(Guard("impact", lambda t, y: mech.gap(y[:n]), self.impact))
            else:
                def lam_n(t, y, mode=mode):
                    return self.forces(mode, t, y)[1]
                gs.append(Guard("lift-off", lam_n, lambda t, y: Jump(
                    "flight", mech.project(t, y, normal_velocity=True), "lift-off (λ_N = 0)")))
                if mode == "stick":
                    static = dict(zip((1, -1), mech.static_mu(), strict=True))

                    def onset(sgn, static=static):
                        mu = static[sgn]

                        def gfun(t, y):
                            _, lamN, lamT, _ = self.forces("stick", t, y)
                            return mu * lamN + sgn * lamT
                        return gfun
                    # leave stick exactly on γ_T = 0: the integrated stick state drifts off it by
                    # rounding (~1e-13), which would put the new slip phase behind its own
                    # stop guard with zero rate (stick and slip coincide at the onset)
                    gs.append(Guard("slip+ onset", onset(1), lambda t, y: Jump(
                        "slip+", self._leave_stick(t, y, 1), "stick→slip+ (λ_T = −μλ_N)")))
                    gs.append(Guard("slip- onset", onset(-1), lambda t, y: Jump(
                        "slip-", self._leave_stick(t, y, -1), "stick→slip- (λ_T = +μλ_N)")))
                else:
                    s = 1 if mode == "slip+" else -1

                    def stop(t, y, s=s):
                        return s * mech.gammas(t, y[:n], y[n:])[1]

                    def stop_rate(t, y, s=s, mode=mode):
                        # s·γ̇_T in this slip mode: lets a phase that starts a rounding error
                        # behind γ_T = 0 but moving away from it run (engine's recover_tol)
                        _, lamN, lamT, (G, b) = self.forces(mode, t, y)
                        return s * (b[1] + G[1, 0] * lamN + G[1, 1] * lamT)
                    if self.stick_tol > 0:
                        gs.append(self._tolerant_stop(mode, s))
                    else:
                        gs.append(Guard("stop", stop, self._stop_transition(s), rate=stop_rate))

                    def painleve(t, y, s=s):
                        _, _, G, _ = mech.terms(t, y[:n], y[n:])
                        return G[0, 0] - s * self.slip_mu(s, t, y) * G[0, 1]

                    def raise_p(t, y, s=s):
                        raise PainleveError("slip", f"D_{'+' if s > 0 else '-'} reached 0 in slip", t=t, state=y)
                    gs.append(Guard("painleve", painleve, raise_p))
            for sec in self.sections:
                def section_fun(t, y, sec=sec, mode=mode):
                    return sec.fun(t, y, self.accel(mode, t, y))
                gs.append(Guard(sec.name, section_fun))
            # compiled guards: the exact model only (the tolerant stop guard is Python's)
            gker = (mech.guard_kernel(mode, tuple(self.sections))
                    if self.stick_tol == 0 and hasattr(mech, "guard_kernel") else None)
            modes[mode] = Mode(mode, self.rhs(mode), tuple(gs),
                               on_zeno=self.end_chattering if mode == "flight" else None,
                               kernel=mech.mode_kernel(mode) if hasattr(mech, "mode_kernel") else None,
                               guard_kernel=gker)
        return HybridModel(modes, name=getattr(mech, "name", "single-contact"))

    def _tolerant_stop(self, mode: str, s: int) -> Guard:
        """Slip guard with the stick tolerance η: g = min(max(sγ_T − η, −margin), sγ_T).

        g ≤ 0 iff (sγ_T ≤ η and stick is admissible) or sγ_T ≤ 0, so a slip phase ends when it
        enters the band |γ_T| ≤ η inside the stick region (or leaves it into the stick region),
        and otherwise at a true reversal as in the exact model.  Its rate is a forward
        difference along the slip flow (used only for the engine's start-of-phase recovery).
        """
        mech, n, eta = self.mech, self.mech.n, self.stick_tol

        def g(t, y):
            gt = s * mech.gammas(t, y[:n], y[n:])[1]
            return np.minimum(np.maximum(gt - eta, -self.stick_margin(t, y)), gt)

        f = self.rhs(mode)

        def rate(t, y, h=1e-7):
            return (g(t + h, y + h * f(t, y)) - g(t, y)) / h
        return Guard("stop", g, self._stop_transition(s), rate=rate)

    def _stop_transition(self, s: int):
        def tr(t, y):
            n = self.mech.n
            y = self._to_stick(t, y)  # exactly on γ_T = 0 (a rounding-size correction); "hold": γ_T kept
            a0, MiW, G, b = self.mech.terms(t, y[:n], y[n:])
            sol = contact_problem(G, b, self.mech.static_mu(), 0.0, self.v_tol, flight_allowed=False, t=t, state=y)
            return Jump(sol.mode, y, f"slip{'+' if s > 0 else '-'} end (γ_T = 0) → {sol.mode}")
        return tr

    def initial_mode(self, t, y) -> str:
        """Mode of a state: flight if g_N > 0, otherwise the contact problem's choice."""
        n = self.mech.n
        if float(self.mech.gap(y[:n])) > 1e-12:
            return "flight"
        return self.decide(t, y, "initial").mode


def default_options(chatter_tol: float = 1e-6, **kw) -> EngineOptions:
    """Engine options for impact runs: absolute chatter tolerance (the paper's rule)."""
    return EngineOptions(zeno_interval=chatter_tol, zeno_relative=False, **kw)


class PointMassOnPlane(ContactMechanics):
    """Hand-built reference: a point mass m on a plane inclined by θ (q = (x along, z normal)).

    Gravity gives f = m g (sin θ, −cos θ); gap g_N = z, γ_T = ẋ (plane at rest), G = I/m,
    b = g (−cos θ, sin θ).  Closed forms: a resting block sticks iff tan θ ≤ μ; a sliding one
    accelerates at g (sin θ − s μ cos θ); with θ = 0, μ = 0 it is the bouncing ball.
    """

    n = 2
    name = "point-mass-on-plane"

    def __init__(self, m: float = 1.0, g: float = 9.81, theta: float = 0.0, mu: float = 0.0, eN: float = 0.0):
        self.m, self.g, self.theta, self.mu, self.eN = float(m), float(g), float(theta), float(mu), float(eN)

    def terms(self, t, q, qd):
        one = np.ones_like(np.asarray(q[0], float))
        a0 = np.array([self.g * np.sin(self.theta) * one, -self.g * np.cos(self.theta) * one])
        MiW = np.array([[0 * one, one / self.m], [one / self.m, 0 * one]])  # columns M⁻¹w_N=(0,1/m), M⁻¹w_T=(1/m,0)
        G = np.array([[one / self.m, 0 * one], [0 * one, one / self.m]])
        b = np.array([a0[1], a0[0]])
        return a0, MiW, G, b

    def gap(self, q):
        return q[1]

    def gammas(self, t, q, qd):
        return qd[1], qd[0]

    def project(self, t, y, normal_velocity: bool = False):
        y = np.array(y, dtype=float)
        y[1] = 0.0
        if normal_velocity:
            y[3] = 0.0
        return y

    def project_stick(self, t, y):
        y = self.project(t, y, normal_velocity=True)
        y[2] = 0.0
        return y
