"""Lifts the revised NIOSH equation gives no index (issue 45): a lifting frequency beyond Table 5
(FM = 0), or H, V, D or A beyond its limit, gives RWL 0; the lift then has no lifting index and
says which limit it crossed and what the manual allows, and the workforce's summary, report.md
section and ergonomics.csv rows report such lifts apart from the indices (no nan, no inf, no
numpy warning)."""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest
from test_niosh import lift_at

from mjwalk.ergonomics.assess import RunErgonomics, TaskErgonomics
from mjwalk.ergonomics.summary import (
    CSV_COLUMNS,
    RunRecord,
    ergonomics_markdown,
    ergonomics_rows,
    ergonomics_summary,
)


def _record(run: int, lis: list[float | None]) -> RunRecord:
    """A cycle with one pick per entry of ``lis``: a finite index, or None (16 lifts/min)."""
    lifts = []
    for k, li in enumerate(lis):
        lf = lift_at(16.0) if li is None else lift_at(1.0)
        if li is not None:
            lf.li = li
        lf.task = k
        lifts.append(lf)
    tasks = [TaskErgonomics(k, "pick", "shelf", 3, 4, 1, 0.5, "wrist", "trunk", "right", 2, True)
             for k in range(len(lis))]  # fmt: skip
    n = 10
    ergo = RunErgonomics(tasks, lifts, [], 30.0, np.full(n, 3, np.int8), np.full(n, 4, np.int8))
    return RunRecord(run, run, "", None, ergo)


def _report(records):
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy's 'invalid value' warnings among them
        e = ergonomics_summary(records)
        md = "\n".join(ergonomics_markdown(e))
        rows = ergonomics_rows(records)
    json.dumps(e, allow_nan=False)  # report.json is strict JSON
    return e, md, rows


def test_the_summary_reports_lifts_without_an_index_apart():
    records = [_record(0, [None]), _record(1, [0.5, None]), _record(2, [1.5]), _record(3, [0.5])]
    e, md, rows = _report(records)
    s = e["overall"]
    assert s["lifting_index"] == {"p50": 0.5, "p95": pytest.approx(1.4), "n": 3}
    # LI > 1 is known for cycles 2 (yes) and 3 (no); 0 and 1 have a lift without an index
    assert (s["cycles_li_over_1"]["k"], s["cycles_li_over_1"]["n"]) == (1, 2)
    w = s["lifting_index_not_computed"]
    assert (w["lifts"], w["of_lifts"], w["cycles"]["k"], w["cycles"]["n"]) == (2, 5, 2, 4)
    assert w["lifts_per_min"] == [16.0, 16.0]
    assert list(w["limits"].values()) == [2]
    assert "nan" not in md and "inf" not in md
    assert "| cycles LI>1 | cycles without LI |" in md
    assert "No NIOSH lifting index for 2 of 5 lifts (2 of 4 cycles with lifts" in md
    assert "at 16.0 lifts/min" in md and "Limits crossed: lifting frequency beyond" in md
    col = {c: i for i, c in enumerate(CSV_COLUMNS)}
    first = rows[0]
    assert first[col["lifting_index"]] == "" and first[col["rwl_kg"]] == "0.000"
    assert first[col["lifts_per_min"]] == "16.00"
    assert first[col["lifting_index_note"]].startswith("no lifting index: lifting frequency 16.0")
    third = rows[3]  # cycle 2's lift
    assert third[col["lifting_index"]] == "1.500" and third[col["lifting_index_note"]] == ""


def test_no_index_at_all_gives_dashes_not_nan_beside_a_share():
    """The issue's report: 'LI P50 nan | LI P95 nan' beside 'cycles LI>1 100 %'."""
    e, md, _ = _report([_record(0, [None, None]), _record(1, [None, None])])
    row = next(ln for ln in md.splitlines() if ln.startswith("| all operators"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert cells[9:13] == ["-", "-", "-", "100 % (34-100)"]
    assert e["overall"]["cycles_li_over_1"]["share"] is None
    assert "No NIOSH lifting index for 4 of 4 lifts (2 of 2 cycles" in md
