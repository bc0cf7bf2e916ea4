"""Levels as groups of surfaces, and a ramp's end meeting a level of several boxes (issue 47):
such a deck is a walk surface when only the ramp reaches it, and a walk plans up the ramp."""

from __future__ import annotations

import math

import mujoco
import pytest

from mjwalk.errors import InputError
from mjwalk.world.contacts import surface_contacts
from mjwalk.world.levelgroups import group_levels, ramp_end_contacts
from mjwalk.world.levels import LevelOptions, level_graph
from mjwalk.world.surfaces import SurfaceOptions, find_walk_surfaces

#: The deck's height and the ramp's slope (under the 10 deg limit, ``norms.MAX_RAMP_SLOPE``).
RISE, SLOPE = 0.5, math.radians(8.0)
#: The ramp's head: x where it meets the deck's west face; the ramp is 1 m wide (y -0.5 to 0.5).
X_TOP = 2.0
#: The deck boxes' y ranges (each 2.5 m deep in x from X_TOP): three boxes meeting the ramp's
#: head along 0.2, 0.4 and 0.4 m (1.0 m joined) ...
THREE = ((0.3, 1.8), (-0.1, 0.3), (-1.8, -0.1))
#: ... or two meeting it along 0.2 and 0.26 m (0.46 m joined: under a body's width, 0.5 m).
TWO = ((0.3, 1.8), (0.04, 0.3))


def ramp() -> str:
    """A 1 m wide ramp (a tilted box 0.1 m thick) from the floor up to z = RISE at x = X_TOP."""
    half = RISE / math.sin(SLOPE) / 2  # half its top face's length
    x = X_TOP - half * math.cos(SLOPE) + 0.05 * math.sin(SLOPE)  # the box's centre: the top's
    z = RISE / 2 - 0.05 * math.cos(SLOPE)  # centre less half the thickness along its normal
    return (
        f'<geom name="ramp" type="box" size="{half} 0.5 0.05" pos="{x} 0 {z}" '
        f'euler="0 {-math.degrees(SLOPE)} 0"/>'
    )


def deck_xml(ys: tuple[tuple[float, float], ...], lift: float = 0.0) -> str:
    """The scene: a floor, the ramp and deck boxes standing on the floor, RISE high (the middle
    box ``lift`` metres higher), one per y range, each from X_TOP to X_TOP + 2.5 m; sites on
    the floor and on the deck."""
    tops = [RISE + (lift if k == 1 else 0.0) for k in range(len(ys))]
    boxes = "".join(
        f'<geom name="deck_{k}" type="box" size="1.25 {(y1 - y0) / 2} {top / 2}" '
        f'pos="{X_TOP + 1.25} {(y0 + y1) / 2} {top / 2}"/>'
        for k, ((y0, y1), top) in enumerate(zip(ys, tops, strict=True))
    )
    return (
        '<mujoco model="deck"><worldbody><geom name="floor" type="plane" size="6 4 0.1" '
        f'pos="0.5 0 0"/>{ramp()}{boxes}<site name="west" pos="-3.5 2.5 0"/>'
        f'<site name="on_deck" pos="{X_TOP + 1.6} 0.9 {RISE}"/></worldbody></mujoco>'
    )


def surfaces_of(ys: tuple[tuple[float, float], ...], lift: float = 0.0, options=None):
    return find_walk_surfaces(mujoco.MjModel.from_xml_string(deck_xml(ys, lift)), None, options)


def test_a_deck_of_boxes_each_meeting_a_ramp_along_less_than_a_body_is_reached_by_it():
    """Three boxes 0.5 m up, reached only by an 8 deg ramp whose head meets them along 0.2,
    0.4 and 0.4 m: the deck's level meets it along 1.0 m, so all three are walk surfaces, one
    level the ramp links to the floor. On ee88a4d no box was a walk surface (reachability went
    surface by surface: none met the ramp along a body's width)."""
    found = surfaces_of(THREE)
    assert sorted(s.name for s in found) == ["deck_0", "deck_1", "deck_2", "floor", "ramp"]
    g = level_graph(found)
    assert [lv.kind for lv in g.levels] == ["floor", "platform"]
    assert len(g.levels[1].surfaces) == 3
    (link,) = g.links
    assert (link.kind, link.lower, link.upper) == ("ramp", 0, 1) and g.notes == ()
    assert link.rise == pytest.approx(RISE, abs=1e-3)
    assert link.slope == pytest.approx(SLOPE, abs=1e-3)
    assert math.dist(*link.upper_edge) == pytest.approx(1.0, abs=0.03)


