"""Exact derivatives of a system's right-hand side at its equilibrium, built lazily.

``Jets(system).order(n)`` builds the n-th derivative tensor of f at y₀ the first time it
is asked for and caches it; :attr:`Jets.built` records which orders were actually built,
so a caller asking only for k_c and ω_c can be shown never to build second or third
derivatives.  Tensors are stored sparsely over sorted index tuples.

Each non-trivial derivative value is replaced by an opaque real *atom* symbol
(``d_u_phi``, …) whose definition is kept in :attr:`Jets.atoms`.  The engine works on
atoms — small rational expressions, exactly the paper's "in terms of F_V, G_φ, …"
formulas (15)–(21) — and the atoms are substituted (for closed forms) or evaluated
first (for compiled code) only at the end.  This is what keeps derivation fast.
"""

from __future__ import annotations

import itertools
from typing import Any, Callable, Mapping, Sequence

import sympy as sp

from landau.support.cx import Cx, as_expr, cx_is_zero
from landau.systems.system import DynamicalSystem


def _is_simple(expr: sp.Expr) -> bool:
    return expr.is_Number or expr.is_Symbol or (expr.is_Mul and len(expr.args) == 2 and expr.args[0].is_Number
                                                and expr.args[1].is_Symbol)


class Jets:
    """Lazy, cached derivative tensors of f at the equilibrium, in atom symbols."""

    def __init__(self, system: DynamicalSystem):
        self.system = system
        self.n = len(system.states)
        self._at = dict(zip(system.states, system.equilibrium, strict=True))
        self._cache: dict[int, dict[tuple[int, ...], sp.Expr]] = {}
        self._param: tuple | None = None
        self.atoms: dict[sp.Symbol, sp.Expr] = {}
        self.built: list[int] = []

    def _atom(self, name: str, value: sp.Expr) -> sp.Expr:
        if value == 0:
            return sp.Integer(0)
        if _is_simple(value) or self.system.parameter in value.free_symbols:
            return value
        sym = sp.Symbol(name, real=True)
        self.atoms[sym] = value
        return sym

    def order(self, n: int) -> dict[tuple[int, ...], sp.Expr]:
        """{(i, j₁ ≤ … ≤ jₙ): ∂ⁿfᵢ/∂y_{j₁}…∂y_{jₙ} at y₀} (atoms), zero entries omitted."""
        if n in self._cache:
            return self._cache[n]
        ys = self.system.states
        out: dict[tuple[int, ...], sp.Expr] = {}
        for i, f in enumerate(self.system.rhs):
            for idx in itertools.combinations_with_replacement(range(self.n), n):
                if not all(ys[j] in f.free_symbols for j in set(idx)):
                    continue
                val = sp.diff(f, *[ys[j] for j in idx]).subs(self._at)
                name = f"d{n}_{ys[i].name}_" + "_".join(ys[j].name for j in idx)
                atom = self._atom(name, val)
                if atom != 0:
                    key = (i, *idx)
                    out[key] = atom
        self._cache[n] = out
        self.built.append(n)
        return out

    def jacobian(self) -> list[list[sp.Expr]]:
        J = [[sp.Integer(0)] * self.n for _ in range(self.n)]
        for (i, j), val in self.order(1).items():
            J[i][j] = val
        return J

    def parameter_derivatives(self) -> tuple[list[sp.Expr], list[list[sp.Expr]]]:
        """(∂f/∂p, ∂J/∂p) at the equilibrium: the unfolding of the Hopf point."""
        if self._param is None:
            p = self.system.parameter
            ys = self.system.states
            fp = [self._atom(f"dp_{ys[i].name}", sp.diff(f, p).subs(self._at)) for i, f in enumerate(self.system.rhs)]
            Jp = [[self._atom(f"dp_{ys[i].name}_{y.name}", sp.diff(f, p, y).subs(self._at)) for y in ys]
                  for i, f in enumerate(self.system.rhs)]
            self._param = (fp, Jp)
        return self._param

    def expand_atoms(self, expr: sp.Expr) -> sp.Expr:
        """Replace atoms by their definitions."""
        return expr.xreplace(self.atoms)


