"""Tests of mjwalk.mocap.bvh: BVH import (a toy file with known answers, its errors; real data)."""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np
import pytest

from mjwalk.errors import CaptureError
from mjwalk.mocap.bvh import bvh_forward_kinematics, load_bvh, parse_bvh
from mjwalk.mocap.skeletons import SkeletonMap
from mjwalk.mocap.take import Take

#: real capture: ``$MJWALK_SHARED_DATA`` or ../shared/data beside the project
DATA = Path(os.environ.get("MJWALK_SHARED_DATA", Path(__file__).parents[3] / "shared" / "data"))

# Toy skeleton: y up, centimetres. The walker faces +z (left hip on +x), i.e. world -y after the
# y-up -> z-up rotation (x, -z, y): pelvis yaw -90 deg in the rest pose.
TOY = SkeletonMap(
    name="toy",
    pelvis="Hips",
    ankle_l="AnkleL",
    ankle_r="AnkleR",
    toe_l="ToeL",
    toe_r="AnkleR_end",
    hip_l="HipL",
    hip_r="HipR",
    scale=0.01,
    up="y",
)

TOY_HIERARCHY = """HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT HipL
  {
    OFFSET 10 0 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT AnkleL
    {
      OFFSET 0 -40 0
      CHANNELS 0
      JOINT ToeL
      {
        OFFSET 0 0 10
        End Site
        {
          OFFSET 0 0 5
        }
      }
    }
  }
  JOINT HipR
  {
    OFFSET -10 0 0
    CHANNELS 6 Xposition Yposition Zposition Xrotation Zrotation Yrotation
    JOINT AnkleR
    {
      OFFSET 0 -40 0
      End Site
      {
        OFFSET 0 0 10
      }
    }
  }
}
MOTION
"""
#: channels: Hips(6) HipL(3: Z X Y) HipR(6: pos, X Z Y)
TOY_FRAMES = [
    # rest pose, pelvis at 90 cm
    "0 90 0 0 0 0  0 0 0  -10 0 0 0 0 0",
    # left hip Zrotation +90: left leg points along +x; right hip position channel moves it to -20
    "0 90 0 0 0 0  90 0 0  -20 0 0 0 0 0",
    # root yaw +90 about the up axis (Yrotation)
    "0 90 0 0 0 90  0 0 0  -10 0 0 0 0 0",
    # right hip X=90 then Z=90 in file order X Z Y: R = Rx(90) Rz(90)
    "0 90 0 0 0 0  0 0 0  -10 0 0 90 90 0",
]


def write_bvh(tmp_path: Path, frames: list[str], frame_time: str = "0.0333333", n=None) -> Path:
    n = len(frames) if n is None else n
    text = TOY_HIERARCHY + f"Frames: {n}\nFrame Time: {frame_time}\n" + "\n".join(frames) + "\n"
    path = tmp_path / "toy.bvh"
    path.write_text(text)
    return path


def joint(take: Take, name: str) -> np.ndarray:
    return take.joints[name]


def test_bvh_fk_known_positions(tmp_path):
    path = write_bvh(tmp_path, TOY_FRAMES, frame_time="0.00833333")  # 120 Hz: no resampling
    take = load_bvh(path, skeleton=TOY)
    assert take.n_frames == 4 and take.fps == 120.0
    # frame 0: cm -> m and y-up -> z-up: file (x, y, z) -> world (x, -z, y) / 100
    np.testing.assert_allclose(take.pelvis[0], [0, 0, 0.9], atol=1e-9)
    np.testing.assert_allclose(joint(take, "HipL")[0], [0.1, 0, 0.9], atol=1e-9)
    np.testing.assert_allclose(take.ankle_l[0], [0.1, 0, 0.5], atol=1e-9)
    np.testing.assert_allclose(take.toe_l[0], [0.1, -0.1, 0.5], atol=1e-9)
    np.testing.assert_allclose(joint(take, "ToeL_end")[0], [0.1, -0.15, 0.5], atol=1e-9)
    np.testing.assert_allclose(take.toe_r[0], [-0.1, -0.1, 0.5], atol=1e-9)  # End Site of AnkleR
    # facing file +z = world -y
    assert take.pelvis_yaw[0] == pytest.approx(-np.pi / 2)
    # frame 1: Rz(90) maps the shin (0,-40,0) to (40,0,0): ankle at file (50, 90, 0)
    np.testing.assert_allclose(take.ankle_l[1], [0.5, 0, 0.9], atol=1e-9)
    np.testing.assert_allclose(take.toe_l[1], [0.5, -0.1, 0.9], atol=1e-9)
    # a 6-channel joint below the root: its position channels replace its OFFSET
    np.testing.assert_allclose(joint(take, "HipR")[1], [-0.2, 0, 0.9], atol=1e-9)
    # frame 2: +90 deg about the up axis turns the walker CCW: yaw -90 -> 0
    np.testing.assert_allclose(joint(take, "HipL")[2], [0, 0.1, 0.9], atol=1e-9)
    assert take.pelvis_yaw[2] == pytest.approx(0.0, abs=1e-9)
    # frame 3: intrinsic order as listed, R = Rx(90) Rz(90): (0,-40,0) -> (40,0,0) -> (40,0,0)
    np.testing.assert_allclose(take.ankle_r[3], [0.3, 0, 0.9], atol=1e-9)


