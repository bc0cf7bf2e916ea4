"""Tests of mjwalk.mocap.naming: detection from joint names, map files, one-line errors."""

from __future__ import annotations

import pytest

from mjwalk.errors import CaptureError
from mjwalk.mocap.naming import (
    CONVENTIONS,
    detect_skeleton,
    load_skeleton_map,
    resolve_skeleton,
)

LEGS = {
    "humanik": ["Hips", "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase", "RightUpLeg",
                "RightLeg", "RightFoot", "RightToeBase", "Spine"],
    "lafan1": ["Hips", "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToe", "RightUpLeg", "RightLeg",
               "RightFoot", "RightToe"],
    "xsens_mvn": ["Pelvis", "L5", "RightUpperLeg", "RightLowerLeg", "RightFoot", "RightToe",
                  "LeftUpperLeg", "LeftLowerLeg", "LeftFoot", "LeftToe"],
    "rokoko": ["hips", "leftThigh", "leftShin", "leftFoot", "leftToe", "rightThigh",
               "rightShin", "rightFoot", "rightToe"],
    "bandai": ["joint_Root", "Hips", "UpperLeg_L", "Foot_L", "Toes_L", "UpperLeg_R", "Foot_R",
               "Toes_R"],
}  # fmt: skip


@pytest.mark.parametrize("conv", sorted(LEGS))
def test_each_convention_is_detected(conv):
    skel = detect_skeleton(LEGS[conv])
    assert skel.name == conv and skel.guess_scale and skel.guess_up
    assert set(skel.required_joints().values()) <= set(LEGS[conv])


def test_mixamo_prefix_and_case_are_ignored():
    names = ["mixamorig:" + n for n in LEGS["humanik"]]
    skel = detect_skeleton(names)
    assert skel.name == "humanik" and skel.ankle_l == "mixamorig:LeftFoot"
    assert detect_skeleton([n.upper() for n in LEGS["lafan1"]]).toe_r == "RIGHTTOE"


def test_cmu_bvh_hip_is_the_femur_head_not_lhipjoint():
    names = ["Hips", "LHipJoint", *LEGS["humanik"][1:]]
    assert detect_skeleton(names).hip_l == "LeftUpLeg"


def test_unknown_skeleton_names_the_map_fix():
    with pytest.raises(CaptureError, match=r"--skeleton map.toml") as exc:
        detect_skeleton(["root", "pelvis", "l_thigh", "l_ankle"], "x.bvh")
    assert "\n" not in str(exc.value)


def test_map_file(tmp_path):
    path = tmp_path / "map.toml"
    path.write_text(
        'pelvis = "Root"\nhip_l = "LH"\nhip_r = "RH"\nankle_l = "LA"\nankle_r = "RA"\n'
        'toe_l = "LT"\ntoe_r = "RT"\nunits = "in"\nup = "z"\n'
    )
    skel = load_skeleton_map(path)
    assert skel.scale == 0.0254 and skel.up == "z" and not skel.guess_scale and skel.verify
    assert resolve_skeleton(str(path), [], path).pelvis == "Root"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('pelvis = "R"\n', "names no joint for hip_l"),
        ('pelvis = "R"\nfoo = 1\n', "unknown key 'foo'"),
        ("pelvis = \n", "not a TOML skeleton map"),
    ],
)
def test_bad_map_files(tmp_path, text, message):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(CaptureError, match=message) as exc:
        load_skeleton_map(path)
    assert "\n" not in str(exc.value)


def test_resolve_presets_and_names():
    assert resolve_skeleton("bandai", [], "f").scale == 0.01
    assert resolve_skeleton("auto", LEGS["rokoko"], "f").name == "rokoko"
    assert resolve_skeleton("lafan1", LEGS["lafan1"], "f").guess_scale
    with pytest.raises(CaptureError, match="unknown skeleton 'nosuch'"):
        resolve_skeleton("nosuch", [], "f")
    assert len({c.name for c in CONVENTIONS}) == len(CONVENTIONS)
