"""LaTeX output that compiles: symbols as a paper writes them, safe text, broken long lines.

Everything the toolkit writes as ``.tex`` goes through this module:

* :func:`symbol_latex` — ``phi1`` → ``\\phi_{1}``, ``V_s`` → ``V_{*}``, ``t_ss`` → ``t_{**}``,
  a derivative of the right-hand side at steady sliding ``d2_u_u_phi`` → ``f_{u,u\\phi}``;
* :func:`escape_text` — user text (a law's name, its source) can never inject LaTeX
  (``}``, ``\\input``, ``$`` are escaped; non-ASCII characters are transliterated);
* :func:`equation_lines` — a long expression becomes several aligned lines: a sum is split
  between its terms; a product, power or function whose argument is too long has that
  argument named (``P_{1}``, ``q_{3}``…) and defined in its own (split) equation, the way a
  paper names the polynomials of a long closed form;
* :func:`hopf_line_latex` — the document of ``landau linear --latex``, or with ``fragment=True``
  only the equations (for ``\\input`` into a paper that loads amsmath).  What a derivation
  prints (``landau derive --latex``) is composed from these pieces in
  :mod:`landau.derivation.latex`.

No line of output exceeds a few hundred characters, whatever the size of the formula.
"""

from __future__ import annotations

import re
import unicodedata
from dataclasses import dataclass
from typing import Iterable, Mapping, Sequence

import sympy as sp

#: source characters per displayed line (10pt, 2 cm margins: ~110 characters of formula source
#: stay inside the text width for the typical mix of symbols, sub- and superscripts)
WIDTH = 110

_GREEK = {"alpha", "beta", "gamma", "delta", "epsilon", "varepsilon", "zeta", "eta", "theta", "vartheta", "iota",
          "kappa", "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "varphi", "chi",
          "psi", "omega", "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi",
          "Omega"}
#: subscripts a paper writes differently from the identifier
_SUBSCRIPTS = {"s": "*", "ss": "**"}
_STATE_SUFFIX = re.compile(r"^([A-Za-z]+?)(\d+)$")

_UNICODE_TEXT = {"–": "--", "—": "---", "−": "-", "’": "'", "‘": "`", "“": "``", "”": "''", "×": r"$\times$",
                 "≈": r"$\approx$", "≤": r"$\le$", "≥": r"$\ge$", "·": r"$\cdot$", "°": r"$^\circ$",
                 "²": r"$^2$", "³": r"$^3$", "µ": r"$\mu$", "…": r"\dots{}",
                 **{chr(0x2080 + i): f"$_{i}$" for i in range(10)}}
_GREEK_UNICODE = {unicodedata.lookup(f"GREEK SMALL LETTER {n.upper().replace('LAMBDA', 'LAMDA')}"): rf"$\{n}$" for n in
                  ("alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa", "lambda",
                   "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi", "omega")}
_TEXT_SPECIAL = {"\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "$": r"\$", "&": r"\&", "#": r"\#",
                 "_": r"\_", "%": r"\%", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}",
                 "<": r"\textless{}", ">": r"\textgreater{}", "|": r"\textbar{}"}

#: the units of the amplitude-equation quantities, typeset
UNITS_LATEX = {"m/s": r"\mathrm{m\,s^{-1}}", "N/m": r"\mathrm{N\,m^{-1}}", "rad/s": r"\mathrm{rad\,s^{-1}}",
               "1/(N s)": r"\mathrm{N^{-1}\,s^{-1}}", "1/(m^2 s)": r"\mathrm{m^{-2}\,s^{-1}}",
               "m/sqrt(N/m)": r"\mathrm{m^{3/2}\,N^{-1/2}}"}


def escape_text(text: str) -> str:
    """Plain text safe for LaTeX's text mode: every special character escaped, common
    non-ASCII characters transliterated, any other one written as its code point."""
    out = []
    for ch in str(text):
        if ch in _TEXT_SPECIAL:
            out.append(_TEXT_SPECIAL[ch])
        elif ord(ch) < 128:
            out.append(ch if ch.isprintable() else " ")
        elif ch in _UNICODE_TEXT:
            out.append(_UNICODE_TEXT[ch])
        elif ch in _GREEK_UNICODE:
            out.append(_GREEK_UNICODE[ch])
        else:
            out.append(f"U+{ord(ch):04X}")
    return "".join(out)


def _name_part(part: str) -> str:
    if part in _GREEK:
        return "\\" + part
    m = _STATE_SUFFIX.match(part)
    if m and m.group(1) in _GREEK:
        return rf"\{m.group(1)}_{{{m.group(2)}}}"
    if len(part) == 1 or part.isdigit():
        return part
    if part.isalnum():
        return rf"\mathrm{{{part}}}"
    return r"\mathrm{" + escape_text(part) + "}"


