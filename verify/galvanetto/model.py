"""One- and two-block stick–slip models of Galvanetto (2004) on the hybrid engine.

Dimensionless equations (paper eqs 2–8; eq. 7 read as below, which reproduces the two-block results):

* one block: Ẍ + cẊ + X = F_k(Ẋ − V) while slipping (4a); sticking (Ẋ = V) allowed while
  −F_s − cV ≤ X ≤ F_s − cV, F_s = 1 (3a);
* two blocks: Ẍᵢ = −Kᵢ + F_si F_k(Ẋᵢ − V), Kᵢ = Xᵢ + α(Xᵢ − Xⱼ) (4b, 8b); sticking allowed
  while −F_si ≤ Kᵢ ≤ F_si, F_s1 = 1, F_s2 = β (3b).

Written uniformly: Kᵢ = Xᵢ + α(Xᵢ − Xⱼ) + cẊᵢ (the one block has no α term), the slip
acceleration is −Kᵢ + F_si F_k(rᵢ), rᵢ = Ẋᵢ − V.  State y = (X₁..Xₙ, Ẋ₁..Ẋₙ).

Modes are strings with one letter per block: ``n`` slipping with rᵢ < 0, ``s`` sticking,
``p`` slipping with rᵢ > 0 (e.g. ``"ns"``: block 1 slower than the belt, block 2 stuck).
Filippov convention at rᵢ = 0: stick if |Kᵢ| ≤ F_si, otherwise cross to the other slip
side; a stuck block leaves when Kᵢ reaches ±F_si (to ``n`` at +F_si, to ``p`` at −F_si).

Optional sections (``sections=True``) log, without switching, the extrema that the
sliding-bifurcation locators need: ``rmax{i}`` (a maximum of rᵢ while slipping with
rᵢ < 0: grazing of the stick surface), ``rmin{i}`` (a minimum while rᵢ > 0), ``rzero{i}``
(a slip branch made transparent at rᵢ = 0 crosses it) and
``Kmin{i}``/``Kmax{i}`` (extrema of Kᵢ while block i sticks: multi-sliding).
"""

from __future__ import annotations

import functools
import itertools
from dataclasses import dataclass, replace

import numpy as np

from landau.errors import InputError
from landau.laws.kinetic import KineticFriction, resolve_kinetic_law
from landau.verify.hybrid import Guard, HybridModel, Jump, Mode


@dataclass(frozen=True, init=False)
class StickSlipParams:
    """Parameters of the one-block (n=1) or two-block (n=2) model; paper's symbols.

    The kinetic friction is the law object ``law`` (:class:`landau.laws.kinetic.KineticFriction`,
    default Galvanetto's eq. (7) with γ = 3, δ = 0); ``gamma``/``delta`` are its parameters
    (given to the constructor they set those of the default law, or of ``law`` when they agree
    with it).
    """

    V: float
    c: float
    alpha: float
    beta: float
    n: int
    law: KineticFriction

    def __init__(self, V: float = 0.25, gamma: float | None = None, delta: float | None = None, c: float = 0.0,
                 alpha: float = 1.2, beta: float = 1.3, n: int = 1, law: KineticFriction | None = None):
        law = resolve_kinetic_law(law, gamma, delta)
        values = {k: _number(k, x) for k, x in (("V", V), ("c", c), ("alpha", alpha), ("beta", beta))}
        if n not in (1, 2):
            raise InputError(f"the Galvanetto models have one or two blocks, got n = {n!r}")
        for k, v in (*values.items(), ("n", int(n)), ("law", law)):
            object.__setattr__(self, k, v)
        self._check()

    def _check(self) -> None:
        """Domain of the paper's parameters: V > 0 (the belt moves), c >= 0 (damping dissipates),
        alpha >= 0 (a spring between the blocks) and beta > 0 (block 2's static level)."""
        for k, ok, what in (("V", self.V > 0, "> 0 (the belt velocity)"),
                            ("c", self.c >= 0, ">= 0 (viscous damping)"),
                            ("alpha", self.alpha >= 0, ">= 0 (the stiffness between the blocks)"),
                            ("beta", self.beta > 0, "> 0 (block 2's static friction level)")):
            if not ok:
                raise InputError(f"Galvanetto model: {k} must be {what}, got {getattr(self, k)!r}")

    @property
    def gamma(self) -> float:
        """γ of the kinetic law."""
        return self.law.gamma

    @property
    def delta(self) -> float:
        """δ of the kinetic law."""
        return self.law.delta

    @property
    def Fs(self) -> tuple[float, ...]:
        return (1.0,) if self.n == 1 else (1.0, self.beta)

    def with_(self, **kw) -> "StickSlipParams":
        """A copy with some parameters changed; ``gamma``/``delta`` change the kinetic law's values."""
        own = {prm.name for prm in self.law.parameters}
        lawkw = {k: float(kw.pop(k)) for k in list(kw) if k in own}
        p = replace(self, **kw)
        return replace(p, law=p.law.with_defaults(**lawkw)) if lawkw else p


