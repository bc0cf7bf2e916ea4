"""The humanoid's motion exported as BVH is read back by mjwalk's own BVH reader to the same
joint angles (within 0.1 deg) and the same body positions; the joint-angle CSV."""

from __future__ import annotations

import csv

import mujoco
import numpy as np
import pytest

from mjwalk.body.humanoid import humanoid_model, pelvis_height
from mjwalk.ergonomics.export import P, bvh_hinge_angles, write_angles_csv, write_bvh
from mjwalk.mocap.bvh import bvh_forward_kinematics, parse_bvh
from mjwalk.timeline.timeline import Timeline


@pytest.fixture(scope="module")
def timeline():
    """40 frames of random poses within the joints' ranges, the root moving and turning."""
    model, jm = humanoid_model(1.68)
    rng = np.random.default_rng(3)
    n = 40
    q = np.tile(jm.neutral_qpos(model, 1.68), (n, 1))
    for k, name in enumerate(jm.names):
        if name == "root":
            continue
        lo, hi = jm.range[k]
        q[:, jm.adr(name)] = rng.uniform(lo, hi, n)
    r = jm.root
    q[:, r : r + 3] = [0.3, -0.2, pelvis_height(1.68)] + rng.normal(0, 0.05, (n, 3))
    yaw = rng.uniform(-np.pi, np.pi, n)
    tilt = rng.normal(0, 0.2, n)
    q[:, r + 3 : r + 7] = np.stack(
        [np.cos(yaw / 2) * np.cos(tilt / 2), -np.sin(yaw / 2) * np.sin(tilt / 2),
         np.cos(yaw / 2) * np.sin(tilt / 2), np.sin(yaw / 2) * np.cos(tilt / 2)], axis=1
    )  # fmt: skip
    return Timeline(model=model, jointmap=jm, fps=30.0, t=np.arange(n) / 30.0, qpos=q)


def test_bvh_round_trip_gives_the_joint_angles(tmp_path, timeline):
    path = write_bvh(timeline, tmp_path / "run.bvh")
    bvh = parse_bvh(path)
    assert bvh.fps == 30.0 and bvh.motion.shape[0] == timeline.n_frames
    angles = bvh_hinge_angles(bvh, timeline.model, timeline.jointmap)
    hinges = [n for n in timeline.jointmap.names if n != "root"]
    assert set(angles) == set(hinges)
    worst = max(
        np.abs(np.degrees(angles[n] - timeline.qpos[:, timeline.jointmap.adr(n)])).max()
        for n in hinges
    )
    assert worst < 0.1  # degrees (written to 1e-6 deg)


def test_bvh_round_trip_gives_the_body_positions(tmp_path, timeline):
    """mjwalk's BVH forward kinematics of the file puts every joint where MuJoCo puts the
    humanoid's body (the root's rotation, every hinge and offset together)."""
    bvh = parse_bvh(write_bvh(timeline, tmp_path / "run.bvh"))
    pos = bvh_forward_kinematics(bvh) / 100.0 @ P  # BVH cm, Y up -> metres, z up
    model = timeline.model
    data = mujoco.MjData(model)
    worst = 0.0
    for f, q in enumerate(timeline.qpos):
        data.qpos[:] = q
        mujoco.mj_kinematics(model, data)
        for j, name in enumerate(bvh.names):
            b = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name)
            worst = max(worst, float(np.linalg.norm(pos[f, j] - data.xpos[b])))
    assert worst < 1e-4  # metres


def test_angles_csv(tmp_path, timeline):
    path = write_angles_csv(timeline, tmp_path / "angles.csv")
    rows = list(csv.reader(path.open()))
    head = rows[0]
    assert len(rows) == 1 + timeline.n_frames
    k = head.index("elbow_l_deg")
    got = np.array([float(r[k]) for r in rows[1:]])
    want = np.degrees(timeline.qpos[:, timeline.jointmap.adr("elbow_l")])
    assert np.abs(got - want).max() < 1e-3
    assert "body_trunk_flexion_deg" in head
