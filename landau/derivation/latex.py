"""What a derivation prints: the amplitude equation's coefficients as a paper writes them.

The documents of ``landau derive --latex`` (:func:`derivation_latex`) and the LaTeX of one
coefficient (:func:`coefficient_latex`, behind ``Coefficient.latex()``): per coefficient the
closed form in V and the law's parameters where the law's derivatives at steady sliding are
rational (Putelat, Dawes & Willis 2010, eqs 7–8 and 15–23), otherwise the form in those
derivatives.  Built from the printing primitives of :mod:`landau.report.latex`.
"""

from __future__ import annotations

from typing import Sequence

import sympy as sp

from landau.report.latex import (
    Equation,
    Namer,
    align_block,
    document,
    equation_lines,
    escape_text,
    law_equations,
    straight_line,
    symbol_latex,
    units_latex,
)

_CONVENTION = (r"\frac{d|A|}{dT} &= \frac{\Gamma |A| + \Lambda |A|^3}{2}, \qquad "
               r"\frac{d\theta}{dT} = \frac{\Omega + \chi |A|^2}{2}, \\ "
               r"\Gamma &= -2\bar\Gamma\,\frac{k-k_c}{\varepsilon^2}, \qquad "
               r"\Omega = 2\bar\Omega\,\frac{k-k_c}{\varepsilon^2}")


def derivation_latex(d, quantities: Sequence[str], fragment: bool = False, progress=None) -> str:
    """The amplitude equation of a :class:`~landau.derivation.multiscale.Derivation` as LaTeX.

    Per coefficient: the closed form in V and the law's parameters where the law's
    derivatives at steady sliding are rational (the factored fraction, ω_c kept as a symbol
    with ω_c² given); otherwise the form in those derivatives (defined in a table of their
    own closed forms), labelled as such.  When the Hopf line has no closed form (several
    state variables) k_c and ω_c are said to be numerical, with the Hopf polynomial they
    solve.

    Parameters
    ----------
    d : landau.derivation.multiscale.Derivation
    quantities : names from :data:`landau.derivation.multiscale.QUANTITIES`.
    fragment : only the equations (for ``\\input``), no preamble.
    progress : callable(str) or None, called before each expensive step.

    Returns
    -------
    str
        The LaTeX source.
    """
    from landau.support import cache

    law = d.block.law
    key = cache.make_key("derivation-latex", cache.system_key(d.system), law.name, law.source,
                         sp.srepr((law.mu, law.states, law.rates)), list(quantities), fragment)
    return cache.cached("derivation-latex", key, lambda: _derivation_latex(d, quantities, fragment, progress))


