"""benchmarks/bench_reach.py on a user's clip folder: bad clips stop it with a clear error
before any work (no traceback, exit status 2)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from mjwalk.arms.armcapture import ArmMovements
from mjwalk.errors import CaptureError
from mjwalk.mocap.skeletons import get_skeleton

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
bench_reach = pytest.importorskip("bench_reach")


#: Leg joint names (hip, ankle, toe) per side of each BVH skeleton preset.
LEGS = {
    "bandai": {"L": ("UpperLeg_L", "Foot_L", "Toes_L"), "R": ("UpperLeg_R", "Foot_R", "Toes_R")},
    "cmu_bvh": {
        "L": ("LeftUpLeg", "LeftFoot", "LeftToeBase"),
        "R": ("RightUpLeg", "RightFoot", "RightToeBase"),
    },
}


def _units(skeleton: str) -> float:
    """File units per centimetre of the preset (its declared units are checked on loading)."""
    return 0.01 / get_skeleton(skeleton).scale


def _leg(side: str, skeleton: str = "bandai") -> str:
    hip, ankle, toe = LEGS[skeleton][side]
    k = _units(skeleton)
    return f"""  JOINT {hip}
  {{
    OFFSET {10 * k if side == "L" else -10 * k} 0 0
    CHANNELS 3 Zrotation Xrotation Yrotation
    JOINT {ankle}
    {{
      OFFSET 0 {-80 * k} 0
      CHANNELS 3 Zrotation Xrotation Yrotation
      JOINT {toe}
      {{
        OFFSET 0 {-5 * k} {10 * k}
        CHANNELS 3 Zrotation Xrotation Yrotation
        End Site
        {{
          OFFSET 0 0 {5 * k}
        }}
      }}
    }}
  }}
