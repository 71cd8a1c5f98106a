"""The amplitude check of the flutter onset by the non-smooth simulation: :func:`check_flutter`.

The prediction: the general engine (:func:`landau.derivation.general.hopf_normal_form`) on the smooth
system of the closed, sliding contact (:func:`sliding_system`), with μ the bifurcation parameter: μ_c,
ω_c, Λ and the amplitude coefficient C of the tangential coordinate.  The measurement: the limit
cycle of the full non-smooth model (:mod:`landau.verify.modecoupling.nonsmooth`, compiled) at
μ = μ_c + side·ε²·μ_c, found by shooting (Newton's method on the period map of the hybrid flow, the
Jacobian by finite differences of the flow, the period a further unknown, the phase fixed at a maximum
of the tangential coordinate), both where it is stable (supercritical) and where it is not
(subcritical); its half peak-to-peak amplitude against C·sqrt|μ − μ_c| and its Floquet multipliers
against the predicted stability, judged by the check's contract (:mod:`landau.analyses.contract`:
the error falls like ε² and extrapolates to 0).

Where the weakly nonlinear cycle ends: the predicted cycle, A·Re(q e^{iωt}) around the sliding
equilibrium with q the critical mode (q_t = 1), opens the contact when A|q_n| reaches the equilibrium
penetration δ* and makes the mass stick when its tangential speed A ω_c reaches the belt speed v₀; the
smaller of the two amplitudes (and its ε²) is reported, and a simulated cycle that opens the contact
or sticks (a mode change on the orbit) is outside the range of validity.

References
----------
Hoffmann, N., Fischer, M., Allgaier, R. & Gaul, L. (2002), Mech. Res. Commun. 29, 197–205.
Kuznetsov, Y. A. (2004), *Elements of Applied Bifurcation Theory*, 3rd ed., Sec. 3.5 and 10.3
(the Hopf normal form; shooting for periodic orbits).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from landau.errors import InputError, IntegratorError, NoHopfError

#: the shooting's integration tolerances (DOP853)
RTOL, ATOL = 1e-12, 1e-14
#: Newton iterations of the shooting at most
NEWTON_ITERATIONS = 12
#: the scan of μ for the first flutter crossing (linearised sliding equilibrium): points and the largest μ
SCAN_POINTS, SCAN_MU_MAX = 400, 10.0

__all__ = ["Cycle", "check_flutter", "hopf_bracket", "linear_mode", "predict", "shoot_cycle", "sliding_system",
           "validity"]


def sliding_system(s):
    """The smooth DynamicalSystem of the closed, sliding contact of the structure ``s`` with Coulomb μ as
    its parameter: states (x, x'), E = diag(I, M), f = (x', −C x' − K x + f_c), f_c[n] = P − N(x_n),
    f_c[t] = μ N(x_n); the equilibrium as unknowns solved at each point (started at the numeric
    equilibrium), the tangential coordinate normalised.

    This is the one builder the branch's check needs; ``ModeCoupling.sliding_system()`` of
    :mod:`landau.systems.mode_coupling` is the same system.
    """
    import sympy as sp

    from landau.systems.system import DynamicalSystem
    from landau.verify.modecoupling.nonsmooth import sliding_equilibrium

    n, nrm, tan = s.n, s.normal, s.tangential
    x = sp.symbols(f"x0:{n}", real=True)
    v = sp.symbols(f"xdot0:{n}", real=True)
    mu = sp.Symbol("mu", real=True)
    eq = sp.symbols(f"x0:{n}__eq", real=True)

    def rational(a):
        return sp.nsimplify(float(a), rational=True) if float(a) == int(a) else sp.Float(float(a), 17)

    def forces(xs, vs):
        N = s.contact.symbolic(xs[nrm], rational(s.contact.kH), rational(s.contact.kNL))
        if s.contact.law == "hertz":      # a closed contact: no clipping at δ = 0 in the smooth system
            N = rational(s.contact.kH) * xs[nrm] * sp.sqrt(xs[nrm])
        f = [-sum(rational(s.C[i, j]) * vs[j] + rational(s.K[i, j]) * xs[j] for j in range(n)) for i in range(n)]
        f[nrm] += rational(s.preload) - N
        f[tan] += mu * N
        return f

    mass = [[sp.Integer(0)] * (2 * n) for _ in range(2 * n)]
    for i in range(n):
        mass[i][i] = sp.Integer(1)
        for j in range(n):
            mass[n + i][n + j] = rational(s.M[i, j])
    guess = sliding_equilibrium(s)[:n]
    return DynamicalSystem(
        name=f"mode-coupling-sliding[n={n},{s.contact.law}]",
        states=(*x, *v), rhs=(*v, *forces(x, v)), mass=mass, parameter=mu,
        equilibrium=(*eq, *([sp.Integer(0)] * n)), normalise=tan, unknowns=eq,
        unknown_equations=tuple(forces(eq, [0] * n)), unknown_guess=tuple(sp.Float(g, 17) for g in guess),
        description="Hoffmann et al. (2002): the closed, sliding contact")


def linear_mode(s, mu: float):
    """(equilibrium, eigenvalues, eigenvectors) of the sliding equilibrium at Coulomb ``mu``, linearised:
    y' = A y with A = [[0, I], [−M⁻¹K_e, −M⁻¹C]], K_e = K + N'(δ*)(e_n − μ e_t)e_nᵀ."""
    from landau.verify.modecoupling.nonsmooth import sliding_equilibrium

    sm = s.with_(mu=float(mu))
    ye = sliding_equilibrium(sm)
    n = s.n
    kN = s.contact.stiffness(float(ye[s.normal]))
    Ke = np.array(s.K, dtype=float)
    Ke[s.normal, s.normal] += kN
    Ke[s.tangential, s.normal] -= mu * kN
    Minv = np.linalg.inv(s.M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ Ke, -Minv @ s.C]])
    lam, vec = np.linalg.eig(A)
    return ye, lam, vec


def hopf_bracket(s, mu_max: float = SCAN_MU_MAX, points: int = SCAN_POINTS) -> tuple[float, float]:
    """An interval of Coulomb μ around the first crossing of a complex pair of the sliding equilibrium
    (the flutter onset), from a scan of the linearised eigenvalues; NoHopfError if none below ``mu_max``."""
    mus = np.linspace(0.0, mu_max, points + 1)
    prev, refused, found = None, None, False
    for mu in mus:
        try:
            _, lam, _ = linear_mode(s, mu)
        except InputError as exc:     # no closed-contact equilibrium at this mu
            prev, refused = None, refused or exc
            continue
        found = True
        osc = lam[np.abs(lam.imag) > 1e-9]
        g = float(osc.real.max()) if len(osc) else -math.inf
        if prev is not None and prev[1] < 0 <= g:
            return float(prev[0]), float(mu)
        prev = (mu, g)
    if not found and refused is not None:
        raise refused
    raise NoHopfError(f"mode-coupling: no flutter (a complex pair crossing into Re > 0) of the sliding equilibrium "
                      f"for mu in [0, {mu_max:g}]")


def predict(s, bracket: tuple[float, float] | None = None):
    """The Hopf point of the sliding equilibrium in Coulomb μ and its amplitude equation (a HopfResult)."""
    from landau.derivation.general import hopf_normal_form

    if bracket is None:
        bracket = hopf_bracket(s)
    return hopf_normal_form(sliding_system(s), {}, bracket)


def validity(s, pr) -> dict:
    """Where the predicted cycle leaves the closed, sliding contact: the amplitude (of the tangential
    coordinate) at which it opens the contact, A|q_n| = δ*, and at which the mass sticks, A ω_c = v₀
    (q the critical mode at μ_c, q_t = 1), with the ε² of each and which comes first."""
    ye, lam, vec = linear_mode(s, pr.p_c)
    k = int(np.argmin(np.abs(lam - 1j * pr.omega_c)))
    q = vec[:, k] / vec[s.tangential, k]
    delta = float(ye[s.normal])
    a_open = delta / abs(q[s.normal]) if abs(q[s.normal]) > 0 else math.inf
    a_stick = s.v0 / pr.omega_c
    C, scale = pr.C, abs(pr.p_c)

    def eps2(a: float) -> float:
        return (a / C) ** 2 / scale if math.isfinite(a) and math.isfinite(C) and C > 0 else math.inf

    first = "contact opens" if a_open <= a_stick else "mass sticks"
    return {"amplitude_contact_opens": a_open, "amplitude_mass_sticks": a_stick, "eps2_contact_opens": eps2(a_open),
            "eps2_mass_sticks": eps2(a_stick), "first": first, "amplitude_first": min(a_open, a_stick),
            "eps2_first": min(eps2(a_open), eps2(a_stick)), "penetration": delta,
            "mode_normal_over_tangential": abs(q[s.normal])}


@dataclass
class Cycle:
    """A periodic orbit of the non-smooth model found by shooting."""

    y0: np.ndarray
    period: float
    amplitude: float
    multipliers: list
    modes: tuple
    iterations: int
    residual: float
    extra: dict = field(default_factory=dict)


def _flow(s, model, y0, T: float, rtol: float):
    from landau.verify.hybrid import EngineOptions
    from landau.verify.hybrid import simulate as run_hybrid
    from landau.verify.hybrid.dop853 import CompiledDOP853
    from landau.verify.modecoupling.nonsmooth import initial_mode

    sol = run_hybrid(model, initial_mode(s, y0), y0, (0.0, T), CompiledDOP853(rtol, rtol * 1e-2),
                     EngineOptions(record=False, max_steps=200_000, max_events=10_000))
    if not sol.success:
        raise IntegratorError(f"mode-coupling: the shooting's flow ended with {sol.status.value}: {sol.message}")
    return sol


def shoot_cycle(s, guess, T: float, rtol: float = RTOL) -> Cycle:
    """The periodic orbit through the neighbourhood of ``guess`` with period near ``T``, by Newton's method
    on φ_T(y₀) − y₀ = 0 with y₀'s tangential velocity fixed at 0 (a maximum or minimum of the tangential
    coordinate) and T an unknown; the Jacobian by forward differences of the flow, ∂φ_T/∂T = f(φ_T(y₀)).

    Raises
    ------
    IntegratorError
        Newton's method does not converge (the message says how far it got).
    """
    from landau.verify.modecoupling.nonsmooth import field_kernel, hybrid_model

    n2, vt = 2 * s.n, s.n + s.tangential
    model = hybrid_model(s, (("x-min", vt, -1.0),))
    slip = field_kernel(s, "slip+")
    y0 = np.array(guess, dtype=float)
    y0[vt] = 0.0
    free = [j for j in range(n2) if j != vt]
    res, iterations = math.inf, 0
    for iterations in range(1, NEWTON_ITERATIONS + 1):  # noqa: B007  (the count is reported)
        end = _flow(s, model, y0, T, rtol).y_final
        R = end - y0
        scale = max(1.0, float(np.abs(y0).max()))
        res = float(np.abs(R).max()) / scale
        if res < 1e-11:
            break
        h = 1e-7 * scale
        J = np.empty((n2, n2))
        for c, j in enumerate(free):
            yp = y0.copy()
            yp[j] += h
            J[:, c] = (_flow(s, model, yp, T, rtol).y_final - end) / h
            J[j, c] -= 1.0
        J[:, -1] = slip(T, end)
        # [∂(φ_T − y₀)/∂y₀,free  f(φ_T)] (Δy₀,free, ΔT) = −(φ_T(y₀) − y₀): one Newton step of the shooting
        d = np.linalg.solve(J, -R)
        y0[free] += d[:-1]
        T += float(d[-1])
        if not (math.isfinite(T) and T > 0):
            raise IntegratorError("mode-coupling: the shooting lost the cycle (the period left (0, inf))")
    else:
        raise IntegratorError(f"mode-coupling: the shooting did not converge in {NEWTON_ITERATIONS} Newton "
                              f"iterations (relative residual {res:.3g})")
    sol = _flow(s, model, y0, T, rtol)
    mins = [float(e.y[s.tangential]) for e in sol.events if e.guard == "x-min"]
    if not mins:
        raise IntegratorError("mode-coupling: the shot orbit has no minimum of the tangential coordinate")
    amplitude = 0.5 * (float(y0[s.tangential]) - min(mins))
    modes = tuple(sorted({e.to_mode for e in sol.events if e.from_mode != e.to_mode}))
    # the monodromy matrix ∂φ_T/∂y₀ (all 2n columns) for the Floquet multipliers
    h = 1e-7 * max(1.0, float(np.abs(y0).max()))
    Mono = np.empty((n2, n2))
    for j in range(n2):
        yp = y0.copy()
        yp[j] += h
        Mono[:, j] = (_flow(s, model, yp, T, rtol).y_final - sol.y_final) / h
    mult, vecs = np.linalg.eig(Mono)
    f0 = slip(0.0, y0)
    along = [abs(np.vdot(vecs[:, j], f0)) / (np.linalg.norm(vecs[:, j]) * np.linalg.norm(f0)) for j in range(n2)]
    trivial = int(np.argmax(along))
    others = [complex(m) for j, m in enumerate(mult) if j != trivial]
    mean = 0.5 * (y0[s.tangential] + min(mins))
    return Cycle(y0, T, abs(amplitude), others, modes, iterations, res,
                 {"trivial_multiplier": complex(mult[trivial]), "mean_tangential": mean})


def _guess(s, pr, mu: float):
    """The predicted cycle's state at its maximum of the tangential coordinate, and its period."""
    ye, lam, vec = linear_mode(s, mu)
    k = int(np.argmin(np.abs(lam - 1j * pr.omega_c)))
    q = vec[:, k] / vec[s.tangential, k]
    A = pr.amplitude(mu)
    return ye + A * q.real, 2 * math.pi / pr.frequency(mu)


