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
    assert level_view(station, 0) is not station  # it has a ramp: its floor view has its sides
    with pytest.raises(InputError, match="no level"):
        level_view(flat, 1)
    with pytest.raises(InputError, match="head height"):
        level_view(station, 0, 9.0)


def test_a_ramps_low_sides_are_obstacles_of_the_floor(station):
    """The 5.5 deg ramp (x 2.2..5.731, y 2.7..3.7, its top 0 at x 5.731) is an obstacle of the
    floor's view from 4 mm above the floor up (a trip edge: norms.LEVEL_TOLERANCE), not only
    above the band's 0.05 m foot (x < 5.21) as in the workplace itself: 0.3 m beside its low
    corner a walker's middle is now 0.25-0.3 m from it; its foot stays free (the crossing's
    stance 0.33 m beyond it keeps the body radius)."""
    view = level_view(station, 0)
    tol = np.tan(np.radians(5.5))
    reach = 5.731 - 0.004 / tol  # where the ramp's top is 4 mm above the floor
    beside = np.array([5.6, 2.4])
    assert float(station.walk_clearance(beside)) > 0.35  # 0.05 m up at x 5.21 only
    assert float(view.walk_clearance(beside)) == pytest.approx(0.3, abs=0.03)
    assert float(view.walk_clearance(np.array([5.731 + 0.33, 3.2]))) > 0.25
    assert float(view.walk_clearance(np.array([reach + 0.1, 3.2]))) == pytest.approx(0.1, abs=0.03)


def test_head_height_sets_the_band(station):
    low = level_view(station, 0, 1.0)  # a head at 1 m: the 1.0 m rack shelves are not in its way
    high = level_view(station, 0, 1.83)
    assert len(low.obstacles) < len(high.obstacles)
