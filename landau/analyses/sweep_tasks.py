"""What a sweep computes at each point: the tasks ``hopf``, ``check``, ``simulate`` and ``regime``.

A task is a small picklable object (it travels to the workers) holding the model, the friction
law's declaration and the fixed parameters; :meth:`Task.run` computes one chunk of points and
returns their status and variables (:class:`~landau.analyses.sweep_engine.ChunkResult`).  The
variables are named as in the matching ``--json`` output.

* ``hopf`` of the spring–block (Putelat et al. 2010): a whole chunk through the vectorised
  compiled kernels of :meth:`~landau.derivation.multiscale.Derivation.evaluate` (k_c, ω_c, Γ̄, Ω̄,
  Λ, χ, C), one evaluation route for every chunk, with the optional terms the grid names built in;
  of the other models (and a spring–block with α_LD), point by point through the model's own Hopf
  analysis (:attr:`landau.models.Model.hopf`).
* ``check`` (spring–block): :func:`landau.check` at each point, its verdict and numbers.
* ``simulate`` (forced oscillator of Skurativskyi et al. 2019): the attractor reached by
  continuation in the forcing frequency ω (impacts per period, Poincaré points, the largest
  Lyapunov exponent on request), :mod:`landau.verify.skurativskyi.sweep`.
* ``regime`` (spring–block): the regime by direct simulation started on both sides,
  :mod:`landau.verify.springblock.regime_map`.
* ``cycles`` (any model with a ``cycles`` declaration): the branch of cycles from the Hopf point at
  each point (:func:`landau.analyses.cycles.follow`), its first fold of cycles LPC and first period
  doubling PD (parameter, period, amplitude; NaN where the branch has none).
* ``scene``: a published value (a scene of ``landau scene list``, named as the model) as a function
  of the scene's parameters, with its difference to the published number.

A task's model is a :class:`landau.models.Model`, looked up by name in the registry: the model
declares its parameters (a grid axis or a fixed value may be any of them; a value outside a
parameter's domain makes that point ``failed`` with the domain error, never a physical status),
its Hopf parameter (never given or swept in ``hopf``) and the other tasks it runs
(:attr:`landau.models.Model.tasks`, task factories that live beside the model).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any, Callable, ClassVar, Sequence

import numpy as np

from landau.analyses.sweep_engine import Chunk, ChunkResult, Grid, chunks
from landau.errors import InputError, LandauError, NoHopfError
from landau.models import LawKind, Model, Setup
from landau.models import get as get_model


def _skip(status: list, message: list, rows: list, why: str, exc: BaseException) -> None:
    """Record a point without a result: its status, the exception's first line, no values."""
    from landau.analyses.sweep_engine import _first_line

    status.append(why)
    message.append(_first_line(exc))
    rows.append({})


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


def _derivation(spec: LawSpec, terms: tuple[str, ...] = ()):
    """The spring–block's derivation for the law ``spec`` with the optional ``terms`` (one per process)."""
    d = _DERIVATIONS.get((spec, terms))
    if d is None:
        from landau.derivation.multiscale import derive
        from landau.systems.system import SpringBlock

        d = _DERIVATIONS[(spec, terms)] = derive(SpringBlock(spec.build(), terms))
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

    @property
    def model_object(self) -> Model:
        """The registered model (:func:`landau.models.get`)."""
        return get_model(self.model)

    def setup(self, params: dict[str, float] | None = None) -> Setup:
        """The model's :class:`~landau.models.Setup` for this task's law and options, at ``params``."""
        return Setup(self.law.build() if self.law is not None else None, dict(params or {}), dict(self.options))

    def units(self) -> dict[str, str]:
        from landau.derivation.multiscale import UNITS

        declared = {p.name: p.unit for p in self.model_object.parameters(self.setup(dict(self.fixed)))}
        return {**UNITS, "eps2": "1", **declared}

    def attrs(self) -> dict[str, Any]:
        from landau import __version__

        model = self.model_object
        return {"task": self.name, "model": self.model, "law": self.law.name if self.law else "",
                "law_declaration": self.law.declaration() if self.law else "",
                "convention": model.convention, "convention_description": model.convention_description,
                "landau_version": __version__,
                "fixed_parameters": json.dumps(dict(self.fixed), sort_keys=True),
                "task_options": json.dumps(dict(self.options), sort_keys=True)}

    def check_grid(self, grid: Grid) -> None:
        """Refuse (InputError) a grid this task cannot run: a name the model does not declare."""
        check_declared(self, grid)

    def for_grid(self, grid: Grid) -> "Task":
        """The task as it runs on ``grid`` (a choice made once, in the calling process)."""
        return self

    def chunks(self, grid: Grid) -> Sequence[Chunk]:
        return chunks(grid, self.chunk_size)

    def prepare(self) -> None:
        """Compile or load what the workers need, in the calling process."""

    def run(self, chunk: Chunk) -> ChunkResult:
        raise NotImplementedError

    def point(self, chunk: Chunk, j: int) -> dict[str, float]:
        """The parameters of the chunk's point ``j``: the fixed values and the swept ones."""
        return {**dict(self.fixed), **{k: float(v[j]) for k, v in chunk.points.items()}}

    def invalid(self, chunk: Chunk) -> tuple[np.ndarray, list[str]]:
        """The chunk's points with a value outside its parameter's declared domain, and their messages."""
        n = len(chunk.index)
        values = {**{k: np.full(n, float(v)) for k, v in self.fixed}, **chunk.points}
        return self.model_object.invalid_points(values, self.setup(dict(self.fixed)))


