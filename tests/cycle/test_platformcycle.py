"""The shipped floor-and-platform cycle on the multi-level station (issue 47, deliverable 5),
scenes/multilevel_platform.toml: a barrier-free group (``step_up = { older_adult = 0.0 }``)
cannot take the platform's 0.17 m step and walks its 5.5 deg ramp instead, the other groups
take the step; the animated cycles have 0 contacts and the report's level split names the
route each group takes."""

from __future__ import annotations

import pytest

from mjwalk.cycle.seeding import run_generator
from mjwalk.cycle.simulate import simulate_cycle
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.report.levelsplit import crossings_of, level_split, split_markdown
from mjwalk.shipped import cycle_file


def test_the_platform_cycle_is_shipped_with_a_barrier_free_group():
    spec = load_cycle_spec(cycle_file("multilevel_platform"))
    assert spec.scene.name == "multilevel_station.xml"
    assert dict(spec.population.step_up) == {"older_adult": 0.0}


@pytest.mark.slow
def test_the_barrier_free_group_takes_the_ramp_with_no_contacts():
    """Seeded: runs 0 and 1 (seed = run) draw a fatigued and an older operator. Animated with
    collisions: 0 contacts in both (the older operator's turns off the ramp's foot cut its low
    corner: 34 contacts before the feet stood and swung on the ramp's plane there); the older
    operator's three walks go up, down and up the ramp, the other's take the step; the report
    names both routes and the ramp's seconds."""
    spec = load_cycle_spec(cycle_file("multilevel_platform"))
    results = [simulate_cycle(spec, seed, run=seed, ergonomics=False) for seed in (0, 1)]
    assert [r.group for r in results] == ["fatigued", "older_adult"]
    for r in results:
        assert r.collisions == []
    ways = {r.group: [crossings_of(w.path) for w in r.walks] for r in results}
    assert ways["older_adult"] == ["ramp up", "ramp down", "ramp up"]
    assert ways["fatigued"] == ["step up", "step down", "step up"]
    split = level_split(results)
    assert split is not None
    assert split["older_adult"]["max_riser"] == [0.0]
    assert split["older_adult"]["mean"]["ramps"] > 0.0
    assert split["older_adult"]["mean"]["steps"] == 0.0
    assert split["fatigued"]["mean"]["ramps"] == 0.0
    text = "\n".join(split_markdown(split))
    assert "- older_adult, stand_rack1->stand_platform1: ramp up (1x)" in text
    assert "- fatigued, stand_rack1->stand_platform1: step up (1x)" in text


@pytest.mark.slow
def test_the_twelve_run_batchs_step_edge_contact_is_gone():
    """Seeded: run 5 of ``mjwalk simulate scenes/multilevel_platform.toml --runs 12`` (seed 0),
    re-simulated alone as ``--only-run`` does, has 0 contacts. Before: run 5 (a fatigued
    operator, step route) put its right toes 1.5 mm into the platform's edge as its foot,
    hanging toes down behind the riser, sank back after lift-off from the step's tread
    (edgeswing.rise_held)."""
    spec = load_cycle_spec(cycle_file("multilevel_platform"))
    r = simulate_cycle(spec, run_generator(0, 5), run=5, ergonomics=False)
    assert r.group == "fatigued"
    assert r.collisions == []


@pytest.mark.slow
def test_the_twelve_run_batchs_ramp_corner_contact_is_gone():
    """Seeded: run 7 of the same batch (an older operator, ramp route) has 0 contacts. Before:
    walking down the ramp and turning back south-west on the floor past its foot, the right
    foot, toes down after push-off, swung its toes 10.3 mm into the ramp's low corner at
    (5.57, 2.73): the swing over a ramp's plane took the sole's points as if the foot were
    flat, 3 cm too far ahead (:func:`mjwalk.body.legs.rampreach.swing_over_ramps`)."""
    spec = load_cycle_spec(cycle_file("multilevel_platform"))
    r = simulate_cycle(spec, run_generator(0, 7), run=7, ergonomics=False)
    assert r.group == "older_adult"
    assert r.collisions == []


@pytest.mark.slow
def test_the_forty_run_batchs_turn_onto_the_ramp_is_gone():
    """Seeded: run 14 of ``mjwalk simulate scenes/multilevel_platform.toml --runs 40`` (an older
    operator, ramp route) has 0 contacts. Before: the floor leg ended at the ramp's stance
    facing 120 deg away and the crossing's first step turned onto the ramp at once; the legs
    could not reach, lowered the pelvis 0.21 m and put the left foot 10.7 cm into the floor
    (40 contacts). Now the leg lines up a step before the ramp, facing up it within
    levelcross.ENTRY_TURN, and such a lowering raises (legs.stance.REACH_DROP_MAX)."""
    spec = load_cycle_spec(cycle_file("multilevel_platform"))
    r = simulate_cycle(spec, run_generator(0, 14), run=14, ergonomics=False)
    assert r.group == "older_adult"
    assert r.collisions == []
