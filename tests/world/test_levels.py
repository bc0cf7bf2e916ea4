"""Levels and links: the shipped multi-level station's step, ramp and stair, and the rules that
refuse a link (a riser above the limit, irregular risers), reach per walker, head clearance."""

from __future__ import annotations

import math

import mujoco
import pytest

from mjwalk.errors import InputError
from mjwalk.world.levels import LevelOptions, describe_levels, level_graph
from mjwalk.world.surfaces import SurfaceOptions, find_walk_surfaces


def scene(geoms: str) -> mujoco.MjModel:
    return mujoco.MjModel.from_xml_string(
        f'<mujoco><worldbody><geom name="floor" type="plane" size="5 5 0.1"/>{geoms}'
        "</worldbody></mujoco>"
    )


def flight(risers: list[float], tread: float = 0.28) -> str:
    """Boxes standing on the floor, one per tread, rising towards +x, then a landing."""
    out, z, x = [], 0.0, 0.0
    for k, r in enumerate(risers[:-1]):
        z += r
        out.append(
            f'<geom name="t{k + 1}" type="box" size="{tread / 2} 0.5 {z / 2}" '
            f'pos="{x + tread / 2} 0 {z / 2}"/>'
        )
        x += tread
    z += risers[-1]
    out.append(f'<geom name="landing" type="box" size="1 1 {z / 2}" pos="{x + 1} 0 {z / 2}"/>')
    return "".join(out)


def three_treads() -> str:
    """Three treads 1.4 m wide rising towards +x from the floor by 0.17 m risers, 0.28 m deep
    (the last tread's top 0.51 m up, its front edge at x = 0.84 m)."""
    return "".join(
        f'<geom name="t{k}" type="box" size="0.14 0.7 {0.085 * k}" '
        f'pos="{0.28 * k - 0.14} 0 {0.085 * k}"/>'
        for k in (1, 2, 3)
    )


