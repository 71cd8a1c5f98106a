"""Regime maps of the spring–block by direct simulation started on both sides (the ``regime`` sweep task).

At each (V, k) the spring–block of Putelat, Dawes & Willis (2010), eq. (4), is integrated from two
starts: *near* steady sliding (displaced by 10⁻³ ℓ along the critical mode) and *far* from it (a
block that has almost stopped and healed: v = V/100, φᵢ = 100 φᵢ,ss, spring at its steady load).
Each run is followed through its maxima of X (the crossings of v = V from above) until it
(a run whose step size collapses at steady sliding itself, where the crossings of v = V
dissolve in round-off, has decayed; any other failing run is repeated once at a tolerance 100
times tighter)

* decays (three maxima below 10⁻⁶ ℓ, or 21 maxima shrinking at a constant ratio per cycle that is
  the linear decay's, exp(2π Re μ/Im μ) for the slowest complex pair μ of the linearisation, within
  a factor 2, :func:`_geometric_decay`): **steady** sliding;
* settles on a cycle (successive maxima within 10⁻⁴, the chunk within 10⁻³): a **small cycle** when
  the slip rate stays above V/10 over it, a **stick–slip** cycle when it falls below (the block
  nearly stops: the large relaxation oscillation of Sec. 3.2).

Steady sliding can be the end of a run only where it is linearly stable (every eigenvalue of the
linearisation with Re λ < 0; for k < k_c a pair has Re λ > 0 and repels every run), so no run is
called steady elsewhere: a run that shrinks there is collapsing onto a cycle, and it is followed
on.  Where sliding is stable, a constant ratio alone is not the linear decay either: a large cycle
collapsing onto a small one shrinks nearly geometrically too (its distance to the cycle decays at
a Floquet rate, so the ratio per cycle creeps towards 1 too slowly for 21 maxima to tell), and so
does a slow passage past the ghost of a fold of cycles (a few per cent of the linear rate); the
decay must therefore be the linearisation's own rate, within the factor 1 ± (a/a*)² that the cubic
terms make at amplitude a (a* the amplitude equation's cycle), and a run still shrinking at a
stable point is followed up to :data:`DECAY_EVENTS` maxima until it is.

The point's ``regime`` is the common verdict, or **bistable** when the two starts end on
different attractors (steady sliding and a cycle, or two cycles: the subcritical side of the
Hopf line, Putelat et al. 2010 Figs 5b and 12), or **undecided** when a run has not settled after
:data:`MAX_EVENTS` cycles and the two could still end on one attractor (the approach slows down
as |k − k_c| → 0, so a band along the Hopf line stays undecided at any finite length).  The
amplitude equation predicts the boundaries: the Hopf line k = k_c(V) with Λ < 0 (supercritical:
a small cycle for k < k_c) or Λ > 0 (subcritical: bistability for k slightly above k_c), drawn on the map by
:func:`plot_regime_map`.  This is the comparison Putelat et al. made with AUTO (their Fig. 12),
here by an independent route.
"""

from __future__ import annotations

import math

import numpy as np

from landau.analyses.sweep_engine import Chunk, ChunkResult
from landau.analyses.sweep_tasks import ModelTask
from landau.errors import InputError, IntegratorError, NoHopfError
from landau.verify.springblock.model import SpringBlockModel
from landau.verify.springblock.simulate import W_INDEX, integrate

#: a cycle whose slip rate falls below this fraction of V is a stick–slip cycle
STICK_FRACTION = 0.1
#: relative size of the near start, and the factor of the far start
NEAR, FAR = 1e-3, 100.0
#: crossings per integration chunk, and at most
CHUNK_EVENTS, MAX_EVENTS = 20, 400
#: at most this many crossings for a run still shrinking where steady sliding is stable (a slow
#: passage past the ghost of a fold of cycles, before the linear decay sets in)
DECAY_EVENTS = 2000
REGIMES = ("steady", "small-cycle", "stick-slip", "bistable", "undecided")
UNITS = {"amplitude_near": "m", "amplitude_far": "m", "period_near": "s", "period_far": "s",
         "v_min_near": "1", "v_min_far": "1", "k": "N/m", "k_c": "N/m", "amplitude_predicted": "m",
         "swing_predicted": "1", "k_fold": "N/m"}


