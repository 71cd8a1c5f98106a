"""What a sweep computes at each point: the tasks ``hopf``, ``check``, ``simulate`` and ``regime``.

A task is a small picklable object (it travels to the workers) holding the model, the friction
law's declaration and the fixed parameters; :meth:`Task.run` computes one chunk of points and
returns their status and variables (:class:`~landau.analyses.sweep_engine.ChunkResult`).  The
variables are named as in the matching ``--json`` output.

* ``hopf`` of the spring–block (Putelat et al. 2010): a whole chunk through the vectorised
  compiled kernels of :meth:`~landau.derivation.multiscale.Derivation.evaluate` (k_c, ω_c, Γ̄, Ω̄,
  Λ, χ, C), one evaluation route for every chunk; of the other models, point by point through
  the model's own Hopf analysis (``landau hopf MODEL``).
* ``check`` (spring–block): :func:`landau.check` at each point, its verdict and numbers.
* ``simulate`` (forced oscillator of Skurativskyi et al. 2019): the attractor reached by
  continuation in the forcing frequency ω (impacts per period, Poincaré points, the largest
  Lyapunov exponent on request), :mod:`landau.verify.skurativskyi.sweep`.
* ``regime`` (spring–block): the regime by direct simulation started on both sides,
  :mod:`landau.verify.springblock.regime_map`.
* ``scene``: a published value (a scene of ``landau scene list``, named as the model) as a function
  of the scene's parameters, with its difference to the published number.

The models above this layer are reached through :data:`IMPLEMENTATIONS` (module and function
names, imported in the worker).
"""

from __future__ import annotations

import argparse
import importlib
import json
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from landau.analyses.sweep_engine import Chunk, ChunkResult, Grid, chunks
from landau.errors import InputError, LandauError, NoHopfError

#: task -> model -> "module:function" computing a chunk (imported where the chunk runs)
IMPLEMENTATIONS: dict[str, dict[str, str]] = {
    "simulate": {"forced-oscillator": "landau.verify.skurativskyi.sweep:simulate_chunk"},
    "regime": {"spring-block": "landau.verify.springblock.regime_map:regime_chunk"},
}

#: SI units of the spring–block's system parameters and of the variables of the tasks
SPRING_BLOCK_UNITS = {"V": "m/s", "k": "N/m", "M": "kg", "g": "m/s^2", "sigma": "Pa", "eps2": "1"}


def _skip(status: list, message: list, rows: list, why: str, exc: BaseException) -> None:
    """Record a point without a result: its status, the exception's first line, no values."""
    from landau.analyses.sweep_engine import _first_line

    status.append(why)
    message.append(_first_line(exc))
    rows.append({})


def _resolve(ref: str):
    mod, fn = ref.split(":")
    return getattr(importlib.import_module(mod), fn)


# ---------------------------------------------------------------------------------------------
# the friction law, rebuilt in every worker from its declaration
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class LawSpec:
    """A friction law by name (built-in) or by its declaration, as the workers rebuild it.

    Parameters
    ----------
    name : str
        A built-in law's name (with ``mu`` None), or the declared law's name.
    mu : str, optional
        The friction coefficient μ(v, φ…) (:meth:`landau.laws.FrictionLaw.from_strings`).
    states : tuple of (str, str)
        Each state's name and its rate dφ/dt.
    params : tuple of (str, float)
        The declared law's parameter values.
    """

    name: str
    mu: str | None = None
    states: tuple[tuple[str, str], ...] = ()
    params: tuple[tuple[str, float], ...] = ()

    def build(self):
        key = (self.name, self.mu, self.states, self.params)
        law = _LAWS.get(key)
        if law is None:
            from landau.laws import FrictionLaw, get_law

            law = (get_law(self.name) if self.mu is None
                   else FrictionLaw.from_strings(self.name, self.mu, dict(self.states), dict(self.params)))
            _LAWS[key] = law
        return law

    @classmethod
    def of(cls, law) -> "LawSpec":
        """The spec of a :class:`~landau.laws.FrictionLaw` object (its name if it is the built-in law of
        that name, else its declaration with its parameters' values)."""
        from landau.laws import BUILTIN, get_law

        if law.name in BUILTIN and get_law(law.name) == law:
            return cls(law.name)
        states = tuple((str(sym), str(rate)) for sym, rate in zip(law.states, law.rates, strict=True))
        params = tuple((p.name, float(p.default)) for p in law.parameters if p.default is not None)
        return cls(law.name, str(law.mu), states, params)

    def declaration(self) -> str:
        law = self.build()
        rates = "; ".join(f"d{s}/dt = {r}" for s, r in zip(law.states, law.rates, strict=True))
        return f"mu = {law.mu}; {rates}"


