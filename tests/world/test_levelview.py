"""Level views (mjwalk.world.levelview): each level as a flat workplace for the planners."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import InputError
from mjwalk.plan.occupancy import CELL_SIZE, MOVES_16, shared_grid
from mjwalk.world import levelview, load_workplace
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


def test_a_view_s_field_is_kept_in_the_workplace_cache_bit_for_bit(
    scenes_dir, tmp_path, monkeypatch
):
    folder = tmp_path / "workplaces"  # an empty workplace cache
    monkeypatch.delenv("MJWALK_CACHE_DIR", raising=False)
    monkeypatch.setenv("MJWALK_CACHE", str(tmp_path))

    def views(cache):
        """The floor's and the mezzanine's views for a 1.83 m head, in a new workplace."""
        wp = load_workplace(scenes_dir / "multilevel_station.xml", cache=cache)
        mezz = level_at(wp, wp.station("stand_mezz_rack").xy)
        return [level_view(wp, lv, 1.83) for lv in (0, mezz)]

    def files(what):
        return sorted(folder.glob(f"*-{what}.npy")) if folder.exists() else []

    plain = views(False)  # cache=False: built, nothing written, no key
    assert not files("levelview") and all(v.cache_key is None for v in plain)
    written = views(None)  # the default: built and stored
    assert len(files("levelview")) == 2
    built = []
    real = levelview.build_clearance

    def counting(*args, **kwargs):
        built.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(levelview, "build_clearance", counting)
    read = views(None)  # a later process's: read back, not built
    assert not built
    for p, w, r in zip(plain, written, read, strict=True):
        assert w.cache_key is not None and r.cache_key == w.cache_key
        assert r.floor_bounds == p.floor_bounds and (r.clearance.x0, r.clearance.y0) == (
            p.clearance.x0,
            p.clearance.y0,
        )
        assert r.clearance.values.dtype == p.clearance.values.dtype
        assert w.clearance.values.tobytes() == p.clearance.values.tobytes()
        assert r.clearance.values.tobytes() == p.clearance.values.tobytes()
    # a keyed view's occupancy grids are kept beside its field, the same cells and moves
    grid = shared_grid(read[1], CELL_SIZE, 0.25, MOVES_16)
    same = shared_grid(plain[1], CELL_SIZE, 0.25, MOVES_16)
    assert files("free") and files("moves")
    assert np.array_equal(grid.free, same.free) and np.array_equal(grid.moves, same.moves)
