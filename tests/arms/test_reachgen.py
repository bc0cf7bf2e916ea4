"""The reach generator (mjwalk.arms.reachgen): shapes, grasp apertures, a human wrist and elbow,
and the working area the reaches end in."""

import numpy as np
import pytest

from mjwalk.anthropometry import ROM_DEG
from mjwalk.arms import reachgen
from mjwalk.arms.chain import ARM_JOINTS, arm_joint_angles, end_effector
from mjwalk.errors import MjwalkError


def test_generator_shapes_and_grasp_aperture():
    data = reachgen.generate("grasp", 20, np.random.default_rng(1))
    assert data.directions.shape == (20, 20, 3, 3)
    np.testing.assert_allclose(end_effector(data.directions, data.lengths), data.hand, atol=1e-9)
    size = data.constraints[:, 0]
    ap = data.extras[:, :, 0]
    # aperture closes on the object (+-2 mm noise) after opening wider than it
    assert np.abs(ap[:, -1] - size).max() < 0.01
    assert (ap.max(1) > size + 0.005).all()  # MGA = 0.8 size + 3.5 cm
    with pytest.raises(MjwalkError, match="unknown constraint space"):
        reachgen.generate("dance", 3, np.random.default_rng(0))


def test_generated_reaches_keep_a_human_wrist_and_elbow():
    """The generator's reaches start with a neutral wrist, keep it in its functional range
    (Ryu et al. 1991), every joint within the humanoid's range of motion, and the elbow swung
    out (abducted) from the hanging arm, not in towards the chest. Before: the hand hung 51
    deg back from the forearm at the start and 81 deg mid-reach (beyond the humanoid's 70 deg),
    and the elbow started 9 cm medial of the shoulder (adducted 16 deg, median)."""
    data = reachgen.generate("endpoints", 80, np.random.default_rng(3))
    q = np.degrees(np.array([arm_joint_angles(u) for u in data.directions]))  # (p, n, 7)
    (flex_lo, flex_hi), (dev_lo, dev_hi) = reachgen.FUNCTIONAL_WRIST
    assert np.abs(q[:, 0, 5:7]).max() < 1.0  # a neutral wrist at the start
    assert flex_lo - 1e-6 <= q[..., 5].min() and q[..., 5].max() <= flex_hi + 1e-6
    assert dev_lo - 1e-6 <= q[..., 6].min() and q[..., 6].max() <= dev_hi + 1e-6
    for k, joint in enumerate(ARM_JOINTS):
        lo, hi = ROM_DEG[joint]
        assert lo - 1e-6 <= q[..., k].min() and q[..., k].max() <= hi + 1e-6, joint
    assert np.median(q[:, 0, 1]) > 5.0  # shoulder abduction at the start (measured 13 deg)
    assert np.median(data.directions[:, 0, 0, 1]) > 0.0  # the elbow lateral (+y, left arm)
    # the ends cover the working area, across the body's midline
    lo, hi = np.array(reachgen.END_BOX).T
    ends = data.hand[:, -1]
    assert ((ends >= lo) & (ends <= hi)).all()
    assert (ends[:, 1] < -0.2).any()
