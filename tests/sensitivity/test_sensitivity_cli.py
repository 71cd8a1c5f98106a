"""``landau derive --sensitivity``: the JSON document, the closed forms in --latex, exit 2 on an unknown
quantity or parameter (with the closest known name)."""

import json

import pytest

from landau.cli import main

P = {"a": 0.0349, "b": 0.0489, "L": 9e-7, "M": 1.2, "sigma": 1.2 * 9.81}


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_sensitivity_json_against_the_closed_form_of_eq_30(capsys):
    code, out, err = run(capsys, "derive", "dieterich", "--V", "1e-5,1e-4", "--quantities", "k_c,Lambda",
                         "--sensitivity", "k_c:a,k_c:b,Lambda:*", "--json")
    assert code == 0 and err == ""
    doc = json.loads(out)
    a, b, L, M, s = P["a"], P["b"], P["L"], P["M"], P["sigma"]
    for row in doc["points"]:
        V = row["V"]
        sens = row["sensitivities"]
        # k_c = σ(b − a)/L + M V²(b − a)/(a L²) (Putelat et al. 2010, eq. 30), differentiated by hand
        assert sens["d(k_c)/d(a)"] == pytest.approx(-s / L - M * V ** 2 * b / (a ** 2 * L ** 2), rel=1e-12)
        assert sens["d(k_c)/d(b)"] == pytest.approx(s / L + M * V ** 2 / (a * L ** 2), rel=1e-12)
        assert {k for k in sens if k.startswith("d(Lambda)")} == {
            f"d(Lambda)/d({p})" for p in ("V", "a_v", "a", "b", "L", "V_s", "M", "sigma")}
        assert sens["d(Lambda)/d(a_v)"] == 0.0       # μ* does not enter the derivatives at steady sliding
    assert doc["sensitivity_units"]["d(k_c)/d(a)"] == "N/m"
    assert doc["sensitivity_units"]["d(Lambda)/d(L)"] == "(1/(m^2 s))/(m)"


def test_sensitivity_text_table(capsys):
    code, out, _ = run(capsys, "derive", "ruina", "--V", "1e-4", "--quantities", "k_c", "--sensitivity", "k_c:b")
    assert code == 0 and "exact sensitivities:" in out and "d(k_c)/d(b)" in out


def test_sensitivity_closed_forms_in_the_latex_file(tmp_path, capsys):
    tex = tmp_path / "s.tex"
    code, out, _ = run(capsys, "derive", "dieterich", "--quantities", "k_c,omega_c", "--latex", str(tex),
                       "--sensitivity", "k_c:a", "--json")
    assert code == 0
    text = tex.read_text()
    assert "\\section*{Sensitivities}" in text and "\\frac{\\partial k_c}{\\partial a}" in text
    assert text.index("Sensitivities") < text.index("\\end{document}")


@pytest.mark.parametrize("spec, needle", [
    ("Lamda:a", "unknown quantity 'Lamda' for a sensitivity; did you mean 'Lambda'?"),
    ("k_c:sigmaa", "unknown parameter 'sigmaa' for a sensitivity of law 'dieterich'; did you mean 'sigma'?"),
    ("k_c", "is not QUANTITY:PARAMETER"),
    (",", "no QUANTITY:PARAMETER pair"),
])
def test_unknown_quantity_or_parameter_exit_2_one_line(capsys, spec, needle):
    code, out, err = run(capsys, "derive", "dieterich", "--V", "1e-4", "--sensitivity", spec, "--json")
    assert code == 2
    assert err.count("\n") == 1 and needle in err
    doc = json.loads(out)
    assert doc["exit_code"] == 2 and needle in doc["error"]
