"""The flutter onset's amplitude equation (the general engine on the closed, sliding contact) against the
limit cycle of the full non-smooth model, on both sides of criticality: a hardening cubic contact
(kNL = +0.5: supercritical, the stable cycle above mu_c) and a softening one (kNL = -0.1: subcritical, the
unstable cycle below mu_c), both damped (c1 = 0.02, c2 = 0.04: a transversal Hopf point), v0 = 5 so
that the cycle neither sticks nor (below eps2 ~ 0.03) opens the contact."""

import json

import numpy as np
import pytest

from landau.analyses import contract
from landau.cli import main
from landau.verify.modecoupling.check import check_flutter, linear_mode
from landau.verify.modecoupling.nonsmooth import hoffmann_structure

CASES = {"hardening": (0.5, "supercritical", True), "softening": (-0.1, "subcritical", False)}


def structure(kNL):
    return hoffmann_structure(contact="cubic", kNL=kNL, P=1.0, v0=5.0, c1=0.02, c2=0.04)


@pytest.mark.parametrize("case", sorted(CASES))
def test_amplitude_check_both_sides(case):
    kNL, crit, stable = CASES[case]
    s = structure(kNL)
    r = check_flutter(s, 4e-3)
    pr = r.prediction
    assert str(pr.criticality) == crit
    # mu_c: the linearised sliding equilibrium has a pair on the imaginary axis at omega_c (an independent
    # numpy eigenvalue computation; mu_c is located to the engine's dps, the eigenvalues to rounding)
    _, lam, _ = linear_mode(s, pr.p_c)
    k = np.argmin(np.abs(lam - 1j * pr.omega_c))
    assert abs(lam[k].real) < 1e-12 and lam[k].imag == pytest.approx(pr.omega_c, rel=1e-12)
    assert r.agrees, r.reason
    pts = r.detail["points"]
    assert [p["eps2"] for p in pts] == [4e-3, 1e-3]
    # the cycle's stability is the predicted one (stable above mu_c when supercritical, unstable below
    # when subcritical), the error is O(eps2): below 1 % at 4e-3, four times smaller at 1e-3 (exponent
    # within the contract's band) and extrapolating to below 0.1 % at eps2 -> 0
    assert all(p["cycle_stable"] is stable for p in pts)
    assert abs(pts[0]["rel_error"]) < 1e-2
    assert contract.EXPONENT_BAND[0] <= r.exponent <= contract.EXPONENT_BAND[1]
    assert abs(r.extrapolated_error) < 1e-3
    # where the weakly nonlinear cycle would end: the contact opens first (the speed amplitude A*omega_c
    # reaches v0 = 5 only much later)
    v = r.detail["validity"]
    assert v["first"] == "contact opens" and v["eps2_contact_opens"] < v["eps2_mass_sticks"]
    assert v["amplitude_mass_sticks"] == pytest.approx(5.0 / pr.omega_c, rel=1e-15)


def test_through_landau_check_and_its_refusals():
    import landau
    from landau.errors import InputError
    from landau.laws.velocity import VelocityFriction

    r = landau.check(structure(-0.1), 4e-3)
    assert r.agrees and r.parameter == "mu" and r.detail["validity"]["first"] == "contact opens"
    law = VelocityFriction.from_strings("stribeck", "md + (ms - md)*exp(-v/vs)", params={"md": 0.5, "ms": 0.9,
                                                                                            "vs": 0.3})
    with pytest.raises(InputError, match="Coulomb"):
        check_flutter(hoffmann_structure(contact="cubic", kNL=0.5, friction=law), 4e-3)
    with pytest.raises(InputError, match="eps2"):
        check_flutter(structure(0.5), 0.7)


@pytest.mark.slow
@pytest.mark.parametrize("case", sorted(CASES))
def test_error_falls_like_eps2(case):
    # three eps2 a factor 2.5 apart: |rel_error| ~ (eps2)^p with p fitted near 1
    kNL, _, _ = CASES[case]
    eps = [1e-2, 4e-3, 1.6e-3]
    r = check_flutter(structure(kNL), eps)
    assert r.agrees, r.reason
    errs = [abs(p["rel_error"]) for p in r.detail["points"]]
    slope = np.polyfit(np.log(eps), np.log(errs), 1)[0]
    assert 0.9 < slope < 1.1


#: the structure of structure(kNL) above as the model's parameters
SMALL = [x for n, v in (("m", 1), ("k1", 1), ("k2", 0.5), ("alpha1", 30), ("alpha2", 60), ("kH", 1), ("P", 1),
                        ("c1", 0.02), ("c2", 0.04), ("v0", 5)) for x in ("--param", f"{n}={v}")]


def test_cli_verify(capsys):
    code = main(["verify", "mode-coupling", "--contact", "cubic", *SMALL, "--param", "kNL=0.5",
                 "--eps2", "4e-3", "--json"])
    doc = json.loads(capsys.readouterr().out)
    assert code == 0 and doc["exit_code"] == 0 and doc["point"]["verdict"] == "agrees"
    assert doc["point"]["validity"]["first"] == "contact opens"
    # the linear contact: the sliding system is linear (Lambda = 0), named, exit 1
    assert main(["verify", "mode-coupling", "--contact", "linear", *SMALL, "--param", "kNL=0", "--json"]) == 1
    assert json.loads(capsys.readouterr().out)["point"]["verdict"] == "outside-validity"
    assert main(["verify", "mode-coupling", "--param", "mu=0.3", "--json"]) == 2
    assert "bifurcation parameter" in json.loads(capsys.readouterr().out)["error"]
    # no closed-contact equilibrium at any mu (a preload pulling the mass off the belt): bad input, not "no flutter"
    assert main(["verify", "mode-coupling", "--param", "P=-1", "--json"]) == 2
    assert "no sliding equilibrium" in json.loads(capsys.readouterr().out)["error"]
    assert main(["verify", "spring-block", "--json"]) == 2
    assert "no check" in json.loads(capsys.readouterr().out)["error"]
