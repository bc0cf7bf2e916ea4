"""Rising on the toes for a reach (mjwalk.cycle.tiptoe): the heels lift the ankles by the rise
asked, the balls of the feet stay where they stood, the toes lie flat, the body leans until
its centre of mass is over the balls, the joints stay in their ranges, and the way up
(crouch_frames) keeps the balls planted at every pose."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from mjwalk.anthropometry import ROM_DEG, ball_offset, leg_geometry
from mjwalk.cycle.context import context_of
from mjwalk.cycle.crouch import crouch_frames
from mjwalk.cycle.poses import frame_contacts, standing_pose
from mjwalk.cycle.tiptoe import (
    BALANCE_TOLERANCE,
    PLANTARFLEXION_SHARE,
    RISE_STEP,
    heel_angle,
    heel_rise_of,
    max_rise,
    rise_steps,
    tiptoe_frames,
    tiptoe_pose,
)


@pytest.fixture(scope="module")
def ctx(scenes_dir):
    return context_of(scenes_dir / "shelving_station.toml")


def _points(ctx, q) -> dict[str, np.ndarray]:
    """World positions of the ankles' and toes' joints (the toe joint: the ball of the foot)."""
    m, jm = ctx.model, ctx.jointmap
    d = mujoco.MjData(m)
    d.qpos[:] = q
    mujoco.mj_kinematics(m, d)
    return {
        f"{j}_{p}": d.xanchor[
            m.joint(f"{jm.prefix}{j}_{p}{'_flex' if j == 'ankle' else ''}").id
        ].copy()
        for j in ("ankle", "toe")
        for p in "lr"
    }


def _com_behind_balls(ctx, q) -> float:
    """How far (m) the centre of mass lies behind the mean of the balls of the feet, along the
    pelvis's heading."""
    m, jm = ctx.model, ctx.jointmap
    d = mujoco.MjData(m)
    d.qpos[:] = q
    mujoco.mj_kinematics(m, d)
    mujoco.mj_comPos(m, d)
    pelvis = m.body(f"{jm.prefix}pelvis").id
    ahead = d.xmat[pelvis].reshape(3, 3)[:, 0]
    pts = _points(ctx, q)
    balls = 0.5 * (pts["toe_l"] + pts["toe_r"])
    return float((balls - d.subtree_com[pelvis])[:2] @ ahead[:2] / np.linalg.norm(ahead[:2]))


@pytest.mark.parametrize("stature", [1.45, 1.53, 1.75, 2.0])
def test_the_heel_angle_lifts_the_ankle_by_the_rise_about_the_ball(stature):
    geom = leg_geometry(stature)
    b, a = ball_offset(geom), geom.ankle_height
    for rise in (0.01, 0.04, max_rise(stature)):
        t = heel_angle(rise, geom)
        assert 0.0 < t < math.radians(50.0)
        assert b * math.sin(t) + a * math.cos(t) - a == pytest.approx(rise, abs=1e-12)
    assert heel_angle(0.0, geom) == 0.0 and heel_angle(-0.1, geom) == 0.0
    # the highest rise is the ankle's lift at 90 % of its 50 deg plantar flexion range
    top = PLANTARFLEXION_SHARE * math.radians(-ROM_DEG["ankle_flex"][0])
    assert heel_angle(max_rise(stature), geom) == pytest.approx(top, abs=1e-12)


def test_the_rises_tried_are_centimetre_steps_up_to_the_highest():
    assert max_rise(1.53) == pytest.approx(0.073, abs=5e-4)  # 7.3 cm at 1.53 m
    assert max_rise(1.45) < max_rise(1.53) < max_rise(1.75)  # a larger foot lifts higher
    steps = rise_steps(1.53)
    assert steps[0] == RISE_STEP and steps[-1] <= max_rise(1.53) < steps[-1] + RISE_STEP
    np.testing.assert_allclose(np.diff(steps), RISE_STEP)


@pytest.mark.parametrize("rise", [0.02, 0.07])
def test_on_the_toes_the_balls_stay_planted_and_the_ankles_rise(ctx, rise):
    jm = ctx.jointmap
    q0 = standing_pose(ctx, -2.6, -1.65, -1.2)
    q = tiptoe_pose(ctx, q0, rise)
    before, after = _points(ctx, q0), _points(ctx, q)
    for p in "lr":
        # the ball of the foot (toe joint) where it stood, within a millimetre
        assert np.linalg.norm(after[f"toe_{p}"] - before[f"toe_{p}"]) < 1e-3
        assert after[f"ankle_{p}"][2] - before[f"ankle_{p}"][2] == pytest.approx(rise, abs=1e-3)
        # the toes extended by the heel angle: flat on the floor (the ankle's own angle is the
        # heel angle less the shank's forward lean, in its range below)
        t = heel_angle(rise, leg_geometry(ctx.spec.stature))
        assert q[jm.adr(f"toe_{p}")] == pytest.approx(t)
        assert heel_rise_of(ctx, q) == pytest.approx(rise, abs=1e-12)
        for name in (f"ankle_{p}_flex", f"toe_{p}", f"knee_{p}", f"hip_{p}_flex"):
            lo, hi = jm.limits(name)
            assert lo - 1e-9 <= q[jm.adr(name)] <= hi + 1e-9
    # the pelvis rises by the rise less what the legs' lean costs (a few millimetres to 1.5 cm)
    assert rise - 0.015 < q[jm.root + 2] - q0[jm.root + 2] <= rise
    # balanced: the centre of mass over the balls of the feet (standing: over the ankles)
    assert abs(_com_behind_balls(ctx, q)) < BALANCE_TOLERANCE
    assert _com_behind_balls(ctx, q0) > 0.1
    assert frame_contacts(ctx, q[None]) == []  # the toes rest on the floor, no deeper
    assert np.array_equal(tiptoe_pose(ctx, q0, 0.0), q0)


def test_the_way_up_onto_the_toes_keeps_the_balls_planted(ctx):
    jm = ctx.jointmap
    q0 = standing_pose(ctx, -2.6, -1.65, -1.2)
    q = tiptoe_pose(ctx, q0, 0.06)
    w = np.linspace(0.0, 1.0, 7)
    frames = crouch_frames(ctx, q0, q, w)
    np.testing.assert_allclose(frames, tiptoe_frames(ctx, q0, 0.06, w), atol=1e-12)
    np.testing.assert_allclose(frames[0], q0, atol=1e-12)
    np.testing.assert_allclose(frames[-1], q, atol=1e-12)
    balls = _points(ctx, q0)
    for f in frames:
        now = _points(ctx, f)
        for p in "lr":
            assert np.linalg.norm(now[f"toe_{p}"] - balls[f"toe_{p}"]) < 1e-3
    assert np.all(np.diff(frames[:, jm.root + 2]) > 0)  # the pelvis goes up all the way
