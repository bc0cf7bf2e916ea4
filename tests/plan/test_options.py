"""PlannerOptions: one frozen, checked record of a planner's choices (mjwalk.plan.options)."""

from __future__ import annotations

import dataclasses
import math

import mujoco
import numpy as np
import pytest

from mjwalk.anthropometry import leg_geometry
from mjwalk.body.humanoid import ROM_DEG, build_humanoid
from mjwalk.body.legs.curves import smoothstep
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.body.legs.steps import HEEL_RISE_MAX, SWING_TURNED, TOE_OFF
from mjwalk.errors import InputError
from mjwalk.gait.corpus import generate_corpus
from mjwalk.gait.segment import segment_takes
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.options import (
    ATTEMPTS,
    FOOT_ROLL_MAX,
    KNEE_LEAD,
    KNEE_SIDE,
    MAX_EXPANSIONS,
    MAX_FOOT_REACH,
    MIN_STEP_ADVANCE,
    SWING_LIFT_TURN,
    SWING_TURN_PHASES,
    PlannerOptions,
    foot_reach,
    knee_pivot,
    knee_reach,
    swing_turned,
    toe_corners,
)
from mjwalk.plan.slots import MAX_GOAL_DISCS
from mjwalk.world import load_workplace


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"heuristic": "manhattan"}, "heuristic must be 'dijkstra' or 'euclidean'"),
        ({"heuristic_weight": 0.9}, "heuristic_weight must be >= 1"),
        ({"heuristic_weight": math.nan}, "heuristic_weight must be >= 1"),
        ({"far_weight": -0.1}, "far_weight must be >= 0"),
        ({"cost": "time"}, "cost must be 'chord', 'path' or 'energy'"),
        ({"heading_weight": math.nan}, "heading_weight must be >= 0"),
        ({"goal_within": ((0.0, 0.0, 1.0),) * MAX_GOAL_DISCS}, "at most 6 discs"),
        ({"goal_within": ((0.0, math.inf, 1.0),)}, "radius > 0"),
        ({"goal_within": ((0.0, 0.0, 0.0),)}, "radius > 0"),
        ({"goal_within": ((0.0, 1.0),)}, r"\(x, y, radius\) triples"),
    ],
)
def test_bad_options_are_refused_on_construction(change, message):
    with pytest.raises(InputError, match=message) as err:
        PlannerOptions(**change)
    assert "\n" not in str(err.value)  # one line


def test_goal_discs_are_float_triples_whatever_they_come_in_and_bad_ones_are_refused():
    """Plain tuples and lists of number triples (a stand zone's, made for every operator) are
    read without NumPy; every other container takes NumPy's conversion: the same floats."""
    base = PlannerOptions(radius=0.3, goal_tolerance=0.1, field_tolerance=0.1, n_stops=0)
    for within in (
        ((1.0, 2.0, 0.5), (3.0, -1000.0, 1000.0)),
        (),
        ((1, 2, 3),),  # ints become floats
        [[1, 2, 3], (4.0, 5.0, 0.25)],
        np.array([[1.0, 2.0, 3.0]]),
        (1.0, 2.0, 3.0),  # one flat triple: NumPy's reshape
    ):
        got = dataclasses.replace(base, goal_tolerance=0.35, goal_within=within).goal_within
        want = np.asarray(within, dtype=float).reshape(-1, 3).tolist()
        assert [list(d) for d in got] == want
        assert type(got) is tuple and all(type(v) is float for d in got for v in d)
    bad = (
        ((1.0, 2.0, -1.0),),
        ((math.nan, 0.0, 1.0),),
        ((0.0, 0.0, 1.0),) * 7,
        ((1.0, 2.0),),
        ((1.0, "x", 2.0),),
    )
    for within in bad:
        with pytest.raises(InputError, match="goal_within"):
            dataclasses.replace(base, goal_tolerance=0.3, goal_within=within)


def test_options_are_frozen_and_normalized():
    options = PlannerOptions(attempts=0, n_stops=-2, heading_weight=3, goal_within=[[1, 2, 0.5]])
    assert options.attempts == 1 and options.n_stops == 0
    assert options.heading_weight == 3.0 and isinstance(options.heading_weight, float)
    assert options.goal_within == ((1.0, 2.0, 0.5),)
    with pytest.raises(dataclasses.FrozenInstanceError):
        options.radius = 0.3  # type: ignore[misc]
    default = PlannerOptions()
    assert (default.attempts, default.max_expansions) == (ATTEMPTS, MAX_EXPANSIONS)
    assert default == PlannerOptions() and hash(default) == hash(PlannerOptions())


def test_heading_bins_follow_the_goal_yaw_unless_given():
    assert PlannerOptions().bins == 1
    assert PlannerOptions(goal_yaw=0.5).bins == 8  # nodes of other headings kept apart
    assert PlannerOptions(goal_yaw=0.5, heading_bins=3).bins == 3
    # a variant re-derives the bins from its own goal yaw
    assert dataclasses.replace(PlannerOptions(), goal_yaw=1.0).bins == 8
    assert PlannerOptions(goal_tolerance=0.4).field_cells == 0.4
    assert PlannerOptions(goal_tolerance=0.4, field_tolerance=0.1).field_cells == 0.1


def test_a_planner_keeps_its_options_and_draws_closing_steps_only_from_a_model_that_has_them(
    scenes_dir,
):
    wp = load_workplace(scenes_dir / "open_floor.xml")
    options = PlannerOptions(radius=0.3, n_stops=4)

    class Stops:
        can_stop = True

    planner = HybridPlanner(wp, (2.0, 0.0), Stops(), options)
    assert planner.options is options and planner.radius == 0.3
    assert HybridPlanner(wp, (2.0, 0.0), object(), options).options.n_stops == 0
    assert HybridPlanner(wp, (2.0, 0.0), object()).options == PlannerOptions(n_stops=0)


