"""Capture read alike whatever its skeleton names, units, up axis, frame rate and troubles.

A walk mjwalk generates itself (fast tier) and a shared Bandai walk (skipped when the data is
absent) are written in ``tmp_path`` under each naming convention, in cm / m / inches, y or z
up, at 24-240 Hz, with a T-pose first frame, frozen or deleted frames and a drifting root,
then read back with the convention, units and up axis detected. Tolerances: the same steps
(count; landing times within one frame of the coarser rate), median step length within 0.5 %
and duration within one frame (horizontal drift: 1 %); the trained models' pace (step length,
duration, speed) within 2 %.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from mjwalk.gait.corpus import generate_corpus
from mjwalk.gait.segment import segment_take
from mjwalk.mocap import Take, load_bvh
from mjwalk.mocap.bvhwrite import write_bvh

DATA = Path(os.environ.get("MJWALK_SHARED_DATA", Path(__file__).parents[3] / "shared" / "data"))
BANDAI_WALK = DATA / "bandai-walk" / "dataset-2_walk_normal_001.bvh"
ARRAYS = ("pelvis", "ankle_l", "ankle_r", "toe_l", "toe_r")


def _clip(n: int = 1800) -> Take:
    """The first 15 s of virtual subject 0's first walk (120 Hz)."""
    tk = generate_corpus(n_subjects=1, seed=0)[0]
    arrays = {k: getattr(tk, k)[:n].copy() for k in ARRAYS}
    return Take(tk.name, tk.fps, pelvis_yaw=tk.pelvis_yaw[:n].copy(), meta=tk.meta, **arrays)


@pytest.fixture(scope="module")
def clip() -> Take:
    return _clip()


def _figures(take: Take) -> dict:
    """Steps' landing times (s), median step length (m) and duration (s), steady steps only."""
    steps = segment_take(take).steps
    steady = [s for s in steps if not s.meta["initiation"] and not s.meta["termination"]]
    return {
        "ends": np.array([s.meta["end_frame"] / take.fps for s in steps]),
        "length": float(np.median([np.hypot(*(s.footprint[:2] - s.stance[:2])) for s in steady])),
        "duration": float(np.median([(s.pelvis.shape[0] - 1) / s.fps for s in steady])),
    }


def _same(ref: dict, got: dict, fps: float, shift: float = 0.0, length_tol: float = 0.005):
    frame = 1.0 / min(fps, 120.0)
    assert got["ends"].size == ref["ends"].size
    np.testing.assert_allclose(got["ends"], ref["ends"] + shift, atol=frame + 1e-9)
    assert got["length"] == pytest.approx(ref["length"], rel=length_tol)
    assert got["duration"] == pytest.approx(ref["duration"], abs=frame + 1e-9)


CASES = [
    ("humanik", "mixamorig:", 0.01, "y", 30),
    ("humanik", "", 1.0, "z", 120),
    ("humanik", "", 0.0254, "y", 60),
    ("lafan1", "", 0.01, "y", 30),
    ("lafan1", "", 1.0, "z", 24),
    ("xsens_mvn", "", 0.01, "z", 60),
    ("xsens_mvn", "", 0.0254, "y", 240),
    ("rokoko", "", 0.01, "y", 120),
    ("rokoko", "", 1.0, "y", 30),
    ("bandai", "", 0.0254, "z", 60),
]


@pytest.mark.parametrize(("conv", "prefix", "scale", "up", "fps"), CASES)
def test_generated_walk_reads_alike(clip, tmp_path, conv, prefix, scale, up, fps):
    ref = _figures(clip)
    path = write_bvh(clip, tmp_path / "w.bvh", conv, scale=scale, up=up, fps=fps, prefix=prefix)
    take = load_bvh(path, skeleton=None)
    assert take.meta["skeleton"] == conv
    assert take.meta["scale"] == scale
    _same(ref, _figures(take), fps)


def _with(take: Take, arrays: dict, yaw=None) -> Take:
    yaw = take.pelvis_yaw if yaw is None else yaw
    return Take(take.name, take.fps, pelvis_yaw=yaw, meta=take.meta, **arrays)


def test_t_pose_first_frame_is_cut(clip, tmp_path):
    pose = {k: np.repeat(getattr(clip, k)[:1], 2, axis=0) for k in ARRAYS}
    pose["pelvis"][:, :2] = 0.0  # bind pose at the origin, legs straight, feet together
    pose["ankle_l"][:] = [0.0, 0.08, 0.07]
    pose["ankle_r"][:] = [0.0, -0.08, 0.07]
    pose["toe_l"][:], pose["toe_r"][:] = [0.14, 0.08, 0.02], [0.14, -0.08, 0.02]
    tpose = Take("tpose", clip.fps, pelvis_yaw=np.zeros(2), meta=clip.meta, **pose)
    t_lines, t_first = _motion_lines(write_bvh(tpose, tmp_path / "p.bvh"))
    ref = _figures(clip)
    for fps in (30, 120):
        path = write_bvh(clip, tmp_path / "t.bvh", fps=fps)
        lines, first = _motion_lines(path)
        lines.insert(first, t_lines[t_first])
        lines[first - 2] = f"Frames: {len(lines) - first}"
        path.write_text("\n".join(lines) + "\n")
        take = load_bvh(path, skeleton=None)
        assert take.meta["cut_start"] == 1
        _same(ref, _figures(take), fps)


