"""plan_walk and plan_walks (mjwalk.plan.walks): seeded walks, their arguments checked."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import InputError
from mjwalk.gait.default import default_model
from mjwalk.plan.walks import plan_walk, plan_walks
from mjwalk.world import load_workplace


@pytest.fixture(scope="module")
def model():
    return default_model(progress=False)


def test_same_seed_same_walks(model, scenes_dir):
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    a = plan_walks(wp, "stand_rack2", "stand_car1", model, n=3, seed=11)
    b = plan_walks(wp, "stand_rack2", "stand_car1", model, n=3, seed=11)
    for p, q in zip(a, b, strict=True):
        np.testing.assert_array_equal(p.xy, q.xy)
    single = plan_walk(wp, "stand_rack2", "stand_car1", model, rng=5)
    again = plan_walk(wp, "stand_rack2", "stand_car1", model, rng=5)
    np.testing.assert_array_equal(single.xy, again.xy)


@pytest.mark.parametrize("n", [-1, 1.5, True])
def test_plan_walks_refuses_a_bad_count(n, scenes_dir):
    wp = load_workplace(scenes_dir / "open_floor.xml")
    with pytest.raises(InputError, match="whole number of walks"):
        plan_walks(wp, "west", "east", object(), n=n)
