"""The shipped multi-level station cycle (issue 47, deliverable 6), scenes/multilevel_station.toml:
up the stair to the mezzanine rack, down it and onto the platform; seeded runs of its batches
replayed alone as ``--only-run`` does."""

from __future__ import annotations

import pytest

from mjwalk.cycle.seeding import run_generator
from mjwalk.cycle.simulate import simulate_cycle
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.shipped import cycle_file


@pytest.mark.slow
def test_the_ten_run_batchs_tall_walker_clears_the_stair():
    """Seeded: run 7 of ``mjwalk simulate scenes/multilevel_station.toml --runs 10`` (seed 0; a
    1.85 m older operator) has 0 contacts. Before: 225, its 0.281 m feet centred on the 0.28 m
    treads stood 0.6 mm into the riser ahead of the toes all the way up (treads 2-5 and the
    mezzanine) and into the riser behind the heel all the way down, where each landing heel
    also caught the upper tread's nosing (5.6-11 mm); such feet now hang over a nosing
    (:data:`mjwalk.plan.levelcross.TREAD_RISER_GAP`)."""
    spec = load_cycle_spec(cycle_file("multilevel_station"))
    r = simulate_cycle(spec, run_generator(0, 7), run=7, ergonomics=False)
    assert r.group == "older_adult"
    assert r.collisions == []
