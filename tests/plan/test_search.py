"""The compiled hybrid-A* search loop (mjwalk.plan.search) through the planner: its outcomes."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk import PlanningError
from mjwalk.gait.default import default_model
from mjwalk.plan import search
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.options import PlannerOptions
from mjwalk.world import load_workplace


@pytest.fixture(scope="module")
def model():
    return default_model(progress=False)


def test_outcomes_are_distinct():
    assert len({search.FOUND, search.EXHAUSTED, search.BUDGET}) == 3


def test_budget_spent_is_reported(model, scenes_dir):
    wp = load_workplace(scenes_dir / "corridor.xml")
    planner = HybridPlanner(wp, "exit", model, PlannerOptions(max_expansions=5))
    with pytest.raises(PlanningError, match="budget of 5"):
        planner.plan("entry", np.random.default_rng(0))


def test_a_found_walk_stays_within_the_budget(model, scenes_dir):
    wp = load_workplace(scenes_dir / "open_floor.xml")
    planner = HybridPlanner(wp, "east", model, PlannerOptions(max_expansions=4000))
    walk = planner.plan("west", np.random.default_rng(0))
    assert 0 < walk.meta["expansions"] <= 4000
    assert walk.meta["generated"] >= walk.meta["expansions"]


def test_closing_draws_left_undrawn_change_nothing(model, scenes_dir, monkeypatch):
    """The closing draws the search leaves undrawn (stepgeom.closing_ends_far, with
    StepDecoder.closing_reach) are ones that could not have ended the walk: the same walks,
    step for step and with the same counts, as with the reach unbounded (every draw made)."""
    from mjwalk.plan.decoder import StepDecoder

    wp = load_workplace(scenes_dir / "open_floor.xml")
    walks = {}
    for bounded in (True, False):
        if not bounded:
            m_gp = len(model.stop_gp["left"].inducing)
            never = (np.array([np.inf, np.inf]), np.zeros(m_gp, complex))
            monkeypatch.setattr(StepDecoder, "closing_reach", lambda self, gp, n=never: n)
        planner = HybridPlanner(wp, "east", model, PlannerOptions())
        walks[bounded] = [planner.plan("west", np.random.default_rng(s)) for s in range(3)]
    for a, b in zip(walks[True], walks[False], strict=True):
        np.testing.assert_array_equal(a.xy, b.xy)
        np.testing.assert_array_equal(a.yaw, b.yaw)
        for k in ("expansions", "generated", "rejected", "stop_draws"):
            assert a.meta[k] == b.meta[k]
