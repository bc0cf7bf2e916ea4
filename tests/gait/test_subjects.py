"""Tests of mjwalk.gait.subjects: drawing virtual subjects."""

from __future__ import annotations

import numpy as np

from mjwalk.gait.subjects import SubjectParams, sample_subject


def test_subjects_are_deterministic_and_human():
    a = sample_subject(np.random.default_rng(7), 3)
    assert a == sample_subject(np.random.default_rng(7), 3)
    assert isinstance(a, SubjectParams) and a.subject == 3
    subjects = [sample_subject(np.random.default_rng(i), i) for i in range(50)]
    stature = np.array([s.stature for s in subjects])
    assert 1.6 < stature.min() and stature.max() < 1.9
    for s in subjects:
        assert s.pelvis_height == 0.51 * s.stature
        assert 0.5 < s.step_length < 0.95 and 0.45 < s.step_duration < 0.65
        assert 0.16 <= s.double_support <= 0.22 and s.turn_strategy in ("step", "spin")
