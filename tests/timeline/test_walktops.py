"""mjwalk.timeline.walktops: the walk tops and the horizontal walk surfaces' heights of a
timeline's scene as the contact check reads them, only for a scene file on several levels."""

from __future__ import annotations

import mujoco
import pytest
from test_collisions import _MULTI, _stair_walk
from test_frames import _scene

from mjwalk.plan.synthetic import synthetic_walk as make_walk
from mjwalk.timeline import timeline_from_walk
from mjwalk.timeline.walktops import level_heights, walk_tops


def test_level_heights_are_the_horizontal_surfaces_of_a_scene_on_levels():
    """The multi-level station: the floor, the step's tread and the platform (0.17, 0.34 m), the
    stair's treads (0.17 m apart) and the mezzanine (1.02 m); not the 5.5 deg ramp."""
    tl = timeline_from_walk(_stair_walk("up"), _MULTI)
    assert level_heights(tl) == pytest.approx((0.0, 0.17, 0.34, 0.51, 0.68, 0.85, 1.02))
    tops = walk_tops(tl)
    assert tops is not None and tops.flags.writeable is False
    names = {mujoco.mj_id2name(tl.model, mujoco.mjtObj.mjOBJ_GEOM, g) for g in tops.nonzero()[0]}
    assert {"platform", "platform_ramp", "mezzanine", "stair_tread1"} <= names
    assert "floor" not in names


def test_a_flat_scene_or_an_mjspec_has_none():
    assert level_heights(timeline_from_walk(make_walk(n_steps=2), _scene(20.0))) == ()  # MjSpec
    flat = _MULTI.parent / "assembly_station.xml"
    tl = timeline_from_walk(make_walk(n_steps=2), flat)
    assert level_heights(tl) == () and walk_tops(tl) is None
