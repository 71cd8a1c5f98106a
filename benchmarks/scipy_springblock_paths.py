"""The scipy routes the quasi-dynamic cell and the load histories took before they were compiled,
for comparison in the ``springblock-paths`` section.

The same symbolic expressions as the toolkit's (the cell's lambdified residual and field, the
history's :func:`_momentum` and :func:`_force_balance` with the parameter values substituted),
lambdified for scipy: ``scipy.integrate.Radau`` stepped in Python for the cell (the slip rate
from the force balance by the safeguarded Newton iteration at every evaluation, and at every step
for the record), ``solve_ivp`` Radau one piece at a time for the histories (at M = 0 the same
Newton iteration inside f and the implicit-function Jacobian f_y − f_w R_y/R_w).  Each returns
the final state in the toolkit's variables: (ξ, ψ…) for the cell, (u, w, ψ…) for a history.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp


def cell_run(cell, y0, t_end: float, rtol: float) -> np.ndarray:
    """The cell from the scaled state ``y0`` over [0, ``t_end``] s: the final (ξ, ψ…)."""
    from scipy.integrate import Radau

    tu = cell.time_unit
    y = np.asarray(y0, float)
    last = [cell.slip_rate(y)]

    def f(_t, yy):
        out, last[0] = cell.rhs(yy, last[0])
        return out

    def jac(_t, yy):
        return cell.jacobian(yy, cell.slip_rate(yy, last[0]))

    solver = Radau(f, 0.0, y, t_end / tu, rtol=rtol, atol=rtol, jac=jac)
    ys, ws = [y.copy()], [last[0]]
    while solver.status == "running":
        msg = solver.step()
        if solver.status == "failed":
            raise RuntimeError(msg)
        ws.append(cell.slip_rate(solver.y, ws[-1]))
        ys.append(solver.y.copy())
    return np.asarray(ys[-1])


def history_run(law, history: str, k: float, params, t_end: float, rtol: float) -> np.ndarray:
    """A load-point history by scipy, piece by piece: the final (u, w, ψ…)."""
    from scipy.integrate import solve_ivp

    from landau.systems.system import SpringBlock
    from landau.verify.springblock.forcebalance import solve_log_rate
    from landau.verify.springblock.history import _force_balance, _momentum, _steady_state, parse_history

    h = parse_history(history)
    block = SpringBlock.for_params(law, params)
    p = block.resolve(params)
    terms = block.terms
    phi0, mu0 = _steady_state(law, h.velocities[0], p)
    eta = float(p.get("eta", 0.0)) if "eta" in terms else 0.0
    gam = float(p.get("gamma_ld", 0.0)) if "gamma_ld" in terms else 0.0
    F0 = (float(p["sigma"]) * mu0 + eta * h.velocities[0]) / (1.0 - gam * mu0)
    y = np.array([F0 / k, math.log(h.velocities[0]), *(math.log(x) for x in phi0)])
    scale = np.array([p.get("L", 1e-6)] + [1.0] * (len(y) - 1))
    T = list(h.times)
    ends = T[1:] + [t_end]
    if p["M"] == 0:
        return _pieces_m0(law, p, k, terms, h, y, T, ends, t_end, rtol, scale, _force_balance, solve_log_rate)
    ys, f, Vlp = _momentum(law, p, k, terms)
    fn = sp.lambdify([ys, Vlp], f, "numpy")
    jn = sp.lambdify([ys, Vlp], sp.Matrix(f).jacobian(sp.Matrix(ys)), "numpy")
    for V, a, b in zip(h.velocities, T, ends, strict=True):
        if a >= t_end:
            break
        sol = solve_ivp(lambda t, yy, V=V: fn(yy, V), (a, min(b, t_end)), y, method="Radau", rtol=rtol,
                        atol=rtol * scale, jac=lambda t, yy, V=V: np.asarray(jn(yy, V), float))
        if not sol.success:
            raise RuntimeError(sol.message)
        y = sol.y[:, -1]
    return y


def _pieces_m0(law, p, k, terms, h, y, T, ends, t_end, rtol, scale, force_balance, solve_log_rate):
    from scipy.integrate import solve_ivp

    w, ys, R, f, Vlp = force_balance(law, p, k, terms)
    res = sp.lambdify([w, *ys], (R, sp.diff(R, w), [sp.diff(R, q) for q in ys]), "math")
    fld = sp.lambdify([w, *ys, Vlp], (f, [sp.diff(e, w) for e in f], [[sp.diff(e, q) for q in ys] for e in f]),
                      "math")
    centre = float(y[1])
    last = [centre]

    def rate(yy):
        last[0] = solve_log_rate(res, yy, last[0], centre)
        return last[0]

    def fun(_t, yy, V):
        return np.asarray(fld(rate(yy), *yy, V)[0], float)

    def jac(_t, yy, V):
        wv = rate(yy)
        _, Rw, Ry = res(wv, *yy)
        _, fw, fy = fld(wv, *yy, V)
        return np.asarray(fy, float) - np.outer(np.asarray(fw, float), np.asarray(Ry, float)) / Rw

    z = np.r_[y[0], y[2:]]
    zscale = np.r_[scale[0], scale[2:]]
    for V, a, b in zip(h.velocities, T, ends, strict=True):
        if a >= t_end:
            break
        sol = solve_ivp(fun, (a, min(b, t_end)), z, method="Radau", rtol=rtol, atol=rtol * zscale, jac=jac,
                        args=(V,))
        if not sol.success:
            raise RuntimeError(sol.message)
        # the slip rate of every recorded point, as the route did for its series
        W = np.array([solve_log_rate(res, q, centre, centre) for q in sol.y[:, 1:].T])
        z = sol.y[:, -1]
    return np.r_[z[0], W[-1], z[1:]]
