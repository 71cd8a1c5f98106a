"""Compiled evaluation with a first-order round-off bound at every point.

:class:`BoundedKernel` turns a few sympy expressions (sharing sub-expressions and
definitions, e.g. k_c, ω_c² and Λ in the derivative atoms of a law) into one straight-line
program: every distinct sub-expression is computed once, in one loop over the points, with
no temporary arrays.  Alongside each value the program computes a bound on its round-off
error: the first-order term of the accumulated rounding error (Linnainmaa 1976),

    |computed − exact| ≲ u · Σ_t |∂out/∂t| · r_t,

summed over the operations t of the program, with r_t the error the operation commits
(|t| for +, −, ×, ÷; 2|t| for a library function — glibc's exp, log, pow, asinh are within
one ulp; |c| for a constant not representable in the working precision; inputs are exact).
The sensitivities ∂out/∂t come from one reverse (adjoint) sweep per output, so errors of a
shared sub-expression that cancel further on are counted with their signs: near a
cancellation (Λ → 0/0 at an extremum of μ_ss) the bound grows with the cancelling terms,
elsewhere it stays within one to three orders of magnitude of the actual error.

The float64 loop is generated as LLVM IR and compiled with llvmlite (numba's code
generator, already a dependency) — numba's own front end takes seconds to type a few
thousand scalar statements, LLVM a fraction of that.  Library functions (exp, log, pow, …)
come from glibc's vector math library (libmvec, eight doubles per call with AVX-512, else four,
within 4 ulps — the bound counts them so) where it is available, else from libm lane by lane
(within 1 ulp).  Powers of one base whose exponents are integer multiples of one exponent
(x**(b/a), x**(2b/a), …) share one library ``pow``.  The
machine code is cached on disk (``landau.cache.cache_dir()/kernels``, named by a hash of the IR
and the CPU).

Points whose float64 bound is too large are refined, first by the compensated program
(:meth:`BoundedKernel.compensated`): the same float64 program computes the rounding error
each operation commits — exactly for +, −, × by error-free transformations (TwoSum, TwoProd
with a fused multiply-add), in x87 extended precision for library functions — and adds the
first-order correction Σ_t (∂out/∂t)·δ_t back (Langlois 2001), gaining about ten digits where
float64 lost them to cancelling terms.  The float64 and compensated programs run as one loop
(:meth:`BoundedKernel.fused`): the correction, propagated forward through the program, only for
the groups of points with a doubtful output, reusing their float64 values and bound.  Then,
for what is still unproven, the program runs in the
x87 80-bit extended type (x86 only: 2048 times finer than float64, one point per iteration,
the bound swept in double, :meth:`BoundedKernel.extended`).

References
----------
Linnainmaa, S. (1976), "Taylor expansion of the accumulated rounding error", BIT 16(2),
146–160.
Higham, N. J. (2002), *Accuracy and Stability of Numerical Algorithms*, 2nd ed., SIAM,
Sec. 3.3 (running error analysis).
Langlois, P. (2001), "Automatic linear correction of rounding errors", BIT 41(3), 515–539.
Ogita, T., Rump, S. M., Oishi, S. (2005), "Accurate sum and dot product", SIAM J. Sci.
Comput. 26(6), 1955–1988 (TwoSum, TwoProd).
"""

from __future__ import annotations

import ctypes
import hashlib
import platform
import struct
import threading
from concurrent.futures import ThreadPoolExecutor
from fractions import Fraction
from typing import Callable, Mapping, Sequence

import numpy as np
import sympy as sp

from landau.cx import as_expr

#: unit round-off of float64 and of the platform's long double
U64 = float(np.finfo(np.float64).eps) / 2
ULD = np.finfo(np.longdouble).eps / 2
#: unit round-off of the x87 80-bit extended format
U80 = 2.0 ** -64
#: whether the platform's long double is wider than float64 (x86: 64-bit mantissa)
EXTENDED = np.finfo(np.longdouble).eps < 1e-18 and platform.machine().lower() in ("x86_64", "amd64", "i386", "i686")
#: whether evaluate_proven refines doubtful points with the compensated float64 loop first
COMPENSATE = True
#: fewest doubtful points for which evaluate_proven compiles the fused float64 + compensated
#: loop (:meth:`BoundedKernel.fused`; about a second, what the extended loop takes for 1e5
#: points) when its machine code is not cached
COMPENSATED_MIN_POINTS = 50_000
#: fewest points for which evaluate_proven looks for the fused loop's machine code in the disk
#: cache (finding out costs writing its IR, ~10 ms, what the extended loop takes for ~2000
#: points); compiled in this process, it is used for any number of points
COMPENSATED_CACHED_MIN_POINTS = 2_000
#: points per chunk of the compiled loop handed to one thread
CHUNK = 65_536

#: sympy function -> C library function or LLVM intrinsic of the compiled loops
_FUNCS = {"exp": "llvm.exp", "log": "llvm.log", "asinh": "asinh", "sin": "llvm.sin", "cos": "llvm.cos",
          "tanh": "tanh", "atan": "atan", "sinh": "sinh", "cosh": "cosh", "sqrt": "llvm.sqrt", "Abs": "llvm.fabs"}


def _exact_in_float(r: sp.Rational) -> bool:
    return Fraction(float(r)) == Fraction(int(r.p), int(r.q))


# --------------------------------------------------------------------------------------------
# emitters: the program is written once against this interface, as LLVM IR or as numpy code
def _hex(x: float) -> str:
    return "0x%016X" % struct.unpack(">Q", struct.pack(">d", float(x)))[0]


#: points per iteration of the compiled loops where glibc's vector math library is not used
#: (4 doubles: one AVX2 register); with it, as many as its widest variant the CPU runs takes
#: (:func:`loop_lanes`)
LANES = 4

#: libmvec variants: doubles per call -> (name prefix, the CPU feature it needs)
_MVEC_ISA = {8: ("_ZGVeN8", "avx512f"), 4: ("_ZGVdN4", "avx2")}
#: sympy function -> libmvec function (after the prefix)
_MVEC_FUNCS = {"exp": "v_exp", "log": "v_log", "sin": "v_sin", "cos": "v_cos", "asinh": "v_asinh",
               "atan": "v_atan", "tanh": "v_tanh", "sinh": "v_sinh", "cosh": "v_cosh", "pow": "vv_pow"}
#: the accuracy glibc states for its vector math functions (ulps)
MVEC_ULPS = 4.0
_mvec_state: list = []


def _mvec_names(lanes: int) -> dict[str, str]:
    """sympy function -> glibc's vector math library (libmvec) function on ``lanes`` doubles."""
    return {k: _MVEC_ISA[lanes][0] + v for k, v in _MVEC_FUNCS.items()}


def _mvec_lanes() -> int:
    """Doubles per call of the widest libmvec variant that is loaded with every function of
    :data:`_MVEC_FUNCS` and that the CPU runs (8: AVX-512, 4: AVX2; 0: none): the compiled
    float64 loops then call it instead of scalar libm."""
    if not _mvec_state:
        lanes = 0
        if platform.system() == "Linux" and platform.machine().lower() in ("x86_64", "amd64"):
            try:
                import ctypes.util

                import llvmlite.binding as llvm

                name = ctypes.util.find_library("mvec") or "libmvec.so.1"
                lib = ctypes.CDLL(name, mode=ctypes.RTLD_GLOBAL)
                features = llvm.get_host_cpu_features()
                for n, (_, feature) in _MVEC_ISA.items():
                    if features.get(feature, False) and all(hasattr(lib, f) for f in _mvec_names(n).values()):
                        lanes = n
                        break
                if lanes:
                    llvm.load_library_permanently(lib._name if "/" in lib._name else name)
            except Exception:          # no glibc, no libmvec: scalar libm, lane by lane
                lanes = 0
        _mvec_state.append(lanes)
    return _mvec_state[0]


def _mvec_available() -> bool:
    """Whether the compiled float64 loops call glibc's vector math library."""
    return _mvec_lanes() > 0


def loop_lanes() -> int:
    """Points per iteration of the compiled float64 loops: the width of the libmvec variant in
    use (8 doubles with AVX-512 — twice the points per instruction, and 32 vector registers for
    a program of a few thousand operations), else :data:`LANES`."""
    return _mvec_lanes() or LANES


