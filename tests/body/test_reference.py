"""Reference gaits (mjwalk.body.legs.reference): the Winter table, the generated default and
the Bandai landmarks it is warped through."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.body.legs.reference import (
    BANDAI_LANDMARKS,
    WINTER_GAIT,
    bandai_reference,
    reference_angle,
    warp_reference,
    winter_reference,
    wrap01,
)


def test_reference_is_periodic_and_wraps_like_numpy():
    """The reference is a gait cycle: cycle fractions c and c + 1 give the same angle, and
    wrap01 is NumPy's floor-mod for negative, zero and whole values."""
    ref = bandai_reference()
    c = np.linspace(0, 1, 9)
    assert np.allclose(ref("knee", c), ref("knee", c + 1.0))
    for x in (-0.25, 0.0, 1.0, 2.75, -3.0):
        assert wrap01(x) == np.mod(x, 1.0)


def test_reference_gait_table():
    assert max(WINTER_GAIT["knee"]) == pytest.approx(63)  # peak swing flexion 60-65 deg
    # the default is the generated reference: through BANDAI_LANDMARKS' heel-strike figures
    assert np.rad2deg(reference_angle("hip", 0.0)) == pytest.approx(22)
    assert np.rad2deg(reference_angle("knee", 1.0)) == pytest.approx(1)
    assert np.rad2deg(winter_reference()("hip", 0.3)) == pytest.approx(10)


def test_warp_reference_meets_its_landmarks():
    """The generated (warped) reference passes through every landmark figure and stays a
    smooth periodic gait; bad landmark order is refused."""
    ref = bandai_reference()
    for name, pairs in BANDAI_LANDMARKS.items():
        for _, (c, deg) in pairs:
            assert np.rad2deg(ref(name, c / 100.0)) == pytest.approx(deg, abs=0.3), (name, c)
    x = np.linspace(0, 1, 401)
    assert np.abs(np.diff(np.rad2deg(ref("knee", x)))).max() < 2.0  # < 2 deg per 0.25 %
    with pytest.raises(ValueError, match="increase"):
        warp_reference({**BANDAI_LANDMARKS, "knee": BANDAI_LANDMARKS["knee"][::-1]})


def test_the_reference_heel_strike_ankle():
    """The default reference's own ankle at heel strike (pitch + knee - thigh at cycle 0,
    reference.heel_strike_ankle) is the bandai actor's +7.0 deg (28 deg pitch, 1 deg knee,
    22 deg thigh), the bound of a walk's first landing (steps.landing_pitches)."""
    from mjwalk.body.legs.reference import heel_strike_ankle

    assert np.rad2deg(heel_strike_ankle(bandai_reference())) == pytest.approx(7.0, abs=0.3)


def test_the_swing_foot_angle_is_the_shank_plus_a_plantarflexed_ankle():
    """The foot's angle to the floor is the shank's from the vertical (thigh minus knee
    flexion) plus the ankle's. Between toe-off (60 %) and mid-swing (75 %) the default
    reference's foot reaches -69 deg (the bandai actor's, BANDAI_LANDMARKS) with its ankle
    plantarflexed 14 deg at most: within Winter 1991's 15-20 deg plantarflexion at toe-off
    (5 deg tolerance), dorsiflexing towards neutral by mid-swing. The Winter table's own
    pitch row (-50 deg at 65 %, after Perry & Burnfield 2010) would, with the same hip and
    knee, leave the ankle dorsiflexed in early swing: it does not meet Winter's ankle, so the
    swing is not brought to -50 (benchmarks/bench_swing_pitch.py)."""
    c = np.linspace(0.60, 0.75, 61)
    ref = bandai_reference()
    pitch, knee, hip = (np.rad2deg(ref(n, c)) for n in ("pitch", "knee", "hip"))
    ankle = pitch + knee - hip
    assert pitch.min() == pytest.approx(-69.3, abs=0.5)
    assert -20.0 - 5.0 <= ankle.min() <= -15.0 + 5.0
    table_ankle = np.rad2deg(winter_reference()("pitch", c)) + knee - hip
    assert table_ankle.min() > -5.0 and table_ankle.max() > 5.0
