"""KernelParams: the one place that encodes a planner's options and a walk's terms into the
compiled kernels' parameter vectors (mjwalk.plan.params)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.plan import slots
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.options import (
    ON_SPOT_TURN_SPEED,
    STOP_REACH,
    PlannerOptions,
    leg_clearance,
)
from mjwalk.plan.params import KernelParams, WalkTerms
from mjwalk.world import load_workplace

GOAL = (2.0, 0.0)


@pytest.fixture(scope="module")
def params(scenes_dir) -> KernelParams:
    wp = load_workplace(scenes_dir / "open_floor.xml")
    options = PlannerOptions(goal_tolerance=0.5, goal_within=((2.2, 0.0, 0.4),), n_successors=7)
    return HybridPlanner(wp, GOAL, object(), options).params


def test_vectors_encode_the_options_and_are_fresh_copies(params):
    par, ipar = params.vectors()
    assert (par[slots.P_GOAL_X], par[slots.P_GOAL_Y], par[slots.P_TOLERANCE]) == (*GOAL, 0.5)
    assert par[slots.P_STOP_REACH] == 0.5 + STOP_REACH
    assert tuple(par[slots.P_DISC0 : slots.P_DISC0 + 3]) == (2.2, 0.0, 0.4)
    assert (ipar[slots.I_N_DISCS], ipar[slots.I_N_SUCCESSORS], ipar[slots.I_BINS]) == (1, 7, 1)
    assert ipar[slots.I_N_STOPS] == 0  # the model has no closing steps
    assert math.isnan(par[slots.P_PACE]) and math.isnan(par[slots.P_GUIDE0])
    par[slots.P_GOAL_X] = 99.0
    assert params.vectors()[0][slots.P_GOAL_X] == GOAL[0]  # the held vectors are untouched
    assert params.vectors(1.5)[0][slots.P_LEG_CLEARANCE] == leg_clearance(1.5)
    assert params.vectors(1.9)[0][slots.P_LEG_CLEARANCE] == leg_clearance(1.9)
    assert len(params.thresholds) == PlannerOptions().samples_per_step + 5  # 3 knee probes
    m = PlannerOptions().samples_per_step
    assert [ipar[slots.I_KNEE_COL0], ipar[slots.I_KNEE_COL1], ipar[slots.I_KNEE_COL2]] == [8, 12, 5]
    assert par[slots.P_KNEE_SHARE2] == pytest.approx(5 / (m - 1))


def test_a_walk_without_terms_changes_only_pace_and_far_weight(params):
    base, ibase = params.vectors()
    par, ipar = params.for_walk(1.75, WalkTerms(start_xy=np.array([-2.0, 0.0]), pace=1.3))
    changed = {int(k) for k in np.flatnonzero(~((par == base) | (np.isnan(par) & np.isnan(base))))}
    assert changed == {slots.P_PACE, slots.P_FAR_WEIGHT}
    assert par[slots.P_PACE] == 1.3 and par[slots.P_FAR_WEIGHT] == 0.0
    np.testing.assert_array_equal(ipar, ibase)


def test_a_spot_is_the_walks_goal_and_keeps_the_planners_goal_area_as_a_disc(params):
    spot = (2.3, 0.2, 0.1)
    par, ipar = params.for_walk(1.75, WalkTerms(start_xy=np.array([-2.0, 0.0]), spot=spot))
    assert (par[slots.P_GOAL_X], par[slots.P_GOAL_Y], par[slots.P_TOLERANCE]) == spot
    assert par[slots.P_STOP_REACH] == par[slots.P_HEADING_FROM] == 0.1 + STOP_REACH
    assert par[slots.P_DIST_OFFSET] == pytest.approx(math.hypot(0.3, 0.2))
    assert ipar[slots.I_N_DISCS] == 2
    assert tuple(par[slots.P_DISC0 + 3 : slots.P_DISC0 + 6]) == (*GOAL, 0.5)


def test_a_turn_on_the_spot_and_a_guide_are_encoded(params):
    guide = np.stack([np.linspace(-2.0, 2.0, 25), np.zeros(25)], axis=1)
    terms = WalkTerms(
        start_xy=np.array([-2.0, 0.0]), guide=guide, facing=math.pi, turn_pace=1.2, far_weight=0.05
    )
    par, _ = params.for_walk(1.75, terms)
    assert par[slots.P_START_YAW] == math.pi
    assert par[slots.P_TURN_COST] == pytest.approx(1.2 / ON_SPOT_TURN_SPEED)
    np.testing.assert_array_equal(par[slots.P_GUIDE0 : slots.P_DISC0], guide.ravel())
    assert par[slots.P_FAR_WEIGHT] == 0.05
    plain, _ = params.for_walk(1.75, WalkTerms(start_xy=np.array([-2.0, 0.0])))
    assert math.isnan(plain[slots.P_TURN_COST]) and math.isnan(plain[slots.P_START_YAW])


def test_a_goal_areas_vectors_are_those_its_own_options_make(scenes_dir):
    wp = load_workplace(scenes_dir / "open_floor.xml")
    site = HybridPlanner(wp, GOAL, object(), PlannerOptions(goal_tolerance=0.5, n_successors=7))
    for tolerance, within in ((0.3, ((2.2, 0.0, 0.4), (1.9, 0.1, 0.5))), (0.5, ())):
        options = PlannerOptions(goal_tolerance=tolerance, goal_within=within, n_successors=7)
        own = HybridPlanner(wp, GOAL, object(), options).params
        area = site.params.for_goal_area(options, own.discs)
        # the base's statures first (its vectors are the area's start), then the area's own
        for stature in (1.75, 1.6, 1.9, 1.75):
            for a, b in zip(area.vectors(stature), own.vectors(stature), strict=True):
                assert a.tobytes() == b.tobytes()  # bit for bit, nan slots included
        assert area.vectors(1.75)[0] is not area.vectors(1.75)[0]  # fresh copies
