"""mjwalk.cycle.actions.walk_to: a walk goes to its task's site, and its record carries the
grid-A* route between the walk's own ends."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.cycle.actions.base import CycleRun
from mjwalk.cycle.actions.walk_to import Walk
from mjwalk.cycle.context import context_of
from mjwalk.cycle.types import TASK_KINDS, Task


def test_the_goal_is_the_tasks_site():
    assert Walk(Task("walk", site="stand_rack1"), TASK_KINDS["walk"], 0).goal == "stand_rack1"


def test_the_record_measures_the_grid_route_between_the_walks_ends(scenes_dir):
    ctx = context_of(scenes_dir / "assembly_station.toml")
    a, b = ctx.workplace.station("stand_rack1").xy, ctx.workplace.station("stand_rack2").xy
    path = ctx.baseline_route(a, b)
    assert path is not None
    rng = np.random.default_rng(0)
    run = CycleRun(ctx, None, 30.0, rng, rng, rng, np.zeros(3))
    walk = Walk(Task("walk", site="stand_rack2"), TASK_KINDS["walk"], 2)
    record = walk.record(run, "stand_rack1", path)
    assert (record.task, record.start_site, record.goal_site) == (2, "stand_rack1", "stand_rack2")
    assert record.route == "stand_rack1->stand_rack2"  # no label: from -> to
    assert math.isclose(record.baseline_length, path.length)
    assert record.baseline_length >= float(np.linalg.norm(np.asarray(b) - np.asarray(a))) - 1e-9
    labelled = Walk(Task("walk", site="stand_rack2", route="T1"), TASK_KINDS["walk"], 2)
    assert labelled.record(run, "stand_rack1", path).route == "T1"


def test_a_walk_over_levels_is_measured_against_the_grid_routes_over_levels(scenes_dir):
    """A walk onto the platform (no grid route on the floor alone: the platform is an obstacle
    there) gets the grid routes over levels through its step (mjwalk.plan.levelgrid)."""
    from mjwalk.plan.walks import plan_walk

    ctx = context_of(scenes_dir / "multilevel_station.toml")
    path = plan_walk(ctx.workplace, "stand_rack1", "stand_platform2", ctx.step_model, rng=0)
    assert path.z is not None and ctx.baseline_route(path.xy[0], path.xy[-1]) is None
    rng = np.random.default_rng(0)
    run = CycleRun(ctx, None, 30.0, rng, rng, rng, np.zeros(3))
    walk = Walk(Task("walk", site="stand_platform2"), TASK_KINDS["walk"], 2)
    record = walk.record(run, "stand_rack1", path)
    assert record.baseline is not None and record.baseline.meta["levels"][-1] == "L3"
    assert record.baseline.xy[0] == pytest.approx(path.xy[0])
    chord = float(np.hypot(*(path.xy[-1] - path.xy[0])))
    assert chord <= record.baseline_length <= 1.0824 * (path.length + 0.05)  # the grid's excess
