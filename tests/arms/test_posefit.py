"""The compiled endpoint pose fit (mjwalk.arms.posefit)."""

import numpy as np

from mjwalk.arms.armpose import apply_pose
from mjwalk.arms.chain import end_effector
from mjwalk.arms.posefit import fit_endpoint_pose


def _aligned(seed):
    """(2, 2, 3) unit directions of upper arm and forearm at the first and last sample."""
    rng = np.random.default_rng(seed)
    a = np.array([[[0.0, 0.2, -1.0], [0.3, 0.1, -1.0]], [[0.6, 0.3, -0.8], [1.0, 0.2, 0.1]]])
    a = a + rng.normal(0.0, 0.02, a.shape)
    return a / np.linalg.norm(a, axis=-1, keepdims=True)


def test_the_pose_that_made_the_hand_ends_is_found_again():
    center = np.array([0.0, 0.0, -1.0])
    a = _aligned(0)
    lengths = np.array([0.3, 0.25])
    pose = np.array([0.1, -0.2, 0.15, 0.2])
    targets = end_effector(apply_pose(center, a, pose), lengths)  # (2, 3) metres
    x, ok = fit_endpoint_pose(center, a, lengths, targets, np.zeros(4))
    assert ok
    np.testing.assert_allclose(end_effector(apply_pose(center, a, x), lengths), targets, atol=1e-9)
    np.testing.assert_allclose(x, pose, atol=1e-6)


def test_a_scale_beyond_its_bounds_is_reported_as_not_converged():
    center = np.array([0.0, 0.0, -1.0])
    a = _aligned(1)
    lengths = np.array([0.3, 0.25])
    targets = end_effector(apply_pose(center, a, np.array([0.0, 0.0, 0.0, 0.8])), lengths)
    x, ok = fit_endpoint_pose(center, a, lengths, targets, np.zeros(4), (-0.3, 0.3))
    assert not ok  # the log scale ends on its bound: the caller hands it to scipy
    assert np.isclose(x[3], 0.3)