def check_declared(task: Task, grid: Grid, *, refuse_hopf_parameter: bool = False,
                   task_axes: tuple[str, ...] = ()) -> None:
    """Every swept and fixed name is a parameter the model declares (for this law and options), but
    ``task_axes``, the task's own swept quantities (eps2 of the check); with ``refuse_hopf_parameter``,
    the Hopf parameter is neither swept nor fixed (its critical value is what the task computes)."""
    model = task.model_object
    setup = task.setup(dict(task.fixed))
    names = (*(n for n in grid.names if n not in task_axes), *(n for n in dict(task.fixed) if n not in task_axes))
    if refuse_hopf_parameter:
        hp = model.bifurcation_parameter(setup)
        if hp is not None and hp in names:
            raise InputError(f"{task.name} {task.model}: {hp} is the bifurcation parameter (its critical value is "
                             "computed), it cannot be swept or fixed")
    model.check_params(names, setup, what=f"{task.name} {task.model}")


# ---------------------------------------------------------------------------------------------
# hopf
# ---------------------------------------------------------------------------------------------
HOPF_NAMES = ["kc", "omega_c", "Gamma_bar", "Omega_bar", "Lambda", "chi", "C"]


@dataclass(frozen=True)
class SpringBlockHopf(Task):
    """k_c, ω_c and the amplitude-equation coefficients over a chunk (vectorised), with the optional
    spring–block terms (:mod:`landau.systems.springblock_terms`) that the grid or the fixed values name."""

    method: str = "auto"
    terms: tuple[str, ...] = ()

    def check_grid(self, grid: Grid) -> None:
        check_declared(self, grid, refuse_hopf_parameter=True)

    def for_grid(self, grid: Grid) -> Task:
        """One evaluation route for every chunk, so that no number depends on how the grid was cut:
        the terms named by the grid built in; the exactly cancelled form (:mod:`landau.derivation.rational`)
        when only V is swept and the law's derivatives are rational in V, else the screened float route
        ("general").  With a term that puts k in the state rates (α_LD: the Hopf line is not affine in k) the
        model's own Hopf analysis point by point (:class:`PointwiseHopf`)."""
        from dataclasses import replace

        from landau.systems.springblock_terms import check_terms, stiffness_in_rates, term_of

        named = {*grid.names, *dict(self.fixed)}
        given = {term_of(n) for n in named}
        terms = check_terms(tuple(t for t in _term_names() if t in given))
        if stiffness_in_rates(terms):
            return PointwiseHopf("hopf", self.model, self.law, self.fixed, self.options, chunk_size=1)
        task = replace(self, terms=terms)
        if self.method != "auto":
            return task
        method = "general"
        if grid.names == ("V",):
            fixed = {k: v for k, v in self.fixed if k != "V"}
            try:
                _derivation(self.spec, terms).evaluate(np.array([grid.axes[0].values[0]]), fixed, HOPF_NAMES,
                                                      method="rational")
                method = "rational"
            except InputError:
                pass
        return replace(task, method=method)

    def prepare(self) -> None:
        _derivation(self.spec, self.terms)

    def run(self, chunk: Chunk) -> ChunkResult:
        n = len(chunk.index)
        bad, why = self.invalid(chunk)
        good = np.flatnonzero(~bad)
        out = {k: np.full(n, np.nan) for k in _HOPF_OUTPUTS}
        status, message, crit = ["failed"] * n, list(why), [""] * n
        if len(good):
            res = self._evaluate({k: np.asarray(v)[good] for k, v in chunk.points.items()}, len(good))
            for k in _HOPF_OUTPUTS:
                out[k][good] = res.values[k]
            for i, j in enumerate(good):
                status[j], message[j], crit[j] = res.status[i], res.message[i], res.strings["criticality"][i]
        return ChunkResult(chunk.index, status, message, out, {"criticality": crit})

    def _evaluate(self, pts: dict[str, np.ndarray], n: int) -> ChunkResult:
        """The coefficients at ``n`` points whose parameters are all in their domains."""
        d = _derivation(self.spec, self.terms)
        fixed = dict(self.fixed)
        V = pts.pop("V") if "V" in pts else np.full(n, float(fixed.pop("V", self.model_object.defaults["V"])))
        fixed.pop("V", None)
        params = {**fixed, **pts}
        if "g" in params and "sigma" not in params:   # the load follows g, as SpringBlock.resolve has it
            from landau.systems.system import M_DEFAULT, default_normal_load

            params["sigma"] = default_normal_load(params.get("M", M_DEFAULT), params["g"])
        # vectorised over V and the parameters alike (for a law with several states too); a point
        # outside the law's or the terms' domain raises, and the engine splits the chunk down to it
        r = d.evaluate(V, params, HOPF_NAMES, method=self.method)
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
        return ChunkResult(np.arange(n), list(status), message, out, {"criticality": list(crit)})


