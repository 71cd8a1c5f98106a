"""Compiled mode fields of eq. (1) of Lancioni, Lenci & Galvanetto (the frictional impact oscillator).

The four regimes of :mod:`landau.verify.lancioni.model` (free flight, slip±, stick) have the
smooth fields ẏ = (φ̇, ẏ, q̈) with

    q̈ = a₀ + M⁻¹w_N λ_N + M⁻¹w_T λ_T,

a₀ = −M⁻¹h the free acceleration and (λ_N, λ_T) the contact forces of the regime: 0 in flight,
G λ = −b in stick, λ_N = −b_N / (G_NN − s μ_s G_NT), λ_T = −s μ_s λ_N in slip s, where
μ_s = s F(s·max(s g_T, 0)) is the friction law F at the current relative velocity g_T = lφ̇ cos φ
− v(t) (G, b as in :meth:`landau.verify.lancioni.model.Lancioni.terms`).  They are written here
once, symbolically, with every number (masses, stiffnesses, belt, the law's parameters) a kernel
parameter, and printed and compiled by :func:`landau.codegen.kernels.generate_kernel`: one
compiled source per (regime, friction law branch, belt kind), cached on disk, so a user's own
law (``--friction 'mu*(1 + alpha*exp(-v/v0))'``) is compiled once per machine like the paper's
Coulomb friction.

The belt is :class:`~landau.verify.lancioni.model.ConstantBelt` (v) or
:class:`~landau.verify.lancioni.model.SineBelt` (A sin Ωt); another belt object has no kernel
(the engine then integrates the Python field).
"""

from __future__ import annotations

import functools
from dataclasses import replace

import numpy as np

__all__ = ["mode_kernel_factory", "guard_kernel_factory", "belt_kind", "slip_kernel"]


def belt_kind(belt) -> tuple[str, tuple[float, ...]] | None:
    """("constant", (v,)) or ("sine", (A, Ω)) for the model's belts, None for any other object."""
    from landau.verify.lancioni.model import ConstantBelt, SineBelt

    if type(belt) is ConstantBelt:
        return "constant", (float(belt.v),)
    if type(belt) is SineBelt:
        return "sine", (float(belt.A), float(belt.Omega))
    return None


def mode_kernel_factory(mech, mode: str):
    """A function of no arguments building (once, on first call) the compiled field of ``mode``
    (``"flight"``, ``"slip+"``, ``"slip-"`` or ``"stick"``) for the mechanics ``mech``
    (a :class:`~landau.verify.lancioni.model.Lancioni`), or None when its belt has no kernel.

    Parameters
    ----------
    mech : Lancioni
        The mechanics: parameters, friction law and belt.
    mode : str
        The regime.

    Returns
    -------
    callable or None
        ``build() -> Kernel`` with the parameter vector of ``mech``.
    """
    kind = belt_kind(mech.belt)
    if kind is None:
        return None
    law = mech.friction
    s = {"slip+": 1, "slip-": -1}.get(mode, 0)
    branch = law.branch(s) if s else None
    symbols = tuple(p.symbol for p in law.parameters) if s else ()
    values = np.array([*mech._c, *kind[1], *(mech._law_values if s else ())], dtype=float)

    @functools.lru_cache(maxsize=None)
    def build():
        return replace(_mode_kernel(mode, kind[0], branch, symbols), p=values)

    return build


