"""The compiled / batched animation code (issue 18 item 3) gives the results of the code it
replaced: arm joint angles, leg IK, pose application, splines, the spread envelope, the
endpoint pose fit, and the collision report's broad phase (the same contacts as the full
check on cases that touch).

The references below are the replaced implementations, kept as the definition of the
expected values (frame-by-frame scipy Rotations, NumPy rotation-matrix stacks, scipy's
CubicSpline / ndimage filters / least_squares). Tolerances: 1e-9 rad for the closed-form code
(same formulas, only the floating-point order differs: measured <= 2e-14), 1e-6 for the
endpoint fit (the old scipy solve stopped within its default tolerances, up to 5e-6 rad from
the optimum on station cycles; here compared with a tight scipy solve).
"""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from scipy.ndimage import gaussian_filter1d, maximum_filter1d
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from mjwalk.arms.armpose import angular_scale, apply_pose
from mjwalk.arms.chain import arm_joint_angles, end_effector, two_link_ik_rows
from mjwalk.arms.posefit import fit_endpoint_pose
from mjwalk.body.humanoid import HUMAN_GROUP, ROM_DEG, leg_geometry
from mjwalk.body.legs.curves import clamped_cubic, spread
from mjwalk.body.legs.footpivot import ball_offset, heel_rise, pivot_ankle
from mjwalk.body.legs.ik import (
    KNEE_MIN,
    generic_joint,
    hip_world,
    leg_ik,
    leg_ik_world,
    rot_x,
    rot_y,
    rot_z,
)
from mjwalk.body.legs.ikcache import LegIKCache
from mjwalk.body.legs.steps import FootTracks
from mjwalk.conventions import side_prefix
from mjwalk.plan.synthetic import synthetic_walk
from mjwalk.timeline import collision_report, timeline_from_walk
from mjwalk.timeline.collisions import candidate_frames

# ------------------------------------------------------------------ reference implementations


def _rom_excess(abc, s: float) -> float:
    """Radians by which the shoulder angles of Euler set ``abc`` lie beyond their ranges."""
    from mjwalk.anthropometry import ROM_DEG

    a, b, c = abc
    out = 0.0
    for value, name in ((-a, "shoulder_flex"), (s * b, "shoulder_abd"), (-s * c, "shoulder_rot")):
        lo, hi = np.radians(ROM_DEG[name])
        out += max(lo - value, 0.0) + max(value - hi, 0.0)
    return out


def _arm_angles_ref(U, side, roll=None):
    """The frame-by-frame scipy implementation of arm_joint_angles (before issue 18), with
    the Euler set within the shoulder's ranges (2026-11-28)."""
    s = 1.0 if side == "left" else -1.0
    q = np.zeros((len(U), 7))
    prev_x = None
    for t in range(len(U)):
        u1, u2 = U[t, 0], U[t, 1]
        z = -u1
        x = u2 - (u2 @ u1) * u1
        if np.linalg.norm(x) < 1e-3:
            x = prev_x if prev_x is not None else np.array([1.0, 0.0, 0.0])
            x = x - (x @ z) * z
        x /= np.linalg.norm(x)
        prev_x = x
        r_sh = Rotation.from_matrix(np.column_stack([x, np.cross(z, x), z]))
        a, b, c = r_sh.as_euler("YXZ")
        # the other Euler set of the same rotation, when it keeps the shoulder in its ranges
        # and scipy's does not (an arm raised sideways above the shoulder)
        alt = (np.angle(-np.exp(1j * a)), np.copysign(np.pi, b) - b, np.angle(-np.exp(1j * c)))
        assert np.allclose(Rotation.from_euler("YXZ", alt).as_matrix(), r_sh.as_matrix())
        if _rom_excess(alt, s) < _rom_excess((a, b, c), s) - 1e-9:
            a, b, c = alt
        elbow = float(np.arccos(np.clip(u1 @ u2, -1, 1)))
        pron = 0.0 if roll is None else float(roll[t])
        q[t, :5] = [-a, s * b, -s * c, elbow, pron]
        r_fa = r_sh * Rotation.from_euler("YZ", [-elbow, -s * pron])
        h = r_fa.inv().apply(U[t, 2])
        q[t, 5] = np.arctan2(h[0], -h[2])
        q[t, 6] = s * np.arcsin(np.clip(h[1], -1, 1))
    q[:, 0] = np.unwrap(q[:, 0])
    q[:, 2] = np.unwrap(q[:, 2])
    return q


def _leg_ik_ref(ankle_rel, foot_yaw, foot_pitch, side, geom, clip=True):
    """The NumPy rotation-matrix implementation of leg_ik (before issue 18)."""
    s = 1.0 if side == "left" else -1.0
    p = side_prefix(side)
    L1, L2 = geom.thigh, geom.shank
    Rf = rot_z(np.asarray(foot_yaw, float)) @ rot_y(-np.asarray(foot_pitch, float))
    u = (np.swapaxes(Rf, -1, -2) @ np.asarray(ankle_rel, float)[..., None])[..., 0]
    r = np.linalg.norm(u, axis=-1)
    rc = np.clip(r, geom.span(np.deg2rad(ROM_DEG["knee"][1])), geom.span(KNEE_MIN))
    knee = geom.knee_for_span(rc)
    phi = np.arctan2(u[:, 1], -u[:, 2])
    m = np.hypot(u[:, 1], u[:, 2])
    a = np.arctan2(L1 * np.sin(knee), L1 * np.cos(knee) + L2) - np.arctan2(u[:, 0], m)
    a = np.mod(a + np.pi, 2 * np.pi) - np.pi
    H = Rf @ rot_x(phi) @ rot_y(a - knee)
    out = {
        f"hip_{p}_rot": -s * np.arctan2(H[:, 1, 0], H[:, 0, 0]),
        f"hip_{p}_flex": np.arcsin(np.clip(H[:, 2, 0], -1, 1)),
        f"hip_{p}_abd": s * np.arctan2(H[:, 2, 1], H[:, 2, 2]),
        f"knee_{p}": knee,
        f"ankle_{p}_flex": a,
        f"ankle_{p}_inv": s * phi,
    }
    if clip:
        out = {k: np.clip(v, *np.deg2rad(ROM_DEG[generic_joint(k)])) for k, v in out.items()}
    return out


