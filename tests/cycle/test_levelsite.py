"""Cycle sites on the levels of a scene (issue 47): standing sites on platforms and the
mezzanine are accepted by the spec loader, placed on their level's height, and a flat cycle
never builds the levels."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.cycle.context import prepare
from mjwalk.cycle.levelsite import (
    START_MARGIN,
    ground_height,
    level_room,
    level_workplace,
    reach_room,
    site_level,
    spec_on_levels,
)
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.cycle.types import TASK_KINDS
from mjwalk.cycle.walking import standing_spot, start_zone
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


def test_a_reach_step_keeps_the_start_margin_on_levels_only(station):
    """The stand-off's least room: the body radius in a flat cycle (today's rule), the radius
    plus START_MARGIN in a cycle over levels (its walks set off without turning on the spot),
    never more than the room where the operator stands."""
    assert reach_room(0.25, False, 0.43) == 0.25
    assert reach_room(0.25, True, 0.43) == pytest.approx(0.25 + START_MARGIN)
    assert reach_room(0.25, True, 0.27) == 0.27
    assert reach_room(0.25, False, 0.20) == 0.20
    # issue 47, run 1 of `mjwalk simulate scenes/multilevel_station.toml --runs 5`: the fastening
    # from stand_platform1 stepped in 0.14 m to (-1.113, 2.952), 0.252 m from the platform's edge,
    # and the next walk found no first step; that spot is now refused
    home, spot = (-1.138, 3.130), (-1.113, 2.952)
    here = level_room(station, home, True)
    assert level_room(station, spot, True, home=home) < reach_room(0.25, True, here)


def test_spots_drawn_on_a_level_keep_the_levels_clearance(scenes_dir):
    """Seeded: spots drawn in every stand zone of the multi-level cycle (on the floor, the
    platform and the mezzanine), 40 draws each, keep the body radius plus START_MARGIN from
    their own level's edges and obstacles, measured in the level's view (level_view)."""
    ctx = prepare(load_cycle_spec(scenes_dir / "multilevel_station.toml"))
    assert ctx.on_levels
    step = ctx.step_model.pace().step_length
    stature = ctx.spec.stature
    zones = [start_zone(ctx.spec, ctx.workplace, stature, step)]
    for i, task in enumerate(ctx.spec.tasks):
        if TASK_KINDS[task.kind].motion == "walk":
            zones.append(ctx.zone(i, stature, step))
    levels = set()
    need = ctx.spec.radius + START_MARGIN
    for zone in zones:
        levels.add(site_level(ctx.workplace, _site_at(ctx, zone.centre)))
        for seed in range(40):
            xy = standing_spot(ctx, zone, np.random.default_rng(seed))
            assert zone.contains(xy)
            room = level_room(ctx.workplace, xy, True, home=zone.centre)
            assert room >= need - 1e-9, (zone.centre, xy, room)
    assert len(levels) >= 3  # the floor, the platform and the mezzanine


def _site_at(ctx, xy) -> str:
    """The standing site whose stand zone is centred at ``xy``."""
    for name, st in ctx.workplace.stations.items():
        if np.hypot(*(np.asarray(st.xy, dtype=float)[:2] - xy)) < 1e-9:
            return name
    raise AssertionError(f"no site at {xy}")


def test_a_site_a_hair_under_a_decks_top_stands_on_it(tmp_path):
    """Generated hall 0 (bench_unseen, issue 47): its mezzanine site was written 0.1 mm under
    the deck's top (both rounded to 0.1 mm); the cycle refused it as "not a standing place"
    though the floor's check takes either side. The generator now writes the deck's top
    exactly (``mjwalk.world.levelgendims``), so the site is put 0.1 mm under it here."""
    from mjwalk.world.levelgen import generate_levels
    from mjwalk.world.workplace import load_workplace

    hall = generate_levels(0)
    site = 'name="mezz_0" pos="-6.3759 -1.0341 1.3188"'
    assert site in hall.xml
    xml = hall.xml.replace(site, 'name="mezz_0" pos="-6.3759 -1.0341 1.3187"')
    (tmp_path / "hall0.xml").write_text(xml)
    wp = load_workplace(tmp_path / "hall0.xml", cache=False)
    lv = site_level(wp, "mezz_0")
    assert lv is not None
    assert wp.levels.levels[lv].height - wp.stations["mezz_0"].pos[2] == pytest.approx(
        1e-4, abs=5e-5
    )
    assert site_level(wp, "pedestal_0") is None
