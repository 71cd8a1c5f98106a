"""``landau hopf mode-coupling``: the 4-DOF family from matrices, the named results, the bad inputs, a sweep.

A 4-DOF structure given as matrix strings on the command line gives the μ_c of the Python API and of
a bisection of max Re λ of the matrices assembled in the test (linear contact: K_eff = K + k_H e_n e_nᵀ
− μ k_H e_t e_nᵀ), to 1e-9 relative; undamped, its threshold is the collision of two squared
frequencies (a plain bisection on the discriminant of the two that merge), named ``mode-coupling``.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from flutter_reference import bisect_threshold, scan_bisect

from landau.analyses.flutter import flutter_hopf
from landau.cli import main
from landau.systems.mode_coupling import ContactLaw, ModeCoupling

M4 = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0.5, 0], [0, 0, 0, 0.8]]
K4 = [[3e4, 1e4, -1e4, 0], [1e4, 2e4, 0, -5e3], [-1e4, 0, 2e4, 0], [0, -5e3, 0, 1.5e4]]
C4 = [[1, 0, 0, 0], [0, 0.5, 0, 0], [0, 0, 0.2, 0], [0, 0, 0, 0.3]]
KH, P = 2e4, 50.0


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def _matrix_args(C=C4):
    return ["--mass-matrix", json.dumps(M4), "--stiffness-matrix", json.dumps(K4), "--damping-matrix", json.dumps(C),
            "--normal", "1", "--tangential", "0", "--contact", "linear", "--param", f"kH={KH}", "--param", f"P={P}"]


def _assembled(mu, C=C4):
    M, K, Cm = np.array(M4, float), np.array(K4, float), np.array(C, float)
    K = K.copy()
    K[1, 1] += KH
    K[0, 1] -= mu * KH
    A = np.zeros((8, 8))
    A[:4, 4:] = np.eye(4)
    A[4:, :4] = -np.linalg.solve(M, K)
    A[4:, 4:] = -np.linalg.solve(M, Cm)
    return A, M, K


def test_four_dof_matrices_through_the_cli(capsys):
    code, out, err = run(capsys, "hopf", "mode-coupling", *_matrix_args(), "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["kind"] == "hopf" and doc["parameter"] == "mu"
    ref = scan_bisect(lambda mu: float(np.max(np.linalg.eigvals(_assembled(mu)[0]).real)), 0.0, 2.0)
    api = flutter_hopf(ModeCoupling(M4, C4, K4, 1, 0, P, 0.1, ContactLaw("linear", KH), 0.3))
    assert doc["p_c"] == pytest.approx(ref, rel=1e-9)
    assert doc["p_c"] == pytest.approx(api.p_c, rel=1e-12)
    assert doc["omega_c"] == pytest.approx(api.omega_c, rel=1e-12)


def test_four_dof_undamped_is_mode_coupling(capsys):
    zero = [[0] * 4 for _ in range(4)]
    code, out, err = run(capsys, "hopf", "mode-coupling", *_matrix_args(zero), "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["kind"] == "mode-coupling"

    def disc(mu):   # the discriminant of the two squared frequencies that merge
        _, M, K = _assembled(mu, zero)
        s = np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)
        i = int(np.argmin(np.diff(s)))
        s2 = np.linalg.eigvals(np.linalg.solve(M, K))
        pair = s2[np.argsort(np.abs(s2 - 0.5 * (s[i] + s[i + 1])))[:2]]
        return -float(((pair[0] - pair[1]) ** 2).real)

    lo = doc["p_c"] * 0.99
    ref = bisect_threshold(disc, lo, doc["p_c"] * 1.01)
    assert doc["p_c"] == pytest.approx(ref, rel=1e-9)
    # just past the collision the merged pair s = ω² is complex, its real part ω_c²
    _, M, K = _assembled(doc["p_c"] * (1 + 1e-7), zero)
    s = np.linalg.eigvals(np.linalg.solve(M, K))
    assert doc["omega_c"] ** 2 == pytest.approx(s[np.argmax(np.abs(s.imag))].real, rel=1e-6)


def test_two_dof_undamped_cli_names_mode_coupling(capsys):
    code, out, err = run(capsys, "hopf", "mode-coupling", "--param", "c1=0", "--param", "c2=0", "--contact",
                         "linear", "--json")
    assert code == 0, err
    doc = json.loads(out)
    assert doc["kind"] == "mode-coupling"
    # the defaults: k11 = 1.5e4, k12 = 0.866e4, k22 = 0.5e4, kH = 2e4, m = 1: mu_c = 1/sqrt(3)
    assert doc["p_c"] == pytest.approx(1 / np.sqrt(3), rel=1e-10)
    assert doc["omega_c"] == pytest.approx(np.sqrt(2e4), rel=1e-10)


@pytest.mark.parametrize("argv,words", [
    (["--param", "P=-5"], "contact opens"),
    (["--param", "mu=0.3"], "bifurcation parameter"),
    (["--mass-matrix", "[[1,0],[0,1]", "--stiffness-matrix", "[[1,0],[0,1]]"], "--mass-matrix"),
    (["--mass-matrix", "[[1,0],[0,1]]", "--stiffness-matrix", "[[1,0,0],[0,1,0],[0,0,1]]"], "2x2"),
    (["--mass-matrix", "[[1,0],[0,1]]", "--stiffness-matrix", "[[1,0],[0,1]]", "--normal", "0"], "differ"),
    (["--mass-matrix", "[[1,0],[0,1]]", "--stiffness-matrix", "[[1,0],[0,1]]", "--normal", "x"], "--normal"),
    (["--param", "m=-1"], "'m'"),
    (["--param", "v0=0"], "v0"),
    (["--param", "kH=0"], "kH"),
    (["--friction-neg", "0.3"], "--friction"),
    (["--param", "q=1"], "unknown parameter"),
    (["--friction", "mu*(1 + a*exp(-v/v0))", "--param", "a=0.2"], "'v0' is a parameter of the model"),
])
def test_bad_input_is_one_line_and_exit_2(capsys, argv, words):
    code, out, err = run(capsys, "hopf", "mode-coupling", *argv)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and words in lines[0] and "Traceback" not in err


def test_a_velocity_law_adds_negative_damping(capsys):
    # a Stribeck-like falling law: mu'(v0) < 0 gives the tangential coordinate negative damping,
    # which lowers the threshold below that of the constant law with the same mu(v0)
    code, out, err = run(capsys, "hopf", "mode-coupling", "--friction", "mu*(1 + 0.5*exp(-v/0.05))",
                         "--json")
    assert code == 0, err
    doc = json.loads(out)
    code, out2, _ = run(capsys, "hopf", "mode-coupling", "--json")
    const = json.loads(out2)
    # at the threshold mu*(1 + 0.5 e^-2) of the law is the constant law's mu_c only without the slope's damping
    assert doc["p_c"] * (1 + 0.5 * np.exp(-2.0)) < const["p_c"]


def test_sweep_over_damping(tmp_path, capsys):
    out = tmp_path / "mc.nc"
    code, _, err = run(capsys, "sweep", "hopf", "mode-coupling", "--grid", "c1=1,3", "--grid", "c2=0.5",
                       "--out", str(out), "--workers", "1", "--json")
    assert code == 0, err
    import xarray as xr

    from landau.analyses.flutter import flutter_hopf as single

    with xr.open_dataset(out) as ds:
        pcs = ds["p_c"].values.ravel()
        c1s = ds["c1"].values
    for c1, pc in zip(c1s, pcs, strict=True):
        assert pc == single(ModeCoupling.hoffmann2002(c1=float(c1), c2=0.5)).p_c


def test_help_says_the_angles_are_in_degrees(capsys):
    with pytest.raises(SystemExit):
        main(["hopf", "--help"])
    out = capsys.readouterr().out
    assert "mode-coupling" in out and "degrees" in out