#: the variables of the spring–block's vectorised hopf task
_HOPF_OUTPUTS = ("p_c", "k_c", "kc", "omega_c", "dRe_lambda_dp", "dIm_lambda_dp", "Gamma_bar", "Omega_bar", "Lambda",
                 "chi", "C")


def _term_names() -> tuple[str, ...]:
    from landau.systems.springblock_terms import TERMS

    return tuple(TERMS)


@dataclass(frozen=True)
class PointwiseHopf(Task):
    """The Hopf point of any registered model, point by point: the model's
    :attr:`~landau.models.Model.hopf` at each point's parameters (a point outside a parameter's
    domain is ``failed`` with the domain error; one without a Hopf point ``no-hopf``)."""

    lead: ClassVar[bool] = True

    def check_grid(self, grid: Grid) -> None:
        model = self.model_object
        unknown = sorted(set(dict(self.options)) - {o.name for o in model.options} - {"chunk_size", "method"})
        if unknown:
            raise InputError(f"hopf {self.model}: option(s) {', '.join(unknown)} do not apply (the model takes: "
                             f"{', '.join(o.name for o in model.options) or 'none'})")
        check_declared(self, grid, refuse_hopf_parameter=True)

    def run(self, chunk: Chunk) -> ChunkResult:
        model = self.model_object
        assert model.hopf is not None   # make_task gives this task only to models with a Hopf analysis
        bad, why = self.invalid(chunk)
        status: list[str] = []
        message: list[str] = []
        rows: list[dict[str, float]] = []
        crit: list[str] = []
        for j in range(len(chunk.index)):
            if bad[j]:
                _skip(status, message, rows, "failed", InputError(why[j]))
                crit.append("")
                continue
            try:
                res = model.hopf(self.setup(self.point(chunk, j)))
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
            # the result's numbers, less the point's own parameters (the sweep's coordinates)
            rows.append({k: float(v) for k, v in doc.items()
                         if isinstance(v, (int, float)) and not isinstance(v, bool) and k not in chunk.points})
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
        check_declared(self, grid, task_axes=("eps2",))
        if "eps2" in dict(self.options):   # one value for every point: refused up front, as `landau verify` does
            from landau.analyses.checking import _eps2_request

            _eps2_request(dict(self.options)["eps2"])

    def invalid(self, chunk: Chunk) -> tuple[np.ndarray, list[str]]:
        eps2 = chunk.points.get("eps2")
        others = Chunk(chunk.number, chunk.index, {k: v for k, v in chunk.points.items() if k != "eps2"})
        fixed = tuple((k, v) for k, v in self.fixed if k != "eps2")
        from dataclasses import replace

        bad, why = Task.invalid(replace(self, fixed=fixed), others)
        if eps2 is not None:
            # the domain landau.check accepts, with its message: 0 < eps2 < 0.5
            for j in np.flatnonzero(~((np.asarray(eps2) > 0) & (np.asarray(eps2) < 0.5)) & ~bad):
                why[j] = f"check: eps2 = |k - k_c|/k_c must be in (0, 0.5), got {float(eps2[j])!r}"
                bad[j] = True
        return bad, why

    def run(self, chunk: Chunk) -> ChunkResult:
        from landau.analyses.checking import check

        opts = dict(self.options)
        status: list[str] = []
        message: list[str] = []
        rows: list[dict[str, float]] = []
        strs: dict[str, list[str]] = {"verdict": [], "criticality_predicted": []}
        bad, why = self.invalid(chunk)
        for j in range(len(chunk.index)):
            point = self.point(chunk, j)
            V = point.pop("V", self.model_object.defaults["V"])
            eps2 = point.pop("eps2", opts.get("eps2", 1e-3))
            if bad[j]:
                _skip(status, message, rows, "failed", InputError(why[j]))
                strs["verdict"].append("")
                strs["criticality_predicted"].append("")
                continue
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
        # a swept eps2 is a coordinate of the dataset, not also a variable
        names = [n for n in (*CHECK_FLOATS, "bistable", "cycle_stable") if n not in chunk.points]
        vals = {k: np.array([r.get(k, np.nan) for r in rows]) for k in names}
        return ChunkResult(chunk.index, status, message, vals, strs)


