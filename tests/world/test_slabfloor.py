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
from mjwalk.world.floor import find_floor, floor_rect, floor_top
from mjwalk.world.slabfloor import FLOOR_SHARE, MIN_FLOOR_AREA, find_slab_floor, slab

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
