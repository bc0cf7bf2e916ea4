"""WalkRequest: what one walk asks of a planner, checked before any planning work
(mjwalk.plan.request)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.errors import InputError
from mjwalk.gait.default import default_model
from mjwalk.plan.guide import GUIDE_POINTS
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.request import WalkRequest
from mjwalk.world import load_workplace


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"spot": (1.0, 2.0)}, r"spot must be \(x, y, tolerance\)"),
        ({"spot": "near"}, r"spot must be \(x, y, tolerance\)"),
        ({"spot": (1.0, math.nan, 0.1)}, "spot must be finite with a tolerance > 0"),
        ({"spot": (1.0, 2.0, 0.0)}, "spot must be finite with a tolerance > 0"),
        ({"goal_heading": math.inf}, "goal_heading must be finite radians"),
        ({"goal_heading": "north"}, "goal_heading must be finite radians"),
        ({"work_heading": math.nan}, "work_heading must be finite radians"),
        ({"guide": [(0.0, 0.0)]}, "guide"),
    ],
)
def test_bad_requests_are_refused_on_construction(change, message):
    with pytest.raises(InputError, match=message) as err:
        WalkRequest((0.0, 0.0), **change)
    assert "\n" not in str(err.value)  # one line


def test_a_request_holds_its_values_checked():
    request = WalkRequest("west", spot=np.array([1, 2, 0.5]), goal_heading=np.float32(1.5))
    assert request.spot == (1.0, 2.0, 0.5) and all(type(v) is float for v in request.spot)
    assert type(request.goal_heading) is float
    guided = WalkRequest("west", guide=[(0.0, 0.0), (3.0, 0.0)])
    assert guided.guide.shape == (GUIDE_POINTS, 2)  # resampled evenly along the polyline
    np.testing.assert_allclose(np.diff(guided.guide[:, 0]), 3.0 / (GUIDE_POINTS - 1))
    with pytest.raises(AttributeError):
        request.spot = None  # type: ignore[misc]
    # a turn is split between the spot and the first steps only for a walker at work
    assert not request.at_work and WalkRequest("west", turn_on_spot=True, at_work=True).at_work
    # the front of the work (None: the start yaw), checked as a heading
    assert request.work_heading is None
    assert type(WalkRequest("west", work_heading=np.float32(1.5)).work_heading) is float


def test_a_start_alone_plans_as_its_request(scenes_dir):
    wp = load_workplace(scenes_dir / "open_floor.xml")
    planner = HybridPlanner(wp, (2.5, 0.0), default_model(progress=False))
    bare = planner.plan((-2.0, 0.3), np.random.default_rng(4))
    asked = planner.plan(WalkRequest((-2.0, 0.3)), np.random.default_rng(4))
    np.testing.assert_array_equal(bare.xy, asked.xy)
    np.testing.assert_array_equal(bare.yaw, asked.yaw)
