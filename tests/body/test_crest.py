"""The ground under a swing foot between a ramp and a level (mjwalk.body.legs.crest)."""

import numpy as np
import pytest

from mjwalk.anthropometry import leg_geometry
from mjwalk.body.legs.crest import CREST_CLEARANCE, crest_ground
from mjwalk.body.legs.edgeswing import StepSurfaces
from mjwalk.body.legs.footpivot import sole_profile
from mjwalk.body.legs.steps import StepFrames
from mjwalk.conventions import DEFAULT_STATURE


def test_crest_checked_between_heel_and_toe():
    """A foot pitched toes down with its heel over a platform and its toe over the ramp below
    its top edge: the ground offset keeps the sole above the edge between them, by
    CREST_CLEARANCE (a swing between a ramp and a level)."""
    g = leg_geometry(DEFAULT_STATURE)
    t = np.tan(np.deg2rad(5.5))
    fr = StepFrames("l", "r", 0, 10, np.array([-0.5, 0.0, 0.0]), np.array([0.6, 0.0, 0.0]),
                    np.zeros(3), False, False)  # fmt: skip
    sf = StepSurfaces(lift=0.34, stance=0.34, land=0.34 - 0.6 * t, land_pitch=-np.deg2rad(5.5))
    ankle = np.array([[-0.05, 0.0, 0.0]])  # the edge at x = 0, between heel and toe
    half = np.tan(np.deg2rad(2.75))  # halfway through its pitch toward the ramp's
    z = crest_ground(ankle, np.zeros(1), fr, sf, g, np.array([-np.deg2rad(2.75)]))
    # the sole's height at the edge (0.05 m ahead of the ankle) is z - 0.05 tan(2.75 deg):
    # on the edge, not 0.7 mm into it (heel, ankle and toe only), plus the clearance
    assert z[0] - 0.05 * half == pytest.approx(0.34 + CREST_CLEARANCE)
    level = StepSurfaces(lift=0.34, stance=0.34, land=0.34)
    assert crest_ground(ankle, np.zeros(1), fr, level, g)[0] == pytest.approx(0.34)


def test_a_toe_tip_rolling_back_off_a_deck_s_edge_keeps_above_it():
    """A ramp's last footfall (9.8 deg, its head at x = 0 meeting a 0.45 m deck) lifts off its
    toe tip standing past the head; the flat swing holds the tip on the floor while the foot
    rolls toes down and the ankle moves on, so the tip slides back over the edge. The ground
    offset for the sole the flat swing holds (``foot``) keeps the tip CREST_CLEARANCE over
    the ground under it everywhere; the flat foot's points (before) let it pass the edge below
    the deck's top (generated hall 526's stress cycle, run 1: the toes 0.24 mm into it)."""
    g = leg_geometry(DEFAULT_STATURE)
    slope, deck = np.deg2rad(9.8), 0.45
    fr = StepFrames("r", "l", 0, 10, np.array([-0.2, 0.0, 0.0]), np.array([0.4, 0.0, 0.0]),
                    np.zeros(3), False, False)  # fmt: skip
    sf = StepSurfaces(lift=deck - 0.2 * np.tan(slope), stance=deck, land=deck, lift_pitch=slope)
    n = 40
    pitch0 = np.linspace(-0.6, -1.1, n)  # the flat swing's foot rolling toes down
    toe = np.linspace(0.6, 0.2, n)
    added = np.full(n, 0.8 * slope)  # most of the lift's slope still added
    fwd, up = sole_profile(pitch0 + added, toe, g)
    ankle = np.zeros((n, 3))
    ankle[:, 0] = 0.01 - fwd[:, 3] + np.linspace(0.0, -0.03, n)  # the tip from past the edge back
    flat_z = -sole_profile(pitch0, toe, g)[1][:, 3]  # the flat tip on the floor
    yaw = np.zeros(n)

    def tip_gap(offset):
        tip_x = ankle[:, 0] + fwd[:, 3]
        ground = np.minimum(deck + np.tan(slope) * tip_x, deck)
        return flat_z + offset + up[:, 3] - ground

    held = crest_ground(ankle, yaw, fr, sf, g, added, (pitch0, toe))
    assert tip_gap(held).min() >= CREST_CLEARANCE - 1e-12
    assert tip_gap(crest_ground(ankle, yaw, fr, sf, g, added)).min() < 0.0  # before