"""


def _armless_bvh(
    path: Path, frames: int = 10, skeleton: str = "bandai", hips: str = "0 0 0"
) -> None:
    """A skeleton with the preset's leg names and no arms (the preset's units, y up, 30 fps)."""
    row = " ".join([f"0 {90 * _units(skeleton)} 0 0 0 0"] + ["0 0 0"] * 6)
    path.write_text(
        f"HIERARCHY\nROOT Hips\n{{\n  OFFSET {hips}\n"
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
        return good, np.array(["skeleton 1"] * 12)

    evaluated = []
    monkeypatch.setattr(bench_reach, "load_side", load)
    monkeypatch.setattr(bench_reach, "run_side", lambda ds, *a: evaluated.append(ds))
    assert bench_reach.main(["--data", str(tmp_path), "--no-synthetic"]) == 2
    assert evaluated == []
    assert "x_raise-up-right-hand_a_001.bvh: bad clip" in capsys.readouterr().err


def test_folder_without_clips_is_reported(tmp_path, capsys):
    assert bench_reach.main(["--data", str(tmp_path), "--no-synthetic"]) == 2
    assert "no raise-up-left/right-hand clips" in capsys.readouterr().out


def test_clips_of_one_skeleton_are_one_walker(tmp_path):
    """Walkers are told apart by their BVH skeleton: the Bandai actors differ in the Hips
    OFFSET only (../shared/data/README.md)."""
    names = ["a_001.bvh", "b_001.bvh", "a_002.bvh", "c_001.bvh"]
    for name, hips in zip(names, ["-0.73 93.31 -2.0", "-17.16 93.16 452.98"] * 2, strict=True):
        _armless_bvh(tmp_path / name, hips=hips)
    _armless_bvh(tmp_path / "c_001.bvh", hips="-0.73 93.31 -2.0", skeleton="cmu_bvh")
    from mjwalk.mocap.bvh import parse_bvh

    got = bench_reach.skeleton_walkers([parse_bvh(tmp_path / n) for n in names])
    assert got == {
        "a_001.bvh": "skeleton 1",
        "b_001.bvh": "skeleton 2",
        "a_002.bvh": "skeleton 1",
        "c_001.bvh": "skeleton 3",  # same offsets, other joint names
    }


def _synthetic_side(monkeypatch, n: int, styles: list[str], seed: int) -> ArmMovements:
    """``n`` generated shelf reaches as one arm's movements of ``styles`` (one per movement),
    and a small quick DCS for the benchmark's tables."""
    import numpy as np

    from mjwalk.arms import reachgen

    data = reachgen.generate("endpoints", n, np.random.default_rng(seed))
    fast = {**bench_reach.CAPTURE_DCS, "n_networks": 1, "max_neurons": 4}
    monkeypatch.setattr(bench_reach, "CAPTURE_DCS", fast)
    return ArmMovements(
        data.constraints,
        data.directions,
        data.lengths,
        np.ones(n),
        np.array(styles),
        [f"{i}.bvh" for i in range(n)],
    )


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore::sklearn.exceptions.ConvergenceWarning")  # the GP baseline
def test_leave_one_walker_out_table(monkeypatch, capsys):
    """With clips of two skeletons, each walker is predicted by a model of the other's clips;
    the table has a row per held-out walker and per style."""
    import numpy as np

    ds = _synthetic_side(monkeypatch, 30, ["feminine", "normal"] * 15, 0)
    walkers = np.array(["skeleton 1"] * 12 + ["skeleton 2"] * 18)
    bench_reach.run_side(ds, Path("clips"), 0.0, 0, walkers)
    out = capsys.readouterr().out
    assert "walkers (clips sharing one BVH skeleton): skeleton 1: feminine, normal;" in out
    table = out.split("per held-out walker")[1].splitlines()
    rows = {line.split()[0] + " " + line.split()[1]: line.split()[2:] for line in table[2:4]}
    assert rows["skeleton 1"][0] == "12" and rows["skeleton 2"][0] == "18"
    assert all(float(x) > 0 for r in rows.values() for x in r[1:])  # every model, both walkers
    assert "per style (of the held-out walker)" in out


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore::sklearn.exceptions.ConvergenceWarning")  # the GP baseline
def test_clips_of_one_skeleton_skip_the_walker_table(monkeypatch, capsys):
    import numpy as np

    ds = _synthetic_side(monkeypatch, 20, ["a"] * 20, 1)
    bench_reach.run_side(ds, Path("clips"), 0.0, 0, np.array(["skeleton 1"] * 20))
    out = capsys.readouterr().out
    assert "leave-one-style-out: skipped (one style only)" in out
    assert "leave-one-walker-out: skipped (the clips share one skeleton)" in out
    assert "per held-out" not in out


def test_a_group_is_held_out_only_with_enough_clips_left_to_train_on():
    """A stray clip of another skeleton is tested on a model of the others; the others are
    not tested on a model of that one clip (it would not train)."""
    import numpy as np

    labels = np.array(["skeleton 1"] * 12 + ["skeleton 2"] * 4)
    splits, held, short = bench_reach.group_splits(labels)
    assert bench_reach.K_NEIGHBOURS == 5
    assert held == ["skeleton 2"] and short == ["skeleton 1"]
    ((train, test),) = splits
    assert list(test) == [12, 13, 14, 15] and list(train) == list(range(12))


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore::sklearn.exceptions.ConvergenceWarning")  # the GP baseline
def test_one_style_per_skeleton_is_not_evaluated_twice(monkeypatch, capsys):
    import numpy as np

    ds = _synthetic_side(monkeypatch, 20, ["a"] * 10 + ["b"] * 10, 2)
    walkers = np.where(ds.groups == "a", "skeleton 1", "skeleton 2")
    bench_reach.run_side(ds, Path("clips"), 0.0, 0, walkers)
    out = capsys.readouterr().out
    assert "per held-out style" in out and "per held-out walker" not in out
    assert "leave-one-walker-out: the leave-one-style-out split (one style per skeleton)" in out