def test_the_knee_probes_turn_with_the_swing_foot_as_the_leg_synthesis_turns_it():
    """The planner's copy of the swing foot's turn (it cannot import the body stage) is the
    leg synthesis's: the same phases, the same smoothstep."""
    assert SWING_TURN_PHASES == (TOE_OFF, SWING_TURNED)
    for share in (0.0, 0.2, 0.5, 0.75, 0.9, 1.0):
        want = float(smoothstep(np.array((share - TOE_OFF) / (SWING_TURNED - TOE_OFF))))
        assert swing_turned(share) == pytest.approx(want, abs=1e-12)
    assert swing_turned(0.5) == pytest.approx(0.394, abs=1e-3)  # at the first probe


def test_the_planted_feet_reach_scales_with_stature_and_rolls_as_the_leg_synthesis_rolls():
    """Issue 50: the planner's copy of the heel rise's limit and of the ball's place (it
    cannot import the body stage) are the leg synthesis's; the reach scales with stature."""
    assert FOOT_ROLL_MAX == pytest.approx(float(HEEL_RISE_MAX), abs=1e-12)
    for stature in (1.55, 1.75, 1.95):
        reach, roll = foot_reach(stature)
        assert reach == pytest.approx(MAX_FOOT_REACH * stature / 1.75)
        want = ball_offset(leg_geometry(stature)) * (1 - math.cos(float(HEEL_RISE_MAX)))
        assert roll == pytest.approx(want, abs=1e-12)
    assert foot_reach()[1] == pytest.approx(0.073, abs=1e-3)  # at 1.75 m


def test_the_knee_probes_scale_with_stature():
    assert knee_reach(1.75) == (KNEE_LEAD, KNEE_SIDE)
    lead, side = knee_reach(1.81)
    assert lead == pytest.approx(KNEE_LEAD * 1.81 / 1.75) and lead > KNEE_LEAD
    assert side == pytest.approx(KNEE_SIDE * 1.81 / 1.75)


def test_the_foot_yaw_knee_probes_lead_from_the_swing_hip():
    # the hip joint centre's offset (0.087 m at 1.75 m), inside KNEE_SIDE: that offset, taken
    # along the pelvis's yaw, also holds the lead turned by the toe-out the foot's yaw turns
    assert knee_pivot(1.75) == pytest.approx(0.087, abs=0.002) and knee_pivot(1.75) < KNEE_SIDE
    assert knee_pivot(1.81) == pytest.approx(knee_pivot(1.75) * 1.81 / 1.75)


def test_a_swing_foot_lifts_within_the_hips_rotation_range():
    # the spin turns' bound (mjwalk.body.legs.spin: the hip-rotation range), which the plan
    # stage cannot import
    assert math.degrees(SWING_LIFT_TURN) == pytest.approx(max(map(abs, ROM_DEG["hip_rot"])))


@pytest.mark.parametrize("stature", [1.55, 1.87])
def test_the_toe_probes_lie_at_the_synthesized_toes_front_corners(stature):
    """The landing toe probes (toe_corners) lie at the front corners of the humanoid's toe box,
    ahead of the ankle along a flat foot and to each side."""
    m = build_humanoid(stature).compile()
    d = mujoco.MjData(m)
    mujoco.mj_kinematics(m, d)
    ankle = d.xpos[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "foot_l")]
    g = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, "toes_l")
    ahead = np.hypot(*(d.geom_xpos[g] - ankle)[:2]) + m.geom_size[g][0]
    front, side = toe_corners(stature)
    assert ahead == pytest.approx(front, abs=1e-3)
    assert m.geom_size[g][1] == pytest.approx(side, abs=1e-3)


def test_no_corpus_step_goes_backward():
    """MIN_STEP_ADVANCE's ground: in the virtual corpus (here one subject's 1.5 minutes, every
    protocol: free walking with side steps and turns on the spot, straight, pole turns, short
    walks, first and closing steps) every step's end pelvis and landing ankle lie ahead of its
    start pelvis along its start heading (the step's local y; the default corpus's 25 037
    steps: at least 0.022 m and 0.002 m), and every walking step's landing ankle ahead of its
    stance ankle (the default corpus's 22 590: at least 0.043 m; its 2 447 closing steps bring
    the foot beside the stance foot, 0.001-0.020 m ahead), so the planner's forward tests refuse
    none of them."""
    takes = generate_corpus(1, seed=5, minutes_per_subject=1.5)
    steps, _ = segment_takes(takes)
    assert len(steps) > 100
    assert {s.meta.get("protocol") for s in steps} >= {"free", "straight", "pole", "short"}
    end = np.array([s.pelvis[-1, 1] for s in steps])
    ankle = np.array([s.footprint[1] for s in steps])
    assert end.min() > MIN_STEP_ADVANCE
    assert ankle.min() > MIN_STEP_ADVANCE
    walking = [s for s in steps if not s.meta.get("termination")]
    closing = [s for s in steps if s.meta.get("termination")]
    assert len(walking) > 100 and len(closing) > 5
    passed = np.array([s.footprint[1] - s.stance[1] for s in walking])
    assert passed.min() > MIN_STEP_ADVANCE + 0.04  # the swing foot passes the stance foot
    beside = np.array([s.footprint[1] - s.stance[1] for s in closing])
    assert np.all(np.abs(beside) < 0.03)  # a closing step's foot comes beside it
    assert MIN_STEP_ADVANCE == 0.0  # the principle itself, not the sample's least figures