def _mechanics(mode: str, belt: str, branch):
    """The symbolic pieces of eq. (1) in ``mode``: the state, time and parameter symbols and the
    contact quantities (g_T, the friction level μ of a slip mode, G, the forces λ_N, λ_T and
    q̈), shared by the field and the guards."""
    import sympy as sp

    from landau.laws.velocity import V_SLIP

    # names no law parameter can take (a law's names never start with "_")
    phi, y, w, yd, t = sp.symbols("_phi _y _w _yd _t", real=True)
    m1, m2, l, ky, kp, cy, cp, p0, y0, g = sp.symbols("_m1 _m2 _l _ky _kphi _cy _cphi _phi0 _y0 _g", real=True)
    if belt == "constant":
        bp = (sp.Symbol("_vb", real=True),)
        v, vdot = bp[0], sp.Integer(0)
    else:
        bp = sp.symbols("_A _Omega", real=True)
        v, vdot = bp[0] * sp.sin(bp[1] * t), bp[0] * bp[1] * sp.cos(bp[1] * t)
    sn, cs = sp.sin(phi), sp.cos(phi)
    det = m1 * l * l * (m2 + m1 * cs * cs)
    i11, i12, i22 = (m1 + m2) / det, -m1 * l * sn / det, m1 * l * l / det
    f1 = -(cp * w + kp * (phi - p0) + m1 * g * l * sn)
    f2 = -(cy * yd + ky * (y - y0) + m1 * l * w * w * cs + (m1 + m2) * g)
    a0 = (i11 * f1 + i12 * f2, i12 * f1 + i22 * f2)
    nN1, nT1 = l * sn, l * cs
    MiN = (i11 * nN1 + i12, i12 * nN1 + i22)
    MiT = (i11 * nT1, i12 * nT1)
    gT = l * cs * w - v
    out = dict(state=[phi, y, w, yd], t=t, base=[m1, m2, l, ky, kp, cy, cp, p0, y0, g, *bp], gT=gT,
               gap=y - l * cs)
    if mode == "flight":
        lamN = lamT = sp.Integer(0)
    else:
        GNN = nN1 * MiN[0] + MiN[1]
        GNT = nN1 * MiT[0] + MiT[1]
        GTT = nT1 * MiT[0]
        bN = nN1 * a0[0] + a0[1] + l * cs * w * w
        bT = nT1 * a0[0] - l * sn * w * w - vdot
        out.update(GNN=GNN, GNT=GNT)
        if mode == "stick":
            d2 = GNN * GTT - GNT * GNT
            lamN = -(GTT * bN - GNT * bT) / d2
            lamT = -(-GNT * bN + GNN * bT) / d2
        else:
            s = 1 if mode == "slip+" else -1
            # |F(g_T)| on the slip side (a g_T a rounding error on the wrong side of 0 is taken as 0)
            mu = s * branch.subs(V_SLIP, s * sp.Max(s * gT, 0))
            lamN = -bN / (GNN - s * mu * GNT)
            lamT = -s * mu * lamN
            out["mu"] = mu
    out.update(lamN=lamN, lamT=lamT, acc=[a0[k] + MiN[k] * lamN + MiT[k] * lamT for k in range(2)])
    return out


@functools.lru_cache(maxsize=64)
def _mode_kernel(mode: str, belt: str, branch, law_symbols: tuple):
    """The generated kernel of ``mode``; parameters p = (m₁, m₂, l, k_y, k_φ, c_y, c_φ, φ₀, y₀, g,
    belt (v) or (A, Ω), the law's parameters) (its ``p`` holds placeholders)."""
    from landau.codegen.kernels import generate_kernel

    M = _mechanics(mode, belt, branch)
    phi, y, w, yd = M["state"]
    params = [*M["base"], *law_symbols]
    return generate_kernel([phi, y, w, yd], [w, yd, *M["acc"]], params, [1.0] * len(params),
                           time=M["t"] if belt == "sine" else None, jacobian=False, name=f"lancioni-{mode}-{belt}")


