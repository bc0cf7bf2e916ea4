"""ReachModel and the reach generator (mjwalk.arms.reach, mjwalk.arms.reachgen)."""

from pathlib import Path

import numpy as np
import pytest

from mjwalk.arms import reachgen
from mjwalk.arms.chain import arm_joint_angles, end_effector, wrist_in_range
from mjwalk.arms.reach import ReachModel
from mjwalk.arms.reachdefault import DEFAULT_DCS
from mjwalk.errors import MjwalkError, ModelFileError
from mjwalk.timeline import reach_in_scene


@pytest.fixture(scope="module")
def endpoint_model():
    # 160 reaches to train (the generator's working area holds the whole normal working area of
    # a hand, across the body's midline, up to a top shelf: reachgen.END_BOX), the last 10
    # held out
    # with the default model's DCS settings
    data = reachgen.generate("endpoints", 170, np.random.default_rng(0))
    model = ReachModel(data.lengths, dcs=DEFAULT_DCS).fit(
        data.constraints[:160], data.directions[:160]
    )
    return model, data


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


def test_prediction_reaches_targets_within_1cm(endpoint_model):
    model, data = endpoint_model
    for i in range(160, 170):
        start, end = data.hand[i, 0], data.hand[i, -1]
        r = model.predict(data.constraints[i], start=start, end=end)
        assert np.linalg.norm(r.hand[-1] - end) < 0.01
        assert np.linalg.norm(r.hand[0] - start) < 0.01
        # seeded: held-out joint-direction error, measured 1.3-13.6 deg, mean 5.2
        err = np.degrees(np.arccos(np.clip((r.directions * data.directions[i]).sum(-1), -1, 1)))
        assert err.mean() < 20.0


def test_generated_reaches_keep_a_human_wrist_and_elbow():
    """The generator's reaches start with a neutral wrist, keep it in its functional range
    (Ryu et al. 1991), every joint within the humanoid's range of motion, and the elbow swung
    out (abducted) from the hanging arm, not in towards the chest. Before: the hand hung 51
    deg back from the forearm at the start and 81 deg mid-reach (beyond the humanoid's 70 deg),
    and the elbow started 9 cm medial of the shoulder (adducted 16 deg, median)."""
    from mjwalk.anthropometry import ROM_DEG
    from mjwalk.arms.chain import ARM_JOINTS

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


def test_outside_constraint_is_flagged_never_silent(endpoint_model):
    model, data = endpoint_model
    far = data.constraints[0] + np.r_[0, 0, 0, 1.5, 1.5, 1.5]
    r = model.predict(far)
    assert r.outside and r.distance > 3 and r.warnings
    with pytest.raises(MjwalkError, match="outside the trained range"):
        model.predict(far, strict=True)
    ok = model.predict(data.constraints[105])
    assert not ok.outside and not ok.warnings


def test_outside_constraint_follows_the_trend_network_and_says_so(endpoint_model, tmp_path):
    _, data = endpoint_model
    model = ReachModel(data.lengths, dcs={"rng": 0, "trend_fallback": True}).fit(
        data.constraints[:50], data.directions[:50]
    )
    far = data.constraints[0] + np.r_[0, 0, 0, 1.5, 1.5, 1.5]
    r = model.predict(far)
    assert r.outside and "follows the trend network (100%)" in r.warnings[0]
    # inside the data the network's own output is used (weight 1 at a training constraint)
    assert model.net_.network_weight(data.constraints[:1])[0] == 1.0
    model.save(tmp_path / "fb.npz")
    back = ReachModel.load(tmp_path / "fb.npz")
    assert back.net_.fallback_ is not None
    np.testing.assert_allclose(back.predict(far).directions, r.directions)


def test_reach_model_save_load(endpoint_model, tmp_path):
    model, data = endpoint_model
    model.save(tmp_path / "reach.npz")
    back = ReachModel.load(tmp_path / "reach.npz")
    a = model.predict(data.constraints[102]).directions
    b = back.predict(data.constraints[102]).directions
    np.testing.assert_allclose(a, b, atol=1e-12)
    (tmp_path / "x.npz").write_text("junk")
    with pytest.raises(ModelFileError):
        ReachModel.load(tmp_path / "x.npz")


def test_joint_angles_reproduce_directions_through_humanoid_chain(endpoint_model):
    from scipy.spatial.transform import Rotation

    _, data = endpoint_model
    U = data.directions[3]
    q = arm_joint_angles(U, side="left")
    for t in range(len(U)):
        flex, abd, rot, elbow, pron, wflex, wdev = q[t]
        r_sh = Rotation.from_euler("YXZ", [-flex, abd, -rot])
        r_fa = r_sh * Rotation.from_euler("YZ", [-elbow, -pron])
        r_h = r_fa * Rotation.from_euler("YX", [-wflex, wdev])
        down = np.array([0.0, 0.0, -1.0])
        np.testing.assert_allclose(r_sh.apply(down), U[t, 0], atol=1e-6)
        np.testing.assert_allclose(r_fa.apply(down), U[t, 1], atol=1e-6)
        np.testing.assert_allclose(r_h.apply(down), U[t, 2], atol=1e-6)


