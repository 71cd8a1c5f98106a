"""List the built-in friction laws with their equations, parameters and sources."""

from __future__ import annotations

from landau.errors import InputError
from landau.laws import BUILTIN, BUILTIN_VELOCITY, get_law


def configure(p) -> None:
    p.add_argument("name", nargs="?", default=None, help="show one law only")


def _parameters(law) -> list[dict]:
    return [{"name": p.name, "default": p.default, "units": p.units, "source": p.source} for p in law.parameters]


def run(args) -> dict:
    if args.name is not None and not args.name.strip():
        raise InputError("empty law name: give a law's name (landau laws dieterich), or none to list them all")
    if args.name in BUILTIN_VELOCITY:
        names, vnames = [], [args.name]
    elif args.name:
        get_law(args.name)                        # an unknown name is an error naming the known ones
        names, vnames = [args.name], []
    else:
        names, vnames = list(BUILTIN), list(BUILTIN_VELOCITY)
    out = []
    for n in vnames:
        vlaw = BUILTIN_VELOCITY[n]()
        out.append({"name": vlaw.name, "kind": "velocity", "source": vlaw.source, "description": vlaw.description,
                    "F(v>0)": str(vlaw.branch(1)), "F(v<0)": str(vlaw.branch(-1)), "quantity": vlaw.quantity,
                    "set_valued_at_zero": vlaw.is_set_valued(), "parameters": _parameters(vlaw)})
    for n in names:
        law = get_law(n)
        out.append({"name": law.name, "kind": "rate-and-state", "source": law.source,
                    "description": law.description, "mu": str(law.mu),
                    "states": {str(s): str(r) for s, r in zip(law.states, law.rates, strict=True)},
                    "convention": "rates are dphi/dt (Putelat et al.: dphi/dt = -G)",
                    "parameters": _parameters(law)})
    if not out:
        raise InputError(f"unknown law {args.name!r}")
    return {"laws": out}


def render(doc: dict) -> str:
    lines = []
    for law in doc["laws"]:
        lines.append(f"{law['name']}  [{law['source']}]")
        if law["kind"] == "velocity":
            what = "mu" if law["quantity"] == "coefficient" else "F [N]"
            lines.append(f"  {what} = {law['F(v>0)']}  (v > 0);  {law['F(v<0)']}  (v < 0)"
                         + ("; set-valued at v = 0 (stick)" if law["set_valued_at_zero"] else ""))
        else:
            lines.append(f"  mu = {law['mu']}")
            for s, r in law["states"].items():
                lines.append(f"  d{s}/dt = {r}")
        lines.append("  parameters: " + ", ".join(
            f"{p['name']}={p['default']:g}{(' ' + p['units']) if p['units'] else ''}" for p in law["parameters"]))
    return "\n".join(lines)
