"""benchmarks/bench_unseen.py: a generated hall planned and scanned end to end (issue 47)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
bench = pytest.importorskip("bench_unseen")


def test_table_counts_outcomes():
    recs = [
        {"seed": 0, "outcomes": [{"stage": "plan:a->b", "kind": "planned"}]},
        {"seed": 1, "outcomes": [{"stage": "plan:a->c", "kind": "no route", "msg": "x 0.19 m"}]},
    ]
    out = bench.table(recs)
    assert "| plan | planned | 1 |" in out and "| plan | no route | 1 |" in out
    assert "1 x x # m" in out


@pytest.mark.slow
@pytest.mark.parametrize("seed", [3, 9])
def test_generated_halls_plan_and_scan(seed):
    """Halls 3 (a 5-riser stair, a two-riser step, a ramp) and 9 (a stair with a landing, a
    two-riser step, a ramp): every walk is planned or refused as it must be (the ramp-only
    walker to the mezzanine), nothing raises, and the scan finds every level within 2 cm and
    every stair and ramp (hall 3's mezzanine and stair were lost before scanlevels looked again;
    hall 9's ramp met a ghost level the second look found on the ramp's head)."""
    rec = bench.run_one(seed, ("plan", "scan"))
    kinds = {o["kind"] for o in rec["outcomes"]}
    assert kinds <= {"planned", "refused as expected"}, rec["outcomes"]
    assert rec["scan"]["missed"] == [] and rec["scan"]["extra"] == []
    for kind, (found, true) in rec["scan"]["links"].items():
        assert found == true, (kind, rec["scan"])


@pytest.mark.slow
def test_hall_201_cycle_walks_down_its_steep_ramp():
    """Hall 201's cycle (the 1.75 m reference walker) walks down its 9.x deg ramp: its ramp
    steps were the level gait's (Tobler and Franz & Kram alone) and the legs reached their
    feet only with the pelvis 0.052 m lowered (PlanningError, over REACH_DROP_MAX); the steps
    within the legs' reach (mjwalk.gait.slope.downhill_step_max) ask for less."""
    rec = bench.run_one(201, ("cycle",))
    assert rec["cycle"]["errors"] == [], rec["cycle"]
