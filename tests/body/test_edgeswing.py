"""The swing foot over step edges (mjwalk.body.legs.edgeswing, issue 47 deliverable 4)."""

import pytest

from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.edgeswing import STAIR_TOE_CLEARANCE, StepSurfaces
from mjwalk.plan.synthetic import synthetic_stair_walk


def test_edged_and_pelvis_level():
    up = StepSurfaces(0.0, 0.17, 0.34)
    assert up.edged and up.pelvis_level() == (0.0, 0.17)
    down = StepSurfaces(0.34, 0.17, 0.0)
    assert down.edged and down.pelvis_level() == (0.17, 0.0)
    assert not StepSurfaces(0.1, 0.1, 0.1).edged
    assert not StepSurfaces(0.0, 0.02, 0.04, land_pitch=0.05).edged  # a ramp has no edge


@pytest.mark.parametrize("direction", ["up", "down"])
def test_swing_clears_every_nosing(direction):
    """Up and down a 0.17/0.28 stair the sole clears every nosing by the cited 3 cm, and the
    ankle never goes more than 0.2 m above the higher of the swing's two treads."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, direction)
    motion = legs_from_walk(walk)
    assert motion.meta["edge_clearance"] >= STAIR_TOE_CLEARANCE - 1e-3
    for k, st in enumerate(walk.steps[1:-1], start=1):
        top = max(walk.steps[k - 1].stance_z, st.foot_z)
        assert motion.ankle[st.side][st.start : st.end, 2].max() - top < 0.2
