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
