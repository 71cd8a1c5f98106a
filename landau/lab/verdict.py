"""From fitted friction parameters to a verdict on a rig: will it stick-slip, and how does it start?

:func:`rig_verdict` carries the parameters of a friction law fitted to laboratory data (a, b, D_c, …)
to the quantities of the spring–block rig that slides on it (its stiffness k, mass M, normal load σ
and radiation damping η): the critical stiffness k_c, the onset frequency ω_c and the Landau
coefficient Λ of the Hopf bifurcation of steady sliding (Putelat, Dawes & Willis 2010, eqs 7–8,
15–21).  Steady sliding at the rig's stiffness is unstable when k < k_c (stick–slip grows); the
onset is subcritical when Λ > 0 (a finite-amplitude cycle coexists with stable sliding above k_c)
and supercritical when Λ < 0.

The uncertainty of the fit is carried two ways:

* first order (the delta method): with J = ∂(k_c, ω_c, Λ)/∂θ the exact sensitivities
  (:mod:`landau.derivation.sensitivity`) at the fitted θ and Σ the covariance of θ, the covariance of
  the quantities is J Σ Jᵀ; in that Gaussian approximation P(unstable) = Φ((k_c − k)/σ_kc) and
  P(subcritical) = Φ(Λ/σ_Λ), Φ the standard normal distribution function;
* from samples of θ (a posterior, e.g. MCMC chains): each sample's k_c and Λ, their spread, and the
  fractions of samples with k < k_c and with Λ > 0 (a sample without a Hopf point — steady sliding
  stable at every stiffness — counts as stable and not subcritical).

The probabilities reported are those of the samples when samples are given, of the first-order
Gaussian otherwise (the point values alone: 0 or 1).

References
----------
Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), "Regimes of frictional sliding of a
spring–block system", J. Mech. Phys. Solids 58(1), 27–53.
Ku, H. H. (1966), "Notes on the use of propagation of error formulas", J. Res. Natl. Bur. Stand.
70C(4), 263–273 (first-order propagation).
"""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

import numpy as np

from landau.errors import InputError

#: the quantities a verdict carries, by their canonical names
VERDICT_QUANTITIES = ("k_c", "omega_c", "Lambda")

#: rig entries (SI, per block or per unit area): stiffness, mass, normal load, radiation damping
RIG_KEYS = {"k": "N/m", "M": "kg", "sigma": "N", "eta": "N s/m"}


def _phi(x: float) -> float:
    """The standard normal distribution function Φ(x) (±inf accepted)."""
    return 0.5 * math.erfc(-x / math.sqrt(2.0))


def _gaussian_probability(mean: float, sd: float) -> float:
    """P(X > 0) for X ~ N(mean, sd²); a step at sd = 0."""
    if not math.isfinite(mean):
        return float("nan")
    if sd == 0:
        return 1.0 if mean > 0 else 0.0
    return _phi(mean / sd)


