"""Short level legs walked as footfalls along their line (mjwalk.plan.shortleg): not searched,
within the walker's step length and time, ending in the goal area; longer, blocked or turning legs
left to the search. Seeded."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.gait.default import default_model
from mjwalk.gait.walker import Walker
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.levelcross import DEFAULT_STEP_WIDTH, ENTRY_TURN
from mjwalk.plan.levelplan import plan_level_walk
from mjwalk.plan.shortleg import SHORT_LEG_STEPS, short_leg
from mjwalk.world import load_workplace


class _Open:
    """A level view with ``clear`` metres of clearance everywhere (world xy)."""

    def __init__(self, clear: float):
        self.clear = clear

    def walk_clearance(self, xy: np.ndarray) -> np.ndarray:
        return np.full(len(np.atleast_2d(xy)), self.clear)


def _leg(d: float, yaw0: float | None = 0.0, heading: float | None = None, clear: float = 1.0):
    walker = Walker()
    start = (np.array([1.0, 2.0]), yaw0)
    aim = np.array([1.0 + d, 2.0])
    rng = np.random.default_rng(3)
    return short_leg(_Open(clear), start, aim, walker, (0.25, 0.25), (None, heading), rng), walker


@pytest.mark.parametrize("steps", [0.4, 1.0, 1.3, 2.0])
def test_footfalls_keep_the_walkers_step_limits(steps):
    walker = Walker()
    walk, _ = _leg(steps * walker.step_length)
    assert walk is not None
    walk.validate()
    d = steps * walker.step_length
    n = math.ceil(d / min(walker.step_length, 0.5) - 1e-9)  # the goal area 0.25 m about it
    assert len(walk.steps) == n
    sides = [s.side for s in walk.steps]
    assert all(a != b for a, b in itertools.pairwise(sides))  # feet alternate
    falls = np.array([s.foot[:2] for s in walk.steps])
    along = falls[:, 0] - 1.0
    assert np.all(np.diff(along) <= walker.step_length + 1e-9)  # none farther apart
    assert np.all(np.diff(along) >= -1e-12)
    across = np.abs(falls[:, 1] - 2.0)
    assert np.allclose(across, 0.5 * (walker.step_width or DEFAULT_STEP_WIDTH))
    m = max(1, round(walker.step_duration * SAMPLE_RATE_HZ))
    assert all(s.end - s.start == m for s in walk.steps)  # the walker's step time
    assert along[-1] == pytest.approx(d)  # the last footfall at the aim
    end = walk.xy[-1] - [1.0 + d, 2.0]
    assert abs(end[1]) < 1e-9 and -0.25 <= end[0] < 0.0  # the pelvis in its goal area
    assert walk.meta["expansions_all"] == 0


def test_left_to_the_search():
    walker = Walker()
    longer = SHORT_LEG_STEPS * walker.step_length + 0.01
    assert _leg(longer)[0] is None  # longer than SHORT_LEG_STEPS step lengths
    assert _leg(0.5, clear=0.2)[0] is None  # the body does not fit along the line
    assert _leg(0.5, yaw0=ENTRY_TURN + 0.05)[0] is None  # turns too far onto it
    assert _leg(0.5, heading=ENTRY_TURN + 0.05)[0] is None  # turns too far off it
    assert _leg(0.0)[0] is None  # no leg
    walk = _leg(0.5, yaw0=None)[0]  # a free start sets off along the line
    assert walk is not None and float(walk.yaw[0]) == 0.0


def test_turns_onto_the_line_in_its_first_step():
    walk, _ = _leg(0.9, yaw0=0.6)
    assert walk is not None
    assert float(walk.yaw[0]) == pytest.approx(0.6)
    first = walk.steps[0]
    assert np.allclose(walk.yaw[first.end :], 0.0)


@pytest.fixture(scope="module")
def station(scenes_dir):
    return load_workplace(scenes_dir / "multilevel_station.xml")


def test_a_step_walks_short_legs_unsearched(station, monkeypatch):
    """stand_step -> stand_platform1: a 0.47 m leg to the step's stance and a 0.89 m leg from
    it, both clear: no HybridPlanner.plan call (on the base tree: two), 0 expansions, every
    footfall within the walker's step length of the one before on its level."""
    model = default_model(progress=False)
    calls = []
    real = HybridPlanner.plan

    def counted(self, request, rng):
        calls.append(1)
        return real(self, request, rng)

    monkeypatch.setattr(HybridPlanner, "plan", counted)
    walk = plan_level_walk(
        station, "stand_step", "stand_platform1", model, np.random.default_rng(1)
    )
    assert calls == []
    assert walk.meta["expansions_all"] == 0
    assert [r["kind"] for r in walk.meta["levels"]["route"]] == ["level", "step", "level"]
    walk.validate()
    walker = Walker()
    reach = math.hypot(walker.step_length, walker.step_width or DEFAULT_STEP_WIDTH) + 1e-9
    for a, b in itertools.pairwise(walk.steps):
        assert b.start == a.end and a.side != b.side
        if abs(a.foot_z - b.foot_z) < 1e-6:  # on one level
            assert float(np.hypot(*(b.foot[:2] - a.foot[:2]))) <= reach
