"""The code of the README and the documentation pages, extracted so that the suite runs it.

* ```` ```python ```` blocks of one page run in order in one namespace (a page is a session);
  a comment block directly under a statement (no blank line between) is the output that
  statement shows — its value's ``repr`` (or the value of the name it assigns) and whatever it
  prints — and must match it: ``...`` stands for any text, and a number matches a computed one
  that rounds to it at the digits printed (the page shows fewer digits, never other ones).
  Comments on the statement's own line are explanations and are not checked.
* ```` ```bash ```` and ```` ```console ```` blocks: every line that starts with ``landau ``
  (``$ `` prompts dropped, ``\\`` continuations joined, comments dropped) runs through the
  command line's entry point and must exit 0 — or the status a trailing ``# exits N`` comment
  names (a run documented to stop at its limit exits 1).
* ``<!-- test: slow -->`` on the line before a block puts it (a Python block, or every command
  of a shell block) in the opt-in slow suite (``pytest -m slow``): the default suite skips it.
"""

from __future__ import annotations

import ast
import contextlib
import io
import math
import re
import shlex
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

#: the pages whose code runs: the README and every page of the documentation site
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]

_FENCE = re.compile(r"(?P<mark><!--\s*test:\s*slow\s*-->\s*\n)?```(?P<lang>[\w-]*)[^\n]*\n(?P<body>.*?)^```",
                    re.S | re.M)


@dataclass
class Block:
    """One fenced code block of a page."""

    page: Path
    lang: str
    body: str
    line: int                 # line of the opening fence in the page (1-based)
    slow: bool = False

    @property
    def where(self) -> str:
        page = self.page.relative_to(ROOT) if self.page.is_relative_to(ROOT) else self.page
        return f"{page}:{self.line}"


def blocks(page: Path, langs: tuple[str, ...]) -> list[Block]:
    text = page.read_text(encoding="utf-8")
    out = []
    for m in _FENCE.finditer(text):
        if m["lang"] in langs:
            line = text.count("\n", 0, m.start("lang")) + 1
            out.append(Block(page, m["lang"], m["body"], line, slow=bool(m["mark"])))
    return out


# --- shell blocks ------------------------------------------------------------------------

@dataclass
class Command:
    argv: list[str]
    text: str
    where: str
    slow: bool
    exit: int = 0


_EXITS = re.compile(r"#\s*exits\s+(\d+)\b")


def commands(page: Path) -> list[Command]:
    """The ``landau ...`` command lines of a page's shell blocks."""
    out = []
    for b in blocks(page, ("bash", "console", "shell", "sh")):
        joined = re.sub(r"\\\n\s*", " ", b.body)
        for i, line in enumerate(joined.splitlines()):
            line = line.strip()
            if line.startswith("$ "):
                line = line[2:].strip()
            if line.startswith("landau ") or line == "landau":
                argv = shlex.split(line, comments=True)[1:]
                status = _EXITS.search(line)
                out.append(Command(argv, line, f"{b.where}+{i + 1}", b.slow,
                                   int(status[1]) if status else 0))
    return out


# --- Python blocks -----------------------------------------------------------------------

@dataclass
class Statement:
    """A top-level statement of a block with the output shown under it (None: nothing shown)."""

    source: str
    node: ast.stmt
    expected: str | None
    line: int


@dataclass
class PythonPage:
    page: Path
    blocks: list[Block] = field(default_factory=list)


def statements(block: Block) -> list[Statement]:
    """The block's top-level statements, each with the comment block directly under it."""
    src = block.body
    lines = src.splitlines()
    tree = ast.parse(src, filename=block.where)
    out = []
    for node in tree.body:
        end = node.end_lineno or node.lineno
        shown = []
        i = end                     # 0-based index of the line after the statement
        while i < len(lines) and lines[i].lstrip().startswith("#") and not lines[i].startswith((" ", "\t")):
            shown.append(re.sub(r"^#\s?", "", lines[i].strip()))
            i += 1
        seg = "\n".join(lines[node.lineno - 1:end])
        out.append(Statement(seg, node, "\n".join(shown) if shown else None, block.line + node.lineno))
    return out


_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def _half_unit(text: str) -> float:
    """Half a unit in the last printed digit of a number as written (rounding tolerance)."""
    mant, _, exp = text.lower().lstrip("+-").partition("e")
    decimals = len(mant.split(".")[1]) if "." in mant else 0
    return 0.5 * 10.0 ** (int(exp or 0) - decimals)


def matches(expected: str, actual: str) -> tuple[bool, str]:
    """Whether ``actual`` shows what ``expected`` documents (see the module docstring)."""
    pattern, numbers = [], []
    pos = 0
    for m in re.finditer(rf"\.\.\.|…|{_NUMBER}|\s+", expected):
        pattern.append(re.escape(expected[pos:m.start()]))
        tok = m.group(0)
        if tok in ("...", "…"):
            pattern.append(r".*?")
        elif tok.isspace():
            pattern.append(r"\s*")
        else:
            pattern.append(rf"({_NUMBER})")
            numbers.append(tok)
        pos = m.end()
    pattern.append(re.escape(expected[pos:]))
    # tokens glued to a number in the page (e.g. "1.2e-03]") stay glued in the output
    m = re.fullmatch(r"\s*" + "".join(pattern) + r"\s*", actual, flags=re.S)
    if m is None:
        return False, "the text differs"
    for want, got in zip(numbers, m.groups(), strict=True):
        w, g = float(want), float(got)
        if math.isclose(w, g, rel_tol=1e-12, abs_tol=0.0):
            continue
        if abs(g - w) > _half_unit(want) * (1 + 1e-9):
            return False, f"{got} is shown as {want}"
    return True, ""


def run_statement(st: Statement, ns: dict) -> str | None:
    """Execute one statement in ``ns``; the text it shows (what it prints, then its value's or
    its assigned name's repr) when the page documents an output, else None."""
    buf = io.StringIO()
    value = None
    with contextlib.redirect_stdout(buf):
        if isinstance(st.node, ast.Expr):
            code = compile(ast.Expression(st.node.value), f"<documentation line {st.line}>", "eval")
            value = eval(code, ns)  # noqa: S307 - the documentation's own code
        else:
            mod = ast.Module(body=[st.node], type_ignores=[])
            exec(compile(mod, f"<documentation line {st.line}>", "exec"), ns)  # noqa: S102 - the documentation's own code
            if (isinstance(st.node, ast.Assign) and len(st.node.targets) == 1
                    and isinstance(st.node.targets[0], ast.Name)):
                value = ns[st.node.targets[0].id]
    if st.expected is None:
        return None
    shown = buf.getvalue()
    if value is not None:
        shown += repr(value)
    return shown.rstrip("\n")
