"""``landau verify mode-coupling``: the flutter onset's amplitude equation checked by the non-smooth simulation.

``landau verify mode-coupling [--contact cubic] [--param kNL=0.5 ...] [--eps2 e1,e2] [--json]``: the
Hopf point μ_c of the sliding equilibrium of the model of Hoffmann et al. (2002) and its amplitude
equation (the general engine on the closed, sliding contact), against the limit cycle of the full
non-smooth model shot at μ = μ_c ± ε² μ_c (:func:`landau.verify.modecoupling.check.check_flutter`),
judged by the check's contract (the model's ``check``, :attr:`landau.models.Model.check`); the
amplitudes at which the predicted cycle opens the contact or makes the mass stick are reported.  Exit 1
when the check does not agree.
"""

from __future__ import annotations

from landau.analyses import contract
from landau.errors import InputError
from landau.models import Setup

AMPLITUDE_DEFINITION = ("amplitude_simulated = half peak-to-peak swing (max x - min x)/2 of the tangential "
                        "coordinate x of the shot cycle; amplitude_predicted = C*sqrt|mu - mu_c|")


def run(setup: Setup, eps2, tolerance: float | None = None) -> dict:
    """The JSON document of ``landau verify mode-coupling`` (the model's ``check``), with its ``text``."""
    from landau.verify.modecoupling.check import check_flutter
    from landau.verify.modecoupling.run import structure

    if "mu" in setup.params:
        raise InputError("verify mode-coupling: --param mu: mu is the bifurcation parameter: its critical value is "
                         "computed")
    s = structure(setup)
    r = check_flutter(s, eps2, tolerance=tolerance)
    rec = r.as_dict()
    rec.update(mu=r.p, mu_c=r.prediction.p_c, omega_c=r.prediction.omega_c, Lambda=r.prediction.Lambda,
               C=r.prediction.C, validity=r.detail.get("validity"))
    doc = {"model": "mode-coupling", "contact": s.contact.law, "params": dict(setup.params),
           "amplitude_definition": AMPLITUDE_DEFINITION,
           "units": {"mu": "1", "amplitude": "m", "frequency": "rad/s"},
           "contract": {"exponent_band": list(contract.EXPONENT_BAND),
                        "extrapolation_bound": contract.EXTRAPOLATION_BOUND, "companion_ratio": contract.RATIO,
                        "multiplier_resolution": contract.MULTIPLIER_RESOLUTION},
           "point": rec, "exit_code": 0 if r.agrees else 1}
    doc["text"] = render(doc)
    return doc


def render(doc: dict) -> str:
    """The human-readable table of :func:`run`'s document."""
    p = doc["point"]
    v = p.get("validity") or {}
    lines = [f"mode-coupling ({doc['contact']} contact): mu_c = {p['mu_c']:.10g}, omega_c = {p['omega_c']:.8g} rad/s, "
             f"Lambda = {p['Lambda']:.6g} ({p['criticality_predicted']}), C = {p['C']:.6g}",
             doc["amplitude_definition"]]
    for q in p["detail"]["points"]:
        sim = "-" if q["amplitude_simulated"] is None else f"{q['amplitude_simulated']:.6g}"
        err = "-" if q["rel_error"] is None else f"{q['rel_error']:+.3e}"
        lines.append(f"  eps2 {q['eps2']:.3g}: mu = {q['p']:.8g}, A_pred {q['amplitude_predicted']:.6g}, A_sim {sim}, "
                     f"rel.err {err}, stable {q['cycle_stable']}")
    if p.get("exponent") is not None:
        lines.append(f"fitted exponent of |rel.err| ~ (eps2)^p: {p['exponent']:.3f}; extrapolated error at eps2 -> 0: "
                     f"{p['extrapolated_error']:+.2e}")
    if v:
        lines.append(f"the predicted cycle opens the contact at amplitude {v['amplitude_contact_opens']:.4g} m "
                     f"(eps2 {v['eps2_contact_opens']:.3g}) and sticks at {v['amplitude_mass_sticks']:.4g} m "
                     f"(eps2 {v['eps2_mass_sticks']:.3g}): first, {v['first']}")
    lines.append(f"verdict: {p['verdict']}" + (f" ({p['reason']})" if p.get("reason") else ""))
    return "\n".join(lines) + "\n"
