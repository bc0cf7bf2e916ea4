"""A cycle in a work pit (issue 47: a level below the floor), scenes/pit_station.toml: a standing
site on the pit's bottom stands on the pit's level, and the animated cycle walks down the stair
into the pit and back up with 0 contacts, its walk record splitting stairs from level walking."""

from __future__ import annotations

import pytest

from mjwalk.body.humanoid import pelvis_height
from mjwalk.cycle.levelsite import ground_height, site_level, spec_on_levels
from mjwalk.cycle.simulate import simulate_cycle
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.gait.stairs import StairGeometry, stair_gait
from mjwalk.report.levelsplit import KINDS, crossings_of, level_split, walk_kinds
from mjwalk.world.workplace import load_workplace

#: The pit's depth below the floor in scenes/pit_station.xml, metres.
DEPTH = 0.51


@pytest.fixture(scope="module")
def pit(scenes_dir):
    return load_workplace(scenes_dir / "pit_station.xml")


def test_a_site_on_the_pits_bottom_stands_on_the_pit_level(pit):
    assert pit.floor_z == 0.0
    assert site_level(pit, "stand_rack") == 0
    lv = site_level(pit, "stand_pit")
    assert lv not in (0, None)
    assert pit.levels.levels[lv].height == pytest.approx(-DEPTH, abs=1e-6)
    assert spec_on_levels(pit, ["stand_rack", "stand_pit"])
    xy = pit.stations["stand_pit"].xy
    assert ground_height(pit, xy, True) == pytest.approx(-DEPTH, abs=1e-6)
    assert ground_height(pit, xy, False) == 0.0  # a flat cycle's ground


@pytest.mark.slow
def test_the_pit_cycle_walks_the_stair_with_no_contacts(scenes_dir):
    """Seeded (seed 0): one animated cycle with collisions on; the operator goes down the stair,
    fastens from the pit's bottom and climbs back; 0 contacts; the split sums to the walk time."""
    spec = load_cycle_spec(scenes_dir / "pit_station.toml")
    r = simulate_cycle(spec, 0, keep_timeline=True, collisions=True, ergonomics=False)
    assert r.collisions == []
    assert [crossings_of(w.path) for w in r.walks] == ["stair down", "stair up"]
    split = level_split([r])
    assert split is not None
    mean = split[r.group]["mean"]
    walk_time = sum(w.duration for w in r.walks)
    assert sum(mean[k] for k in KINDS) == pytest.approx(walk_time, abs=1e-6)
    assert mean["stairs"] > 0.0 and mean["level"] > 0.0
    assert mean["ramps"] == 0.0 and mean["steps"] == 0.0
    # each flight (3 risers of 0.17 m, 0.28 m treads) counts its risers' steps at the
    # operator's stair step time (mjwalk.gait.stairs, from the cited 0.58 s up and 0.46 s down
    # of the reference adult) and the trailing foot's level step off the last tread; the line-up
    # and departure steps beside the stair are level walking
    walker = r.operator
    assert walker is not None
    for w, way in zip(r.walks, ("down", "up"), strict=True):
        step = stair_gait(walker, StairGeometry(0.17, 0.28), way).step_time
        stairs = walk_kinds(w.path)["stairs"]
        assert stairs == pytest.approx(3 * step + walker.step_duration, abs=4 / 120)
    # the operator ends standing at the rack on the floor (the humanoid has the operator's
    # stature); on the pit's bottom beyond the stair (x > -0.44 m) the root stands DEPTH lower
    # (the gait's pelvis rise, a few cm, above it; lower while stooping to fasten), never a
    # floor's height
    tl = r.timeline
    root = tl.qpos[:, tl.jointmap.root : tl.jointmap.root + 3]
    standing = root[-1, 2]
    assert standing == pytest.approx(pelvis_height(r.operator.stature), abs=0.05)
    in_pit = root[:, 0] > -0.3
    assert in_pit.any()
    assert root[in_pit, 2].max() == pytest.approx(standing - DEPTH, abs=0.04)
