"""benchmarks/bench_reach.py on a user's clip folder: bad clips stop it with a clear error
before any work (no traceback, exit status 2)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from mjwalk.arms.armcapture import ArmMovements
from mjwalk.errors import CaptureError

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
bench_reach = pytest.importorskip("bench_reach")


#: Leg joint names (hip, ankle, toe) per side of each BVH skeleton preset.
LEGS = {
    "bandai": {"L": ("UpperLeg_L", "Foot_L", "Toes_L"), "R": ("UpperLeg_R", "Foot_R", "Toes_R")},
    "cmu_bvh": {
        "L": ("LeftUpLeg", "LeftFoot", "LeftToeBase"),
        "R": ("RightUpLeg", "RightFoot", "RightToeBase"),
    },
}


def _leg(side: str, skeleton: str = "bandai") -> str:
    hip, ankle, toe = LEGS[skeleton][side]
    return f"""  JOINT {hip}
  {{
    OFFSET {"10" if side == "L" else "-10"} 0 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT {ankle}
    {{
      OFFSET 0 -80 0
      CHANNELS 3 Zrotation Xrotation Yrotation
      JOINT {toe}
      {{
        OFFSET 0 -5 10
        CHANNELS 3 Zrotation Xrotation Yrotation
        End Site
        {{
          OFFSET 0 0 5
        }}
      }}
    }}
  }}
"""


def _armless_bvh(path: Path, frames: int = 10, skeleton: str = "bandai") -> None:
    """A skeleton with the preset's leg names and no arms (centimetres, y up, 30 fps)."""
    row = " ".join(["0 90 0 0 0 0"] + ["0 0 0"] * 6)
    path.write_text(
        "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n"
        "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
        + _leg("L", skeleton)
        + _leg("R", skeleton)
        + f"}}\nMOTION\nFrames: {frames}\nFrame Time: 0.0333333\n"
        + "\n".join([row] * frames)
        + "\n"
    )


def test_corrupt_clip_stops_the_run_with_the_file_named(tmp_path, capsys):
    (tmp_path / "x_raise-up-left-hand_a_001.bvh").write_text("garbage\n")
    assert bench_reach.main(["--data", str(tmp_path), "--no-synthetic"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("bench_reach: error:")
    assert "x_raise-up-left-hand_a_001.bvh" in err and "HIERARCHY" in err


@pytest.mark.parametrize(
    "skeleton, arm",
    [
        ("bandai", "UpperArm_R, LowerArm_R, Hand_R"),
        ("cmu_bvh", "RightArm, RightForeArm, RightHand"),
    ],
)
def test_clip_without_arm_joints_names_the_missing_joints(tmp_path, capsys, skeleton, arm):
    _armless_bvh(tmp_path / "x_raise-up-right-hand_a_001.bvh", skeleton=skeleton)
    argv = ["--data", str(tmp_path), "--no-synthetic", "--skeleton", skeleton]
    assert bench_reach.main(argv) == 2
    err = capsys.readouterr().err
    assert f"no joint {arm} (the right arm of the {skeleton} skeleton" in err
    assert "joints present: Hips" in err


def test_every_clip_is_loaded_before_any_arm_is_evaluated(tmp_path, monkeypatch, capsys):
    """A bad right-arm clip stops the run before the (long) left-arm evaluation starts."""
    import numpy as np

    (tmp_path / "x_raise-up-left-hand_a_001.bvh").write_text("not read: load is replaced\n")
    good = ArmMovements(
        np.zeros((12, 9)),
        np.zeros((12, 20, 2, 3)),
        np.ones(2),
        np.ones(12),
        np.array(["a"] * 12),
        [],
    )

    def load(data_dir, max_clips, side, skeleton):
        if side == "right":
            raise CaptureError("x_raise-up-right-hand_a_001.bvh: bad clip")
        return good

    evaluated = []
    monkeypatch.setattr(bench_reach, "load_raise_hand", load)
    monkeypatch.setattr(bench_reach, "run_side", lambda ds, *a: evaluated.append(ds))
    assert bench_reach.main(["--data", str(tmp_path), "--no-synthetic"]) == 2
    assert evaluated == []
    assert "x_raise-up-right-hand_a_001.bvh: bad clip" in capsys.readouterr().err


def test_folder_without_clips_is_reported(tmp_path, capsys):
    assert bench_reach.main(["--data", str(tmp_path), "--no-synthetic"]) == 2
    assert "no raise-up-left/right-hand clips" in capsys.readouterr().out
