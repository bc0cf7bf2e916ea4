"""The compiled hybrid-A* search loop (mjwalk.plan.search) through the planner: its outcomes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk import PlanningError
from mjwalk.gait.default import default_model
from mjwalk.plan import search
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.slots import I_N_STOPS, P_GOAL_X, P_GOAL_Y, P_STOP_REACH
from mjwalk.plan.stepgeom import cell_key, in_goal, within
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


def test_a_cell_is_expanded_by_its_cheapest_node(model, scenes_dir, monkeypatch):
    """Hybrid-state A* (Dolgov et al. 2010, IJRR 29(5)): a grid cell keeps the one continuous
    state of lowest g, so the node that expands a cell (away from the goal, where cells close
    at once) is never dearer than a node that reached the cell before it closed. The base
    search expanded the first node popped, by f, and kept no best g: 17 of 45 expansions
    (seed 0, open_floor west -> east) were dearer than a node waiting in the same cell.

    The loop runs as Python (``py_func``, the compiled helpers unchanged) with its step check
    and legs' recheck wrapped to log each expansion and each accepted successor."""
    events, fails = [], []
    real_check, real_legs = search.check_into, search.legs_recheck

    def check(*args):
        node, par, ipar, out = args[8], args[10], args[11], args[14]
        goal = complex(par[P_GOAL_X], par[P_GOAL_Y])

        def ending(e, th):
            near = ipar[I_N_STOPS] > 0 and within(e - goal, par[P_STOP_REACH])
            return in_goal(e, th, par, ipar) or near

        p, g = node[0, 0], node[0, 3].real
        start = math.isnan(node[0, 1].real)
        events.append((False, cell_key(p, 0.0, par, ipar), g, ending(p, 0.0) or start))
        n = real_check(*args)
        keys, gs, ends, ths = out[1], out[3], out[4], out[5]
        for c in range(n):
            events.append((True, int(keys[c]), float(gs[c]), ending(ends[c], ths[c])))
        return n

    def legs(*args):
        ok = real_legs(*args)
        fails.append(not ok)
        return ok

    monkeypatch.setattr(search, "check_into", check)
    monkeypatch.setattr(search, "legs_recheck", legs)
    monkeypatch.setattr(search, "search", search.search.py_func)
    wp = load_workplace(scenes_dir / "open_floor.xml")
    planner = HybridPlanner(wp, "east", model, PlannerOptions())
    planner.plan("west", np.random.default_rng(0))
    assert not any(fails)  # no node dropped at its pop: the cheapest reached is expandable
    best: dict[int, float] = {}
    closed: set[int] = set()
    dearer = expanded = 0
    for reached, key, g, exempt in events:
        if exempt:  # the start, and nodes near the goal (closed after several expansions)
            continue
        if reached:
            if key not in closed:
                best[key] = min(best.get(key, math.inf), g)
        elif key not in closed:
            expanded += 1
            dearer += g > best[key]
            closed.add(key)
    assert expanded > 20
    assert dearer == 0
