"""Tests of mjwalk.mocap.bodycheck: units and up axis from the body, declared ones checked,
frame repairs; every bad file gets one line naming the fix."""

from __future__ import annotations

import itertools
import sys
from pathlib import Path

import numpy as np
import pytest

from mjwalk.errors import CaptureError
from mjwalk.mocap import bodycheck, load_bvh
from mjwalk.mocap.bvhwrite import write_bvh

sys.path.insert(0, str(Path(__file__).parent))
from test_invariance import _clip, _motion_lines


@pytest.fixture(scope="module")
def clip():
    return _clip(900)


def _map(tmp_path, **extra) -> Path:
    roles = dict(pelvis="Hips", hip_l="LeftUpLeg", hip_r="RightUpLeg", ankle_l="LeftFoot",
                 ankle_r="RightFoot", toe_l="LeftToeBase", toe_r="RightToeBase")  # fmt: skip
    roles.update(extra)
    path = tmp_path / "map.toml"
    path.write_text("".join(f"{k} = {v!r}\n".replace("'", '"') for k, v in roles.items()))
    return path


def _one_line(exc) -> str:
    text = str(exc.value)
    assert "\n" not in text
    return text


def test_declared_units_contradicting_the_body(clip, tmp_path):
    path = write_bvh(clip, tmp_path / "m.bvh", scale=1.0)  # metres, read as Bandai's cm
    with pytest.raises(CaptureError) as exc:
        load_bvh(path, skeleton=_map(tmp_path, units="cm"))
    assert "the data fit units = 'm'" in _one_line(exc)


def test_declared_up_contradicting_the_body(clip, tmp_path):
    path = write_bvh(clip, tmp_path / "z.bvh", up="z")
    with pytest.raises(CaptureError) as exc:
        load_bvh(path, skeleton=_map(tmp_path, up="y"))
    assert "use up = 'z'" in _one_line(exc)


def test_map_file_declaring_the_truth_reads(clip, tmp_path):
    path = write_bvh(clip, tmp_path / "i.bvh", scale=0.0254, up="z")
    take = load_bvh(path, skeleton=_map(tmp_path, units="in", up="z"))
    np.testing.assert_allclose(take.pelvis, clip.pelvis, atol=1e-5)


def test_pelvis_mapped_to_a_foot(clip, tmp_path):
    path = write_bvh(clip, tmp_path / "p.bvh")
    with pytest.raises(CaptureError) as exc:
        load_bvh(path, skeleton=_map(tmp_path, pelvis="LeftLeg"))
    assert "map the hip-centre joint as pelvis" in _one_line(exc)


def test_tiny_or_huge_units_name_the_map(clip, tmp_path):
    path = write_bvh(clip, tmp_path / "f.bvh", scale=0.3048)  # feet: not a unit tried
    with pytest.raises(CaptureError) as exc:
        load_bvh(path, skeleton=None)
    assert "give units in a skeleton map" in _one_line(exc)


def test_low_frame_rate_is_refused(clip, tmp_path):
    path = write_bvh(clip, tmp_path / "l.bvh", fps=15)
    with pytest.raises(CaptureError) as exc:
        load_bvh(path, skeleton=None)
    assert "below 24 Hz" in _one_line(exc)


def test_long_tracking_loss_is_refused(clip, tmp_path):
    path = write_bvh(clip, tmp_path / "g.bvh", fps=30)
    lines, first = _motion_lines(path)
    for t in range(200, 212):  # 0.4 s frozen while walking
        lines[first + t] = lines[first + 199]
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(CaptureError) as exc:
        load_bvh(path, skeleton=None)
    assert "tracking was lost there" in _one_line(exc)


def test_lying_body_has_no_up_axis(clip, tmp_path):
    path = write_bvh(clip, tmp_path / "x.bvh", up="z")
    text = path.read_text().replace(
        "Xposition Yposition Zposition", "Zposition Yposition Xposition"
    )
    path.write_text(text)  # the body now stands along the file's x
    with pytest.raises(CaptureError) as exc:
        load_bvh(path, skeleton=None)
    assert "only y or z up is supported" in _one_line(exc)


def test_cli_names_the_fix(tmp_path, capsys):
    from mjwalk import cli

    path = tmp_path / "odd.bvh"
    path.write_text(
        "HIERARCHY\nROOT a\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition Yposition Zposition\n"
        " End Site\n {\n  OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 1\nFrame Time: 0.01\n0 0 0\n"
    )
    status = cli.main(["train", "--bvh", str(path), "-o", str(tmp_path / "m.npz")])
    err = capsys.readouterr().err.strip()
    assert status == 2 and "--skeleton map.toml" in err and len(err.splitlines()) == 1
    assert not (tmp_path / "m.npz").exists()


def test_proportions_and_unit_choice():
    assert bodycheck.LEG_PER_STATURE == pytest.approx(0.491)  # Winter 2009: thigh + shank
    lo, hi = bodycheck.STATURE_RANGE
    # the candidate units are further apart than the stature range is wide: one fits at most
    ratios = sorted(bodycheck.UNIT_CANDIDATES.values())
    assert min(b / a for a, b in itertools.pairwise(ratios)) > hi / lo


def test_nothing_to_repair_returns_the_positions_unchanged(clip, tmp_path):
    from mjwalk.mocap.bvh import bvh_forward_kinematics, parse_bvh
    from mjwalk.mocap.naming import detect_skeleton

    bvh = parse_bvh(write_bvh(clip, tmp_path / "c.bvh"))
    pos = bvh_forward_kinematics(bvh)
    skel = bodycheck.body_frame(pos, bvh.names, detect_skeleton(bvh.names))
    out, done = bodycheck.repair_frames(pos, bvh.names, skel, bvh.fps)
    assert out is pos and done == {}