#: without k on the grid, each point is simulated at k = K_OVER_KC · k_c of its own parameters: just
#: above the Hopf point, on the stable side, where a supercritical point slides steadily and a
#: subcritical one inside its fold of cycles is bistable (the hysteresis that tells the two apart)
K_OVER_KC = 1.003


_FOLD_DERIVATIONS: dict = {}


def _fold(law, V: float, params) -> float:
    """k_fold, the fold of cycles of the quintic amplitude equation at V
    (:func:`landau.analyses.bautin.spring_block_fold`), NaN where Λ and Λ₅ have the same sign."""
    from landau.analyses.bautin import spring_block_fold
    from landau.derivation.multiscale import derive
    from landau.systems.system import SpringBlock

    block = SpringBlock.for_params(law, params)
    key = (id(law), block.terms)
    if key not in _FOLD_DERIVATIONS:
        _FOLD_DERIVATIONS[key] = (law, derive(block))
    fold = spring_block_fold(_FOLD_DERIVATIONS[key][1], V, params)
    return float(fold.p_fold) if fold is not None else float("nan")


def prediction_at(h, V: float, r: float, law=None, params=None) -> dict:
    """The amplitude equation's numbers at k = r k_c: ``k``, ``k_c``, ``Lambda``, ``criticality``, the
    cycle's half swing ``amplitude_predicted`` = C √|k − k_c| (Putelat et al. 2010, eq. 23: the small
    stable cycle below a supercritical k_c, the unstable one above a subcritical k_c) and its slip-rate
    swing as a fraction of V, ``swing_predicted`` = A ω_c / V (at 1 the weakly nonlinear cycle reverses
    the slip: beyond the prediction's validity); above k_c at a subcritical point also ``k_fold``, the
    fold of cycles of the quintic amplitude equation that bounds the bistable window k_c < k < k_fold
    (NaN where none is predicted: Λ and Λ₅ of one sign)."""
    C, w, kc = float(h.C), float(h.omega_c), float(h.p_c)
    A = C * np.sqrt(abs(1.0 - r) * kc) if np.isfinite(C) else np.nan
    out = {"k": r * kc, "k_c": kc, "Lambda": float(h.Lambda), "criticality": str(h.criticality),
           "amplitude_predicted": A, "swing_predicted": A * w / V}
    if r > 1:
        out["k_fold"] = _fold(law, V, params) if str(h.criticality) == "subcritical" else float("nan")
    return out


def make_task(task: str, model: str, law, fixed: tuple, options: tuple) -> ModelTask:
    """The ``regime`` task of the spring–block (built by the model's task factory).

    Without ``k`` on the grid or among the fixed values, each point is run at k = r k_c(point)
    (option ``k_over_kc`` r, default :data:`K_OVER_KC`), and the point also records the amplitude
    equation's prediction there (:func:`prediction_at`): a map over (V, η) or any other parameters
    whose simulated regimes and amplitudes are compared with the predicted super/subcritical boundary."""
    opts = dict(options)
    unknown = sorted(set(opts) - {"chunk_size", "rtol", "k_over_kc"})
    if unknown:
        raise InputError(f"regime spring-block: option(s) {', '.join(unknown)} do not apply (known: chunk_size, "
                         "rtol, k_over_kc)")
    r = float(opts.get("k_over_kc", K_OVER_KC))
    if not (np.isfinite(r) and r > 0 and r != 1):
        raise InputError(f"regime spring-block: k_over_kc = k/k_c must be > 0 and not 1, got {r!r}")
    return ModelTask(task, model, law, fixed, options, chunk_size=int(opts.get("chunk_size", 1)),
                     chunk_fn=regime_chunk, grid_fn=check_grid, prepare_fn=prepare, extra_units=tuple(UNITS.items()))


