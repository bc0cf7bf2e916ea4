"""The planner's step check (mjwalk.plan.stepcheck.check_steps) on sampled steps."""

from __future__ import annotations

import numpy as np
import pytest
from test_lean import FRAME, M

from mjwalk.gait.default import default_model
from mjwalk.plan import stepcheck
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.lean import lean_in_range, stance_lean
from mjwalk.world import load_workplace


@pytest.mark.parametrize("foot_x", [0.1, -0.2])
def test_check_steps_refuses_the_steps_the_stance_leg_cannot_follow(scenes_dir, foot_x, request):
    """In the planner's step check (sampled steps, decoded by the planner's affine map) a step
    is refused exactly when its stance leg leans out of range, by the NumPy form on the
    model's own decoding; the stance foot is the node's landed foot (column 4: its heading).
    Without a heading (a start node) the check is skipped."""
    model = default_model()
    wp = load_workplace(scenes_dir / "open_floor.xml")
    pl = HybridPlanner(wp, "east", model)
    par, ipar = pl.params.vectors()
    dec = pl.decoder()
    rng = np.random.default_rng(2)
    z = model.sample_next_features(model.sample_first(1, rng, "right").features, "right", 300, rng)
    batch = model.decode(z, "left")  # swing left: the right foot stands
    local, yaw = batch.resample(M)
    stance = np.array([foot_x, 0.05, FRAME])  # the landed right foot, beside the start
    args = (dec.matrix, dec.offset, len(z), len(z), np.array([FRAME]), np.array([True]),
            np.zeros(1, bool))  # fmt: skip
    rest = (pl.params.thresholds, par, ipar, wp.walk_field().values, pl.distance.flat_bound())
    node = np.array([[0j, complex(stance[0], stance[1]), np.nan, 0.0, stance[2]]])
    rows = stepcheck.check_steps(z, *args, node, *rest)[0]
    node[0, 4] = np.nan
    free = stepcheck.check_steps(z, *args, node, *rest)[0]
    want = [
        r
        for r in free
        if lean_in_range(*stance_lean(local[r], FRAME + yaw[r], stance, False, par), par)
    ]
    np.testing.assert_array_equal(rows, want)
    if foot_x > 0:  # a foot under the hip: (measured) all but a few steps pass
        assert len(rows) > 0.9 * len(free)
    else:  # a foot crossed under the other: most are refused
        assert len(rows) < 0.5 * len(free)
