"""mjwalk.ergonomics.angles: the body angles measured on the humanoid by forward kinematics
read back its own hinge angles."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.humanoid import humanoid_model, pelvis_height
from mjwalk.ergonomics import rula
from mjwalk.ergonomics.angles import POINTS, angles_from_points, angles_from_qpos


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


def humanoid_motion(n: int, **joints) -> np.ndarray:
    """(2n, nq) qpos of the humanoid: n frames standing, then n frames with the hinge angles
    ``joints`` (deg); with the model and joint map."""
    model, jm = humanoid_model()
    q = jm.neutral_qpos(model)
    q[jm.root + 2] = pelvis_height(1.75)
    qpos = np.tile(q, (2 * n, 1))
    for name, deg in joints.items():
        qpos[n:, jm.adr(name)] = np.radians(deg)
    return model, jm, qpos


def test_frames_selects_the_frames_of_every_array():
    model, jm, qpos = humanoid_motion(3, shoulder_l_flex=100.0)
    a = angles_from_qpos(model, jm, qpos, walking=np.arange(6) < 2)
    assert a.n_frames == 6 and a.hands.shape == (6, 2, 3)
    b = a.frames(slice(3, None))
    assert b.n_frames == 3 and b.twist_range == a.twist_range
    np.testing.assert_array_equal(b.upper_arm_angle, a.upper_arm_angle[3:])
    assert not b.walking.any() and a.walking[:2].all()
    assert a.upper_arm_angle[4, 0] == pytest.approx(100.0, abs=1e-6)


def test_angles_from_points_of_an_upright_capture():
    """Joint positions of an upright person (x forward, y left): neutral trunk and neck,
    arms hanging; the grip points default to the wrists, the wrist angles to zero."""
    z = 1.0
    pts = {
        "pelvis": (0, 0, z), "neck": (0, 0, z + 0.5), "head": (0, 0, z + 0.7),
        "shoulder_l": (0, 0.2, z + 0.5), "shoulder_r": (0, -0.2, z + 0.5),
        "elbow_l": (0, 0.2, z + 0.2), "elbow_r": (0, -0.2, z + 0.2),
        "wrist_l": (0, 0.2, z - 0.05), "wrist_r": (0, -0.2, z - 0.05),
        "hip_l": (0, 0.1, z), "hip_r": (0, -0.1, z), "knee_l": (0, 0.1, 0.5),
        "knee_r": (0, -0.1, 0.5), "ankle_l": (0, 0.1, 0.08), "ankle_r": (0, -0.1, 0.08),
    }  # fmt: skip
    p = {k: np.array([v], dtype=float) for k, v in pts.items()}
    assert set(p) == set(POINTS)
    a = angles_from_points(p)
    assert a.trunk_flexion[0] == pytest.approx(0.0) and a.neck_flexion[0] == pytest.approx(0.0)
    np.testing.assert_allclose(a.upper_arm_angle[0], 0.0, atol=1e-9)
    np.testing.assert_allclose(a.forward[0], [1.0, 0.0, 0.0])
    np.testing.assert_array_equal(a.hands[0], [pts["wrist_l"], pts["wrist_r"]])
    assert not a.wrist_flexion.any() and a.feet_down.all() and a.legs_supported[0]


def test_arm_elevation_is_from_the_vertical_whatever_the_trunk_does():
    """A person stooped 45 deg forward (x forward, y left): an arm hanging plumb is elevated
    0 deg from the vertical (what exposure.py and ISO 11226's inclinometric reading judge) and
    45 deg from the trunk's downward axis (RULA's upper-arm angle); an arm held straight forward,
    horizontally (reaching into a low shelf from the stoop) is elevated 90 deg from the vertical
    and 135 deg from the trunk: a stooped reach passes 60 deg by either definition."""
    z, s = 1.0, np.sqrt(0.5)
    neck = np.array([0.5 * s, 0.0, z + 0.5 * s])  # the trunk axis 45 deg forward
    pts = {
        "pelvis": (0, 0, z), "neck": neck, "head": neck + (0.2 * s, 0, 0.2 * s),
        "shoulder_l": neck + (0, 0.2, 0), "shoulder_r": neck + (0, -0.2, 0),
        "elbow_l": neck + (0, 0.2, -0.3), "elbow_r": neck + (0.3, -0.2, 0),
        "wrist_l": neck + (0, 0.2, -0.55), "wrist_r": neck + (0.55, -0.2, 0),
        "hip_l": (0, 0.1, z), "hip_r": (0, -0.1, z), "knee_l": (0, 0.1, 0.5),
        "knee_r": (0, -0.1, 0.5), "ankle_l": (0, 0.1, 0.08), "ankle_r": (0, -0.1, 0.08),
    }  # fmt: skip
    a = angles_from_points({k: np.array([v], dtype=float) for k, v in pts.items()})
    assert a.trunk_flexion[0] == pytest.approx(45.0)
    np.testing.assert_allclose(a.upper_arm_elevation[0], [0.0, 90.0], atol=1e-9)
    np.testing.assert_allclose(a.upper_arm_angle[0], [45.0, 135.0], atol=1e-9)


def test_angles_from_a_shared_geom_table_are_the_same_bit_for_bit():
    """Body angles read from a table of the humanoid's geom poses (a cycle's, shared with its
    contact check) are the numbers computed from the poses alone."""
    from mjwalk.timeline.geomposes import geom_table

    model, jm, qpos = humanoid_motion(5, shoulder_l_flex=70.0, lumbar_flex=30.0, knee_r=40.0)
    qpos[:, jm.root] += np.linspace(0.0, 1.0, len(qpos))  # walking along x
    table = geom_table(model, qpos, np.arange(model.ngeom))
    a, b = angles_from_qpos(model, jm, qpos), angles_from_qpos(model, jm, qpos, table=table)
    for name in a.__dataclass_fields__:
        x, y = getattr(a, name), getattr(b, name)
        assert np.asarray(x).tobytes() == np.asarray(y).tobytes(), name


def test_select_first_is_np_select_value_for_value():
    """select_first gives np.select's values and dtype (first true condition wins, NaN
    compares false) over seeded inputs, with array and scalar choices and scalar conditions."""
    from mjwalk.ergonomics.angles import select_first

    rng = np.random.default_rng(50)
    for _ in range(200):
        x = rng.normal(scale=60.0, size=int(rng.integers(1, 400)))
        x[rng.random(len(x)) < 0.05] = np.nan
        held = rng.random(len(x)) < 0.5
        conds = [x > 90, x > 45, (x > 20) | (x < -20)]
        for choices, default in (
            ([4, 3, 2], 1),
            ([np.where(held, 3, 2), np.where(held, 2, 1), 7], 0),
        ):
            want = np.select(conds, choices, default)
            got = select_first(conds, choices, default)
            assert got.dtype == want.dtype and np.array_equal(got, want)
    for v in (-1.0, 3.0, 5.0, np.nan):
        want = np.select([v >= 5, v >= 3], [2, 1], 0)
        got = select_first([v >= 5, v >= 3], [2, 1], 0)
        assert np.shape(got) == np.shape(want) and got == want and got.dtype == want.dtype
