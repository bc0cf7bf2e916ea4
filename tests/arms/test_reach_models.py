"""Reach models of either arm and of any arm size in scenes and cycles: where reaches start
(``ReachModel.rest_hand``), the arm-size scaling of scene targets (``arm_scale``), the right
arm's own model (``[models] reach_right``) and endpoint models trained on capture
(``arm_movements(..., hand=True)``)."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from mjwalk.arms import reachgen
from mjwalk.arms.chain import REST_HAND, arm_segment_lengths
from mjwalk.arms.reach import ReachModel, arm_scale, reach_for_side
from mjwalk.conventions import side_prefix
from mjwalk.cycle.simulate import prepare, simulate_cycle
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import CycleSpecError, MjwalkError
from mjwalk.timeline import reach_in_scene


def _model(seed: int, stature: float = 1.75, p: int = 60) -> tuple[ReachModel, reachgen.ReachData]:
    """An endpoint model fitted on ``p`` generated reaches of a ``stature`` m person."""
    data = reachgen.generate("endpoints", p, np.random.default_rng(seed), stature=stature)
    return ReachModel(data.lengths, dcs={"rng": 0}).fit(data.constraints, data.directions), data


@pytest.fixture(scope="module")
def two_models():
    return _model(1)[0], _model(2)[0]


@pytest.fixture(scope="module")
def small_arm_model():
    """A model trained on 80 reaches of a 1.50 m person's arms (fitted once for both arms'
    tests: reaching with a model leaves it as it was)."""
    return _model(4, stature=1.50, p=80)[0]


def test_rest_hand_is_where_the_training_reaches_start_and_is_saved(tmp_path):
    model, data = _model(3)
    np.testing.assert_allclose(model.rest_hand, data.constraints[:, :3].mean(axis=0))
    # the generator's reaches start within 2 cm (sd) of REST_HAND: the mean within a few mm
    assert np.linalg.norm(model.rest_hand - REST_HAND) < 0.01
    model.save(tmp_path / "m.npz")
    np.testing.assert_allclose(ReachModel.load(tmp_path / "m.npz").rest_hand, model.rest_hand)
    given = ReachModel(data.lengths, dcs={"rng": 0}, rest_hand=REST_HAND)
    given.fit(data.constraints, data.directions)
    np.testing.assert_allclose(given.rest_hand, REST_HAND)
    # a model of another constraint (obstacle ratio) has no start in it: the generated rest
    obstacle = reachgen.generate("obstacle", 30, np.random.default_rng(0))
    other = ReachModel(obstacle.lengths, dcs={"rng": 0})
    other.fit(obstacle.constraints, obstacle.directions)
    np.testing.assert_allclose(other.rest_hand, REST_HAND)
    with pytest.raises(MjwalkError, match="rest_hand must be three finite numbers"):
        ReachModel(rest_hand=(0.1, np.nan, 0.0))
    # either arm's reach starts there by default (a right arm: mirrored)
    end = np.array([0.4, 0.1, -0.1])
    for side, sign in (("left", 1.0), ("right", -1.0)):
        res = reach_for_side(model, end, side)
        np.testing.assert_allclose(res.hand[0], model.rest_hand * [1.0, sign, 1.0], atol=0.01)


@pytest.mark.parametrize("side", ["left", "right"])
def test_a_model_of_another_arm_size_reaches_scene_targets_within_1cm(
    scenes_dir, side, small_arm_model
):
    # trained on reaches of a 1.50 m person's arms, driving the 1.75 m humanoid: the target is
    # scaled into the model's size, the joint angles carry over (geometric similarity)
    model = small_arm_model
    scale = arm_scale(model, 1.75)
    assert scale == pytest.approx(1.50 / 1.75)
    tl, res = reach_in_scene(
        scenes_dir / "assembly_station.xml",
        model,
        "stand_rack2",
        "rack2_screw2" if side == "left" else "rack2_screw1",
        side=side,
        target_offset=(0, 0, 0.06),
    )
    assert tl.meta["scale"] == pytest.approx(scale)
    assert not res.outside and not tl.meta["clipped_joints"]
    data = mujoco.MjData(tl.model)
    data.qpos[:] = tl.qpos[-1]
    mujoco.mj_kinematics(tl.model, data)
    wrist = data.xpos[tl.model.body(f"human/hand_{side_prefix(side)}").id]
    # the humanoid's hand (1.75 m): the model's hand length unscaled
    hand = arm_segment_lengths(1.75)[2] * (tl.meta["frame"] @ res.directions[-1, 2])
    assert np.linalg.norm(wrist + hand - tl.meta["target_world"]) < 0.01


def _spec_with(scenes_dir, tmp_path, models: str):
    text = (scenes_dir / "assembly_station.toml").read_text()
    text = text.replace(
        'scene = "assembly_station.xml"', f'scene = "{scenes_dir}/assembly_station.xml"'
    )
    head, rest = text.split("[models]\n", 1)
    rest = rest.split("\n\n", 1)[1]
    path = tmp_path / "station.toml"
    path.write_text(f"{head}[models]\n{models}\n\n{rest}")
    return path


def test_the_right_arm_gets_its_own_model(scenes_dir, tmp_path, two_models, monkeypatch):

    left, right = two_models
    left.save(tmp_path / "left.npz")
    right.save(tmp_path / "right.npz")
    spec = load_cycle_spec(
        _spec_with(scenes_dir, tmp_path, 'reach = "left.npz"\nreach_right = "right.npz"')
    )
    assert spec.reach_model == str(tmp_path / "left.npz")
    assert spec.reach_model_right == str(tmp_path / "right.npz")
    ctx = prepare(spec)
    assert ctx.reach_model_for("left") is ctx.reach_model
    assert ctx.reach_model_for("right") is ctx.reach_model_right
    used: dict[str, set[int]] = {"left": set(), "right": set()}
    import mjwalk.arms.reach as reach_mod

    real = reach_mod.reach_for_side

    def spy(model, end, side, *args, **kwargs):
        used[side].add(id(model))
        return real(model, end, side, *args, **kwargs)

    monkeypatch.setattr(reach_mod, "reach_for_side", spy)
    res = simulate_cycle(ctx, rng=0)
    assert used == {"left": {id(ctx.reach_model)}, "right": {id(ctx.reach_model_right)}}
    assert {a.hand for a in res.arms} == {"left", "right"}
    assert max(a.hand_error for a in res.arms) < 0.01
    # the report says which models the runs used
    from mjwalk.report import format_markdown, report_dict

    rep = report_dict([res])
    assert rep["models"] == {
        "step": "default",
        "reach": str(tmp_path / "left.npz"),
        "reach_right": str(tmp_path / "right.npz"),
    }
    assert f"left arm `{tmp_path / 'left.npz'}`, right arm `{tmp_path / 'right.npz'}`" in (
        format_markdown(rep)
    )
    # without reach_right the right arm mirrors the reach model
    spec1 = load_cycle_spec(_spec_with(scenes_dir, tmp_path, 'reach = "left.npz"'))
    assert spec1.reach_model_right is None
    ctx1 = prepare(spec1)
    assert ctx1.reach_model_for("right") is ctx1.reach_model


def test_a_right_model_of_another_kind_is_refused_by_name(scenes_dir, tmp_path):
    data = reachgen.generate("obstacle", 20, np.random.default_rng(0))
    ReachModel(data.lengths, dcs={"rng": 0}).fit(data.constraints, data.directions).save(
        tmp_path / "bad.npz"
    )
    with pytest.raises(CycleSpecError, match=r"key 'reach_right' in \[models\]: .*1 inputs"):
        load_cycle_spec(_spec_with(scenes_dir, tmp_path, 'reach_right = "bad.npz"'))
    with pytest.raises(CycleSpecError, match=r"reach_right.*not found"):
        load_cycle_spec(_spec_with(scenes_dir, tmp_path, 'reach_right = "none.npz"'))


@pytest.mark.slow
def test_endpoint_models_trained_on_capture_drive_a_scene_reach(shared_data, scenes_dir):
    """Bandai raises of each arm (hand=True: the hand continues the forearm, the clips have no
    hand) -> an endpoint model per side -> the humanoid raises either hand in a scene to where
    the clips' raises end, within 1 cm, starting where the clips start."""
    from mjwalk.arms.armcapture import arm_movements
    from mjwalk.arms.reachdefault import CAPTURE_DCS
    from mjwalk.mocap.bvh import load_bvh

    folder = shared_data / "bandai-raise-hand"
    for side in ("left", "right"):
        files = sorted(folder.glob(f"*raise-up-{side}-hand*.bvh"))[::4]  # 64 of 257 clips
        mv = arm_movements([load_bvh(f) for f in files], side, "bandai", hand=True)
        assert mv.constraints.shape[1] == 6 and mv.directions.shape[2] == 3
        model = ReachModel(mv.lengths, dcs={**CAPTURE_DCS, "n_networks": 1}).fit(
            mv.constraints, mv.directions
        )
        # the clips' raises start from hanging arms and end overhead (left shoulder frame)
        assert model.rest_hand[2] < -0.5 and mv.constraints[:, 5].mean() > 0.3
        end_m = np.median(mv.constraints[:, 3:], axis=0)  # a typical raise's end, model size
        scale = arm_scale(model, 1.75)
        res = reach_for_side(model, end_m * [1.0, 1.0 if side == "left" else -1.0, 1.0], side)
        assert not res.outside
        # in a scene: the target where that raise ends for the 1.75 m humanoid
        scene = scenes_dir / "open_floor.xml"
        tl0, _ = reach_in_scene(scene, model, "west", "west", side=side)
        sh, fr = tl0.meta["shoulder"], tl0.meta["frame"]
        target = sh + fr @ (end_m * [1.0, 1.0 if side == "left" else -1.0, 1.0] / scale)
        site = tl0.meta["target_world"]
        tl, res = reach_in_scene(
            scene, model, "west", "west", side=side, target_offset=target - site
        )
        assert not res.outside and not res.warnings
        data = mujoco.MjData(tl.model)
        for k, want in ((0, None), (len(tl.qpos) - 1, target)):
            data.qpos[:] = tl.qpos[k]
            mujoco.mj_kinematics(tl.model, data)
            wrist = data.xpos[tl.model.body(f"human/hand_{side_prefix(side)}").id]
            hand = tl.meta["arm_lengths"][2] / scale  # the humanoid's hand, metres
            tip = wrist + fr @ (res.directions[-1 if k else 0, 2] * hand)
            if want is None:  # it starts where the clips' reaches start
                rest = model.rest_hand * [1.0, 1.0 if side == "left" else -1.0, 1.0]
                assert np.linalg.norm(tip - (sh + fr @ rest / scale)) < 0.01
            else:
                assert np.linalg.norm(tip - want) < 0.01


def test_a_model_file_is_read_once_for_the_spec_check_and_the_cycle(
    scenes_dir, tmp_path, two_models, monkeypatch
):
    """load_cycle_spec checks the reach model file and prepare() uses it: one read, one
    object; a rewritten file is read again."""
    from mjwalk.arms.reach import ReachModel

    left, _ = two_models
    left.save(tmp_path / "left.npz")  # a new file: not read before
    reads = []
    real = ReachModel.load.__func__

    def counting(cls, path):
        reads.append(str(path))
        return real(cls, path)

    monkeypatch.setattr(ReachModel, "load", classmethod(counting))
    spec = load_cycle_spec(_spec_with(scenes_dir, tmp_path, 'reach = "left.npz"'))
    ctx = prepare(spec)
    assert len(reads) == 1
    assert ctx.reach_model.n_neurons == left.n_neurons
    import os

    st = os.stat(tmp_path / "left.npz")
    os.utime(tmp_path / "left.npz", ns=(st.st_atime_ns, st.st_mtime_ns + 1_000_000_000))
    load_cycle_spec(_spec_with(scenes_dir, tmp_path, 'reach = "left.npz"'))
    assert len(reads) == 2
