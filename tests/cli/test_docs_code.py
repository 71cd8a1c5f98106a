"""Every code block of the README and the documentation runs, and shows what the page says.

The extraction rules are in ``tests/cli/docs_code.py``: a page's Python blocks run in order
in one namespace and the output written under a statement must be what it shows; every
``landau ...`` line of a shell block must exit 0.  Blocks marked ``<!-- test: slow -->`` (those
that simulate for minutes or regenerate whole figures) run in the opt-in slow suite.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))

from docs_code import PAGES, ROOT, blocks, commands, matches, run_statement, statements  # noqa: E402

from landau.cli import main  # noqa: E402


def _rel(p: Path) -> str:
    return str(p.relative_to(ROOT))


def _python_params():
    out = []
    for page in PAGES:
        bs = blocks(page, ("python",))
        if any(not b.slow for b in bs):
            out.append(pytest.param(page, False, id=_rel(page)))
        if any(b.slow for b in bs):
            out.append(pytest.param(page, True, id=_rel(page) + "-with-slow-blocks", marks=pytest.mark.slow))
    return out


def _command_params():
    out = []
    for page in PAGES:
        for c in commands(page):
            out.append(pytest.param(c, id=f"{_rel(page)}: {c.text[:70]}",
                                    marks=[pytest.mark.slow] if c.slow else []))
    return out


@pytest.fixture
def session(tmp_path, monkeypatch):
    """A fresh folder to write in and matplotlib without a display."""
    import matplotlib

    matplotlib.use("Agg")
    monkeypatch.chdir(tmp_path)
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


@pytest.mark.parametrize(("page", "with_slow"), _python_params())
def test_python_blocks_run_and_show_what_the_page_says(page, with_slow, session):
    ns: dict = {"__name__": "__docs__"}
    ran = 0
    for b in blocks(page, ("python",)):
        if b.slow and not with_slow:
            continue
        for st in statements(b):
            try:
                shown = run_statement(st, ns)
            except Exception as exc:  # noqa: BLE001 - reported with the page and line
                pytest.fail(f"{_rel(page)}:{st.line}: {st.source.splitlines()[0]!r} raised "
                            f"{type(exc).__name__}: {exc}")
            if st.expected is not None:
                ok, why = matches(st.expected, shown)
                assert ok, (f"{_rel(page)}:{st.line}: {st.source.splitlines()[0]!r} shows\n{shown}\n"
                            f"but the page says\n{st.expected}\n({why})")
            ran += 1
    assert ran


@pytest.mark.parametrize("cmd", _command_params())
def test_shell_command_runs(cmd, session, capsys):
    code = main(cmd.argv)
    out, err = capsys.readouterr()
    assert code == cmd.exit, f"{cmd.where}: {cmd.text!r} exited {code}: {err.strip()[:400]}"


def test_the_pages_show_code():
    """The extraction finds what the README is known to show (a guard against a format change
    that would silently leave everything out)."""
    readme = ROOT / "README.md"
    cmds = [c.text for c in commands(readme)]
    assert len(cmds) >= 10 and any("--friction" in c for c in cmds) and any(c.startswith("landau hopf") for c in cmds)
    assert any(c.startswith("landau plot") for c in cmds)
    assert len(blocks(readme, ("python",))) >= 5
    guide = ROOT / "docs" / "guide.md"
    assert sum(st.expected is not None for b in blocks(guide, ("python",)) for st in statements(b)) >= 3


def test_output_matching_rules():
    assert matches("HopfResult(p_c = 0, ω_c = 2, C = 0.57735, l1 = -0.6)",
                   "HopfResult(p_c = 0, ω_c = 2, C = 0.5773502692, l1 = -0.6)")[0]
    assert not matches("C = 0.57736", "C = 0.5773502692")[0]        # a wrong digit
    assert matches("'\\Lambda = \\frac{M V^{3} ...", "'\\Lambda = \\frac{M V^{3} \\sigma ...}'")[0]
    assert not matches("k_c = 169829", "k_c = 169839.1")[0]
    assert matches("array([1.e-04, 1.2e-03])", "array([1.e-04, 1.2e-03])")[0]
    assert not matches("(supercritical)", "(subcritical)")[0]


def test_no_formula_is_set_in_italics():
    """Asterisks of a formula (V*(p), p*, V_*) are escaped: MkDocs' Markdown would otherwise set
    the text between two of them in italics."""
    markdown = pytest.importorskip("markdown")
    bad = []
    for page in PAGES:
        html = markdown.markdown(page.read_text(encoding="utf-8"), extensions=["tables", "fenced_code"])
        html = re.sub(r"<code>.*?</code>", "", html, flags=re.S)
        for em in re.findall(r"<em>(.*?)</em>", html, flags=re.S):
            if re.search(r"[=_]", em) or re.match(r"[()]", em) or re.search(r"[(_]$", em):
                bad.append(f"{_rel(page)}: *{em[:80]}*")
    assert not bad, "\n".join(bad)


def test_slow_marker_and_output_rules_of_the_extraction(tmp_path):
    from docs_code import Block

    page = tmp_path / "page.md"
    page.write_text("text\n\n<!-- test: slow -->\n```bash\nlandau verify ruina \\\n  --V 1e-4\n```\n\n"
                    "```python\nx = 1 + 1\n# 2\ny = 3   # an explanation, not checked\n```\n", encoding="utf-8")
    (cmd,) = commands(page)
    assert cmd.slow and cmd.argv == ["verify", "ruina", "--V", "1e-4"]
    (b,) = blocks(page, ("python",))
    assert isinstance(b, Block) and not b.slow
    sts = statements(b)
    assert [s.expected for s in sts] == ["2", None]
    ns: dict = {}
    assert run_statement(sts[0], ns) == "2" and run_statement(sts[1], ns) is None
