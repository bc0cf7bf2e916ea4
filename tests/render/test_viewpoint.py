"""The tracking camera's viewpoint: a clear line of sight to the legs, moving smoothly."""

from __future__ import annotations

import copy
import os

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco
import numpy as np
import pytest

from mjwalk.body.humanoid import HUMAN_GROUP
from mjwalk.errors import MjwalkError
from mjwalk.plan.synthetic import synthetic_walk as make_walk
from mjwalk.render.viewpoint import (
    MAX_TURN_RATE,
    TARGETS,
    TRACK_ELEVATION,
    fixed_view,
    preferred_azimuth,
    sight_lines,
    track_view,
)
from mjwalk.timeline import timeline_from_walk

FLOOR = """<geom name="floor" type="plane" size="10 10 .1" rgba=".2 .6 .2 1"/>
<light pos="0 0 6" dir="0 0 -1" directional="true"/>"""
#: a 2.5 m wall along the walk (+x from the origin), 1.5 m to its left: between the walker
#: and the default camera, which stands on the walker's left (+y), 3.4 m away
WALL = '<geom name="wall" type="box" size="4 .05 1.25" pos="1.5 1.5 1.25" rgba=".5 .5 .5 1"/>'
FEET = [TARGETS.index("foot_l"), TARGETS.index("foot_r")]


def scene(*geoms: str) -> mujoco.MjSpec:
    return mujoco.MjSpec.from_string(
        f"<mujoco><worldbody>{FLOOR}{''.join(geoms)}</worldbody></mujoco>"
    )


@pytest.fixture(scope="module")
def walled():
    return timeline_from_walk(make_walk(n_steps=5), scene(WALL), fps=30)


def test_open_floor_keeps_the_preferred_camera():
    tl = timeline_from_walk(make_walk(n_steps=4), scene(), fps=30)
    view = track_view(tl)
    # exactly the fixed camera (so its frames are identical to before): walker's left, 15 deg
    assert view.preferred == pytest.approx(-90.0)  # walking +x: the left is +y
    assert np.all(view.azimuth == preferred_azimuth(tl))
    assert np.all(view.elevation == TRACK_ELEVATION)
    assert view.visible.all()


def test_wall_between_camera_and_walker_is_avoided(walled):
    tl = walled
    view = track_view(tl)
    # the default position sees no foot behind the wall; the chosen one sees both nearly always
    assert view.visible_preferred[:, FEET].mean() < 0.05
    assert view.visible[:, FEET].all(1).mean() > 0.9
    # independent check of the chosen angles at every 4th frame (not only the samples)
    frames = np.arange(0, tl.n_frames, 4)
    seen = sight_lines(tl, frames, view.azimuth[frames], view.elevation[frames])
    assert seen[:, FEET].all(1).mean() > 0.9
    # smooth: no jumps beyond the turn-rate bound (per frame, degrees)
    step = np.abs(np.diff(view.azimuth)) + np.abs(np.diff(view.elevation))
    assert step.max() <= MAX_TURN_RATE / tl.fps + 1e-6


def test_chosen_camera_shows_the_feet_in_the_image(walled):
    render = pytest.importorskip("mjwalk.render.video")
    tl = walled
    i = tl.n_frames // 2
    view = track_view(tl)
    hidden = copy.copy(tl.model)  # the same scene and camera without the humanoid drawn
    hidden.geom_group[hidden.geom_group == HUMAN_GROUP] = HUMAN_GROUP - 1  # group not shown
    bg_tl = type(tl)(**{**tl.__dict__, "model": hidden})
    data = mujoco.MjData(tl.model)
    data.qpos[:] = tl.qpos[i]
    mujoco.mj_kinematics(tl.model, data)
    feet = np.array(
        [data.body(f"{tl.jointmap.prefix}{b}").xpos for b in ("foot_l", "foot_r", "toes_l")]
    )
    shown = {}
    try:
        for label, v in (("chosen", view), ("fixed", fixed_view(tl))):
            imgs = []
            for t in (tl, bg_tl):
                ((_, img, r),) = render.render_frames(
                    t, "track", (320, 240), frames=[i], draw_path=False, view=v
                )
                if t is tl:
                    uv = np.round(render.project(r, feet)).astype(int)
                imgs.append(img.astype(int))
            human = np.abs(imgs[0] - imgs[1]).sum(-1) > 30  # pixels where the humanoid shows
            inside = (uv[:, 0] >= 3) & (uv[:, 0] < 317) & (uv[:, 1] >= 3) & (uv[:, 1] < 237)
            shown[label] = [
                bool(human[v_ - 3 : v_ + 4, u - 3 : u + 4].any())
                for (u, v_), ok in zip(uv, inside, strict=True)
                if ok
            ]
    except MjwalkError as exc:
        pytest.skip(str(exc))
    assert len(shown["chosen"]) == 3 and all(shown["chosen"])  # feet in the image, visible
    assert not any(shown["fixed"])  # behind the wall from the default position
