"""Tests of mjwalk.gait.segment: key frames, steps, drops, real Bandai clips."""

from __future__ import annotations

import dataclasses
import itertools
import os
from pathlib import Path

import numpy as np
import pytest

from mjwalk.errors import CaptureError
from mjwalk.gait.corpus import generate_corpus
from mjwalk.gait.segment import (
    ContactOptions,
    SegmentationSummary,
    count_transitions,
    foot_contact,
    segment_take,
    segment_takes,
    step_sway,
    step_width,
)

#: real capture: ``$MJWALK_SHARED_DATA`` or ../shared/data beside the project
DATA = (
    Path(os.environ.get("MJWALK_SHARED_DATA", Path(__file__).parents[3] / "shared" / "data"))
    / "bandai-walk"
)


@pytest.fixture(scope="module")
def takes():
    # One virtual subject, 1.5 minutes: ~40 takes of all three protocols.
    return generate_corpus(1, seed=5, minutes_per_subject=1.5)


def _true_events(take):
    hs = sorted((int(f), s) for s in ("left", "right") for f in take.meta["heel_strikes"][s])
    return hs


def test_key_frames_within_two_frames_of_truth(takes):
    n = 0
    for take in takes:
        seg = segment_take(take)
        for side in ("left", "right"):
            for found, key in ((seg.heel_strikes, "heel_strikes"), (seg.toe_offs, "toe_offs")):
                truth = take.meta[key][side]
                assert found[side].shape == truth.shape, (take.name, side, key)
                assert np.all(np.abs(found[side] - truth) <= 2), (take.name, side, key)
                n += truth.size
        assert np.array_equal(seg.key_frames, np.sort(seg.key_frames))
    assert n > 300


def test_steps_match_true_footsteps(takes):
    """Footstep lengths within 1 cm, pelvis step lengths within 1.5 cm of the truth."""
    n = 0
    for take in takes:
        seg = segment_take(take)
        events = _true_events(take)
        assert len(seg.steps) == len(events)  # every step, including initiation, is kept
        ankles = {"left": take.ankle_l, "right": take.ankle_r}
        for step in seg.steps:
            k = step.index
            f1, side = events[k]
            assert step.side == side
            other = "right" if side == "left" else "left"
            f0 = events[k - 1][0] if k else step.meta["start_frame"]
            true_len = np.hypot(*(take.pelvis[f1, :2] - take.pelvis[f0, :2]))
            # Key frames are exact to +-1 frame, i.e. ~1.1 cm of pelvis travel at 1.3 m/s.
            assert abs(step.length - true_len) < 0.015
            true_foot = np.hypot(*(ankles[side][f1, :2] - ankles[other][f1, :2]))
            assert abs(np.hypot(*(step.footprint[:2] - step.stance[:2])) - true_foot) < 0.01
            n += 1
    assert n > 150


def test_step_structure_and_local_frame(takes):
    steps, summary = segment_takes(takes)
    assert isinstance(summary, SegmentationSummary)
    assert summary.n_steps == len(steps)
    assert summary.n_takes == len(takes)
    assert summary.n_initiations == len(takes)  # every virtual take starts standing
    assert summary.n_transitions == count_transitions(steps) == len(steps) - len(takes)
    assert sum(summary.dropped.values()) == 0
    text = str(summary)
    assert f"{summary.n_steps} steps" in text and "transitions" in text
    by_take: dict[str, list] = {}
    for s in steps:
        by_take.setdefault(s.take, []).append(s)
        assert np.allclose(s.pelvis[0], 0.0) and s.yaw[0] == 0.0
        assert s.pelvis.shape == (s.n_samples, 2) and s.yaw.shape == (s.n_samples,)
        assert 0.25 <= s.duration <= 1.5
        # The swing foot lands on its own side of the stance foot, across the mean foot yaw
        # (local frame: yaw 0 = +y, the walker's right is (cos yaw, sin yaw)).
        yaw = 0.5 * (s.stance[2] + s.footprint[2])
        lateral = (s.footprint[:2] - s.stance[:2]) @ [np.cos(yaw), np.sin(yaw)]
        if s.meta["protocol"] == "straight":
            assert (lateral < 0) == (s.side == "left")
    for ss in by_take.values():
        assert ss[0].meta["initiation"] and ss[0].index == 0
        assert ss[-1].meta["termination"]
        assert [s.index for s in ss] == list(range(len(ss)))
        assert all(a.side != b.side for a, b in itertools.pairwise(ss))