@dataclass(frozen=True)
class RigVerdict:
    """What the fitted friction law says about one rig (module docstring).

    Parameters
    ----------
    law : str
        The friction law's name.
    V : float
        The driving (load-point) velocity, m/s.
    rig : dict
        The rig: k, and M, sigma, eta where given (SI).
    params : dict
        Every parameter the quantities were evaluated at (the fitted values and the rig's).
    values : dict
        k_c [N/m], omega_c [rad/s], Lambda [1/(m² s)] at the fitted parameters (NaN: no Hopf point).
    criticality : str
        "supercritical", "subcritical", "degenerate" or "no Hopf point", at the fitted parameters.
    unstable : bool
        Whether k < k_c at the fitted parameters.
    sensitivities : dict
        quantity -> {fitted parameter -> ∂q/∂θ} at the fitted parameters (0 for a parameter that does
        not enter the rig's quantities).
    sd_first_order : dict or None
        quantity -> standard deviation by first-order propagation (with a covariance).
    sd_samples : dict or None
        quantity -> standard deviation over the samples with a Hopf point (with samples).
    p_unstable, p_subcritical : float
        P(k < k_c) and P(Λ > 0).
    probabilities_from : str
        "samples", "first-order Gaussian" or "point values".
    p_unstable_gaussian, p_subcritical_gaussian : float or None
        The first-order Gaussian probabilities (with a covariance), also when samples decide.
    n_samples, n_no_hopf : int
        Samples used, and how many of them have no Hopf point.
    inert : tuple of str
        Fitted names that are no parameter of the rig's quantities (a fit's μ₀ trend, say): carried
        with sensitivity 0.
    """

    law: str
    V: float
    rig: dict
    params: dict
    values: dict
    criticality: str
    unstable: bool
    sensitivities: dict
    sd_first_order: dict | None
    sd_samples: dict | None
    p_unstable: float
    p_subcritical: float
    probabilities_from: str
    p_unstable_gaussian: float | None = None
    p_subcritical_gaussian: float | None = None
    n_samples: int = 0
    n_no_hopf: int = 0
    inert: tuple[str, ...] = ()
    units: dict = field(default_factory=lambda: {"k_c": "N/m", "omega_c": "rad/s", "Lambda": "1/(m^2 s)",
                                                 "V": "m/s", **RIG_KEYS})

    def as_dict(self) -> dict[str, Any]:
        """The verdict as JSON-ready fields."""
        from dataclasses import asdict

        d = asdict(self)
        d["inert"] = list(self.inert)
        return d

    def __repr__(self) -> str:
        def pm(q: str) -> str:
            sd = (self.sd_samples or {}).get(q, (self.sd_first_order or {}).get(q))
            v = self.values[q]
            return f"{v:.6g}" + (f" ± {sd:.2g}" if sd is not None else "")
        return (f"RigVerdict(law {self.law!r} at V = {self.V:g} m/s, k = {self.rig['k']:g} N/m: "
                f"k_c = {pm('k_c')} N/m, omega_c = {pm('omega_c')} rad/s, Lambda = {pm('Lambda')} 1/(m^2 s), "
                f"{self.criticality}; P(unstable) = {self.p_unstable:.4g}, P(subcritical) = "
                f"{self.p_subcritical:.4g} ({self.probabilities_from}))")


def _check_rig(rig: Mapping[str, float]) -> dict[str, float]:
    if not isinstance(rig, Mapping):
        raise InputError(f"rig must be a mapping of k, M, sigma, eta to values, got {type(rig).__name__}")
    out: dict[str, float] = {}
    for key, val in rig.items():
        if key not in RIG_KEYS:
            close = difflib.get_close_matches(str(key), list(RIG_KEYS), n=1)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise InputError(f"unknown rig entry {key!r}{hint} (known: {', '.join(RIG_KEYS)})")
        try:
            x = float(val)
        except (TypeError, ValueError):
            raise InputError(f"rig entry {key!r} must be a number, got {val!r}") from None
        if not math.isfinite(x):
            raise InputError(f"rig entry {key!r} must be finite, got {val!r}")
        out[key] = x
    if "k" not in out:
        raise InputError("rig needs its stiffness k (N/m)")
    if out["k"] <= 0:
        raise InputError(f"rig stiffness k must be > 0, got {out['k']!r}")
    return out


def _check_matrix(covariance, n: int) -> np.ndarray:
    try:
        cov = np.array(covariance, dtype=float)
    except (TypeError, ValueError):
        raise InputError("covariance must be a square matrix of numbers") from None
    if cov.shape != (n, n):
        raise InputError(f"covariance must be {n} x {n} (one row per name), got shape {cov.shape}")
    if not np.all(np.isfinite(cov)):
        raise InputError("covariance has a non-finite entry")
    if not np.allclose(cov, cov.T, rtol=1e-10, atol=0.0):
        raise InputError("covariance must be symmetric")
    scale = max(float(np.max(np.abs(np.diag(cov)))), np.finfo(float).tiny)
    if n and float(np.min(np.linalg.eigvalsh(cov))) < -1e-10 * scale:
        raise InputError("covariance must be positive semi-definite (it has a negative eigenvalue)")
    return cov


