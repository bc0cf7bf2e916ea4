"""Tests of mjwalk.mocap.asf: ASF/AMC import (a toy skeleton with known answers, its errors;
real CMU data)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from test_bvh import DATA, _lateral

from mjwalk.errors import CaptureError
from mjwalk.mocap.asf import load_amc, parse_asf
from mjwalk.mocap.skeletons import SkeletonMap

TOY_ASF = """# toy skeleton
:version 1.10
:name toy
:units
  mass 1.0
  length 0.5
  angle deg
:root
   order TX TY TZ RX RY RZ
   axis XYZ
   position 0 0 0
   orientation 0 0 0
:bonedata
  begin
     id 1
     name lhipjoint
     direction 1 0 0
     length 1
     axis 0 0 0 XYZ
  end
  begin
     id 2
     name lfemur
     direction 0 -1 0
     length 4
     axis 0 90 0 XYZ
    dof rx ry rz
    limits (-160.0 20.0)
           (-70.0 70.0)
           (-60.0 70.0)
  end
  begin
     id 3
     name lfoot
     direction 0 0 1
     length 1
     axis 0 0 0 XYZ
    dof rx
  end
  begin
     id 4
     name rhipjoint
     direction -1 0 0
     length 1
     axis 0 0 0 XYZ
  end
  begin
     id 5
     name rfemur
     direction 0 -1 0
     length 4
     axis 0 0 0 XYZ
    dof rx ry rz
  end
:hierarchy
  begin
    root lhipjoint rhipjoint
    lhipjoint lfemur
    lfemur lfoot
    rhipjoint rfemur
  end