def _motion_lines(path: Path) -> tuple[list[str], int]:
    lines = path.read_text().splitlines()
    return lines, next(k for k, s in enumerate(lines) if s.startswith("Frame Time")) + 1


def test_frozen_frames_are_interpolated(clip, tmp_path):
    ref = _figures(clip)
    path = write_bvh(clip, tmp_path / "f.bvh", fps=30)
    lines, first = _motion_lines(path)
    for t in (100, 101, 300, 301, 302):  # the tracker repeats the last pose it had
        lines[first + t] = lines[first + t - 1]
    path.write_text("\n".join(lines) + "\n")
    take = load_bvh(path, skeleton=None)
    assert take.meta["frozen_filled"] == 5
    _same(ref, _figures(take), 30)


def test_dropped_frames_keep_the_steps(clip, tmp_path):
    ref = _figures(clip)
    path = write_bvh(clip, tmp_path / "d.bvh", fps=120)
    lines, first = _motion_lines(path)
    for t in (700, 401, 400, 150):  # four frames missing from the file
        del lines[first + t]
    lines[first - 2] = f"Frames: {len(lines) - first}"
    path.write_text("\n".join(lines) + "\n")
    got = _figures(load_bvh(path, skeleton=None))
    assert got["ends"].size == ref["ends"].size
    np.testing.assert_allclose(got["ends"], ref["ends"], atol=4 / 120 + 1e-9)
    assert got["length"] == pytest.approx(ref["length"], rel=0.005)
    assert got["duration"] == pytest.approx(ref["duration"], abs=1 / 120 + 1e-9)


@pytest.mark.parametrize(
    ("drift", "length_tol"),
    [((0.0, 0.0, 0.01), 0.005), ((0.02, 0.01, 0.0), 0.01)],
    ids=["vertical-1cm/s", "horizontal-2cm/s"],
)
def test_root_drift(clip, tmp_path, drift, length_tol):
    t = clip.time[:, None]
    drifted = _with(clip, {k: getattr(clip, k) + t * np.array(drift) for k in ARRAYS})
    take = load_bvh(write_bvh(drifted, tmp_path / "r.bvh", fps=60), skeleton=None)
    if drift[2]:
        assert take.meta["floor_drift_m"] == pytest.approx(drift[2] * clip.duration, rel=0.1)
    _same(_figures(clip), _figures(take), 60, length_tol=length_tol)


@pytest.mark.parametrize("size", [0.8, 1.1])
def test_other_statures_get_their_units(clip, tmp_path, size):
    """A 1.40 m and a 1.93 m walker (the clip scaled): units still found, steps scale."""
    scaled = _with(clip, {k: getattr(clip, k) * size for k in ARRAYS})
    for scale in (0.01, 0.0254, 1.0):
        take = load_bvh(write_bvh(scaled, tmp_path / "s.bvh", scale=scale), skeleton=None)
        assert take.meta["scale"] == scale
    ref = _figures(clip)
    got = _figures(take)
    assert got["length"] == pytest.approx(size * ref["length"], rel=0.005)


@pytest.mark.skipif(not BANDAI_WALK.exists(), reason="shared Bandai data absent")
@pytest.mark.parametrize(("conv", "prefix", "scale", "up", "fps"), CASES[:6])
def test_bandai_walk_reads_alike(tmp_path, conv, prefix, scale, up, fps):
    bandai = load_bvh(BANDAI_WALK, skeleton="bandai")
    ref = _figures(bandai)
    path = write_bvh(bandai, tmp_path / "b.bvh", conv, scale=scale, up=up, fps=fps, prefix=prefix)
    take = load_bvh(path, skeleton=None)
    assert take.meta["skeleton"] == conv and take.meta["scale"] == scale
    got = _figures(take)
    _same(ref, got, min(fps, 30.0))  # the source is 30 Hz capture


@pytest.mark.slow
def test_trained_model_figures_match(clip, tmp_path):
    """The pace of models trained on the clip and on two rewritten copies agree within 2 %."""
    from mjwalk.gait.default import train_model

    def pace(take):
        model, _ = train_model([take], seed=0)
        return model.pace()

    ref = pace(clip)
    for conv, prefix, scale, up, fps in (CASES[0], CASES[6]):
        path = write_bvh(clip, tmp_path / "m.bvh", conv, scale=scale, up=up, fps=fps, prefix=prefix)
        got = pace(load_bvh(path, skeleton=None))
        assert got.step_length == pytest.approx(ref.step_length, rel=0.02)
        assert got.step_duration == pytest.approx(ref.step_duration, rel=0.02)
        speed = got.step_length / got.step_duration
        assert speed == pytest.approx(ref.step_length / ref.step_duration, rel=0.02)
