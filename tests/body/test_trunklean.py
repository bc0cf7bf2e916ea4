"""The trunk leaned forward in stair ascent (mjwalk.body.legs.trunklean, issue 47)."""

import numpy as np
import pytest

from mjwalk.body.legs import legs_from_walk, synthesis
from mjwalk.body.legs.pelvistilt import STAIR_ASCENT_PELVIC_TILT, ascent_share, ascent_tilt
from mjwalk.body.legs.trunklean import (
    LUMBAR_LEAN_SHARE,
    STAIR_ASCENT_TRUNK_LEAN,
    ascent_lean,
    lean_spine,
)
from mjwalk.plan.synthetic import synthetic_stair_walk


def test_the_cited_lean_and_its_split():
    """12.4 deg: the controls' mean anterior trunk tilt ascending a 17 cm stair (13.7 deg) less
    level walking's (1.3 deg); the lumbar joint takes 60/105 of it (the flexion ranges)."""
    assert np.degrees(STAIR_ASCENT_TRUNK_LEAN) == pytest.approx(12.4)
    assert LUMBAR_LEAN_SHARE == pytest.approx(60.0 / 105.0)


def test_ascent_lean_over_a_flight_up():
    """Up a six-riser flight: no lean before the first step, the full lean from the end of the
    first step to the end of the last riser's step, eased out over the step onto the landing,
    timed as the pelvic tilt (the same share of each held figure at every sample)."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    n = len(walk.t)
    lean = ascent_lean(walk, n)
    first, last, off = walk.steps[0], walk.steps[-2], walk.steps[-1]
    assert lean[first.start] == 0.0
    assert np.allclose(lean[first.end : last.end + 1], STAIR_ASCENT_TRUNK_LEAN)
    assert np.all(np.diff(lean[off.start : off.end + 1]) <= 0)
    assert np.abs(lean[off.end :]).max() == 0.0
    share = ascent_share(walk, n)
    assert share.min() >= 0.0 and share.max() == pytest.approx(1.0)
    np.testing.assert_allclose(lean, STAIR_ASCENT_TRUNK_LEAN * share, rtol=0, atol=1e-15)
    np.testing.assert_allclose(ascent_tilt(walk, n), STAIR_ASCENT_PELVIC_TILT * share, atol=0)


def test_no_lean_off_a_stair_ascent(off_ascent_walk):
    """Down a stair (no figure cited), on the floor and up a ramp the trunk keeps its pose:
    no lean, and the legs carry none."""
    assert not ascent_lean(off_ascent_walk, len(off_ascent_walk.t)).any()
    assert "trunk_lean" not in legs_from_walk(off_ascent_walk).meta


def test_lean_spine_adds_the_lean_to_the_two_joints():
    """The two flexions grow by the lumbar share and the rest, together by the lean."""
    rng = np.random.default_rng(47)
    lumbar, thoracic, lean = (rng.uniform(-0.3, 0.3, 50) for _ in range(3))
    lu, th = lean_spine(lumbar, thoracic, lean)
    np.testing.assert_allclose(lu - lumbar, LUMBAR_LEAN_SHARE * lean, atol=1e-15)
    np.testing.assert_allclose((lu - lumbar) + (th - thoracic), lean, atol=1e-15)


def test_the_lean_leaves_the_legs_alone(monkeypatch):
    """The lean is the spine's: up the stair the legs' root and every joint angle are those of
    the synthesis without it (the pelvis keeps its posterior tilt, the hips their flexion to
    it: the ascent hip peak does not change)."""
    walk = synthetic_stair_walk(0.17, 0.28, 6, "up")
    leaning = legs_from_walk(walk)
    assert "trunk_lean" in leaning.meta
    monkeypatch.setattr(synthesis, "ascent_lean", lambda w, n: np.zeros(n))
    upright = legs_from_walk(walk)
    assert "trunk_lean" not in upright.meta
    assert np.array_equal(leaning.root, upright.root)
    assert leaning.angles.keys() == upright.angles.keys()
    for name, v in leaning.angles.items():
        assert np.array_equal(v, upright.angles[name]), name
    assert np.array_equal(leaning.meta["pelvis_tilt"], upright.meta["pelvis_tilt"])