def _check_samples(samples, n: int) -> np.ndarray:
    try:
        s = np.array(samples, dtype=float)
    except (TypeError, ValueError):
        raise InputError("samples must be an array of numbers, one row per sample") from None
    if s.ndim != 2 or s.shape[1] != n:
        raise InputError(f"samples must have shape (n_samples, {n}) (one column per name), got {s.shape}")
    if s.shape[0] < 2:
        raise InputError("samples: at least 2 samples are needed for a spread")
    if not np.all(np.isfinite(s)):
        raise InputError("samples have a non-finite entry")
    return s


def _setup(law, fitted: Mapping[str, float], rig: Mapping[str, float], names: Sequence[str] | None):
    """(derivation, resolved parameters, rig, names, parameters of the quantities among the names)."""
    from landau.derivation.multiscale import Derivation, _as_block
    from landau.derivation.sensitivity import parameters
    from landau.systems.system import SpringBlock

    rig = _check_rig(rig)
    if not isinstance(fitted, Mapping) or not fitted:
        raise InputError("fitted must be a non-empty mapping of parameter names to values")
    block = _as_block(law)
    block = SpringBlock(block.law, tuple(dict.fromkeys([*block.terms, *(("eta",) if "eta" in rig else ())])))
    d = Derivation(block)
    known = set(parameters(d))
    names = list(fitted) if names is None else [str(x) for x in names]
    if len(set(names)) != len(names):
        raise InputError("names: a parameter is named twice")
    missing = [x for x in names if x not in fitted]
    if missing:
        raise InputError(f"names: {missing[0]!r} has no fitted value")
    clash = sorted(set(fitted) & {"M", "sigma", "eta"} & set(rig))
    if clash:
        raise InputError(f"parameter {clash[0]!r} is given twice (fitted and rig)")
    own = {key: float(v) for key, v in fitted.items() if key in known}
    rig_params = {key: v for key, v in rig.items() if key != "k"}
    if "V" in own:
        raise InputError("the driving velocity is the argument V, not a fitted parameter")
    params = block.resolve({**own, **rig_params})
    active = [x for x in names if x in known]
    return d, params, rig, names, active


