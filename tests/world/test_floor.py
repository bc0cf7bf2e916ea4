"""mjwalk.world.floor: which plane is the floor, and floors too large to plan on."""

from __future__ import annotations

import mujoco
import pytest

from mjwalk.errors import SceneError
from mjwalk.world.floor import MAX_FLOOR_NODES, check_floor_nodes, check_floor_size, find_floor


def _model(body: str) -> tuple[mujoco.MjModel, mujoco.MjData]:
    model = mujoco.MjModel.from_xml_string(f"<mujoco><worldbody>{body}</worldbody></mujoco>")
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    return model, data


def test_the_plane_named_floor_wins_else_the_lowest():
    model, data = _model(
        '<geom name="deck" type="plane" pos="0 0 -1" size="1 1 .1"/>'
        '<geom name="Floor" type="plane" size="1 1 .1"/>'
    )
    assert find_floor(model, data, "s") == 1
    model, data = _model(
        '<geom name="a" type="plane" pos="0 0 1" size="1 1 .1"/>'
        '<geom name="b" type="plane" pos="0 0 -1" size="1 1 .1"/>'
    )
    assert find_floor(model, data, "s") == 1


def test_no_floor_or_a_tilted_one_is_named():
    model, data = _model('<geom type="box" size=".3 .3 1"/>')  # a box too small to be a floor
    with pytest.raises(SceneError, match="s: no floor"):
        find_floor(model, data, "s")
    model, data = _model('<geom name="ramp" type="plane" size="1 1 .1" euler="10 0 0"/>')
    with pytest.raises(SceneError, match=r"plane 'ramp' is tilted 10\.0 deg"):
        find_floor(model, data, "s")


def test_floor_node_limit():
    check_floor_nodes((0.0, 0.0, 100.0, 100.0), 0.02, "s", "floor")  # 2.5e7 nodes
    side = (MAX_FLOOR_NODES**0.5) * 0.02
    with pytest.raises(SceneError, match="the floor 'floor' spans"):
        check_floor_nodes((0.0, 0.0, 2 * side, side), 0.02, "s", "floor")
    with pytest.raises(SceneError, match="no finite extent"):
        check_floor_nodes((0.0, 0.0, float("inf"), 1.0), 0.02, "s", "floor")
    model, _ = _model('<geom name="floor" type="plane" size="500 500 .1"/>')
    with pytest.raises(SceneError, match="spans 1000 x 1000 m"):
        check_floor_size(model, "s")