def symbol_latex(name: str) -> str:
    """How a paper writes the identifier ``name``: ``phi1`` → ``\\phi_{1}``, ``V_s`` → ``V_{*}``,
    ``t_ss`` → ``t_{**}``, ``a_v`` → ``a_{v}``, ``omega_c`` → ``\\omega_{c}``, ``b2`` → ``b_{2}``;
    the derivative atoms of :mod:`landau.derivation.jets` (``d2_u_u_phi``: ∂²f_u/∂u∂φ at steady sliding) →
    ``f_{u,u\\phi}``, ``dp_u_X`` (∂²f_u/∂k∂X) → ``f_{u,kX}``."""
    m = re.fullmatch(r"d(\d+|p)_([A-Za-z0-9]+)((?:_[A-Za-z0-9]+)*)", name)
    if m:
        comp = _name_part(m.group(2))
        idx = [p for p in m.group(3).split("_") if p]
        wrt = ("k" if m.group(1) == "p" else "") + "".join(
            _name_part(p) + (" " if _name_part(p).startswith("\\") else "") for p in idx)
        return rf"f_{{{comp},{wrt.strip()}}}"
    head, _, tail = name.partition("_")
    if not tail:
        m = _STATE_SUFFIX.match(name)
        if m and not name.isdigit():
            return rf"{_name_part(m.group(1))}_{{{m.group(2)}}}"
        return _name_part(name)
    sub = _SUBSCRIPTS.get(tail, ",".join(_name_part(p) for p in tail.split("_") if p))
    return rf"{_name_part(head)}_{{{sub}}}"


def symbol_names(symbols: Iterable[sp.Symbol]) -> dict[sp.Symbol, str]:
    """``symbol_names=`` mapping for :func:`sympy.latex` over the given symbols."""
    return {s: symbol_latex(s.name) for s in symbols if isinstance(s, sp.Symbol)}


def to_latex(expr: sp.Basic, names: Mapping[sp.Symbol, str] | None = None) -> str:
    """sympy's LaTeX with the paper's symbols, on one line."""
    names = dict(names or {})
    names.update({s: symbol_latex(s.name) for s in expr.free_symbols if isinstance(s, sp.Symbol) and s not in names})
    return sp.latex(expr, symbol_names=names, mul_symbol=None).replace("\n", " ")


@dataclass(frozen=True)
class Equation:
    """One displayed equation: ``lhs = lines[0]``, continued by ``lines[1:]``."""

    lhs: str
    lines: tuple[str, ...]
    relation: str = "="

    def align_rows(self) -> list[str]:
        rows = [rf"{self.lhs} &{self.relation} {self.lines[0]}"]
        rows += [rf"&\quad {line}" for line in self.lines[1:]]
        return rows


class Namer:
    """Fresh names P_{1}, P_{2}, … for sub-expressions split off a long formula."""

    def __init__(self, letter: str = "P"):
        self.letter = letter
        self.count = 0
        self.defined: dict[sp.Basic, sp.Symbol] = {}

    def label(self, sym: sp.Symbol) -> str:
        return rf"\mathcal{{{self.letter}}}_{{{sym.name[len(self.letter):]}}}"

    def name(self, expr: sp.Basic) -> sp.Symbol:
        if expr not in self.defined:
            self.count += 1
            self.defined[expr] = sp.Dummy(f"{self.letter}{self.count}")
        return self.defined[expr]


def equation_lines(lhs: str, expr: sp.Basic, names: Mapping | None = None, width: int = WIDTH,
                   letter: str = "P", namer: Namer | None = None) -> list[Equation]:
    """``lhs = expr`` as one or more :class:`Equation`: lines of at most ~``width`` source
    characters.  A sum is split between terms; an over-long product, power or function
    argument is named (``letter`` with an index) and defined in a following equation."""
    names = dict(names or {})
    namer = namer or Namer(letter)
    out: list[Equation] = []
    pending: list[tuple[str, sp.Basic]] = [(lhs, expr)]
    while pending:
        left, e = pending.pop(0)
        before = dict(namer.defined)
        lines = _split(e, names, width, namer)
        out.append(Equation(left, tuple(lines)))
        for sub, sym in namer.defined.items():
            if sub not in before:
                names[sym] = namer.label(sym)
                pending.append((names[sym], sub))
    return out


def _split(e: sp.Basic, names, width: int, namer: Namer) -> list[str]:
    text = to_latex(e, names)
    if len(text) <= width:
        return [text]
    if isinstance(e, sp.Add):
        lines: list[str] = []
        cur = ""
        for term in e.as_ordered_terms():
            neg = term.could_extract_minus_sign()
            body = -term if neg else term
            t = to_latex(body, names)
            if len(t) > width:
                t = _shorten(body, names, width, namer)
            piece = ("- " if neg else ("+ " if (lines or cur) else "")) + t
            if cur and len(cur) + len(piece) + 1 > width:
                lines.append(cur)
                cur = piece
            else:
                cur = f"{cur} {piece}" if cur else piece
        if cur:
            lines.append(cur)
        return lines
    return [_shorten(e, names, width, namer)]


