"""Leg kinematics (mjwalk.body.legs.ik): rotations, the analytic IK and FK."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from mjwalk.body.humanoid import humanoid_model, leg_geometry
from mjwalk.body.legs.ik import (
    foot_lowest,
    leg_fk,
    leg_ik,
    rot_x,
    rot_y,
    rot_z,
)
from mjwalk.conventions import side_of_prefix


def test_rotations_are_right_handed_and_batched():
    """rot_z/rot_y/rot_x are proper rotations (orthonormal, det 1) of any batch shape and turn
    the axes the right-handed way: z by 90 deg takes +x to +y, y takes +z to +x, x takes +y
    to +z."""
    a = np.linspace(-3, 3, 12).reshape(3, 4)
    for rot in (rot_z, rot_y, rot_x):
        R = rot(a)
        assert R.shape == (3, 4, 3, 3)
        assert np.allclose(R @ np.swapaxes(R, -1, -2), np.eye(3))
        assert np.allclose(np.linalg.det(R), 1.0)
    q = np.array(np.pi / 2)
    assert np.allclose(rot_z(q) @ [1, 0, 0], [0, 1, 0])
    assert np.allclose(rot_y(q) @ [0, 0, 1], [1, 0, 0])
    assert np.allclose(rot_x(q) @ [0, 1, 0], [0, 0, 1])


def test_ik_round_trip():
    g = leg_geometry()
    model, jm = humanoid_model()
    data = mujoco.MjData(model)
    rng = np.random.default_rng(0)
    checked = 0
    for _ in range(40):
        target = np.array(
            [rng.uniform(-0.25, 0.25), g.hip_y + rng.uniform(-0.05, 0.05), -rng.uniform(0.55, 0.78)]
        )
        yaw, pitch = rng.uniform(-0.3, 0.3), rng.uniform(-0.2, 0.1)
        ang = leg_ik(
            (target - [0, g.hip_y, 0])[None], np.array([yaw]), np.array([pitch]), "left", g
        )
        if any(np.isclose(v[0], jm.limits(k)).any() for k, v in ang.items()):
            continue  # clipped at a joint limit: the pose is not reachable exactly
        checked += 1
        q = jm.neutral_qpos(model)
        q[:3] = 0
        for k, v in ang.items():
            q[jm.adr(k)] = v[0]
        data.qpos[:] = q
        mujoco.mj_kinematics(model, data)
        assert np.allclose(data.xpos[model.body("foot_l").id], target, atol=1e-6)
        R = data.xmat[model.body("foot_l").id].reshape(3, 3)
        assert abs(np.arcsin(R[2, 0]) - pitch) < 0.01  # foot x axis rises by the pitch
        assert abs(R[2, 1]) < 0.01  # sole level sideways (2-DOF ankle: tiny yaw residual)
    assert checked >= 5


def test_leg_fk_matches_mujoco():
    """leg_fk / foot_lowest agree with MuJoCo's forward kinematics of the humanoid."""
    g = leg_geometry()
    model, jm = humanoid_model()
    data = mujoco.MjData(model)
    rng = np.random.default_rng(1)
    for side in "lr":
        ang = {
            n.format(side): rng.uniform(*np.radians(r), size=20)
            for n, r in (
                ("hip_{}_rot", (-30, 30)),
                ("hip_{}_flex", (-25, 60)),
                ("hip_{}_abd", (-10, 20)),
                ("knee_{}", (0, 90)),
                ("ankle_{}_flex", (-40, 15)),
                ("ankle_{}_inv", (-10, 20)),
                ("toe_{}", (-20, 50)),
            )
        }
        ankle, R = leg_fk(ang, side_of_prefix(side), g)
        low = foot_lowest(ang, side_of_prefix(side), g)
        for i in range(20):
            q = jm.neutral_qpos(model)
            q[:3] = [0, 0, 2.0]
            for k, v in ang.items():
                q[jm.adr(k)] = v[i]
            data.qpos[:] = q
            mujoco.mj_kinematics(model, data)
            hip = data.xpos[model.body(f"thigh_{side}").id]
            assert np.allclose(data.xpos[model.body(f"foot_{side}").id] - hip, ankle[i], atol=1e-9)
            assert np.allclose(data.xmat[model.body(f"foot_{side}").id].reshape(3, 3), R[i])
            z = []
            for gname in (f"foot_{side}", f"toes_{side}"):
                gid = model.geom(gname).id
                Rg = data.geom_xmat[gid].reshape(3, 3)
                z.append(data.geom_xpos[gid][2] - np.abs(Rg[2] * model.geom_size[gid]).sum())
            assert min(z) - hip[2] == pytest.approx(low[i], abs=1e-9)
