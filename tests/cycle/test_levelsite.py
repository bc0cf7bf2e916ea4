"""Cycle sites on the levels of a scene (issue 47): standing sites on platforms and the
mezzanine are accepted by the spec loader, placed on their level's height, and a flat cycle
never builds the levels."""

from __future__ import annotations

import pytest

from mjwalk.cycle.levelsite import (
    ground_height,
    level_room,
    level_workplace,
    site_level,
    spec_on_levels,
)
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import CycleSpecError
from mjwalk.world.workplace import load_workplace


@pytest.fixture(scope="module")
def station(scenes_dir):
    return load_workplace(scenes_dir / "multilevel_station.xml")


def _height(wp, level):
    return wp.levels.levels[level].height - wp.floor_z


def test_standing_sites_stand_on_their_levels(station):
    assert site_level(station, "stand_stair") == 0
    plat, mezz = site_level(station, "stand_platform1"), site_level(station, "stand_mezz_rack")
    assert plat not in (0, None) and mezz not in (0, None)
    assert _height(station, plat) == pytest.approx(0.34, abs=1e-6)
    assert _height(station, mezz) == pytest.approx(1.02, abs=1e-6)
    assert site_level(station, "car_roof1") is None  # on the car's roof: no walk surface
    assert spec_on_levels(station, ["stand_stair", "stand_mezz_rack"])
    assert not spec_on_levels(station, ["stand_stair", "stand_rack1"])


def test_ground_and_room_are_the_levels(station):
    xy = station.stations["stand_platform1"].xy
    assert ground_height(station, xy, True) == pytest.approx(0.34, abs=1e-6)
    assert ground_height(station, xy, False) == 0.0  # a flat cycle: the floor
    view = level_workplace(station, site_level(station, "stand_platform1"))
    assert level_room(station, xy, True) == pytest.approx(float(view.walk_clearance(xy)))
    # on the floor's workplace the platform is an obstacle: no room there
    assert level_room(station, xy, False) <= 0.0
    # a step back off the platform's edge has no room on the platform's level
    off = (float(xy[0]), 2.5)
    assert level_room(station, off, True, home=xy) <= 0.0


def _spec(tmp_path, scenes_dir, site: str, start: str = "stand_stair") -> str:
    path = tmp_path / "c.toml"
    path.write_text(
        f'scene = "{scenes_dir / "multilevel_station.xml"}"\nstart = "{start}"\n'
        "[walking]\nradius = 0.25\n"
        f'[[task]]\nkind = "walk"\nsite = "{site}"\n'
    )
    return str(path)


def test_a_spec_with_a_site_on_a_level_is_accepted(tmp_path, scenes_dir):
    spec = load_cycle_spec(_spec(tmp_path, scenes_dir, "stand_mezz_rack"))
    assert spec.tasks[0].site == "stand_mezz_rack"
    spec = load_cycle_spec(_spec(tmp_path, scenes_dir, "stand_platform2", "stand_mezz_rack"))
    assert spec.start == "stand_mezz_rack"


def test_a_site_on_no_walk_surface_is_refused(tmp_path, scenes_dir):
    with pytest.raises(CycleSpecError, match="not a standing place"):
        load_cycle_spec(_spec(tmp_path, scenes_dir, "car_roof1"))