def multilinear(tensor: Mapping[tuple[int, ...], Any], vectors: Sequence[Sequence[Cx]], n: int,
                convert: Callable[[Any], Any] = lambda x: x) -> list[Cx]:
    """Σ over all index orderings of D[i, j₁…jₘ] a¹_{j₁}…aᵐ_{jₘ} (symmetric multilinear form)."""
    out = [Cx(0, 0) for _ in range(n)]
    for key, val in tensor.items():
        i, idx = key[0], key[1:]
        val = convert(val)
        for perm in set(itertools.permutations(idx)):
            term: Cx | None = None
            for slot, j in enumerate(perm):
                comp = vectors[slot][j]
                if cx_is_zero(comp):
                    term = None
                    break
                term = comp if term is None else term * comp
            if term is not None:
                out[i] = out[i] + term * val
    return out


# --- numeric jets by truncated multivariate Taylor arithmetic ---------------------------------------
#
# A series in the variables δ₀…δ_{m−1} truncated at total degree K is a list ``s`` of K + 1 dicts,
# ``s[d]`` = {sorted index tuple of length d: coefficient}.  The coefficient of the monomial
# δ_{j₁}…δ_{j_d} (j₁ ≤ … ≤ j_d) is ∂^d f/∂y_{j₁}…∂y_{j_d} divided by the product of the factorials
# of the index multiplicities.  Evaluating the expression tree of f once in this arithmetic gives
# every derivative tensor up to order K at the point — no symbolic differentiation, so the cost
# grows like the number of monomials (n^K/K!) times the size of f instead of the symbolic n^K
# derivatives of ever larger expressions.


def _merge(a: tuple, b: tuple) -> tuple:
    return tuple(sorted(a + b)) if a and b else (a or b)


class _Series:
    __slots__ = ("c", "K")

    def __init__(self, coeffs: list, K: int):
        self.c = coeffs
        self.K = K

    @classmethod
    def const(cls, value, K: int) -> "_Series":
        return cls([{(): value}] + [{} for _ in range(K)], K)

    @property
    def value(self):
        return self.c[0].get((), 0)

    def is_const(self) -> bool:
        return not any(self.c[d] for d in range(1, self.K + 1))

    def __add__(self, o: "_Series") -> "_Series":
        out = [dict(d) for d in self.c]
        for d in range(self.K + 1):
            od = out[d]
            for k, v in o.c[d].items():
                od[k] = od[k] + v if k in od else v
        return _Series(out, self.K)

    def scale(self, s) -> "_Series":
        return _Series([{k: v * s for k, v in d.items()} for d in self.c], self.K)

    def __mul__(self, o: "_Series") -> "_Series":
        if o.is_const():
            return self.scale(o.value)
        if self.is_const():
            return o.scale(self.value)
        K = self.K
        out: list[dict] = [{} for _ in range(K + 1)]
        for d1 in range(K + 1):
            a = self.c[d1]
            if not a:
                continue
            for d2 in range(K + 1 - d1):
                b = o.c[d2]
                if not b:
                    continue
                od = out[d1 + d2]
                for k1, v1 in a.items():
                    for k2, v2 in b.items():
                        k = _merge(k1, k2)
                        od[k] = od[k] + v1 * v2 if k in od else v1 * v2
        return _Series(out, K)

    def compose(self, derivs: Sequence) -> "_Series":
        """g(self) from derivs[k] = g⁽ᵏ⁾(self.value), k = 0…K."""
        K = self.K
        h = _Series([{}] + [dict(d) for d in self.c[1:]], K)
        out = _Series.const(derivs[0], K)
        power = None
        fact = 1
        for k in range(1, K + 1):
            power = h if power is None else power * h
            fact *= k
            if derivs[k] != 0:
                out = out + power.scale(derivs[k] / fact)
        return out


def _unary_derivatives(func, x, K: int, as_float: bool):
    """g⁽ᵏ⁾(x), k = 0…K, for the common elementary functions without symbolic differentiation (else None)."""
    import math

    import mpmath

    lib = math if as_float else mpmath
    if func is sp.exp:
        e = lib.exp(x)
        return [e] * (K + 1)
    if func is sp.log:
        out = [lib.log(x)]
        fact = 1
        for k in range(1, K + 1):
            out.append((-1) ** (k - 1) * fact / x ** k)
            fact *= k
        return out
    if func in (sp.sin, sp.cos):
        s, c = lib.sin(x), lib.cos(x)
        cyc = [s, c, -s, -c] if func is sp.sin else [c, -s, -c, s]
        return [cyc[k % 4] for k in range(K + 1)]
    if func in (sp.sinh, sp.cosh):
        s, c = lib.sinh(x), lib.cosh(x)
        cyc = [s, c] if func is sp.sinh else [c, s]
        return [cyc[k % 2] for k in range(K + 1)]
    if func is sp.tanh:
        # dᵏ tanh/dxᵏ = Pₖ(t), t = tanh x, P₀ = t, Pₖ₊₁ = Pₖ'(t)(1 − t²)
        t = lib.tanh(x)
        poly = [0, 1]  # coefficients of P in powers of t
        out = []
        for _ in range(K + 1):
            out.append(sum(c * t ** i for i, c in enumerate(poly)))
            d = [i * c for i, c in enumerate(poly)][1:]
            nxt = [0] * (len(d) + 2)
            for i, c in enumerate(d):
                nxt[i] += c
                nxt[i + 2] -= c
            poly = nxt
        return out
    return None


