"""Tests of mjwalk.plan.windercross: a winder that meets DIN 18065 on its walk line walked tread
by tread along it (issue 47). The scenes are ``tests/conftest.py``'s quarter-turn winders."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mjwalk.errors import PlanningError
from mjwalk.gait.stairs import StairGeometry, stair_gait
from mjwalk.gait.walker import Walker
from mjwalk.plan import windercross
from mjwalk.plan.levelcross import RISER_GAP
from mjwalk.plan.occupancy import CELL_SIZE
from mjwalk.plan.options import PlannerOptions
from mjwalk.plan.turnsplit import WALKING_TURN_MAX
from mjwalk.plan.windercross import (
    TREAD_EDGE_GAP,
    held_corners,
    sole_corners,
    tread_foot,
    winder_crossings,
    winder_footfalls,
    winder_time,
    winder_walk,
)
from mjwalk.world import load_workplace

CLEAR = PlannerOptions().radius + CELL_SIZE


def _workplace(tmp_path_factory, winder_xml, kind: str):
    path = tmp_path_factory.mktemp(kind) / f"{kind}.xml"
    path.write_text(winder_xml(kind))
    return load_workplace(path)


@pytest.fixture(scope="module")
def balanced(tmp_path_factory, winder_xml):
    """The conforming quarter-turn winder: seven treads (five turned) between floor and deck."""
    return _workplace(tmp_path_factory, winder_xml, "balanced")


@pytest.fixture(scope="module")
def winder(balanced):
    (c,) = winder_crossings(balanced.levels, CLEAR)
    return c


def test_the_conforming_winder_is_a_crossing_of_its_seven_treads(balanced, winder):
    names = [t.name for t in winder.treads]
    assert names == [f"tread{i}" for i in range(1, 8)]
    assert (winder.lower, winder.upper) == (0, balanced.levels.level_of[-1] or winder.upper)
    assert len(winder.nosings) == 8 and len(winder.risers) == 8
    assert np.allclose(winder.risers, 0.17, atol=1e-6)
    # the stances a body clearance off the first and last nosing, on the walk line
    assert np.allclose(winder.end(winder.lower), [-0.5861 - CLEAR, -0.5], atol=1e-3)
    assert np.allclose(winder.end(winder.upper), [0.5, 0.5861 + CLEAR], atol=1e-3)


def test_a_winder_breaking_the_step_rule_is_no_crossing(tmp_path_factory, winder_xml):
    """The three-wedge winder (0.38-0.43 m on its walk line) stays refused: no crossing."""
    wedges = _workplace(tmp_path_factory, winder_xml, "wedges")
    assert winder_crossings(wedges.levels, CLEAR) == []


def _inside_nosings(winder, i: int, pts: np.ndarray) -> np.ndarray:
    """How far (m) points lie on tread ``i`` beyond its lower nosing and before its upper one
    (the smaller of the two; negative: over a nosing), from the nosing lines alone."""
    out = []
    for k, sign in ((i, 1.0), (i + 1, -1.0)):
        a, b = winder.nosings[k]
        d = (b - a) / np.linalg.norm(b - a)
        n = sign * winder.normal(k)
        assert abs(float(n @ d)) < 1e-9
        out.append((pts - a) @ n)
    return np.minimum(*out)


@pytest.mark.parametrize("direction", ["up", "down"])
@pytest.mark.parametrize("stature", [1.55, 1.65, 1.75])
def test_every_tread_footfall_stands_wholly_on_its_tread(balanced, winder, direction, stature):
    """One footfall per tread, in order; each sole's corners at least the edge gap inside the
    tread's outline and behind both its nosings (tested against the nosing lines too)."""
    f = winder_footfalls(winder, direction, Walker(stature=stature))
    on = f.tread[f.tread >= 0]
    want = np.arange(7) if direction == "up" else np.arange(7)[::-1]
    assert np.array_equal(on, want)
    for centre, yaw, i in zip(f.centre, f.yaw, f.tread, strict=True):
        if i < 0:
            continue
        corners = sole_corners(centre, float(yaw), stature)
        surface = balanced.levels.surfaces[
            balanced.levels.levels[winder.treads[i].level].surfaces[0]
        ]
        assert np.all(surface.footprint.signed_distance(corners) <= -TREAD_EDGE_GAP + 1e-9)
        assert np.all(_inside_nosings(winder, i, corners) >= TREAD_EDGE_GAP - 1e-9)
        # the foot's centre within the walk zone: 0.1 of the mean nosing length off the line
        t = winder.treads[i]
        s, e = np.array(t.start), np.array(t.end)
        h = (e - s) / np.linalg.norm(e - s)
        off = abs(float((centre - 0.5 * (s + e)) @ np.array([-h[1], h[0]])))
        width = 0.5 * sum(np.linalg.norm(n[1] - n[0]) for n in winder.nosings[i : i + 2])
        assert off <= 0.1 * width + 1e-9


@pytest.mark.parametrize("direction", ["up", "down"])
def test_the_feet_turn_with_the_walk_line(winder, direction):
    """Each tread footfall's heading is its walk-line chord's (up) or its reverse (down); the
    heading turns a quarter left going up (right going down), never back, each step within
    60 deg."""
    f = winder_footfalls(winder, direction, Walker())
    for yaw, i in zip(f.yaw, f.tread, strict=True):
        if i < 0:
            continue
        chord = np.subtract(winder.treads[i].end, winder.treads[i].start)
        want = math.atan2(chord[1], chord[0]) + (0.0 if direction == "up" else math.pi)
        assert abs(math.remainder(float(yaw) - want, math.tau)) < 1e-9
    turns = np.diff(f.yaw)
    sign = 1.0 if direction == "up" else -1.0
    assert np.all(sign * turns >= -1e-6)  # the meshes' vertices are rounded to 0.1 mm
    assert abs(float(f.yaw[-1] - f.yaw[0]) - sign * math.pi / 2) < 1e-6
    assert np.max(np.abs(turns)) <= WALKING_TURN_MAX
    assert len(np.unique(np.round(f.yaw[f.tread >= 0], 6))) >= 4  # step by step, not at once