def _number(name: str, x) -> float:
    """``x`` as a finite float, else an InputError naming the parameter."""
    import math

    try:
        v = float(x)
    except (TypeError, ValueError):
        raise InputError(f"Galvanetto model: {name} must be a number, got {x!r}") from None
    if not math.isfinite(v):
        raise InputError(f"Galvanetto model: {name} must be finite, got {x!r}")
    return v


def one_block(V: float, gamma: float | None = None, delta: float | None = None, c: float = 0.0, *,
              law: KineticFriction | None = None) -> StickSlipParams:
    """Parameters of the one-block model (dimensionless, the paper's symbols).

    Parameters
    ----------
    V : float
        Belt velocity.
    gamma : float, optional
        Velocity weakening γ of the kinetic friction (default 3, the paper's examples).
    delta : float, optional
        Residual kinetic friction level δ in [0, 1] (default 0).
    c : float, optional
        Viscous damping.
    law : KineticFriction, optional
        The kinetic friction law (default eq. (7) with ``gamma``, ``delta``); e.g.
        ``KineticFriction.from_expression("(1 - delta)*exp(gamma*r) + delta")``.
    """
    return StickSlipParams(V=V, gamma=gamma, delta=delta, c=c, n=1, law=law)


def two_blocks(V: float, alpha: float = 1.2, beta: float = 1.3, gamma: float | None = None,
               delta: float | None = None, *, law: KineticFriction | None = None) -> StickSlipParams:
    """Parameters of the two-block model (dimensionless, the paper's symbols).

    Parameters
    ----------
    V : float
        Belt velocity.
    alpha : float, optional
        Stiffness α of the spring between the blocks.
    beta : float, optional
        Static friction level β of block 2 (block 1's is 1).
    gamma : float, optional
        Velocity weakening γ of the kinetic friction (default 3).
    delta : float, optional
        Residual kinetic friction level δ in [0, 1] (default 0).
    law : KineticFriction, optional
        The kinetic friction law (default eq. (7) with ``gamma``, ``delta``).
    """
    return StickSlipParams(V=V, gamma=gamma, delta=delta, alpha=alpha, beta=beta, n=2, law=law)


def _parameters_doc_tail(equations: str) -> str:
    """The Returns and References sections shared by :func:`one_block` and :func:`two_blocks`."""
    return f"""
    Returns
    -------
    StickSlipParams
        Input of :func:`build_model`.

    References
    ----------
    Galvanetto, U. (2004), "Sliding bifurcations in the dynamics of mechanical systems with dry
    friction — remarks for engineers and applied scientists", J. Sound Vib. 276, 121–139, eqs {equations}.
    """


one_block.__doc__ = (one_block.__doc__ or "") + _parameters_doc_tail("(3a), (4a), (7)")
two_blocks.__doc__ = (two_blocks.__doc__ or "") + _parameters_doc_tail("(3b), (4b), (7), (8b)")


#: relative width of the band outside ±F_s where a landing block whose spring force moves into
#: its sticking interval sticks at once (see :func:`build_model`)
CORNER_TOL = 1e-6


def K_of(p: StickSlipParams, y):
    """Spring(+damper) force Kᵢ on each block; works on y of shape (2n,) or (2n, m)."""
    return tuple(_K_fun(p, i)(y) for i in range(p.n))


def _K_fun(p: StickSlipParams, i: int):
    """y -> Kᵢ alone (a guard of one block needs only its own force)."""
    c = p.c
    if p.n == 1:
        return lambda y: y[0] + c * y[1]
    a, j = p.alpha, 1 - i
    return lambda y: y[i] + a * (y[i] - y[j]) + c * y[2 + i]


def _make_rhs(p: StickSlipParams, code: str):
    V, n, Fs, law = p.V, p.n, p.Fs, p.law
    fneg, fpos = law.neg, law.pos   # the branches of eq. (7), generated from the law's symbolic form
    if n == 1:
        c = p.c
        if code == "s":
            return lambda t, y: np.array([V, 0.0])
        if code == "n":
            return lambda t, y: np.array([y[1], -(y[0] + c * y[1]) + fneg(y[1] - V)])
        return lambda t, y: np.array([y[1], -(y[0] + c * y[1]) + fpos(y[1] - V)])
    a, c = p.alpha, p.c
    F1, F2 = Fs

    def fr(ch, r, F):
        return F * (fneg(r) if ch == "n" else fpos(r))

    c1, c2 = code[0], code[1]

    def rhs(t, y):
        x1, x2, v1, v2 = y
        a1 = 0.0 if c1 == "s" else -(x1 + a * (x1 - x2) + c * v1) + fr(c1, v1 - V, F1)
        a2 = 0.0 if c2 == "s" else -(x2 + a * (x2 - x1) + c * v2) + fr(c2, v2 - V, F2)
        return np.array([v1, v2, a1, a2])

    return rhs