class _IREmitter:
    """LLVM IR on vectors of :func:`loop_lanes` doubles (one basic block); library functions from glibc's
    vector math library where ``mvec`` (and it is available), else lane by lane."""

    #: error of a library function, in ulps (glibc's scalar functions: within one ulp)
    lib_ulps = 1.0

    def __init__(self, lanes: int | None = None, mvec: bool = False):
        lanes = loop_lanes() if lanes is None else lanes
        self.lines: list[str] = []
        self.n = 0
        self.used: set[str] = set()
        self.lanes = lanes
        self.T = f"<{lanes} x double>"
        self.sfx = f"v{lanes}f64"
        self.mvec = bool(mvec and lanes == _mvec_lanes())
        self._mvec = _mvec_names(lanes) if self.mvec else {}
        if self.mvec:
            self.lib_ulps = MVEC_ULPS

    def _new(self, code: str) -> str:
        self.n += 1
        name = f"%v{self.n}"
        self.lines.append(f"  {name} = {code}")
        return name

    def const(self, x: float) -> str:
        h = _hex(x)
        return "<" + ", ".join([f"double {h}"] * self.lanes) + ">"

    def cref(self, j: int) -> str:
        return f"%c{j}"

    def add(self, a, b):
        return self._new(f"fadd {self.T} {a}, {b}")

    def mul(self, a, b):
        return self._new(f"fmul {self.T} {a}, {b}")

    def div(self, a, b):
        return self._new(f"fdiv {self.T} {a}, {b}")

    def neg(self, a):
        return self._new(f"fneg {self.T} {a}")

    def _intrinsic(self, name: str, *args: str, extra: str = "") -> str:
        f = f"llvm.{name}.{self.sfx}{extra}"
        self.used.add(f)
        return self._new(f"call {self.T} @{f}(" + ", ".join(args) + ")")

    def abs(self, a):
        return self._intrinsic("fabs", f"{self.T} {a}")

    def sign(self, a):
        return self._intrinsic("copysign", f"{self.T} {self.const(1.0)}", f"{self.T} {a}")

    def powi(self, a, n: int):
        return self._intrinsic("powi", f"{self.T} {a}", f"i32 {n}", extra=".i32")

    def pow(self, a, b):
        if self.mvec:
            self.used.add(self._mvec["pow"])
            return self._new(f"call {self.T} @{self._mvec['pow']}({self.T} {a}, {self.T} {b})")
        return self._intrinsic("pow", f"{self.T} {a}", f"{self.T} {b}")

    def fma(self, a, b, c):
        """a·b + c with one rounding."""
        return self._intrinsic("fma", f"{self.T} {a}", f"{self.T} {b}", f"{self.T} {c}")

    def call(self, fname: str, a):
        f = _FUNCS[fname]
        if self.mvec and fname in self._mvec:
            self.used.add(self._mvec[fname])
            return self._new(f"call {self.T} @{self._mvec[fname]}({self.T} {a})")
        if f.startswith("llvm."):
            return self._intrinsic(f.split(".")[1], f"{self.T} {a}")
        self.used.add(f)
        acc = "poison"
        for k in range(self.lanes):
            x = self._new(f"extractelement {self.T} {a}, i32 {k}")
            y = self._new(f"call double @{f}(double {x})")
            acc = self._new(f"insertelement {self.T} {acc}, double {y}, i32 {k}")
        return acc

    def declarations(self) -> list[str]:
        out = []
        for f in sorted(self.used):
            if f.startswith("_ZGV"):
                out.append(f"declare {self.T} @{f}(" + ", ".join([self.T] * (2 if "vv_" in f else 1)) + ") #0")
            elif not f.startswith("llvm."):
                # a library function without side effects (errno is not read): calls can be shared
                out.append(f"declare double @{f}(double) #0")
            elif ".powi." in f:
                out.append(f"declare {self.T} @{f}({self.T}, i32)")
            else:
                n_args = 3 if ".fma." in f else 2 if (".copysign." in f or ".pow." in f) else 1
                out.append(f"declare {self.T} @{f}(" + ", ".join([self.T] * n_args) + ")")
        return out


class _IRDoubleEmitter(_IREmitter):
    """LLVM IR on scalar doubles, registers named %w… (the bound of the extended pass)."""

    def __init__(self, lines: list[str]):
        super().__init__(1)
        self.lines = lines
        self.T = "double"
        self.sfx = "f64"

    def _new(self, code: str) -> str:
        self.n += 1
        name = f"%w{self.n}"
        self.lines.append(f"  {name} = {code}")
        return name

    def const(self, x: float) -> str:
        return _hex(x)

    def call(self, fname: str, a):
        f = _FUNCS[fname]
        if f.startswith("llvm."):
            return self._intrinsic(f.split(".")[1], f"double {a}")
        self.used.add(f)
        return self._new(f"call double @{f}(double {a})")


class _IR80Emitter(_IREmitter):
    """LLVM IR in the x87 80-bit extended type, one point per iteration (the refinement pass);
    integer powers by repeated multiplication, library functions from libm's long-double set."""

    def __init__(self):
        super().__init__(1)
        self.T = "x86_fp80"
        self.sfx = "f80"

    def const(self, x: float) -> str:
        raw = np.longdouble(x).tobytes()[:10]
        return "0xK" + raw[::-1].hex().upper()

    def powi(self, a, n: int):
        result, base, k = None, a, n
        while k:
            if k & 1:
                result = base if result is None else self.mul(result, base)
            k >>= 1
            if k:
                base = self.mul(base, base)
        return result

    def call(self, fname: str, a):
        f = _FUNCS[fname]
        if f.startswith("llvm."):
            return self._intrinsic(f.split(".")[1], f"{self.T} {a}")
        self.used.add(f + "l")
        return self._new(f"call {self.T} @{f}l({self.T} {a})")

    def declarations(self) -> list[str]:
        out = []
        for f in sorted(self.used):
            if not f.startswith("llvm."):
                out.append(f"declare {self.T} @{f}({self.T}) #0")
            else:
                n_args = 2 if (".copysign." in f or ".pow." in f) else 1
                out.append(f"declare {self.T} @{f}(" + ", ".join([self.T] * n_args) + ")")
        return out


class _IR80LaneEmitter(_IR80Emitter):
    """x87 extended-precision scalars (registers %x…) written into another emitter's lines: one
    lane of the compensated loop's library-function corrections."""

    def __init__(self, lines: list[str]):
        super().__init__()
        self.lines = lines

    def _new(self, code: str) -> str:
        self.n += 1
        name = f"%x{self.n}"
        self.lines.append(f"  {name} = {code}")
        return name


#: largest |k| for which x**(k g) is computed as (x**g)**k (its bound grows with |k|)
POWER_SHARE_MAX = 8


def _power_plan(exprs: Sequence[sp.Basic]) -> dict:
    """Which non-integer powers are computed from another power of the same base.

    Powers x**e_i of one base whose exponents are integer multiples k_i of one exponent g
    (|k_i| ≤ :data:`POWER_SHARE_MAX`; e.g. x**(b/a), x**(2b/a), x**(3b/a)) become (x**g)**k_i:
    one library ``pow`` (and, in the compensated program, one extended-precision exp and log
    per lane) instead of one per exponent, the rest integer powers, whose rounding errors the
    compensated program computes exactly.  Half-integer powers x**(n/2) become sqrt(x)**n
    (correctly rounded square root, no library ``pow``).

    Parameters
    ----------
    exprs : sequence of sympy.Basic
        Every expression the program is built from.

    Returns
    -------
    dict
        Power -> (root power x**g, k); the roots themselves are not keys.
    """
    by_base: dict[sp.Basic, dict] = {}
    seen: set = set()
    stack = list(exprs)
    while stack:                            # every distinct sub-expression once
        node = stack.pop()
        if node in seen:
            continue
        seen.add(node)
        if node.is_Pow and not node.exp.is_Integer:
            by_base.setdefault(node.base, {})[node.exp] = node
        stack.extend(node.args)
    plan: dict = {}
    for base, nodes in by_base.items():
        rest = sorted(nodes, key=sp.default_sort_key)
        while rest:
            e0 = rest.pop(0)
            if e0.is_Rational and e0.q == 2:        # x**(n/2) = sqrt(x)**n
                g = sp.Rational(1, 2)
                ks = {e: int(2 * e) for e in [e0, *rest] if e.is_Rational and e.q == 2}
            else:
                ratios = {e: e / e0 for e in [e0, *rest]}
                ratios = {e: r for e, r in ratios.items() if r.is_Rational}
                den = 1
                for r in ratios.values():
                    den = sp.ilcm(den, r.q)
                g = e0 / den
                ks = {e: int(r * den) for e, r in ratios.items()}
                if sum(k < 0 for k in ks.values()) > sum(k > 0 for k in ks.values()):
                    g, ks = -g, {e: -k for e, k in ks.items()}
            ks = {e: k for e, k in ks.items() if abs(k) <= POWER_SHARE_MAX}
            rest = [e for e in rest if e not in ks]
            root = sp.Pow(base, g)
            if not (root.is_Pow and root.base == base and root.exp == g):
                continue                            # sympy rewrote the root: leave the powers alone
            for e, k in ks.items():
                if k != 1:
                    plan[nodes[e]] = (root, k)
    return plan


def _quick_two_sum(E, a, b) -> tuple[object, object]:
    """(s, e) with s + e = a + b exactly, for |a| ≥ |b| (Dekker 1971)."""
    s = E.add(a, b)
    return s, E.add(b, E.neg(E.add(s, E.neg(a))))


# --------------------------------------------------------------------------------------------
class _Op:
    """One operation t = kind(args) of the program."""

    __slots__ = ("kind", "args", "param")

    def __init__(self, kind: str, args: tuple = (), param=None):
        self.kind, self.args, self.param = kind, args, param


