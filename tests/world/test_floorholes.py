"""mjwalk.world.floorholes: a floor with an opening (a pit reached by a stair) is written as
boxes around the opening over a plane at the pit's bottom; the workplace's floor is the boxes'
tops, the opening is a wall on the floor, and the level graph gives the floor at 0, the pit at
its depth and the stair between them (issue 47)."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from mjwalk.errors import SceneError
from mjwalk.world.floorholes import FLOOR_BOX_PREFIX, floor_boxes, opening_area
from mjwalk.world.footprint import Footprint
from mjwalk.world.workplace import workplace_from_model


@pytest.fixture(scope="module")
def pit(pit_xml):
    return workplace_from_model(mujoco.MjModel.from_xml_string(pit_xml))


def test_floor_boxes_are_found_and_plain_floors_have_none(pit_xml):
    model = mujoco.MjModel.from_xml_string(pit_xml)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    boxes = floor_boxes(model, data, 0, "pit")
    assert FLOOR_BOX_PREFIX == "floor_"
    assert boxes is not None and boxes.height == pytest.approx(0.0) and len(boxes.geoms) == 4
    flat = mujoco.MjModel.from_xml_string(
        '<mujoco><worldbody><geom name="floor" type="plane" size="2 2 0.1"/>'
        '<geom name="floorplate" type="box" pos="0 0 0.01" size="0.5 0.5 0.01"/>'
        "</worldbody></mujoco>"
    )
    d = mujoco.MjData(flat)
    mujoco.mj_kinematics(flat, d)
    assert floor_boxes(flat, d, 0, "flat") is None


@pytest.mark.parametrize(
    ("geom", "match"),
    [
        ('<geom name="floor_x" type="box" pos="0 0 -0.2" size="1 1 0.05"/>', "tops differ"),
        (  # a rack named floor_...: the message names it and the naming rule
            '<geom name="floor_rack_shelf" type="box" pos="3 2 1.0" size="0.4 0.25 0.02"/>',
            r"'floor_rack_shelf' at 1\.020 m, .* geoms named 'floor_\.\.\.' are the floor's boxes",
        ),
        ('<geom name="floor_x" type="sphere" pos="0 0 -0.2" size="0.1"/>', "must be a box"),
    ],
)
def test_bad_floor_boxes_are_refused_in_one_line(geom, match, pit_xml):
    model = mujoco.MjModel.from_xml_string(pit_xml.replace("</worldbody>", geom + "</worldbody>"))
    with pytest.raises(SceneError, match=match) as err:
        workplace_from_model(model)
    assert "\n" not in str(err.value)


def test_the_floor_is_at_the_boxes_and_the_opening_is_a_wall(pit):
    assert pit.floor_z == 0.0
    assert pit.floor_bounds == (-4.0, -3.0, 4.0, 3.0)
    assert float(pit.walk_clearance((0.0, 0.5))) < -0.9  # the opening's middle: 1 m from its rim
    assert float(pit.walk_clearance((-1.5, 0.5))) == pytest.approx(0.5, abs=0.02)
    assert float(pit.walk_clearance((-3.0, -2.0))) == pytest.approx(1.0, abs=0.02)
    assert [f.name for f in pit.obstacles] == ["rack"]  # the boxes and the treads are not


def test_level_graph_gives_the_floor_the_pit_and_the_stair(pit):
    graph = pit.levels
    heights = [round(lv.height, 3) for lv in graph.levels]
    assert heights == [0.0, -0.51, -0.34, -0.17]
    assert graph.levels[0].kind == "floor"
    # areas: the floor boxes' 44 m2, the pit's 2 x 2 m opening (not the 8 x 6 m plane under it)
    assert graph.levels[0].area == pytest.approx(44.0)
    assert graph.levels[1].area == pytest.approx(4.0)
    assert {graph.surfaces[i].name for i in graph.levels[0].surfaces} == {
        f"floor_{k}" for k in range(4)
    }
    (stair,) = graph.links
    assert stair.kind == "stair" and (stair.lower, stair.upper) == (1, 0)
    assert stair.risers == pytest.approx((0.17, 0.17, 0.17), abs=1e-6)
    assert stair.tread == pytest.approx(0.28, abs=1e-6)
    assert graph.reachable(0, max_riser=0.19) == {0, 1}  # the treads are the stair's via
    assert graph.reachable(0, max_riser=0.15) == {0}  # a riser above the walker's limit
    # where a point stands: in the pit on the plane, beside it on the floor boxes
    assert graph.level_of[graph.surface_at((0.5, 0.5))] == 1
    assert graph.level_of[graph.surface_at((-2.0, 0.5))] == 0


def test_a_deeper_opening_without_a_stair_is_not_a_level(pit_xml):
    xml = pit_xml.replace('<geom name="s1"', '<geom name="s1" contype="0"').replace(
        'size="0.14 1 0.17"', 'size="0.14 1 0.17" group="4"'
    )
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    from mjwalk.world.surfaces import SurfaceOptions, find_walk_surfaces

    surfaces = find_walk_surfaces(model, data, SurfaceOptions(groups=frozenset({0})))
    names = {s.name for s in surfaces}
    assert "s2" not in names and "floor" not in names  # 0.34 m below the floor: no step
    assert np.isclose(surfaces[0].z, 0.0)


def _rect(x0, y0, x1, y1):
    return Footprint("r", -1, np.array([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], dtype=float))


def test_opening_area_counts_overlapping_boxes_once():
    plane = _rect(-2, -2, 2, 2)  # 16 m2
    boxes = (_rect(-2, -2, 2, 0), _rect(-2, -1, 0, 2))  # 8 + 6 m2 of which 2 m2 overlap
    assert opening_area(plane, boxes) == pytest.approx(16 - 12)
    assert opening_area(plane, (_rect(-3, -3, 3, 3),)) == pytest.approx(0.0)