def _heel_rise_ref(foot, hip, knee, p0, geom, lo=-1.0472):
    """The NumPy implementation of heel_rise (before issue 18), (n,) samples."""
    hip, p0 = np.atleast_2d(hip), np.atleast_1d(p0)
    d = geom.span(np.broadcast_to(knee, p0.shape))

    def gap(h, p, dd=d):
        return np.linalg.norm(h - _pivot_ref(foot, p, geom), axis=-1) - dd

    p = p0.copy()
    j = np.flatnonzero(gap(hip, p0) > 0)
    if not len(j):
        return p
    hj, dj = hip[j], d[j]
    ball, ah = ball_offset(geom), geom.ankle_height
    rho, beta = np.hypot(ball, ah), np.arctan2(ah, ball)
    f = np.array([np.cos(foot[2]), np.sin(foot[2])])
    rel = hj - np.array([foot[0] + ball * f[0], foot[1] + ball * f[1], 0.0])
    a_, c_ = rel[:, :2] @ f, rel[:, 2]
    k_ = ((rel**2).sum(1) + rho**2 - dj**2) / (2 * rho)
    t = np.arctan2(a_, c_) + np.arcsin(np.clip(k_ / np.hypot(a_, c_), -1.0, 1.0))
    p[j] = np.clip(beta - t, lo, np.minimum(p0[j], 0.0))
    up = j[p0[j] > 0]
    up = up[gap(hip[up], np.zeros(len(up)), d[up]) <= 0]
    if len(up):
        hu, du = hip[up], d[up]
        a, b = np.zeros(len(up)), p0[up]
        for _ in range(40):
            m = 0.5 * (a + b)
            out = gap(hu, m, du) > 0
            b, a = np.where(out, m, b), np.where(out, a, m)
        p[up] = 0.5 * (a + b)
    return p


def _pivot_ref(foot, pitch, geom):
    """The NumPy implementation of pivot_ankle (before issue 18)."""
    ah = geom.ankle_height
    pitch = np.atleast_1d(pitch)
    lever = np.where(pitch <= 0, ball_offset(geom), -geom.foot_back)
    fx, fy = np.cos(foot[..., 2]), np.sin(foot[..., 2])
    c, s = np.cos(pitch), np.sin(pitch)
    along = lever * (c - 1) + ah * s
    return np.column_stack(
        [foot[..., 0] - along * fx, foot[..., 1] - along * fy, ah * c - lever * s]
    )


def _unit(rng, shape):
    v = rng.normal(size=(*shape, 3))
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


# ------------------------------------------------------------------ arms


@pytest.mark.parametrize("side", ["left", "right"])
def test_arm_joint_angles_match_the_frame_by_frame_rotations(side):
    rng = np.random.default_rng(0)
    for trial in range(20):
        U = _unit(rng, (25, 3))
        U[4:7, 1] = U[4:7, 0]  # straight elbows: the twist carries over from the frame before
        if trial == 0:
            U[0, 1] = U[0, 0]  # ... or starts from +x
        roll = rng.normal(size=25) if trial % 2 else None
        # atol 1e-7 rad (6e-6 deg): at a straight elbow the twist is an angle of ~1e-8 rad that
        # the two formulas round differently (scipy 1.17: 1.5e-8 vs 2.1e-8)
        np.testing.assert_allclose(
            arm_joint_angles(U, side, roll), _arm_angles_ref(U, side, roll), atol=1e-7
        )


@pytest.mark.filterwarnings("ignore:Gimbal lock detected")
def test_arm_joint_angles_at_gimbal_lock_match_scipy():
    """An upper arm straight out sideways (middle YXZ angle +-90 deg): scipy's convention."""
    rng = np.random.default_rng(1)
    U = _unit(rng, (6, 3))
    U[:3, 0] = [0.0, 1.0, 0.0]
    U[3:, 0] = [0.0, -1.0, 0.0]
    for side in ("left", "right"):
        np.testing.assert_allclose(arm_joint_angles(U, side), _arm_angles_ref(U, side), atol=1e-9)


def test_apply_pose_matches_scipy_rotation():
    rng = np.random.default_rng(2)
    c = np.array([0.0, 0.0, -1.0])
    for scale in (1e-6, 1e-3, 0.5, 2.0):  # both sides of the small-angle series
        a = _unit(rng, (10, 3))
        pose = np.r_[rng.normal(size=3) * scale, 0.3 * rng.normal()]
        ref = Rotation.from_rotvec(pose[:3]).apply(
            angular_scale(c, a, float(np.exp(pose[3]))).reshape(-1, 3)
        )
        np.testing.assert_allclose(apply_pose(c, a, pose).reshape(-1, 3), ref, atol=1e-13)


def test_two_link_ik_rows_reach_the_targets():
    rng = np.random.default_rng(3)
    l1, l2 = 0.33, 0.26
    target = rng.normal(size=(50, 3))
    target *= rng.uniform(0.1, 0.55, size=(50, 1)) / np.linalg.norm(target, axis=1, keepdims=True)
    hint = rng.normal(size=(50, 3))
    hint[:3] = target[:3]  # a hint along the shoulder-wrist axis
    up, fore = two_link_ik_rows(target, l1, l2, hint)
    np.testing.assert_allclose(np.linalg.norm(up, axis=1), 1.0, atol=1e-12)
    np.testing.assert_allclose(l1 * up + l2 * fore, target, atol=1e-9)


def test_endpoint_pose_fit_reaches_the_least_squares_optimum():
    """The compiled Levenberg-Marquardt ends where a tight scipy solve ends (same residual)."""
    from mjwalk.arms import reachgen
    from mjwalk.arms.reach import ReachModel

    data = reachgen.generate("endpoints", 40, np.random.default_rng(0))
    model = ReachModel(data.lengths, dcs={"rng": 0}).fit(data.constraints, data.directions)
    rng = np.random.default_rng(4)
    for _ in range(6):
        c = data.constraints[rng.integers(len(data.constraints))]
        start, end = c[:3], c[3:6] + rng.normal(scale=0.05, size=3)
        out = np.asarray(model.net_.predict(c[None]))[0]
        b, pose0 = out[: model.n_modes_], out[model.n_modes_ :]
        A = model.rep_.inverse_transform(b[None])[0][0]
        Asub, tgt = A[[0, -1]], np.array([start, end])

        def resid(x, Asub=Asub, tgt=tgt):
            u = apply_pose(model.rep_.center_, Asub, x)
            return (end_effector(u, model.lengths) - tgt).ravel()

        lb, ub = np.r_[-np.inf, -np.inf, -np.inf, -1.0], np.r_[np.inf, np.inf, np.inf, 1.0]
        x0 = np.clip(pose0, lb + 1e-9, ub - 1e-9)
        tight = least_squares(resid, x0, bounds=(lb, ub), xtol=1e-15, ftol=1e-15, gtol=1e-15)
        x, ok = fit_endpoint_pose(model.rep_.center_, Asub, model.lengths, tgt, x0)
        assert ok
        np.testing.assert_allclose(x, tight.x, atol=1e-6)
        assert resid(x) @ resid(x) <= tight.cost * 2 + 1e-15