def test_bvh_channel_order_matters(tmp_path):
    # same angles, order Z X Y on HipL: R = Rz(90) Rx(90): (0,-40,0) -> (0,0,-40) -> (0,0,-40)
    path = write_bvh(tmp_path, ["0 90 0 0 0 0  90 90 0  -10 0 0 0 0 0"], frame_time="0.00833333")
    pos = bvh_forward_kinematics(parse_bvh(path))
    bvh = parse_bvh(path)
    ankle = pos[0, bvh.names.index("AnkleL")]
    np.testing.assert_allclose(ankle, [10, 90, -40], atol=1e-9)


def test_bvh_resampling_30_to_120(tmp_path):
    n = 10
    # pelvis walks along file +z (world -y) at 30 cm per frame, with a small vertical sine
    frames = [
        f"0 {90 + 2 * np.sin(k / 2):.6f} {30 * k} 0 0 0  0 0 0  -10 0 0 0 0 0" for k in range(n)
    ]
    take = load_bvh(write_bvh(tmp_path, frames), skeleton=TOY)
    assert take.fps == 120.0
    assert take.n_frames == 4 * n - 3
    assert take.meta["source_fps"] == pytest.approx(30.0)
    # original samples are reproduced exactly at their times
    src = parse_bvh(tmp_path / "toy.bvh").motion
    np.testing.assert_allclose(take.pelvis[::4, 1], -src[:, 2] / 100, atol=1e-9)
    np.testing.assert_allclose(take.pelvis[::4, 2], src[:, 1] / 100, atol=1e-9)
    # linear motion stays linear in between: 9 m/s / 120 Hz = 2.5 mm per sample
    np.testing.assert_allclose(np.diff(take.pelvis[:, 1]), -0.3 * 30 / 120, atol=1e-9)
    assert take.duration == pytest.approx((n - 1) / 30)


# ---------------------------------------------------------------- BVH errors


def _raises(path: Path, pattern: str, skeleton=TOY):
    with pytest.raises(CaptureError) as info:
        load_bvh(path, skeleton=skeleton)
    msg = str(info.value)
    assert path.name in msg, msg
    assert re.search(pattern, msg), msg
    return msg


def test_bvh_missing_file(tmp_path):
    _raises(tmp_path / "absent.bvh", "cannot read")


def test_bvh_truncated_frames(tmp_path):
    path = write_bvh(tmp_path, TOY_FRAMES[:2], n=4)
    _raises(path, r"line \d+: truncated.*Frames: 4.*2 frames")


def test_bvh_short_last_line(tmp_path):
    frames = [*TOY_FRAMES[:3], TOY_FRAMES[3].rsplit(" ", 3)[0]]
    path = write_bvh(tmp_path, frames)
    n_hier = TOY_HIERARCHY.count("\n")
    _raises(path, rf"line {n_hier + 2 + 4}: frame 4 has 12 values.*15 channels")


def test_bvh_wrong_value_count_mid_file(tmp_path):
    frames = list(TOY_FRAMES)
    frames[1] += " 7"
    n_hier = TOY_HIERARCHY.count("\n")
    _raises(write_bvh(tmp_path, frames), rf"line {n_hier + 2 + 2}: frame 2 has 16 values")


def test_bvh_too_many_frames_and_bad_number(tmp_path):
    _raises(write_bvh(tmp_path, TOY_FRAMES, n=3), r"line \d+: 'Frames: 3' but more")
    frames = list(TOY_FRAMES)
    frames[2] = frames[2].replace("90", "9O", 1)
    n_hier = TOY_HIERARCHY.count("\n")
    _raises(write_bvh(tmp_path, frames), rf"line {n_hier + 2 + 3}: .*'9O' is not a number")


def test_bvh_non_finite_and_empty(tmp_path):
    frames = list(TOY_FRAMES)
    frames[1] = frames[1].replace("90", "nan", 1)
    n_hier = TOY_HIERARCHY.count("\n")
    _raises(write_bvh(tmp_path, frames), rf"line {n_hier + 2 + 2}: frame 2, value 2 is nan")
    _raises(write_bvh(tmp_path, []), "Frames: 0")


def test_bvh_missing_joint(tmp_path):
    path = write_bvh(tmp_path, TOY_FRAMES)
    msg = _raises(path, "'Foot_L'", skeleton="bandai")
    assert "ankle_l" in msg


