"""The alignment pose (mjwalk.arms.armpose): sphere exp/log, angular scaling, rotation vectors
and the pose fit."""

import numpy as np
from scipy.spatial.transform import Rotation
from test_armrep import _synthetic_set

from mjwalk.arms.armpose import (
    angular_scale,
    apply_pose,
    fit_poses,
    remove_pose,
    remove_poses,
    rotvec_matrix,
    sphere_exp,
    sphere_log,
)


def test_pose_apply_remove_is_exact_inverse():
    U = _synthetic_set(1, 0)[0]
    c = np.array([0.0, 0.6, -0.8])
    pose = np.array([0.2, -0.1, 0.3, 0.15])
    np.testing.assert_allclose(remove_pose(c, apply_pose(c, U, pose), pose), U, atol=1e-12)


def test_sphere_log_exp_invert_and_scaling_scales_the_angle():
    c = np.array([0.0, 0.0, -1.0])
    a = np.array([[np.sin(0.4), 0.0, -np.cos(0.4)], [0.0, np.sin(1.0), -np.cos(1.0)]])
    w = sphere_log(c, a)
    np.testing.assert_allclose(np.linalg.norm(w, axis=1), [0.4, 1.0])
    np.testing.assert_allclose(sphere_exp(c, w), a, atol=1e-12)
    np.testing.assert_allclose(
        np.linalg.norm(sphere_log(c, angular_scale(c, a, 0.5)), axis=1), [0.2, 0.5]
    )
    np.testing.assert_allclose(sphere_log(c, c[None]), 0.0)  # the centre maps to 0


def test_rotvec_matrix_matches_scipy_and_batched_fit_recovers_poses():
    for r in ([0.0, 0.0, 0.0], [1e-4, 2e-4, -1e-4], [0.3, -1.2, 0.8]):
        np.testing.assert_allclose(
            rotvec_matrix(np.array(r)), Rotation.from_rotvec(r).as_matrix(), atol=1e-15
        )
    c = np.array([0.0, 0.0, -1.0])
    A = _synthetic_set(3, 4)  # aligned-like movements (3, 15, 2, 3)
    target = A[0]
    poses = np.array([[0.1, -0.05, 0.2, 0.1], [-0.2, 0.1, 0.0, -0.15], [0.0, 0.0, 0.0, 0.0]])
    U = np.array([apply_pose(c, target, x) for x in poses])
    got = fit_poses(c, U, target)
    np.testing.assert_allclose(got, poses, atol=1e-5)
    np.testing.assert_allclose(remove_poses(c, U, got), [target] * 3, atol=1e-6)
    np.testing.assert_allclose(remove_pose(c, U[0], got[0]), target, atol=1e-6)