def test_straight_steps_heading_sway_width(takes):
    straight = [t for t in takes if t.meta["protocol"] == "straight"]
    steps, _ = segment_takes(straight)
    mid = [s for s in steps if not (s.meta["initiation"] or s.meta["termination"])]
    params = straight[0].meta["params"]
    # Straight ahead: landing footprints are in front, pelvis ends ahead on +y.
    assert all(s.pelvis[-1, 1] > 0.3 for s in mid)
    assert np.median([abs(s.footprint[2]) for s in mid]) < np.radians(20)
    sway = np.array([step_sway(s) for s in mid])
    assert 0.01 < np.median(sway) < 0.05
    width = np.median([step_width(s) for s in mid])
    assert abs(width - params["step_width"]) < 0.02


def test_contact_options_drive_detection(takes):
    take = takes[0]
    default = foot_contact(take)
    assert default.shape == (take.n_frames, 2) and default.dtype == bool
    assert np.array_equal(default, foot_contact(take, ContactOptions()))
    assert np.array_equal(segment_take(take).contact, default)
    # a height threshold below the planted ankle/toe noise floor finds less contact
    strict = foot_contact(take, ContactOptions(height_offset=-0.05))
    assert strict.sum() < default.sum()
    with pytest.raises(dataclasses.FrozenInstanceError):
        ContactOptions().sigma = 2.0  # type: ignore[misc]


def test_drops_are_counted_by_reason(takes):
    take = takes[0]
    base = segment_take(take)
    n = len(base.steps)
    seg = segment_take(take, max_duration=0.45)
    assert seg.dropped["too_long"] > 0 and len(seg.steps) == n - seg.dropped["too_long"]
    seg = segment_take(take, min_duration=0.7)
    assert seg.dropped["too_short"] > 0 and len(seg.steps) == n - seg.dropped["too_short"]
    seg = segment_take(take, max_length=0.3)
    assert seg.dropped["absurd_length"] > 0
    # Remove one swing of the right foot: two left heel strikes in a row -> no alternation.
    hs, to = take.meta["heel_strikes"]["right"], take.meta["toe_offs"]["right"]
    i = len(hs) // 2
    ankle, toe = take.ankle_r.copy(), take.toe_r.copy()
    ankle[to[i] : hs[i] + 1] = ankle[to[i] - 1]
    toe[to[i] : hs[i] + 1] = toe[to[i] - 1]
    ankle[hs[i] + 1 :] += ankle[to[i] - 1] - take.ankle_r[hs[i]]
    toe[hs[i] + 1 :] += toe[to[i] - 1] - take.toe_r[hs[i]]
    bad = dataclasses.replace(take, ankle_r=ankle, toe_r=toe)
    seg = segment_take(bad)
    assert seg.dropped["no_alternation"] >= 1


def test_bad_take_raises_capture_error(takes):
    take = takes[0]
    with pytest.raises(CaptureError, match="ankle_l"):
        segment_take(dataclasses.replace(take, ankle_l=take.ankle_l[:-1]))
    nan = take.toe_r.copy()
    nan[10, 2] = np.nan
    with pytest.raises(CaptureError, match=r"toe_r.*non-finite"):
        segment_take(dataclasses.replace(take, toe_r=nan))


@pytest.mark.skipif(not DATA.is_dir(), reason="../shared/data/bandai-walk not available")
def test_real_bandai_walk_clips():
    from mjwalk.mocap.bvh import load_bvh

    files = sorted(DATA.glob("dataset-2_walk_*.bvh"))[::3]  # 35 of the 103 straight walk clips
    assert files
    steps, summary = segment_takes(load_bvh(f) for f in files)
    assert summary.n_steps > 300
    durations = np.array([s.duration for s in steps if not s.meta["initiation"]])
    rate = 1.0 / np.median(durations)
    assert 1.6 <= rate <= 2.4  # steps per second
    # Left and right alternate: almost no candidate is dropped for lack of alternation.
    assert summary.dropped["no_alternation"] <= 0.02 * summary.n_candidates
    assert count_transitions(steps) >= 0.8 * len(steps)
    lengths = np.array([s.length for s in steps if not s.meta["initiation"]])
    assert 0.55 < np.median(lengths) < 0.8