_LAWS: dict[tuple, Any] = {}
_DERIVATIONS: dict[tuple, Any] = {}


def _derivation(spec: LawSpec):
    d = _DERIVATIONS.get((spec,))
    if d is None:
        from landau.derivation.multiscale import derive
        from landau.systems.system import SpringBlock

        d = _DERIVATIONS[(spec,)] = derive(SpringBlock(spec.build()))
    return d


# ---------------------------------------------------------------------------------------------
# the task interface
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Task:
    """A sweep task: name, model, law and fixed parameters; see the module docstring."""

    name: str
    model: str
    law: LawSpec | None
    fixed: tuple[tuple[str, Any], ...] = ()
    options: tuple[tuple[str, Any], ...] = ()
    chunk_size: int = 1
    continuation: bool = False
    #: on local processes, run the first chunk in the calling process before the workers start, so
    #: that what the task builds lazily (a derivation, compiled simulations) is built once and
    #: inherited by the forked workers (tasks without a :meth:`prepare` of their own)
    lead: ClassVar[bool] = False

    @property
    def spec(self) -> LawSpec:
        """The friction law (InputError for a model without one)."""
        if self.law is None:
            raise InputError(f"{self.name} {self.model}: this model has no rate-and-state law")
        return self.law

    def units(self) -> dict[str, str]:
        from landau.derivation.multiscale import UNITS

        own = {p.name: p.units for p in self.law.build().parameters if p.units} if self.law else {}
        return {**UNITS, **SPRING_BLOCK_UNITS, **own}

    def attrs(self) -> dict[str, Any]:
        from landau import __version__
        from landau.derivation.multiscale import CONVENTION

        return {"task": self.name, "model": self.model, "law": self.law.name if self.law else "",
                "law_declaration": self.law.declaration() if self.law else "",
                "convention": "putelat2010" if self.model == "spring-block" else "",
                "convention_description": CONVENTION if self.model == "spring-block" else "",
                "landau_version": __version__,
                "fixed_parameters": json.dumps(dict(self.fixed), sort_keys=True),
                "task_options": json.dumps(dict(self.options), sort_keys=True)}

    def check_grid(self, grid: Grid) -> None:
        """Refuse (InputError) a grid this task cannot run."""

    def for_grid(self, grid: Grid) -> "Task":
        """The task as it runs on ``grid`` (a choice made once, in the calling process)."""
        return self

    def chunks(self, grid: Grid) -> list[Chunk]:
        return chunks(grid, self.chunk_size)

    def prepare(self) -> None:
        """Compile or load what the workers need, in the calling process."""

    def run(self, chunk: Chunk) -> ChunkResult:
        raise NotImplementedError


