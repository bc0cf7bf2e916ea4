"""mjwalk.ergonomics.postures: RULA, REBA, OWAS and ISO 11226 as registered scores."""

from __future__ import annotations

import numpy as np
from test_assess import FPS, reach_cycle

from mjwalk.ergonomics import rula
from mjwalk.ergonomics.postures import Iso11226Score, OwasScore, RebaScore, RulaScore
from mjwalk.ergonomics.score import score_context


def test_per_frame_scores_follow_the_methods_and_the_task_takes_the_peak():
    ang, spans = reach_cycle()
    ctx = score_context(ang, spans, cycle_time=4.0, fps=FPS)
    frames = RulaScore().per_frame(ang, ctx)
    assert frames.arm.shape == (40, 2)
    np.testing.assert_array_equal(frames.frame, frames.arm.max(axis=1))
    # before the pick the hands are empty: the left arm scored as rula.parts_score does
    want = rula.parts_score(rula.part_scores(ang, 0), ctx.muscle[:, 0], 0)
    np.testing.assert_array_equal(frames.arm[:20, 0], want[:20])
    task = RulaScore().per_task(frames, spans[1], ctx)
    assert task["rula"] == frames.frame[20:40].max() and task["side"] == "left"
    assert task["upper_arm"] == 4 and 2.0 <= task["rula_time"] < 4.0
    reba = RebaScore().per_frame(ang, ctx)
    assert reba.arm[20:, 0].max() > reba.arm[:20, 0].max()
    owas = OwasScore().per_frame(ang, ctx)
    assert owas.shape == (40,) and set(np.unique(owas)) <= {1, 2, 3, 4}
    iso = Iso11226Score().per_run(None, ang, ctx)
    parts = [h.part for h in iso["holdings"]]
    assert parts == ["trunk", "upper_arm_left", "upper_arm_right"]
    assert iso["holdings"][0].held == 0.0  # an upright trunk is never held in the 20-60 zone


def test_body_parts_shared_by_both_arms_are_each_arms_own():
    """RULA and REBA score the neck, trunk and legs once for both arms (``body_parts``): each
    arm's part scores are those it gets computing them itself, on random body angles."""
    from dataclasses import replace

    from mjwalk.ergonomics import reba

    ang, _ = reach_cycle()
    rng = np.random.default_rng(3)
    n = ang.n_frames
    ang = replace(
        ang,
        trunk_flexion=rng.uniform(-30, 90, n),
        trunk_side_bend=rng.uniform(-20, 20, n),
        trunk_twist=rng.uniform(-20, 20, n),
        neck_flexion=rng.uniform(-20, 40, n),
        neck_twist=rng.uniform(-20, 20, n),
        knee_flexion=rng.uniform(0, 90, (n, 2)),
        feet_down=rng.random((n, 2)) < 0.7,
        walking=rng.random(n) < 0.3,
    )
    for method in (rula, reba):
        body = method.body_parts(ang)
        for side in (0, 1):
            own, shared = method.part_scores(ang, side), method.part_scores(ang, side, body)
            for a, b in zip(vars(own).values(), vars(shared).values(), strict=True):
                assert a.dtype == b.dtype
                np.testing.assert_array_equal(a, b)