def test_obstacle_space_hand_clears_the_obstacle():
    data = reachgen.generate("obstacle", 10, np.random.default_rng(2))
    for c, hand in zip(data.constraints, data.hand, strict=True):
        a, b = hand[0], hand[-1]
        obstacle = a + c[0] * (b - a)
        # the hand passes at least 8 cm above the obstacle point on the start-end line
        above = hand[:, 2] - obstacle[2]
        near = np.linalg.norm(hand[:, :2] - obstacle[:2], axis=1) < 0.05
        assert near.any() and (above[near] > 0.08).any()


def test_grasp_closes_fingers_on_object_within_5mm():
    from mjwalk.arms.hands import finger_trajectory, fingers_for_aperture, pinch_aperture

    data = reachgen.generate("grasp", 60, np.random.default_rng(4))
    model = ReachModel(data.lengths, dcs={"rng": 0}).fit(
        data.constraints[:50], data.directions[:50], data.extras[:50]
    )
    for i in (50, 51, 52):
        size = data.constraints[i, 0]
        r = model.predict(data.constraints[i], data.hand[i, 0], data.hand[i, -1], object_size=size)
        assert r.extras.shape == (20, 2)
        assert r.extras[:, 0].max() > size  # opens wider than the object first
        q = fingers_for_aperture(r.extras[-1, 0])
        assert abs(pinch_aperture(q) - size) < 0.005
    traj = finger_trajectory(r.extras[:, 0])
    assert traj["index_l_mcp"].shape == (20,)
    with pytest.raises(MjwalkError, match="outside the hand's range"):
        fingers_for_aperture(0.5)


SCENE = Path(__file__).parents[2] / "scenes" / "assembly_station.xml"


@pytest.mark.skipif(not SCENE.is_file(), reason="scenes/assembly_station.xml absent")
def test_reach_into_rack_shelf_without_contact(endpoint_model):
    import mujoco

    from mjwalk.timeline import collision_report

    model, _ = endpoint_model
    # hand tip 6 cm above the screw on the rack-2 shelf (top of the shelf at z = 1.02 m)
    tl, res = reach_in_scene(
        SCENE, model, "stand_rack2", "rack2_screw2", target_offset=(0, 0, 0.06)
    )
    assert not res.outside and not tl.meta["clipped_joints"]
    assert collision_report(tl) == []
    # MuJoCo forward kinematics of the humanoid: wrist + hand direction lands on the target
    data = mujoco.MjData(tl.model)
    data.qpos[:] = tl.qpos[-1]
    mujoco.mj_kinematics(tl.model, data)
    wrist = data.xpos[tl.model.body("human/hand_l").id]
    tip = wrist + tl.meta["frame"] @ (res.directions[-1, 2] * model.lengths[2])
    assert np.linalg.norm(tip - tl.meta["target_world"]) < 0.01
    # straight onto the screw the fingers would hit the shelf: the check does see contacts
    tl2, _ = reach_in_scene(SCENE, model, "stand_rack2", "rack2_screw2")
    assert any(c.scene_geom == "rack2_shelf" for c in collision_report(tl2))
    # 80 cm below the screw (near the floor) is out of the standing arm's range: flagged
    _, far = reach_in_scene(SCENE, model, "stand_rack2", "rack2_screw2", target_offset=(0, 0, -0.8))
    assert far.outside and far.warnings


@pytest.mark.parametrize("side", ["left", "right"])
def test_either_hand_reaches_the_shelf_target_within_1cm_other_hand_at_rest(endpoint_model, side):
    """Issue 16: the hand asked for reaches (right-arm reaches mirror the left-arm model through
    the sagittal plane); the other hand stays where it was, and the shelf reach is
    collision-free by MuJoCo's check."""
    import mujoco

    from mjwalk.conventions import side_prefix
    from mjwalk.timeline.collisions import collision_report

    model, _ = endpoint_model
    # the screw on the hand's side of the body (facing the rack, screw 2 is on the left)
    screw = "rack2_screw2" if side == "left" else "rack2_screw1"
    tl, res = reach_in_scene(
        SCENE, model, "stand_rack2", screw, side=side, target_offset=(0, 0, 0.06)
    )
    assert not res.outside
    assert collision_report(tl) == []
    m, data = tl.model, mujoco.MjData(tl.model)
    other = "right" if side == "left" else "left"
    rest = None
    for k in (0, len(tl.qpos) - 1):
        data.qpos[:] = tl.qpos[k]
        mujoco.mj_kinematics(m, data)
        hand_other = data.xpos[m.body(f"human/hand_{side_prefix(other)}").id].copy()
        rest = hand_other if rest is None else rest
        assert np.linalg.norm(hand_other - rest) < 1e-9  # the other hand does not move
    wrist = data.xpos[m.body(f"human/hand_{side_prefix(side)}").id]
    tip = wrist + tl.meta["frame"] @ (res.directions[-1, 2] * model.lengths[2])
    assert np.linalg.norm(tip - tl.meta["target_world"]) < 0.01