def check_flutter(s, eps2=1e-2, *, tolerance: float | None = None, bracket: tuple[float, float] | None = None,
                  rtol: float = RTOL):
    """Check the flutter onset's amplitude equation of the structure ``s`` (Coulomb friction) by the
    non-smooth simulation (module docstring).

    Parameters
    ----------
    s : Structure
        The structure (its ``mu`` is replaced: μ is the bifurcation parameter).
    eps2 : float or sequence of float
        ε² = |μ − μ_c|/μ_c in (0, 0.5); a single value is measured with ε²/4 (the contract's companion).
    tolerance : float, optional
        An extra bound on |relative amplitude error| at the largest ε².
    bracket : (float, float), optional
        An interval of μ holding the onset (default: a scan of the linearised eigenvalues).
    rtol : float
        The shooting's integration tolerance.

    Returns
    -------
    CheckResult
        The verdict of the contract, with ``detail["validity"]`` (:func:`validity`) and each point's
        shot cycle; ``eps2_max_valid`` the ε² where the cycle first opens the contact or sticks.
    """
    from landau.analyses import contract
    from landau.analyses.checking import Verdict, _eps2_request, _Point, _primary, _result, _run_contract
    from landau.derivation.hopf import Criticality

    if s.law.name != "coulomb":
        raise InputError(f"mode-coupling: the check takes Coulomb friction mu (the bifurcation parameter), got the "
                         f"law {s.law.name!r}")
    eps2 = _eps2_request(eps2)
    if tolerance is not None and not (0 < tolerance < 1):
        raise InputError(f"tolerance must be in (0, 1), got {tolerance!r}")
    pr = predict(s, bracket)
    crit = Criticality(str(pr.criticality))
    sub = crit == Criticality.SUBCRITICAL
    scale = abs(pr.p_c)
    primary = _primary(eps2)
    common = dict(system="mode-coupling", parameter="mu", eps2=primary, prediction=pr, tolerance=tolerance)
    if crit == Criticality.DEGENERATE or pr.cycle_side == 0:
        return _result(common, None, pr, pr.p_c, Verdict.OUTSIDE_VALIDITY,
                       "Lambda = 0 (codimension-two point): the cubic amplitude equation predicts no amplitude",
                       None, [], None, 0.0, 0.0)
    valid = validity(s, pr)
    lo = contract.smallest_resolvable_eps2(pr, scale)
    hi = min(0.5, valid["eps2_first"])
    p = pr.p_c + pr.cycle_side * primary * scale
    if primary >= hi:
        why = (f"the predicted cycle {'opens the contact' if valid['first'] == 'contact opens' else 'sticks'} at "
               f"eps2 = {valid['eps2_first']:.3g} (amplitude {valid['amplitude_first']:.3g} m): no weakly nonlinear "
               "cycle of the sliding contact there")
        res = _result(common, None, pr, p, Verdict.OUTSIDE_VALIDITY, why, None, [], hi, lo, hi)
        return replace(res, detail={**res.detail, "validity": valid})

    def measure(e: float, is_primary: bool) -> _Point:
        mu = pr.p_c + pr.cycle_side * e * scale
        pt = _Point(e, mu, pr.amplitude(mu), pr.frequency(mu), rtol=rtol)
        sm = s.with_(mu=mu)
        try:
            guess, T = _guess(s, pr, mu)
            cyc = shoot_cycle(sm, guess, T, rtol)
        except (IntegratorError, InputError, np.linalg.LinAlgError) as exc:
            pt.error = str(exc)
            return pt
        pt.amplitude_simulated, pt.frequency_simulated = cyc.amplitude, 2 * math.pi / cyc.period
        pt.set_multipliers(cyc.multipliers)
        if cyc.modes:
            pt.error = (f"the simulated cycle leaves the sliding contact ({', '.join(cyc.modes)}): outside the weakly "
                        "nonlinear range")
        pt.extra = {"floquet_multipliers": [abs(m) for m in cyc.multipliers], "period": cyc.period,
                    "newton_iterations": cyc.iterations, "residual": cyc.residual, "modes_visited": list(cyc.modes)}
        return pt

    main, sc, verdict, why, emax, pts = _run_contract(measure, eps2, primary, lo, hi, sub, tolerance,
                                                      lambda e: contract.multiplier_gap(pr, e, scale))
    res = _result(common, main, pr, p, verdict, why, sc, pts, emax if emax is not None else valid["eps2_first"],
                  lo, hi)
    return replace(res, detail={**res.detail, "validity": valid})