# ---------------------------------------------------------------------------------------------
# cycles
# ---------------------------------------------------------------------------------------------
#: the numbers of the ``cycles`` task: the Hopf point, and where the branch first folds and first doubles
CYCLES_FLOATS = ("p_c", "lpc_p", "lpc_period", "lpc_amplitude", "pd_p", "pd_period", "pd_amplitude",
                 "p_end", "points")


@dataclass(frozen=True)
class CyclesTask(Task):
    """The branch of cycles from the Hopf point at each point (options ``steps``, ``ds``), with its first
    LPC and first PD: status ``ok`` with NaN where the branch has none, ``no-hopf`` without a Hopf
    point, ``failed`` with the first line of the error (a continuation that fails)."""

    lead: ClassVar[bool] = True

    def check_grid(self, grid: Grid) -> None:
        model = self.model_object
        known = {o.name for o in model.options} | {"chunk_size", "steps", "ds"}
        unknown = sorted(set(dict(self.options)) - known)
        if unknown:
            raise InputError(f"cycles {self.model}: option(s) {', '.join(unknown)} do not apply (the task takes "
                             f"steps, ds and the model's options)")
        check_declared(self, grid, refuse_hopf_parameter=True)

    def run(self, chunk: Chunk) -> ChunkResult:
        from landau.analyses.cycles import branch_table, follow

        model = self.model_object
        assert model.cycles is not None   # make_task gives this task only to models that declare cycles
        opts = dict(self.options)
        steps, ds = int(opts.get("steps", 60)), opts.get("ds")
        own = {k: v for k, v in opts.items() if k not in ("chunk_size", "steps", "ds")}
        bad, why = self.invalid(chunk)
        status: list[str] = []
        message: list[str] = []
        rows: list[dict[str, float]] = []
        for j in range(len(chunk.index)):
            if bad[j]:
                _skip(status, message, rows, "failed", InputError(why[j]))
                continue
            setup = Setup(self.setup().law, self.point(chunk, j), own)
            try:
                problem = model.cycles(setup)
                table = branch_table(follow(problem, steps=steps, ds=None if ds is None else float(ds)), problem)
            except NoHopfError as exc:
                _skip(status, message, rows, "no-hopf", exc)
                continue
            except (LandauError, ArithmeticError, ValueError, np.linalg.LinAlgError) as exc:
                _skip(status, message, rows, "failed", exc)
                continue
            row = {"p_c": problem.hopf.p_c if problem.hopf else np.nan, "p_end": float(table.p[-1]),
                   "points": float(table.p.size)}
            for kind in ("LPC", "PD"):
                sp = table.first(kind)
                for name in ("p", "period", "amplitude"):
                    row[f"{kind.lower()}_{name}"] = np.nan if sp is None else float(getattr(sp, name))
            rows.append(row)
            status.append("ok")
            message.append("")
        vals = {k: np.array([r.get(k, np.nan) for r in rows]) for k in CYCLES_FLOATS}
        return ChunkResult(chunk.index, status, message, vals, {})


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
        from landau import __version__

        sc = self._scene()
        return {"task": self.name, "model": self.model, "law": "", "law_declaration": "", "convention": "",
                "convention_description": "", "landau_version": __version__,
                "fixed_parameters": json.dumps(dict(self.fixed), sort_keys=True),
                "task_options": json.dumps(dict(self.options), sort_keys=True),
                "scene_parameter": sc.parameter, "source": sc.source}

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
    """A task whose chunk function lives beside the model (a model's :attr:`~landau.models.Model.tasks`
    factory builds it): ``chunk_fn(task, chunk) -> ChunkResult``, ``grid_fn(task, grid)`` checks a grid
    beyond the declared names, ``prepare_fn(task)`` compiles before the workers start.  The functions
    are module-level, so that the task pickles by reference to the workers."""

    along: str | None = None
    overlap: int = 0
    descending: bool = False
    chunk_fn: Callable[["ModelTask", Chunk], ChunkResult] | None = None
    grid_fn: Callable[["ModelTask", Grid], None] | None = None
    prepare_fn: Callable[["ModelTask"], None] | None = None
    extra_units: tuple[tuple[str, str], ...] = field(default=())
    #: names a grid may hold besides the model's declared parameters (a task's own axes)
    extra_names: tuple[str, ...] = ()

    def units(self) -> dict[str, str]:
        return {**super().units(), **dict(self.extra_units)}

    def check_grid(self, grid: Grid) -> None:
        check_declared(self, grid, task_axes=tuple(self.extra_names))
        if self.grid_fn is not None:
            self.grid_fn(self, grid)

    def chunks(self, grid: Grid) -> Sequence[Chunk]:
        return chunks(grid, self.chunk_size, self.along, self.overlap, self.descending)

    def prepare(self) -> None:
        if self.prepare_fn is not None:
            self.prepare_fn(self)

    def run(self, chunk: Chunk) -> ChunkResult:
        assert self.chunk_fn is not None   # every factory sets it
        return self.chunk_fn(self, chunk)


