"""mjwalk.ergonomics.angles: the body angles measured on the humanoid by forward kinematics
read back its own hinge angles."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.humanoid import humanoid_model, pelvis_height
from mjwalk.ergonomics import rula
from mjwalk.ergonomics.angles import angles_from_qpos


def humanoid_angles(**joints):
    """The body angles of the humanoid standing, with the hinge angles ``joints`` (deg)."""
    model, jm = humanoid_model()
    q = jm.neutral_qpos(model)
    for name, deg in joints.items():
        q[jm.adr(name)] = np.radians(deg)
    q[jm.root + 2] = pelvis_height(1.75)
    return angles_from_qpos(model, jm, q[None])


def test_neutral_humanoid_measures_neutral():
    a = humanoid_angles()
    assert abs(a.trunk_flexion[0]) < 1e-6 and abs(a.neck_flexion[0]) < 1e-6
    assert np.allclose(a.upper_arm_angle[0], 0.0, atol=1e-6)
    assert np.allclose(a.elbow_flexion[0], 0.0, atol=1e-6)
    assert a.legs_supported[0]
    p = rula.part_scores(a, 0)
    assert (p.upper_arm[0], p.neck[0], p.trunk[0], p.legs[0]) == (1, 1, 1, 1)


@pytest.mark.parametrize("deg", [10.0, 30.0, 60.0, 100.0])
def test_joint_angles_read_back(deg):
    """The body angles measured by forward kinematics equal the humanoid's hinge angles; the
    trunk's flexion (pelvis to C7) follows a lumbar flexion, less the part of the trunk below
    the lumbar joint."""
    a = humanoid_angles(shoulder_l_flex=deg, elbow_l=deg / 2, neck_flex=deg / 3)
    assert a.upper_arm_angle[0, 0] == pytest.approx(deg, abs=1e-6)
    assert a.upper_arm_elevation[0, 0] == pytest.approx(deg, abs=1e-6)
    assert a.elbow_flexion[0, 0] == pytest.approx(deg / 2, abs=1e-6)
    assert a.neck_flexion[0] == pytest.approx(deg / 3, abs=1e-6)
    b = humanoid_angles(lumbar_flex=deg / 2)
    assert 0.8 * deg / 2 < b.trunk_flexion[0] <= deg / 2 + 1e-9
    assert b.trunk_inclination[0] == pytest.approx(b.trunk_flexion[0])