def rig_verdict(law, fitted: Mapping[str, float], rig: Mapping[str, float], *, covariance: np.ndarray | None = None,
                names: Sequence[str] | None = None, samples: np.ndarray | None = None, V: float) -> RigVerdict:
    """k_c, ω_c, Λ and the criticality of a rig from fitted law parameters, with their uncertainties.

    Parameters
    ----------
    law : FrictionLaw or str
        The fitted friction law (or a built-in law's name).
    fitted : mapping of str to float
        The fitted parameter values (law parameters; a name that is no parameter of the rig's
        quantities is carried with sensitivity 0 and listed in ``inert``).
    rig : mapping of str to float
        The rig, SI: ``k`` (stiffness, N/m, required), ``M`` (kg), ``sigma`` (normal load, N),
        ``eta`` (radiation damping, N·s/m); per unit area consistently (Pa/m, kg/m², Pa, Pa·s/m).
    covariance : array_like, optional
        The covariance of the fitted parameters, rows in the order of ``names``.
    names : sequence of str, optional
        The order of the covariance's rows and of the samples' columns (default: ``fitted``'s order).
    samples : array_like, optional
        Samples of the fitted parameters (a posterior), shape (n_samples, len(names)).
    V : float
        The driving (load-point) velocity, m/s.

    Returns
    -------
    RigVerdict

    Raises
    ------
    InputError
        A malformed rig, covariance or samples; an unknown parameter; a velocity that is not > 0.
    """
    from landau.derivation.linear import one_velocity
    from landau.derivation.multiscale import criticality as crit

    V = one_velocity(V, "V", "a verdict per velocity")
    d, params, rig, names, active = _setup(law, fitted, rig, names)
    sens = d.sensitivities(V, params, VERDICT_QUANTITIES, active or None)
    values = {q: float(np.ravel(sens["value"][q])[0]) for q in VERDICT_QUANTITIES}
    hopf = math.isfinite(values["k_c"])
    J = np.zeros((len(VERDICT_QUANTITIES), len(names)))
    if hopf:
        for i, q in enumerate(VERDICT_QUANTITIES):
            for j, x in enumerate(names):
                if x in active:
                    J[i, j] = float(np.ravel(sens[q][x])[0])
    k = rig["k"]
    out: dict[str, Any] = {
        "law": d.block.law.name, "V": V, "rig": rig, "params": params, "values": values,
        "criticality": crit(values["Lambda"]) if hopf else "no Hopf point",
        "unstable": bool(hopf and k < values["k_c"]),
        "sensitivities": {q: {x: float(J[i, j]) for j, x in enumerate(names)}
                          for i, q in enumerate(VERDICT_QUANTITIES)},
        "sd_first_order": None, "sd_samples": None, "inert": tuple(x for x in names if x not in active)}
    p_unstable = 1.0 if out["unstable"] else 0.0
    p_sub = 1.0 if hopf and values["Lambda"] > 0 else 0.0
    source = "point values"
    if covariance is not None:
        cov = _check_matrix(covariance, len(names))
        # first-order propagation: Cov(q) = J Σ Jᵀ
        qcov = J @ cov @ J.T
        sd = {q: float(math.sqrt(max(qcov[i, i], 0.0))) for i, q in enumerate(VERDICT_QUANTITIES)}
        out["sd_first_order"] = sd if hopf else {q: float("nan") for q in VERDICT_QUANTITIES}
        if hopf:
            out["p_unstable_gaussian"] = _gaussian_probability(values["k_c"] - k, sd["k_c"])
            out["p_subcritical_gaussian"] = _gaussian_probability(values["Lambda"], sd["Lambda"])
            p_unstable, p_sub = out["p_unstable_gaussian"], out["p_subcritical_gaussian"]
        source = "first-order Gaussian"
    if samples is not None:
        s = _check_samples(samples, len(names))
        kc, lam = _sample_quantities(d, V, params, names, active, s)
        ok = np.isfinite(kc)
        out["n_samples"], out["n_no_hopf"] = int(s.shape[0]), int((~ok).sum())
        out["sd_samples"] = ({"k_c": float(np.std(kc[ok], ddof=1)), "Lambda": float(np.std(lam[ok], ddof=1))}
                             if ok.sum() >= 2 else {"k_c": float("nan"), "Lambda": float("nan")})
        p_unstable = float(np.mean(ok & (k < np.where(ok, kc, -np.inf))))
        p_sub = float(np.mean(ok & (np.where(ok, lam, -np.inf) > 0)))
        source = "samples"
    return RigVerdict(**out, p_unstable=p_unstable, p_subcritical=p_sub, probabilities_from=source)


def _sample_quantities(d, V: float, params: Mapping[str, float], names: Sequence[str], active: Sequence[str],
                       samples: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """k_c and Λ at each sample (NaN where a sample has no Hopf point or is outside the law's domain)."""
    from landau.errors import LandauError

    cols = {x: samples[:, j] for j, x in enumerate(names) if x in active}
    for prm in d.block.law.parameters:
        if prm.positive and prm.name in cols and np.any(cols[prm.name] <= 0):
            bad = int(np.sum(cols[prm.name] <= 0))
            raise InputError(f"samples: parameter {prm.name!r} must be > 0, but {bad} sample(s) are not")
    for x in ("M", "sigma", "eta"):
        if x in cols and np.any(cols[x] < 0):
            raise InputError(f"samples: parameter {x!r} must be >= 0")
    base = {key: v for key, v in params.items() if key not in cols and key != "g"}
    if d.hopf.closed_form is not None:
        try:
            table = d.evaluate(np.array([V]), {**base, **cols}, ["kc", "Lambda"])
            return np.asarray(table["kc"], dtype=float), np.asarray(table["Lambda"], dtype=float)
        except LandauError:
            pass                  # a sample outside the law's domain: one by one below, it alone NaN
    kc = np.full(samples.shape[0], np.nan)
    lam = np.full(samples.shape[0], np.nan)
    for i in range(samples.shape[0]):
        try:
            t = d.evaluate(np.array([V]), {**base, **{x: float(c[i]) for x, c in cols.items()}}, ["kc", "Lambda"])
        except LandauError:
            continue
        kc[i], lam[i] = float(np.ravel(t["kc"])[0]), float(np.ravel(t["Lambda"])[0])
    return kc, lam


__all__ = ["RIG_KEYS", "VERDICT_QUANTITIES", "RigVerdict", "rig_verdict"]