#: tasks and what each computes
TASKS = {"hopf": "the Hopf point and amplitude-equation coefficients (any model with a Hopf analysis)",
         "check": "the direct-simulation verdict of landau.check (spring-block)",
         "simulate": "statistics of a settled run (forced-oscillator: continuation in omega)",
         "regime": "the regime by direct simulation started on both sides (spring-block)",
         "scene": "a published value as a function of parameters (MODEL: a scene of landau scene list)",
         "cycles": "the first fold of cycles (LPC) and period doubling (PD) on the branch from the Hopf point "
                   "(any model declaring cycles)"}


def make_task(task: str, model: str, law: LawSpec | None, fixed: dict[str, Any], options: dict[str, Any]) -> Task:
    """The :class:`Task` for ``task`` on ``model`` (a registered model, or a scene's name for ``scene``).

    Raises
    ------
    InputError
        An unknown task or model, a model that does not run the task, a law the model does not take.
    """
    if task not in TASKS:
        raise InputError(f"unknown sweep task {task!r} (tasks: {', '.join(TASKS)})")
    fx = tuple(sorted((k, float(v)) for k, v in fixed.items()))
    opts = tuple(sorted(options.items()))
    if task == "scene":
        if law is not None:
            raise InputError(f"scene {model}: a scene takes no law (its model and law are the paper's)")
        return SceneTask("scene", model, None, fx, opts, chunk_size=int(options.get("chunk_size", 1)))
    m = get_model(model)
    if not m.offers(task):
        from landau.models import offering

        raise InputError(f"{task}: the model {model!r} does not run this task (models that do: "
                         f"{', '.join(offering(task)) or 'none'})")
    if m.law_kind is LawKind.RATE_AND_STATE:
        if law is None:
            raise InputError(f"{task} {model}: name a law (built-in or --mu/--state)")
    elif law is not None:
        raise InputError(f"{task} {model}: this model takes no rate-and-state law")
    if task in m.tasks:
        return m.tasks[task](task, model, law, fx, opts)
    if task == "cycles":
        return CyclesTask("cycles", model, law, fx, opts, chunk_size=int(options.get("chunk_size", 1)))
    return PointwiseHopf("hopf", model, law, fx, opts, chunk_size=int(options.get("chunk_size", 1)))
