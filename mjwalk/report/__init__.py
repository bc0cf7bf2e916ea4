"""Report of many simulated cycles: walk-length distributions per route, cycle time, collisions.

:func:`report_dict` computes the figures (plain, JSON-ready data, :mod:`.figures`);
:func:`format_markdown` and :func:`format_summary` set them as Markdown and as a short table for
the terminal (:mod:`.markdown`); :func:`write_report` writes them with tables and charts into a
folder, all files or none (:mod:`.files`).
"""

from __future__ import annotations

from mjwalk.report.figures import (
    CAPTURE_TABLE1,
    CYCLE_PERCENTILES,
    TAKT_CONFIDENCE,
    describe,
    over_takt,
    percentiles,
    report_dict,
    split_failed,
)
from mjwalk.report.files import (
    ERGONOMICS_FILES,
    OPERATOR_COLUMNS,
    REPORT_FILES,
    BaselineArg,
    write_report,
)
from mjwalk.report.markdown import MD_PAIRS, ROUTE_COLUMNS, format_markdown, format_summary

__all__ = [
    "CAPTURE_TABLE1",
    "CYCLE_PERCENTILES",
    "ERGONOMICS_FILES",
    "MD_PAIRS",
    "OPERATOR_COLUMNS",
    "REPORT_FILES",
    "ROUTE_COLUMNS",
    "TAKT_CONFIDENCE",
    "BaselineArg",
    "describe",
    "format_markdown",
    "format_summary",
    "over_takt",
    "percentiles",
    "report_dict",
    "split_failed",
    "write_report",
]