def test_boxes_meeting_a_ramp_along_less_than_a_body_together_stay_unreached():
    """Two touching boxes (one level) meeting the ramp's head along 0.2 and 0.26 m, 0.46 m
    joined, the rest of the head over a 0.5 m drop: no crossing a body wide, so the deck is
    out of reach (the ramp stays a surface: its foot meets the floor)."""
    found = surfaces_of(TWO)
    assert sorted(s.name for s in found) == ["floor", "ramp"]
    assert not [k for k in level_graph(found).links if k.kind == "ramp"]


def test_the_surface_options_level_tolerance_decides_a_ramp_reached_deck():
    """The three-box deck with its middle box 6 mm higher: under the default 4 mm tolerance
    (``norms.LEVEL_TOLERANCE``) the boxes are three levels, none meeting the ramp a body wide,
    so the deck is unreached; with ``SurfaceOptions(level_tol=0.008)`` they are one level the
    ramp reaches, and the level graph under the same tolerance links it. On 261f168 the
    option did not exist and reachability always used 4 mm."""
    assert sorted(s.name for s in surfaces_of(THREE, 0.006)) == ["floor", "ramp"]
    found = surfaces_of(THREE, 0.006, SurfaceOptions(level_tol=0.008))
    assert sorted(s.name for s in found) == ["deck_0", "deck_1", "deck_2", "floor", "ramp"]
    g = level_graph(found, LevelOptions(level_tol=0.008))
    (link,) = g.links
    assert (link.kind, link.lower, link.upper) == ("ramp", 0, 1)
    assert len(g.levels[1].surfaces) == 3


def test_surface_options_refuse_a_level_tolerance_over_the_riser():
    """A level tolerance must be positive and under the step limit (one-line InputError)."""
    with pytest.raises(InputError, match="level_tol"):
        SurfaceOptions(level_tol=0.0)
    with pytest.raises(InputError, match="must exceed level_tol"):
        SurfaceOptions(level_tol=0.2)


def test_group_levels_joins_touching_horizontal_surfaces_and_leaves_ramps_out():
    """The deck of three boxes with the floor and the ramp (all reached): groups are the floor
    alone and the three deck boxes; the ramp is in none. The ramp's head meets the deck's level
    along its 1 m and its foot the floor, though it meets no deck box alone a body wide."""
    found = surfaces_of(THREE)
    names = [s.name for s in found]
    contacts = surface_contacts(found)
    groups = sorted(sorted(names[i] for i in g) for g in group_levels(found, contacts))
    assert groups == [["deck_0", "deck_1", "deck_2"], ["floor"]]
    ends = ramp_end_contacts(found, contacts)
    assert {names[c.a] for c in ends} == {"ramp"}
    by_level = {names[c.b].split("_")[0]: c for c in ends if abs(c.rise) < 0.01}
    assert set(by_level) == {"deck", "floor"}
    assert by_level["deck"].length == pytest.approx(1.0, abs=0.03)
    pair = [{names[c.a], names[c.b]} for c in contacts]
    assert not [p for p in pair if "ramp" in p and p & {"deck_0", "deck_1", "deck_2"}]


def test_a_walk_from_the_floor_onto_the_deck_plans_up_the_ramp(tmp_path):
    """Seeded (rng 0): a walk from the floor's west end to a site on the three-box deck takes
    the ramp (the route: level, ramp, level) and ends 0.5 m up."""
    from mjwalk.gait.default import default_model  # deferred: loads the gait model, this test
    from mjwalk.plan.walks import plan_walk  # deferred: only this test plans
    from mjwalk.world import load_workplace  # deferred: only this test loads a workplace

    path = tmp_path / "deck.xml"
    path.write_text(deck_xml(THREE))
    wp = load_workplace(path, cache=False)
    walk = plan_walk(wp, "west", "on_deck", default_model(progress=False), rng=0)
    assert [r["kind"] for r in walk.meta["levels"]["route"]] == ["level", "ramp", "level"]
    assert walk.ground[-1] == pytest.approx(RISE, abs=1e-6)