def _spring_block_grid(task: Task, grid: Grid, allowed_extra: tuple[str, ...] = ()) -> None:
    from landau.systems.system import SpringBlock

    block = SpringBlock(task.spec.build())
    known = {p.name for p in block.law.parameters} | set(block.defaults) | {"V", *allowed_extra}
    for name in (*grid.names, *dict(task.fixed)):
        if name not in known:
            raise InputError(f"{task.name} spring-block: unknown parameter {name!r} for law {block.law.name!r} "
                             f"(known: {', '.join(sorted(known))})")
    if "V" not in grid.names and "V" not in dict(task.fixed):
        raise InputError(f"{task.name} spring-block: give the driving velocity as --grid V=... or --param V=...")
    for name in grid.names:
        vals = np.asarray(grid.axes[grid.names.index(name)].values)
        if name in ("V", "M", "L", "V_s", "sigma", "k", "eps2") and np.any(vals <= 0) and name != "M":
            raise InputError(f"--grid {name}: values must be > 0")
        if name == "M" and np.any(vals < 0):
            raise InputError("--grid M: values must be >= 0")


# ---------------------------------------------------------------------------------------------
# hopf
# ---------------------------------------------------------------------------------------------
HOPF_NAMES = ["kc", "omega_c", "Gamma_bar", "Omega_bar", "Lambda", "chi", "C"]


@dataclass(frozen=True)
class SpringBlockHopf(Task):
    """k_c, ω_c and the amplitude-equation coefficients over a chunk (vectorised)."""

    method: str = "auto"

    def check_grid(self, grid: Grid) -> None:
        if "k" in grid.names or "k" in dict(self.fixed):
            raise InputError("hopf spring-block: k is the bifurcation parameter (its critical value k_c is "
                             "computed), it cannot be swept")
        _spring_block_grid(self, grid)

    def for_grid(self, grid: Grid) -> "SpringBlockHopf":
        """One evaluation route for every chunk, so that no number depends on how the grid was cut:
        the exactly cancelled form (:mod:`landau.derivation.rational`) when only V is swept and the
        law's derivatives are rational in V, else the screened float route ("general")."""
        if self.method != "auto":
            return self
        from dataclasses import replace

        method = "general"
        if grid.names == ("V",):
            fixed = {k: v for k, v in self.fixed if k != "V"}
            try:
                _derivation(self.spec).evaluate(np.array([grid.axes[0].values[0]]), fixed, HOPF_NAMES,
                                               method="rational")
                method = "rational"
            except InputError:
                pass
        return replace(self, method=method)

    def prepare(self) -> None:
        _derivation(self.spec)

    def run(self, chunk: Chunk) -> ChunkResult:
        d = _derivation(self.spec)
        pts = dict(chunk.points)
        fixed = dict(self.fixed)
        V = pts.pop("V") if "V" in pts else np.full(len(chunk.index), float(fixed.pop("V")))
        fixed.pop("V", None)
        params = {**fixed, **pts}
        try:
            r = d.evaluate(V, params, HOPF_NAMES, method=self.method)
        except InputError:
            if not pts:
                raise
            # array-valued parameters need a closed-form Hopf line: point by point
            rows = [d.evaluate(np.array([V[j]]), {**fixed, **{k: float(v[j]) for k, v in pts.items()}},
                               HOPF_NAMES, method=self.method) for j in range(len(V))]
            r = {n: np.array([float(np.ravel(row[n])[0]) for row in rows]) for n in [*HOPF_NAMES, "degenerate"]}
        n = len(chunk.index)
        vals = {k: np.broadcast_to(np.asarray(r[k], dtype=float), (n,)).copy() for k in HOPF_NAMES}
        degenerate = np.broadcast_to(np.asarray(r.get("degenerate", False), dtype=bool), (n,))
        kc = vals["kc"]
        ok = np.isfinite(kc) & (kc > 0)
        for k in HOPF_NAMES:
            vals[k] = np.where(ok, vals[k], np.nan)
        lam = vals["Lambda"]
        crit = np.where(~ok, "", np.where(degenerate | ~np.isfinite(lam) | (lam == 0), "degenerate",
                                          np.where(lam < 0, "supercritical", "subcritical")))
        status = np.where(~ok, "no-hopf", np.where(crit == "degenerate", "degenerate", "ok"))
        message = [f"no Hopf point at V = {V[j]:.6g} m/s (steady sliding does not lose stability)" if not ok[j]
                   else ("Lambda = 0: codimension-two point, the cubic amplitude equation predicts no amplitude"
                         if status[j] == "degenerate" else "") for j in range(n)]
        out = {"p_c": vals["kc"], "k_c": vals["kc"], "kc": vals["kc"], "omega_c": vals["omega_c"],
               "dRe_lambda_dp": -vals["Gamma_bar"], "dIm_lambda_dp": vals["Omega_bar"],
               "Gamma_bar": vals["Gamma_bar"], "Omega_bar": vals["Omega_bar"], "Lambda": lam,
               "chi": vals["chi"], "C": vals["C"]}
        return ChunkResult(chunk.index, list(status), message, out, {"criticality": list(crit)})


