"""mjwalk.world.floor: which plane is the floor, and floors too large to plan on."""

from __future__ import annotations

import mujoco
import pytest

from mjwalk.errors import SceneError
from mjwalk.world.floor import (
    MAX_FLOOR_NODES,
    check_floor_nodes,
    check_floor_size,
    find_floor,
    flush_geoms,
    geom_z_extents,
)


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


#: A floor with what lies on it: tape 2 mm thick (flush), a 15 mm mat (no trip-free 4 mm: not
#: flush), an inlaid plate sunk from -3 to +1 mm (flush), a pit wall box reaching 1 m down
#: (not flush), tape on a moving body (not flush) and an upright strip 3 cm tall (not flush).
FLUSH_SCENE = """<mujoco><worldbody><geom name="floor" type="plane" size="5 5 .1"/>
<geom name="tape" type="box" size="2 .025 .001" pos="0 0 .001"/>
<geom name="mat" type="box" size=".75 .45 .0075" pos="0 1 .0075"/>
<geom name="inlay" type="box" size=".3 .3 .002" pos="1 -1 -.001"/>
<geom name="wall" type="box" size=".5 .1 .5" pos="-2 -2 -.5"/>
<geom name="tape_up" type="box" size="1 .001 .015" pos="0 -2 .015"/>
<body name="cart" pos="2 2 0"><freejoint/>
<geom name="tape_cart" type="box" size=".2 .2 .001"/></body>
</worldbody></mujoco>"""


def _flush_names(xml: str, levels: tuple[float, ...] = ()) -> set[str]:
    """The names of a scene's geoms flush with its floor (and with the ``levels``' heights)."""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    mask = flush_geoms(model, data, levels)
    return {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) for g in mask.nonzero()[0]}


def test_flush_geoms_are_the_static_ones_within_the_level_tolerance_of_the_floor():
    assert _flush_names(FLUSH_SCENE) == {"tape", "inlay"}


def test_flush_geoms_on_a_slab_floor_are_those_on_its_top():
    """A floor given as a box (no plane): the tape on its top is flush, the box itself is not."""
    xml = FLUSH_SCENE.replace(
        '<geom name="floor" type="plane" size="5 5 .1"/>',
        '<geom name="floor" type="box" size="5 5 .05" pos="0 0 -.05"/>',
    )
    assert xml != FLUSH_SCENE
    assert _flush_names(xml) == {"tape", "inlay"}


def test_flush_geoms_on_a_level_are_those_within_the_tolerance_of_its_top():
    """Tape 3 mm thick on a 0.34 m platform is flush with the platform's top when its height
    is given (the contact check gives its walk surfaces'); a 15 mm mat on it is not, nor the
    platform itself; without the level only the floor's tape is flush, as before."""
    xml = FLUSH_SCENE.replace(
        "<body",
        '<geom name="platform" type="box" size="2 .5 .17" pos="0 3 .17"/>'
        '<geom name="ptape" type="box" size=".025 .5 .0015" pos="-1 3 .3415"/>'
        '<geom name="pmat" type="box" size=".6 .35 .0075" pos=".6 3 .3475"/><body',
    )
    assert _flush_names(xml) == {"tape", "inlay"}
    assert _flush_names(xml, (0.0, 0.34)) == {"tape", "inlay", "ptape"}
    assert _flush_names(xml, (0.34 + 0.005,)) == {"tape", "inlay"}  # 5 mm off: no longer


def test_geom_z_extents_are_the_world_heights_of_upright_and_turned_geoms():
    xml = """<mujoco><worldbody><geom name="floor" type="plane" size="5 5 .1"/>
<geom name="mat" type="box" size=".75 .45 .0075" pos="0 1 .0075" euler="0 0 30"/>
<geom name="beam" type="box" size=".5 .1 .1" pos="1 0 1" euler="0 90 0"/>
</worldbody></mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    bottom, top = geom_z_extents(model, data)
    assert (bottom[1], top[1]) == pytest.approx((0.0, 0.015))  # turned about z: exact
    assert (bottom[2], top[2]) == pytest.approx((0.5, 1.5))  # stood on end: its length


def test_flush_geoms_kept_per_model_follow_the_levels_and_a_moved_geom():
    """The mask is kept per model by the levels and where the static geoms lie: asked again it
    is the same (a copy the caller may change), another level or a static geom moved (its
    placement recomputed) gives that case's mask, as a model of its own would."""
    xml = FLUSH_SCENE.replace(
        "<body", '<geom name="ptape" type="box" size=".025 .5 .0015" pos="-1 3 .3415"/><body'
    )
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    first = flush_geoms(model, data, (0.34,))
    first[:] = False  # the caller's copy
    again = flush_geoms(model, data, (0.34,))
    assert again.any() and again.tolist() == flush_geoms(model, data, [0.34]).tolist()
    assert flush_geoms(model, data).tolist() != again.tolist()  # without the level: no ptape
    tape = model.geom("tape").id
    model.geom_pos[tape, 2] += 0.02  # lifted 2 cm: no longer flush
    mujoco.mj_kinematics(model, data)
    lifted = flush_geoms(model, data, (0.34,)).tolist()
    assert lifted == [bool(v) and g != tape for g, v in enumerate(again)]  # the rest as before