def _K_weights(p: StickSlipParams, i: int) -> np.ndarray:
    """w with Kᵢ = w·y (:func:`K_of` as a linear form)."""
    n = p.n
    w = np.zeros(2 * n)
    w[i] += 1.0
    if n == 2:
        w[i] += p.alpha
        w[1 - i] -= p.alpha
    w[n + i] += p.c
    return w


def _affine(w, b: float) -> tuple[tuple[float, ...], float]:
    return tuple(float(x) for x in w), float(b)


def _kernel_factory(p: StickSlipParams, code: str):
    """A function building (once, on first call) the compiled field of mode ``code``.

    The law's branches enter symbolically and every number as a kernel parameter, so one
    compiled source serves all parameter values of a law (:func:`_mode_kernel`).
    """

    @functools.lru_cache(maxsize=None)
    def build():
        Fs = p.Fs + (1.0,) * (2 - p.n)
        values = np.array([p.V, p.c, p.alpha, *Fs, p.law.gamma, p.law.delta])
        return replace(_mode_kernel(p.law.neg_expr, p.law.pos_expr, p.n, code), p=values)

    return build


@functools.lru_cache(maxsize=64)
def _mode_kernel(neg_expr, pos_expr, n: int, code: str):
    """The generated kernel of mode ``code`` for a law with these branches; parameters
    p = (V, c, α, F_s1, F_s2, γ, δ) (its ``p`` holds placeholders)."""
    import sympy as sp

    from landau.codegen.kernels import generate_kernel
    from landau.laws.kinetic import DELTA, GAMMA, R

    xs, vs = sp.symbols(f"x1:{n + 1}"), sp.symbols(f"v1:{n + 1}")
    V, c, a, F1, F2 = sp.symbols("V c alpha F1 F2")
    F = (F1, F2)
    K = [xs[0] + c * vs[0]] if n == 1 else [xs[i] + a * (xs[i] - xs[1 - i]) + c * vs[i] for i in range(2)]
    dx, dv = [], []
    for i, ch in enumerate(code):
        if ch == "s":
            dx.append(V if n == 1 else vs[i])
            dv.append(sp.Integer(0))
        else:
            dx.append(vs[i])
            dv.append(-K[i] + F[i] * (neg_expr if ch == "n" else pos_expr).subs(R, vs[i] - V))
    params = [V, c, a, F1, F2, GAMMA, DELTA]
    return generate_kernel([*xs, *vs], dx + dv, params, [1.0] * len(params), jacobian=False,
                           name=f"galvanetto{n}-{code}")


def _accel_fun(p: StickSlipParams, i: int, ch: str):
    """Slip acceleration of block i on branch ch, vectorised (for the r-extremum sections)."""
    n, V, Fs, law = p.n, p.V, p.Fs[i], p.law
    br = law.neg if ch == "n" else law.pos
    return lambda t, y: -K_of(p, y)[i] + Fs * br(y[n + i] - V)


