"""Low tops as the legs' steps take them (mjwalk.body.legs.lowtreads)."""

from dataclasses import replace
from types import SimpleNamespace

from mjwalk.body.legs.edgeswing import StepSurfaces
from mjwalk.body.legs.lowtreads import low_treads


def test_low_treads_marks_a_low_top_a_plane_only_in_level_steps():
    """A footprint on a low top's height is a plane in a level step and a tread in a riser
    step; one at another height, or pitched, is left as it was."""
    steps = [SimpleNamespace(stance=(0.0, 0.0, 0.0), foot=(0.3, 0.0, 0.0)) for _ in range(2)]
    walk = SimpleNamespace(steps=steps)
    sf = StepSurfaces(lift=0.015, stance=0.015, land=0.17, lift_ramp=True, stance_ramp=True)
    low = lambda p: (0.015, 0.0) if p[0] < 0.1 else None  # noqa: E731
    a, b = low_treads(walk, [sf, sf], [True, False], low)
    assert a == sf
    assert (b.lift_ramp, b.stance_ramp, b.land_ramp) == (False, False, False) and b.edged
    pitched = replace(sf, stance_pitch=0.05)
    assert low_treads(SimpleNamespace(steps=steps[:1]), [pitched], [False], low)[0].stance_ramp
