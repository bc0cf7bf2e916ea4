"""The turn after a crossing: its steps on the spot and their time (mjwalk.plan.spotturn), as
the body steps it (mjwalk.plan.stepturn) and as the hybrid A* costs it (issue 47)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import mjwalk.plan.levelplan as levelplan
from mjwalk.gait.default import default_model
from mjwalk.gait.walker import Walker
from mjwalk.plan import slots, stepcheck
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.params import WalkTerms
from mjwalk.plan.spotturn import (
    TURN_PER_STEP,
    spot_step_samples,
    spot_step_time,
    spot_steps,
    spot_turn_time,
)
from mjwalk.plan.stepturn import stepped_turn
from mjwalk.plan.synthetic import synthetic_walk
from mjwalk.plan.walks import plan_walk
from mjwalk.world import load_workplace

#: The synthetic walks' walker: 0.55 s steps (66 samples), feet 0.18 m apart.
WALKER = Walker(cadence=60.0 / 0.55, step_width=0.18)
#: Turns (degrees) clear of the step counts' bounds (45, 90, 180 deg) by more than a starter's
#: pelvis yaw at its first sample (a few degrees): 0, 0, 2, 4 and 4 steps on the spot.
TURNS_DEG = (0.0, 20.0, -70.0, 120.0, 180.0)


def test_the_steps_and_their_time():
    assert [spot_steps(math.radians(t)) for t in TURNS_DEG] == [0, 0, 2, 4, 4]
    assert spot_steps(TURN_PER_STEP) == 0 and spot_steps(TURN_PER_STEP + 1e-6) == 2
    assert spot_steps(-2.0 * TURN_PER_STEP) == 2 and spot_steps(2.0 * TURN_PER_STEP + 1e-6) == 4
    assert spot_step_samples(0.55) == 66 and spot_step_time(0.55) == pytest.approx(0.55)
    assert spot_step_samples(0.5312) == 64  # whole samples, as the animation plays them
    assert spot_turn_time(math.pi, 0.55) == pytest.approx(4 * 0.55)
    assert spot_turn_time(math.radians(30.0), 0.55) == 0.0


@pytest.mark.parametrize("turn_deg", TURNS_DEG)
def test_the_time_is_what_the_stepped_turn_adds_to_the_walk(turn_deg):
    """The body's stepped turn (on synthetic walks: one arriving along +x, a standing start
    turned ``turn_deg`` from where it stops) lasts exactly :func:`spot_turn_time` longer than
    the leg it is put before (a turn walked on adds nothing)."""
    arrive = synthetic_walk(n_steps=4, start=(0.0, 0.0, 0.0))
    leave = synthetic_walk(n_steps=4, start=(*arrive.xy[-1], math.radians(turn_deg)))
    walk = stepped_turn(leave, arrive, WALKER)
    added = (len(walk.t) - len(leave.t)) / 120.0
    turn = math.remainder(float(leave.yaw[0]) - float(arrive.yaw[-1]), 2.0 * math.pi)
    assert added == pytest.approx(spot_turn_time(turn, WALKER.step_duration), abs=1e-12)


@pytest.fixture(scope="module")
def starters(scenes_dir):
    """A planner on the open floor and 40 gait-initiation draws (seed 4) set off from (-2, 0)."""
    model = default_model()
    planner = HybridPlanner(load_workplace(scenes_dir / "open_floor.xml"), (3.5, 0.0), model)
    z, side = model.sample_first_features(40, np.random.default_rng(4))
    return planner, model, z, side == "left"


def _starter_g(planner, model, z, left, frame, terms):
    """The search's cost g (metres) of each starter set off at heading ``frame`` (radians)
    from (-2, 0) under the walk's ``terms``: by row (nan where the check refuses it)."""
    dec = planner.decoder(model)
    par, ipar = planner.params.for_walk(1.75, terms)
    node = np.array([[complex(-2.0, 0.0), np.nan, np.nan, 0.0, complex(np.nan, np.nan)]])
    frames = np.full(len(z), frame)
    near = np.zeros(1, bool)
    args = (dec.matrix, dec.offset, len(z), len(z), frames, left, near, node)
    rest = (planner.params.thresholds, par, ipar)
    field = (planner.workplace.walk_field().values, planner.distance.flat_bound())
    out = stepcheck.check_steps(z, *args, *rest, *field)
    g = np.full(len(z), np.nan)
    g[out[0]] = out[3]
    first_yaw = (z @ dec.matrix + dec.offset)[:, ipar[slots.I_M] + 2].real  # pelvis yaw, t = 0
    return g, frame + first_yaw


