"""The arm chain (mjwalk.arms.chain): joint angles from segment directions, the wrist kept in
its range, and the hand's end (forward kinematics)."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from mjwalk.anthropometry import ROM_DEG
from mjwalk.arms import reachgen
from mjwalk.arms.chain import (
    ARM_JOINT_NAMES,
    ARM_JOINTS,
    ARM_SEGMENT_SHARES,
    _shoulder_branch,
    arm_frames,
    arm_joint,
    arm_joint_angles,
    arm_ranges,
    arm_segment_lengths,
    clipped_joints,
    end_effector,
    min_jerk,
    rows_in_range,
    two_link_ik,
    wrist_in_range,
)
from mjwalk.body.humanoid import humanoid_model


@pytest.mark.parametrize("side", ["left", "right"])
def test_wrist_in_range_turns_the_hand_to_the_limit_and_keeps_its_end(side):
    """A hand direction the wrist cannot hold is turned to the range's edge (not past it, not
    short of it), the arm re-solved so the hand's end stays on the target; a direction within
    the range is kept as it is."""
    rng = np.random.default_rng(3)
    lengths = np.array([0.30, 0.27, 0.18])
    s = 1.0 if side == "left" else -1.0
    n = 40
    end = np.column_stack(
        [rng.uniform(0.25, 0.5, n), s * rng.uniform(-0.1, 0.25, n), rng.uniform(-0.4, 0.0, n)]
    )
    hand = rng.normal(size=(n, 3))
    hand /= np.linalg.norm(hand, axis=1, keepdims=True)
    hint = np.tile([0.0, s * 0.3, -1.0], (n, 1))
    limits = np.radians(reachgen.FUNCTIONAL_WRIST)
    arm = wrist_in_range(end, hand, lengths, hint, limits, side, iterations=20)
    assert np.allclose(np.linalg.norm(arm, axis=2), 1.0)
    assert np.abs(end_effector(arm, lengths) - end).max() < 1e-6
    q = arm_joint_angles(arm, side)[:, 5:7]
    lo, hi = limits.T
    assert ((q >= lo - 1e-3) & (q <= hi + 1e-3)).all()
    q_free = arm_joint_angles(wrist_in_range(end, hand, lengths, hint, limits, side, 0), side)
    inside = ((q_free[:, 5:7] >= lo) & (q_free[:, 5:7] <= hi)).all(axis=1)
    assert 0 < inside.sum() < n  # both kinds among the random directions
    assert np.allclose(arm[inside, 2], hand[inside])
    # outside: the least turn, so the wrist ends on its range's edge in one of its two angles
    edge = np.minimum(np.abs(q - lo), np.abs(q - hi)).min(axis=1)
    assert edge[~inside].max() < np.radians(0.1)
    # and no direction between the wanted one and the result is in range: 10 points along it
    for t in np.linspace(0.0, 0.99, 10):
        h = (1 - t) * hand[~inside] + t * arm[~inside, 2]
        h /= np.linalg.norm(h, axis=1, keepdims=True)
        qt = arm_joint_angles(
            wrist_in_range(end[~inside], h, lengths, hint[~inside], limits, side, 0), side
        )[:, 5:7]
        assert (((qt < lo - 1e-9) | (qt > hi + 1e-9)).any(axis=1)).all()


@pytest.mark.parametrize("side", ["left", "right"])
def test_arm_joint_angles_recover_poses_across_the_shoulders_range(side):
    """Upper arm and forearm directions made by the humanoid's shoulder chain (R = Ry(-flex)
    Rx(s abd) Rz(-s rot), the arm along -z, the elbow Ry(-elbow)) from angles anywhere in the
    joints' ranges give those angles back -- an arm raised sideways above the shoulder
    (abduction beyond 90 deg) too, which came back as 180 deg flexion and rotation, beyond
    their ranges (a reach to a 1.95 m shelf ended 1.3 m off)."""
    s = 1.0 if side == "left" else -1.0
    rng = np.random.default_rng(7)
    names = ("shoulder_flex", "shoulder_abd", "shoulder_rot")
    lo, hi = np.radians([ROM_DEG[j] for j in names]).T
    q = rng.uniform(lo, hi, size=(400, 3))
    q = q[np.abs(q[:, 1] - np.pi / 2) > np.radians(5.0)]  # away from the gimbal pose
    assert (q[:, 1] > np.radians(100.0)).sum() > 50  # raised sideways above the shoulder
    elbow = rng.uniform(np.radians(20.0), np.radians(140.0), size=len(q))
    dirs = np.empty((len(q), 3, 3))
    down = np.array([0.0, 0.0, -1.0])
    for k, (flex, abd, rot) in enumerate(q):
        r = Rotation.from_euler("YXZ", [-flex, s * abd, -s * rot]).as_matrix()
        fore = r @ Rotation.from_euler("Y", -elbow[k]).as_matrix() @ down
        dirs[k] = [r @ down, fore, fore]
    got = np.array([arm_joint_angles(d[None], side)[0] for d in dirs])
    np.testing.assert_allclose(got[:, :3], q, atol=1e-6)
    np.testing.assert_allclose(got[:, 3], elbow, atol=1e-6)


def test_end_effector_min_jerk_and_segment_lengths():
    lengths = np.array([0.3, 0.25])
    dirs = np.array([[[0.0, 0.0, -1.0], [1.0, 0.0, 0.0]]])  # upper arm down, forearm forward
    np.testing.assert_allclose(end_effector(dirs, lengths), [[0.25, 0.0, -0.3]])
    t = np.array([-0.5, 0.0, 0.5, 1.0, 2.0])
    np.testing.assert_allclose(min_jerk(t), [0.0, 0.0, 0.5, 1.0, 1.0])
    np.testing.assert_allclose(arm_segment_lengths(2.0), 2.0 * np.array(ARM_SEGMENT_SHARES))
    assert len(arm_segment_lengths(with_hand=False)) == 2
    assert arm_joint("shoulder_flex", "right") == "shoulder_r_flex"


def test_two_link_ik_puts_the_wrist_on_a_reachable_target_and_clamps_a_far_one():
    up, fore = two_link_ik(np.array([0.2, 0.1, -0.3]), 0.3, 0.25, np.array([0.0, 1.0, 0.0]))
    np.testing.assert_allclose(0.3 * up + 0.25 * fore, [0.2, 0.1, -0.3], atol=1e-12)
    assert np.isclose(np.linalg.norm(up), 1.0) and np.isclose(np.linalg.norm(fore), 1.0)
    assert up[1] > 0  # the elbow towards the hint
    up, fore = two_link_ik(np.array([0.0, 0.0, -2.0]), 0.3, 0.25, np.array([0.0, 1.0, 0.0]))
    np.testing.assert_allclose(0.3 * up + 0.25 * fore, [0.0, 0.0, -0.55], atol=1e-5)


@pytest.mark.parametrize("side", ["left", "right"])
def test_arm_frames_interpolate_clip_and_name_the_clipped_joints(side):
    """arm_frames interpolates the arm's angles over [0, 1], clips them to the humanoid's ranges
    and names the joints it clipped; clipped_joints names the same joints without the poses;
    the rest of the pose is the base pose's."""
    model, jm = humanoid_model()
    names = ARM_JOINT_NAMES[side]
    assert names == tuple(arm_joint(n, side) for n in ARM_JOINTS)
    lo, hi = np.array([jm.limits(n) for n in names]).T
    q = np.tile(0.5 * (lo + hi), (3, 1))
    q[:, 3] = [lo[3], 0.5 * (lo[3] + hi[3]), hi[3]]  # the elbow across its range
    q[2, 0] = hi[0] + 1.0  # the shoulder's flexion beyond its range at the end
    q0 = model.qpos0.copy()
    poses, clipped = arm_frames(q0, jm, q, side, np.array([0.0, 0.25, 1.0]))
    assert clipped == [names[0]] == clipped_joints(jm, q[2:], side)
    assert clipped_joints(jm, q[:2], side) == []
    assert poses[1, jm.adr(names[3])] == pytest.approx(0.75 * lo[3] + 0.25 * hi[3])
    assert poses[2, jm.adr(names[0])] == hi[0]  # clipped to the range
    others = np.setdiff1d(np.arange(model.nq), [jm.adr(n) for n in names])
    assert np.array_equal(poses[:, others], np.tile(q0[others], (3, 1)))


