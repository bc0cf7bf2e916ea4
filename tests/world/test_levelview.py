"""Level views (mjwalk.world.levelview): each level as a flat workplace for the planners."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import InputError
from mjwalk.world import load_workplace
from mjwalk.world.levelview import level_at, level_view


@pytest.fixture(scope="module")
def station(scenes_dir):
    return load_workplace(scenes_dir / "multilevel_station.xml")


def test_sites_stand_on_their_levels(station):
    levels = station.levels.levels
    assert level_at(station, station.station("stand_step").xy, 0.0) == 0
    assert levels[level_at(station, station.station("stand_platform1").xy, 0.34)].height == (
        pytest.approx(0.34)
    )
    mezz = level_at(station, station.station("stand_mezz_rack").xy, None)
    assert levels[mezz].height == pytest.approx(1.02)


def test_a_level_view_walls_its_edges_and_keeps_its_obstacles(station):
    mezz = level_at(station, station.station("stand_mezz_rack").xy)
    view = level_view(station, mezz, 1.83)
    assert view.floor_bounds == pytest.approx((-6.0, -4.5, -3.8, -1.5))
    assert view.floor_z == pytest.approx(1.02)
    names = {f.name for f in view.obstacles}
    assert "mezz_rack_frame_l" in names and "mezzanine" not in names
    assert float(view.walk_clearance(station.station("stand_mezz_rack").xy)) > 0.25
    assert float(view.walk_clearance(np.array([-4.9, -1.6]))) == pytest.approx(0.1, abs=0.02)
    assert level_view(station, mezz, 1.83) is view  # kept


def test_flat_views_are_the_workplace(scenes_dir, station):
    flat = load_workplace(scenes_dir / "assembly_station.xml")
    fingerprint = flat.fingerprint
    assert len(flat.levels.levels) == 1 and not flat.levels.links
    assert level_view(flat, 0) is flat and flat.fingerprint == fingerprint
    assert level_view(station, 0) is station
    with pytest.raises(InputError, match="no level"):
        level_view(flat, 1)
    with pytest.raises(InputError, match="head height"):
        level_view(station, 0, 9.0)


def test_head_height_sets_the_band(station):
    low = level_view(station, 0, 1.0)  # a head at 1 m: the 1.0 m rack shelves are not in its way
    high = level_view(station, 0, 1.83)
    assert len(low.obstacles) < len(high.obstacles)
