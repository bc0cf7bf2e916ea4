"""The grip synergy and the thumb-index aperture of the humanoid hand (mjwalk.arms.hands)."""

import numpy as np
import pytest

from mjwalk.arms.hands import (
    finger_trajectory,
    fingers_for_aperture,
    grip_synergy,
    pinch_aperture,
)
from mjwalk.errors import MjwalkError


def test_grip_synergy_opens_the_thumb_and_flexes_the_fingers():
    open_, closed = grip_synergy(0.0), grip_synergy(1.0, "right")
    assert open_["thumb_l_cmc"] == pytest.approx(1.1) and open_["index_l_mcp"] == 0.0
    assert closed["thumb_r_cmc"] == 0.0 and closed["little_r_pip"] == pytest.approx(1.0)
    assert closed["ring_r_dip"] == pytest.approx(0.7)
    assert grip_synergy(2.0) == grip_synergy(1.0)  # closure clipped to [0, 1]


def test_aperture_closes_with_the_grip_and_is_found_again():
    wide = pinch_aperture(grip_synergy(0.0))
    narrow = pinch_aperture(grip_synergy(1.0))
    assert 0.0 <= narrow < wide < 0.3  # metres
    target = 0.5 * (wide + narrow)
    assert pinch_aperture(fingers_for_aperture(target)) == pytest.approx(target, abs=1e-4)
    with pytest.raises(MjwalkError, match="outside the hand's range"):
        fingers_for_aperture(wide + 0.05)
    traj = finger_trajectory(np.array([narrow, target, wide + 0.1]))
    assert traj["index_l_mcp"].shape == (3,)
    assert traj["index_l_mcp"][0] > traj["index_l_mcp"][1] > traj["index_l_mcp"][2]


def test_apertures_asked_from_several_threads_at_once_are_the_serial_ones():
    """Each thread has its own MjData for the forward kinematics (threads may ask at once)."""
    from concurrent.futures import ThreadPoolExecutor

    closures = np.linspace(0.0, 1.0, 40)
    statures = [1.55, 1.75, 1.95]
    jobs = [(g, s) for s in statures for g in closures]
    serial = [pinch_aperture(grip_synergy(g), stature=s) for g, s in jobs]
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(lambda a: pinch_aperture(grip_synergy(a[0]), stature=a[1]), jobs))
    assert threaded == serial