"""

# Joints: lfemur starts at the left hip, lfoot at the left ankle, lfoot_end is the toe.
TOY_ASF_MAP = SkeletonMap(
    name="toy_asf",
    pelvis="root",
    ankle_l="lfoot",
    ankle_r="rfemur_end",
    toe_l="lfoot_end",
    toe_r="rfemur_end",
    hip_l="lfemur",
    hip_r="rfemur",
    scale=0.25,
    up="y",
    asf_length=0.25,  # the file says 0.5, so the effective scale is 0.125 m per unit
)


def toy_amc(frames: list[list[str]]) -> str:
    out = ["# toy", ":FULLY-SPECIFIED", ":DEGREES"]
    for k, lines in enumerate(frames, start=1):
        out.append(str(k))
        out.extend(lines)
    return "\n".join(out) + "\n"


AMC_REST = ["root 0 8 0 0 0 0", "lfemur 0 0 0", "lfoot 0", "rfemur 0 0 0"]
# lfemur rx = 90 inside C = Ry(90): a rotation by 90 deg about C·x = -z, (0,-4,0) -> (-4,0,0)
AMC_BENT = ["root 0 8 0 0 0 0", "lfemur 90 0 0", "lfoot 0", "rfemur 0 0 0"]


def write_asf_amc(tmp_path, amc_text: str, asf_text: str = TOY_ASF):
    asf, amc = tmp_path / "toy.asf", tmp_path / "toy.amc"
    asf.write_text(asf_text)
    amc.write_text(amc_text)
    return amc, asf


def test_parse_asf_reads_units_bones_and_hierarchy(tmp_path):
    path = tmp_path / "toy.asf"
    path.write_text(TOY_ASF)
    asf = parse_asf(path)
    assert asf.length_unit == 0.5 and asf.degrees
    assert asf.root_order == ["tx", "ty", "tz", "rx", "ry", "rz"] and asf.root_axis == "XYZ"
    assert list(asf.bones) == ["lhipjoint", "lfemur", "lfoot", "rhipjoint", "rfemur"]
    parents = {name: bone.parent for name, bone in asf.bones.items()}
    assert parents == {
        "lhipjoint": "root",
        "lfemur": "lhipjoint",
        "lfoot": "lfemur",
        "rhipjoint": "root",
        "rfemur": "rhipjoint",
    }
    femur = asf.bones["lfemur"]
    np.testing.assert_allclose(femur.direction, [0.0, -1.0, 0.0])
    np.testing.assert_allclose(femur.axis, [0.0, 90.0, 0.0])
    assert femur.length == 4.0 and femur.dof == ["rx", "ry", "rz"]


def test_amc_fk_known_positions(tmp_path):
    amc, asf = write_asf_amc(tmp_path, toy_amc([AMC_REST, AMC_BENT]))
    take = load_amc(amc, asf, skeleton=TOY_ASF_MAP, fps=120.0, amc_fps=120.0)
    s = 0.125  # metres per unit after the :units length adjustment
    assert take.meta["scale"] == pytest.approx(s)
    np.testing.assert_allclose(take.pelvis[0], np.array([0, 0, 8]) * s, atol=1e-9)
    np.testing.assert_allclose(take.joints["lfemur"][0], np.array([1, 0, 8]) * s, atol=1e-9)
    np.testing.assert_allclose(take.ankle_l[0], np.array([1, 0, 4]) * s, atol=1e-9)
    # toe: ASF +z (forward) is world -y
    np.testing.assert_allclose(take.toe_l[0], np.array([1, -1, 4]) * s, atol=1e-9)
    np.testing.assert_allclose(take.ankle_l[1], np.array([-3, 0, 8]) * s, atol=1e-9)
    assert take.pelvis_yaw[0] == pytest.approx(-np.pi / 2)


def test_amc_root_rotation_order(tmp_path):
    # root RY = 90 turns the walker CCW about the up axis: yaw -90 -> 0 deg
    frames = [["root 0 8 0 0 90 0", "lfemur 0 0 0", "lfoot 0", "rfemur 0 0 0"]]
    amc, asf = write_asf_amc(tmp_path, toy_amc(frames))
    take = load_amc(amc, asf, skeleton=TOY_ASF_MAP)
    assert take.pelvis_yaw[0] == pytest.approx(0.0, abs=1e-9)
    np.testing.assert_allclose(take.joints["lfemur"][0], np.array([0, 1, 8]) * 0.125, atol=1e-9)


def _amc_raises(amc, asf, pattern, skeleton=TOY_ASF_MAP, name=None):
    with pytest.raises(CaptureError) as info:
        load_amc(amc, asf, skeleton=skeleton)
    msg = str(info.value)
    assert (name or Path(amc).name) in msg, msg
    assert re.search(pattern, msg), msg


def test_amc_errors(tmp_path):
    # truncated: the last frame lacks bones
    amc, asf = write_asf_amc(tmp_path, toy_amc([AMC_REST, AMC_REST[:2]]))
    _amc_raises(amc, asf, r"line 11: frame 2 .*truncated: bone 'lfoot' missing")
    # short line: wrong number of values
    amc, asf = write_asf_amc(tmp_path, toy_amc([AMC_REST, ["root 0 8 0 0 0", *AMC_REST[1:]]]))
    _amc_raises(amc, asf, r"line 10: bone 'root' has 5 values, toy.asf declares 6")
    # missing joint named by the preset
    amc, asf = write_asf_amc(tmp_path, toy_amc([AMC_REST]))
    _amc_raises(amc, asf, r"'rfoot' \(ankle_r\)", skeleton="cmu", name="toy.asf")
    # missing files
    _amc_raises(tmp_path / "nope.amc", asf, "cannot read AMC")
    _amc_raises(amc, tmp_path / "nope.asf", "cannot read ASF", name="nope.asf")
    # malformed ASF: a bone never placed in the hierarchy / unknown parent
    bad = TOY_ASF.replace("    rhipjoint rfemur\n", "")
    amc, asf = write_asf_amc(tmp_path, toy_amc([AMC_REST]), bad)
    _amc_raises(amc, asf, "bone 'rfemur' is missing from :hierarchy", name="toy.asf")
    bad = TOY_ASF.replace("lfemur lfoot", "lfemurr lfoot")
    amc, asf = write_asf_amc(tmp_path, toy_amc([AMC_REST]), bad)
    _amc_raises(amc, asf, r"line 59: unknown parent bone 'lfemurr'", name="toy.asf")


# ---------------------------------------------------------------- real capture


def test_cmu_35_01_amc():
    folder = DATA / "cmu-35"
    if not (folder / "35_01.amc").is_file():
        pytest.skip("real capture ../shared/data/cmu-35 not present")
    take = load_amc(folder / "35_01.amc", folder / "35.asf", skeleton="cmu")
    assert take.fps == 120.0 and take.n_frames == 358
    assert 0.8 <= np.median(take.pelvis[:, 2]) <= 1.1
    speed = np.linalg.norm(take.pelvis[-1, :2] - take.pelvis[0, :2]) / take.duration
    assert 0.8 <= speed <= 1.6
    d = take.pelvis[-1, :2] - take.pelvis[0, :2]
    err = np.angle(np.exp(1j * (np.mean(take.pelvis_yaw) - np.arctan2(d[1], d[0]))))
    assert abs(np.degrees(err)) < 20
    assert (
        np.mean(_lateral(take, take.ankle_l)) > 0.03 > -0.03 > np.mean(_lateral(take, take.ankle_r))
    )
    # bone lengths are rigid: femur 7.41015 units in 35.asf
    femur = np.linalg.norm(take.joints["ltibia"] - take.joints["lfemur"], axis=1)
    np.testing.assert_allclose(femur, 7.41015 * 0.056444, rtol=1e-6)