@dataclass(frozen=True)
class PointwiseHopf(Task):
    """The Hopf point of any model registered with ``landau hopf``, point by point: the model's
    function is called with the arguments the command line would give it (swept values as
    ``--param NAME=VALUE``, ``V`` as ``--V``)."""

    lead: ClassVar[bool] = True

    def _function(self):
        hopf = importlib.import_module("landau.cli.hopf")
        hopf._load_models()
        if self.model not in hopf.MODELS:
            raise InputError(f"hopf: unknown model {self.model!r}; known: {', '.join(hopf.MODELS)}")
        return hopf.MODELS[self.model][1]

    def check_grid(self, grid: Grid) -> None:
        self._function()
        unknown = sorted(set(dict(self.options)) - {"friction", "friction_neg", "friction_name", "kinetic",
                                                     "kinetic_pos", "parameter", "chunk_size"})
        if unknown:
            raise InputError(f"hopf {self.model}: option(s) {', '.join(unknown)} do not apply")

    def run(self, chunk: Chunk) -> ChunkResult:
        fn = self._function()
        status: list[str] = []
        message: list[str] = []
        rows: list[dict[str, float]] = []
        crit: list[str] = []
        opts = dict(self.options)
        for j in range(len(chunk.index)):
            point = {**dict(self.fixed), **{k: float(v[j]) for k, v in chunk.points.items()}}
            V = point.pop("V", None)
            args = argparse.Namespace(law=None, mu=None, state=[], friction=opts.get("friction"),
                                      friction_neg=opts.get("friction_neg"),
                                      friction_name=opts.get("friction_name", "user-friction"),
                                      kinetic=opts.get("kinetic"), kinetic_pos=opts.get("kinetic_pos"),
                                      parameter=opts.get("parameter"), V=None if V is None else repr(V),
                                      param=[f"{k}={v!r}" for k, v in point.items()])
            try:
                res = fn(args)
            except NoHopfError as exc:
                _skip(status, message, rows, "no-hopf", exc)
                crit.append("")
                continue
            except (LandauError, ArithmeticError, ValueError) as exc:
                _skip(status, message, rows, "failed", exc)
                crit.append("")
                continue
            doc = res.as_dict()
            c = str(doc.get("criticality", ""))
            rows.append({k: float(v) for k, v in doc.items()
                         if isinstance(v, (int, float)) and not isinstance(v, bool)})
            crit.append(c)
            status.append("degenerate" if c == "degenerate" else "ok")
            message.append("")
        names = sorted({k for r in rows for k in r})
        vals = {k: np.array([r.get(k, np.nan) for r in rows]) for k in names}
        return ChunkResult(chunk.index, status, message, vals, {"criticality": crit})


# ---------------------------------------------------------------------------------------------
# check
# ---------------------------------------------------------------------------------------------
CHECK_FLOATS = ("p", "eps2", "p_c", "amplitude_predicted", "amplitude_simulated", "rel_error",
                "frequency_predicted", "frequency_simulated", "frequency_rel_error", "tolerance", "eps2_max_valid")


