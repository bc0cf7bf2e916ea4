"""Tests of mjwalk.gait.corpus: determinism, protocol, feet, LIPM pelvis, calibration."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from mjwalk.errors import MjwalkError
from mjwalk.gait.bout import ANKLE_HEIGHT, TOE_HEIGHT
from mjwalk.gait.corpus import generate_corpus
from mjwalk.gait.segment import segment_takes, step_sway
from mjwalk.gait.subjects import REAL_FIGURES, SubjectParams, sample_subject
from mjwalk.mocap.take import Take

ARRAYS = ("pelvis", "pelvis_yaw", "ankle_l", "ankle_r", "toe_l", "toe_r")


@pytest.fixture(scope="module")
def small():
    return generate_corpus(2, seed=11, minutes_per_subject=1.0)


def test_deterministic_and_seeded(small):
    again = generate_corpus(2, seed=11, minutes_per_subject=1.0)
    assert [t.name for t in again] == [t.name for t in small]
    for a, b in zip(small, again, strict=True):
        for name in ARRAYS:
            assert np.array_equal(getattr(a, name), getattr(b, name))
    other = generate_corpus(2, seed=12, minutes_per_subject=1.0)
    assert not np.array_equal(other[0].pelvis[:50], small[0].pelvis[:50]) or len(other) != len(
        small
    )
    # A subject's takes do not depend on how many subjects are generated.
    one = generate_corpus(1, seed=11, minutes_per_subject=1.0)
    assert np.array_equal(one[-1].pelvis, [t for t in small if t.meta["subject"] == 0][-1].pelvis)


def test_sample_subject_inter_subject_variance():
    rng = np.random.default_rng(0)
    subs = [sample_subject(rng, i) for i in range(400)]
    assert isinstance(subs[0], SubjectParams)
    stature = np.array([s.stature for s in subs])
    assert abs(stature.mean() - 1.75) < 0.01 and abs(stature.std() - 0.04) < 0.008
    assert len({s.turn_strategy for s in subs}) == 2
    assert np.std([s.step_length for s in subs]) > 0.01


def test_takes_follow_the_protocol(small):
    assert {t.meta["protocol"] for t in small} == {"free", "straight", "pole", "short"}
    assert len({t.name for t in small}) == len(small)
    pole = [t for t in small if t.meta["protocol"] == "pole"]
    assert {abs(t.meta["turn_deg"]) for t in pole} == {45.0, 90.0, 135.0, 180.0}
    for t in small:
        assert isinstance(t, Take) and t.fps == 120.0
        n = t.n_frames
        assert t.pelvis.shape == (n, 3) and t.pelvis_yaw.shape == (n,)
        assert {"subject", "protocol", "params"} <= t.meta.keys()
        # Starts and ends standing still: pelvis speed < 5 cm/s over the first/last 0.2 s.
        v = np.linalg.norm(np.diff(t.pelvis[:, :2], axis=0), axis=1) * t.fps
        assert v[:24].max() < 0.05 and v[-24:].max() < 0.05
        for foot in (t.ankle_l, t.ankle_r):
            assert np.ptp(foot[:24], axis=0).max() == 0.0 and np.ptp(foot[-24:], axis=0).max() == 0
    straight = [t for t in small if t.meta["protocol"] == "straight"]
    for t in straight:
        travel = np.hypot(*(t.pelvis[-1, :2] - t.pelvis[0, :2]))
        assert abs(travel - t.meta["distance"]) < 0.6
    for t in pole:
        turned = np.degrees(t.pelvis_yaw[-1] - t.pelvis_yaw[0])
        assert abs(turned - t.meta["turn_deg"]) < 15.0
    # Short walks end at their spot (``distance`` along a walking line that bends by up to
    # SHORT_TURN): the pelvis comes to rest over the end stance centre.
    for t in (t for t in small if t.meta["protocol"] == "short"):
        travel = np.hypot(*(t.pelvis[-1, :2] - t.pelvis[0, :2]))
        assert 0.985 * t.meta["distance"] - 0.005 < travel < t.meta["distance"] + 0.005


def test_short_walks_scale_their_steps():
    """Step-length targeting (seeded, 3 subjects): the short walks' initiation and closing
    steps spread over a wider range than those of the long bouts, and their steps are shorter
    the shorter the walk (pelvis chords in metres, from the segmented takes)."""
    steps, _ = segment_takes(generate_corpus(3, seed=0))
    short = [s for s in steps if s.meta["protocol"] == "short"]
    long = [s for s in steps if s.meta["protocol"] in ("straight", "pole")]
    for kind in ("initiation", "termination"):
        a = np.array([s.length for s in short if s.meta[kind]])
        b = np.array([s.length for s in long if s.meta[kind]])
        assert len(a) > 50
        assert a.std() > 1.3 * b.std(), (kind, a.std(), b.std())
        assert np.percentile(a, 10) < np.percentile(b, 10) - 0.03, kind
    by_walk: dict[str, list[float]] = {}
    dist: dict[str, float] = {}
    for s in short:
        by_walk.setdefault(s.take, []).append(s.length)
        dist[s.take] = s.meta["distance"]
    mean_chord = [np.mean(v) for v in by_walk.values()]
    assert np.corrcoef([dist[k] for k in by_walk], mean_chord)[0, 1] > 0.5


def test_feet_planted_in_stance_and_swing_arc(small):
    for t in small[:10]:
        p = t.meta["params"]
        for side, ankle, toe in (("left", t.ankle_l, t.toe_l), ("right", t.ankle_r, t.toe_r)):
            hs, to = t.meta["heel_strikes"][side], t.meta["toe_offs"][side]
            assert np.all(to < hs)
            # Stance: from each heel strike to the next toe-off, exactly stationary.
            for a, b in zip(hs[:-1], to[1:], strict=True):
                assert np.ptp(ankle[a:b], axis=0).max() == 0.0
                assert np.ptp(toe[a:b], axis=0).max() == 0.0
                assert ankle[a, 2] == pytest.approx(ANKLE_HEIGHT)
                assert toe[a, 2] == pytest.approx(TOE_HEIGHT)
            # Swing: the foot moves and lifts by the clearance.
            for a, b in zip(to, hs, strict=True):
                lift = ankle[a:b, 2].max() - ANKLE_HEIGHT
                assert 0.9 * p["clearance"] < lift <= p["clearance"] + 1e-9
            assert np.allclose(np.linalg.norm((toe - ankle)[:, :2], axis=1), p["foot_length"])


def test_lipm_pelvis_sways_towards_the_stance_foot(small):
    straight = [t for t in small if t.meta["protocol"] == "straight"]
    signs, amps = [], []
    for t in straight:
        events = sorted((int(f), s) for s in ("left", "right") for f in t.meta["heel_strikes"][s])
        ankles = {"left": t.ankle_l, "right": t.ankle_r}
        d = t.pelvis[-1, :2] - t.pelvis[0, :2]
        d /= np.linalg.norm(d)
        right = np.array([d[1], -d[0]])
        for (f0, s0), (f1, _) in itertools.pairwise(events[1:-1]):
            mid = (f0 + f1) // 2  # single support on foot s0
            lat_pelvis = (t.pelvis[mid, :2] - t.pelvis[0, :2]) @ right
            lat_foot = (ankles[s0][mid, :2] - t.pelvis[0, :2]) @ right
            lat_other = ankles["right" if s0 == "left" else "left"][mid, :2] - t.pelvis[0, :2]
            centre = 0.5 * (lat_foot + lat_other @ right)
            signs.append(np.sign(lat_pelvis - centre) == np.sign(lat_foot - centre))
            amps.append(abs(lat_pelvis - centre))
    assert np.mean(signs) > 0.95
    assert 0.01 < np.median(amps) < 0.05
    # Vertical bob: a small oscillation about the pelvis height.
    z = np.concatenate([t.pelvis[:, 2] for t in straight])
    assert 0.005 < np.ptp(z) < 0.05


def test_corpus_matches_calibration_figures():
    """Seeded statistical test: pooled step length / duration / sway of a 12-subject corpus
    match the captured figures (REAL_FIGURES["all"], Bandai) within stated tolerances."""
    # the paper's scenarios get the 1.5 minutes they had before the short walks (2.5 of 26.5)
    takes = generate_corpus(12, seed=0, minutes_per_subject=1.66)
    steps, _ = segment_takes(takes)
    steps = [s for s in steps if not (s.meta["initiation"] or s.meta["termination"])]
    assert len(steps) > 1500
    real = REAL_FIGURES["all"]
    length = np.array([s.length for s in steps])
    assert abs(length.mean() - real["length"][3]) < 0.03  # metres
    assert abs(length.std() - real["length"][4]) < 0.025
    duration = np.array([s.duration for s in steps])
    assert abs(np.median(duration) - real["duration"][0]) < 0.02  # seconds
    assert abs(duration.std() - real["duration"][4]) < 0.015
    sway = np.array([step_sway(s) for s in steps])
    assert abs(np.median(sway) - real["sway"][0]) < 0.006  # metres


def test_default_corpus_size():
    """The default corpus holds >= 20 000 captured transitions (n - 1 per take of n steps)."""
    takes = generate_corpus()
    assert len({t.meta["subject"] for t in takes}) == 12
    assert sum(t.meta["n_steps"] - 1 for t in takes) >= 20_000


def test_bad_arguments():
    with pytest.raises(MjwalkError, match="n_subjects"):
        generate_corpus(0)
    with pytest.raises(MjwalkError, match="minutes_per_subject"):
        generate_corpus(1, minutes_per_subject=-1.0)
