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
def test_run_33s_palm_clears_the_trolley():
    """Seeded: run 33 of ``mjwalk simulate scenes/multilevel_platform.toml --runs 40`` (seed 0;
    a 1.88 m adult, step route) has 0 contacts. Before: carrying the screws from rack 1 to the
    step between the trolley and the car, its hanging left arm turned with a trunk that was
    thrown from +17 to -19 degrees and back between frames (the least turn's side flipped as
    the shoulder line swung through the trolley's direction), and the left palm went 2.1 mm
    into the trolley at 48.67 s (:func:`mjwalk.timeline.frames.turn_sides`)."""
    spec = load_cycle_spec(cycle_file("multilevel_platform"))
    r = simulate_cycle(spec, run_generator(0, 33), run=33, ergonomics=False)
    assert r.group == "adult"
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
@pytest.mark.parametrize("run", [15, 18, 38])
def test_the_forty_run_batchs_ramp_crest_contacts_are_gone(run):
    """Seeded: runs 15, 18 and 38 of ``mjwalk simulate scenes/multilevel_platform.toml --runs
    40`` (older operators, ramp route) have 0 contacts. Before: 26, 1 and 2, the toes 0.1-0.6
    mm below the platform's top at its edge where the ramp's top meets it (x 2.2): the stance
    foot on the ramp's last footprint was turned onto the slope about the point under its
    ankle, not its footprint, so its ball and toes sank with the heel's rise (6 mm by
    toe-off; :func:`mjwalk.body.legs.rampreach.tilt`); the heel's rise at the ankle's
    dorsiflexion limit left up to 0.4 deg clipped (run 15,
    :data:`mjwalk.body.legs.legheights.HEEL_RISE_PASSES`); the flat swing's 0.5 mm toe dip
    after toe-off (run 18, :data:`mjwalk.body.legs.crest.CREST_CLEARANCE`)."""
    spec = load_cycle_spec(cycle_file("multilevel_platform"))
    r = simulate_cycle(spec, run_generator(0, run), run=run, ergonomics=False)
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