def check_grid(task: ModelTask, grid) -> None:
    fixed = dict(task.fixed)
    if "V" not in grid.names and "V" not in fixed:
        raise InputError("regime spring-block: give V as --grid V=... or --param V=...")
    if "k_over_kc" in dict(task.options) and ("k" in grid.names or "k" in fixed):
        raise InputError("regime spring-block: k_over_kc sets k = k_over_kc * k_c where k is not given; give one of "
                         "them")
    M = fixed.get("M", 1.0)
    if "M" in grid.names:
        M = min(grid.axes[grid.names.index("M")].values)
    if M <= 0:
        raise InputError("regime spring-block: direct simulation needs a block mass M > 0")


class _Fate:
    """Where one run went: regime, amplitude (last max of X − x₀, m), slowest slip / V, period (s),
    whether it settled, and its trend when it did not (+1 growing, −1 shrinking)."""

    def __init__(self, regime, amplitude=0.0, v_min=1.0, period=float("nan"), settled=True, trend=0):
        self.regime, self.amplitude, self.v_min, self.period = regime, amplitude, v_min, period
        self.settled, self.trend = settled, trend


def _follow(model: SpringBlockModel, y0: np.ndarray, rtol: float) -> _Fate:
    """The attractor reached from ``y0`` (see the module docstring)."""
    lam, _ = model.critical_mode()
    period = 2 * math.pi / abs(lam.imag) * model.time_unit if lam.imag else 1e3 * model.time_unit
    # steady sliding is an attractor only where it is linearly stable; there, its linear decay
    # shrinks successive maxima by exp(2π Re μ/Im μ) per cycle (μ its slowest complex pair)
    stable, log_ratio = _linear_decay(model)
    y, t = np.asarray(y0, dtype=float), 0.0
    xs: list[float] = []
    ts: list[float] = []
    settled = False
    new: list[float] = []
    tiny = 1e-6 * model.ell
    quiet = 0
    while len(xs) < MAX_EVENTS or (stable and len(xs) < DECAY_EVENTS and _shrinking(new)):
        try:
            run = integrate(model, y, (t, t + 50 * CHUNK_EVENTS * period), rtol=rtol, event_index=W_INDEX,
                            event_direction=-1, stop_after=CHUNK_EVENTS)
        except IntegratorError as exc:
            if stable and _at_rest(model, exc.state):  # the crossings of v = V dissolved in round-off: decayed
                return _Fate("steady")
            raise
        down = run.event_y[run.event_dir < 0]
        if len(down) == 0:
            if stable:  # no oscillation left in 50 periods per crossing wanted: relaxed
                return _Fate("steady")
            quiet += 1  # unstable sliding: a long stick (or a slow start), followed on
            if quiet > QUIET_CHUNKS:
                raise IntegratorError(f"no crossing of v = V in {QUIET_CHUNKS} runs of {50 * CHUNK_EVENTS} linear "
                                      "periods although steady sliding is linearly unstable here", t=run.t_final)
            y, t = run.y_final.copy(), run.t_final
            continue
        new = list(down[:, 0] * model.ell)
        xs += new
        ts += list(run.event_t[run.event_dir < 0])
        if stable and len(xs) >= 3 and all(abs(x) < tiny for x in xs[-3:]):
            return _Fate("steady")
        if stable and len(xs) >= 21 and _geometric_decay(xs[-21:], log_ratio):
            return _Fate("steady")
        a = abs(new[-1])
        if len(new) > 2 and abs(new[-1] - new[-2]) < 1e-4 * a and abs(new[-1] - new[0]) < 1e-3 * a:
            settled = True
            break
        y = run.y_final.copy()
        t = run.t_final
    trend = 0 if settled else (1 if abs(new[-1]) > abs(new[0]) else -1)
    T = float(ts[-1] - ts[-2]) if len(ts) > 1 else period
    # one more cycle with its steps recorded: the slowest slip over it
    y_last = run.event_y[run.event_dir < 0][-1].copy()
    y_last[W_INDEX] = 0.0
    rec = integrate(model, y_last, (0.0, 1.5 * T), rtol=rtol, event_index=W_INDEX, event_direction=-1,
                    stop_after=1, record=200_000)
    v_min = float(np.exp(rec.y[W_INDEX].min()))
    regime = "stick-slip" if v_min < STICK_FRACTION else "small-cycle"
    return _Fate(regime, float(xs[-1]), v_min, T, settled, trend)


