"""docs/performance.md is generated from the committed benchmark results and cannot drift.

``benchmarks/report.py`` fills ``benchmarks/performance_template.md`` from
``benchmarks/results/*.json``; the page on disk must be exactly what it produces.
"""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _report():
    spec = importlib.util.spec_from_file_location("landau_bench_report", ROOT / "benchmarks" / "report.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_performance_page_is_generated_from_the_results():
    report = _report()
    page = (ROOT / "docs" / "performance.md").read_text(encoding="utf-8")
    assert page == report.render(), "docs/performance.md differs: run python benchmarks/report.py"


def test_every_goal_on_the_page_comes_from_a_result_file():
    report = _report()
    chosen = report.newest_per_section(report.load_results())
    page = (ROOT / "docs" / "performance.md").read_text(encoding="utf-8")
    assert chosen, "no benchmark results committed"
    for section, (name, res) in chosen.items():
        assert f"benchmarks/results/{name}" in page
        for g in report._goals_of(res, section):
            assert g["measure"] in page


def test_a_newer_run_replaces_only_its_own_sections(tmp_path):
    report = _report()
    old = {"machine": {"date": "2026-01-01 00:00 UTC"}, "sections": ["forced", "derive"],
           "goals": [{"section": "forced", "goal": "3", "measure": "old forced", "value": 2.0, "target": 1.0,
                      "sense": ">=", "note": "", "passed": True},
                     {"section": "derive", "goal": "6", "measure": "old derive", "value": 0.5, "target": 2.0,
                      "sense": "<=", "note": "", "passed": True}],
           "tables": {"forced": "OLD-FORCED", "derive": "OLD-DERIVE"}, "raw": {}}
    new = {"machine": {"date": "2026-02-01 00:00 UTC"}, "sections": ["forced"],
           "goals": [{"section": "forced", "goal": "3", "measure": "new forced", "value": 3.0, "target": 1.0,
                      "sense": ">=", "note": "", "passed": True}],
           "tables": {"forced": "NEW-FORCED"}, "raw": {}}
    (tmp_path / "a.json").write_text(json.dumps(new))
    (tmp_path / "b.json").write_text(json.dumps(old))
    page = report.render(report.load_results(tmp_path), "{{ goals }}\n\n{{ sections }}\n")
    assert "NEW-FORCED" in page and "new forced" in page
    assert "OLD-FORCED" not in page and "old forced" not in page
    assert "OLD-DERIVE" in page and "old derive" in page
