"""Contacts between walk surfaces: where edges meet, the rise across them, what is reachable."""

from __future__ import annotations

import math

import mujoco
import pytest

from mjwalk.errors import InputError
from mjwalk.world.contacts import MIN_CROSSING, level_contacts, reachable, surface_contacts
from mjwalk.world.surfaces import SurfaceOptions, find_walk_surfaces


def surfaces(geoms: str, **options):
    model = mujoco.MjModel.from_xml_string(
        f'<mujoco><worldbody><geom name="floor" type="plane" size="5 5 0.1"/>{geoms}'
        "</worldbody></mujoco>"
    )
    return find_walk_surfaces(model, None, SurfaceOptions(**options))


def test_a_box_on_the_floor_meets_it_along_its_edges():
    ss = surfaces('<geom name="pad" type="box" size="0.5 0.4 0.075" pos="0 0 0.075"/>')
    down = [c for c in surface_contacts(ss) if c.a == 1]
    assert len(down) == 4  # all four sides of the pad, each at least a body wide
    assert all(c.b == 0 and c.rise == pytest.approx(-0.15) for c in down)
    assert sorted(round(c.length, 6) for c in down) == [0.8, 0.8, 1.0, 1.0]


def test_narrow_crossings_and_blocked_edges_are_left_out():
    # the pad's west side is against a wall: no contact there; its 0.3 m sides are too narrow
    ss = surfaces(
        '<geom name="pad" type="box" size="0.5 0.15 0.075" pos="0 0 0.075"/>'
        '<geom name="wall" type="box" size="0.05 1 1" pos="-0.55 0 1"/>'
    )
    down = [c for c in surface_contacts(ss) if c.a == 1]
    assert 0.3 < MIN_CROSSING
    assert sorted(round(c.edge[0][1], 6) for c in down) == [-0.15, 0.15]  # south and north
    assert all(c.length == pytest.approx(1.0) for c in down)


def test_reachable_and_arguments():
    ss = surfaces(
        '<geom name="low" type="box" size="0.5 0.5 0.075" pos="2 0 0.075"/>'
        '<geom name="high" type="box" size="0.5 0.5 0.15" pos="3 0 0.15"/>',
        max_riser=0.19,
    )
    cs = surface_contacts(ss)
    assert reachable(len(ss), cs) == {0, 1, 2}
    assert reachable(len(ss), [c for c in cs if {c.a, c.b} != {1, 2}]) == {0, 1}
    with pytest.raises(InputError, match="gap"):
        surface_contacts(ss, gap=0.0)


def test_a_riser_at_the_limit_rounded_over_it_is_a_contact(tmp_path):
    """Generated hall 214 (``benchmarks/bench_unseen.py``): the landing's top (0.5696 m) and
    the upper flight's first tread (0.7596 m) are a riser of exactly ``MAX_RISER`` (0.19 m),
    computed 0.19000000000000006 m from the geoms' corners; without a slack the flight and the
    1.52 m mezzanine were no walk surfaces (the walks there "inside obstacle 'mezz_deck'").
    Now they are, and the mezzanine is linked by a five-riser stair."""
    from mjwalk.world.levelgen import generate_levels
    from mjwalk.world.workplace import load_workplace

    wp = load_workplace(generate_levels(214).write(tmp_path / "levels_214.xml"), cache=False)
    names = {s.name for s in wp.levels.surfaces}
    assert {"mezz_s2t1", "mezz_s2t4", "mezz_deck"} <= names
    deck = wp.levels.level_of[[s.name for s in wp.levels.surfaces].index("mezz_deck")]
    stairs = [k for k in wp.levels.links if k.kind == "stair" and deck in (k.lower, k.upper)]
    assert [len(k.risers) for k in stairs] == [5]


def split_deck() -> str:
    """A 5 deg ramp 0.9 m wide up to a 0.18 m deck (a step up too) written as two boxes that
    meet on the ramp's axis (a level in strips, as a scan writes a floor cut round a pit):
    each box meets the ramp's high end along 0.45 m, less than a body's width
    (``MIN_CROSSING``, 0.5 m)."""
    half = 0.18 / math.sin(math.radians(5.0)) / 2
    x = 1.5 - half * math.cos(math.radians(5.0))
    z = 0.09 - 0.05 * math.cos(math.radians(5.0))
    return (
        '<geom name="deck_a" type="box" size="1.5 0.6 0.09" pos="3 0.6 0.09"/>'
        '<geom name="deck_b" type="box" size="1.5 0.6 0.09" pos="3 -0.6 0.09"/>'
        f'<geom name="ramp" type="box" size="{half} 0.45 0.05" pos="{x} 0 {z}" euler="0 -5 0"/>'
    )


def test_a_level_of_several_boxes_meets_a_ramp_end_along_their_joined_stretches():
    """No one deck box meets the ramp's high end a body wide, the deck's level does: the two
    0.45 m stretches join into one 0.9 m contact (hall 1243's scanned floor, issue 47)."""
    ss = surfaces(split_deck())
    names = [s.name for s in ss]
    ramp, decks = names.index("ramp"), {names.index("deck_a"), names.index("deck_b")}
    assert 0.45 < MIN_CROSSING
    assert not [c for c in surface_contacts(ss) if c.a == ramp and c.b in decks]
    level_of = [None if s.is_ramp else (1 if i in decks else 0) for i, s in enumerate(ss)]
    by_level = level_contacts(ss, level_of)
    assert all(c.a == ramp for c in by_level)
    (top,) = [c for c in by_level if c.b in decks]
    assert top.length == pytest.approx(0.9, abs=0.02)
    assert max(map(abs, top.rise_range)) < 1e-3  # the ramp's top meets the deck flush
    (foot,) = [c for c in by_level if c.b == 0 and abs(c.rise) < 1e-3]
    assert foot.length == pytest.approx(0.9, abs=0.02)  # its low end on the floor
