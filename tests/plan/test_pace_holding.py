"""The planner's energy cost: walks hold the walker's pace as people do (hybrid module doc)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.gait.default import default_model
from mjwalk.gait.walker import Walker
from mjwalk.plan.hybrid import HybridPlanner, preferred_speed
from mjwalk.plan.options import WALK_PACE_SD, PlannerOptions
from mjwalk.world import load_workplace


@pytest.fixture(scope="module")
def hall(tmp_path_factory):
    path = tmp_path_factory.mktemp("hall") / "hall.xml"
    path.write_text(
        '<mujoco model="hall"><worldbody>'
        '<geom name="floor" type="plane" size="8 3 0.05"/>'
        "</worldbody></mujoco>"
    )
    return load_workplace(path, cache=False)


def _steady_speeds(walk, x0: float, lo: float, hi: float) -> np.ndarray:
    """Log speeds (m/s) of a walk's steps that start beyond ``lo`` and end before ``hi``
    metres along +x from ``x0``."""
    ends = np.array([walk.xy[s.end, 0] - x0 for s in walk.steps])
    t = np.array([walk.t[s.end] for s in walk.steps])
    starts = np.concatenate([[0.0], ends[:-1]])
    t0 = np.concatenate([[0.0], t[:-1]])
    keep = (starts >= lo) & (ends <= hi)
    return np.log((ends - starts)[keep] / (t - t0)[keep])


def test_planned_straight_walks_hold_the_walkers_pace(hall):
    """40 seeded 11.5 m walks of a 1.2 m/s, 110 steps/min walker, steps between 2.5 and 10 m
    (steady walking). Captured straight walks of the four Bandai styles (91, steady steps):
    SD of log step speed within a walk 0.039-0.048 and of a walk's mean 0.034-0.087. Asserted:
    median speed within 5 % of the walker's; within-walk SD <= 0.06 (chord cost: 0.105); the
    walks' means spread as WALK_PACE_SD says, SD within 0.02-0.07. Measured: 1.197 m/s, 0.033,
    0.035 (chord cost: 1.194 m/s, 0.109, 0.139)."""
    walker = Walker(speed=1.2, cadence=110.0)
    model = default_model(progress=False).for_walker(walker)
    assert preferred_speed(model) == 1.2
    x0 = -7.0
    planner = HybridPlanner(hall, (x0 + 11.5, 0.0), model)
    rng = np.random.default_rng(0)
    walks = [_steady_speeds(planner.plan(f"{x0},0,0", rng), x0, 2.5, 10.0) for _ in range(40)]
    every = np.concatenate(walks)
    assert math.exp(np.median(every)) == pytest.approx(1.2, rel=0.05)
    within = np.mean([w.std() for w in walks])
    assert within <= 0.06, within
    means = np.std([w.mean() for w in walks])
    assert 0.02 <= means <= 0.07, (means, WALK_PACE_SD)


def test_validate_reports_planned_straight_walks(tmp_path):
    """The fidelity report (``mjwalk validate``) times the captured straight walks as the
    planner walks them too, beside the greedy walks: per walk ``planned`` plans, their median
    and IQR, and how many could not be planned. (The corpus's 3-4 m bouts start and end at
    rest, and a planned walk is timed as it walks through: the model's median is some 20 %
    shorter than the bouts'; the Bandai walks, cut mid-walk, are compared in
    ``benchmarks/bench_variability.py``.)"""
    from mjwalk.gait.corpus import generate_corpus
    from mjwalk.gait.fidelity import fidelity_from_steps
    from mjwalk.gait.segment import segment_takes
    from mjwalk.gait.straight import captured_straight_walks

    steps, _ = segment_takes(generate_corpus(1, seed=3))
    model = default_model(progress=False)
    from mjwalk.plan.walktimes import planned_straight_walks

    rng = np.random.default_rng(0)
    rep = fidelity_from_steps(
        model, steps, rng, n_chains=40, planned=2, planned_walks=planned_straight_walks
    )
    p = rep["straight_walks"]["planned"]
    n = len(captured_straight_walks(steps))
    assert n > 0 and p["per_walk"] == 2
    assert p["time"]["model"]["n"] + p["failed"] == 2 * n and p["failed"] <= 2 * n // 10
    dist = rep["straight_walks"]["distance"]["capture"]["median"]
    speed = model.pace().speed
    assert 0.6 < speed * p["time"]["model"]["median"] / dist < 1.4


def test_cost_options(hall):
    """An unknown cost is refused by name; the paper's chord cost and the arc still plan; a
    model not conditioned on a walker holds its own steady pace."""
    from mjwalk.errors import InputError

    model = default_model(progress=False)
    assert preferred_speed(model) == pytest.approx(model.pace().speed)
    with pytest.raises(InputError, match="cost must be 'chord', 'path' or 'energy'"):
        PlannerOptions(cost="time")
    for cost in ("chord", "path", "energy"):
        walk = HybridPlanner(hall, (3.0, 0.0), model, PlannerOptions(cost=cost)).plan(
            "-3,0,0", np.random.default_rng(0)
        )
        assert np.hypot(walk.xy[-1, 0] - 3.0, walk.xy[-1, 1]) <= 0.25 + 1e-9