def build_model(p: StickSlipParams, sections: bool = False, transparent: frozenset = frozenset()) -> HybridModel:
    """The hybrid model (all 3ⁿ modes) for parameters ``p``.

    ``transparent`` removes switching guards to continue a smooth field past its switching
    surface (a *virtual* orbit, used only to define smooth grazing functions): entries are
    ``"r{i}=0:n"`` / ``"r{i}=0:p"`` (block i does not stop slipping on that side) or
    ``"K{i}=+Fs"`` / ``"K{i}=-Fs"`` (a stuck block i does not leave on that side), or
    ``"stick{i}:n"``, ``"stick{i}:p"`` (block i sticks whenever rᵢ reaches 0 from that side,
    whatever Kᵢ).

    Parameters
    ----------
    p : StickSlipParams
        From :func:`one_block` or :func:`two_blocks`.
    sections : bool, optional
        Log the extrema the sliding-bifurcation locators need (see the module docstring).
    transparent : frozenset of str, optional
        Guards to remove (see above).

    Returns
    -------
    HybridModel
        For :func:`landau.verify.hybrid.simulate`.

    References
    ----------
    Galvanetto, U. (2004), "Sliding bifurcations in the dynamics of mechanical systems with dry
    friction — remarks for engineers and applied scientists", J. Sound Vib. 276, 121–139, eqs (2)–(8).
    """
    n, V, Fs = p.n, p.V, p.Fs
    modes = {}
    for code in map("".join, itertools.product("nsp", repeat=n)):
        guards = []
        for i, ch in enumerate(code):
            if ch in "np":
                sgn = -1.0 if ch == "n" else 1.0

                def r_guard(t, y, i=i, sgn=sgn):
                    return sgn * (y[n + i] - V)

                def land(t, y, i=i, code=code, ch=ch):
                    y = np.array(y, dtype=float)
                    y[n + i] = V  # exactly on the surface
                    K = K_of(p, y)[i]
                    # dKᵢ/dt with block i at the belt speed (its stick-phase rate)
                    kd = p.V if n == 1 else (1 + p.alpha) * y[n + i] - p.alpha * y[2 * n - 1 - i]
                    # a landing just outside the sticking interval (by < CORNER_TOL F_s, the accuracy
                    # of a located event near a sliding bifurcation) while Kᵢ moves into it: the
                    # slip on the other side would reverse at once (an O(ε²) excursion), so it sticks
                    corner = ((-Fs[i] * (1 + CORNER_TOL) <= K < -Fs[i] and kd > 0)
                              or (Fs[i] < K <= Fs[i] * (1 + CORNER_TOL) and kd < 0))
                    if -Fs[i] <= K <= Fs[i] or corner or f"stick{i + 1}:{ch}" in transparent:
                        new, note = "s", "slip→stick"
                    elif K < -Fs[i]:
                        new, note = "p", "slip→slip (crossing, r>0)"
                    else:
                        new, note = "n", "slip→slip (crossing, r<0)"
                    if new == ch:  # cannot stay on the side it is leaving: stick, let guards decide
                        new = "s"
                    return Jump(code[:i] + new + code[i + 1:], y, note)

                w = np.zeros(2 * n)
                w[n + i] = sgn
                r_affine = _affine(w, -sgn * V)
                if f"r{i + 1}=0:{ch}" not in transparent:
                    guards.append(Guard(f"r{i + 1}=0", r_guard, land, affine=r_affine))
                elif sections:   # the continued slip branch crosses r = 0: logged (``rzero{i}``)
                    guards.append(Guard(f"rzero{i + 1}", r_guard, affine=r_affine))
                if sections:
                    acc = _accel_fun(p, i, ch)
                    u = np.zeros(2 * n)   # the acceleration of block i is the field's component n + i
                    u[n + i] = 1.0 if ch == "n" else -1.0
                    acc_affine = (tuple(0.0 for _ in u), 0.0, tuple(float(x) for x in u))
                    if ch == "n":
                        guards.append(Guard(f"rmax{i + 1}", acc, affine=acc_affine))
                    else:
                        def minus_acc(t, y, acc=acc):
                            return -acc(t, y)
                        guards.append(Guard(f"rmin{i + 1}", minus_acc, affine=acc_affine))
            else:
                def up(t, y, K=_K_fun(p, i), F=Fs[i]):
                    return F - K(y)

                def lo(t, y, K=_K_fun(p, i), F=Fs[i]):
                    return K(y) + F

                def leave(side, i=i, code=code):
                    return lambda t, y: Jump(code[:i] + side + code[i + 1:], y, "stick→slip")

                def kdot(t, y, i=i):
                    # dKᵢ/dt while block i sticks (its acceleration is 0)
                    if n == 1:
                        return V
                    return (1 + p.alpha) * y[n + i] - p.alpha * y[n + 1 - i]

                wK = _K_weights(p, i)
                if f"K{i + 1}=+Fs" not in transparent:
                    def minus_kdot(t, y, k=kdot):
                        return -k(t, y)
                    guards.append(Guard(f"K{i + 1}=+Fs", up, leave("n"), rate=minus_kdot,
                                        affine=_affine(-wK, Fs[i])))
                if f"K{i + 1}=-Fs" not in transparent:
                    guards.append(Guard(f"K{i + 1}=-Fs", lo, leave("p"), rate=kdot, affine=_affine(wK, Fs[i])))
                if sections and n == 2:
                    j = 1 - i
                    a = p.alpha

                    def kdiff(t, y, i=i, j=j, a=a):  # dKᵢ/dt in the section's combination
                        return (1 + a) * y[n + i] - a * y[n + j]

                    def minus_kdiff(t, y, f=kdiff):
                        return -f(t, y)

                    wd = np.zeros(2 * n)
                    wd[n + i], wd[n + j] = 1 + a, -a
                    guards.append(Guard(f"Kmin{i + 1}", minus_kdiff, affine=_affine(-wd, 0.0)))
                    guards.append(Guard(f"Kmax{i + 1}", kdiff, affine=_affine(wd, 0.0)))
        modes[code] = Mode(code, _make_rhs(p, code), tuple(guards), kernel=_kernel_factory(p, code))
    return HybridModel(modes, name=f"galvanetto2004-{n}block")