@pytest.mark.parametrize("direction", ["up", "down"])
def test_the_stair_steps_take_the_stair_gaits_time(winder, direction):
    walker = Walker()
    f = winder_footfalls(winder, direction, walker)
    climb = stair_gait(walker, StairGeometry(max(winder.risers), winder.tread), direction)
    before = np.concatenate([[winder.z[0] if direction == "up" else winder.z[-1]], f.z[:-1]])
    stair = np.abs(f.z - before) > 1e-6
    assert stair.sum() == 8  # every riser climbed or descended once
    assert np.allclose(f.times[stair], climb.step_time)
    assert np.allclose(f.times[~stair], walker.step_duration)
    assert winder_time(winder, direction, walker) == pytest.approx(float(f.times.sum()))


@pytest.mark.parametrize("direction", ["up", "down"])
def test_a_foot_longer_than_a_tread_hangs_over_its_nosing_keeping_its_share(
    balanced, winder, direction
):
    """A 1.85 m walker's 0.281 m foot fits not every 0.29 m tread wholly with 5 mm to spare
    (refused before the tread-share rule) and hangs over the tread's nosing, as on a straight 0.28 m
    flight (mjwalk.plan.treadshare): on every tread the part of the sole towards the riser at
    the tread's back, 0.6 of the foot (the toes going up; going down the heel, 3 cm off that
    riser), keeps 5 mm inside the tread where the whole foot does not (some treads hold it whole
    at their wide end); no corner crosses the riser at the back, and the overhang is over the
    nosing before it."""
    stature = 1.85
    f = winder_footfalls(winder, direction, Walker(stature=stature))
    over = 0
    for centre, yaw, i in zip(f.centre, f.yaw, f.tread, strict=True):
        if i < 0:
            continue
        surface = balanced.levels.surfaces[
            balanced.levels.levels[winder.treads[i].level].surfaces[0]
        ]
        t = winder.treads[i]
        up = np.subtract(t.end, t.start) / np.linalg.norm(np.subtract(t.end, t.start))
        corners = sole_corners(centre, float(yaw), stature)
        a, b = winder.nosings[i + 1]
        d = (b - a) / np.linalg.norm(b - a)
        n = -winder.normal(i + 1)  # into the tread from the riser at its back
        assert abs(float(n @ d)) < 1e-9
        assert np.all((corners - a) @ n >= TREAD_EDGE_GAP - 1e-9)
        if np.any(surface.footprint.signed_distance(corners) > -TREAD_EDGE_GAP + 1e-9):
            over += 1  # not wholly on the tread: its held part is
            held = held_corners(centre[None], up, stature, direction)[0]
            assert np.all(surface.footprint.signed_distance(held) <= -TREAD_EDGE_GAP + 1e-9)
            lower = _inside_nosings(winder, i, corners)
            assert np.min(lower) < TREAD_EDGE_GAP  # hangs over the nosing before it
            if direction == "down":  # the heel 3 cm off the riser behind it along the foot
                heel = corners + (RISER_GAP - TREAD_EDGE_GAP) * up
                assert np.all((heel - a) @ n >= TREAD_EDGE_GAP - 1e-9)
    assert over >= 1  # the rule is what let this walker on


def test_a_tread_holding_too_little_of_the_foot_is_refused_naming_it(winder, monkeypatch):
    """Where no place in the walk zone holds the share of the foot a tread must (here the whole
    foot: the rule's machinery, not its figure), the walk is refused, the tread named."""
    monkeypatch.setattr(windercross, "MIN_TREAD_SHARE", 1.0)
    with pytest.raises(PlanningError, match=r"winder tread tread1: 100 % of a 0.281 m foot") as e:
        winder_footfalls(winder, "up", Walker(stature=1.85))
    assert "\n" not in str(e.value) and "going up" in str(e.value)


def test_a_foot_that_does_not_fit_on_the_walk_line_moves_to_the_wider_end(winder):
    """On the turned tread3 (0.29 m on the walk line) a 1.75 m walker's sole, turned along the
    chord, crosses a nosing on the walk line; it is moved outwards (towards y -1, the wide end)."""
    centre = tread_foot(winder, 2, 1.75, 0.0)
    t = winder.treads[2]
    middle = 0.5 * (np.array(t.start) + np.array(t.end))
    assert centre[1] < middle[1] - 0.05


def test_the_winder_walk_alternates_its_feet_and_turns_its_pelvis(winder):
    walker = Walker()
    walk = winder_walk(winder, "up", walker, 0.0)
    walk.validate("winder walk")
    sides = [s.side for s in walk.steps]
    assert sides == ["left", "right"] * (len(sides) // 2) + ["left"] * (len(sides) % 2)
    assert walk.meta["crossing"] == "winder" and len(walk.meta["edges"]) == 8
    assert abs(float(walk.yaw[-1] - walk.yaw[0]) - math.pi / 2) < 1e-6
    assert float(np.max(np.abs(np.diff(walk.yaw)))) < math.radians(5.0)  # smooth at 120 Hz
    assert walk.z is not None and abs(float(walk.z[-1]) - 1.36) < 1e-3
    assert walk.duration == pytest.approx(winder_time(winder, "up", walker), abs=0.05)


def test_a_bad_direction_is_refused(winder):
    with pytest.raises(PlanningError, match="direction 'sideways'"):
        winder_footfalls(winder, "sideways", Walker())