@dataclass(frozen=True)
class SpringBlockCheck(Task):
    """The direct-simulation verdict of :func:`landau.check` at each (V, eps2, parameters) point."""

    lead: ClassVar[bool] = True

    def check_grid(self, grid: Grid) -> None:
        if "k" in grid.names or "k" in dict(self.fixed):
            raise InputError("check spring-block: the stiffness is set by eps2 = |k - k_c|/k_c (sweep eps2, not k)")
        _spring_block_grid(self, grid, ("eps2",))

    def run(self, chunk: Chunk) -> ChunkResult:
        from landau.analyses.checking import check

        opts = dict(self.options)
        status: list[str] = []
        message: list[str] = []
        rows: list[dict[str, float]] = []
        strs: dict[str, list[str]] = {"verdict": [], "criticality_predicted": []}
        for j in range(len(chunk.index)):
            point = {**dict(self.fixed), **{k: float(v[j]) for k, v in chunk.points.items()}}
            V = point.pop("V")
            eps2 = point.pop("eps2", opts.get("eps2", 1e-3))
            try:
                res = check(self.spec.build(), V=V, eps2=eps2, params=point,
                            bistability=bool(opts.get("bistability", False)))
            except NoHopfError as exc:
                _skip(status, message, rows, "no-hopf", exc)
                strs["verdict"].append("")
                strs["criticality_predicted"].append("")
                continue
            doc = res.as_dict()
            rows.append({k: (np.nan if doc.get(k) is None else float(doc[k])) for k in CHECK_FLOATS}
                        | {"bistable": np.nan if doc.get("bistable") is None else float(doc["bistable"]),
                           "cycle_stable": np.nan if doc.get("cycle_stable") is None else float(doc["cycle_stable"])})
            strs["verdict"].append(doc["verdict"])
            strs["criticality_predicted"].append(doc["criticality_predicted"])
            status.append({"outside-validity": "outside-validity", "failed": "failed"}.get(doc["verdict"], "ok"))
            message.append(doc.get("reason") or "")
        names = [*CHECK_FLOATS, "bistable", "cycle_stable"]
        vals = {k: np.array([r.get(k, np.nan) for r in rows]) for k in names}
        return ChunkResult(chunk.index, status, message, vals, strs)


# ---------------------------------------------------------------------------------------------
# scene
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class SceneTask(Task):
    """A published value as a function of parameters: the scene ``model`` (``landau scene list``) run
    at each point with the swept values as its parameters (:func:`landau.scenes.run_scene`)."""

    lead: ClassVar[bool] = True

    def _scene(self):
        from landau.scenes import get_scene

        return get_scene(self.model)

    def units(self) -> dict[str, str]:
        return {"value": self._scene().units, "published": self._scene().units, "rel_diff": "1"}

    def attrs(self) -> dict[str, Any]:
        sc = self._scene()
        return {**super().attrs(), "scene_parameter": sc.parameter, "source": sc.source}

    def check_grid(self, grid: Grid) -> None:
        known = set(self._scene().defaults)
        for name in (*grid.names, *dict(self.fixed)):
            if name not in known:
                raise InputError(f"scene {self.model!r} has no parameter {name!r} (known: "
                                 f"{', '.join(sorted(known)) or 'none'})")

    def run(self, chunk: Chunk) -> ChunkResult:
        from landau.scenes import run_scene

        status: list[str] = []
        message: list[str] = []
        rows: list[dict[str, float]] = []
        agrees: list[str] = []
        for j in range(len(chunk.index)):
            point = {**dict(self.fixed), **{k: float(v[j]) for k, v in chunk.points.items()}}
            try:
                doc = run_scene(self.model, point)
            except (LandauError, ArithmeticError, ValueError) as exc:
                _skip(status, message, rows, "failed", exc)
                agrees.append("")
                continue
            rows.append({k: float(doc[k]) for k in ("value", "published", "rel_diff", "tolerance")
                         if isinstance(doc.get(k), (int, float)) and not isinstance(doc.get(k), bool)})
            agrees.append("" if doc.get("agrees") is None else str(bool(doc["agrees"])).lower())
            status.append("ok")
            message.append("")
        vals = {k: np.array([r.get(k, np.nan) for r in rows]) for k in ("value", "published", "rel_diff", "tolerance")}
        return ChunkResult(chunk.index, status, message, vals, {"agrees": agrees})


