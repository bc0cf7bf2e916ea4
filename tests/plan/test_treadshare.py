"""Tests of mjwalk.plan.treadshare: how much of a walker's foot stands on a straight flight's
treads, and the flights a walker's foot refuses (issue 47 item 4: each foot on a tread, not
hanging over the nosing without limit). The flight is the multi-level station's (six 0.17 m
risers, 0.28 m treads), and copies of it with shallower treads."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from mjwalk.anthropometry import leg_geometry
from mjwalk.errors import PlanningError
from mjwalk.gait.walker import Walker
from mjwalk.plan import treadshare
from mjwalk.plan.levelcross import RISER_GAP, TREAD_RISER_GAP
from mjwalk.plan.levelplan import endpoint
from mjwalk.plan.levelroute import crossings, step_up_limit
from mjwalk.plan.levelsearch import level_route
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.treadshare import flight_notes, flight_refusal, tread_shares
from mjwalk.plan.windercross import TREAD_EDGE_GAP
from mjwalk.world import load_workplace
from mjwalk.world.norms import MIN_TREAD_SHARE


@pytest.fixture(scope="module")
def station(scenes_dir):
    return load_workplace(scenes_dir / "multilevel_station.xml")


@pytest.fixture(scope="module")
def stair(station):
    return next(c for c in crossings(station.levels, 0.33) if c.kind == "stair")


def _shallower(stair, tread: float):
    """The flight with ``tread`` m treads (its footfall track scaled about its first)."""
    track = stair.track[0] + (stair.track - stair.track[0]) * tread / stair.tread
    return replace(stair, track=track, tread=tread)


def _foot(stature: float) -> float:
    g = leg_geometry(stature)
    return g.foot_front + g.foot_back


@pytest.mark.parametrize("direction", ["up", "down"])
@pytest.mark.parametrize("stature", [1.55, 1.65, 1.75])
def test_a_foot_that_fits_stands_wholly_on_every_tread(stair, direction, stature):
    """Up to 1.78 m the foot is no longer than the 0.28 m tread less 2 x 5 mm: centred, all of
    it on every tread, and the walker takes the flight."""
    shares = tread_shares(stair, stature, direction)
    assert len(shares) == len(stair.risers) - 1  # one footfall per tread
    assert np.allclose(shares, 1.0)
    assert flight_refusal(stair, Walker(stature=stature)) is None


def test_a_long_foot_keeps_its_share_up_and_down_and_the_flight_is_taken(stair):
    """A 1.85 m walker's 0.281 m foot hangs over the nosing: going up its toes keep 5 mm off the
    riser ahead, so all but the 5 mm before the nosing behind stands on the tread (0.96 of the
    foot); going down its heel keeps 3 cm off the riser behind (0.87); both above the 0.6
    a foot keeps on a tread."""
    foot = _foot(1.85)
    up = tread_shares(stair, 1.85, "up")
    down = tread_shares(stair, 1.85, "down")
    assert np.allclose(up, (stair.tread - TREAD_RISER_GAP - TREAD_EDGE_GAP) / foot)
    assert np.allclose(down, (stair.tread - RISER_GAP - TREAD_EDGE_GAP) / foot)
    assert MIN_TREAD_SHARE < float(down.min()) < float(up.min()) < 1.0
    assert flight_refusal(stair, Walker(stature=1.85)) is None


@pytest.mark.parametrize(
    ("tread", "direction", "shorter"), [(0.19, "down", 1.55), (0.17, "up", 1.45)]
)
def test_a_flight_whose_treads_hold_too_little_of_the_foot_is_refused(
    stair, tread, direction, shorter
):
    """On 0.19 m treads a 1.85 m walker keeps 0.64 of its foot going up but 0.55 going down;
    on 0.17 m treads 0.57 going up: refused, the direction and the share named, one line; a
    shorter walker (1.55 m, 1.45 m) keeps enough of its foot on the same treads."""
    flight = _shallower(stair, tread)
    walker = Walker(stature=1.85)
    shares = tread_shares(flight, 1.85, direction)
    assert float(shares.min()) < MIN_TREAD_SHARE
    why = flight_refusal(flight, walker)
    assert why is not None and "\n" not in why
    assert f"its {tread:.3f} m treads hold" in why and f"going {direction}" in why
    assert f"{100 * float(shares.min()):.0f} % of a 0.281 m foot (stature 1.85 m)" in why
    (note,) = flight_notes([flight], walker)
    assert note.startswith(f"the stair from L{flight.lower} to L{flight.upper} is not taken")
    # a shorter walker's foot keeps enough of itself on the same treads
    assert flight_refusal(flight, Walker(stature=shorter)) is None


def test_ramps_and_single_steps_have_no_treads(station):
    for c in crossings(station.levels, 0.33):
        if c.kind == "ramp" or len(c.track) < 3:
            assert len(tread_shares(c, 1.85, "up")) == 0
            assert flight_refusal(c, Walker(stature=2.2)) is None


def test_the_route_refuses_a_flight_the_foot_does_not_keep(station, monkeypatch):
    """The route over levels leaves a refused flight out and names it: with a share above the
    1.85 m walker's 0.87 going down (0.9: the rule's machinery, not its figure), the mezzanine,
    reached by the stair alone, has no route."""
    tall = Walker(stature=1.85)
    a = endpoint(station, "stand_rack1", "start")
    b = endpoint(station, "stand_mezz_rack", "goal")
    options = PlannerOptions()
    assert level_route(station, a, b, tall, options, step_up_limit(tall))
    monkeypatch.setattr(treadshare, "MIN_TREAD_SHARE", 0.9)
    with pytest.raises(PlanningError) as err:
        level_route(station, a, b, Walker(stature=1.86), options, step_up_limit(tall))
    msg = str(err.value)
    assert "the stair from L" in msg and "is not taken: its 0.280 m treads hold" in msg
    assert "going down, less than the 90 %" in msg and "\n" not in msg