class TaylorJets:
    """Every derivative of f up to total order K at a point, by Taylor arithmetic on the expression tree.

    Parameters
    ----------
    exprs : sequence of sympy expressions
        The components of f.
    variables : sequence of sympy symbols
        The variables to differentiate in (states, and the Hopf parameter where its derivatives
        are wanted); every other free symbol must get a value in :meth:`at`.
    order : int
        Highest total derivative order K.

    Notes
    -----
    Elementary functions are expanded through their derivatives at the current value (computed
    symbolically once per function and order, then evaluated), so any smooth sympy function
    works; non-smooth ones (``Abs``, ``Piecewise``, ``sign``) are rejected.  Numbers are mpmath
    numbers at the caller's working precision.
    """

    _unary_cache: dict = {}

    def __init__(self, exprs: Sequence[sp.Expr], variables: Sequence[sp.Symbol], order: int):
        from landau.errors import InputError

        self.variables = tuple(variables)
        self.K = int(order)
        exprs = [as_expr(e) for e in exprs]
        for e in exprs:
            bad = e.atoms(sp.Piecewise, sp.Abs, sp.sign, sp.Heaviside, sp.Min, sp.Max, sp.floor, sp.ceiling)
            if bad:
                raise InputError(f"Taylor jets need a smooth right-hand side; found {sorted(map(str, bad))[0]}")
        self.replacements, self.reduced = sp.cse(exprs)
        self.free = sorted(set().union(*(e.free_symbols for e in exprs)) - set(self.variables), key=lambda s: s.name)
        self._build_tape()

    def _unary(self, func, x):
        fast = _unary_derivatives(func, x, self.K, self._float)
        if fast is not None:
            return fast
        key = (func, self.K, self._float)
        fns = self._unary_cache.get(key)
        if fns is None:
            t = sp.Dummy("t")
            fns = [sp.lambdify(t, sp.diff(func(t), t, k), "math" if self._float else "mpmath")
                   for k in range(self.K + 1)]
            self._unary_cache[key] = fns
        return [self._num(f(x)) for f in fns]

    def _compile(self, e: sp.Expr, slots: dict, tape: list) -> int:
        """Append the instructions computing ``e`` to ``tape``; returns its register."""
        from landau.errors import InputError

        if e in slots:
            return slots[e]
        ins: tuple[Any, ...]   # (operation, operands...)
        if e.is_Number or e.is_NumberSymbol:
            ins = ("const", e)
        elif e.is_Add or e.is_Mul:
            ins = ("add" if e.is_Add else "mul", [self._compile(a, slots, tape) for a in e.args])
        elif e.is_Pow:
            base, ex = e.args
            b = self._compile(base, slots, tape)
            if ex.is_Integer and ex >= 0:
                ins = ("powint", b, int(ex))
            elif not (ex.free_symbols & set(self.variables)) and not ex.free_symbols:
                ins = ("powconst", b, ex)
            else:
                ins = ("powgen", b, self._compile(ex, slots, tape))
        elif isinstance(e, sp.Function) and len(e.args) == 1:
            ins = ("func", e.func, self._compile(e.args[0], slots, tape))
        elif e.is_Symbol:
            raise InputError(f"Taylor jets: no value for {e}")
        else:
            raise InputError(f"Taylor jets: cannot expand {type(e).__name__} ({e})")
        tape.append(ins)
        slots[e] = len(tape) - 1
        return slots[e]

    def _build_tape(self) -> None:
        slots: dict = {}
        tape: list = []
        for j, v in enumerate(self.variables):
            tape.append(("var", j))
            slots[v] = len(tape) - 1
        for s in self.free:
            tape.append(("value", s))
            slots[s] = len(tape) - 1
        for sym, e in self.replacements:
            slots[sym] = self._compile(e, slots, tape)
        self.outputs = [self._compile(e, slots, tape) for e in self.reduced]
        self.tape = tape

    def _run(self, seeds: list, values: dict) -> list:
        import mpmath

        K = self.K
        reg: list = []
        num = self._num
        for ins in self.tape:
            op = ins[0]
            if op == "var":
                r = seeds[ins[1]]
            elif op == "value":
                r = _Series.const(num(values[ins[1]]), K)
            elif op == "const":
                e = ins[1]
                if self._float:
                    r = _Series.const(float(e), K)
                elif e.is_Rational:
                    r = _Series.const(mpmath.mpf(e.p) / e.q, K)
                else:
                    r = _Series.const(mpmath.mpf(str(sp.N(e, mpmath.mp.dps + 5))), K)
            elif op == "add":
                r = reg[ins[1][0]]
                for a in ins[1][1:]:
                    r = r + reg[a]
            elif op == "mul":
                r = reg[ins[1][0]]
                for a in ins[1][1:]:
                    r = r * reg[a]
            elif op == "powint":
                b, n = reg[ins[1]], ins[2]
                r = _Series.const(num(1), K)
                sq = b
                while n:
                    if n & 1:
                        r = r * sq
                    n >>= 1
                    if n:
                        sq = sq * sq
            elif op == "powconst":
                b = reg[ins[1]]
                ex = ins[2]
                rr = float(ex) if self._float else (mpmath.mpf(ex.p) / ex.q if ex.is_Rational
                                                    else mpmath.mpf(str(sp.N(ex, mpmath.mp.dps + 5))))
                v = b.value
                derivs = []
                coef = num(1)
                for k in range(K + 1):
                    derivs.append(coef * (v ** (rr - k) if self._float else mpmath.power(v, rr - k)))
                    coef *= (rr - k)
                r = b.compose(derivs)
            elif op == "powgen":  # b**x = exp(x log b)
                b, x = reg[ins[1]], reg[ins[2]]
                lg = b.compose(self._unary(sp.log, b.value))
                arg = x * lg
                r = arg.compose(self._unary(sp.exp, arg.value))
            else:  # func
                a = reg[ins[2]]
                r = a.compose(self._unary(ins[1], a.value))
            reg.append(r)
        return [reg[i] for i in self.outputs]

    _float = False

    def _num(self, x):
        import mpmath

        return float(x) if self._float else mpmath.mpmathify(x)

    def at(self, point: Sequence, values: dict | None = None, directions: Sequence[Sequence] | None = None,
           left=None, as_float: bool = False) -> dict[int, dict[tuple[int, ...], object]]:
        """Derivative tensors {order m: {(i, j₁ ≤ … ≤ j_m): ∂ᵐ fᵢ/∂x_{j₁}…∂x_{j_m}}} at ``point``.

        Parameters
        ----------
        point : sequence of numbers
            Values of :attr:`variables`.
        values : dict, optional
            Values of the other free symbols (by symbol).
        directions : matrix, optional
            Differentiate along x = point + R·δ instead of x = point + δ (R given as rows).
        left : matrix, optional
            Left-multiply f by this matrix (rows) before taking the tensors.
        as_float : bool
            Compute in float64 instead of mpmath numbers (fast Jacobians for scans).
        Order 0 holds f itself under the key (i,).
        """
        import math

        self._float = bool(as_float)
        K = self.K
        m = len(self.variables)
        for s in self.free:
            if values is None or s not in values:
                from landau.errors import InputError

                raise InputError(f"Taylor jets: no value for {s.name}")
        seeds = []
        for j, x0 in enumerate(point):
            c: list[dict[tuple[int, ...], Any]] = [{} for _ in range(K + 1)]
            c[0][()] = self._num(x0)
            if K >= 1:
                if directions is None:
                    c[1] = {(j,): self._num(1)}
                else:
                    c[1] = {(k,): directions[j][k] for k in range(m) if directions[j][k] != 0}
            seeds.append(_Series(c, K))
        outs = self._run(seeds, values or {})
        if left is not None:
            comb = []
            for i in range(len(outs)):
                acc = None
                for k, s in enumerate(outs):
                    if left[i][k] != 0:
                        t = s.scale(left[i][k])
                        acc = t if acc is None else acc + t
                comb.append(acc if acc is not None else _Series.const(self._num(0), K))
            outs = comb
        tens: dict[int, dict[tuple[int, ...], object]] = {d: {} for d in range(K + 1)}
        for i, s in enumerate(outs):
            for d in range(K + 1):
                for key, v in s.c[d].items():
                    if v == 0:
                        continue
                    mult = 1
                    for j in set(key):
                        mult *= math.factorial(key.count(j))
                    full = (i, *key)
                    tens[d][full] = v * mult
        return tens