@pytest.mark.parametrize("turn_deg", TURNS_DEG)
def test_the_planner_costs_the_turn_after_a_crossing_as_its_steps_on_the_spot(starters, turn_deg):
    """A standing start after a crossing (``turn_step``, the walker's step duration) costs each
    starter its stepped turn's time (:func:`spot_turn_time` from where the walker faces to the
    walk's first yaw) times the turn's pace, within 1e-9 m: a half turn 4 x 0.55 s (before,
    at ON_SPOT_TURN_SPEED, 1.0 s), a 20 deg turn nothing (before 0.11 s) -- the time the
    stepped turn adds to the animated walk (test above)."""
    planner, model, z, left = starters
    facing, pace, step = 0.3, 1.3, WALKER.step_duration
    frame = facing + math.radians(turn_deg)
    start = np.array([-2.0, 0.0])
    plain, first = _starter_g(planner, model, z, left, frame, WalkTerms(start_xy=start))
    stepped = WalkTerms(start_xy=start, facing=facing, turn_pace=pace, turn_step=step)
    g, _ = _starter_g(planner, model, z, left, frame, stepped)
    ok = np.isfinite(plain)
    assert ok.sum() >= 20  # most starters clear on the open floor
    np.testing.assert_array_equal(np.isfinite(g), ok)
    turned = [math.remainder(y - facing, 2.0 * math.pi) for y in first[ok]]
    want = pace * np.array([spot_turn_time(t, step) for t in turned])
    np.testing.assert_allclose(g[ok] - plain[ok], want, rtol=0.0, atol=1e-9)
    steps = {0.0: 0, 20.0: 0, -70.0: 2, 120.0: 4, 180.0: 4}[turn_deg]
    np.testing.assert_allclose(want, pace * steps * 0.55, rtol=0.0, atol=1e-9)


def test_a_walk_over_levels_costs_its_turn_after_the_stair_as_stepped(scenes_dir, monkeypatch):
    """The station's walk from the mezzanine's rack down the stair to rack 1 (seed 0) turns
    about 140 deg after the stair: the level leg after it is planned with the walker's step as
    its ``turn_step``, and the cost the planner charges for its turn (:func:`spot_turn_time`
    from the heading the stair leaves the walker at, in seconds) equals the time the stepped
    turn adds to the walk's samples, within half a sample (the request's own turn from the
    stair's heading to the leg's first yaw: 4 steps of the walker's)."""
    requests, turns = [], []
    plan, step = HybridPlanner.plan, levelplan.stepped_turn

    def plan_spy(self, walk, rng):
        requests.append(walk)
        return plan(self, walk, rng)

    def step_spy(walk, crossing, walker):
        out = step(walk, crossing, walker)
        turns.append((walk, crossing, walker, (len(out.t) - len(walk.t)) / 120.0))
        return out

    monkeypatch.setattr(HybridPlanner, "plan", plan_spy)
    monkeypatch.setattr(levelplan, "stepped_turn", step_spy)
    wp = load_workplace(scenes_dir / "multilevel_station.xml")
    plan_walk(wp, "stand_mezz_rack", "stand_rack1", rng=0)
    assert len(turns) == 1
    leg, crossing, walker, added = turns[0]
    after = [r for r in requests if r.turn_on_spot]
    assert after and all(r.turn_step == walker.step_duration for r in after)
    facing = float(after[-1].start[2])  # the stair's heading, where the walker stands
    turn = math.remainder(float(leg.yaw[0]) - facing, 2.0 * math.pi)
    assert abs(math.remainder(facing - float(crossing.yaw[-1]), 2 * math.pi)) < 1e-9
    assert math.radians(120.0) < abs(turn) < math.radians(160.0)
    charged = spot_turn_time(turn, after[-1].turn_step)
    assert charged == pytest.approx(added, abs=0.5 / 120.0)
    assert charged == pytest.approx(4 * spot_step_time(walker.step_duration), abs=1e-12)
