"""Fit a rate-and-state law to a laboratory record: least squares on the compiled forward model.

:func:`fit` adjusts the chosen parameters of any law of :mod:`landau.laws` (a, b, L, a_v, a second
state's b₂, L₂, …; the stiffness k′ and a linear trend on request) so that the quasi-static
spring–slider of :mod:`landau.lab.forward` reproduces the recorded friction.  The residual is
r_i = μ(t_i; p) + c (x_lp,i − x_lp,0) − μ_obs,i (c the optional trend), minimised by
``scipy.optimize.least_squares`` (trust-region reflective, positive parameters bounded below by
zero) with the Jacobian ∂r/∂p from the forward sensitivities (exact to the integration's
tolerance, not finite differences).  The standard errors are those of the linearised model
(Bates & Watts 1988, Sec. 2.3): cov = s² (JᵀJ)⁻¹ with s² = Σr²/(n − q); the correlation matrix
follows.  Optionally a posterior by the affine-invariant ensemble sampler of Goodman & Weare
(2010) as implemented by emcee (Foreman-Mackey et al. 2013), with a Gaussian likelihood of the
fitted noise level s and flat priors (positive where the parameter is), its chains saved to an
``.npz`` file.

Units: SI throughout (lengths in m, velocities in m/s, k′ = k/σ in 1/m, the trend in 1/m).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

import numpy as np

from landau.errors import InputError, IntegratorError
from landau.lab.data import LabData, read_csv
from landau.lab.forward import RTOL, STIFFNESS, forward_model
from landau.laws.law import FrictionLaw

#: the name of the linear trend coefficient (1/m: friction per metre of load-point displacement)
TREND = "trend"
#: parameters never fitted by default (the reference velocity: only its product with e^{a_v/a} matters)
NOT_FITTED_BY_DEFAULT = ("V_s",)
#: the residual returned where the forward model fails at a trial point (the step is then rejected)
_FAILED = 1e3


@dataclass
class FitResult:
    """A fitted law: values, standard errors, correlations, residual, and optionally a posterior.

    Attributes
    ----------
    law : FrictionLaw
        The law fitted.
    names : tuple of str
        The fitted parameters, the order of :attr:`covariance`'s rows and :attr:`samples`' columns.
    params : dict
        Every parameter's value (SI): the law's (fitted and fixed), ``"k"`` (k′, 1/m) and, with a
        trend, ``"trend"`` (1/m).
    standard_errors : dict
        The standard error of each fitted parameter.
    covariance : ndarray (q, q)
        s² (JᵀJ)⁻¹.
    correlation : ndarray (q, q)
        The correlation matrix.
    residual : ndarray (n,)
        Model minus data at each sample.
    rms : float
        √(Σr²/(n − q)), the fitted noise level s.
    samples : ndarray (draws, q) or None
        Posterior draws after burn-in (with ``mcmc``).
    """

    law: FrictionLaw
    names: tuple[str, ...]
    params: dict[str, float]
    standard_errors: dict[str, float]
    covariance: np.ndarray
    correlation: np.ndarray
    residual: np.ndarray
    rms: float
    nfev: int
    success: bool
    message: str
    model: np.ndarray = field(repr=False)
    samples: np.ndarray | None = None
    acceptance: float | None = None
    chains_path: str | None = None

    def verdict(self, rig: Mapping[str, float], V: float):
        """The fitted law carried to the spring–block rig ``rig`` (k, M, σ, η, SI) at driving velocity V:
        k_c, ω_c, Λ and the criticality with their uncertainties (:func:`landau.lab.verdict.rig_verdict`).

        Only the law's parameters are handed on (with their rows of the covariance and columns of
        the samples): the lab's k′ and the trend are not the rig's."""
        from landau.lab.verdict import rig_verdict

        law_names = {p.name for p in self.law.parameters}
        keep = [i for i, n in enumerate(self.names) if n in law_names]
        names = [self.names[i] for i in keep]
        fitted = {n: self.params[n] for n in law_names}
        cov = self.covariance[np.ix_(keep, keep)]
        samples = None if self.samples is None else self.samples[:, keep]
        return rig_verdict(self.law, fitted, rig, covariance=cov, names=names, samples=samples, V=V)

    def to_dict(self) -> dict[str, Any]:
        """The result as plain data (the ``--json`` document; a value that is not finite, such as the
        standard error of a parameter the record does not determine, is None)."""
        return _finite({
            "law": self.law.name,
            "fitted": {n: {"value": self.params[n], "standard_error": self.standard_errors[n]} for n in self.names},
            "fixed": {n: v for n, v in self.params.items() if n not in self.names},
            "correlation": {"names": list(self.names), "matrix": self.correlation.tolist()},
            "covariance": self.covariance.tolist(),
            "rms_residual": self.rms, "samples": int(self.residual.size), "nfev": self.nfev,
            "success": self.success, "message": self.message,
            "mcmc": None if self.samples is None else {
                "draws": int(self.samples.shape[0]), "acceptance": self.acceptance, "chains": self.chains_path,
                "mean": dict(zip(self.names, self.samples.mean(axis=0).tolist(), strict=True)),
                "std": dict(zip(self.names, self.samples.std(axis=0, ddof=1).tolist(), strict=True))},
        })


def _finite(obj):
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_finite(v) for v in obj]
    return obj


class _Problem:
    """The residual and its Jacobian in the fitted parameters (one forward run per point)."""

    def __init__(self, law: FrictionLaw, data: LabData, names: Sequence[str], values: Mapping[str, float],
                 rtol: float, sensitivities: bool = True) -> None:
        self.law, self.data, self.names = law, data, tuple(names)
        self.values = dict(values)
        sens = [n for n in self.names if n != TREND] if sensitivities else []
        self.fm = forward_model(law, sens)
        self.sensitivities = sensitivities
        self.rtol = rtol
        self.dx = data.x_lp - data.x_lp[0]
        self._last: tuple[bytes, np.ndarray, np.ndarray | None] | None = None

    def point(self, x: np.ndarray) -> dict[str, float]:
        vals = dict(self.values)
        vals.update(zip(self.names, (float(z) for z in x), strict=True))
        return vals

    def evaluate(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        key = np.asarray(x, float).tobytes()
        if self._last is not None and self._last[0] == key:
            return self._last[1], self._last[2]
        vals = self.point(x)
        law_vals = {p.name: vals[p.name] for p in self.law.parameters}
        try:
            with np.errstate(all="ignore"):
                run = self.fm.run(self.data.t, self.data.V_lp, law_vals, vals[STIFFNESS], rtol=self.rtol)
            mu = run.mu + vals.get(TREND, 0.0) * self.dx
            r = mu - self.data.mu
            if not np.all(np.isfinite(r)) or not np.all(np.isfinite(run.dmu)):
                raise IntegratorError("not finite")
        except (IntegratorError, InputError, np.linalg.LinAlgError, ZeroDivisionError, OverflowError):
            r, J = np.full(self.data.t.size, _FAILED), None
            self._last = (key, r, J)
            return r, J
        if not self.sensitivities:        # the MCMC's runs: the residual only
            self._last = (key, r, None)
            return r, None
        cols, j = [], 0
        for n in self.names:
            if n == TREND:
                cols.append(self.dx)
            else:
                cols.append(run.dmu[:, j])
                j += 1
        J = np.column_stack(cols) if cols else np.zeros((r.size, 0))
        self._last = (key, r, J)
        return r, J

    def residual(self, x):
        return self.evaluate(x)[0]

    def jacobian(self, x):
        r, J = self.evaluate(x)
        return J if J is not None else np.zeros((r.size, len(self.names)))


def _resolve(law: FrictionLaw | str, data: LabData, free: Sequence[str] | None, params: Mapping[str, float] | None,
             k: float | None, fit_k: bool, trend: bool) -> tuple[FrictionLaw, list[str], dict[str, float]]:
    """The law, the fitted names and every starting (or fixed) value."""
    if isinstance(law, str):
        from landau.laws import get_law

        law = get_law(law)
    if not isinstance(law, FrictionLaw):
        raise InputError(f"fit needs a rate-and-state law (a name or a FrictionLaw), got {type(law).__name__}")
    law_names = [p.name for p in law.parameters]
    given = dict(params or {})
    known = set(law_names) | {STIFFNESS, TREND}
    for n, val in given.items():
        if n not in known:
            raise InputError(f"{n!r} is not a parameter of law {law.name!r} (its parameters: {', '.join(law_names)})")
        if not (isinstance(val, (int, float)) and math.isfinite(float(val))):
            raise InputError(f"parameter {n!r} must be a finite number, got {val!r}")
    if k is None and STIFFNESS not in given:
        raise InputError("the stiffness k' = k/sigma is needed (1/m; --k 1e-3/um on the command line)")
    values: dict[str, float] = {p.name: float(p.default) for p in law.parameters if p.default is not None}
    if "V_s" in law_names:
        values["V_s"] = float(data.V_lp[0])      # the reference velocity: the initial one, as in the lab
    if "a_v" in law_names and "a_v" not in given:
        values["a_v"] = float(data.mu[0])        # at steady sliding at V_s = V_lp(0), μ = a_v
    values.update({n: float(v) for n, v in given.items()})
    values[STIFFNESS] = float(given.get(STIFFNESS, k))   # type: ignore[arg-type]
    if not values[STIFFNESS] > 0:
        raise InputError(f"the stiffness k' must be > 0, got {values[STIFFNESS]:g} 1/m")
    if free is None:
        names = [n for n in law_names if n not in NOT_FITTED_BY_DEFAULT]
    else:
        names = list(free)
        for n in names:
            if n not in law_names and n not in (STIFFNESS, TREND):
                raise InputError(f"cannot fit {n!r}: it is not a parameter of law {law.name!r} "
                                 f"(its parameters: {', '.join(law_names)})")
        if len(set(names)) != len(names):
            raise InputError(f"a fitted parameter is named twice: {', '.join(names)}")
    if fit_k and STIFFNESS not in names:
        names.append(STIFFNESS)
    if trend and TREND not in names:
        names.append(TREND)
    if TREND in names:
        values.setdefault(TREND, 0.0)
    missing = [n for n in law_names if n not in values]
    if missing:
        raise InputError(f"law {law.name!r}: give a value for {', '.join(missing)} (it has no default)")
    if not names:
        raise InputError("nothing to fit: name at least one parameter")
    if data.t.size <= len(names):
        raise InputError(f"{data.t.size} samples for {len(names)} parameters: a fit needs more samples")
    return law, names, values


def _positive(law: FrictionLaw, names: Sequence[str]) -> np.ndarray:
    """Which fitted parameters are positive (searched in ln p) and which are not (searched in p)."""
    return np.array([n == STIFFNESS or (n != TREND and law.parameter(n).positive) for n in names], dtype=bool)


def _covariance(J: np.ndarray, rss: float, dof: int) -> np.ndarray:
    """s² (JᵀJ)⁻¹ by the singular values of J (no normal equations formed)."""
    U, sv, Vt = np.linalg.svd(J, full_matrices=False)
    if sv.size == 0 or sv[-1] <= sv[0] * 1e-14:
        return np.full((J.shape[1], J.shape[1]), np.inf)
    s2 = rss / dof
    # J = U Σ Vᵀ  ⇒  (JᵀJ)⁻¹ = V Σ⁻² Vᵀ
    return s2 * (Vt.T / sv**2) @ Vt


def fit(data: LabData | str | os.PathLike, law: FrictionLaw | str, *, free: Sequence[str] | None = None,
        params: Mapping[str, float] | None = None, k: float | None = None, fit_k: bool = False,
        trend: bool = False, mcmc: int = 0, walkers: int | None = None, burn: int | None = None,
        seed: int = 0, chains: str | os.PathLike | None = None, rtol: float = RTOL,
        max_nfev: int = 200) -> FitResult:
    """Fit ``law`` to the record ``data`` by least squares (and optionally MCMC).

    Parameters
    ----------
    data : LabData or path
        The record (a path is read by :func:`landau.lab.data.read_csv` with landau's columns).
    law : FrictionLaw or str
        A law object (a built-in or a user's) or a built-in's name.
    free : sequence of str, optional
        The parameters fitted (default: every parameter of the law except the reference velocity
        V_s, which is set to the first sample's load-point velocity unless given).
    params : mapping, optional
        Starting values of the fitted parameters and values of the fixed ones (SI); the law's
        defaults otherwise, and a_v = μ at the first sample.
    k : float
        The stiffness k′ = k/σ (1/m): fixed, or the starting value with ``fit_k``.
    fit_k : bool
        Fit the stiffness as well.
    trend : bool
        Fit a linear trend c (1/m) of friction against load-point displacement.
    mcmc : int
        Steps of each emcee walker (0: no MCMC); the first ``burn`` (default half) are dropped.
    walkers : int, optional
        Number of walkers (default max(4q, 16)).
    seed : int
        Seed of the walkers' start and moves.
    chains : path, optional
        Where to save the chains (``.npz``, written atomically).
    rtol : float
        Relative tolerance of the forward integration.
    max_nfev : int
        Most forward runs of the least-squares search.

    Returns
    -------
    FitResult

    Examples
    --------
    >>> res = fit("velocity_step.csv", "dieterich", k=1e3)      # doctest: +SKIP
    >>> res.params["b"], res.standard_errors["b"]                # doctest: +SKIP
    """
    from scipy.optimize import least_squares

    if not isinstance(data, LabData):
        data = read_csv(data)
    law, names, values = _resolve(law, data, free, params, k, fit_k, trend)
    prob = _Problem(law, data, names, values, rtol)
    x0 = np.array([values[n] for n in names])
    pos = _positive(law, names)
    if np.any(x0[pos] <= 0):
        bad = [n for n, p in zip(names, pos, strict=True) if p and values[n] <= 0][0]
        raise InputError(f"the starting value of {bad!r} must be > 0, got {values[bad]:g}")
    r0 = prob.residual(x0)
    if np.all(r0 == _FAILED):
        raise InputError(f"the forward model of {law.name!r} cannot be run at the starting values "
                         f"{ {n: values[n] for n in names} }: give other ones (params=...)")

    # the search runs in z = ln p for the positive parameters (scale-free, positivity kept) and
    # z = p for the others: ∂r/∂z = p ∂r/∂p, resp. ∂r/∂p
    def to_x(z):
        return np.where(pos, np.exp(np.where(pos, z, 0.0)), z)

    def jac_z(z):
        x = to_x(z)
        return prob.jacobian(x) * np.where(pos, x, 1.0)[None, :]

    z0 = np.where(pos, np.log(np.where(pos, x0, 1.0)), x0)
    sol = least_squares(lambda z: prob.residual(to_x(z)), z0, jac=jac_z, x_scale="jac", method="trf",
                        xtol=1e-14, ftol=1e-15, gtol=1e-15, max_nfev=max_nfev)
    xhat = to_x(sol.x)
    r, J = prob.evaluate(xhat)
    if J is None:
        raise IntegratorError(f"the forward model of {law.name!r} fails at the fitted parameters")
    n, q = r.size, len(names)
    rss = float(r @ r)
    cov = _covariance(J, rss, n - q)
    se = np.sqrt(np.diag(cov))
    with np.errstate(all="ignore"):
        corr = cov / np.outer(se, se)
    fitted = prob.point(xhat)
    result = FitResult(law, tuple(names), fitted, dict(zip(names, se.tolist(), strict=True)), cov, corr, r,
                       math.sqrt(rss / (n - q)), int(sol.nfev), bool(sol.success), str(sol.message),
                       model=data.mu + r)
    if mcmc:
        _posterior(result, prob, xhat, np.where(pos, 0.0, -np.inf), mcmc, walkers, burn, seed, chains)
    return result


def _posterior(result: FitResult, prob: _Problem, x: np.ndarray, lo: np.ndarray, steps: int, walkers: int | None,
               burn: int | None, seed: int, chains) -> None:
    """emcee's ensemble around the least-squares point; fills ``result.samples`` (and saves the chains)."""
    try:
        import emcee
    except ImportError:
        raise InputError("MCMC needs emcee: pip install 'landau-friction[fit]'") from None
    if not (isinstance(steps, int) and steps >= 2):
        raise InputError(f"mcmc must be a number of steps >= 2, got {steps!r}")
    q = x.size
    nw = walkers or max(4 * q, 16)
    if nw < 2 * q:
        raise InputError(f"emcee needs at least {2 * q} walkers for {q} parameters, got {nw}")
    burn = steps // 2 if burn is None else burn
    if not 0 <= burn < steps:
        raise InputError(f"burn must be in [0, {steps}), got {burn}")
    plain = _Problem(prob.law, prob.data, prob.names, prob.values, prob.rtol, sensitivities=False)
    s2 = result.rms ** 2

    def log_prob(z):
        if np.any(z <= lo):
            return -np.inf
        r = plain.residual(z)
        if r[0] == _FAILED and np.all(r == _FAILED):
            return -np.inf
        return -0.5 * float(r @ r) / s2

    rng = np.random.default_rng(seed)
    cov = result.covariance if np.all(np.isfinite(result.covariance)) else np.diag((1e-3 * np.abs(x)) ** 2)
    start = rng.multivariate_normal(x, cov, size=nw)
    start = np.where(start <= lo, x + np.abs(start - x), start)
    sampler = emcee.EnsembleSampler(nw, q, log_prob)
    sampler.random_state = np.random.RandomState(seed).get_state()   # the moves' draws, reproducible
    sampler.run_mcmc(start, steps, progress=False)
    chain = sampler.get_chain()
    result.samples = chain[burn:].reshape(-1, q)
    result.acceptance = float(np.mean(sampler.acceptance_fraction))
    if chains is not None:
        from landau.support.io import atomic_write

        lp = sampler.get_log_prob()
        atomic_write(chains, lambda fh: np.savez(fh, chain=chain, log_prob=lp, names=np.array(result.names),
                                                 burn=burn, law=result.law.name), mode="wb")
        result.chains_path = os.fspath(chains)

