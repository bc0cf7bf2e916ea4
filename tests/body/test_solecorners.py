"""The swing sole's corners over slanted step edges (mjwalk.body.legs.solecorners, issue 47:
winder stairs)."""

import dataclasses

import numpy as np
import pytest

from mjwalk.anthropometry import leg_geometry
from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.footcheck import box_corners, posed
from mjwalk.body.legs.solecorners import (
    corner_lift,
    corner_need,
    corner_shortfall,
    rising_risers,
    sole_outline,
)
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.gait.walker import Walker
from mjwalk.plan.windercross import winder_crossings, winder_walk
from mjwalk.world import load_workplace

G = leg_geometry(DEFAULT_STATURE)


def test_the_outline_is_the_sole_at_both_sides():
    """A level foot heading +y: heel and toe tip at the foot's back and front, half its width
    left and right (left is -x for a foot heading +y), on the sole (one ankle height down);
    the toe block's top front 0.4 ankle heights over the toe tip."""
    one = np.zeros(1)
    xy, z = sole_outline(one, one, np.full(1, np.pi / 2), G)
    half = 0.5 * G.foot_width
    assert xy[0, 0, 0] == pytest.approx([-half, -G.foot_back])
    assert xy[0, 1, 2] == pytest.approx([half, G.foot_front])
    assert z[0, :, :3] == pytest.approx(np.full((2, 3), -G.ankle_height))
    assert z[0, 0, 3] - z[0, 0, 2] == pytest.approx(0.4 * G.ankle_height)
    xy0, _ = sole_outline(one, one, one, G, 0.0)
    assert np.allclose(xy0[0, 0], xy0[0, 1])  # no width: the centre line


def test_the_risers_a_step_goes_up_over():
    """A chord along +x over two risers going up finds both, each with its normal; a step
    down, a riser of other heights and one far beside the chord are not taken."""
    risers = ((0.2, 0.0, 1.0, 0.0, 0.0, 0.17, 0.5), (0.5, 0.05, 0.9, 0.1, 0.17, 0.34, 0.5))
    lines = rising_risers((0.0, 0.0), (0.7, 0.0), [0.0, 0.17, 0.34], risers)
    assert [top for _, _, top in lines] == pytest.approx([0.17, 0.34])
    assert np.hypot(*lines[1][1]) == pytest.approx(1.0)
    assert rising_risers((0.0, 0.0), (0.7, 0.0), [0.34, 0.17, 0.0], risers) == []
    assert rising_risers((0.0, 0.0), (0.7, 0.0), [0.0, 0.19], risers) == []
    far = ((0.2, 3.0, 1.0, 0.0, 0.0, 0.17, 0.5),)
    assert rising_risers((0.0, 0.0), (0.7, 0.0), [0.0, 0.17], far) == []


def _turned_swing(angle_deg: float):
    """A level foot heading +x, ankle 5 cm over a 0.17 m riser's top, toe tip 2 cm behind
    the riser's line where it crosses the foot's centre line, that line turned by the angle."""
    a = np.radians(angle_deg)
    n = np.array([np.cos(a), np.sin(a)])
    m = 5
    ankle = np.column_stack([np.zeros(m), np.zeros(m), np.full(m, 0.17 + G.ankle_height + 0.005)])
    q = np.array([G.foot_front + 0.02, 0.0])
    zero = np.zeros(m)
    return ankle, (zero, zero, zero, G), [(q, n, 0.17)]


def test_a_foot_along_the_risers_normal_needs_nothing_more_than_its_centre_line():
    """A straight flight's foot (its heading the riser's normal) is short of nothing its centre
    line is not: no shortfall, and corner_lift leaves its heights exactly as they were."""
    ankle, foot, lines = _turned_swing(0.0)
    assert not corner_shortfall(ankle, foot, lines, (0.002, 0.03)).any()
    assert np.array_equal(corner_lift(ankle, foot, lines, (0.002, 0.03), 0.45), ankle[:, 2])


@pytest.mark.parametrize("angle", [30.0, 35.0, -35.0])
def test_a_foot_turned_against_a_nosing_is_raised_by_its_corner(angle):
    """Turned 30-35 deg against the riser, the foot's leading toe corner lies past the riser's
    line (its centre line 2 cm behind it): it is raised until the sole's side crossing the
    line clears the nosing by the clearance and every point past the line is over the tread
    by the margin; the grounded ends stay."""
    ankle, foot, lines = _turned_swing(angle)
    short = corner_shortfall(ankle, foot, lines, (0.002, 0.03))
    assert short[0] == 0.0 and short[-1] == 0.0 and (short[1:-1] > 0.0).all()
    z = corner_lift(ankle, foot, lines, (0.002, 0.03), 0.45)
    raised = np.column_stack([ankle[:, :2], z])
    need = corner_need(raised[:, :2], sole_outline(*foot), lines, 0.002, 0.03)
    assert (z[1:-1] >= need[1:-1] - 1e-9).all()
    assert z[0] == ankle[0, 2] and z[-1] == ankle[-1, 2]


@pytest.fixture(scope="module")
def winder(tmp_path_factory, winder_xml):
    """The conforming quarter-turn winder and its workplace (floor at 0)."""
    path = tmp_path_factory.mktemp("balanced") / "balanced.xml"
    path.write_text(winder_xml("balanced"))
    wp = load_workplace(path)
    (c,) = winder_crossings(wp.levels, 0.3)
    return wp, dataclasses.replace(c, clear=0.16)


@pytest.mark.parametrize("stature", [1.55, 1.65, DEFAULT_STATURE])
def test_every_sole_corner_clears_the_winders_risers_going_up(winder, stature):
    """Up the conforming winder (one footfall per tread, the foot along the walk line, its
    nosings slanted up to ~35 deg against it; the walk from its first footfall's stance, as
    winder47b's demo), no corner of either foot's sole or toe boxes (MuJoCo forward
    kinematics) lies past a nosing's line, within its length, below its top by more than
    0.1 mm (the grounded soles rest on it: 0.02 mm). Before (21d832d), with the clearance
    measured along the foot's centre line: the right toe box 9.3 cm (1.65 m) and 9.2 cm
    (1.75 m) below the top of tread 4 past its nosing (MuJoCo: 2.2 / 2.8 mm into its riser);
    1.55 m clean."""
    wp, c = winder
    walk = winder_walk(c, "up", Walker(stature=stature), wp.floor_z)
    legs = legs_from_walk(walk, stature)
    worst = np.inf
    for _, model, data in posed(legs, stature):
        for name in ("foot_l", "foot_r", "toes_l", "toes_r"):
            pts = box_corners(model, data, model.geom(name).id)
            for e in walk.meta["edges"]:
                q, n = np.array(e["xy"]), np.array(e["normal"])
                rel = pts[:, :2] - q
                past = (rel @ n > 0) & (np.abs(rel @ np.array([-n[1], n[0]])) <= e["half_width"])
                if past.any():
                    worst = min(worst, float((pts[past, 2] - wp.floor_z - e["high"]).min()))
    assert worst >= -1e-4
