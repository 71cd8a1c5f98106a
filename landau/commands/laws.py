"""List the built-in friction laws with their equations, parameters and sources."""

from __future__ import annotations


from landau.laws import BUILTIN, get_law


def configure(p) -> None:
    p.add_argument("name", nargs="?", default=None, help="show one law only")


def run(args) -> dict:
    names = [args.name] if args.name else list(BUILTIN)
    out = []
    for n in names:
        law = get_law(n)
        out.append({"name": law.name, "source": law.source, "description": law.description,
                    "mu": str(law.mu), "states": {str(s): str(r) for s, r in zip(law.states, law.rates)},
                    "convention": "rates are dphi/dt (Putelat et al.: dphi/dt = -G)",
                    "parameters": [{"name": p.name, "default": p.default, "units": p.units, "source": p.source}
                                   for p in law.parameters]})
    return {"laws": out}


def render(doc: dict) -> str:
    lines = []
    for law in doc["laws"]:
        lines.append(f"{law['name']}  [{law['source']}]")
        lines.append(f"  mu = {law['mu']}")
        for s, r in law["states"].items():
            lines.append(f"  d{s}/dt = {r}")
        lines.append("  parameters: " + ", ".join(f"{p['name']}={p['default']:g}{(' ' + p['units']) if p['units'] else ''}"
                                              for p in law["parameters"]))
    return "\n".join(lines)