def _at_rest(model: SpringBlockModel, state) -> bool:
    """Whether a physical state (X, v, φ…) is steady sliding to within 1e-9 (relative; X against ℓ)."""
    if state is None:
        return False
    X, v, *phis = state
    return (abs(X) <= 1e-9 * model.ell and abs(v / model.V - 1) <= 1e-9
            and all(abs(ph / p0 - 1) <= 1e-9 for ph, p0 in zip(phis, model.phi0, strict=True)))


def _shrinking(x) -> bool:
    """Whether the maxima of the last chunk shrink (each below the one before)."""
    a = np.abs(np.asarray(x, dtype=float))
    return len(a) > 1 and bool(np.all(np.diff(a) < 0))


def _linear_decay(model: SpringBlockModel) -> tuple[bool, float]:
    """Whether steady sliding is linearly stable (every eigenvalue of J(0) with Re < 0), and the log of
    the factor by which its linear decay shrinks successive maxima of X: 2π Re μ/|Im μ| for μ the
    complex pair with the largest real part (NaN where J(0) has none: no oscillatory decay)."""
    lam = np.linalg.eigvals(model.J(np.zeros(model.n)))
    stable = bool(np.all(lam.real < 0))
    pairs = lam[lam.imag > 1e-12 * np.abs(lam)]
    if pairs.size == 0:
        return stable, float("nan")
    mu = pairs[int(np.argmax(pairs.real))]
    return stable, float(2 * math.pi * mu.real / abs(mu.imag))


def _geometric_decay(x, log_ratio: float) -> bool:
    """Whether 21 successive maxima shrink at a constant ratio per cycle (to 10 %) that is the linear
    decay of steady sliding: ρ = log(aᵢ₊₁₀/aᵢ)/10 over each half within a factor
    :data:`LINEAR_MATCH` of ``log_ratio`` (:func:`_linear_decay`, negative: stable sliding).  A
    constant ratio alone is not enough: a large cycle collapsing slowly onto a small one also
    shrinks nearly geometrically, at a ratio unrelated to the linear one (and where sliding is
    unstable, the linear ratio is a growth).  The cubic terms at the amplitude a reached change the
    linear rate by the factor 1 ± (a/a*)², a* the amplitude equation's cycle at k (Putelat et al.
    2010, eq. 23), so a run inside a* decays within the factor 2 and one collapsing from far outside
    it does not."""
    a = np.abs(np.asarray(x, dtype=float))
    if not (np.isfinite(log_ratio) and log_ratio < 0) or np.any(a <= 0) or not np.all(np.diff(a) < 0):
        return False
    r1, r2 = math.log(a[10] / a[0]) / 10, math.log(a[20] / a[10]) / 10
    linear = all(1 / LINEAR_MATCH <= r / log_ratio <= LINEAR_MATCH for r in (r1, r2))
    return linear and abs(r2 - r1) <= 0.1 * abs(r1)


#: the measured decay per cycle must be the linear one within this factor
LINEAR_MATCH = 2.0
#: runs of 50·CHUNK_EVENTS linear periods without a crossing of v = V tolerated where steady
#: sliding is unstable (a long stick) before the run is reported failed
QUIET_CHUNKS = 3


def _far_start(model: SpringBlockModel) -> np.ndarray:
    n_states = len(model.law.states)
    # the terms' states (pore pressure, temperature) start at their steady values
    return np.array([0.0, -math.log(FAR), *([math.log(FAR)] * n_states), *([0.0] * (model.n - 2 - n_states))])


def _combine(near: _Fate, far: _Fate) -> str:
    """The point's regime from the two runs; ``undecided`` where a run has not settled and the two
    could still end on one attractor or on two (a slow approach close to the Hopf line)."""
    if near.regime == far.regime == "steady":
        return "steady"
    if "steady" in (near.regime, far.regime):
        cycle = far if near.regime == "steady" else near
        # steady sliding attracts the near start and a cycle holds the other: bistable
        return "bistable" if near.regime == "steady" and (cycle.settled or cycle.trend > 0) else "undecided"
    lo, hi = sorted((near, far), key=lambda f: abs(f.amplitude))
    if abs(hi.amplitude - lo.amplitude) <= 1e-2 * abs(hi.amplitude):
        return hi.regime if near.regime == far.regime else "undecided"
    if lo.settled and hi.settled:
        return "bistable"   # two distinct cycles
    if lo.trend > 0 and hi.settled:
        return hi.regime    # the smaller run grows towards the cycle the larger one settled on
    if hi.trend < 0 and lo.settled:
        return lo.regime
    if lo.trend > 0 and hi.trend < 0 and lo.regime == hi.regime:
        return lo.regime    # closing in on one cycle from both sides
    return "undecided"


