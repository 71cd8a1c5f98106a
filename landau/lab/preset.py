"""The ``lab`` preset: the quasi-static spring–slider per unit normal stress, in µm, µm/s and 1/µm.

Laboratory rate-and-state models (Ruina 1983; Gu et al. 1984; Marone 1998; rsfmodel, PyRSF)
leave out inertia and radiation damping: the force balance is algebraic,

    k (x_lp − x) = σ μ(v, φ),   so per unit normal stress   dμ/dt = k′ (V_lp − v),   k′ = k/σ,

and fixes the slip rate v through the implicit function μ(v, φ) = k′ (x_lp − x) (unique where
∂μ/∂v > 0, the direct effect a > 0).  The preset sets M = 0, η = 0 and σ = 1 (stresses in units
of the normal stress, so k = k′ numerically), and reads and writes the lab's units: stiffness k′
in 1/µm, velocities in µm/s, displacements and memory lengths in µm, times in s.  A bare number
is in these units; a number with a unit (:mod:`landau.lab.units`) in its own.  Inside, every
value is SI (k′ in 1/m).

The ``si`` preset is the toolkit's default (the block of Putelat et al. 2010, M = 1.2 kg,
σ = Mg, k in N/m, m/s, m); there ``--k 1e-3/um`` is k = k′σ with the block's σ.

References
----------
Ruina, A. (1983), Slip instability and state variable friction laws, J. Geophys. Res. 88, 10359–10370.
Gu, J.-C., Rice, J. R., Ruina, A. L. & Tse, S. T. (1984), Slip motion and stability of a single
degree of freedom elastic system with rate and state dependent friction, J. Mech. Phys. Solids 32, 167–196.
Marone, C. (1998), Annu. Rev. Earth Planet. Sci. 26, 643–696.
Putelat, T., Dawes, J. H. P. & Willis, J. R. (2010), J. Mech. Phys. Solids 58, 27–53.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Mapping

import numpy as np

from landau.errors import InputError
from landau.lab.units import parse_value, to_unit


@dataclass(frozen=True)
class Preset:
    """A set of conventions: the block parameters it fixes and the units of bare numbers and outputs.

    ``block`` is merged under the user's parameters (a value given explicitly wins); ``length``,
    ``velocity`` and ``stiffness`` are the units of a bare number of that kind and of the outputs.
    """

    name: str
    block: Mapping[str, float] = field(default_factory=dict)
    length: str = "m"
    velocity: str = "m/s"
    stiffness: str = "N/m"

    def stiffness_value(self, text: str | float, sigma: float, what: str = "--k") -> float:
        """The spring stiffness k [N/m] of ``text``: a force per length as it is, a stiffness per unit
        normal stress k′ (1/length) times ``sigma`` [N]."""
        x, kind = parse_value(text, ("stiffness", "inverse length"), what, self.stiffness)
        if not x > 0:
            raise InputError(f"{what}: the stiffness must be > 0, got {text!r}")
        return x * sigma if kind == "inverse length" else x

    def velocity_value(self, text: str | float, what: str) -> float:
        """A velocity [m/s] (a bare number in :attr:`velocity`)."""
        return parse_value(text, "velocity", what, self.velocity)[0]

    def length_value(self, text: str | float, what: str) -> float:
        """A length [m] (a bare number in :attr:`length`)."""
        return parse_value(text, "length", what, self.length)[0]

    def parameter_value(self, text: str | float, si_unit: str, what: str) -> float:
        """A law or block parameter [SI] whose declared unit is ``si_unit``: lengths and velocities in this
        preset's units when bare, any other parameter a plain number in its SI unit."""
        if si_unit == "m":
            return self.length_value(text, what)
        if si_unit == "m/s":
            return self.velocity_value(text, what)
        return parse_value(text, "number", what)[0]

    def unit_of(self, si_unit: str) -> str:
        """The output unit of a column whose SI unit is ``si_unit``."""
        return {"m": self.length, "m/s": self.velocity}.get(si_unit, si_unit)

    def convert(self, sim, order: tuple[str, ...] = ()):
        """A copy of the Simulation ``sim`` (SI, with its ``units``) in this preset's units, with the
        columns named in ``order`` first; its ``units`` say the new units."""
        units = dict(sim.units)
        names = list(sim.state_names)
        first = [n for n in order if n in names]
        idx = [names.index(n) for n in first] + [i for i, n in enumerate(names) if n not in first]
        rows, finals, new = [], [], {}
        for i in idx:
            nm = names[i]
            out = self.unit_of(units.get(nm, ""))
            if nm == "F" and self.block.get("sigma") == 1.0:
                out = "1"   # the spring force per unit normal stress
            elif out != units.get(nm, ""):
                rows.append(to_unit(sim.y[i], out))
                finals.append(float(to_unit(sim.y_final[i], out)))
                new[nm] = out
                continue
            rows.append(sim.y[i])
            finals.append(float(sim.y_final[i]))
            new[nm] = out if nm == "F" else units.get(nm, "")
        y = np.vstack(rows) if rows else sim.y
        return replace(sim, y=y, y_final=np.array(finals), state_names=tuple(names[i] for i in idx),
                       units={**units, **new})


#: the toolkit's default conventions (SI, the block of Putelat et al. 2010)
SI = Preset("si")
#: the laboratory's: quasi-static (M = 0, η = 0), per unit normal stress (σ = 1), µm, µm/s, 1/µm
LAB = Preset("lab", {"M": 0.0, "eta": 0.0, "sigma": 1.0}, length="um", velocity="um/s", stiffness="1/um")
#: the presets by name
PRESETS = {p.name: p for p in (SI, LAB)}
#: the lab's column order of a protocol's series
LAB_COLUMNS = ("x_lp", "slip", "mu", "v", "V")


def get_preset(name: str) -> Preset:
    """The preset of that name (``"si"``, ``"lab"``); InputError naming the known ones otherwise."""
    try:
        return PRESETS[str(name)]
    except KeyError:
        raise InputError(f"--preset: unknown preset {name!r} (known: {', '.join(PRESETS)})") from None


__all__ = ["LAB", "LAB_COLUMNS", "PRESETS", "SI", "Preset", "get_preset"]
