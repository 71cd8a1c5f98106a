"""The CLI contract: --json prints one JSON document; bad input exits 2 with a one-line message."""

import json

import pytest

from landau.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_linear_json_points(capsys):
    code, out, err = run(capsys, "linear", "dieterich", "--V", "1e-5,1e-2", "--json")
    assert code == 0 and err == ""
    doc = json.loads(out)
    ok = doc["points"][0]
    assert ok["status"] == "ok"
    # eq. (30) at V = 1e-5 m/s: σ(b−a)/L (1 + MV²/(Laσ))
    s, a, b, L, M, V = 1.2 * 9.81, 0.0349, 0.0489, 0.9e-6, 1.2, 1e-5
    assert ok["kc"] == pytest.approx(s * (b - a) / L * (1 + M * V ** 2 / (L * a * s)), rel=1e-12)
    assert isinstance(ok["omega_c"], float) and isinstance(ok["V"], float)


def test_velocity_strengthening_is_reported_not_a_negative_kc(capsys):
    code, out, _ = run(capsys, "linear", "spinodal", "--V", "1e-2", "--json")
    pt = json.loads(out)["points"][0]
    assert code == 0 and pt["status"] == "no-hopf"
    assert pt["reason"] == "no Hopf bifurcation: steady sliding is stable for all k"
    assert "kc" not in pt


@pytest.mark.parametrize("argv, needle", [
    (["linear", "x", "--mu", "__import__('os').getcwd()", "--state", "phi=1-v*phi/L", "--V", "1e-5"], "__import__"),
    (["linear", "x", "--mu", "a*log(v).real", "--state", "phi=1-v*phi/L", "--V", "1e-5"], "attribute access"),
    (["linear", "x", "--mu", "a*gamma(v)", "--state", "phi=1-v*phi/L", "--V", "1e-5"], "unknown function 'gamma'"),
    (["linear", "x", "--mu", "a*log(v/V_s) + q", "--state", "phi=1-v*phi/L", "--V", "1e-5"], "unknown symbol 'q'"),
    (["linear", "dieterich", "--V", "0"], "must be > 0"),
    (["linear", "dieterich", "--V=-1e-5"], "must be > 0"),
    (["linear", "nosuchlaw", "--V", "1e-5"], "unknown law 'nosuchlaw'"),
    (["linear", "dieterich", "--V", "1e-5", "--param", "zz=1"], "unknown parameter 'zz'"),
    (["derive", "dieterich", "--V", "1e-5", "--quantities", "Lambda,foo"], "unknown quantity 'foo'"),
    (["scene", "run", "nope/none"], "unknown scene"),
])
def test_bad_input_exit_2_one_line(capsys, argv, needle):
    code, out, err = run(capsys, *argv, "--json")
    assert code == 2
    assert err.count("\n") == 1 and needle in err
    # with --json the error is also one JSON document on stdout (the CLI contract)
    doc = json.loads(out)
    assert doc["exit_code"] == 2 and needle in doc["error"] and doc["kind"].endswith("Error")


def test_inline_law_equals_builtin(capsys):
    _, out1, _ = run(capsys, "derive", "--mu", "a_v + a*log(v/V_s) + b*log(V_s*phi/L)", "--state",
                     "phi=1 - v*phi/L", "--V", "2e-5,3e-4", "--json")
    _, out2, _ = run(capsys, "derive", "dieterich", "--V", "2e-5,3e-4", "--json")
    p1, p2 = json.loads(out1)["points"], json.loads(out2)["points"]
    for a, b in zip(p1, p2, strict=True):
        for key in ("kc", "omega_c", "Gamma_bar", "Lambda", "chi", "C"):
            assert a[key] == pytest.approx(b[key], rel=1e-12)


def test_scene_run_spinodal_vm(capsys):
    code, out, _ = run(capsys, "scene", "run", "putelat2010/spinodal-V_m", "--json")
    doc = json.loads(out)
    assert code == 0
    assert doc["value"] == pytest.approx(4.052e-4, rel=5e-4)    # Putelat et al. 2010, Sec. 4.1
    assert doc["published"] == 4.052e-4 and "Sec. 4.1" in doc["source"]
    code, out, _ = run(capsys, "scene", "run", "putelat2010/spinodal-V_m", "--param", "c=3e-4", "--json")
    assert json.loads(out)["value"] > 1e-3                      # V_m grows as c decreases (Fig. 9)


def test_scene_list_json(capsys):
    code, out, _ = run(capsys, "scene", "list", "--json")
    names = [s["scene"] for s in json.loads(out)["scenes"]]
    assert code == 0 and "putelat2010/V-hat" in names


def test_derive_latex_is_compile_ready(tmp_path, capsys):
    f = tmp_path / "d.tex"
    code, out, _ = run(capsys, "derive", "dieterich", "--latex", str(f), "--quantities", "kc,omega_c,Gamma_bar,Lambda",
                       "--json")
    assert code == 0
    tex = f.read_text()
    assert tex.startswith(r"\documentclass") and tex.rstrip().endswith(r"\end{document}")
    assert tex.count("{") == tex.count("}")
    for env in ("document", "align*"):
        assert tex.count(rf"\begin{{{env}}}") == tex.count(rf"\end{{{env}}}")
    # the closed-form k_c typesets with matplotlib's mathtext (no TeX installation needed)
    import matplotlib
    matplotlib.use("Agg")
    import re

    from matplotlib.mathtext import MathTextParser
    kc = re.search(r"^k_c &= (.*)$", tex, re.M).group(1)
    MathTextParser("agg").parse(f"${kc}$")
