"""mjwalk.timeline.reachscene: the checks reach_in_scene makes before it solves a reach (the
solved reaches themselves are tested with the reach models, tests/arms/test_reach.py)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import MjwalkError
from mjwalk.timeline.reachscene import SceneReachOptions, reach_in_scene


def test_options_default_to_an_endpoint_reach_of_1_2_s_at_30_fps():
    o = SceneReachOptions()
    assert (o.constraint, o.duration, o.fps, o.object_size) == (None, 1.2, 30.0, None)


def test_bad_side_constraint_and_sites_are_refused(scenes_dir):
    scene = scenes_dir / "assembly_station.xml"
    with pytest.raises(MjwalkError, match="side"):
        reach_in_scene(scene, None, "stand_rack2", "rack2_screw2", side="up")
    with pytest.raises(MjwalkError, match="mirrors"):
        reach_in_scene(scene, None, "stand_rack2", "rack2_screw2", side="right",
                       options=SceneReachOptions(constraint=np.zeros(6)))  # fmt: skip
    with pytest.raises(MjwalkError, match="no site 'nowhere'"):
        reach_in_scene(scene, None, "stand_rack2", "nowhere")
    with pytest.raises(MjwalkError, match="no site 'nowhere'"):
        reach_in_scene(scene, None, "nowhere", "rack2_screw2")


_PLATFORM = """<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <geom name="deck" type="box" pos="{dx} 0 {hz}" size="1 1 {hz}"/>
    <site name="stand" pos="{x} 0 {z}" euler="0 0 90"/>
    <site name="target" pos="{x} 0.45 {tz}"/>
  </worldbody>
</mujoco>
"""


def _platform_xml(tmp_path, name: str, deck: float) -> str:
    """A scene with a 2 x 2 m deck 0.34 m high, a stand site ``deck`` m high (on the deck at
    0.34, else on the floor 4 m beside it) and a target 0.45 m ahead and 1.0 m above it."""
    path = tmp_path / f"{name}.xml"
    dx = 2.0 if deck else -2.0
    path.write_text(_PLATFORM.format(x=2.0, dx=dx, hz=0.17, z=deck, tz=deck + 1.0))
    return str(path)


def test_ground_under_is_the_surface_below_a_stand_site(tmp_path):
    import mujoco

    from mjwalk.timeline.reachscene import ground_under

    m = mujoco.MjModel.from_xml_path(_platform_xml(tmp_path, "deck", 0.34))
    d = mujoco.MjData(m)
    mujoco.mj_kinematics(m, d)
    assert ground_under(m, d, [0.0, 0.0, 0.0]) == 0.0  # on the floor plane: exactly 0
    assert abs(ground_under(m, d, [2.0, 0.0, 0.34]) - 0.34) < 1e-12  # on the deck
    assert abs(ground_under(m, d, [2.0, 0.0, 0.338]) - 0.34) < 1e-12  # 2 mm under its top
    assert abs(ground_under(m, d, [2.0, 0.0, 1.5]) - 0.34) < 1e-12  # high above it
    assert ground_under(m, d, [9.0, 9.0, 0.5]) == 0.0  # over nothing: z = 0


def test_a_reach_from_a_platform_is_the_floor_reach_lifted(tmp_path):
    """The same reach on a 0.34 m deck and on the floor (target 1 m above the feet in both):
    the same joint angles, the pelvis 0.34 m higher (before: at the floor's pelvis height,
    the deck in the legs)."""
    from mjwalk.arms import reachgen
    from mjwalk.arms.reach import ReachModel

    data = reachgen.generate("endpoints", 60, np.random.default_rng(0))
    model = ReachModel(data.lengths).fit(data.constraints, data.directions)
    low, _ = reach_in_scene(_platform_xml(tmp_path, "floor", 0.0), model, "stand", "target")
    high, _ = reach_in_scene(_platform_xml(tmp_path, "deck", 0.34), model, "stand", "target")
    r = low.jointmap.root
    assert np.allclose(np.delete(high.qpos, r + 2, axis=1), np.delete(low.qpos, r + 2, axis=1),
                       rtol=0.0, atol=1e-9)  # fmt: skip
    assert np.allclose(high.qpos[:, r + 2] - low.qpos[:, r + 2], 0.34, rtol=0.0, atol=1e-12)
