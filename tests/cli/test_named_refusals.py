"""Inputs that ended in an internal error ("please report", exit 1) now end in the right answer or
in a named refusal (exit 2, one line naming what is wrong).  Each case is the command line that
failed, with its old output in the comment."""

from __future__ import annotations

import json

import pytest

from landau.cli.app import main

DIETERICH_MU = "a*log(v/V_s) + a_v + b*log(V_s*phi/L)"


def run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.mark.parametrize("argv, needle", [
    # ZeroDivisionError: float division by zero
    (["scene", "run", "putelat2010/spinodal-V_m", "--param", "c=0"], "V_m (eq. 41) = inf"),
    # OverflowError: cannot convert float infinity to integer
    (["scene", "run", "putelat2010/spinodal-V_m", "--param", "t_ss=1e300"], "L/t_ss = 9e-307 m/s"),
    (["scene", "run", "putelat2010/modified-dieterich-V_m", "--param", "c=0"], "is not positive and finite"),
    # OverflowError: int too big to convert
    (["simulate", "forced-oscillator", "--param", "omega=1e300"], "shorter than the integrator resolves"),
    # OverflowError: (34, 'Numerical result out of range')
    (["hopf", "galvanetto-one-block", "--V", "1e300"], "F_k'(-V) leaves the float64 range at V = 1e+300"),
    (["hopf", "galvanetto-one-block", "--param", "gamma=1e300"], "with gamma = 1e+300"),
    # 40 "Hopf points" found on a scan whose eigenvalues are all on the axis to round-off
    (["hopf", "galvanetto-one-block", "--V", "1e150"], "below float64's resolution"),
    # wrote into the current folder
    (["figures", "putelat2010", "--only", "fig8", "--out", ""], "--out: the output folder is empty"),
    # accepted: a negative stiffness, damping or gravity, a rest angle of 1e300 rad
    (["hopf", "impact-oscillator", "--param", "k_y=-5"], "'k_y' is a spring stiffness and must be >= 0"),
    (["hopf", "impact-oscillator", "--param", "c_y=-1"], "'c_y' is a damping and must be >= 0"),
    (["simulate", "impact-oscillator", "--param", "g=-9.81"], "'g' is the gravitational acceleration"),
    (["hopf", "impact-oscillator", "--param", "phi0=1e300"], "must lie in [-2 pi, 2 pi]"),
    # ZeroDivisionError / math domain error in a scene's formula
    (["scene", "run", "putelat2010/V-hat", "--param", "M=0"], "is undefined for M = 0"),
    (["scene", "run", "putelat2010/V-hat", "--param", "a=-1"], "is undefined for a = -1"),
    # exit 0 with k_c, Lambda = null
    (["derive", "dieterich", "--param", "b=1e308", "--V", "1", "--json"], "kc = 4.24493e+321 N/m"),
])
def test_named_refusal(capsys, tmp_path, monkeypatch, argv, needle):
    monkeypatch.chdir(tmp_path)
    code, out, err = run(capsys, *argv)
    assert code == 2, (out, err)
    assert needle in err and "internal error" not in err
    assert len(err.strip().splitlines()) == 1
    # nothing on stdout but, with --json, the error's one JSON document (the CLI contract)
    assert (json.loads(out)["error"] in err) if "--json" in argv else not out
    assert not list(tmp_path.iterdir())          # nothing written


def test_huge_sigma_has_a_hopf_point(capsys):
    # was: "no Hopf point" although k_c = σ(b − a)/L = 1.56e304 N/m is representable
    code, out, err = run(capsys, "derive", "dieterich", "--param", "sigma=1e300", "--V", "1", "--json")
    assert code == 0, err
    pt = json.loads(out)["points"][0]
    assert pt["status"] == "ok" and pt["kc"] == pytest.approx(1e300 * (0.0489 - 0.0349) / 9e-7, rel=1e-12)
    assert all(pt[n] is not None for n in ("omega_c", "Gamma_bar", "Lambda", "C"))


def test_impact_oscillator_tiny_scale_is_quiet(capsys):
    # was: a wall of RuntimeWarnings (divide by zero in the lambdified Jacobian) before the answer
    code, out, err = run(capsys, "hopf", "impact-oscillator", "--friction", "mu*tanh(v/e)", "--param", "e=1e-300",
                         "--param", "mu=0.3")
    assert "internal error" not in err and "Warning" not in err
    assert code == 1 and err.startswith("landau: NoHopfError: no Hopf point")


def test_latex_with_large_flint_coefficients(capsys, tmp_path):
    # Dieterich + 3e-9 (v/V_s)^4: flint's factor() overflowed ("value too large to convert to int")
    out_file = tmp_path / "law.tex"
    code, out, err = run(capsys, "derive", "--mu", DIETERICH_MU + " + 3e-9*(v/V_s)**4", "--state", "phi=1 - phi*v/L",
                         "--param", "a_v=0.369", "--param", "a=0.0349", "--param", "b=0.0489", "--param", "L=9e-7",
                         "--param", "V_s=1e-6", "--latex", str(out_file))
    assert code == 0, err
    text = out_file.read_text()
    assert r"\Lambda" in text and r"10^{-9}" in text


def test_out_of_memory_is_not_called_input_too_large(capsys, monkeypatch):
    import landau.cli.laws as laws

    def boom(args):
        raise MemoryError
    monkeypatch.setattr(laws, "run", boom)
    code, out, err = run(capsys, "laws")
    assert code == 2 and "out of memory" in err and "too large" not in err


def test_linear_huge_sigma_has_a_hopf_point(capsys):
    # was: "k_c or omega_c^2 leaves the floating-point range (k_c = nan ...)" although k_c = 1.56e304 N/m
    code, out, err = run(capsys, "linear", "dieterich", "--param", "sigma=1e300", "--V", "1", "--json")
    assert code == 0, err
    pt = json.loads(out)["points"][0]
    assert pt["kc"] == pytest.approx(1e300 * (0.0489 - 0.0349) / 9e-7, rel=1e-12)
