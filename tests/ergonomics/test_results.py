"""mjwalk.ergonomics.results: what each run keeps of its ergonomics, and its plain summary."""

from __future__ import annotations

import json

import numpy as np
from test_niosh import lift_at

from mjwalk.ergonomics.results import RunErgonomics, TaskErgonomics


def _run(lifts) -> RunErgonomics:
    task = TaskErgonomics(0, "pick", "shelf", 3, 4, 2, 0.5, "upper arm", "trunk", "right", 2,
                          reach=True, extra={"custom": 1.5})  # fmt: skip
    rula, reba = np.array([1, 5, 3], np.int8), np.array([2, 9, 4], np.int8)
    return RunErgonomics([task], lifts, [], 10.0, rula, reba)


def test_peaks_levels_and_lifting_index():
    run = _run([lift_at(1.0), lift_at(16.0)])
    assert (run.rula_peak, run.reba_peak, run.owas_peak) == (5, 9, 2)
    assert run.max_li == run.lifts[0].li and run.lifts_without_li == [run.lifts[1]]
    assert _run([]).max_li == 0.0 and _run([lift_at(16.0)]).max_li is None
    s = run.summary()
    assert (s["rula_action_level"], s["reba_risk_level"]) == (3, 3)
    assert s["tasks"][0]["custom"] == 1.5 and "reach" not in s["tasks"][0]
    assert len(s["lifts"]) == 2 and s["iso11226"] == []
    json.dumps(s, default=float)