def _shorten(e: sp.Basic, names, width: int, namer: Namer) -> str:
    """``e`` on one line of about ``width`` characters: its longest sums (then its longest
    other arguments) are named, as a paper names the polynomials of a long fraction."""
    work = e
    for _ in range(256):
        text = to_latex(work, names)
        if len(text) <= width or not work.args:
            return text
        sums: dict[sp.Expr, None] = {}
        others: dict[sp.Expr, None] = {}
        for sub in sp.preorder_traversal(work):
            if sub is work or sub.is_Atom or sub in names:
                continue
            if sub.is_Pow and (sub.exp.is_Integer and sub.exp < 0 or sub.base.is_Atom):
                continue                                    # name the base, keep the fraction
            (sums if isinstance(sub, sp.Add) else others)[sub] = None
        pool = sums or {o: None for o in others if len(to_latex(o, names)) >= 25}
        if not pool:
            return text                                     # a product of short factors: one line
        best = max(pool, key=lambda x: len(to_latex(x, names)))
        namer.name(best)
        names.setdefault(namer.defined[best], namer.label(namer.defined[best]))
        work = work.xreplace({best: namer.defined[best]})
    return to_latex(work, names)


def align_block(equations: Sequence[Equation]) -> str:
    """One ``align*`` environment, one row per line."""
    rows = [r for eq in equations for r in eq.align_rows()]
    return "\\begin{align*}\n" + " \\\\\n".join(rows) + "\n\\end{align*}"


PREAMBLE = (r"\documentclass[10pt]{article}", r"\usepackage{amsmath}", r"\usepackage{amssymb}",
            r"\usepackage[margin=2cm]{geometry}", r"\allowdisplaybreaks", r"\begin{document}")


def document(title: str, body: Sequence[str], fragment: bool = False) -> str:
    """A complete document (or, ``fragment=True``, only ``body`` with a comment header)."""
    if fragment:
        head = [f"% {title.replace(chr(10), ' ')}", "% generated by landau; needs \\usepackage{amsmath}"]
        return "\n".join([*head, *body]) + "\n"
    return "\n".join([*PREAMBLE, rf"\section*{{{escape_text(title)}}}", *body, r"\end{document}"]) + "\n"


def law_equations(law, names: Mapping | None = None) -> list[Equation]:
    """μ and the state rates of a friction law, split to fit."""
    names = dict(names or {})
    eqs = equation_lines(r"\mu", law.mu, names, letter="M")
    for s, r in zip(law.states, law.rates, strict=True):
        eqs += equation_lines(rf"\frac{{d{symbol_latex(s.name)}}}{{dt}}", r, names, letter="R")
    return eqs


# --- the documents ------------------------------------------------------------------------
def units_latex(u: str) -> str:
    return UNITS_LATEX.get(u, r"\text{" + escape_text(u) + "}")


def straight_line(expr: sp.Expr) -> tuple[list[tuple[sp.Symbol, sp.Expr]], sp.Expr]:
    """``expr`` as intermediate quantities and a final expression (common subexpressions in
    the order of the expression; one-operation intermediates such as 2x, x², 1/x are put
    back where they are used, so each remaining one is worth its name)."""
    reps, (red,) = sp.cse(expr, symbols=sp.numbered_symbols("q", cls=sp.Dummy), order="none")
    inline: dict = {}
    kept = []
    for sym, e in reps:
        e = e.xreplace(inline)
        if sp.count_ops(e) <= 1 and len(to_latex(e)) < 40:
            inline[sym] = e
        else:
            kept.append((sym, e))
    return kept, red.xreplace(inline)


def hopf_line_latex(hl, fragment: bool = False) -> str:
    """k_c(V) and ω_c²(V) of a :class:`~landau.derivation.linear.HopfLine` (Putelat et al. 2010, eqs 7–8)."""
    law = hl.block.law
    body = [rf"Friction law ({escape_text(law.source)}):" if law.source else "Friction law:",
            align_block(law_equations(law))]
    if hl.closed_form is not None:
        names: dict = {}
        eqs = []
        for lhs, e, letter in (("k_c", hl.kc_expr, "K"), (r"\omega_c^2", hl.omega2_expr, "W")):
            if e.is_rational_function(*e.free_symbols):
                e = sp.factor(sp.cancel(e))
            eqs += equation_lines(lhs, e, names, letter=letter)
        body.append(align_block(eqs))
    else:
        body.append(r"$k_c$ and $\omega_c$ have no closed form (several state variables): computed numerically.")
    return document(f"Linear stability: {law.name}", body, fragment)