def _derivation_latex(d, quantities: Sequence[str], fragment: bool, progress) -> str:
    from landau.derivation.linear import w as omega
    from landau.derivation.multiscale import QUANTITIES, UNITS
    from landau.support.progress import progress as bar

    law = d.block.law
    pbar = bar(total=len(quantities) + 1, desc=f"LaTeX {law.name}", unit="step")

    def step(msg: str) -> None:
        pbar.set_description_str(f"LaTeX {law.name}: {msg}")
        if progress:
            progress(msg)
    kc_sym, om_sym = sp.Symbol("k_c", positive=True), sp.Symbol("omega_c", positive=True)
    names: dict = {kc_sym: "k_c", om_sym: r"\omega_c"}
    body: list[str] = []
    text = lambda s: body.append(s)
    src = f" ({escape_text(law.source)})" if law.source else ""
    text(rf"Friction law{src}, slip rate $v$, state variables "
         + ", ".join(f"${symbol_latex(s.name)}$" for s in law.states) + ":")
    text(align_block(law_equations(law)))
    text(r"Spring--block (Putelat et al.\ 2010, eq.~4) driven at velocity $V$, stiffness $k$, mass $M$, "
         r"normal load $\sigma$. Amplitude equation (Putelat et al.\ 2010, eq.~20):")
    text(r"\begin{align*}" + "\n" + _CONVENTION + "\n" + r"\end{align*}")
    text(r"$\Lambda<0$: supercritical, $\Lambda>0$: subcritical; slip amplitude "
         r"$\max|x-x_0| \approx C\sqrt{|k_c-k|}$, $C = 2\sqrt{2\bar\Gamma/|\Lambda|}$ (eq.~23).")

    for q in quantities:
        d.coefficient(q)
    numeric_hopf = d.hopf.closed_form is None
    rational = not numeric_hopf and _rational_in_parameters(d)
    parts = None
    if rational:
        step("closed forms in V and the parameters")
        parts = _cached_parts(d, [q for q in quantities if q not in ("kc", "omega_c", "C")])

    atoms = d.jets.atoms
    ys = ", ".join(symbol_latex(s.name) for s in d.system.states)
    if parts is None:
        text(r"\subsection*{Derivatives at steady sliding}")
        text(rf"$f_{{i,jk\dots}} = \partial^n f_i/\partial y_j\partial y_k\cdots$ at steady sliding, where "
             rf"$E\dot y = f(y)$ is the spring--block in $y = ({ys})$ (slip $X = x - x_0(t)$, $u = \dot x - V$) "
             r"and $f_{i,k}$ is the derivative with respect to $k$:")
        eqs = []
        for a in sorted(atoms, key=lambda s: s.name):
            eqs += equation_lines(symbol_latex(a.name), atoms[a], names, letter="A")
        text(align_block(eqs) if eqs else r"(none)")
        if d.system.unknowns:
            text("The steady state " + ", ".join(f"${symbol_latex(u.name)}$" for u in d.system.unknowns)
                 + " has no closed form: it is solved numerically.")

    text(r"\subsection*{Coefficients}")
    if numeric_hopf:
        H, re_pq, q2 = d.hopf._hopf_polys
        Wsym = sp.Symbol("W")
        text(rf"The Hopf line has no closed form ({_why_numeric(d)}): $k_c$ and $\omega_c$ are computed "
             r"numerically. $\omega_c^2$ is the positive root $W$ of the Hopf polynomial below at which the "
             r"stiffness $k = -\mathrm{Re}(P\bar Q)/|Q|^2$ is largest ($\det(\lambda E - J) = P(\lambda) + k "
             r"Q(\lambda)$, "
             r"$\lambda = i\omega$):")
        text(align_block(equation_lines("0", H.as_expr().xreplace({d.hopf._hopf_polys[0].gen: Wsym}), names,
                                        letter="H")))
    for q in quantities:
        pbar.update(1)
        sym = QUANTITIES[q][0]
        label = rf"{_DESCRIPTIONS[q]} (Putelat et al.\ 2010, {_EQUATIONS[q]}), units ${units_latex(UNITS[q])}$"
        if q in ("kc", "omega_c"):
            if numeric_hopf:
                continue
            text(rf"\paragraph{{}}{label}:")
            kc, W = (parts["kc"], parts["W"]) if parts else d.hopf.closed_form
            if q == "kc":
                text(align_block(equation_lines("k_c", kc, names, letter="K")))
            else:
                text(align_block(equation_lines(r"\omega_c^2", W, names, letter="W")))
            continue
        if q == "C":
            text(rf"\paragraph{{}}{label}: $C = 2\sqrt{{2\bar\Gamma/|\Lambda|}}$.")
            continue
        if parts is not None and q in parts:
            P, Q = parts[q]
            e = P + om_sym * Q if Q != 0 else P
            text(rf"\paragraph{{}}{label}, closed form in $V$ and the law's parameters:")
            step(f"typesetting {q}")
            text(align_block(equation_lines(sym, e, names, letter=_letter(q))))
            continue
        form = d.coefficient(q).formula.xreplace({omega: om_sym, d.k: kc_sym})
        where = (r"with $k_c$, $\omega_c$ from the Hopf polynomial" if numeric_hopf else
                 r"with $k_c$, $\omega_c$ above")
        text(rf"\paragraph{{}}{label}, in terms of the derivatives at steady sliding ({where}); "
             r"intermediate quantities $q_j$ first:")
        step(f"common subexpressions of {q}")
        reps, red = straight_line(form)
        loc = dict(names)
        eqs = []
        for i, (s, _e) in enumerate(reps, 1):
            loc[s] = rf"q_{{{i}}}"
        namer = Namer(_letter(q))
        for s, e in reps:
            eqs += equation_lines(loc[s], e, loc, namer=namer)
        eqs += equation_lines(sym, red, loc, namer=namer)
        text(align_block(eqs))
    pbar.close()
    return document(f"Amplitude equation: {law.name}", body, fragment)


_DESCRIPTIONS = {"kc": "Critical stiffness", "omega_c": "Angular frequency at onset",
                 "Gamma_bar": r"Linear growth rate per unit $k_c - k$",
                 "Omega_bar": r"Linear frequency shift per unit $k - k_c$", "Lambda": "Landau coefficient",
                 "chi": "Nonlinear frequency coefficient", "C": r"Slip amplitude per $\sqrt{|k_c - k|}$"}