@pytest.fixture(scope="module")
def station(scenes_dir):
    model = mujoco.MjModel.from_xml_path(str(scenes_dir / "multilevel_station.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    return model, data, level_graph(find_walk_surfaces(model, data))


def level_named(graph, name):
    i = [s.name for s in graph.surfaces].index(name)
    return graph.level_of[i]


def test_station_levels_and_links(station):
    _, _, g = station
    heights = sorted(round(lv.height, 3) for lv in g.levels)
    assert heights == [0.0, 0.17, 0.17, 0.34, 0.34, 0.51, 0.68, 0.85, 1.02]
    assert g.levels[0].kind == "floor"
    floor, step, plat = 0, level_named(g, "platform_step"), level_named(g, "platform")
    mezz = level_named(g, "mezzanine")
    by_kind = {k: [lk for lk in g.links if lk.kind == k] for k in ("step", "ramp", "stair")}
    steps = {(lk.lower, lk.upper): lk for lk in by_kind["step"]}
    assert set(steps) == {(floor, step), (step, plat)}
    for lk in steps.values():
        assert lk.risers == pytest.approx((0.17,), abs=1e-3)
    (ramp,) = by_kind["ramp"]
    assert (ramp.lower, ramp.upper) == (floor, plat)
    assert math.degrees(ramp.slope) == pytest.approx(5.5, abs=0.01)
    assert ramp.rise == pytest.approx(0.34, abs=1e-3)
    assert g.surfaces[ramp.via[0]].name == "platform_ramp"
    (stair,) = by_kind["stair"]
    assert (stair.lower, stair.upper) == (floor, mezz)
    assert stair.risers == pytest.approx((0.17,) * 6, abs=1e-3)
    assert stair.tread == pytest.approx(0.28, abs=1e-3)
    assert [g.surfaces[i].name for i in stair.via] == [f"stair_tread{k}" for k in range(1, 6)]
    # the stair's first riser at y = -0.10, its last at the mezzanine's edge y = -1.5
    assert stair.lower_edge[0][1] == pytest.approx(-0.10, abs=0.03)
    assert stair.upper_edge[0][1] == pytest.approx(-1.50, abs=0.03)


def test_sites_stand_on_their_levels(station):
    model, data, g = station
    where = {}
    for name in ("stand_car1", "stand_platform1", "stand_mezz_rack", "stand_stair"):
        pos = data.site_xpos[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_SITE, name)]
        where[name] = g.surfaces[g.surface_at(pos[:2], pos[2])].name
    assert where == {
        "stand_car1": "floor",
        "stand_platform1": "platform",
        "stand_mezz_rack": "mezzanine",
        "stand_stair": "floor",
    }


def test_reach_depends_on_the_walkers_riser(station):
    _, _, g = station
    plat, mezz = level_named(g, "platform"), level_named(g, "mezzanine")
    assert {plat, mezz} <= g.reachable()
    low = g.reachable(max_riser=0.15)  # a walker stepping at most 0.15 m takes the ramp only
    assert plat in low and mezz not in low


def test_a_walker_whose_limit_is_the_riser_rounded_takes_the_stair(station):
    """A stair's riser computed from geoms' corners carries float rounding: a walker whose
    step-up limit is that riser less a mesh vertex's rounding (1e-7 m) still takes the stair (as the
    contacts and the stair check allow, ``norms.ROUNDING_SLACK``); 10 µm less does not."""
    _, _, g = station
    mezz = level_named(g, "mezzanine")
    r = max(
        r for k in g.links if k.kind == "stair" and mezz in (k.lower, k.upper) for r in k.risers
    )
    assert mezz in g.reachable(max_riser=r - 1e-7)
    assert mezz not in g.reachable(max_riser=r - 1e-5)


def test_a_riser_above_the_limit_gives_no_link():
    # surfaces found with a 0.25 m step limit; the default level options link at most 0.19 m
    model = scene('<geom name="box" type="box" size="1 1 0.105" pos="2 0 0.105"/>')
    surfaces = find_walk_surfaces(model, None, SurfaceOptions(max_riser=0.25))
    assert [s.name for s in surfaces] == ["floor", "box"]
    g = level_graph(surfaces)
    assert len(g.levels) == 2 and g.links == ()
    links = level_graph(surfaces, LevelOptions(max_riser=0.25)).links
    assert len(links) == 4 and {lk.kind for lk in links} == {"step"}  # each side of the box


def test_regular_flight_is_a_stair_irregular_one_stays_steps():
    g = level_graph(find_walk_surfaces(scene(flight([0.17] * 4)), None))
    assert [lk.kind for lk in g.links] == ["stair"]
    assert g.links[0].risers == pytest.approx((0.17,) * 4, abs=1e-6)
    g = level_graph(find_walk_surfaces(scene(flight([0.15, 0.17, 0.19, 0.17])), None))
    assert [lk.kind for lk in g.links] == ["step"] * 4
    g = level_graph(find_walk_surfaces(scene(flight([0.17, 0.17])), None))
    assert [lk.kind for lk in g.links] == ["step"] * 2  # two risers: single steps (DIN 18065)


def test_a_flight_within_the_build_tolerance_beyond_the_limits_is_no_stair():
    """DIN 18065's 5 mm tolerance bounds how regular a flight is, not its limits
    (``norms.STAIR_TOLERANCE``): a regular flight whose step rule 2 h + g is 0.2 mm over 0.65 m
    is four single steps; one whose risers are 0.2 mm over 0.19 m links nothing."""
    g = level_graph(find_walk_surfaces(scene(flight([0.17] * 4, tread=0.3102)), None))
    assert [lk.kind for lk in g.links] == ["step"] * 4
    g = level_graph(find_walk_surfaces(scene(flight([0.17] * 4, tread=0.3098)), None))
    assert [lk.kind for lk in g.links] == ["stair"]
    opts = SurfaceOptions(max_riser=0.25)  # the treads found, the level options' 0.19 m limit
    g = level_graph(find_walk_surfaces(scene(flight([0.1902] * 4, tread=0.26)), None, opts))
    assert g.links == ()


@pytest.mark.parametrize("name", ["assembly_station", "corridor", "open_floor"])
def test_flat_shipped_scenes_have_one_level(scenes_dir, name):
    model = mujoco.MjModel.from_xml_path(str(scenes_dir / f"{name}.xml"))
    g = level_graph(find_walk_surfaces(model, None))
    assert len(g.levels) == 1 and g.links == ()


def test_head_clearance_refuses_the_tall_walker_only():
    deck = '<geom name="deck" type="box" size="1 0.5 0.085" pos="0 0 0.085"/>'
    beam = '<geom name="beam" type="box" size="0.1 0.7 0.1" pos="0.5 0 2.17"/>'
    g = level_graph(find_walk_surfaces(scene(deck + beam), None))
    assert g.levels[1].lowest_ceiling == pytest.approx(1.9, abs=1e-9)
    assert not g.head_fits((0.5, 0.0), 0.17, 1.90)
    assert g.head_fits((0.5, 0.0), 0.17, 1.60)
    assert g.head_fits((-0.5, 0.0), 0.17, 1.90)


def test_describe_levels(station):
    text = describe_levels(station[2])
    assert text.splitlines()[0] == "levels: 9, links: 4"
    assert "ramp  L0 -> L3  slope 5.50 deg (9.6 %), rise 0.340 m" in text
    assert "stair L0 -> L8  6 risers x 0.170 m, tread 0.280 m (2h+g 0.620 m)" in text


def test_describe_levels_prints_a_round_podiums_steps_once():
    """A cylinder's top is a polygon: its step down to the floor is one link per edge, printed
    as one line with their count."""
    g = level_graph(
        find_walk_surfaces(
            scene('<geom name="pod" type="cylinder" size="1.2 0.085" pos="0 0 0.085"/>')
        )
    )
    steps = [k for k in g.links if k.kind == "step"]
    assert len(steps) > 4
    lines = describe_levels(g).splitlines()
    assert lines[-1] == f"  step  L0 -> L1  riser 0.170 m  ({len(steps)} edges)"
    assert lines[0] == f"levels: 2, links: {len(steps)}"


def _rolled_ramp(roll_deg: float) -> str:
    """A 5 deg ramp up to a 0.30 m deck, its top rolled about its axis by ``roll_deg``."""
    half = 0.30 / math.sin(math.radians(5.0)) / 2
    x = 1.5 - half * math.cos(math.radians(5.0))
    z = 0.15 - 0.05 * math.cos(math.radians(5.0))
    return (
        '<geom name="deck" type="box" size="1.5 1.2 0.15" pos="3 0 0.15"/>'
        f'<geom name="ramp" type="box" size="{half} 0.6 0.05" pos="{x} 0 {z}" '
        f'euler="{roll_deg} -5 0"/>'  # degrees: MJCF's default
    )


def test_a_ramp_with_a_cross_slope_links_nothing_and_says_why():
    """A 0.5 deg roll leaves a 5 mm lip where the 1.2 m wide ramp meets the deck: more than
    ASR A1.5/1,2's 4 mm, so no link (as before), but now a note says so, and the level
    planner's "no route" carries it; the same ramp without the roll links and has no note."""
    plain = level_graph(find_walk_surfaces(scene(_rolled_ramp(0.0))))
    assert [k.kind for k in plain.links] == ["ramp"] and plain.notes == ()
    rolled = level_graph(find_walk_surfaces(scene(_rolled_ramp(0.5))))
    assert rolled.links == ()
    (note,) = rolled.notes
    assert note.startswith("ramp 'ramp' links no levels: its high end meets L1 with a lip of up")
    assert "5.2 mm" in note and "within 4 mm" in note
    assert f"  note: {note}" in describe_levels(rolled)


def test_a_ramp_up_to_a_level_of_several_boxes_links_it():
    """A 5 deg ramp's high end meets a 0.18 m deck (a step up too) written as two boxes, each
    along 0.45 m only (less than a body's width): the deck's level meets it along 0.9 m, so
    the ramp links floor and deck (before: no ramp link, "its ends do not meet two levels";
    hall 1243's scanned floor, cut round a pit into strips, lost its ramp so)."""
    half = 0.18 / math.sin(math.radians(5.0)) / 2
    x = 1.5 - half * math.cos(math.radians(5.0))
    z = 0.09 - 0.05 * math.cos(math.radians(5.0))
    g = level_graph(
        find_walk_surfaces(
            scene(
                '<geom name="deck_a" type="box" size="1.5 0.6 0.09" pos="3 0.6 0.09"/>'
                '<geom name="deck_b" type="box" size="1.5 0.6 0.09" pos="3 -0.6 0.09"/>'
                f'<geom name="ramp" type="box" size="{half} 0.45 0.05" pos="{x} 0 {z}" '
                'euler="0 -5 0"/>'
            )
        )
    )
    assert [lv.kind for lv in g.levels] == ["floor", "platform"]
    (ramp,) = [k for k in g.links if k.kind == "ramp"]
    assert (ramp.lower, ramp.upper) == (0, 1) and g.notes == ()
    assert ramp.rise == pytest.approx(0.18, abs=1e-3)
    assert math.dist(*ramp.upper_edge) == pytest.approx(0.9, abs=0.02)


def test_level_options_are_checked():
    with pytest.raises(InputError, match="level_tol"):
        LevelOptions(level_tol=0.0)
    with pytest.raises(InputError, match="riser_range"):
        LevelOptions(riser_range=(0.2, 0.1))
    with pytest.raises(InputError, match="no walk surfaces"):
        level_graph(())


def test_a_slab_a_hair_over_the_pit_plane_leaves_it_no_standing_room(tmp_path):
    """Generated hall 0 (bench_unseen, issue 47): its floor boxes round a pit are written 0.1 mm
    over the plane at the pit's bottom. A site on a pedestal no one can climb was placed on
    the pit's level (the plane went on under the boxes with 0.1 mm free) instead of on none."""
    from mjwalk.world.levelgen import generate_levels
    from mjwalk.world.levelview import level_at
    from mjwalk.world.workplace import load_workplace

    hall = generate_levels(0)
    assert "pit" in hall.features and "pedestal" in hall.features
    wp = load_workplace(hall.write(tmp_path / "hall0.xml"), cache=False)
    ped = wp.stations["pedestal_0"]
    assert level_at(wp, ped.xy, float(ped.pos[2])) is None
    pit = wp.stations["pit_0"]
    assert wp.levels.levels[level_at(wp, pit.xy, float(pit.pos[2]))].height == pytest.approx(
        hall.site("pit_0").pos[2], abs=1e-3
    )
    floor = wp.stations["floor_0"]
    assert level_at(wp, floor.xy, 0.0) == 0


def test_a_top_tread_meeting_the_landing_in_two_stretches_is_still_a_stair():
    """A flight of four 0.17 m risers whose landing is two boxes side by side (a pit's rim
    written as several floor boxes, issue 47's scanned hall 1117): its top tread meets the
    landing's level along two stretches of one riser, two step links. The flight is one stair
    crossed at the longer stretch, and neither stretch stays a step (on the base tree the chain
    stopped at two candidates: four steps, no stair)."""
    landing = (  # split at y = -0.2: stretches of 0.5 m and 0.9 m along the top riser
        '<geom name="deck_a" type="box" size="1 0.5 0.34" pos="1.84 -0.7 0.34"/>'
        '<geom name="deck_b" type="box" size="1 0.8 0.34" pos="1.84 0.6 0.34"/>'
    )
    g = level_graph(find_walk_surfaces(scene(three_treads() + landing), None))
    deck = level_named(g, "deck_a")
    assert level_named(g, "deck_b") == deck
    assert [(k.kind, k.lower, k.upper) for k in g.links] == [("stair", 0, deck)]
    stair = g.links[0]
    assert stair.risers == pytest.approx((0.17,) * 4, abs=1e-6)
    assert stair.tread == pytest.approx(0.28, abs=1e-6)
    (x0, y0), (x1, y1) = stair.upper_edge
    assert x0 == pytest.approx(0.84, abs=0.03) and x1 == pytest.approx(0.84, abs=0.03)
    assert abs(y1 - y0) == pytest.approx(0.9, abs=0.05)  # the longer stretch, deck_b's


def test_a_tread_meeting_two_levels_in_line_stops_the_flight():
    """The same flight with the landing's two boxes at heights 0.680 m and 0.6845 m (two
    levels: 4.5 mm apart, over the 4 mm level tolerance, within the 5 mm stair tolerance): the
    top riser's two stretches rise to different levels, so which the flight reaches is not
    clear and the treads stay steps."""
    landing = (
        '<geom name="deck_a" type="box" size="1 0.5 0.34" pos="1.84 -0.7 0.34"/>'
        '<geom name="deck_b" type="box" size="1 0.8 0.34225" pos="1.84 0.6 0.34225"/>'
    )
    g = level_graph(find_walk_surfaces(scene(three_treads() + landing), None))
    assert level_named(g, "deck_a") != level_named(g, "deck_b")
    assert {k.kind for k in g.links} == {"step"}


def test_a_landing_box_a_centimetre_behind_the_top_riser_is_the_same_riser():
    """The flight's landing as a tread-wide box flush with the top riser and a deck box whose
    edge lies 1 cm behind it (within the 2 cm contact gap: touching), as the scan writes a deck
    and its inferred top tread (issue 47's scanned hall 1038): both meet the top tread, one riser
    of one level. The flight is one stair measured to the riser's front (tread 0.28 m), and no
    step is left over it (the base tree gave four steps)."""
    landing = (
        '<geom name="top" type="box" size="0.14 0.7 0.34" pos="0.98 0 0.34"/>'
        '<geom name="deck" type="box" size="1 1.2 0.34" pos="1.85 0 0.34"/>'
    )
    g = level_graph(find_walk_surfaces(scene(three_treads() + landing), None))
    deck = level_named(g, "deck")
    assert level_named(g, "top") == deck
    assert [(k.kind, k.lower, k.upper) for k in g.links] == [("stair", 0, deck)]
    assert g.links[0].tread == pytest.approx(0.28, abs=1e-6)


def test_a_first_riser_meeting_the_floor_in_two_stretches_is_the_stairs_alone():
    """A flight of four 0.17 m risers on a floor written as two boxes side by side, their seam
    across the first riser at y = -0.1 (a floor round a pit, fresh hall 1162 of
    benchmarks/bench_unseen.py): the floor meets the first tread along two stretches of one
    riser (0.6 m and 0.8 m), two step links. The flight is one stair crossed at the longer
    stretch, and the other stays no step onto its first tread (before: an extra step link)."""
    geoms = (
        '<geom name="floor_a" type="box" size="3.5 1.45 0.05" pos="0.5 -1.55 -0.05"/>'
        '<geom name="floor_b" type="box" size="3.5 1.55 0.05" pos="0.5 1.45 -0.05"/>'
        + three_treads()
        + '<geom name="deck" type="box" size="1 1 0.34" pos="1.84 0 0.34"/>'
    )
    model = mujoco.MjModel.from_xml_string(f"<mujoco><worldbody>{geoms}</worldbody></mujoco>")
    g = level_graph(find_walk_surfaces(model, None))
    deck = level_named(g, "deck")
    assert level_named(g, "floor_a") == level_named(g, "floor_b") == 0
    assert [(k.kind, k.lower, k.upper) for k in g.links] == [("stair", 0, deck)]
    (x0, y0), (x1, y1) = g.links[0].lower_edge
    assert x0 == pytest.approx(0.0, abs=0.03) and x1 == pytest.approx(0.0, abs=0.03)
    assert abs(y1 - y0) == pytest.approx(0.8, abs=0.05)  # the longer stretch, floor_b's


def _mesh_flight(riser: float, tread: float, n: int) -> mujoco.MjModel:
    """A flight of ``n`` risers towards +x built as a CAD export writes it: each tread and the
    landing one prism mesh standing on the floor (vertices in world coordinates, stored by
    MuJoCo in single precision), 1.2 m wide."""
    assets, geoms = [], []
    for k in range(1, n + 1):
        x0, depth, half = 0.37 + (k - 1) * tread, tread if k < n else 2.0, 0.6 if k < n else 1.0
        v = " ".join(
            f"{x:.6f} {y:.6f} {z:.6f}"
            for x in (x0, x0 + depth)
            for y in (-half, half)
            for z in (0.0, riser * k)
        )
        assets.append(f'<mesh name="m{k}" vertex="{v}"/>')
        geoms.append(f'<geom name="t{k}" type="mesh" mesh="m{k}"/>')
    return mujoco.MjModel.from_xml_string(
        f"<mujoco><asset>{''.join(assets)}</asset><worldbody>"
        f'<geom name="floor" type="plane" size="9 9 0.1"/>{"".join(geoms)}</worldbody></mujoco>'
    )


@pytest.mark.parametrize("riser", [0.17, 0.19])
def test_a_mesh_flight_at_the_limits_is_the_stair_its_boxes_are(riser):
    """A flight of prism meshes with 0.26 m treads (``MIN_TREAD``) and 0.17 or 0.19 m risers
    (``MAX_RISER``) is one stair, as the same flight of boxes: its treads' depths and risers,
    read from single-precision vertices, miss the limits by ~1e-8 m (the tread 0.2599999x m),
    within ``norms.ROUNDING_SLACK`` (with a 1e-9 m slack the treads were no walk surfaces)."""
    model = _mesh_flight(riser, 0.26, 6)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    g = level_graph(find_walk_surfaces(model, data))
    assert [k.kind for k in g.links] == ["stair"]
    assert max(g.links[0].risers) == pytest.approx(riser, abs=1e-6)
