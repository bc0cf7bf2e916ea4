"""mjwalk.world.slabfloor: a floor given as a box, mesh or height-field slab instead of a plane
plans, animates and checks collisions like the same scene with a plane at the slab's top."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from mjwalk.errors import SceneError
from mjwalk.gait.default import default_model
from mjwalk.plan.walks import plan_walk
from mjwalk.timeline.collisions import check_collisions, floor_geoms
from mjwalk.world import load_workplace
from mjwalk.world.floor import find_floor, floor_rect, floor_top, slab_floor_mask
from mjwalk.world.slabfloor import (
    FLOOR_SHARE,
    MIN_FLOOR_AREA,
    find_floor_slabs,
    find_slab_floor,
    region_area,
    slab,
)

#: A platform 0.34 m high reached by one 0.17 m step, a crate on the floor, three sites.
LEVELS = """<mujoco model="slab_levels"><worldbody>
{floor}
<geom name="platform" type="box" size="2.2 0.8 0.17" pos="0 0 0.17"/>
<geom name="step" type="box" size="0.15 0.6 0.085" pos="-2.35 0 0.085"/>
<geom name="crate" type="box" size="0.3 0.3 0.5" pos="-2 1.4 0.5"/>
<site name="west" pos="-3.3 0 0"/><site name="on_platform" pos="1.0 0 0.34"/>
<site name="east" pos="3.5 1.2 0"/>
</worldbody></mujoco>"""
PLANE = '<geom name="floor" type="plane" size="5.25 2 0.05" pos="1.25 0 0"/>'
BOX = '<geom name="ground" type="box" size="5.25 2 0.05" pos="1.25 0 -0.05"/>'
CRATE = '<geom name="crate" type="box" size="0.3 0.3 0.5" pos="1 1 0.5"/>'


def _model(body: str, asset: str = "") -> tuple[mujoco.MjModel, mujoco.MjData]:
    xml = f"<mujoco><asset>{asset}</asset><worldbody>{body}</worldbody></mujoco>"
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    return model, data


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    d = tmp_path_factory.mktemp("slab")
    paths = []
    for tag, floor in (("plane", PLANE), ("box", BOX)):
        paths.append(d / f"{tag}.xml")
        paths[-1].write_text(LEVELS.format(floor=floor))
    return paths


def test_a_box_floor_is_the_plane_at_its_top(pair):
    plane, box = (load_workplace(p) for p in pair)
    assert box.floor == "ground" and box.floor_z == plane.floor_z == 0.0
    assert box.floor_bounds == plane.floor_bounds == (-4.0, -2.0, 6.5, 2.0)
    assert [o.name for o in box.obstacles] == [o.name for o in plane.obstacles]  # not the box
    assert np.array_equal(box.clearance.values, plane.clearance.values)
    got = [(lv.kind, lv.height) for lv in box.levels.levels]
    assert got == [(lv.kind, lv.height) for lv in plane.levels.levels]
    assert [s.name for s in box.levels.surfaces] == ["ground", "step", "platform"]
    assert (
        [k.kind for k in box.levels.links]
        == [k.kind for k in plane.levels.links]
        == [
            "step",
            "step",
        ]
    )


def test_the_box_floor_counts_as_floor_in_the_contact_check(pair):
    model = mujoco.MjModel.from_xml_path(str(pair[1]))
    mask = floor_geoms(model)
    assert mask.tolist() == [g == model.geom("ground").id for g in range(model.ngeom)]


def test_mesh_and_flat_height_field_slabs():
    mesh = (
        '<mesh name="m" vertex="-4 -3 -0.1  4 -3 -0.1  4 3 -0.1  -4 3 -0.1  '
        '-4 -3 0  4 -3 0  4 3 0  -4 3 0"/>'
    )
    model, data = _model(f'<geom name="cad" type="mesh" mesh="m"/>{CRATE}', mesh)
    g = find_floor(model, data, "s")
    assert model.geom(g).name == "cad" and floor_top(model, data, g) == pytest.approx(0, abs=1e-9)
    assert floor_rect(model, data, g) == pytest.approx((-4, -3, 4, 3), abs=1e-9)
    hf = '<hfield name="h" nrow="3" ncol="3" size="4 3 0.5 0.1" elevation="1 1 1 1 1 1 1 1 1"/>'
    model, data = _model(f'<geom name="hf" type="hfield" hfield="h" pos="0 0 0.2"/>{CRATE}', hf)
    g = find_floor(model, data, "s")
    assert model.geom(g).name == "hf" and floor_top(model, data, g) == pytest.approx(0.2)
    bumpy = '<hfield name="h" nrow="2" ncol="2" size="4 3 0.5 0.1" elevation="0 1 0 1"/>'
    model, data = _model('<geom name="hf" type="hfield" hfield="h"/>', bumpy)
    assert slab(model, data, 0) is None  # a terrain, not a floor


def test_the_lowest_large_slab_wins_and_hidden_or_small_ones_do_not_count():
    model, data = _model(
        '<geom name="roof" type="box" size="4 3 0.05" pos="0 0 3"/>'
        '<geom name="foundation" type="box" size="3 2 0.3" pos="0 0 -0.4"/>'  # inside the slab
        '<geom name="drain" type="box" size="0.3 0.3 0.05" pos="5 0 -0.3"/>'  # below, small
        '<geom name="slab" type="box" size="4 3 0.5" pos="0 0 -0.5"/>'
    )
    assert find_slab_floor(model, data, "s").name == "slab"
    assert 0.36 < MIN_FLOOR_AREA <= FLOOR_SHARE * 48  # the drain: too small to be a floor


def test_a_scene_with_no_clear_floor_names_both_slabs():
    model, data = _model(
        '<geom name="low" type="box" size="2 2 0.05" pos="0 0 -0.55"/>'
        '<geom name="deck" type="box" size="4 3 0.05" pos="3 3 -0.05"/>'
    )
    with pytest.raises(SceneError, match=r"s: no clear floor: 'low' .* 'deck' .* largest"):
        find_floor(model, data, "s")


def test_a_yawed_slab_walls_off_its_bounding_box(tmp_path):
    path = tmp_path / "yawed.xml"
    path.write_text(
        f'<mujoco><worldbody><geom name="g" type="box" size="4 3 0.05" pos="0 0 -0.05" '
        f'euler="0 0 20"/>{CRATE}<site name="a" pos="-2 0 0"/></worldbody></mujoco>'
    )
    wp = load_workplace(path)
    x0, _, _, y1 = wp.floor_bounds
    corner, centre = np.array([[x0 + 0.1, y1 - 0.1]]), np.array([[-2.0, 0.0]])
    assert wp.clearance(corner)[0] < 0 < wp.clearance(centre)[0]


def test_walks_over_a_box_floor_equal_the_planes_and_touch_nothing(pair):
    """Seeded: a walk up the step onto the platform and one on past the crate plan the same
    footfalls on the box floor as on the plane, and the body played on the box floor stands on
    it: 0 contacts."""
    model = default_model(progress=False)
    plane, box = (load_workplace(p) for p in pair)
    for start, goal, seed in (("west", "on_platform", 3), ("on_platform", "east", 4)):
        a = plan_walk(plane, start, goal, model, rng=seed)
        b = plan_walk(box, start, goal, model, rng=seed)
        assert np.array_equal(a.xy, b.xy) and np.array_equal(a.ground, b.ground)
        assert np.array_equal([s.foot for s in a.steps], [s.foot for s in b.steps])
        assert check_collisions(b, pair[1]) == []


TILES = """<mujoco><worldbody>
<geom name="tile_a" type="box" pos="-3 0 -0.05" size="1.5 2 0.05"/>
<geom name="tile_b" type="box" pos="0.005 0 -0.05" size="1.5 2 0.05"/>
<geom name="tile_c" type="box" pos="3.015 0 -0.0505" size="1.5 2 0.05"/>
<geom name="post" type="box" pos="0 1.4 0.5" size="0.2 0.2 0.5"/>
<site name="west" pos="-3.8 0 0"/><site name="east" pos="3.8 -0.3 0"/>
</worldbody></mujoco>"""


def test_a_yawed_slab_floor_is_its_own_rectangle(tmp_path):
    """The walk surface of a slab turned 30 deg is its turned 8 x 4 m rectangle, not its
    bounding box: a point in the box's corner stands on no level (before: on the floor)."""
    path = tmp_path / "yawed.xml"
    path.write_text(
        '<mujoco><worldbody><geom name="g" type="box" size="4 2 0.05" pos="0 0 -0.05" '
        'euler="0 0 30"/><site name="a" pos="-2 0 0"/></worldbody></mujoco>'
    )
    wp = load_workplace(path)
    (floor,) = wp.levels.surfaces
    assert floor.kind == "floor" and floor.area == pytest.approx(32.0)
    assert (floor.depth, floor.width) == pytest.approx((4.0, 8.0))
    x0, _, _, y1 = wp.floor_bounds
    assert wp.floor_bounds == pytest.approx(floor.footprint.bounds())  # the extent: its box
    assert wp.levels.surface_at((x0 + 0.3, y1 - 0.3)) is None
    assert wp.levels.surface_at((-2.0, 0.0)) == 0