_EQUATIONS = {"kc": "eq.~7", "omega_c": "eq.~8", "Gamma_bar": "eqs 18, 21", "Omega_bar": "eqs 18, 21",
              "Lambda": "eqs 15--21", "chi": "eqs 15--21", "C": "eq.~23"}


def _coefficient_rows(d, q: str, names: dict, parts: dict | None) -> tuple[list[Equation], str]:
    """The equations of one coefficient and what they are ("closed form" or "derivatives")."""
    from landau.derivation.linear import w as omega
    from landau.derivation.multiscale import QUANTITIES

    sym = QUANTITIES[q][0]
    kc_sym, om_sym = sp.Symbol("k_c", positive=True), sp.Symbol("omega_c", positive=True)
    names.setdefault(kc_sym, "k_c")
    names.setdefault(om_sym, r"\omega_c")
    if parts is not None and q in parts:
        P, Q = parts[q]
        return equation_lines(sym, P + om_sym * Q if Q != 0 else P, names, letter=_letter(q)), "closed form"
    form = d.coefficient(q).formula.xreplace({omega: om_sym, d.k: kc_sym})
    reps, red = straight_line(form)
    loc = dict(names)
    for i, (s, _) in enumerate(reps, 1):
        loc[s] = rf"q_{{{i}}}"
    namer = Namer(_letter(q))
    eqs = equation_lines(sym, red, loc, namer=namer)
    for s, e in reps:
        eqs += equation_lines(loc[s], e, loc, namer=namer)
    return eqs, "derivatives"


def coefficient_latex(coefficient) -> str:
    """One coefficient as an ``aligned`` block: the closed form in V and the parameters
    (with ω_c²) where the law's derivatives at steady sliding are rational, else the form in
    those derivatives followed by their definitions.  Cached on disk (:mod:`landau.support.cache`)."""
    from landau.support import cache

    d, q = coefficient.derivation, coefficient.name
    key = cache.make_key("coefficient-latex", cache.system_key(d.system), q)
    return cache.cached("coefficient-latex", key, lambda: _coefficient_latex(d, q))


def _coefficient_latex(d, q: str) -> str:
    from landau.derivation.multiscale import DERIVED

    names: dict = {}
    if q in DERIVED:
        return r"C = 2\sqrt{2\bar\Gamma/|\Lambda|}"
    numeric_hopf = d.hopf.closed_form is None
    rational = not numeric_hopf and _rational_in_parameters(d)
    if q in ("kc", "omega_c"):
        if numeric_hopf:
            return (r"k_c,\ \omega_c:\ \text{numerical (largest-stiffness root of the Hopf polynomial; "
                    + _why_numeric(d) + ")}")
        kc, W = d.hopf.closed_form
        if rational:
            parts = _cached_parts(d, [])
            kc, W = parts["kc"], parts["W"]
        eqs = equation_lines("k_c", kc, names, letter="K") if q == "kc" else \
            equation_lines(r"\omega_c^2", W, names, letter="W")
    else:
        parts = _cached_parts(d, [q]) if rational else None
        eqs, kind = _coefficient_rows(d, q, names, parts)
        if parts is not None:
            eqs += equation_lines(r"\omega_c^2", parts["W"], names, letter="W")
    if not rational:
        # the derivatives at steady sliding the formula uses, each in V and the parameters
        text = " ".join(line for eq in eqs for line in eq.lines)
        used = [a for a in d.jets.atoms if symbol_latex(a.name) in text]
        for a in sorted(used, key=lambda s: s.name):
            eqs += equation_lines(symbol_latex(a.name), d.jets.atoms[a], names, letter="A")
    rows = [r for eq in eqs for r in eq.align_rows()]
    return "\\begin{aligned}\n" + " \\\\\n".join(rows) + "\n\\end{aligned}"


def _why_numeric(d) -> str:
    """Why the Hopf line k_c(V), ω_c(V) has no closed form, as LaTeX text: a steady state that is
    solved numerically, or a Hopf polynomial of degree ≥ 2 in ω² (several state variables)."""
    if d.system.unknowns:
        return "it depends on the steady state, which has no closed form"
    n = len(d.block.law.states)
    return f"{n} state variables: the Hopf polynomial in $\\omega^2$ has degree {d.hopf._hopf_polys[0].degree()}"


def _letter(q: str) -> str:
    return {"Gamma_bar": "G", "Omega_bar": "O", "Lambda": "L", "chi": "X"}.get(q, "P")


def _rational_in_parameters(d) -> bool:
    return all(e.is_rational_function(*d.args) for e in d.jets.atoms.values())


def _cached_parts(d, quantities):
    from landau.derivation.rational import closed_form_parts

    return closed_form_parts(d, quantities)