def test_right_arm_reach_is_the_mirror_of_the_left(endpoint_model):
    """Mirror symmetry: the right-arm reach to a target equals the left-arm reach to the target
    mirrored through the sagittal plane, mirrored back, and its joint angles equal the left
    arm's (the humanoid's joint signs are anatomical, the same for both sides)."""
    from mjwalk.arms.chain import MIRROR_Y, REST_HAND
    from mjwalk.arms.reach import mirror_result

    model, _ = endpoint_model
    start = np.asarray(REST_HAND)
    end_left = np.array([0.35, 0.12, -0.25])
    left = model.predict(np.r_[start, end_left], start=start, end=end_left)
    right = mirror_result(left)
    assert np.allclose(right.hand[-1], end_left * MIRROR_Y, atol=0.01)
    assert np.allclose(mirror_result(right).directions, left.directions)
    q_left = arm_joint_angles(left.directions, "left")
    q_right = arm_joint_angles(right.directions, "right")
    assert np.allclose(q_left, q_right, atol=1e-9)


def test_a_scene_reach_refuses_a_model_of_another_kind():
    # a model of capture raises (mjwalk.arm_movements: start elbow + start hand + end hand,
    # upper arm and forearm only) cannot drive the humanoid's three-segment arm to a target
    from mjwalk.arms.reach import check_endpoint_model, reach_for_side

    data = reachgen.generate("endpoints", 30, np.random.default_rng(0))
    elbow = data.directions[:, 0, 0] * data.lengths[0]
    model = ReachModel(data.lengths[:2], dcs={"rng": 0, "max_neurons": 4}).fit(
        np.c_[elbow, data.constraints], data.directions[:, :, :2]
    )
    assert model.n_inputs == 9
    for side in ("left", "right"):
        with pytest.raises(MjwalkError, match="takes 9 inputs and has 2 segments"):
            reach_for_side(model, np.array([0.3, 0.1, -0.2]), side)
    # the model itself still predicts from its own constraint
    r = model.predict(np.r_[elbow[0], data.constraints[0]])
    assert r.directions.shape == (20, 2, 3)
    with pytest.raises(MjwalkError, match="not fitted"):
        check_endpoint_model(ReachModel(data.lengths))


@pytest.mark.parametrize("side", ["left", "right"])
def test_arm_joint_angles_recover_poses_across_the_shoulders_range(side):
    """Upper arm and forearm directions made by the humanoid's shoulder chain (R = Ry(-flex)
    Rx(s abd) Rz(-s rot), the arm along -z, the elbow Ry(-elbow)) from angles anywhere in the
    joints' ranges give those angles back -- an arm raised sideways above the shoulder
    (abduction beyond 90 deg) too, which came back as 180 deg flexion and rotation, beyond
    their ranges (a reach to a 1.95 m shelf ended 1.3 m off)."""
    from scipy.spatial.transform import Rotation

    from mjwalk.anthropometry import ROM_DEG

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


@pytest.mark.parametrize("hand", ["left", "right"])
@pytest.mark.parametrize("height", ["1.85", "1.95"])
def test_a_pick_from_a_shelf_above_the_head_ends_on_the_target(scenes_dir, tmp_path, hand, height):
    """A part 1.85 or 1.95 m up on bench a of the two-handed station (a top shelf, above the
    1.75 m operator's head), picked with one hand: the hand ends on it (1.95 m: it ended 1.3 m
    off, the arm clipped into extension by joint angles on the wrong Euler branch; 1.85 m:
    0.18 m off, beyond the working area the default model was trained on, reachgen.END_BOX)."""
    from mjwalk.cycle import reaching, reachspot
    from mjwalk.cycle.simulate import prepare
    from mjwalk.cycle.spec import load_cycle_spec

    xml = (scenes_dir / "assembly_station_2h.xml").read_text()
    xml = xml.replace(
        'name="bench_a_box" pos="0 -0.1 1.05"', f'name="bench_a_box" pos="0 -0.1 {height}"'
    )
    (tmp_path / "s.xml").write_text(xml)
    (tmp_path / "c.toml").write_text(
        'scene = "s.xml"\nstart = "stand_bench_a"\n[humanoid]\nstature = 1.75\n'
        f'[[task]]\nkind = "pick"\nsite = "bench_a_box"\nhand = "{hand}"\n'
    )
    ctx = prepare(load_cycle_spec(tmp_path / "c.toml"))
    st = ctx.workplace.station("stand_bench_a")
    r = reachspot.reach_task(
        ctx,
        ctx.spec.tasks[0],
        reachspot.ReachStart(st.pos[0], st.pos[1], st.yaw),
        reaching.ReachPace(0.4, 30.0, reaching.default_timing),
    )
    assert r.error < 0.01 and r.distance == np.inf