@pytest.mark.parametrize(
    ("edit", "pattern"),
    [
        # drop the closing brace of ToeL's End Site: MOTION arrives with a joint still open
        (lambda t: t.replace("OFFSET 0 0 5\n        }", "OFFSET 0 0 5\n"), r"joint 'Hips'"),
        (lambda t: t.replace("}\nMOTION", "}\n}\nMOTION"), r"line 38: unmatched"),
        (
            lambda t: t.replace("CHANNELS 3 Zrotation", "CHANNELS 3 Zrot"),
            r"line 9: joint 'HipL': unknown channel 'Zrot'",
        ),
        (
            lambda t: t.replace("OFFSET 10 0 0", "OFFSET 10 0"),
            r"line 8: OFFSET of 'HipL': 'CHANNELS' is not",
        ),
        (lambda t: t.replace("JOINT AnkleR", "JOINT HipL"), r"line 28: joint 'HipL' defined twice"),
        (lambda t: t.replace("HIERARCHY", "HIERARCHIE"), r"line 1: expected 'HIERARCHY'"),
        (lambda t: t.replace("MOTION", "MOTOIN"), r"unexpected 'MOTOIN'"),
        (lambda t: t.replace("OFFSET -10 0 0\n", ""), r"joint 'HipR' has no OFFSET"),
    ],
)
def test_bvh_malformed_hierarchy(tmp_path, edit, pattern):
    text = edit(TOY_HIERARCHY) + "Frames: 1\nFrame Time: 0.01\n" + TOY_FRAMES[0] + "\n"
    path = tmp_path / "bad.bvh"
    path.write_text(text)
    _raises(path, pattern)


# ---------------------------------------------------------------- ASF/AMC


# ---------------------------------------------------------------- real capture

BANDAI_CLIPS = [
    "dataset-2_walk_normal_001.bvh",
    "dataset-2_walk_masculine_002.bvh",
    "dataset-2_walk_feminine_003.bvh",
    "dataset-2_walk_youthful_004.bvh",
    "dataset-2_walk-turn-left_normal_005.bvh",
    "dataset-2_walk-turn-right_feminine_006.bvh",
]


def _lateral(take: Take, points: np.ndarray) -> np.ndarray:
    """Signed distance (m) of points to the left of the pelvis heading, per frame."""
    left = np.stack([-np.sin(take.pelvis_yaw), np.cos(take.pelvis_yaw)], axis=1)
    return np.sum((points[:, :2] - take.pelvis[:, :2]) * left, axis=1)


@pytest.fixture(scope="module")
def bandai_takes():
    folder = DATA / "bandai-walk"
    if not folder.is_dir():
        pytest.skip("real capture ../shared/data/bandai-walk not present")
    return {name: load_bvh(folder / name, skeleton="bandai") for name in BANDAI_CLIPS}


@pytest.mark.parametrize("name", BANDAI_CLIPS)
def test_bandai_walk_plausible(bandai_takes, name):
    take = bandai_takes[name]
    src = parse_bvh(DATA / "bandai-walk" / name)
    assert take.n_frames == 4 * src.motion.shape[0] - 3  # 30 -> 120 Hz
    # README: pelvis height about 0.89 m, walking speed 0.7-1.4 m/s
    assert 0.85 <= np.median(take.pelvis[:, 2]) <= 0.95
    step = np.linalg.norm(np.diff(take.pelvis[::12, :2], axis=0), axis=1)  # 0.1 s hops
    speed = step.sum() / (take.time[::12][-1])
    assert 0.7 <= speed <= 1.5
    # feet on the floor: ankles 5-20 cm, toes 0-10 cm high at their lowest
    for ankle, toe in ((take.ankle_l, take.toe_l), (take.ankle_r, take.toe_r)):
        assert 0.05 < ankle[:, 2].min() < 0.2
        assert -0.02 < toe[:, 2].min() < 0.1
    # the left ankle is on the walker's left, the right one on its right (on average)
    assert np.mean(_lateral(take, take.ankle_l)) > np.mean(_lateral(take, take.ankle_r)) + 0.05
    assert np.mean(_lateral(take, take.joints["UpperLeg_L"])) > 0.05


@pytest.mark.parametrize("name", [n for n in BANDAI_CLIPS if "_walk_" in n])
def test_bandai_yaw_matches_travel(bandai_takes, name):
    take = bandai_takes[name]
    w = int(take.fps)  # 1 s windows: one gait cycle averages the pelvis sway out
    d = take.pelvis[w:, :2] - take.pelvis[:-w, :2]
    moving = np.linalg.norm(d, axis=1) > 0.5
    travel = np.arctan2(d[:, 1], d[:, 0])
    yaw = np.convolve(take.pelvis_yaw, np.ones(w + 1) / (w + 1), mode="valid")
    err = np.degrees(np.angle(np.exp(1j * (yaw - travel))))[moving]
    assert moving.mean() > 0.5
    assert np.median(np.abs(err)) < 20.0


def test_bandai_turn_clip_turns(bandai_takes):
    left = bandai_takes["dataset-2_walk-turn-left_normal_005.bvh"].pelvis_yaw
    right = bandai_takes["dataset-2_walk-turn-right_feminine_006.bvh"].pelvis_yaw
    # README: about 90 deg per turn clip (CCW positive)
    assert 45 < np.degrees(left[-60:].mean() - left[:60].mean()) < 135
    assert -135 < np.degrees(right[-60:].mean() - right[:60].mean()) < -45