def test_box_tiles_side_by_side_are_one_floor(tmp_path):
    """Three 3 x 4 m tiles, joints 5 and 10 mm wide and a 0.5 mm step: one floor 9.015 m long
    (before: the first tile's 3 m); the tiles are floor to the contact check; a 25 mm gap or
    a 5 mm step up parts them (ASR A1.5/1,2: norms.CONTACT_GAP, LEVEL_TOLERANCE)."""
    path = tmp_path / "tiles.xml"
    path.write_text(TILES)
    wp = load_workplace(path)
    assert wp.floor == "tile_a" and wp.floor_z == 0.0
    assert wp.floor_bounds == pytest.approx((-4.5, -2.0, 4.515, 2.0))
    model = wp.model
    mask = slab_floor_mask(model)
    assert mask.tolist() == [model.geom(g).name.startswith("tile") for g in range(model.ngeom)]
    assert [lv.height for lv in wp.levels.levels] == [0.0]
    assert wp.clearance(np.array([[1.5, 0.0], [3.0, 0.0]])).min() > 0.5  # no wall at the joints
    for gap, dz, joined in ((0.025, 0.0, False), (0.0, -0.005, False), (0.0, 0.0035, True)):
        tiles = TILES.replace('pos="3.015 0 -0.0505"', f'pos="{3.005 + gap} 0 {-0.05 - dz}"')
        m, d = _model(tiles.split("<worldbody>")[1].split("</worldbody>")[0])
        names = [t.name for t in find_floor_slabs(m, d, "s")]
        assert names == (["tile_a", "tile_b", "tile_c"] if joined else ["tile_a", "tile_b"])