def guard_kernel_factory(mech, mode: str, sections=()):
    """A function of no arguments building (once, on first call) the guards of ``mode`` as one
    compiled vector function (:attr:`landau.verify.hybrid.model.Mode.guard_kernel`), in the order
    of :class:`~landau.verify.hybrid.contact.ContactModel`: flight g_N = y − l cos φ (``impact``);
    slip s λ_N (``lift-off``), s·g_T (``stop``), D_s = G_NN − sμ(g_T)G_NT (``painleve``); stick
    λ_N, μ₊λ_N + λ_T and μ₋λ_N − λ_T (``slip± onset``); then each section's ``symbolic`` form at
    the mode's q̈.  None when the belt has no kernel or a section has no symbolic form.

    Parameters
    ----------
    mech : Lancioni
        The mechanics: parameters, friction law and belt.
    mode : str
        The regime.
    sections : tuple of Section
        The model's sections (:class:`~landau.verify.hybrid.contact.Section`).

    Returns
    -------
    callable or None
        ``build() -> Kernel`` with the parameter vector of ``mech``.
    """
    kind = belt_kind(mech.belt)
    if kind is None or any(getattr(sec, "symbolic", None) is None for sec in sections):
        return None
    law = mech.friction
    s = {"slip+": 1, "slip-": -1}.get(mode, 0)
    branch = law.branch(s) if s else None
    symbols = tuple(p.symbol for p in law.parameters) if s else ()
    values = np.array([*mech._c, *kind[1], *(mech._law_values if s else ()), *mech._static], dtype=float)
    sections = tuple(sections)

    @functools.lru_cache(maxsize=None)
    def build():
        k = _guard_kernel(mode, kind[0], branch, symbols, sections)
        return None if k is None else replace(k, p=values)

    return build


@functools.lru_cache(maxsize=64)
def _guard_kernel(mode: str, belt: str, branch, law_symbols: tuple, sections: tuple):
    """The generated guard vector of ``mode`` (parameters as :func:`_mode_kernel`'s, then the
    static friction levels μ₊, μ₋), or None when a section's symbolic form is not a sympy
    expression."""
    import sympy as sp

    from landau.codegen.kernels import generate_vector_function

    M = _mechanics(mode, belt, branch)
    mup, mum = sp.symbols("_mup _mum", real=True)
    if mode == "flight":
        gs = [M["gap"]]
    elif mode == "stick":
        gs = [M["lamN"], mup * M["lamN"] + M["lamT"], mum * M["lamN"] - M["lamT"]]
    else:
        s = 1 if mode == "slip+" else -1
        gs = [M["lamN"], s * M["gT"], M["GNN"] - s * M["mu"] * M["GNT"]]
    for sec in sections:
        try:
            e = sp.sympify(sec.symbolic(M["t"], list(M["state"]), list(M["acc"])), strict=True)
        except Exception:  # a section that is not symbolic after all: its guards stay in Python
            return None
        if not isinstance(e, sp.Expr) or e.free_symbols - {M["t"], *M["state"], *M["base"], *law_symbols}:
            return None
        gs.append(e)
    params = [*M["base"], *law_symbols, mup, mum]
    return generate_vector_function(M["state"], gs, params, [1.0] * len(params), time=M["t"],
                                    name=f"lancioni-{mode}-{belt}-guards")


def slip_kernel(s: int, friction, values):
    """The smooth slip mode of :mod:`landau.verify.lancioni.slip` (state (φ, φ̇), the constraint
    g_N = 0 eliminated: φ̈ = F_s(φ, φ̇)) as a compiled kernel with the parameter values ``values``
    (in the order of :func:`landau.verify.lancioni.slip.slip_functions` ``names``).

    Parameters
    ----------
    s : {+1, -1}
        Slip sign.
    friction : VelocityFriction or None
        Friction-coefficient law (None: Coulomb).
    values : sequence of float
        Mechanical parameters, belt velocity and the law's parameters.

    Returns
    -------
    Kernel
    """
    from landau.verify.lancioni import slip as S

    law = S._law(friction)
    k = _slip_kernel(int(s), S.friction_branch(s, friction), tuple(p.name for p in law.parameters))
    return replace(k, p=np.asarray(values, dtype=float))


@functools.lru_cache(maxsize=16)
def _slip_kernel(s: int, Fs, law_names: tuple):
    from landau.codegen.kernels import generate_kernel
    from landau.verify.lancioni import slip as S

    F, _ = S._accelerations(s, Fs)
    params = [*S.MECHANICAL.values(), S.v_belt, *map(S._law_symbol, law_names)]
    return generate_kernel([S.phi, S.omega], [S.omega, F], params, [1.0] * len(params), jacobian=False,
                           name=f"lancioni-slip{'+' if s > 0 else '-'}")