# ------------------------------------------------------------------ legs


@pytest.mark.parametrize("side", ["left", "right"])
def test_leg_ik_matches_the_rotation_matrix_stack(side):
    geom = leg_geometry(1.75)
    rng = np.random.default_rng(5)
    n = 400
    rel = rng.normal(scale=0.3, size=(n, 3)) + [0.0, 0.0, -0.7]
    yaw, pitch = rng.normal(scale=0.6, size=n), rng.normal(scale=0.4, size=n)
    for clip in (True, False):
        got = leg_ik(rel, yaw, pitch, side, geom, clip)
        ref = _leg_ik_ref(rel, yaw, pitch, side, geom, clip)
        assert got.keys() == ref.keys()
        for k in ref:
            np.testing.assert_allclose(got[k], ref[k], atol=1e-9, err_msg=k)


@pytest.mark.parametrize("s_", ["l", "r"])
def test_leg_ik_world_matches_the_pelvis_frame_ik(s_):
    geom = leg_geometry(1.75)
    rng = np.random.default_rng(6)
    n = 300
    root = np.column_stack([rng.normal(size=(n, 2)), 0.9 + 0.05 * rng.normal(size=n)])
    yaw = rng.uniform(-4, 4, n)
    ankle = root + rng.normal(scale=0.3, size=(n, 3))
    ankle[:, 2] = rng.uniform(0.05, 0.4, n)
    fyaw, pitch = yaw + rng.normal(scale=0.5, size=n), rng.normal(scale=0.3, size=n)
    rel = (rot_z(-yaw) @ (ankle - hip_world(root, yaw, s_, geom))[..., None])[..., 0]
    yrel = np.angle(np.exp(1j * (fyaw - yaw)))
    ref = _leg_ik_ref(rel, yrel, pitch, "left" if s_ == "l" else "right", geom, clip=False)
    got = leg_ik_world(ankle, fyaw, pitch, root, yaw, s_, geom)
    for k in ref:
        np.testing.assert_allclose(got[k], ref[k], atol=1e-9, err_msg=k)


def test_leg_ik_cache_resolves_the_changed_samples():
    """The synthesis's IK cache re-solves exactly the samples whose inputs changed: after any
    change its angles are those of a fresh leg_ik_world call, bit for bit."""
    geom = leg_geometry(1.75)
    rng = np.random.default_rng(9)
    n = 200
    root = np.column_stack([rng.normal(size=(n, 2)), np.full(n, 0.9)])
    yaw = rng.uniform(-3, 3, n)
    ankle = root + rng.normal(scale=0.2, size=(n, 3))
    ankle[:, 2] = rng.uniform(0.05, 0.3, n)
    fyaw, pitch = yaw + rng.normal(scale=0.3, size=n), rng.normal(scale=0.2, size=n)
    cache = LegIKCache("r", geom)
    for step in range(4):
        got = cache(ankle, fyaw, pitch, root, yaw)
        ref = leg_ik_world(ankle, fyaw, pitch, root, yaw, "r", geom)
        for k in ref:
            np.testing.assert_array_equal(got[k], ref[k], err_msg=f"{k}, step {step}")
        sel = rng.uniform(size=n) < 0.2  # change a few samples' inputs, as the loops do
        ankle = ankle.copy()
        ankle[sel, 2] += 0.01
        pitch = np.where(rng.uniform(size=n) < 0.1, pitch - 0.05, pitch)
        root = root.copy()
        root[sel[::-1], 2] -= 0.003


