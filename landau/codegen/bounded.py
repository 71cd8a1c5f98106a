"""Formulas evaluated with an error bound: float64 at full speed, double-double for the points
the float64 bound does not certify.

A formula (a DAG of sympy operations in the arguments, atoms defined through other atoms) is
linearised once into a straight-line :class:`Program` (:func:`linearise`), encoded as arrays
(:func:`encode`) and run over the points by two interpreters compiled once for every program
(so no formula pays a numba compilation of its own):

* :func:`run_f64` — every operation in float64; for each output y the first-order
  a-posteriori bound Σᵢ |∂y/∂zᵢ|·Lᵢ, where Lᵢ bounds the rounding of operation i alone (u|zᵢ|
  for +, ×, ÷, √ with u = 2⁻⁵³, summed over the partial sums of a sum and the partial
  products of a product; 4u|zᵢ| for the C library's exp, log, pow, asinh, within one ulp) and
  ∂y/∂zᵢ is accumulated in reverse (Linnainmaa 1976; Higham 2002, *Accuracy and Stability of
  Numerical Algorithms*, 2nd ed., Sec. 3.3 and the automatic error analysis of Sec. 26.2).  The
  derivatives carry the signs, so a rounding whose effect cancels along two paths is not
  counted twice — a running bound of magnitudes is orders of magnitude more pessimistic on
  these formulas.  Terms of second order in u are left out: where the bound is below 1e-10 they
  are below 1e-20.
* :func:`run_dd` — the same program in double-double (:mod:`landau.codegen.ddarith`) with a
  rigorous running bound of each operation (magnitudes: |x̂ŷ − xy| ≤ |x̂|e_y + |ŷ|e_x + e_x e_y,
  (1 − ρ)^(−|p|) − 1 for a power, e^e − 1 for exp, −log(1 − ρ) for log, the largest slope for
  asinh) plus the rounding of the double-double operation itself.

A varying argument may carry an absolute error of its own (``EX``; in double-double also a low
part ``XL``), counted as the rounding of an operation is: the bound then covers what the inputs'
error does to every output, with the signs of the derivatives (where the inputs are computed
themselves: the numeric Hopf point of :mod:`landau.codegen.bounded_hopf`).

Each returns the values and, per point, the largest relative bound eᵢ/|vᵢ| over the outputs
(∞ where a bound is infinite or NaN; 0 where the point certainly has no Hopf point: k_c or ω_c²
negative by more than its bound) and the same over k_c and ω_c² alone.  Arguments that are the
same for every point, and every operation on them alone, are evaluated once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction
from typing import Any, Mapping, Sequence

import numba as nb
import numpy as np
import sympy as sp

from landau.codegen import ddarith

#: unit round-off of float64
U = 2.0 ** -53
#: rounding allowed for a C-library elementary function (exp, log, pow, asinh, …): two ulps
U_LIBM = 4 * U
#: IEEE semantics (never fastmath), NaN/inf instead of exceptions, cached on disk
_jit = nb.njit(cache=True, error_model="numpy", nogil=True)
_INF = math.inf


# --- the propagation of one operation's bound in double-double -----------------------------------
@_jit
def b_pow(ax, ex, az, r, rnd):
    """Bound on |x|^p, |p| = r: with ρ = e_x/|x̂| and s = rρ/(1 − ρ) ≥ −r log(1 − ρ), the relative
    change (1 − ρ)^(−r) − 1 ≤ s/(1 − s); plus the rounding rnd·|ẑ|."""
    if not ex < ax:
        return _INF if ex > 0.0 or ax == 0.0 else 0.0
    rho = ex / ax
    s = r * rho / (1.0 - rho)
    if not s < 1.0:
        return _INF
    return az * (s / (1.0 - s) + rnd)


@_jit
def b_exp(ex, az, rnd):
    """Bound on e^x: |ẑ|(e^{e_x} − 1 + rnd), e^t − 1 ≤ t/(1 − t)."""
    if not ex < 1.0:
        return _INF
    return az * (ex / (1.0 - ex) + rnd)


@_jit
def b_log(ax, ex, az, rnd, rnd_abs):
    """Bound on log x: −log(1 − ρ) ≤ ρ/(1 − ρ), ρ = e_x/|x̂|; plus rnd·|ẑ| + rnd_abs."""
    if not ex < ax:
        return _INF
    rho = ex / ax
    return rho / (1.0 - rho) + rnd * az + rnd_abs


@_jit
def b_asinh(ax, ex, az, rnd, rnd_abs):
    """Bound on asinh x: e_x times the largest slope 1/√(1 + m²), m = max(|x̂| − e_x, 0)."""
    m = ax - ex
    if m < 0.0:
        m = 0.0
    return ex / math.sqrt(1.0 + m * m) + rnd * az + rnd_abs


@_jit
def b_sign(ax, ex):
    return 0.0 if ex < ax else _INF


# --- the program -----------------------------------------------------------------------------
@dataclass
class Program:
    """A straight-line program: ``ops[i]`` = (kind, value, argument slots) computes slot i.

    Kinds: ``in`` (value: argument index), ``const`` (a sympy number), ``neg``, ``add``, ``mul``,
    ``pow`` (a rational exponent), ``powx`` (base, exponent slots), ``func`` (a function name).
    ``varying[i]``: slot i depends on an argument that varies over the points."""

    ops: list[tuple[str, Any, tuple[int, ...]]]
    outs: list[int]
    varying: list[bool]
    gate: tuple[int, int] | None = None     # slots of k_c and ω_c² (no Hopf point where either < 0)


_FUNCS = ("exp", "log", "asinh", "Abs", "sign", "sin", "cos", "tanh", "atan", "sinh", "cosh")
_DD_FUNCS = ("exp", "log", "asinh", "Abs", "sign")


class Unsupported(ValueError):
    """An operation the bounded kernels do not implement (the caller takes another route)."""


class _Builder:
    def __init__(self, inputs: Sequence[sp.Symbol], varying: Sequence[bool], defs: Mapping[sp.Symbol, sp.Expr]):
        self.slot: dict[sp.Basic, int] = {s: i for i, s in enumerate(inputs)}
        self.ops: list[tuple[str, Any, tuple[int, ...]]] = [("in", i, ()) for i in range(len(inputs))]
        self.varying = list(varying)
        self.defs = defs

    def _new(self, op) -> int:
        self.ops.append(op)
        self.varying.append(any(self.varying[a] for a in op[2]))
        return len(self.ops) - 1

    def add_op(self, op) -> int:
        return self._new(op)

    def emit(self, expr: sp.Basic) -> int:
        slot = self.slot
        stack = [(expr, False)]
        while stack:
            node, done = stack.pop()
            if node in slot:
                continue
            if node.is_Symbol:
                if node not in self.defs:
                    raise Unsupported(f"symbol {node} is neither an argument nor an atom")
                if not done:
                    stack.append((node, True))
                    stack.append((self.defs[node], False))
                else:
                    slot[node] = slot[self.defs[node]]
                continue
            if node.is_Number or node in (sp.pi, sp.E):
                if not (node.is_Rational or node.is_Float or node in (sp.pi, sp.E)):
                    raise Unsupported(f"constant {node}")
                slot[node] = self._new(("const", node, ()))
                continue
            if not done:
                stack.append((node, True))
                stack.extend((a, False) for a in node.args if a not in slot)
                continue
            args = tuple(slot[a] for a in node.args)
            if node.is_Add:
                op = ("add", None, args)
            elif node.is_Mul:
                if len(node.args) == 2 and node.args[0] == -1:
                    op = ("neg", None, args[1:])
                else:
                    op = ("mul", None, args)
            elif node.is_Pow:
                e = node.exp
                if e.is_Rational and e.q in (1, 2):
                    op = ("pow", e, args[:1])
                else:                   # x^y = exp(y log x); a rational y as a (rounded) constant
                    op = ("powx", None, args)
            elif isinstance(node, sp.Function) and type(node).__name__ in _FUNCS and len(args) == 1:
                op = ("func", type(node).__name__, args)
            else:
                raise Unsupported(f"no bounded operation for {type(node).__name__}")
            slot[node] = self._new(op)
        return slot[expr]


def linearise(outputs: Sequence[sp.Expr], inputs: Sequence[sp.Symbol], varying: Sequence[bool],
              defs: Mapping[sp.Symbol, sp.Expr], given: Mapping[sp.Symbol, tuple] | None = None) -> Program:
    """The program computing ``outputs`` from ``inputs`` (atoms ``defs`` expanded on the way).

    ``given``: symbols defined by an operation on earlier outputs, e.g. ``{w: ("sqrt", 1)}`` for
    ω = √(output 1); they are appended once the outputs before them are emitted."""
    b = _Builder(inputs, varying, defs)
    outs: list[int] = []
    pending = dict(given or {})
    for expr in outputs:
        for sym, (kind, which) in list(pending.items()):
            if which < len(outs):
                src = outs[which]
                b.slot[sym] = src if kind == "same" else b.add_op(("pow", sp.Rational(1, 2), (src,)))
                del pending[sym]
        outs.append(b.emit(expr))
    return Program(b.ops, outs, b.varying)


# --- constants ---------------------------------------------------------------------------------
def _exact(c: sp.Basic) -> tuple[float, bool]:
    """(float value, whether it is exact)."""
    if c.is_Rational:
        f = float(c)
        return f, Fraction(f) == Fraction(int(c.p), int(c.q))
    if isinstance(c, sp.Float):
        import mpmath

        f = float(c)
        return f, mpmath.mpf(c._mpf_) == f
    return float(c), False


def _exact_fraction(c: sp.Basic):
    if c.is_Rational:
        return Fraction(int(c.p), int(c.q))
    import mpmath

    if isinstance(c, sp.Float):
        return mpmath.mpf(c._mpf_)
    with mpmath.workdps(40):
        return +mpmath.pi if c is sp.pi else +mpmath.e


# --- the program as arrays, run by two compiled interpreters ------------------------------------
(K_IN, K_CONST, K_NEG, K_ADD, K_MUL, K_POWI, K_POWH, K_POWX, K_EXP, K_LOG, K_ASINH, K_ABS, K_SIGN,
 K_SIN, K_COS, K_TANH, K_ATAN, K_SINH, K_COSH) = range(19)
_KIND = {"exp": K_EXP, "log": K_LOG, "asinh": K_ASINH, "Abs": K_ABS, "sign": K_SIGN, "sin": K_SIN,
         "cos": K_COS, "tanh": K_TANH, "atan": K_ATAN, "sinh": K_SINH, "cosh": K_COSH}
#: points per block of the interpreters (the block's registers stay in the L2 cache)
BLOCK = 256


@dataclass(frozen=True)
class Encoded:
    """A :class:`Program` as flat arrays for the interpreters :func:`run_f64`, :func:`run_dd`."""

    kind: np.ndarray        # int64 per slot
    off: np.ndarray         # first argument in ``args``
    cnt: np.ndarray         # number of arguments
    args: np.ndarray        # int64, the argument slots of every operation in turn
    ival: np.ndarray        # input row (varying) or index (fixed); integer exponent; 2×exponent (POWH)
    fhi: np.ndarray         # constant (float64 nearest), or the high part of its double-double
    flo: np.ndarray         # the low part
    cerr: np.ndarray        # |error| of the float64 constant
    cerr_dd: np.ndarray     # |error| of the double-double constant
    var: np.ndarray         # int64 0/1: depends on a varying argument
    outs: np.ndarray        # int64 output slots
    gate: np.ndarray        # int64 (k_c slot, ω_c² slot) or (−1, −1)
    cone: np.ndarray        # int64 (outputs × slots) 0/1: the slots an output depends on


def encode(prog: Program) -> Encoded:
    n = len(prog.ops)
    kind, off, cnt, ival = (np.zeros(n, dtype=np.int64) for _ in range(4))
    fhi, flo, cerr, cerr_dd = (np.zeros(n) for _ in range(4))
    args: list[int] = []
    rows = {i: j for j, i in enumerate(i for i, op in enumerate(prog.ops) if op[0] == "in" and prog.varying[i])}
    for i, (k, val, a) in enumerate(prog.ops):
        off[i], cnt[i] = len(args), len(a)
        args.extend(a)
        if k == "in":
            kind[i], ival[i] = K_IN, rows.get(i, val)
        elif k == "const":
            f, exact = _exact(val)
            hi, lo = ddarith.dd_const(_exact_fraction(val))
            kind[i], fhi[i], flo[i] = K_CONST, hi, lo
            cerr[i] = 0.0 if exact else U * abs(f)
            cerr_dd[i] = 0.0 if (exact and lo == 0.0) else ddarith.UNIT * abs(hi)
        elif k == "neg":
            kind[i] = K_NEG
        elif k == "add":
            kind[i] = K_ADD
        elif k == "mul":
            kind[i] = K_MUL
        elif k == "pow":
            kind[i], ival[i] = (K_POWI, int(val)) if val.q == 1 else (K_POWH, int(val.p))
        elif k == "powx":
            kind[i] = K_POWX
        else:
            kind[i] = _KIND[val]
    gate = np.array(prog.gate if prog.gate is not None else (-1, -1), dtype=np.int64)
    cone = np.zeros((len(prog.outs), n), dtype=np.int64)
    for q, top in enumerate(prog.outs):
        cone[q, top] = 1
        for i in range(top, -1, -1):
            if cone[q, i]:
                cone[q, list(prog.ops[i][2])] = 1
    return Encoded(kind, off, cnt, np.array(args or [0], dtype=np.int64), ival, fhi, flo, cerr, cerr_dd,
                   np.array(prog.varying, dtype=np.int64), np.array(prog.outs, dtype=np.int64), gate, cone)


@_jit
def _fwd64(i, k, off, cnt, args, ival, fhi, cerr, v, L, X, EX, Q, start, m):
    """Slot i in float64 for m points: value v[i], bound on its own rounding L[i] (for a varying
    argument: its given error EX)."""
    a0 = args[off[i]]
    if k == K_IN:
        for j in range(m):
            v[i, j] = X[ival[i], start + j] if start >= 0 else Q[ival[i]]
            L[i, j] = EX[ival[i], start + j] if start >= 0 else 0.0
    elif k == K_CONST:
        for j in range(m):
            v[i, j] = fhi[i]
            L[i, j] = cerr[i]
    elif k == K_NEG:
        for j in range(m):
            v[i, j] = -v[a0, j]
            L[i, j] = 0.0
    elif k == K_ADD:
        for j in range(m):
            v[i, j] = v[a0, j]
            L[i, j] = 0.0
        for q in range(1, cnt[i]):
            b = args[off[i] + q]
            for j in range(m):
                s = v[i, j] + v[b, j]
                v[i, j] = s
                L[i, j] += abs(s)
        for j in range(m):
            L[i, j] *= U
    elif k == K_MUL:
        for j in range(m):
            v[i, j] = v[a0, j]
        for q in range(1, cnt[i]):
            b = args[off[i] + q]
            for j in range(m):
                v[i, j] *= v[b, j]
        c = (cnt[i] - 1) * U
        for j in range(m):
            L[i, j] = c * abs(v[i, j])
    elif k == K_POWI:
        n = ival[i]
        an = abs(n)
        if an <= 8:
            c = (an - 1 + (1 if n < 0 else 0)) * U
            for j in range(m):
                x = v[a0, j]
                p = x
                for _ in range(an - 1):
                    p *= x
                z = 1.0 / p if n < 0 else p
                v[i, j] = z
                L[i, j] = c * abs(z)
        else:
            for j in range(m):
                z = math.pow(v[a0, j], float(n))
                v[i, j] = z
                L[i, j] = U_LIBM * abs(z)
    elif k == K_POWH:
        p2 = ival[i]
        for j in range(m):
            x = v[a0, j]
            if p2 == 1:
                z = math.sqrt(x)
                c = U
            elif p2 == -1:
                z = 1.0 / math.sqrt(x)
                c = 2 * U
            else:
                z = math.pow(x, 0.5 * p2)
                c = U_LIBM
            v[i, j] = z
            L[i, j] = c * abs(z)
    elif k == K_POWX:
        y = args[off[i] + 1]
        for j in range(m):
            z = math.pow(v[a0, j], v[y, j])
            v[i, j] = z
            L[i, j] = U_LIBM * abs(z)
    elif k == K_ABS:
        for j in range(m):
            v[i, j] = abs(v[a0, j])
            L[i, j] = 0.0
    elif k == K_SIGN:
        for j in range(m):
            x = v[a0, j]
            v[i, j] = (1.0 if x > 0.0 else -1.0) if x != 0.0 else 0.0
            L[i, j] = 0.0
    else:
        for j in range(m):
            x = v[a0, j]
            if k == K_EXP:
                z = math.exp(x)
            elif k == K_LOG:
                z = math.log(x)
            elif k == K_ASINH:
                z = math.asinh(x)
            elif k == K_SIN:
                z = math.sin(x)
            elif k == K_COS:
                z = math.cos(x)
            elif k == K_TANH:
                z = math.tanh(x)
            elif k == K_ATAN:
                z = math.atan(x)
            elif k == K_SINH:
                z = math.sinh(x)
            else:
                z = math.cosh(x)
            v[i, j] = z
            L[i, j] = U_LIBM * abs(z)


@_jit
def _rev64(i, k, off, cnt, args, ival, v, adj, S, P, m):
    """Adjoints of slot i's arguments from adj[i] (∂output/∂slot, reverse accumulation); S and P
    are scratch rows for a product of more than two factors (``cnt.max()`` × BLOCK and BLOCK)."""
    a0 = args[off[i]]
    if k == K_IN or k == K_CONST:
        return
    if k == K_NEG:
        for j in range(m):
            adj[a0, j] -= adj[i, j]
    elif k == K_ADD:
        for q in range(cnt[i]):
            b = args[off[i] + q]
            for j in range(m):
                adj[b, j] += adj[i, j]
    elif k == K_MUL:
        n = cnt[i]
        if n == 2:
            b = args[off[i] + 1]
            for j in range(m):
                g = adj[i, j]
                adj[a0, j] += g * v[b, j]
                adj[b, j] += g * v[a0, j]
        else:
            # ∂z/∂x_q = Π_{r<q} x_r · Π_{r>q} x_r: the suffix products S[q] = Π_{r>q} x_r first,
            # then the prefix g·Π_{r<q} x_r in P while the factors are walked forward.  No
            # division and no branch (a zero factor needs no special case), so the loops over the
            # points vectorise; z/x_q, divided point by point, made this the interpreter's slowest
            # operation (3n divisions a point for an n-factor product)
            for j in range(m):
                S[n - 1, j] = 1.0
            for q in range(n - 1, 0, -1):
                b = args[off[i] + q]
                for j in range(m):
                    S[q - 1, j] = S[q, j] * v[b, j]
            for j in range(m):
                P[j] = adj[i, j]
            for q in range(n):
                b = args[off[i] + q]
                for j in range(m):
                    adj[b, j] += P[j] * S[q, j]
                    P[j] *= v[b, j]
    elif k == K_POWI or k == K_POWH:
        r = float(ival[i]) if k == K_POWI else 0.5 * ival[i]
        for j in range(m):
            adj[a0, j] += adj[i, j] * r * v[i, j] / v[a0, j]
    elif k == K_POWX:
        y = args[off[i] + 1]
        for j in range(m):
            g = adj[i, j] * v[i, j]
            adj[a0, j] += g * v[y, j] / v[a0, j]
            adj[y, j] += g * math.log(v[a0, j])
    else:
        for j in range(m):
            x = v[a0, j]
            if k == K_EXP:
                d = v[i, j]
            elif k == K_LOG:
                d = 1.0 / x
            elif k == K_ASINH:
                d = 1.0 / math.sqrt(1.0 + x * x)
            elif k == K_ABS:
                d = 1.0 if x >= 0.0 else -1.0
            elif k == K_SIGN:
                d = 0.0
            elif k == K_SIN:
                d = math.cos(x)
            elif k == K_COS:
                d = -math.sin(x)
            elif k == K_TANH:
                d = 1.0 - v[i, j] * v[i, j]
            elif k == K_ATAN:
                d = 1.0 / (1.0 + x * x)
            elif k == K_SINH:
                d = math.cosh(x)
            else:
                d = math.sinh(x)
            adj[a0, j] += adj[i, j] * d


@_jit
def _finish(outs, gate, v, bnd, out, rb, start, m):
    """Values and relative bounds of the outputs (rb[0]: all, rb[1]: the gate k_c, ω_c²)."""
    for j in range(m):
        mx = 0.0
        mg = 0.0
        for q in range(outs.size):
            s = outs[q]
            z = v[s, j]
            out[q, start + j] = z
            r = bnd[q, j] / abs(z)
            if not r <= mx:
                mx = r
            if (s == gate[0] or s == gate[1]) and not r <= mg:
                mg = r
        if mx != mx:
            mx = math.inf
        if mg != mg:
            mg = math.inf
        if gate[0] >= 0:
            kc, W = v[gate[0], j], v[gate[1], j]
            ekc = bnd[_index(outs, gate[0]), j]
            eW = bnd[_index(outs, gate[1]), j]
            if (kc <= 0.0 and ekc < -kc) or (W <= 0.0 and eW < -W):
                mx = 0.0
                mg = 0.0
        rb[0, start + j] = mx
        rb[1, start + j] = mg


@_jit
def _index(outs, s):
    for q in range(outs.size):
        if outs[q] == s:
            return q
    return 0


@_jit
def run_f64(kind, off, cnt, args, ival, fhi, cerr, var, outs, gate, cone, X, EX, Q, out, rb, oe):
    """Every output in float64 with the first-order error bound Σᵢ |∂y/∂zᵢ|·Lᵢ over the slots zᵢ
    (Lᵢ: the bound on the rounding of slot i itself, or the given error EX of a varying argument;
    ∂y/∂zᵢ by reverse accumulation), the linearised a-posteriori bound of Higham (2002),
    Sec. 3.3; blocks of :data:`BLOCK` points.  out: values, rb: relative bounds, oe: the
    absolute bound of each output."""
    ns = kind.size
    npts = X.shape[1]
    v = np.zeros((ns, BLOCK))
    L = np.zeros((ns, BLOCK))
    adj = np.zeros((ns, BLOCK))
    S = np.empty((max(cnt.max(), 1), BLOCK))
    P = np.empty(BLOCK)
    bnd = np.zeros((outs.size, BLOCK))
    for i in range(ns):                   # the fixed slots once, for the whole block
        if var[i] == 0:
            _fwd64(i, kind[i], off, cnt, args, ival, fhi, cerr, v, L, X, EX, Q, -1, 1)
            for j in range(1, BLOCK):
                v[i, j] = v[i, 0]
                L[i, j] = L[i, 0]
    for start in range(0, npts, BLOCK):
        m = min(BLOCK, npts - start)
        for i in range(ns):
            if var[i] != 0:
                _fwd64(i, kind[i], off, cnt, args, ival, fhi, cerr, v, L, X, EX, Q, start, m)
        for q in range(outs.size):
            top = outs[q]
            for i in range(top + 1):
                if cone[q, i] != 0:
                    for j in range(m):
                        adj[i, j] = 0.0
            for j in range(m):
                adj[top, j] = 1.0
                bnd[q, j] = 0.0
            for i in range(top, -1, -1):
                if cone[q, i] == 0:
                    continue
                if kind[i] != K_NEG and kind[i] != K_ABS and kind[i] != K_SIGN:
                    for j in range(m):
                        bnd[q, j] += abs(adj[i, j]) * L[i, j]
                _rev64(i, kind[i], off, cnt, args, ival, v, adj, S, P, m)
            for j in range(m):
                oe[q, start + j] = bnd[q, j]
        _finish(outs, gate, v, bnd, out, rb, start, m)


@_jit
def _fwd_dd(i, k, off, cnt, args, ival, fhi, flo, cerr, h, lo, e, X, XL, EX, Q, start, m):
    """Slot i in double-double for m points, with its running error bound e[i] (a varying
    argument: X + XL, off by at most EX)."""
    UD, UV, UF = ddarith.UNIT, ddarith.UNIT_DIV, ddarith.UNIT_FUNC
    a0 = args[off[i]]
    if k == K_ADD or k == K_MUL:    # most operations: one loop over the points per argument
        for j in range(m):
            h[i, j], lo[i, j], e[i, j] = h[a0, j], lo[a0, j], e[a0, j]
        for q in range(1, cnt[i]):
            b = args[off[i] + q]
            if k == K_ADD:
                for j in range(m):
                    zh, zl = ddarith.dd_add(h[i, j], lo[i, j], h[b, j], lo[b, j])
                    h[i, j], lo[i, j] = zh, zl
                    e[i, j] = e[i, j] + e[b, j] + UD * abs(zh)
            else:
                for j in range(m):
                    zh, ez = h[i, j], e[i, j]
                    ph, pl = ddarith.dd_mul(zh, lo[i, j], h[b, j], lo[b, j])
                    e[i, j] = abs(zh) * e[b, j] + abs(h[b, j]) * ez + ez * e[b, j] + UD * abs(ph)
                    h[i, j], lo[i, j] = ph, pl
        return
    for j in range(m):
        if k == K_IN:
            if start >= 0:
                h[i, j], lo[i, j], e[i, j] = X[ival[i], start + j], XL[ival[i], start + j], EX[ival[i], start + j]
            else:
                h[i, j], lo[i, j], e[i, j] = Q[ival[i]], 0.0, 0.0
            continue
        if k == K_CONST:
            h[i, j], lo[i, j], e[i, j] = fhi[i], flo[i], cerr[i]
            continue
        xh, xl, ex = h[a0, j], lo[a0, j], e[a0, j]
        ax = abs(xh)
        if k == K_NEG:
            zh, zl, ez = -xh, -xl, ex
        elif k == K_POWI or k == K_POWH:
            n = ival[i]
            an = abs(n)
            if k == K_POWH:
                th, tl = ddarith.dd_sqrt(xh, xl)
                rnd = UV
            else:
                th, tl = xh, xl
                rnd = 0.0
            if an > 1:
                th, tl = ddarith.dd_powi(th, tl, an)
                rnd += 2 * UD * (64 - _clz(an))
            if n < 0:
                th, tl = ddarith.dd_recip(th, tl)
                rnd += UV
            zh, zl = th, tl
            r = float(an) if k == K_POWI else 0.5 * an
            ez = b_pow(ax, ex, abs(zh), r, rnd * (1.0 + 1e-12))
        elif k == K_POWX:
            y = args[off[i] + 1]
            yh, yl, ey = h[y, j], lo[y, j], e[y, j]
            lh, ll = ddarith.dd_log(xh, xl)
            el = b_log(ax, ex, abs(lh), UF, UF)
            th, tl = ddarith.dd_mul(lh, ll, yh, yl)
            et = abs(lh) * ey + abs(yh) * el + el * ey + UD * abs(th)
            zh, zl = ddarith.dd_exp(th, tl)
            ez = b_exp(et, abs(zh), UF)
        elif k == K_EXP:
            zh, zl = ddarith.dd_exp(xh, xl)
            ez = b_exp(ex, abs(zh), UF)
        elif k == K_LOG:
            zh, zl = ddarith.dd_log(xh, xl)
            ez = b_log(ax, ex, abs(zh), UF, UF)
        elif k == K_ASINH:
            zh, zl = ddarith.dd_asinh(xh, xl)
            ez = b_asinh(ax, ex, abs(zh), UF, UF)
        elif k == K_ABS:
            zh, zl, ez = (xh, xl, ex) if xh >= 0.0 else (-xh, -xl, ex)
        elif k == K_SIGN:
            zh, zl, ez = ((1.0 if xh > 0.0 else -1.0) if xh != 0.0 else 0.0), 0.0, b_sign(ax, ex)
        else:                                   # no double-double version (the caller checks)
            zh, zl, ez = math.nan, 0.0, math.inf
        h[i, j], lo[i, j], e[i, j] = zh, zl, ez


@_jit
def _clz(n):
    c = 0
    while n > 0 and c < 64:
        n >>= 1
        c += 1
    return 64 - c


@_jit
def run_dd(kind, off, cnt, args, ival, fhi, flo, cerr, var, outs, gate, X, XL, EX, Q, out, rb, ohi, olo, oe):
    """Every output in double-double with the running error bound of each operation: out (hi + lo
    rounded to float64), rb (relative bounds), and for a caller that goes on in double-double the
    parts ohi, olo and the absolute bounds oe."""
    ns = kind.size
    npts = X.shape[1]
    h = np.zeros((ns, BLOCK))
    lo = np.zeros((ns, BLOCK))
    e = np.zeros((ns, BLOCK))
    bnd = np.zeros((outs.size, BLOCK))
    for i in range(ns):
        if var[i] == 0:
            _fwd_dd(i, kind[i], off, cnt, args, ival, fhi, flo, cerr, h, lo, e, X, XL, EX, Q, -1, 1)
            for j in range(1, BLOCK):
                h[i, j], lo[i, j], e[i, j] = h[i, 0], lo[i, 0], e[i, 0]
    for start in range(0, npts, BLOCK):
        m = min(BLOCK, npts - start)
        for i in range(ns):
            if var[i] != 0:
                _fwd_dd(i, kind[i], off, cnt, args, ival, fhi, flo, cerr, h, lo, e, X, XL, EX, Q, start, m)
        for q in range(outs.size):
            s = outs[q]
            for j in range(m):
                bnd[q, j] = e[s, j]
                oe[q, start + j] = e[s, j]
                ohi[q, start + j] = h[s, j]
                olo[q, start + j] = lo[s, j]
        for q in range(outs.size):
            s = outs[q]
            for j in range(m):
                h[s, j] = h[s, j] + lo[s, j]
        _finish(outs, gate, h, bnd, out, rb, start, m)


class BoundedKernels:
    """A :class:`Program` evaluated over points: ``f64(X, Q)`` (float64 values with their
    first-order bound) and ``dd(X, Q)`` (double-double with its running bound).

    X holds the varying arguments (one row each, in the order of the program's varying
    inputs), Q every argument (the varying ones unused).  Both return (values: outputs ×
    points, relative bounds: 2 × points, the largest over all outputs and over k_c, ω_c²).
    The two interpreters are compiled once for every program (numba's disk cache)."""

    def __init__(self, prog: Program):
        self.program = prog
        self.enc = encode(prog)
        self.dd_ok = all(op[0] != "func" or op[1] in _DD_FUNCS for op in prog.ops)

    def _prep(self, X, Q):
        X = np.ascontiguousarray(X, dtype=float)
        return X, np.ascontiguousarray(Q, dtype=float), np.empty((len(self.program.outs), X.shape[1])), \
            np.empty((2, X.shape[1]))

    @staticmethod
    def _given(A, X):
        """``A`` broadcast to X's shape as a new writable C-contiguous float64 array (zeros for
        None): numba compiles the interpreters once per array type, and the read-only view
        ``np.broadcast_to`` returns is another type (a second build of both, ~8 CPU-s cold)."""
        return np.zeros_like(X) if A is None else np.array(np.broadcast_to(A, X.shape), dtype=float, order="C")

    def f64_parts(self, X, Q, EX=None):
        """Float64 (values, relative bounds, absolute bound of each output); ``EX``: absolute
        errors of the varying arguments (same shape as X; none by default)."""
        X, Q, out, rb = self._prep(X, Q)
        oe = np.empty_like(out)
        c = self.enc
        run_f64(c.kind, c.off, c.cnt, c.args, c.ival, c.fhi, c.cerr, c.var, c.outs, c.gate, c.cone,
                X, self._given(EX, X), Q, out, rb, oe)
        return out, rb, oe

    def f64(self, X, Q, EX=None):
        """Float64 values and relative bounds (see :meth:`f64_parts`)."""
        out, rb, _ = self.f64_parts(X, Q, EX)
        return out, rb

    def dd_parts(self, X, Q, XL=None, EX=None):
        """Double-double evaluation at the arguments X + XL (varying ones; each off by at most
        EX): (values rounded to float64, relative bounds, high parts, low parts, absolute bounds)."""
        if not self.dd_ok:
            raise Unsupported("a function without a double-double version")
        X, Q, out, rb = self._prep(X, Q)
        hi, lo, e = (np.empty_like(out) for _ in range(3))
        c = self.enc
        run_dd(c.kind, c.off, c.cnt, c.args, c.ival, c.fhi, c.flo, c.cerr_dd, c.var, c.outs, c.gate,
               X, self._given(XL, X), self._given(EX, X), Q, out, rb, hi, lo, e)
        return out, rb, hi, lo, e

    def dd(self, X, Q, XL=None, EX=None):
        """Double-double values (rounded to float64) and relative bounds."""
        out, rb, _, _, _ = self.dd_parts(X, Q, XL, EX)
        return out, rb