def regime_at(law, V: float, k: float, params=None, rtol: float = 1e-8) -> dict:
    """The regime of the spring–block at (V, k) from both starts (see the module docstring).

    Returns
    -------
    dict
        ``regime`` (steady, small-cycle, stick-slip, bistable, or undecided where a run has not
        settled after :data:`MAX_EVENTS` cycles), ``regime_near``, ``regime_far`` and per start the
        amplitude (max X − x₀, m), the slowest slip rate over the cycle as a fraction of V, the
        period (s) and whether it settled.
    """
    model = SpringBlockModel.build(law, V, k, params)
    out: dict = {}
    fates = {}
    for side, y0 in (("near", model.perturbed(NEAR * model.ell)), ("far", _far_start(model))):
        try:
            f = _follow(model, y0, rtol)
        except IntegratorError:  # a run decaying into the tolerance's noise: once more, 100 times tighter
            f = _follow(model, y0, rtol * 1e-2)
        fates[side] = f
        out.update({f"regime_{side}": f.regime, f"amplitude_{side}": f.amplitude, f"v_min_{side}": f.v_min,
                    f"period_{side}": f.period, f"settled_{side}": float(f.settled)})
    out["regime"] = _combine(fates["near"], fates["far"])
    return out


def regime_chunk(task: ModelTask, chunk: Chunk) -> ChunkResult:
    """The ``regime`` of each point of a chunk (a point whose simulation fails is ``failed``)."""
    from landau.analyses.sweep_engine import _first_line

    law = task.spec.build()
    opts = dict(task.options)
    rtol = float(opts.get("rtol", 1e-8))
    r = float(opts.get("k_over_kc", K_OVER_KC))
    bad, why = task.invalid(chunk)
    status: list[str] = []
    message: list[str] = []
    rows: list[dict] = []
    for j in range(len(chunk.index)):
        pt = {**dict(task.fixed), **{k: float(v[j]) for k, v in chunk.points.items()}}
        if bad[j]:
            rows.append({})
            status.append("failed")
            message.append(why[j])
            continue
        V, k = pt.pop("V"), pt.pop("k", None)
        try:
            prediction = {}
            if k is None:   # at k_over_kc * k_c of this point, with the amplitude equation's prediction
                from landau.models import Setup
                from landau.verify.springblock.declaration import spring_block_hopf

                prediction = prediction_at(spring_block_hopf(Setup(law, {**pt, "V": V})), V, r, law, pt)
                k = prediction["k"]
            row = {**regime_at(law, V, k, pt, rtol), **prediction}
            rows.append(row)
            status.append("ok")
            message.append("" if row["regime"] != "undecided" else
                           f"a run has not settled after {MAX_EVENTS} cycles (a slow approach near the Hopf line)")
        except NoHopfError as exc:   # no Hopf point to set k from
            rows.append({})
            status.append("no-hopf")
            message.append(_first_line(exc))
        except (IntegratorError, InputError, ArithmeticError) as exc:
            rows.append({})
            status.append("failed")
            message.append(_first_line(exc))
    names = [f"{q}_{s}" for q in ("amplitude", "v_min", "period", "settled") for s in ("near", "far")]
    if "k" not in chunk.points and "k" not in dict(task.fixed):
        names += ["k", "k_c", "Lambda", "amplitude_predicted", "swing_predicted"] + (["k_fold"] if r > 1 else [])
    vals = {n: np.array([r.get(n, np.nan) for r in rows], dtype=float) for n in names}
    strs = {n: [r.get(n, "") for r in rows] for n in ("regime", "regime_near", "regime_far")}
    if "k" in names:
        strs["criticality"] = [r.get("criticality", "") for r in rows]
    return ChunkResult(chunk.index, status, message, vals, strs)


