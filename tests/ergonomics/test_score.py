"""The task context every method reads: a part's mass is in its hand from its pick to its place,
both included; a hand reaching 4 times a minute or more, or holding a reach over a minute, counts
as repeated or static (a held posture: both arms); a part's coupling is REBA's score while a
hand handles it."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from mjwalk.ergonomics.score import STATIC_S, TaskSpan, percentiles, score_context, share

FPS = 10.0


def _ang(n: int):
    return SimpleNamespace(n_frames=n)  # score_context reads only the frame count


def test_a_part_is_in_its_hand_from_pick_to_place():
    spans = [
        TaskSpan(0, "walk", 0, 10),
        TaskSpan(1, "pick", 10, 20, "left", mass=4.0, coupling="fair", reach=True, part="take"),
        TaskSpan(2, "walk", 20, 30),
        TaskSpan(3, "place", 30, 40, "left", mass=4.0, coupling="fair", reach=True, part="put"),
        TaskSpan(4, "pick", 40, 50, "both", mass=6.0, reach=True, part="take"),
    ]
    ctx = score_context(_ang(50), spans, cycle_time=5.0, fps=FPS)
    np.testing.assert_array_equal(ctx.load[:10], 0.0)
    np.testing.assert_array_equal(ctx.load[10:40, 0], 4.0)
    np.testing.assert_array_equal(ctx.load[10:40, 1], 0.0)
    np.testing.assert_array_equal(ctx.load[40:], 3.0)  # both hands share it
    np.testing.assert_array_equal(ctx.coupling[10:20, 0], 1)  # fair
    np.testing.assert_array_equal(ctx.coupling[20:30], 0)  # walking with it: no handling
    np.testing.assert_array_equal(ctx.coupling[40:], 2)  # poor, the default
    # 3 reaches of the left hand, 1 of the right, in 5 s: both repeat more than 4/min
    assert ctx.muscle.all()


def test_a_long_hold_is_static_and_few_reaches_are_not_repeated():
    hold = int((STATIC_S + 1.0) * FPS)
    spans = [TaskSpan(0, "walk", 0, 100), TaskSpan(1, "fasten", 100, 100 + hold, "right",
                                                   reach=True)]  # fmt: skip
    ctx = score_context(_ang(100 + hold), spans, cycle_time=(100 + hold) / FPS, fps=FPS)
    assert not ctx.muscle[:100].any()  # 1 reach in 71 s is not repeated
    assert ctx.muscle[100:].all()  # the held posture is static, both arms (as assess had it)


def test_shares_and_percentiles():
    s = share(3, 10)
    assert s["share"] == 0.3 and s["low"] < 0.3 < s["high"]
    assert share(0, 0)["share"] is None
    assert percentiles([1, 2, 3])["p50"] == 2.0 and percentiles([])["n"] == 0