def test_small_tiles_together_make_a_floor():
    """Four 0.8 x 0.8 m tiles (0.64 m^2 each, under MIN_FLOOR_AREA alone) make a 2.56 m^2
    floor; a deck larger than one tile but smaller than them all is no rival."""
    tiles = "".join(
        f'<geom name="t{i}" type="box" size="0.4 0.4 0.05" pos="{x} {y} -0.05"/>'
        for i, (x, y) in enumerate(((0, 0), (0.8, 0), (0, 0.8), (0.8, 0.8)))
    )
    deck = '<geom name="deck" type="box" size="0.6 0.6 0.05" pos="5 0 0.25"/>'
    model, data = _model(tiles + deck)
    got = find_floor_slabs(model, data, "s")
    assert [s.name for s in got] == ["t0", "t1", "t2", "t3"] and region_area(got) == pytest.approx(
        2.56
    )
    assert MIN_FLOOR_AREA > 0.64


def test_walks_across_tile_joints_touch_nothing(tmp_path):
    """Seeded: a walk from the first tile to the third, over both joints, plans (before: the
    goal lay off the floor) and its body touches nothing: 0 contacts."""
    path = tmp_path / "tiles.xml"
    path.write_text(TILES)
    model = default_model(progress=False)
    wp = load_workplace(path)
    walk = plan_walk(wp, "west", "east", model, rng=0)
    assert walk.xy[0, 0] < -3 and walk.xy[-1, 0] > 3
    assert check_collisions(walk, path) == []


def test_the_contact_check_finds_the_slab_floor_once_per_model(pair, monkeypatch):
    """The slab floor is kept per model: two contact checks of a timeline search for it once
    (the model's first ask), not once a report (with a ConvexHull for a mesh slab)."""
    from mjwalk.body.humanoid import attach_humanoid, pelvis_height
    from mjwalk.timeline.collisions import collision_report
    from mjwalk.timeline.timeline import Timeline
    from mjwalk.world import floor as floor_module

    calls = []
    real = floor_module.find_floor_slabs
    monkeypatch.setattr(floor_module, "find_floor_slabs", lambda *a: calls.append(1) or real(*a))
    mj, jm = attach_humanoid(str(pair[1]), 1.75)
    q = jm.neutral_qpos(mj, 1.75)
    q[jm.root : jm.root + 3] = [-3.3, 0.0, pelvis_height(1.75)]
    tl = Timeline(model=mj, jointmap=jm, fps=30.0, t=np.arange(3) / 30.0,
                  qpos=np.tile(q, (3, 1)), scene=str(pair[1]), stature=1.75)  # fmt: skip
    for _ in range(3):
        assert collision_report(tl) == []
    assert len(calls) == 1