def prepare(task: ModelTask) -> None:
    """Compile the law's callbacks and the integrator in this process (before local workers fork)."""
    from landau.verify.springblock.model import compile_law

    compile_law(task.spec.build())


# ---------------------------------------------------------------------------------------------
# the map with the amplitude equation's boundaries
# ---------------------------------------------------------------------------------------------
COLOURS = {"steady": "#dde6f0", "small-cycle": "#8fc98f", "stick-slip": "#e8a33d", "bistable": "#b04a7a",
           "undecided": "#9a9a9a", "": "#ffffff"}


def plot_regime_map(ds, ax=None, n_line: int = 300, overlay=None):
    """A ``regime`` sweep over (V, k) as a coloured map, with the amplitude equation's boundaries on
    top: the Hopf line k_c(V) (solid where Λ < 0, supercritical; dashed where Λ > 0, subcritical),
    the fold of cycles k_fold(V) of the quintic amplitude equation and the codimension-two
    velocities V* (Putelat et al. 2010, Fig. 12), from
    :func:`landau.analyses.regime_overlay.regime_overlay`.

    Parameters
    ----------
    ds : xarray.Dataset
        The result of ``landau.sweep("regime", {"V": ..., "k": ...}, law=...)``.
    ax : matplotlib Axes, optional
    n_line : int
        Velocities on the drawn Hopf line.
    overlay : dict, optional
        The boundaries already computed by ``regime_overlay(ds)`` (computed here otherwise).

    Returns
    -------
    matplotlib.axes.Axes
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    from landau.analyses.regime_overlay import regime_overlay

    if ax is None:
        from matplotlib.figure import Figure

        ax = Figure(figsize=(6.4, 4.6)).subplots()
    if set(ds.regime.dims) != {"V", "k"}:
        raise InputError("the regime map needs a sweep over exactly V and k")
    reg = ds.regime.transpose("k", "V").values.astype(str)
    codes = np.vectorize({r: i for i, r in enumerate(REGIMES)}.get)(np.where(np.isin(reg, REGIMES), reg, "steady"))
    V, k = np.asarray(ds.V.values), np.asarray(ds.k.values)
    cmap = ListedColormap([COLOURS[r] for r in REGIMES])
    ax.pcolormesh(V, k, codes, cmap=cmap, vmin=-0.5, vmax=len(REGIMES) - 0.5, shading="nearest")
    ov = overlay if overlay is not None else regime_overlay(ds, n_line=n_line)
    if ov is not None:
        kc, lam = ov["kc"], ov["Lambda"]
        ax.plot(ov["V_line"], np.where(lam < 0, kc, np.nan), "k-", lw=1.6, label="k_c(V), Λ < 0 (supercritical)")
        ax.plot(ov["V_line"], np.where(lam > 0, kc, np.nan), "k--", lw=1.6, label="k_c(V), Λ > 0 (subcritical)")
        ax.plot(ov["V_fold"], ov["k_fold"], color="#1f5fbf", ls="-.", lw=1.4,
                label=r"fold of cycles $k_c - \Lambda^2/(8\Lambda_5\bar\Gamma)$")
        for i, Vs in enumerate(ov["V_star"]):
            ax.axvline(Vs, color="0.3", lw=0.9, ls=":", label="V* (Λ = 0, codimension two)" if i == 0 else None)
    ax.set_xscale("log")
    ax.set_yscale("log")
    if V.min() < V.max():
        ax.set_xlim(V.min(), V.max())
    if k.min() < k.max():
        ax.set_ylim(k.min(), k.max())
    ax.set_xlabel("V (m/s)")
    ax.set_ylabel("k (N/m)")
    handles = [Patch(color=COLOURS[r], label=r) for r in REGIMES] + ax.get_legend_handles_labels()[0]
    ax.legend(handles=handles, fontsize=7, loc="upper left", framealpha=0.9)
    ax.set_title(f"{ds.attrs.get('law', '')}: regimes by direct simulation, boundaries from the amplitude equation",
                 fontsize=8)
    return ax

