"""``landau derive LAW --V ... --codim2 LO:HI`` in text mode: the points table, then the Λ₅/l₂ table."""

from __future__ import annotations

import json

from landau.cli import main


def test_codim2_text_prints_the_quintic_table(capsys):
    argv = ["derive", "modified-dieterich", "--V", "1e-4", "--codim2", "1e-7:1e-2"]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert main([*argv, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    (c,) = doc["codim2"]
    lines = text.splitlines()
    head = next(i for i, line in enumerate(lines) if line.split()[:3] == ["V*", "[m/s]", "k_c"])
    assert "Lambda5" in lines[head] and "l2" in lines[head]
    row = lines[head + 2].split()
    # the row holds the JSON document's numbers (as printed: 10 and 6 significant digits)
    assert float(row[0]) == float(f"{c['V']:.10g}")
    assert [float(x) for x in row[1:5]] == [float(f"{c[k]:.6g}") for k in ("kc", "omega_c", "Lambda5", "l2")]
    assert " ".join(row[5:]) == "supercritical / subcritical"     # Λ < 0 below V*, > 0 above
    assert any(line.startswith("fold of cycles from V*") for line in lines)
    # the points table keeps its own columns (no Lambda5/l2 column for --V)
    table = next(line for line in lines if line.lstrip().startswith("V [m/s]"))
    assert "Lambda5" not in table and "k_c" in table.split()