@pytest.mark.parametrize("side", ["left", "right"])
def test_independent_rows_get_the_angles_each_gets_alone(side):
    """With ``independent`` a batch of alternative arms (one with a straight elbow, angles
    that would unwrap across rows) gives each row exactly the angles it gives alone; without
    it the rows are frames of one movement (unwrapped, the straight elbow's twist carried)."""
    rng = np.random.default_rng(5)
    dirs = rng.normal(size=(40, 3, 3))
    dirs /= np.linalg.norm(dirs, axis=2, keepdims=True)
    dirs[7, 1] = dirs[7, 0]  # a straight elbow
    alone = np.array([arm_joint_angles(d[None], side)[0] for d in dirs])
    batch = arm_joint_angles(dirs, side, None, True)
    assert np.array_equal(batch, alone)
    assert not np.array_equal(arm_joint_angles(dirs, side), alone)


@pytest.mark.parametrize("side", ["left", "right"])
def test_rows_in_range_agrees_with_clipped_joints_row_by_row(side):
    """rows_in_range is True exactly for the rows clipped_joints finds nothing to clip in."""
    _, jm = humanoid_model()
    lo, hi = np.array([jm.limits(n) for n in ARM_JOINT_NAMES[side]]).T
    q = lo + np.random.default_rng(2).uniform(-0.3, 1.3, size=(60, 7)) * (hi - lo)
    q[0] = 0.5 * (lo + hi)
    q[1] = hi + 5e-7  # within the 1e-6 rad tolerance
    want = np.array([not clipped_joints(jm, row[None], side) for row in q])
    assert want[:2].all() and not want.all()
    assert np.array_equal(rows_in_range(jm, q, side), want)


