"""Walk-independent pieces of a walk over levels kept on their owner (mjwalk.plan.levelmemo)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from mjwalk.gait.walker import Walker
from mjwalk.plan import levelcross
from mjwalk.plan.levelmemo import MAX_KEPT, default_options, kept, variant
from mjwalk.plan.levelroute import crossings
from mjwalk.plan.options import PlannerOptions
from mjwalk.world import load_workplace


class Owner:
    """Anything with an instance dictionary."""


def test_kept_makes_a_value_once_per_key_and_makes_its_arrays_read_only():
    owner, made = Owner(), []

    def make():
        made.append(1)
        return np.arange(3.0), 2.0

    first = kept(owner, "_x", ("up", 1.5), make)
    assert kept(owner, "_x", ("up", 1.5), make) is first and len(made) == 1
    kept(owner, "_x", ("down", 1.5), make)
    assert len(made) == 2
    with pytest.raises(ValueError):
        first[0][0] = 1.0  # read-only: no caller can change it for the next
    for k in range(MAX_KEPT + 10):  # bounded: the oldest go first
        kept(owner, "_y", k, lambda: 0)
    assert len(owner.__dict__["_y"]) == MAX_KEPT and 0 not in owner.__dict__["_y"]
    assert kept(Owner, "_z", 1, lambda: 5) == 5  # a class keeps nothing
    assert "_z" not in vars(Owner)


def test_variant_is_replace_made_once_and_tells_the_sign_of_zero_apart():
    options = PlannerOptions()
    a = variant(options, max_expansions=400)
    assert a == replace(options, max_expansions=400)
    assert variant(options, max_expansions=400) is a
    assert variant(PlannerOptions(), max_expansions=400) is not a  # per options object
    plus, minus = variant(options, goal_yaw=0.0), variant(options, goal_yaw=-0.0)
    assert plus is not minus and np.copysign(1.0, minus.goal_yaw) == -1.0
    assert default_options() is default_options() and default_options() == PlannerOptions()


@pytest.fixture(scope="module")
def station(scenes_dir):
    return load_workplace(scenes_dir / "multilevel_station.xml")


def test_kept_crossing_pieces_equal_the_computed_ones(station):
    """A crossing's footfalls, its first footfall, its departure and a clear line are each
    the value the computation gives (the same arrays, bit for bit), kept on their owner."""
    walker = Walker(stature=1.62)
    for c in crossings(station.levels, 0.33):
        for direction in ("up", "down"):
            s, t = levelcross._footfalls(c, direction, walker)
            s0, t0 = levelcross._steps(c, direction, walker)
            assert np.array_equal(s, s0) and np.array_equal(t, t0) and not s.flags.writeable
            first = levelcross.flight_start(c, direction, walker)
            assert levelcross.flight_start(c, direction, walker) is first
            walked = levelcross.departure(c, direction, 0.6)
            assert levelcross.departure(c, direction, 0.6) is walked
            assert walked.end(c.upper if direction == "up" else c.lower) is not None
    rng = np.random.default_rng(3)
    for _ in range(20):
        a, b = rng.uniform(-4.0, 4.0, (2, 2))
        assert levelcross.line_clear(station, a, b, 0.3) == levelcross._line_clear(
            station, a, b, 0.3
        )