def test_pivot_ankle_and_heel_rise_match_numpy():
    """Compiled per sample: the ankle of a foot rolled about its heel or ball, and the heel
    rise that lets a leg reach its hip (closed form, and the bisection of a toes-up foot)."""
    geom = leg_geometry(1.75)
    rng = np.random.default_rng(10)
    bisected = 0
    for _ in range(60):
        foot = np.r_[rng.normal(size=2), rng.uniform(-3, 3)]
        n = 40
        hip = np.column_stack(
            [foot[:2] + rng.normal(scale=0.35, size=(n, 2)), rng.uniform(0.75, 0.95, n)]
        )
        knee, p0 = rng.uniform(0.03, 0.6, n), rng.normal(scale=0.3, size=n)
        # and hips just within reach of the flat foot's ankle, the toes up: bisected
        flat = _pivot_ref(foot, 0.0, geom)[0]
        up = _unit(rng, (n // 2,))
        up[:, 2] = np.abs(up[:, 2]) + 1.0
        up /= np.linalg.norm(up, axis=1, keepdims=True)
        reach = geom.span(knee[: n // 2]) * rng.uniform(0.97, 1.0, n // 2)
        hip[: n // 2] = flat + reach[:, None] * up
        p0[: n // 2] = rng.uniform(0.05, 0.5, n // 2)
        np.testing.assert_allclose(pivot_ankle(foot, p0, geom), _pivot_ref(foot, p0, geom))
        prints = np.column_stack([hip[:, :2], rng.uniform(-3, 3, n)])
        np.testing.assert_allclose(pivot_ankle(prints, p0, geom), _pivot_ref(prints, p0, geom))
        ref = _heel_rise_ref(foot, hip, knee, p0, geom)
        np.testing.assert_allclose(heel_rise(foot, hip, knee, p0, geom), ref, atol=1e-12)
        bisected += int(np.sum((ref > 0) & (ref < p0)))
        one = heel_rise(foot, hip[0], float(knee[0]), float(p0[0]), geom)
        assert isinstance(one, float) and abs(one - ref[0]) < 1e-12
    assert bisected > 0  # the toes-up bisection was exercised


def test_clamped_cubic_matches_scipy():
    rng = np.random.default_rng(7)
    for m in (2, 3, 5, 7):
        x = np.r_[0.0, np.sort(rng.uniform(0.05, 0.95, m - 2)), 1.0]
        xq = np.linspace(-0.1, 1.1, 37)  # extrapolated beyond the knots too
        y = rng.normal(size=(m, 3))
        d0, d1 = rng.normal(size=3), rng.normal(size=3)
        ref = CubicSpline(x, y, bc_type=((1, d0), (1, d1)))(xq)
        np.testing.assert_allclose(clamped_cubic(x, y, d0, d1, xq), ref, atol=1e-12)
        ref1 = CubicSpline(x, y[:, 0], bc_type=((1, d0[0]), (1, d1[0])))(xq)
        np.testing.assert_allclose(clamped_cubic(x, y[:, 0], d0[0], d1[0], xq), ref1, atol=1e-12)


def test_spread_matches_scipy_ndimage():
    rng = np.random.default_rng(8)
    for n, win in ((40, 3), (200, 6), (513, 11), (8, 5)):
        need = np.maximum(rng.normal(size=n), 0.0) * (rng.uniform(size=n) < 0.2)
        need[0] = need[-1] = 1.0  # corrections at the ends: the reflecting boundary counts
        ref = gaussian_filter1d(maximum_filter1d(need, 2 * win + 1), win / 3)
        np.testing.assert_allclose(spread(need, win), ref, atol=1e-12)


# ------------------------------------------------------------------ collisions

SCENE = """<mujoco><worldbody><geom name="floor" type="plane" size="10 10 .1"/>
<body name="shelf" pos="{x} {y} .6"><geom name="box" type="box" size=".25 .25 .6"/></body>
<body name="bar" pos="2.6 0 1.55" euler="0 0 30"><geom name="bar" type="capsule"
  size=".03 .6" euler="90 0 0"/></body>
</worldbody></mujoco>"""


def _same(a, b):
    return len(a) == len(b) and all(
        (x.time, x.body_part, x.scene_geom, x.depth) == (y.time, y.body_part, y.scene_geom, y.depth)
        and np.array_equal(x.pos, y.pos)
        for x, y in zip(a, b, strict=True)
    )


@pytest.mark.parametrize("x", [2.0, 2.3])
def test_broad_phase_finds_the_same_contacts(x):
    """A walk into a box and under a tilted bar, with held (repeated) poses, and with the
    floor's tolerance lowered so that foot contacts count: the broad phase reports exactly
    the contacts of the full check."""
    spec = mujoco.MjSpec.from_string(SCENE.format(x=x, y=0.0))
    tl = timeline_from_walk(synthetic_walk(n_steps=6), spec)
    tl.qpos = np.vstack([tl.qpos[:20], np.repeat(tl.qpos[20:21], 5, axis=0), tl.qpos[20:]])
    tl.t = np.arange(len(tl.qpos)) / tl.fps
    for tol in (0.01, -0.005):
        full = collision_report(tl, tol, broad_phase=False)
        assert full, "the case must touch"
        assert _same(collision_report(tl, tol), full)
    # and it does prune: with the floor's ordinary tolerance fewer than half the frames are
    # handed to MuJoCo (measured: 45 and 31 of 112)
    m = tl.model
    human, floorish = m.geom_group == HUMAN_GROUP, m.geom_type == mujoco.mjtGeom.mjGEOM_PLANE
    assert candidate_frames(m, tl.qpos, human, floorish, 0.01).sum() < len(tl.qpos) / 2


def test_broad_phase_skips_clear_frames():
    """Far from every obstacle only the floor is near; the frames without a candidate are
    skipped (nothing reported either way)."""
    spec = mujoco.MjSpec.from_string(SCENE.format(x=20.0, y=0.0).replace("2.6 0 1.55", "20 5 2"))
    tl = timeline_from_walk(synthetic_walk(n_steps=6), spec)
    m = tl.model
    human = m.geom_group == HUMAN_GROUP
    floorish = m.geom_type == mujoco.mjtGeom.mjGEOM_PLANE
    assert not candidate_frames(m, tl.qpos, human, floorish, 0.01).any()
    assert collision_report(tl) == collision_report(tl, broad_phase=False) == []


SMALL_BOX = """<mujoco><worldbody><geom name="floor" type="plane" size="10 10 .1"/>
<body pos="1.5 {y} {z}"><geom name="box" type="box" size=".04 .04 .04"/></body>
</worldbody></mujoco>"""


@pytest.mark.parametrize("y", [0.12, 0.18, 0.25, 0.32])
def test_broad_phase_is_exact_for_a_small_box_beside_the_limbs(y):
    """A small box beside the walk, at the height of a shin, thigh, hip, arm or shoulder: the
    limbs' capsules (looked at by the spheres along their axes) pass close to it or touch it,
    and the broad phase reports exactly the contacts and clearance of the full check."""
    from mjwalk.cycle.standoff import ArmClearance

    walk = synthetic_walk(n_steps=6)
    for z in (0.25, 0.5, 0.8, 1.1, 1.4):
        tl = timeline_from_walk(walk, mujoco.MjSpec.from_string(SMALL_BOX.format(y=y, z=z)))
        assert _same(collision_report(tl), collision_report(tl, broad_phase=False))
        check = ArmClearance(tl.model, tl.jointmap, clearance=0.05)
        assert check.distance(tl.qpos) == check.distance(tl.qpos, broad_phase=False)


@pytest.mark.parametrize("x", [2.0, 2.6, 20.0])
def test_arm_clearance_distance_same_with_broad_phase(x):
    """The reach's clearance check (arm geoms with a margin) finds the same smallest distance
    with and without the broad phase: near the box and bar, and clear of them (inf)."""
    from mjwalk.cycle.standoff import ArmClearance

    spec = mujoco.MjSpec.from_string(SCENE.format(x=x, y=0.3))
    tl = timeline_from_walk(synthetic_walk(n_steps=6), spec)
    check = ArmClearance(tl.model, tl.jointmap, clearance=0.05)
    for part in (tl.qpos, tl.qpos[::7], tl.qpos[-5:]):
        full = check.distance(part, broad_phase=False)
        assert check.distance(part) == full
    if x < 10:
        assert np.isfinite(check.distance(tl.qpos, broad_phase=False))


@pytest.mark.parametrize("x", [2.0, 20.0])
def test_arm_clearance_floor_broad_phase(x):
    """The clearance check's arm margin does not enter the floor test (a contact's distance is
    the geometry's): with the feet on the floor and no solid near, no frame is a candidate;
    with the body lowered into the floor by 5 to 25 mm (the floor counts below 10 mm) the
    broad phase still finds the full check's smallest distance."""
    from mjwalk.cycle.standoff import FLOOR_TOLERANCE, ArmClearance

    spec = mujoco.MjSpec.from_string(SCENE.format(x=x, y=0.3).replace("2.6 0 1.55", "20 5 2"))
    tl = timeline_from_walk(synthetic_walk(n_steps=6), spec)
    check = ArmClearance(tl.model, tl.jointmap, clearance=0.05)
    if x > 10:
        cand = candidate_frames(
            check.model, tl.qpos, check.human, check.floor, FLOOR_TOLERANCE, check.data
        )
        assert not cand.any()
    for drop in (0.005, 0.0095, 0.0105, 0.015, 0.025):
        q = tl.qpos.copy()
        q[:, 2] -= drop  # the free joint's height
        full = check.distance(q, broad_phase=False)
        assert check.distance(q) == full
        if x > 10 and drop > 0.012:
            assert np.isfinite(full)  # the floor counts


JOINTS = """<mujoco><worldbody><geom name="floor" type="plane" size="5 5 .1"/>
<body name="a" pos=".1 .2 1" quat=".9 .1 .3 -.2"><freejoint/><geom type="box" size=".1 .2 .3"/>
 <body name="b" pos="0 .3 .1" euler="10 20 30"><joint type="ball" pos=".05 0 .02"/>
  <geom type="capsule" size=".05 .2" pos=".1 0 0" euler="30 0 10"/>
  <body name="c" pos=".2 0 0"><joint type="hinge" axis="0 .6 .8" pos="0 .1 0" ref="20"/>
   <joint type="slide" axis="1 0 0" ref=".1"/><joint type="hinge" axis="1 0 0"/>
   <geom type="sphere" size=".05" pos="0 0 .1"/></body></body></body>
<body name="d" pos="1 0 0"><joint type="hinge" axis="0 0 1" pos=".1 0 0"/>
 <geom type="cylinder" size=".05 .1"/></body>
</worldbody></mujoco>"""


def test_geom_poses_match_mujoco():
    """The compiled forward kinematics of the broad phase leaves the geoms where
    ``mj_kinematics`` does (round-off): on a humanoid walk, and on a model with free, ball,
    hinge and slide joints, anchors off the body origin and a joint reference angle."""
    from mjwalk.timeline.geomposes import geom_poses, supported

    rng = np.random.default_rng(9)
    spec = mujoco.MjSpec.from_string(SCENE.format(x=2.0, y=0.0))
    tl = timeline_from_walk(synthetic_walk(n_steps=4), spec)
    small = mujoco.MjModel.from_xml_string(JOINTS)
    q_small = small.qpos0 + rng.normal(scale=0.7, size=(40, small.nq))
    for m, qpos in ((tl.model, tl.qpos), (small, q_small)):
        assert supported(m)
        geoms = np.arange(m.ngeom)
        xpos, xmat = geom_poses(m, qpos, geoms)
        d = mujoco.MjData(m)
        for f, q in enumerate(qpos):
            d.qpos[:] = q
            mujoco.mj_kinematics(m, d)
            np.testing.assert_allclose(xpos[f], d.geom_xpos, atol=1e-12)
            np.testing.assert_allclose(xmat[f], d.geom_xmat, atol=1e-12)


# ------------------------------------------------------------------ leg pitch corrections


def _repitch_ref(ankle, pitch, toe, fyaw, ground, prints, dp, geom):
    """The NumPy repitch of legs_from_walk before pitchfit (returns new ankle, pitch, toe)."""
    n = len(pitch)
    p0, p1 = pitch, pitch - dp
    virtual = np.column_stack([np.zeros((n, 2)), fyaw])
    moved = ankle + pivot_ankle(virtual, p1, geom) - pivot_ankle(virtual, p0, geom)
    moved[ground] = pivot_ankle(prints[ground], p1[ground], geom)
    return moved, p1, toe + (np.minimum(p0, 0.0) - np.minimum(p1, 0.0))


def _fit_ref(ik, ankle, fyaw, pitch, toe, ground, prints, root, yaw, dorsi, plantar, win, geom,
             tol=0.0):  # fmt: skip
    """The NumPy ankle-range rounds of legs_from_walk before pitchfit (synthesis's
    _fit_ankle_rounds), stopping once no grounded ankle is more than ``tol`` past its bounds."""
    s_ = ik.side
    for _ in range(8):
        flex = ik(ankle, fyaw, pitch, root, yaw)[f"ankle_{s_}_flex"]
        excess = np.where(ground, flex - dorsi, 0.0)
        short = np.where(ground & (pitch < 0), plantar - flex, 0.0)
        if excess.max() <= tol and short.max() <= tol:
            break
        down = spread(1.2 * np.maximum(excess, 0.0), win)
        up = spread(1.2 * np.maximum(short, 0.0), win)
        dp = down - np.minimum(up, np.maximum(-pitch, 0.0))
        ankle, pitch, toe = _repitch_ref(ankle, pitch, toe, fyaw, ground, prints, dp, geom)
    return ankle, pitch, toe


def _leg_case(rng, n, geom):
    """A foot on and off the floor beside a walking pelvis, pitched up and down."""
    t = np.linspace(0.0, 1.0, n)
    yaw = 0.3 * np.sin(3 * t)
    root = np.column_stack([0.6 * t, 0.05 * t, 0.9 + 0.02 * np.sin(9 * t)])
    fyaw = yaw + rng.normal(scale=0.05, size=n)
    pitch = 0.5 * np.sin(7 * t) + rng.normal(scale=0.02, size=n)
    ground = (np.sin(5 * t) > -0.3) | (t < 0.1)
    prints = np.column_stack([0.6 * t + 0.15, 0.15 + 0 * t, fyaw])
    ankle = pivot_ankle(prints, pitch, geom)
    ankle[~ground, 2] += 0.05
    ankle[:, 0] += rng.normal(scale=0.1, size=n)  # ahead of and behind the hip
    return ankle, fyaw, pitch, ground, prints, root, yaw


@pytest.mark.parametrize("tol", [0.0, np.deg2rad(0.01), 0.02])
@pytest.mark.parametrize("side", ["l", "r"])
def test_compiled_pitch_fit_matches_numpy(side, tol):
    """pitchfit's compiled repitch and ankle-range rounds give the NumPy code's numbers bit
    for bit (same arithmetic in the same order, the same stop at the tolerance ``tol``,
    radians), the IK cache giving the same angles after."""
    from mjwalk.body.legs import pitchfit

    geom = leg_geometry(1.75)
    rng = np.random.default_rng(11)
    dorsi = np.deg2rad(ROM_DEG["ankle_flex"][1] - 1.0)
    plantar = np.deg2rad(ROM_DEG["ankle_flex"][0] + 1.0)
    rounds = 0
    for n in (40, 300):
        ankle, fyaw, pitch, ground, prints, root, yaw = _leg_case(rng, n, geom)
        toe = -np.minimum(pitch, 0.0)
        dp = rng.normal(scale=0.1, size=n) * (rng.uniform(size=n) < 0.5)
        ref = _repitch_ref(ankle, pitch, toe, fyaw, ground, prints, dp, geom)
        toe_c = toe.copy()
        a_c, p_c = pitchfit.repitch_foot(ankle, pitch, toe_c, fyaw, ground, prints, dp, geom)
        for x, y in zip(ref, (a_c, p_c, toe_c), strict=True):
            assert np.array_equal(x, y)
        ik_ref, ik_c = LegIKCache(side, geom), LegIKCache(side, geom)
        args = (fyaw, pitch, toe, ground, prints, root, yaw, dorsi, plantar, 3)
        ref = _fit_ref(ik_ref, ankle, *args, geom, tol)
        toe_c = toe.copy()
        feet = FootTracks(*({side: a} for a in (ankle, fyaw, pitch, toe_c, ground, prints)))
        fit = pitchfit.fit_ankle_range(
            ik_c, feet, root, yaw, pitchfit.AnkleFit(dorsi, plantar, 3, 8, tol)
        )
        assert fit is not None
        for x, y in zip(ref, (*fit, toe_c), strict=True):
            assert np.array_equal(x, y)
        # the compiled rounds solve only the grounded rows: the cache's next call gives the
        # same angles as the NumPy rounds' cache
        final = (fit[0], fyaw, fit[1], root, yaw)
        got, want = ik_c(*final), ik_ref(*final)
        assert all(np.array_equal(got[k], want[k]) for k in want)
        rounds += int(not np.array_equal(fit[1], pitch))
    assert rounds == 2  # both cases were corrected
    # too short for the compiled spread: the caller's NumPy rounds
    ankle, fyaw, pitch, ground, prints, root, yaw = _leg_case(rng, 7, geom)
    short = FootTracks(*({side: a} for a in (ankle, fyaw, pitch, np.zeros(7), ground, prints)))
    bounds = pitchfit.AnkleFit(dorsi, plantar, 3, 8)
    assert pitchfit.fit_ankle_range(LegIKCache(side, geom), short, root, yaw, bounds) is None


def test_end_slopes_match_numpy_gradient():
    """The swing's end slopes are np.gradient's first and last rows, bit for bit (uneven and
    even spacing, two samples and many, vectors and scalars)."""
    from mjwalk.body.legs.steps import _end_slopes

    rng = np.random.default_rng(12)
    for n in (2, 3, 17):
        for x in (np.sort(rng.uniform(size=n)), np.arange(n) / 7.0):
            for f in (rng.normal(size=(n, 3)), rng.normal(size=n)):
                g = np.gradient(f, x, axis=0)
                assert np.array_equal(_end_slopes(f, x), g[[0, -1]])


def _matmul_is_fma() -> bool:
    """Whether NumPy's (m, 2) @ (2,) gives fma(r0, s0, r1 s1) here, as the compiled swing
    assumes (OpenBLAS's kernels on FMA machines); elsewhere the two differ by rounding."""
    from numba import njit

    from mjwalk._jit import fma

    @njit
    def rows(r, s):
        return np.array([fma(r[i, 0], s[0], r[i, 1] * s[1]) for i in range(r.shape[0])])

    rng = np.random.default_rng(16)
    r, s = rng.normal(size=(500, 2)), rng.normal(size=2)
    return bool(np.array_equal(r @ s, rows(r, s)))


def _kernel_walks():
    """Synthetic walks for the kernel comparisons: straight, curved, short quick steps, long
    slow steps (lift-offs early and late)."""
    return [
        synthetic_walk(n_steps=6),
        synthetic_walk(n_steps=6, radius=1.2),
        synthetic_walk(n_steps=5, step_len=0.12, step_time=0.45),
        synthetic_walk(n_steps=4, step_len=0.95, step_time=0.6),
    ]


@pytest.mark.parametrize("reference", ["default", "winter"])
def test_compiled_swing_foot_matches_numpy(monkeypatch, reference):
    """The compiled swing foot (body.legs.swing) gives steps.swing_foot's numbers bit for bit
    on every step of straight, turning, short-stepped and long-stepped walks, with both
    reference tables; the leg motion is the NumPy path's. (Bit for bit where NumPy's
    2-vector products are fused multiply-adds, :func:`_matmul_is_fma`; else to 1e-12.)"""
    from mjwalk.body.legs import steps, synthesis
    from mjwalk.body.legs.reference import DEFAULT_REFERENCE, winter_reference
    from mjwalk.body.legs.swing import swing_foot

    ref = DEFAULT_REFERENCE if reference == "default" else winter_reference()
    calls = []
    exact = _matmul_is_fma()

    def both(fr, phi, hip_xy, z_hip, ref_, geom, land_p):
        got = swing_foot(fr, phi, hip_xy, z_hip, ref_, geom, land_p)
        want = steps.swing_foot(
            fr, phi, np.arange(len(phi)), z_hip,
            lambda i, side, zz=None: hip_xy[i] if zz is None else np.column_stack([hip_xy[i], zz]),
            ref_, geom, land_p,
        )  # fmt: skip
        for x, y in zip(want, got, strict=True):
            assert np.array_equal(x, y) if exact else np.allclose(x, y, rtol=0, atol=1e-12)
        calls.append(want[4])
        return got

    monkeypatch.setattr(synthesis, "swing_foot_compiled", both)
    monkeypatch.setattr(synthesis, "COMPILED_STEPS", False)  # (step by step: the calls seen)
    walks = _kernel_walks()
    for walk in walks:
        synthesis.legs_from_walk(walk, reference=ref)
    assert len(calls) == sum(len(w.steps) for w in walks)
    assert any(phi_to < 0.2 for phi_to in calls)  # an early lift-off among them


def _stance_foot_ref(fr, phi, p_ref, land_prev, hs_pitch, hip_end, knee_end, geom):
    """The stance foot as legs_from_walk computed it in NumPy (before stance.stance_foot)."""
    from mjwalk.body.legs.curves import smoothstep, soft_flat
    from mjwalk.body.legs.steps import FOOT_FLAT

    p_st = np.where(phi < FOOT_FLAT, np.maximum(p_ref, 0), np.minimum(p_ref, 0))
    if land_prev is not None:
        p_st = np.where(phi < FOOT_FLAT, p_st * land_prev / hs_pitch, p_st)
    p_st = soft_flat(p_st)
    if fr.first:
        p_st = np.minimum(p_st, 0.0)
    p1 = heel_rise(fr.stance, hip_end, knee_end, float(p_st[-1]), geom)
    p_st = p_st + (p1 - p_st[-1]) * smoothstep((phi - FOOT_FLAT) / (1.0 - FOOT_FLAT))
    return p_st, pivot_ankle(fr.stance, p_st, geom)


def _stance_knee_ref(ref, phi, k_ref, ends, hip_xy, ankle, geom):
    """The stance knee and pelvis height as legs_from_walk computed them in NumPy."""
    from mjwalk.body.legs.steps import stance_angle

    th0, v0, th1, v1 = ends.th0, ends.v0, ends.th1, ends.v1
    assert np.array_equal(k_ref, ref("knee", 0.5 * phi))
    knee = np.clip(stance_angle(ref, "knee", phi, th0, v0, th1, v1), KNEE_MIN, np.deg2rad(80))
    h = np.linalg.norm(hip_xy - ankle[:, :2], axis=-1)
    return knee, ankle[:, 2] + np.sqrt(np.maximum(geom.span(knee) ** 2 - h**2, 1e-6))


def _pelvis_height_ref(phi, z_flat, pos, hip_sw, hip_st, knee_st, p_st, fr, d_max_sq, d_land,
                       ease_from, geom):  # fmt: skip
    """The pelvis height and landing ease as legs_from_walk computed them in NumPy."""
    hsw = np.linalg.norm(hip_sw - pos[:, :2], axis=-1)
    z_sw = pos[:, 2] + np.sqrt(np.maximum(d_max_sq - hsw**2, 1e-6))
    z = np.minimum(z_flat, z_sw)
    lj = np.flatnonzero(phi >= ease_from)
    if not (len(lj) >= 3 and lj[0] > 0):
        return z, None
    j = lj[0]
    hj = np.column_stack([hip_sw[j - 1 : j + 1], z[j - 1 : j + 1]])
    dj = np.linalg.norm(hj - pos[j - 1 : j + 1], axis=-1)
    span, gap = 1.0 - phi[j], d_land - dj[1]
    m0 = span * (dj[1] - dj[0]) / (phi[j] - phi[j - 1])
    m0 = float(np.clip(m0, min(0.0, 3 * gap), max(0.0, 3 * gap)))
    u = (phi[lj] - phi[j]) / span
    d_prof = dj[1] + (u**3 - 2 * u**2 + u) * m0 + (3 * u**2 - 2 * u**3) * gap
    h_prof = np.linalg.norm(hip_sw[lj] - pos[lj, :2], axis=-1)
    z_prof = pos[lj, 2] + np.sqrt(np.maximum(d_prof**2 - h_prof**2, 1e-6))
    z[lj] = np.minimum(z_prof, z_sw[lj])
    hip = np.column_stack([hip_st[lj], z[lj]])
    p_up = heel_rise(fr.stance, hip, knee_st[lj], np.minimum(p_st[lj], 0), geom)
    p_st[lj] = np.where(p_st[lj] <= 0, p_up, p_st[lj])
    return z, pivot_ankle(fr.stance, p_st, geom)


@pytest.mark.parametrize("reference", ["default", "winter"])
def test_compiled_stance_leg_matches_numpy(monkeypatch, reference):
    """stance.stance_foot, stance.stance_knee and stance.pelvis_height give the NumPy code's
    numbers bit for bit on every step of straight, turning, short-stepped and long-stepped
    walks."""
    from mjwalk.body.legs import stance, synthesis
    from mjwalk.body.legs.reference import DEFAULT_REFERENCE, winter_reference

    ref = DEFAULT_REFERENCE if reference == "default" else winter_reference()
    seen = {"foot": 0, "knee": 0, "scaled": 0, "height": 0, "eased": 0}

    def foot(*args):
        got, want = stance.stance_foot(*args), _stance_foot_ref(*args)
        for x, y in zip(want, got, strict=True):
            assert np.array_equal(x, y)
        seen["foot"] += 1
        seen["scaled"] += args[3] is not None
        return got

    def knee(*args):
        got, want = stance.stance_knee(*args), _stance_knee_ref(*args)
        for x, y in zip(want, got, strict=True):
            assert np.array_equal(x, y)
        seen["knee"] += 1
        return got

    def height(phi, z_flat, pos, hip_sw, leg, fr, ease, geom):
        p_ref = leg.pitch.copy()
        got = stance.pelvis_height(phi, z_flat, pos, hip_sw, leg, fr, ease, geom)
        want = _pelvis_height_ref(
            phi, z_flat, pos, hip_sw, leg.hip_xy, leg.knee, p_ref, fr, ease.d_max_sq,
            ease.d_land, ease.ease_from, geom,
        )  # fmt: skip
        assert np.array_equal(want[0], got[0])
        assert (want[1] is None) == (got[1] is None)
        if got[1] is not None:
            assert np.array_equal(want[1], got[1])
            assert np.array_equal(p_ref, leg.pitch)
            seen["eased"] += 1
        seen["height"] += 1
        return got

    monkeypatch.setattr(synthesis, "stance_foot", foot)
    monkeypatch.setattr(synthesis, "pelvis_height", height)
    monkeypatch.setattr(synthesis, "stance_knee", knee)
    monkeypatch.setattr(synthesis, "COMPILED_STEPS", False)  # (step by step: the calls seen)
    walks = _kernel_walks()
    for walk in walks:
        synthesis.legs_from_walk(walk, reference=ref)
    n_steps = sum(len(w.steps) for w in walks)
    assert seen["foot"] == seen["knee"] == seen["height"] == n_steps
    assert seen["eased"] > n_steps // 2
    assert seen["scaled"] == n_steps - len(walks)  # all but the first steps roll down


def _landing_pitches_ref(frames, xy, yaw, hs_pitch, d_land, dorsi_max, geom):
    """steps.landing_pitches as NumPy code (before it was compiled): the landing pitches."""
    b = np.array([fr.end for fr in frames])
    land = np.array([fr.land for fr in frames])
    left = np.array([fr.side == "l" for fr in frames])
    land_p = np.full(len(frames), hs_pitch)
    for _ in range(4):
        pos = pivot_ankle(land, land_p, geom)
        z = np.zeros(len(b))
        flex = np.zeros(len(b))
        for side, sel in (("l", left), ("r", ~left)):
            if not sel.any():
                continue
            bs = b[sel]
            hip = hip_world(np.column_stack([xy[bs], z[sel]]), yaw[bs], side, geom)
            hz = np.linalg.norm(hip[:, :2] - pos[sel, :2], axis=-1)
            z[sel] = pos[sel, 2] + np.sqrt(np.maximum(d_land**2 - hz**2, 1e-6))
            root = np.column_stack([xy[bs], z[sel]])
            raw = leg_ik_world(pos[sel], land[sel, 2], land_p[sel], root, yaw[bs], side, geom)
            flex[sel] = raw[f"ankle_{side}_flex"]
        over = flex - dorsi_max
        if not np.any((over > 0) & (land_p > 0)):
            break
        land_p = np.where(over > 0, np.maximum(land_p - 1.2 * over, 0.0), land_p)
    return land_p


def test_compiled_landing_pitches_match_numpy():
    """steps.landing_pitches (compiled rounds) gives the NumPy rounds' pitches bit for bit,
    on steps landing ahead of the hip (the reference pitch kept) and under it (flattened)."""
    from mjwalk.body.legs.reference import DEFAULT_REFERENCE as ref
    from mjwalk.body.legs.steps import landing_pitches, step_frames

    geom = leg_geometry(1.75)
    hs_pitch = max(0.0, float(ref("pitch", 0.0)))
    d_land = geom.span(max(ref("knee", 0.0), KNEE_MIN))
    dorsi = np.deg2rad(ROM_DEG["ankle_flex"][1] - 1.0)
    rng = np.random.default_rng(13)
    kept = flat = 0
    for walk in (synthetic_walk(n_steps=6), synthetic_walk(n_steps=6, radius=1.2)):
        for shift in (0.0, 0.2, 0.35):  # the pelvis moved ahead of the feet by that (m)
            frames = step_frames(walk)
            xy = np.asarray(walk.xy, float) + shift * np.array([1.0, 0.0])
            xy = xy + rng.normal(scale=0.01, size=xy.shape)
            yaw = np.asarray(walk.yaw, float)
            want = _landing_pitches_ref(frames, xy, yaw, hs_pitch, d_land, dorsi, geom)
            landing_pitches(frames, xy, yaw, hs_pitch, d_land, dorsi, geom)
            got = np.array([fr.land_p for fr in frames])
            assert np.array_equal(want, got)
            kept += int(np.sum(got == hs_pitch))
            flat += int(np.sum(got < hs_pitch))
    assert kept > 0 and flat > 0


@pytest.mark.parametrize("s_", ["l", "r"])
def test_spin_hip_rotation_excess_matches_numpy(s_):
    """spin._hip_rotation_excess gives leg_ik_world's hip rotation and soft_excess's
    overshoots bit for bit on the grounded samples and leaves the others alone."""
    from mjwalk.body.legs.curves import soft_excess
    from mjwalk.body.legs.ik import ik_lengths
    from mjwalk.body.legs.spin import _hip_rotation_excess

    geom = leg_geometry(1.75)
    rng = np.random.default_rng(14)
    n = 300
    ankle, fyaw, pitch, ground, _, root, yaw = _leg_case(rng, n, geom)
    fyaw = fyaw + rng.normal(scale=0.6, size=n)  # hips turned past their range too
    top, bottom, w = np.deg2rad(39.0), np.deg2rad(-39.0), np.deg2rad(2.0)
    rot, up, down = np.full(n, 7.0), np.full(n, 7.0), np.full(n, 7.0)
    sgn = 1.0 if s_ == "l" else -1.0
    args = (ankle, fyaw, pitch, root, yaw, sgn, geom.hip_y, *ik_lengths(geom))
    bufs = (np.full((n, 9), np.nan), np.empty((n, 6)), np.full((n, 2), np.nan), np.empty((n, 7)))
    _hip_rotation_excess(ground, *args, top, bottom, w, rot, up, down, *bufs)
    on = np.flatnonzero(ground)
    want = leg_ik_world(ankle[on], fyaw[on], pitch[on], root[on], yaw[on], s_, geom)
    r = want[f"hip_{s_}_rot"]
    assert np.array_equal(rot[on], r)
    assert np.array_equal(up[on], soft_excess(r - top, w))
    assert np.array_equal(down[on], soft_excess(bottom - r, w))
    assert np.all(rot[~ground] == 7.0) and np.all(up[~ground] == 7.0)
    assert np.any(up[on] > 0) and np.any(down[on] > 0) and np.any((up[on] == 0) & (down[on] == 0))


def test_reach_deficit_matches_numpy():
    """stance.reach_deficit gives the NumPy deficit of the synthesis's pelvis-lowering
    passes (the larger of both grounded legs' reach deficits) bit for bit."""
    from mjwalk.body.legs.stance import reach_deficit

    geom = leg_geometry(1.75)
    rng = np.random.default_rng(15)
    n = 300
    ankle, ground, reach_sq = {}, {}, {}
    for s_ in "lr":
        a, _, _, g, _, root, yaw = _leg_case(rng, n, geom)
        ankle[s_], ground[s_] = a, g
        reach_sq[s_] = geom.span(np.deg2rad(rng.uniform(2.0, 10.0, n))) ** 2
    root = root.copy()
    root[:, 2] += rng.normal(scale=0.08, size=n)  # some legs short of their feet, some not
    want = np.zeros(n)
    for s_ in "lr":
        h = np.linalg.norm(hip_world(root, yaw, s_, geom)[:, :2] - ankle[s_][:, :2], axis=1)
        cap = ankle[s_][:, 2] + np.sqrt(np.maximum(reach_sq[s_] - h**2, 0.0))
        want = np.maximum(want, np.where(ground[s_], root[:, 2] - cap, 0.0))
    got = reach_deficit(root, yaw, ankle, ground, reach_sq, geom)
    assert np.array_equal(want, got)
    assert np.any(got > 1e-3) and np.any((got == 0) & (ground["l"] | ground["r"]))
