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
