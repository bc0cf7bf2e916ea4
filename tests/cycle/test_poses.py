"""mjwalk.cycle.poses: the standing pose, turning on the spot at the turning speed (and the
step during the turn), the palms' positions and the two-handed carrying posture."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.body.humanoid import pelvis_height
from mjwalk.cycle.context import context_of
from mjwalk.cycle.poses import (
    MIN_TURN,
    TURN_SPEED,
    carry_pose,
    hand_points,
    standing_pose,
    turn_frames,
)
from mjwalk.timeline.frames import yaw_quat


@pytest.fixture(scope="module")
def ctx(scenes_dir):
    return context_of(scenes_dir / "assembly_station.toml")


def test_the_standing_pose_stands_at_the_spot_facing_yaw(ctx):
    q = standing_pose(ctx, 0.4, -0.3, 1.2)
    r = ctx.jointmap.root
    np.testing.assert_allclose(q[r : r + 3], [0.4, -0.3, pelvis_height(ctx.spec.stature)])
    np.testing.assert_allclose(q[r + 3 : r + 7], yaw_quat(np.array([1.2]))[0])


def test_a_turn_goes_at_the_turning_speed_and_ends_facing_its_yaw(ctx):
    frames, seconds = turn_frames(ctx, (0.0, 0.0), 0.0, math.pi / 2, 30.0)
    assert seconds == pytest.approx(max(MIN_TURN, (math.pi / 2) / TURN_SPEED), abs=1 / 30)
    assert len(frames) == round(seconds * 30.0)
    r = ctx.jointmap.root
    np.testing.assert_allclose(frames[-1, r + 3 : r + 7], yaw_quat(np.array([math.pi / 2]))[0])
    _, dt = turn_frames(ctx, (0.0, 0.0), 0.0, 0.01, 30.0)
    assert dt == pytest.approx(MIN_TURN, abs=1 / 30)  # the shortest turn


def test_a_turn_with_a_step_moves_the_pelvis_there(ctx):
    frames, _ = turn_frames(ctx, (0.0, 0.0), 0.0, 0.0, 30.0, to=(-0.3, 0.0))
    r = ctx.jointmap.root
    np.testing.assert_allclose(frames[-1, r : r + 2], [-0.3, 0.0], atol=1e-12)
    assert np.all(np.diff(frames[:, r]) < 0.0)  # steadily back


def test_the_carrying_posture_holds_the_palms_the_parts_width_apart(ctx):
    q = carry_pose(ctx, standing_pose(ctx, 0.0, 0.0, 0.0), 0.40)
    palms = hand_points(ctx, q[None])
    assert palms.shape == (1, 2, 3)
    assert float(np.linalg.norm(palms[0, 0] - palms[0, 1])) == pytest.approx(0.40, abs=1e-3)


def test_a_turn_settling_from_a_landing_keeps_the_feet_on_the_floor(ctx):
    # a landing pose (hip, knee and ankle flexed): blended joint by joint into the standing pose
    # its toes would dip 4 mm into the floor; the settle lifts the pelvis of those frames
    import mujoco  # deferred: only this test poses the humanoid itself

    from mjwalk.body.legs.footcheck import lowest_point

    m, jm = ctx.model, ctx.jointmap
    r = jm.root
    landing = standing_pose(ctx, 0.0, 0.0, 0.0)
    for name in ("hip_r_flex", "knee_r", "ankle_r_flex"):
        landing[jm.adr(name)] = 0.4
    frames, _ = turn_frames(ctx, (0.0, 0.0), 0.0, 1.0, 30.0, settle=landing)
    data = mujoco.MjData(m)
    feet = [m.geom(f"{jm.prefix}{g}").id for g in ("foot_l", "foot_r", "toes_l", "toes_r")]
    lows = []
    for q in frames:
        data.qpos[:] = q
        mujoco.mj_kinematics(m, data)
        lows.append(lowest_point(m, data, feet))
    assert min(lows) > -1e-12  # on or above the floor, to round-off
    assert frames[:, r + 2].max() > landing[r + 2] + 1e-3  # settled, and lifted
    assert frames[-1, r + 2] == pytest.approx(standing_pose(ctx, 0.0, 0.0, 1.0)[r + 2], abs=1e-9)
