"""Planned straight walks timed as captured ones are (``mjwalk validate``, bench_variability)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import MjwalkError
from mjwalk.gait.default import default_model
from mjwalk.gait.walker import Walker
from mjwalk.plan.walktimes import planned_straight_walks


def test_planned_straight_walks_take_the_walkers_time():
    """20 planned 6 m walks (10 from rest, 10 in motion) of a 1.3 m/s walker: in motion about
    6 / 1.3 = 4.6 s (median within 5 %); from rest longer (gait initiation); bad distances are
    refused before any planning."""
    model = default_model(progress=False).for_walker(Walker(speed=1.3, cadence=112.0))
    rng = np.random.default_rng(0)
    times = np.array(planned_straight_walks(model, [6.0] * 20, [False] * 10 + [True] * 10, rng))
    assert np.median(times[10:]) == pytest.approx(6.0 / 1.3, rel=0.05)
    assert np.median(times[:10]) > np.median(times[10:])
    for bad in ([-1.0], [np.nan], [np.inf]):
        with pytest.raises(MjwalkError, match="positive and finite"):
            planned_straight_walks(model, bad, [False], rng)
    with pytest.raises(MjwalkError, match="in_motion"):
        planned_straight_walks(model, [1.0, 2.0], [False], rng)
    assert planned_straight_walks(model, [], [], rng) == []
