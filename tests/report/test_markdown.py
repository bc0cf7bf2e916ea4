"""The report as Markdown and as the terminal summary (mjwalk.report.markdown)."""

from __future__ import annotations

import pytest
from test_figures import SCENE, _results

from mjwalk.report.figures import report_dict
from mjwalk.report.markdown import format_markdown, format_summary
from mjwalk.world import load_workplace


@pytest.fixture(scope="module")
def workplace():
    return load_workplace(SCENE)


def test_the_sources_planner_stands_beside_the_routes(workplace):
    """A reference with the source's own planner's (median, IQR) puts both in the report's
    data and in its route table, under a line naming the source."""
    results = _results(workplace)
    ref = {"T1": (2.38, 0.21, 2.41, 0.16)}
    rep = report_dict(results, reference=ref)
    assert rep["routes"]["T1"]["reference"]["planner_iqr"] == 0.16
    assert "planner_iqr" not in rep["routes"]["T2"].get("reference", {})
    md = format_markdown(rep)
    assert "source's planner 50th [m]" in md
    assert "| 2.41 | 0.16 |" in md


def test_summary_names_routes_runs_and_cycle_time(workplace):
    rep = report_dict(_results(workplace, runs=4))
    summary = format_summary(rep)
    assert "4 run(s)" in summary and "cycle time" in summary
    for label in ("T1", "T2", "T5"):
        assert label in summary
    md = format_markdown(rep)
    assert md.startswith("#") and "## Cycle time" in md