def _shoulder_branch_numpy(a, b, c, s):
    """The NumPy form of chain._shoulder_branch (before it was compiled), as the reference."""
    ranges = {k: np.radians(ROM_DEG[k]) for k in ("shoulder_flex", "shoulder_abd", "shoulder_rot")}

    def excess(a, b, c):
        out = np.zeros_like(a)
        for value, name in (
            (-a, "shoulder_flex"),
            (s * b, "shoulder_abd"),
            (-s * c, "shoulder_rot"),
        ):
            lo, hi = ranges[name]
            out += np.maximum(lo - value, 0.0) + np.maximum(value - hi, 0.0)
        return out

    def wrap(x):
        return (x + np.pi) % (2.0 * np.pi) - np.pi

    a2, b2, c2 = wrap(a + np.pi), np.where(b >= 0.0, np.pi, -np.pi) - b, wrap(c + np.pi)
    other = excess(a2, b2, c2) < excess(a, b, c) - 1e-9
    return np.where(other, a2, a), np.where(other, b2, b), np.where(other, c2, c)


@pytest.mark.parametrize("s", [1.0, -1.0])
def test_compiled_shoulder_branch_gives_the_numpy_numbers_bit_for_bit(s):
    """The compiled shoulder branch choice (arms raised over 90 deg sideways written with the
    second Euler set) gives the NumPy arithmetic's numbers exactly, both sets chosen, with
    +-pi, zeros and a NaN among the angles."""
    rng = np.random.default_rng(11)
    a = rng.uniform(-4.0, 4.0, 400)
    b = rng.uniform(-0.5 * np.pi, 0.5 * np.pi, 400)
    c = rng.uniform(-4.0, 4.0, 400)
    a[:20], b[20:40], c[40:60], a[60] = -np.pi, 0.0, np.pi, np.nan
    got = _shoulder_branch(a, b, c, s)
    want = _shoulder_branch_numpy(a, b, c, s)
    assert not np.array_equal(want[1], b)  # (the second set chosen somewhere)
    for g, w in zip(got, want, strict=True):
        assert np.array_equal(g.view(np.int64), w.view(np.int64))


def _arm_frames_numpy(q0, jm, q, side, times):
    """The NumPy form of chain.arm_frames (before it was compiled), as the reference."""
    names = ARM_JOINT_NAMES[side]
    idx = [jm.index(jn) for jn in names]
    lo, hi = jm.range[idx, 0], jm.range[idx, 1]
    src = np.linspace(0.0, 1.0, len(q))
    out = np.repeat(np.asarray(q0)[None], len(times), axis=0)
    qi = np.column_stack([np.interp(times, src, q[:, k]) for k in range(len(names))])
    out[:, jm.qposadr[idx]] = np.clip(qi, lo, hi)
    bad = ((qi < lo - 1e-6) | (qi > hi + 1e-6)).any(axis=0)
    return out, [names[k] for k in np.flatnonzero(bad)]


@pytest.mark.parametrize("side", ["left", "right"])
def test_compiled_arm_frames_give_the_numpy_numbers_bit_for_bit(side):
    """arm_frames (compiled interpolation and clipping) gives np.interp's and np.clip's numbers
    exactly: times before, after and on the samples, a single sample, angles on and beyond the
    limits, zeros and NaNs."""
    _, jm = humanoid_model()
    names = ARM_JOINT_NAMES[side]
    lo, hi = np.array([jm.limits(n) for n in names]).T
    rng = np.random.default_rng(8)
    for trial in range(300):
        n, m = int(rng.integers(1, 30)), int(rng.integers(1, 90))
        q = lo + rng.uniform(-0.3, 1.3, (n, 7)) * (hi - lo)
        q[0, 3], q[-1, 0], q[n // 2, 1] = lo[3], hi[0], -0.0
        times = rng.uniform(-0.1, 1.1, m)
        times[: m // 2] = np.linspace(0.0, 1.0, n)[rng.integers(0, n, m // 2)]
        if trial % 10 == 0:
            q[n // 2, 2], times[-1] = np.nan, np.nan
        q0 = rng.normal(size=jm.root + 7 + len(jm.names))
        got, got_names = arm_frames(q0, jm, q, side, times)
        want, want_names = _arm_frames_numpy(q0, jm, q, side, times)
        assert np.array_equal(got.view(np.int64), want.view(np.int64))
        assert got_names == want_names


def test_arm_ranges_are_the_joint_maps_and_follow_a_new_range_array():
    _, jm = humanoid_model()
    for side in ("left", "right"):
        idx = [jm.index(jn) for jn in ARM_JOINT_NAMES[side]]
        lo, hi, adr = arm_ranges(jm, side)
        assert np.array_equal(lo, jm.range[idx, 0]) and np.array_equal(hi, jm.range[idx, 1])
        assert np.array_equal(adr, jm.qposadr[idx]) and adr.dtype == np.int64
        assert arm_ranges(jm, side)[0] is lo  # kept with the joint map
    jm.range = jm.range * 0.5  # a new array: looked up again
    lo, hi, _ = arm_ranges(jm, "left")
    assert np.array_equal(lo, jm.range[[jm.index(j) for j in ARM_JOINT_NAMES["left"]], 0])
