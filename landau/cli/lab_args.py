"""The lab's conventions on the command line of ``landau simulate spring-block``: ``--preset`` and units.

``--preset lab`` is the quasi-static spring–slider per unit normal stress (M = 0, η = 0, σ = 1;
:mod:`landau.lab.preset`): bare numbers of ``--k`` are k′ in 1/µm, of ``--V``, ``--V-history`` and
the law's velocity parameters µm/s, of its lengths µm, and the files are written in these units.
Under either preset a value may carry its unit (:mod:`landau.lab.units`): ``--k 1e-3/um`` (k′; k =
k′σ), ``--k 2e4N/m``, ``--V-history "1um/s@0,10um/s@10"``, ``--param L=10um``.
"""

from __future__ import annotations

from landau import models
from landau.errors import InputError


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


#: the kind of value a law parameter of each declared unit takes
KIND_OF_UNIT = {"m": "length", "m/s": "velocity", "s": "time", "1/m": "inverse length", "N/m": "stiffness"}


def convert_params(args, preset) -> dict[str, str | None]:
    """``args.param`` with every value that carries a unit written in SI (in place); returns each given
    name's kind of value (None: a bare number) for :func:`finish_params`."""
    from landau.lab.units import KINDS, parse_value

    items: list[str] = []
    kinds: dict[str, str | None] = {}
    for item in args.param:
        name, sep, val = item.partition("=")
        if not sep or _is_number(val.strip()):
            items.append(item)
            if sep:
                kinds[name.strip()] = None
            continue
        x, kind = parse_value(val, tuple(KINDS), f"--param {name.strip()}")
        items.append(f"{name.strip()}={x!r}")
        kinds[name.strip()] = kind
    args.param = items
    return kinds


def finish_params(law, params: dict, kinds: dict[str, str | None], preset) -> None:
    """Check each value with a unit against the parameter's declared unit, and put the law's lengths and
    velocities given as bare numbers from the preset's units into SI (in place)."""
    units = {p.name: p.units for p in law.parameters}
    for name, kind in kinds.items():
        if name not in params:
            continue
        if kind is not None and name in units and units[name] in ("", "1"):
            continue   # a parameter without a declared unit (an inline law's): its value in SI as given
        want = KIND_OF_UNIT.get(units.get(name, ""), "number")
        if kind is None:
            if units.get(name) in ("m", "m/s"):
                params[name] = preset.parameter_value(str(params[name]), units[name], f"--param {name}")
        elif kind != want:
            unit = units.get(name)
            raise InputError(f"--param {name}: the value is a {kind}, but {name} is "
                             + (f"a {want} ({unit})" if unit and want != "number" else "a plain number"
                                + (f" in {unit}" if unit and unit not in ("", "1") else "")))


def stiffness(text: str, law, params: dict, preset) -> float:
    """``--k`` in N/m: a stiffness as given, k′ (1/length) times the block's σ."""
    from landau.systems.system import SpringBlock

    sigma = params.get("sigma")
    if sigma is None:   # the block's default σ (= M g) at these values; V and k are not the block's parameters
        block = {name: value for name, value in params.items() if name not in ("V", "k")}
        sigma = SpringBlock.for_params(law, block).resolve(block)["sigma"]
    return preset.stiffness_value(text, float(sigma), "--k")


def history_pairs(text: str, preset) -> list[tuple[float, float]]:
    """``--V-history`` with units as (V_i [m/s], t_i [s]) pairs."""
    from landau.lab.protocols import velocity_history

    h = velocity_history(text, preset=preset).history
    return list(zip(h.velocities, h.times, strict=True))


def check_preset(args, model) -> None:
    """``--preset lab`` runs a protocol of a model that declares the preset (the spring–block): InputError for
    another model or no history."""
    if getattr(args, "preset", "si") == "lab":
        if "lab" not in model.defaults.get("presets", ("si",)):
            offering = [m.name for m in models.all_models() if "lab" in m.defaults.get("presets", ("si",))]
            raise InputError(f"--preset lab applies to {', '.join(offering)} only, not {model.name}")
        if args.V_history is None:
            raise InputError("--preset lab runs a laboratory protocol: give --V-history (e.g. '1um/s@0,10um/s@10')")


__all__ = ["KIND_OF_UNIT", "check_preset", "convert_params", "finish_params", "history_pairs", "stiffness"]