class BoundedKernel:
    """Values of several expressions with a first-order round-off bound, compiled once.

    Parameters
    ----------
    outputs : sequence of sympy.Expr
        The expressions to evaluate.
    inputs : sequence of sympy.Symbol
        Their arguments, in call order (taken as exact).
    definitions : mapping of sympy.Symbol to sympy.Expr, optional
        Symbols that stand for expressions (possibly through one another), e.g. derivative
        atoms, ω in terms of ω_c²; each is evaluated once.

    Raises
    ------
    ValueError
        An operation the kernel does not know (a distribution, a piecewise function): the
        caller evaluates such expressions another way.

    Notes
    -----
    ``kernel(*vals)`` returns ``(values, rel_bound)``, two float64 arrays of shape
    ``(len(outputs), n)``; ``rel_bound`` bounds |computed − exact| / |computed| to first
    order in the unit round-off (NaN or inf where it cannot be stated: a division by an
    exact zero, an overflow — treat those points as unproven).
    """

    def __init__(self, outputs: Sequence[sp.Expr], inputs: Sequence[sp.Symbol],
                 definitions: Mapping[sp.Symbol, sp.Expr] | None = None):
        self.inputs = tuple(inputs)
        self.n_out = len(outputs)
        definitions = dict(definitions or {})
        # slots: 0..n_in-1 inputs, then one per operation
        slot: dict[sp.Basic, int] = {s: i for i, s in enumerate(self.inputs)}
        ops: list[_Op] = []
        consts: list[sp.Rational] = []
        n_in = len(self.inputs)

        def push(op: _Op) -> int:
            ops.append(op)
            return n_in + len(ops) - 1

        # powers of one base whose exponents are integer multiples of one exponent g share one
        # pow call: x**(k g) = (x**g)**k (and x**(n/2) = sqrt(x)**n), see _power_plan
        plan = _power_plan([as_expr(o) for o in outputs] + [as_expr(d) for d in definitions.values()])
        for o in outputs:
            stack = [(as_expr(o), False)]
            while stack:
                cur, done = stack.pop()
                if cur in slot:
                    continue
                if cur.is_Symbol:
                    if cur not in definitions:
                        raise ValueError(f"symbol {cur} is neither an input nor defined")
                    d = definitions[cur]
                    if not done:
                        stack.append((cur, True))
                        if d not in slot:
                            stack.append((d, False))
                        continue
                    slot[cur] = slot[d]
                    continue
                if cur.is_Number or cur in (sp.pi, sp.E):
                    if not (cur.is_Rational or cur.is_Float):
                        raise ValueError(f"constant {cur} is not a number the kernel handles")
                    r = sp.Rational(cur)
                    slot[cur] = push(_Op("const", (), (len(consts), bool(cur.is_Rational and _exact_in_float(r)))))
                    consts.append(r)
                    continue
                if not done:
                    stack.append((cur, True))
                    stack.extend((a, False) for a in ((plan[cur][0],) if cur in plan else cur.args) if a not in slot)
                    continue
                if cur in plan:
                    root, k = plan[cur]
                    slot[cur] = self._lower_powi(slot[root], k, push)
                else:
                    slot[cur] = self._lower(cur, slot, push)
        self._ops = ops
        self._n_in = n_in
        self._outs = [slot[as_expr(o)] for o in outputs]
        self.consts = tuple(consts)
        self._lock = threading.Lock()
        self._fn64: dict[tuple, tuple] = {}
        self._paths: dict[tuple, object] = {}

    @staticmethod
    def _lower_powi(x: int, n: int, push) -> int:
        """The operation x**n (n a nonzero integer) of the value in slot ``x``."""
        if n == 1:
            return x
        if n == -1:
            return push(_Op("inv", (x,)))
        if n == 2:
            return push(_Op("sq", (x,)))
        return push(_Op("powi", (x,), n))

    @staticmethod
    def _lower(node, slot, push) -> int:
        a = [slot[x] for x in node.args]
        if node.is_Add or node.is_Mul:
            acc = a[0]
            for x in a[1:]:
                acc = push(_Op("add" if node.is_Add else "mul", (acc, x)))
            return acc
        if node.is_Pow:
            x, p = slot[node.base], node.exp
            if p.is_Integer:
                return BoundedKernel._lower_powi(x, int(p), push)
            if p == sp.Rational(1, 2):
                return push(_Op("func", (x,), "sqrt"))
            if p.is_Rational and _exact_in_float(p):
                return push(_Op("powf", (x,), float(p)))
            return push(_Op("powx", (x, slot[p])))
        fname = type(node).__name__
        if isinstance(node, sp.Function) and fname in _FUNCS and len(a) == 1:
            return push(_Op("func", (a[0],), fname))
        raise ValueError(f"no bounded operation for {fname}")

    # --- the program, written against an emitter ---------------------------------------------
    def _forward(self, E, vals: list, vary: Sequence[bool] | None = None, pre: list | None = None) -> None:
        """Append the value of every operation to ``vals`` (inputs already there); with ``vary``
        (per slot) and ``pre``, the operations that do not vary are written into ``pre`` (the
        lines before the loop)."""
        body = E.lines
        for s, op in enumerate(self._ops, start=self._n_in):
            E.lines = pre if (pre is not None and not vary[s]) else body
            k, a = op.kind, [vals[i] for i in op.args]
            if k == "const":
                vals.append(E.cref(op.param[0]))
            elif k == "add":
                vals.append(E.add(a[0], a[1]))
            elif k == "mul":
                vals.append(E.mul(a[0], a[1]))
            elif k == "inv":
                vals.append(E.div(E.const(1.0), a[0]))
            elif k == "sq":
                vals.append(E.mul(a[0], a[0]))
            elif k == "powi":
                n = op.param
                vals.append(E.powi(a[0], n) if n > 0 else E.div(E.const(1.0), E.powi(a[0], -n)))
            elif k == "powf":
                vals.append(E.pow(a[0], E.const(op.param)))
            elif k == "powx":
                vals.append(E.pow(a[0], a[1]))
            else:
                vals.append(E.call(op.param, a[0]))
        E.lines = body

    def _local(self, E, op: _Op, vals: list, t) -> tuple[list, object]:
        """(∂t/∂arg for each arg, the rounding error t commits in units of u) as emitter values."""
        k, a = op.kind, [vals[i] for i in op.args]
        one, two = E.const(1.0), E.const(2.0)
        at = E.abs(t) if k != "const" else None
        if k == "const":
            return [], (None if op.param[1] else E.abs(t))
        if k == "add":
            return [one, one], at
        if k == "mul":
            return [a[1], a[0]], at
        if k == "inv":
            return [E.neg(E.mul(t, t))], at
        if k == "sq":
            return [E.mul(two, a[0])], at
        if k == "powi":
            n = op.param
            return [E.mul(E.const(n), E.div(t, a[0]))], E.mul(E.const(abs(n) + 1), at)
        lib = E.const(2.0 * E.lib_ulps)          # a library function: within lib_ulps ulps
        if k == "powf":
            return [E.mul(E.const(op.param), E.div(t, a[0]))], E.mul(lib, at)
        if k == "powx":
            return [E.div(E.mul(a[1], t), a[0]), E.mul(t, E.call("log", a[0]))], E.mul(lib, at)
        f, x = op.param, a[0]
        if f == "sqrt":
            return [E.div(E.const(0.5), t)], at
        if f == "Abs":
            return [E.sign(x)], None
        if f == "exp":
            d = t
        elif f == "log":
            d = E.div(one, x)
        elif f == "asinh":
            d = E.div(one, E.call("sqrt", E.add(one, E.mul(x, x))))
        elif f == "atan":
            d = E.div(one, E.add(one, E.mul(x, x)))
        elif f == "tanh":
            d = E.add(one, E.neg(E.mul(t, t)))
        elif f == "sin":
            d = E.call("cos", x)
        elif f == "cos":
            d = E.neg(E.call("sin", x))
        elif f == "sinh":
            d = E.call("cosh", x)
        else:  # cosh
            d = E.call("sinh", x)
        return [d], E.mul(lib, at)

    def _program(self, E, vals: list, B=None, convert=None) -> list[tuple[object, object]]:
        """Forward sweep with emitter ``E``, then one reverse sweep per output with emitter
        ``B`` (default ``E``; ``convert`` maps a value of ``E`` to ``B``'s type — the bound
        needs no more than a few correct digits): [(value, absolute bound / u)]."""
        self._forward(E, vals)
        if B is None:
            B, bvals = E, vals
        else:
            bvals = [convert(v) for v in vals]
        vals_fwd, vals, E = vals, bvals, B
        n_in = self._n_in
        local: dict[int, tuple] = {}
        res = []
        for out in self._outs:
            if out < n_in:
                res.append((vals_fwd[out], E.const(0.0)))
                continue
            cone, stack = set(), [out]
            while stack:
                s = stack.pop()
                if s in cone or s < n_in:
                    continue
                cone.add(s)
                stack.extend(self._ops[s - n_in].args)
            contrib: dict[int, list] = {out: [E.const(1.0)]}
            bound = None
            for s in sorted(cone, reverse=True):
                op = self._ops[s - n_in]
                terms = contrib.pop(s)
                g = terms[0]
                for x in terms[1:]:
                    g = E.add(g, x)
                if s not in local:
                    local[s] = self._local(E, op, vals, vals[s])
                partials, rnd = local[s]
                if rnd is not None:
                    term = E.mul(E.abs(g), rnd)
                    bound = term if bound is None else E.add(bound, term)
                for arg, d in zip(op.args, partials):
                    if arg >= n_in:
                        contrib.setdefault(arg, []).append(g if d == E.const(1.0) else E.mul(g, d))
            res.append((vals_fwd[out], bound if bound is not None else E.const(0.0)))
        return res

    # --- compensated float64: the rounding errors themselves, propagated to the outputs -------
    def _local_error(self, E, X, op: _Op, vals: list, t, dref, varying: bool = True) -> tuple[object, object]:
        """(δ, ρ): the rounding error δ = exact(op(computed args)) − t the operation commits, as
        computed, and a bound ρ on |error of δ| (None: δ is exactly 0 / ρ is 0).

        +, ×, x² by error-free transformations (TwoSum; TwoProd with a fused multiply-add),
        1/x and √x from their exact fma residuals, integer powers in double-double, library
        functions and fractional powers in x87 extended precision (lane by lane; once where
        the operation does not vary from lane to lane)."""
        k, a = op.kind, [vals[i] for i in op.args]
        one = E.const(1.0)
        if k == "const":
            if op.param[1]:
                return None, None
            d = dref(op.param[0])
            return d, E.mul(E.abs(d), E.const(U64))
        if k == "add":
            bb = E.add(t, E.neg(a[0]))
            d = E.add(E.add(a[0], E.neg(E.add(t, E.neg(bb)))), E.add(a[1], E.neg(bb)))
            return d, None
        if k in ("mul", "sq"):
            return E.fma(a[0], a[-1], E.neg(t)), None
        if k == "inv":
            d = E.mul(E.fma(E.neg(t), a[0], one), t)
            return d, E.mul(E.abs(d), E.const(4 * U64))
        if k == "func" and op.param == "sqrt":
            d = E.div(E.fma(E.neg(t), t, a[0]), E.add(t, t))
            return d, E.mul(E.abs(d), E.const(4 * U64))
        if k == "func" and op.param == "Abs":
            return None, None
        if k == "powi":
            n = op.param
            hi, lo = self._dd_powi(E, a[0], abs(n))
            if n < 0:
                q = E.div(one, hi)
                r = E.fma(E.neg(q), hi, one) if lo is None else E.add(E.fma(E.neg(q), hi, one), E.neg(E.mul(q, lo)))
                hi, lo = _quick_two_sum(E, q, E.mul(r, q))
            d = E.add(E.add(hi, E.neg(t)), lo) if lo is not None else E.add(hi, E.neg(t))
            return d, E.mul(E.abs(t), E.const((8 * abs(n) + 8) * U64 * U64))
        # library functions and fractional powers: in x87 extended precision, lane by lane
        T80 = X.T
        dv, zv = "poison", "poison"
        for lane in range(E.lanes if varying else 1):
            args80 = []
            for x in a:
                xs = E._new(f"extractelement {E.T} {x}, i32 {lane}")
                args80.append(X._new(f"fpext double {xs} to {T80}"))
            z = None
            if k == "powf" and float(2 * op.param).is_integer():
                m = int(abs(2 * op.param))
                y = X.powi(X.call("sqrt", args80[0]), m) if m % 2 else X.powi(args80[0], m // 2)
                if op.param < 0:
                    y = X.div(X.const(1.0), y)
            elif k in ("powf", "powx"):
                p80 = X.const(op.param) if k == "powf" else args80[1]
                z = X.mul(p80, X.call("log", args80[0]))
                y = X.call("exp", z)
            else:
                y = X.call(op.param, args80[0])
            ts = E._new(f"extractelement {E.T} {t}, i32 {lane}")
            diff = X.add(y, X.neg(X._new(f"fpext double {ts} to {T80}")))
            dv = E._new(f"insertelement {E.T} {dv}, double {X._new(f'fptrunc {T80} {diff} to double')}, i32 {lane}")
            if z is not None:
                zv = E._new(f"insertelement {E.T} {zv}, double {X._new(f'fptrunc {T80} {z} to double')}, i32 {lane}")
        if not varying:
            dv = E._new(f"shufflevector {E.T} {dv}, {E.T} poison, <{E.lanes} x i32> zeroinitializer")
            if zv != "poison":
                zv = E._new(f"shufflevector {E.T} {zv}, {E.T} poison, <{E.lanes} x i32> zeroinitializer")
        if k == "powf" and float(2 * op.param).is_integer():
            scale = E.const((2 * abs(2 * op.param) + 8) * U80)
        elif k in ("powf", "powx"):
            # log, ×, exp each within a few ulps of 2^-64; the product's error is amplified by |z|
            scale = E.mul(E.const(4 * U80), E.add(E.const(4.0), E.abs(zv)))
        else:
            scale = E.const(16 * U80)
        return dv, E.mul(E.abs(t), scale)

    def _x87_error_bound(self, E, op: _Op, vals: list, t):
        """A float64 bound on the error of the rounding error δ that :meth:`_local_error`
        computes in x87 extended precision (library functions, fractional powers other than
        half-integer ones; None for the other operations, whose δ is exact or within 8u of
        itself): the ρ of :meth:`_local_error`, with z = p·log x in float64."""
        k = op.kind
        if k == "powf" and float(2 * op.param).is_integer():
            return E.mul(E.abs(t), E.const((2 * abs(2 * op.param) + 8) * U80))
        if k in ("powf", "powx"):
            a = [vals[i] for i in op.args]
            p = E.const(op.param) if k == "powf" else a[1]
            z = E.mul(p, E.call("log", a[0]))
            # 2^-40 relative slack for z in float64 and this product
            return E.mul(E.abs(t), E.mul(E.const(4 * U80 * (1 + 2.0 ** -40)), E.add(E.const(4.0), E.abs(z))))
        if k == "func" and op.param not in ("sqrt", "Abs"):
            return E.mul(E.abs(t), E.const(16 * U80))
        return None

    @staticmethod
    def _dd_powi(E, x, n: int) -> tuple[object, object]:
        """x**n (n ≥ 1) in double-double by binary powering: (hi, lo), lo None when exact."""
        def mul(p, q):
            h = E.mul(p[0], q[0])
            e = E.fma(p[0], q[0], E.neg(h))
            if p[1] is not None:
                e = E.add(e, E.mul(p[1], q[0]))
            if q[1] is not None:
                e = E.add(e, E.mul(p[0], q[1]))
            return _quick_two_sum(E, h, e)

        result, base = None, (x, None)
        while n:
            if n & 1:
                result = base if result is None else mul(result, base)
            n >>= 1
            if n:
                base = mul(base, base)
        return result

    def _compensated_program(self, E, X, vals: list, dref, varying: Sequence[bool],
                             outputs: Sequence[int]) -> list[tuple]:
        """Forward sweep, then per output in ``outputs`` one reverse sweep accumulating the
        first-order bound (as :meth:`_program`), the correction Σ g_t δ_t, Σ |g_t δ_t| and
        Σ |g_t| ρ_t."""
        self._forward(E, vals)
        n_in = self._n_in
        vary = [bool(v) for v in varying]
        for op in self._ops:
            vary.append(any(vary[i] for i in op.args))
        local: dict[int, tuple] = {}
        errs: dict[int, tuple] = {}
        zero = E.const(0.0)
        res = []
        for out in (self._outs[j] for j in outputs):
            if out < n_in:
                res.append((vals[out], zero, zero, zero, zero))
                continue
            cone, stack = set(), [out]
            while stack:
                s = stack.pop()
                if s in cone or s < n_in:
                    continue
                cone.add(s)
                stack.extend(self._ops[s - n_in].args)
            contrib: dict[int, list] = {out: [E.const(1.0)]}
            bound, corr, sgd, rho = zero, zero, zero, zero
            for s in sorted(cone, reverse=True):
                op = self._ops[s - n_in]
                terms = contrib.pop(s)
                g = terms[0]
                for x in terms[1:]:
                    g = E.add(g, x)
                if s not in local:
                    local[s] = self._local(E, op, vals, vals[s])
                    errs[s] = self._local_error(E, X, op, vals, vals[s], dref, vary[s])
                partials, rnd = local[s]
                delta, rs = errs[s]
                ag = E.abs(g)
                if rnd is not None:
                    bound = E.add(bound, E.mul(ag, rnd))
                if delta is not None:
                    corr = E.fma(g, delta, corr)
                    sgd = E.add(sgd, E.abs(E.mul(g, delta)))
                if rs is not None:
                    rho = E.add(rho, E.mul(ag, rs))
                for arg, d in zip(op.args, partials):
                    if arg >= n_in:
                        contrib.setdefault(arg, []).append(g if d == E.const(1.0) else E.mul(g, d))
            res.append((vals[out], bound, corr, sgd, rho))
        return res

    # --- float64: LLVM IR compiled with llvmlite -------------------------------------------
    def ir(self, varying: Sequence[bool]) -> str:
        """The float64 loop as LLVM IR, :func:`loop_lanes` points per iteration:
        ``void kernel(i64 n, ptr A, ptr C, double U, ptr V, ptr R)`` (n a multiple of them);
        input k is ``A[k][i]`` where ``varying[k]`` else ``A[k][0]``; output j goes to
        ``V[j*n + i]``, its relative bound to ``R[j*n + i]``."""
        E = _IREmitter(mvec=True)
        T, L = E.T, E.lanes
        n_in = self._n_in
        head, vals = [], []

        def splat(name: str, scalar: str) -> list[str]:
            return [f"  %{name}_1 = insertelement {T} poison, double {scalar}, i32 0",
                    f"  %{name} = shufflevector {T} %{name}_1, {T} poison, <{L} x i32> zeroinitializer"]

        for k in range(n_in):
            head += [f"  %pa{k} = getelementptr ptr, ptr %A, i64 {k}", f"  %A{k} = load ptr, ptr %pa{k}"]
            if varying[k]:
                E.lines += [f"  %px{k} = getelementptr double, ptr %A{k}, i64 %i", f"  %a{k} = load {T}, ptr %px{k}, align 8"]
            else:
                head += [f"  %s{k} = load double, ptr %A{k}", *splat(f"a{k}", f"%s{k}")]
            vals.append(f"%a{k}")
        for j in range(len(self.consts)):
            head += [f"  %pc{j} = getelementptr double, ptr %C, i64 {j}", f"  %sc{j} = load double, ptr %pc{j}",
                     *splat(f"c{j}", f"%sc{j}")]
        head += splat("U", "%u")
        res = self._program(E, vals)
        store = []
        for j, (v, b) in enumerate(res):
            rel = E.div(E.mul(b, "%U"), E.abs(v))
            store += [f"  %o{j} = mul i64 %n, {j}", f"  %oi{j} = add i64 %o{j}, %i",
                      f"  %pv{j} = getelementptr double, ptr %V, i64 %oi{j}", f"  store {T} {v}, ptr %pv{j}, align 8",
                      f"  %pr{j} = getelementptr double, ptr %R, i64 %oi{j}", f"  store {T} {rel}, ptr %pr{j}, align 8"]
        text = "\n".join(E.lines)      # the program, then |value| and the relative bound of each output
        return "\n".join([
            *E.declarations(), "",
            "define void @kernel(i64 %n, ptr noalias %A, ptr noalias %C, double %u, ptr noalias %V, ptr noalias %R) {",
            "entry:", *head, "  br label %loop", "loop:",
            "  %i = phi i64 [0, %entry], [%inext, %loop]",
            text, *store,
            f"  %inext = add i64 %i, {L}", "  %more = icmp slt i64 %inext, %n",
            "  br i1 %more, label %loop, label %exit", "exit:", "  ret void", "}", "",
            "attributes #0 = { nounwind willreturn memory(none) }", ""])

    def ir_extended(self) -> str:
        """The refinement loop as LLVM IR in x87 80-bit extended precision, one point per
        iteration: ``void kernel(i64 n, ptr A, ptr S, ptr C, double U, ptr V, ptr R)`` with
        float64 inputs ``A[k][i*S[k]]``, long-double constants ``C``, long-double values
        ``V[j*n + i]`` and float64 relative bounds ``R[j*n + i]``."""
        E = _IR80Emitter()
        T = E.T
        head, vals = [], []
        for k in range(self._n_in):
            head += [f"  %pa{k} = getelementptr ptr, ptr %A, i64 {k}", f"  %A{k} = load ptr, ptr %pa{k}",
                     f"  %ps{k} = getelementptr i64, ptr %S, i64 {k}", f"  %S{k} = load i64, ptr %ps{k}"]
            E.lines += [f"  %ix{k} = mul i64 %i, %S{k}", f"  %px{k} = getelementptr double, ptr %A{k}, i64 %ix{k}",
                        f"  %d{k} = load double, ptr %px{k}", f"  %a{k} = fpext double %d{k} to {T}"]
            vals.append(f"%a{k}")
        for j in range(len(self.consts)):
            head += [f"  %pc{j} = getelementptr {T}, ptr %C, i64 {j}", f"  %c{j} = load {T}, ptr %pc{j}, align 16"]
        B = _IRDoubleEmitter(E.lines)
        res = self._program(E, vals, B, lambda v: B._new(f"fptrunc {T} {v} to double"))
        store = []
        for j, (v, b) in enumerate(res):
            rel = B.div(B.mul(b, "%u"), B.abs(B._new(f"fptrunc {T} {v} to double")))
            store += [f"  %o{j} = mul i64 %n, {j}", f"  %oi{j} = add i64 %o{j}, %i",
                      f"  %pv{j} = getelementptr {T}, ptr %V, i64 %oi{j}", f"  store {T} {v}, ptr %pv{j}, align 16",
                      f"  %pr{j} = getelementptr double, ptr %R, i64 %oi{j}", f"  store double {rel}, ptr %pr{j}"]
        return "\n".join([
            *E.declarations(), *B.declarations(), "",
            "define void @kernel(i64 %n, ptr noalias %A, ptr noalias %S, ptr noalias %C, double %u, ptr noalias %V, "
            "ptr noalias %R) {",
            "entry:", *head, "  br label %loop", "loop:",
            "  %i = phi i64 [0, %entry], [%inext, %loop]",
            "\n".join(E.lines), *store,
            "  %inext = add i64 %i, 1", "  %more = icmp slt i64 %inext, %n",
            "  br i1 %more, label %loop, label %exit", "exit:", "  ret void", "}", "",
            "attributes #0 = { nounwind willreturn memory(none) }", ""])

    def ir_compensated(self, varying: Sequence[bool], outputs: Sequence[int]) -> str:
        """The compensated float64 loop for the outputs ``outputs`` as LLVM IR, :func:`loop_lanes` points per
        iteration: ``void kernel(i64 n, ptr A, ptr C, ptr D, double U, ptr V, ptr R)`` with
        inputs as in :meth:`ir`, constants ``C`` and their rounding errors ``D``; writes the
        corrected values ``V`` and their relative bounds ``R`` (see :meth:`compensated`)."""
        E = _IREmitter(mvec=True)
        T, L = E.T, E.lanes
        X = _IR80LaneEmitter(E.lines)
        head, vals = [], []

        def splat(name: str, scalar: str) -> list[str]:
            return [f"  %{name}_1 = insertelement {T} poison, double {scalar}, i32 0",
                    f"  %{name} = shufflevector {T} %{name}_1, {T} poison, <{L} x i32> zeroinitializer"]

        for k in range(self._n_in):
            head += [f"  %pa{k} = getelementptr ptr, ptr %A, i64 {k}", f"  %A{k} = load ptr, ptr %pa{k}"]
            if varying[k]:
                E.lines += [f"  %px{k} = getelementptr double, ptr %A{k}, i64 %i", f"  %a{k} = load {T}, ptr %px{k}, align 8"]
            else:
                head += [f"  %s{k} = load double, ptr %A{k}", *splat(f"a{k}", f"%s{k}")]
            vals.append(f"%a{k}")
        for j, c in enumerate(self.consts):
            head += [f"  %pc{j} = getelementptr double, ptr %C, i64 {j}", f"  %sc{j} = load double, ptr %pc{j}",
                     *splat(f"c{j}", f"%sc{j}")]
            head += [f"  %pd{j} = getelementptr double, ptr %D, i64 {j}", f"  %sd{j} = load double, ptr %pd{j}",
                     *splat(f"d{j}", f"%sd{j}")]
        head += splat("U", "%u")
        res = self._compensated_program(E, X, vals, lambda j: f"%d{j}", varying, outputs)
        store = []
        for j, (v, b, corr, sgd, rho) in enumerate(res):
            vc = E.add(v, corr)
            b1 = E.mul(b, "%U")
            # rounding of the sum, the inexact corrections, an allowance of 2^-10 of the correction
            # for the float64 sensitivities, and 2^10 (b1/|v|)·b1 for the second-order terms
            tot = E.add(E.add(E.mul("%U", E.abs(vc)), rho),
                        E.add(E.mul(E.const(2.0 ** -10), sgd), E.div(E.mul(E.const(2.0 ** 10), E.mul(b1, b1)), E.abs(v))))
            rel = E.div(tot, E.abs(vc))
            store += [f"  %o{j} = mul i64 %n, {j}", f"  %oi{j} = add i64 %o{j}, %i",
                      f"  %pv{j} = getelementptr double, ptr %V, i64 %oi{j}", f"  store {T} {vc}, ptr %pv{j}, align 8",
                      f"  %pr{j} = getelementptr double, ptr %R, i64 %oi{j}", f"  store {T} {rel}, ptr %pr{j}, align 8"]
        decl = sorted(set(E.declarations()) | set(X.declarations()))
        return "\n".join([
            *decl, "",
            "define void @kernel(i64 %n, ptr noalias %A, ptr noalias %C, ptr noalias %D, double %u, ptr noalias %V, "
            "ptr noalias %R) {",
            "entry:", *head, "  br label %loop", "loop:",
            "  %i = phi i64 [0, %entry], [%inext, %loop]",
            "\n".join(E.lines), *store,
            f"  %inext = add i64 %i, {L}", "  %more = icmp slt i64 %inext, %n",
            "  br i1 %more, label %loop, label %exit", "exit:", "  ret void", "}", "",
            "attributes #0 = { nounwind willreturn memory(none) }", ""])

    # --- fused: float64 with its bound, compensated where a group of points is doubtful --------
    def ir_fused(self, varying: Sequence[bool]) -> str:
        """The float64 loop and the compensated loop in one, as LLVM IR, :func:`loop_lanes` points per
        iteration: ``void kernel(i64 n, ptr A, ptr C, ptr D, double U, double tol, ptr V, ptr R)``
        (arguments as in :meth:`ir_compensated`).

        Every iteration runs the float64 program with its first-order bound b (:meth:`ir`) and
        stores values and relative bounds.  Where a relative bound of the iteration's points
        exceeds ``tol`` (or is NaN), the rounding errors δ_t are computed as in
        :meth:`compensated` and their first-order effect is propagated forward,
        e_t = Σ ∂t/∂arg·e_arg + δ_t (Langlois 2001), from the float64 values and partial
        derivatives already at hand; a point's output takes the compensated value v + e where
        its own bound exceeds ``tol`` and the compensated bound is smaller.  That bound: the
        rounding of v + e, the error of the δ computed in extended precision (summed in the
        float64 sweep), (2^-10 + 2^-49)·b·u for the float64 sensitivities and the residual
        errors of the error-free transformations (each |δ_t| is within the rounding error b
        counts, so Σ|∂out/∂t·δ_t| ≤ b·u), and 2^10 (b·u)²/|v| for the second-order terms.
        The δ computed lane by lane in extended precision (library functions, fractional
        powers) are left out where the share of b they account for is below 2^-4 ``tol``·|v|
        for every doubtful output of the iteration; that share then stays in the bound.
        Operations that do not vary from point to point (and their rounding errors) are
        computed once, before the loop."""
        E = _IREmitter(mvec=True)
        T, L = E.T, E.lanes
        X = _IR80LaneEmitter(E.lines)
        n_in = self._n_in
        head, vals = [], []

        def splat(name: str, scalar: str) -> list[str]:
            return [f"  %{name}_1 = insertelement {T} poison, double {scalar}, i32 0",
                    f"  %{name} = shufflevector {T} %{name}_1, {T} poison, <{L} x i32> zeroinitializer"]

        for k in range(n_in):
            head += [f"  %pa{k} = getelementptr ptr, ptr %A, i64 {k}", f"  %A{k} = load ptr, ptr %pa{k}"]
            if varying[k]:
                E.lines += [f"  %px{k} = getelementptr double, ptr %A{k}, i64 %i", f"  %a{k} = load {T}, ptr %px{k}, align 8"]
            else:
                head += [f"  %s{k} = load double, ptr %A{k}", *splat(f"a{k}", f"%s{k}")]
            vals.append(f"%a{k}")
        for j in range(len(self.consts)):
            head += [f"  %pc{j} = getelementptr double, ptr %C, i64 {j}", f"  %sc{j} = load double, ptr %pc{j}",
                     *splat(f"c{j}", f"%sc{j}"),
                     f"  %pd{j} = getelementptr double, ptr %D, i64 {j}", f"  %sd{j} = load double, ptr %pd{j}",
                     *splat(f"d{j}", f"%sd{j}")]
        head += splat("U", "%u") + splat("TOL", "%tol")
        vary = [bool(v) for v in varying]
        for op in self._ops:
            vary.append(any(vary[i] for i in op.args))
        body = E.lines
        self._forward(E, vals, vary, head)
        # float64: one reverse sweep per output for the first-order bound (as in ir), and the
        # bound of the error that the correction itself carries where the rounding error of an
        # operation is computed in extended precision only (library functions, powers)
        one, zero = E.const(1.0), E.const(0.0)
        local: dict[int, tuple] = {}
        x87_err: dict[int, object] = {}
        sweeps = []
        for out in self._outs:
            bound, rho, bx = zero, zero, zero
            if out >= n_in:
                cone, stack = set(), [out]
                while stack:
                    s = stack.pop()
                    if s in cone or s < n_in:
                        continue
                    cone.add(s)
                    stack.extend(self._ops[s - n_in].args)
                contrib: dict[int, list] = {out: [one]}
                for s in sorted(cone, reverse=True):
                    op = self._ops[s - n_in]
                    terms = contrib.pop(s)
                    g = terms[0]
                    for x in terms[1:]:
                        g = E.add(g, x)
                    if s not in local:
                        local[s] = self._local(E, op, vals, vals[s])
                    partials, rnd = local[s]
                    if rnd is not None:
                        ag = E.abs(g)
                        bound = E.add(bound, E.mul(ag, rnd))
                        if s not in x87_err:
                            x87_err[s] = self._x87_error_bound(E, op, vals, vals[s])
                        if x87_err[s] is not None:
                            rho = E.add(rho, E.mul(ag, x87_err[s]))
                            if vary[s]:
                                bx = E.add(bx, E.mul(ag, rnd))
                    for arg, d in zip(op.args, partials):
                        if arg >= n_in:
                            contrib.setdefault(arg, []).append(g if d == one else E.mul(g, d))
            sweeps.append((vals[out], bound, rho, bx))
        store, doubt, rels = [], None, []
        for j, (v, b, _, _) in enumerate(sweeps):
            rel = E.div(E.mul(b, "%U"), E.abs(v))
            rels.append(rel)
            bd = E._new(f"fcmp ugt {T} {rel}, %TOL")
            doubt = bd if doubt is None else E._new(f"or <{L} x i1> {doubt}, {bd}")
            store += [f"  %o{j} = mul i64 %n, {j}", f"  %oi{j} = add i64 %o{j}, %i",
                      f"  %pv{j} = getelementptr double, ptr %V, i64 %oi{j}", f"  store {T} {v}, ptr %pv{j}, align 8",
                      f"  %pr{j} = getelementptr double, ptr %R, i64 %oi{j}", f"  store {T} {rel}, ptr %pr{j}, align 8"]
        any_doubt = E._new(f"call i1 @llvm.vector.reduce.or.v{L}i1(<{L} x i1> {doubt})")
        # the correction, forward: the first-order error e_t = Σ ∂t/∂arg · e_arg + δ_t of every
        # value (Langlois 2001), in its own block (in the preheader for what does not vary)
        # The rounding errors computed in extended precision lane by lane (library functions,
        # fractional powers) are the costly ones: they are computed only where the part of the
        # first-order bound they account for, bx, is above 2^-4 tol for a doubtful output of
        # the iteration's points; elsewhere their share of the bound stays in the bound.
        fix, fixx, fix2 = [], [], []
        E.lines = fix
        need = None
        for j, (v, b, rho, bx) in enumerate(sweeps):
            big = E._new(f"fcmp ogt {T} " + E.mul(bx, "%U") + ", " + E.mul(E.const(2.0 ** -4), E.mul("%TOL", E.abs(v))))
            nj = E._new(f"and <{L} x i1> {big}, " + E._new(f"fcmp ugt {T} {rels[j]}, %TOL"))
            need = nj if need is None else E._new(f"or <{L} x i1> {need}, {nj}")
        any_need = E._new(f"call i1 @llvm.vector.reduce.or.v{L}i1(<{L} x i1> {need})")
        x87_delta: dict[int, object] = {}
        E.lines = X.lines = fixx
        for s, op in enumerate(self._ops, start=n_in):
            if vary[s] and s in x87_err and x87_err[s] is not None:
                delta, _ = self._local_error(E, X, op, vals, vals[s], lambda c: f"%d{c}", True)
                x87_delta[s] = E._new(f"phi {T} [{delta}, %fixx], [zeroinitializer, %fix]")
                fixx.pop()                   # the phi belongs to fix2
                fix2.append(f"  {x87_delta[s]} = phi {T} [{delta}, %fixx], [zeroinitializer, %fix]")
        skipped = []
        for j, (v, b, rho, bx) in enumerate(sweeps):
            name = f"%skip{j}"
            fix2.append(f"  {name} = phi {T} [zeroinitializer, %fixx], [{bx}, %fix]")
            skipped.append(name)
        errs: dict[int, object] = {}
        for s, op in enumerate(self._ops, start=n_in):
            E.lines = X.lines = fix2 if vary[s] else head
            if s in x87_delta:
                delta = x87_delta[s]
            else:
                delta, _ = self._local_error(E, X, op, vals, vals[s], lambda c: f"%d{c}", vary[s])
            partials = local[s][0] if (vary[s] and s in local) else self._local(E, op, vals, vals[s])[0]
            e = delta
            for arg, d in zip(op.args, partials):
                ea = errs.get(arg)
                if ea is None:
                    continue
                if d == one:
                    e = ea if e is None else E.add(e, ea)
                else:
                    e = E.mul(d, ea) if e is None else E.fma(d, ea, e)
            if e is not None:
                errs[s] = e
        E.lines = X.lines = fix2
        for j, (v, b, rho, _) in enumerate(sweeps):
            e = errs.get(self._outs[j])
            vc = v if e is None else E.add(v, e)
            b1 = E.mul(b, "%U")
            rho = E.add(rho, E.mul(skipped[j], "%U"))
            # rounding of the sum, the corrections' own error, an allowance of 2^-10 of the
            # first-order bound (≥ Σ|∂out/∂t·δ_t|) for the float64 sensitivities and 2^-49 of it
            # for the error-free transformations' residual errors (1/x, √x, x**n: within 8u of
            # their δ), and 2^10 (b1/|v|)·b1 for the second-order terms
            tot = E.add(E.add(E.mul("%U", E.abs(vc)), rho),
                        E.add(E.mul(E.const(2.0 ** -10 + 2.0 ** -49), b1),
                              E.div(E.mul(E.const(2.0 ** 10), E.mul(b1, b1)), E.abs(v))))
            relc = E.div(tot, E.abs(vc))
            better = E._new(f"fcmp olt {T} {relc}, {rels[j]}")
            use = E._new(f"and <{L} x i1> {better}, " + E._new(f"fcmp ugt {T} {rels[j]}, %TOL"))
            vo = E._new(f"select <{L} x i1> {use}, {T} {vc}, {T} {v}")
            ro = E._new(f"select <{L} x i1> {use}, {T} {relc}, {T} {rels[j]}")
            fix2 += [f"  store {T} {vo}, ptr %pv{j}, align 8", f"  store {T} {ro}, ptr %pr{j}, align 8"]
        E.lines = body
        decl = sorted(set(E.declarations()) | set(X.declarations())
                      | {f"declare i1 @llvm.vector.reduce.or.v{L}i1(<{L} x i1>)"})
        return "\n".join([
            *decl, "",
            "define void @kernel(i64 %n, ptr noalias %A, ptr noalias %C, ptr noalias %D, double %u, double %tol, "
            "ptr noalias %V, ptr noalias %R) {",
            "entry:", *head, "  br label %loop", "loop:",
            "  %i = phi i64 [0, %entry], [%inext, %next]",
            "\n".join(body), *store,
            f"  br i1 {any_doubt}, label %fix, label %next", "fix:",
            "\n".join(fix), f"  br i1 {any_need}, label %fixx, label %fix2", "fixx:",
            "\n".join(fixx), "  br label %fix2", "fix2:",
            "\n".join(fix2), "  br label %next", "next:",
            f"  %inext = add i64 %i, {L}", "  %more = icmp slt i64 %inext, %n",
            "  br i1 %more, label %loop, label %exit", "exit:", "  ret void", "}", "",
            "attributes #0 = { nounwind willreturn memory(none) }", ""])

    def compiled_fused(self, varying: Sequence[bool]) -> Callable:
        """The compiled fused loop (:meth:`ir_fused`) for ``varying``, compiled on first use."""
        key = ("fused", tuple(bool(x) for x in varying))
        with self._lock:
            if key not in self._fn64:
                self._fn64[key] = _jit(self.ir_fused(key[1]), extended=True, doubles=2)
        return self._fn64[key][0]

    def fused_ready(self, varying: Sequence[bool], compiled_only: bool = False) -> bool:
        """Whether :meth:`fused` for ``varying`` costs no compilation: compiled in this process,
        or (unless ``compiled_only``) its object file is in the disk cache (writing its IR to
        find out takes ~10 ms, once per process)."""
        key = ("fused", tuple(bool(x) for x in varying))
        with self._lock:
            if key in self._fn64:
                return True
            if compiled_only:
                return False
            path = self._paths.get(key, False)
        if path is False:
            try:
                path = _object_path(self.ir_fused(key[1]))
            except Exception:
                path = None
            self._paths[key] = path
        return path is not None and path.exists()

    def fused(self, *vals, tol: float, workers: int = 1) -> tuple[np.ndarray, np.ndarray]:
        """Values and relative bounds as from calling the kernel, with the compensated pass
        (:meth:`compensated`) run in the same loop for the groups of :func:`loop_lanes` points where
        a bound exceeds ``tol`` (x86 only).

        Parameters
        ----------
        *vals : float or array_like
            One value per input, as for calling the kernel.
        tol : float
            Relative bound above which a point's output takes the compensated value (where
            that is better proven).
        workers : int, optional
            Threads for large batches.

        Returns
        -------
        values, rel_bound : numpy.ndarray
            Shape ``(n_outputs, n)``: the float64 value and bound where the bound is at most
            ``tol``, else the better proven of the float64 and compensated ones.
        """
        arrs = [_flat(v) for v in vals]
        if len(arrs) != self._n_in:
            raise ValueError(f"kernel takes {self._n_in} inputs, got {len(arrs)}")
        fn = self.compiled_fused([a.size > 1 for a in arrs])
        C = np.array([float(c) for c in self.consts] or [0.0], dtype=np.float64)
        D = np.array([float(Fraction(int(c.p), int(c.q)) - Fraction(float(c))) for c in self.consts] or [0.0])
        return self._run(arrs, lambda m, ptrs, v, r: fn(m, ptrs, C.ctypes.data, D.ctypes.data, U64, float(tol),
                                                         v.ctypes.data, r.ctypes.data), workers)

    def _run(self, arrs: list, call: Callable, workers: int) -> tuple[np.ndarray, np.ndarray]:
        """Run a compiled loop over the broadcast inputs ``arrs`` (padded to a multiple of
        :func:`loop_lanes`), in chunks on ``workers`` threads: ``call(n, ptrs, V, R)``."""
        n = max((a.size for a in arrs), default=1)
        if any(a.size not in (1, n) for a in arrs):
            raise ValueError("inputs must have one element or a common length")
        if n == 0:
            return np.empty((self.n_out, 0)), np.empty((self.n_out, 0))
        size = n
        lanes = loop_lanes()
        if n % lanes:                   # the loop takes `lanes` points at a time: pad with the last point
            n = n + lanes - n % lanes
            arrs = [a if a.size == 1 else np.concatenate([a, np.full(n - size, a[-1])]) for a in arrs]
        V = np.empty((self.n_out, n))
        R = np.empty((self.n_out, n))

        def run(lo: int, hi: int, v: np.ndarray, r: np.ndarray) -> None:
            ptrs = (ctypes.c_void_p * len(arrs))(*[a.ctypes.data + (0 if a.size == 1 else 8 * lo) for a in arrs])
            call(hi - lo, ptrs, v, r)

        if workers <= 1 or n <= CHUNK:
            run(0, n, V, R)
            return V[:, :size], R[:, :size]

        def chunk(lo: int) -> None:
            hi = min(lo + CHUNK, n)
            v, r = np.empty((self.n_out, hi - lo)), np.empty((self.n_out, hi - lo))
            run(lo, hi, v, r)
            V[:, lo:hi], R[:, lo:hi] = v, r

        with ThreadPoolExecutor(max_workers=workers) as pool:
            list(pool.map(chunk, range(0, n, CHUNK)))
        return V[:, :size], R[:, :size]

    def compiled(self, varying: Sequence[bool]) -> Callable:
        """The compiled float64 loop for inputs that vary (arrays) or not (scalars): a ctypes
        function, which releases the GIL while it runs."""
        key = tuple(bool(x) for x in varying)
        with self._lock:
            if key not in self._fn64:
                self._fn64[key] = _jit(self.ir(key))
        return self._fn64[key][0]

    def ready(self, varying: Sequence[bool]) -> bool:
        """Whether the float64 and extended loops for ``varying`` cost no compilation: compiled in
        this process already, or their object files are in the disk cache.

        Parameters
        ----------
        varying : sequence of bool
            Which inputs vary (see :meth:`compiled`).

        Returns
        -------
        bool
        """
        key = tuple(bool(x) for x in varying)
        with self._lock:
            have64 = key in self._fn64
            have_ext = "ext" in self._fn64 or not EXTENDED
        try:
            if not have64:
                p = _object_path(self.ir(key))
                have64 = p is not None and p.exists()
            if not have_ext:
                p = _object_path(self.ir_extended())
                have_ext = p is not None and p.exists()
        except Exception:  # an IR the emitter cannot write: not ready (the caller falls back)
            return False
        return have64 and have_ext

    def __call__(self, *vals, workers: int = 1) -> tuple[np.ndarray, np.ndarray]:
        """Values and relative bounds in float64 over the broadcast inputs (flattened).

        Parameters
        ----------
        *vals : float or array_like
            One value per input; arrays broadcast (scalars and length-1 arrays against the rest).
        workers : int, optional
            Threads for large batches (the compiled loop releases the GIL).

        Returns
        -------
        values, rel_bound : numpy.ndarray
            Shape ``(n_outputs, n)``.
        """
        arrs = [_flat(v) for v in vals]
        if len(arrs) != self._n_in:
            raise ValueError(f"kernel takes {self._n_in} inputs, got {len(arrs)}")
        n = max((a.size for a in arrs), default=1)
        if any(a.size not in (1, n) for a in arrs):
            raise ValueError("inputs must have one element or a common length")
        fn = self.compiled([a.size > 1 for a in arrs])
        C = np.array([float(c) for c in self.consts] or [0.0], dtype=np.float64)
        if n == 0:
            return np.empty((self.n_out, 0)), np.empty((self.n_out, 0))
        size = n
        lanes = loop_lanes()
        if n % lanes:                   # the loop takes `lanes` points at a time: pad with the last point
            n = n + lanes - n % lanes
            arrs = [a if a.size == 1 else np.concatenate([a, np.full(n - size, a[-1])]) for a in arrs]
        V = np.empty((self.n_out, n))
        R = np.empty((self.n_out, n))

        def run(lo: int, hi: int, v: np.ndarray, r: np.ndarray) -> None:
            ptrs = (ctypes.c_void_p * len(arrs))(*[a.ctypes.data + (0 if a.size == 1 else 8 * lo) for a in arrs])
            fn(hi - lo, ptrs, C.ctypes.data, U64, v.ctypes.data, r.ctypes.data)

        if workers <= 1 or n <= CHUNK:
            run(0, n, V, R)
            return V[:, :size], R[:, :size]

        def chunk(lo: int) -> None:
            hi = min(lo + CHUNK, n)
            v, r = np.empty((self.n_out, hi - lo)), np.empty((self.n_out, hi - lo))
            run(lo, hi, v, r)
            V[:, lo:hi], R[:, lo:hi] = v, r

        with ThreadPoolExecutor(max_workers=workers) as pool:
            list(pool.map(chunk, range(0, n, CHUNK)))
        return V[:, :size], R[:, :size]

    # --- x87 extended precision: the refinement pass -----------------------------------------
    def compiled_extended(self) -> Callable:
        """The compiled extended-precision loop (a ctypes function), compiled on first use."""
        with self._lock:
            if "ext" not in self._fn64:
                self._fn64["ext"] = _jit(self.ir_extended(), extended=True)
        return self._fn64["ext"][0]

    def extended(self, *vals) -> tuple[np.ndarray, np.ndarray]:
        """The same program in x87 80-bit extended precision (compiled, x86 only) with its own
        bound; for the points whose float64 bound is too large.

        Returns
        -------
        values, rel_bound : numpy.ndarray
            Long-double values and float64 relative bounds, shape ``(n_outputs, n)``.
        """
        fn = self.compiled_extended()
        arrs = [_flat(v) for v in vals]
        n = max((a.size for a in arrs), default=1)
        ld = np.longdouble
        C = np.array([ld(int(c.p)) / ld(int(c.q)) for c in self.consts] or [ld(0)], dtype=ld)
        V = np.empty((self.n_out, n), dtype=ld)
        R = np.empty((self.n_out, n))
        if n:
            ptrs = (ctypes.c_void_p * len(arrs))(*[a.ctypes.data for a in arrs])
            S = np.array([0 if a.size == 1 else 1 for a in arrs] or [0], dtype=np.int64)
            fn(n, ptrs, S.ctypes.data, C.ctypes.data, U80, V.ctypes.data, R.ctypes.data)
        return V, R


    # --- compensated float64: the tail of the points whose float64 bound is too large --------
    def _comp_key(self, varying: Sequence[bool], outputs: Sequence[int] | None) -> tuple:
        outs = tuple(range(self.n_out)) if outputs is None else tuple(int(j) for j in outputs)
        return ("comp", tuple(bool(x) for x in varying), outs)

    def compiled_compensated(self, varying: Sequence[bool], outputs: Sequence[int] | None = None) -> Callable:
        """The compiled compensated loop for ``varying`` and ``outputs`` (default all; a ctypes
        function), compiled on first use."""
        key = self._comp_key(varying, outputs)
        with self._lock:
            if key not in self._fn64:
                self._fn64[key] = _jit(self.ir_compensated(*key[1:]), extended=True)
        return self._fn64[key][0]

    def compensated_ready(self, varying: Sequence[bool], outputs: Sequence[int] | None = None) -> bool:
        """Whether :meth:`compensated` for ``varying`` and ``outputs`` costs no compilation
        (compiled in this process, or its object file is in the disk cache)."""
        key = self._comp_key(varying, outputs)
        with self._lock:
            if key in self._fn64:
                return True
            path = self._paths.get(key, False)
        if path is False:
            try:
                path = _object_path(self.ir_compensated(*key[1:]))
            except Exception:
                path = None
            self._paths[key] = path      # writing the IR takes ~10 ms: once per process
        return path is not None and path.exists()

    def compensated(self, *vals, outputs: Sequence[int] | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The program in float64 with its own rounding errors added back (x86 only).

        Every operation's rounding error δ_t is computed — exactly for +, −, ×, x² (error-free
        transformations: TwoSum, TwoProd with a fused multiply-add), from exact fma residuals for
        1/x and √x, in double-double for integer powers, in x87 extended precision for library
        functions and fractional powers — and the first-order correction Σ_t (∂out/∂t) δ_t is
        added to the value (Langlois 2001).  Its bound: what the corrections leave (their own
        errors), an allowance of 2^-10 of Σ|∂out/∂t·δ_t| for the float64 sensitivities, and
        2^10·b²/|value| for the second-order terms, b the first-order bound of the uncorrected
        value — so about ten more digits than float64 where the float64 bound is large because
        of cancelling terms.

        Parameters
        ----------
        *vals : float or array_like
            One value per input, as for calling the kernel.
        outputs : sequence of int, optional
            Which outputs to compute (default all).

        Returns
        -------
        values, rel_bound : numpy.ndarray
            Shape ``(len(outputs), n)``.

        References
        ----------
        Langlois, P. (2001), "Automatic linear correction of rounding errors", BIT 41(3), 515–539.
        Ogita, T., Rump, S. M., Oishi, S. (2005), "Accurate sum and dot product", SIAM J. Sci.
        Comput. 26(6), 1955–1988 (TwoSum, TwoProd).
        """
        arrs = [_flat(v) for v in vals]
        n = max((a.size for a in arrs), default=1)
        if any(a.size not in (1, n) for a in arrs):
            raise ValueError("inputs must have one element or a common length")
        key = self._comp_key([a.size > 1 for a in arrs], outputs)
        fn = self.compiled_compensated(*key[1:])
        n_out = len(key[2])
        C = np.array([float(c) for c in self.consts] or [0.0], dtype=np.float64)
        D = np.array([float(Fraction(int(c.p), int(c.q)) - Fraction(float(c))) for c in self.consts] or [0.0])
        if n == 0:
            return np.empty((n_out, 0)), np.empty((n_out, 0))
        size = n
        lanes = loop_lanes()
        if n % lanes:
            n = n + lanes - n % lanes
            arrs = [a if a.size == 1 else np.concatenate([a, np.full(n - size, a[-1])]) for a in arrs]
        V = np.empty((n_out, n))
        R = np.empty((n_out, n))
        ptrs = (ctypes.c_void_p * len(arrs))(*[a.ctypes.data for a in arrs])
        fn(n, ptrs, C.ctypes.data, D.ctypes.data, U64, V.ctypes.data, R.ctypes.data)
        return V[:, :size], R[:, :size]

def _flat(v) -> np.ndarray:
    """A contiguous float64 vector; an array broadcast from one value (all strides 0) as that value."""
    a = np.asarray(v, dtype=np.float64)
    if a.ndim and a.size and not any(a.strides):
        return np.ascontiguousarray(a.reshape(-1)[:1])
    return np.ascontiguousarray(np.ravel(a))


def _refine(V, R, bad, todo, Vt, Rt, tol, rows: Sequence[int] | None = None) -> None:
    """Take the refined values ``Vt``, ``Rt`` of outputs ``rows`` (default all) at points
    ``todo`` where they are better proven."""
    for i, j in enumerate(range(V.shape[0]) if rows is None else rows):
        use = bad[j, todo] & (Rt[i] < R[j, todo])
        V[j, todo] = np.where(use, Vt[i], V[j, todo])
        R[j, todo] = np.where(use, Rt[i], R[j, todo])
        bad[j, todo] = ~(Rt[i] <= tol) & bad[j, todo]


def _subset(vals: Sequence, varying: Sequence[bool], idx: np.ndarray) -> list[np.ndarray]:
    """The inputs at points ``idx`` (an input that does not vary: its one value)."""
    return [np.ravel(v)[idx] if vary else np.array([np.asarray(v, dtype=np.float64).flat[0]])
            for v, vary in zip(vals, varying)]


def evaluate_proven(kernel: BoundedKernel, vals: Sequence, tol: float, workers: int = 1,
                    sign_only: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Values of ``kernel``'s outputs, each proven to ``tol`` relative where possible.

    float64 first (compiled); points whose bound exceeds ``tol`` are refined by the
    compensated float64 program (:meth:`BoundedKernel.compensated`), then what is still
    unproven again in long double with its own bound (both when the platform's long double is
    the x87 extended type).  The float64 and compensated programs run as one loop
    (:meth:`BoundedKernel.fused`): over all points when it is compiled already (in this
    process, or from the disk cache for at least :data:`COMPENSATED_CACHED_MIN_POINTS`
    points), else over the doubtful points of the float64 loop when there are at least
    :data:`COMPENSATED_MIN_POINTS` of them (compiling it).  The first two
    outputs are taken to be k_c and ω_c²: a point where either is negative beyond doubt has no
    Hopf point and is not refined.

    Parameters
    ----------
    kernel : BoundedKernel
    vals : sequence of float or array_like
        The kernel's inputs.
    tol : float
        The relative accuracy to prove.
    workers : int, optional
        Threads for the float64 loop.
    sign_only : bool, optional
        A value whose sign is proven (bound below 1/2) counts as proven.

    Returns
    -------
    values : numpy.ndarray
        Shape ``(n_outputs, n)`` (float64).
    unproven : numpy.ndarray of bool
        Where the value is not proven to ``tol`` (the caller evaluates those another way).
    """
    varying = [np.size(v) > 1 and any(np.asarray(v).strides) for v in vals]
    n = max((np.size(v) for v in vals), default=1)
    fuse = COMPENSATE and EXTENDED and (kernel.fused_ready(varying, compiled_only=True) or (
        n >= COMPENSATED_CACHED_MIN_POINTS and kernel.fused_ready(varying)))
    # with the fused loop at hand: float64 and, for the groups of points it leaves doubtful,
    # the compensated pass in one loop over all points
    V, R = kernel.fused(*vals, tol=tol, workers=workers) if fuse else kernel(*vals, workers=workers)
    bad = ~(R <= tol)
    no_hopf = np.zeros(V.shape[1], dtype=bool)
    for j in range(min(2, V.shape[0])):
        no_hopf |= (V[j] < 0) & (R[j] < 0.5)
    todo = np.flatnonzero(bad.any(axis=0) & ~no_hopf)
    if not (todo.size and EXTENDED) or fuse:
        pass
    elif COMPENSATE and todo.size >= COMPENSATED_MIN_POINTS:
        # the doubtful points again through the fused loop (compiled now): the same float64
        # values, compensated where doubtful
        # (one doubtful point is taken twice: the loop compiled for varying inputs serves it)
        idx = todo if todo.size > 1 else np.repeat(todo, 2)
        Vc, Rc = kernel.fused(*_subset(vals, varying, idx), tol=tol, workers=workers)
        V[:, todo], R[:, todo] = Vc[:, :todo.size], Rc[:, :todo.size]
        bad[:, todo] = ~(R[:, todo] <= tol)
        todo = np.flatnonzero(bad.any(axis=0) & ~no_hopf)
    if todo.size and EXTENDED:
        Ve, Re = kernel.extended(*_subset(vals, varying, todo))
        _refine(V, R, bad, todo, Ve.astype(np.float64), Re, tol)
    if sign_only:
        bad &= ~(R < 0.5)
    bad[:, no_hopf] = False
    return V, bad


# --------------------------------------------------------------------------------------------
def _target_machine():
    """A new target machine for the host CPU (an execution engine owns the one it is given)."""
    import llvmlite.binding as llvm

    llvm.initialize_native_target()
    llvm.initialize_native_asmprinter()
    target = llvm.Target.from_default_triple()
    return target.create_target_machine(cpu=llvm.get_host_cpu_name(), features=llvm.get_host_cpu_features().flatten(),
                                        opt=2)


def _jit(ir: str, extended: bool = False, doubles: int = 1):
    """Compile ``ir`` (function ``kernel``) to machine code, the object file cached on disk."""
    import llvmlite.binding as llvm

    tm = _target_machine()
    mod = llvm.parse_assembly(ir)
    mod.verify()
    path = _object_path(ir, tm.triple)
    if path is None or not path.exists():
        # optimise only what will be compiled: on a cache hit the engine loads the object file
        # and never generates code from the module
        pto = llvm.create_pipeline_tuning_options(speed_level=2)
        pto.loop_vectorization = True
        pto.slp_vectorization = True
        pb = llvm.create_pass_builder(tm, pto)
        pb.getModulePassManager().run(mod, pb)
    engine = llvm.create_mcjit_compiler(mod, tm)

    def notify(_module, buffer: bytes) -> None:
        if path is not None:
            try:
                from landau.io import atomic_write

                atomic_write(path, lambda f: f.write(buffer), mode="wb")
            except OSError:
                pass

    def getbuffer(_module):
        if path is not None and path.exists():
            try:
                return path.read_bytes()
            except OSError:
                return None
        return None

    engine.set_object_cache(notify, getbuffer)
    engine._landau_keep = (notify, getbuffer, tm)     # alive as long as the engine
    engine.finalize_object()
    addr = engine.get_function_address("kernel")
    ptrs = 3 if extended else 2
    proto = ctypes.CFUNCTYPE(None, ctypes.c_int64, *[ctypes.c_void_p] * ptrs, *[ctypes.c_double] * doubles,
                             ctypes.c_void_p, ctypes.c_void_p)
    return proto(addr), engine


def _object_path(ir: str, triple: str | None = None):
    """Where the object file compiled from ``ir`` for this machine is kept (None: no disk cache)."""
    import llvmlite.binding as llvm

    if triple is None:
        triple = llvm.get_default_triple()
    key = hashlib.sha256((ir + triple + str(llvm.get_host_cpu_name())).encode()).hexdigest()[:32]
    return _cache_path(key)


def _cache_path(key: str):
    from landau import cache

    if not cache.enabled():
        return None
    try:
        folder = cache.cache_dir() / "kernels"
        folder.mkdir(parents=True, exist_ok=True, mode=0o700)
    except OSError:
        return None
    return folder / f"bounded_{key}.o"