# ---------------------------------------------------------------------------------------------
# tasks implemented by the models' own modules (simulate, regime)
# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class ModelTask(Task):
    """A task whose chunk function lives in the model's module (:data:`IMPLEMENTATIONS`)."""

    along: str | None = None
    overlap: int = 0
    descending: bool = False
    check_ref: str | None = None
    extra_units: tuple[tuple[str, str], ...] = field(default=())

    def units(self) -> dict[str, str]:
        return {**super().units(), **dict(self.extra_units)}

    def check_grid(self, grid: Grid) -> None:
        if self.law is not None and self.model == "spring-block":
            _spring_block_grid(self, grid, ("k",))
        if self.check_ref:
            _resolve(self.check_ref)(self, grid)

    def chunks(self, grid: Grid) -> list[Chunk]:
        return chunks(grid, self.chunk_size, self.along, self.overlap, self.descending)

    def prepare(self) -> None:
        ref = IMPLEMENTATIONS[self.name][self.model]
        mod = importlib.import_module(ref.split(":")[0])
        if hasattr(mod, "prepare"):
            mod.prepare(self)

    def run(self, chunk: Chunk) -> ChunkResult:
        return _resolve(IMPLEMENTATIONS[self.name][self.model])(self, chunk)


#: tasks and the models each runs on
TASKS = {"hopf": "the Hopf point and amplitude-equation coefficients (any model of landau hopf)",
         "check": "the direct-simulation verdict of landau.check (spring-block)",
         "simulate": "statistics of a settled run (forced-oscillator: continuation in omega)",
         "regime": "the regime by direct simulation started on both sides (spring-block)",
         "scene": "a published value as a function of parameters (MODEL: a scene of landau scene list)"}


def make_task(task: str, model: str, law: LawSpec | None, fixed: dict[str, Any], options: dict[str, Any]) -> Task:
    """The :class:`Task` for ``task`` on ``model``.

    Raises
    ------
    InputError
        An unknown task, a model the task does not run on, a missing law.
    """
    if task not in TASKS:
        raise InputError(f"unknown sweep task {task!r} (tasks: {', '.join(TASKS)})")
    fx = tuple(sorted((k, float(v)) for k, v in fixed.items()))
    opts = tuple(sorted(options.items()))
    if model == "spring-block" and law is None:
        raise InputError(f"{task} spring-block: name a law (built-in or --mu/--state)")
    if model != "spring-block" and law is not None:
        raise InputError(f"{task} {model}: this model takes no rate-and-state law")
    if task == "hopf":
        if model == "spring-block":
            return SpringBlockHopf("hopf", model, law, fx, opts, chunk_size=int(options.get("chunk_size", 4096)),
                                   method=str(options.get("method", "auto")))
        return PointwiseHopf("hopf", model, None, fx, opts, chunk_size=int(options.get("chunk_size", 1)))
    if task == "scene":
        if law is not None:
            raise InputError(f"scene {model}: a scene takes no law (its model and law are the paper's)")
        return SceneTask("scene", model, None, fx, opts, chunk_size=int(options.get("chunk_size", 1)))
    if task == "check":
        if model != "spring-block":
            raise InputError(f"check: the sweep runs the spring-block's check (got model {model!r})")
        return SpringBlockCheck("check", model, law, fx, opts, chunk_size=1)
    impl = IMPLEMENTATIONS[task]
    if model not in impl:
        raise InputError(f"{task}: runs on {', '.join(impl)} (got model {model!r})")
    mod = importlib.import_module(impl[model].split(":")[0])
    return mod.make_task(task, model, law, fx, opts)
