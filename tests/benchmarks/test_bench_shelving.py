"""benchmarks/bench_shelving.py: its workplace loads, and in a cycle there the place into the
low compartment (under a shelf, at knuckle height) is clear of the scene (the operator
stoops or crouches for it: tests/cycle/test_crouch.py) with the hand on its target."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from mjwalk.cycle.simulate import simulate_cycles
from mjwalk.cycle.spec import load_cycle_spec

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
import bench_shelving as bench


def test_bad_runs_stop_with_status_2(capsys):
    with pytest.raises(SystemExit) as exc:
        bench.main(["--runs", "0"])
    assert exc.value.code == 2
    assert "--runs: must be an integer >= 1, got '0'" in capsys.readouterr().err


def test_the_low_compartment_place_is_clear_of_the_shelf(tmp_path):
    """Four operators of the station's workforce (seed 0; at the code of 2026-11-28's start
    each touched the upper shelf with thumb, palm or forearm in this place)."""
    results = simulate_cycles(load_cycle_spec(bench.write_workplace(tmp_path)), 4, 0)
    for res in results:
        place = next(t for t in res.tasks if t.site == "rack1_waist")
        assert not [c for c in res.collisions if place.start <= c.time <= place.end]
        assert next(a for a in res.arms if a.site == "rack1_waist").hand_error < 0.01
