"""Walk surfaces found in MJCF scenes: the shipped multi-level station, flat scenes, and small
scenes for each rule (reach, size, slope, headroom, hidden, options)."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from mjwalk.errors import InputError
from mjwalk.world import surfaces as surfaces_module
from mjwalk.world.norms import MAX_RAMP_SLOPE, MAX_TREAD
from mjwalk.world.surfaces import SurfaceOptions, find_walk_surfaces
from mjwalk.world.walksurface import head_fits
from mjwalk.world.workplace import HUMANOID_PREFIXES


def scene(geoms: str) -> mujoco.MjModel:
    """A 10 x 10 m floor with the given geoms."""
    return mujoco.MjModel.from_xml_string(
        f'<mujoco><worldbody><geom name="floor" type="plane" size="5 5 0.1"/>{geoms}'
        "</worldbody></mujoco>"
    )


def names(model: mujoco.MjModel, options: SurfaceOptions | None = None) -> list[str]:
    return [s.name for s in find_walk_surfaces(model, None, options)]


@pytest.fixture(scope="module")
def multilevel(scenes_dir):
    model = mujoco.MjModel.from_xml_path(str(scenes_dir / "multilevel_station.xml"))
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    return {s.name: s for s in find_walk_surfaces(model, data)}


def test_multilevel_station_surfaces_at_their_heights(multilevel):
    expect = {
        "floor": ("floor", 0.0),
        "platform_step": ("tread", 0.17),
        "platform": ("platform", 0.34),
        "mezzanine": ("platform", 1.02),
        **{f"stair_tread{k}": ("tread", 0.17 * k) for k in range(1, 6)},
    }
    assert set(multilevel) == set(expect) | {"platform_ramp"}
    for name, (kind, z) in expect.items():
        s = multilevel[name]
        assert s.kind == kind, name
        assert s.z == pytest.approx(z, abs=1e-3), name
        assert s.slope == 0.0
    ramp = multilevel["platform_ramp"]
    assert ramp.kind == "ramp"
    assert (ramp.z_low, ramp.z_high) == pytest.approx((0.0, 0.34), abs=1e-3)
    assert math.degrees(ramp.slope) == pytest.approx(5.5, abs=0.01)
    assert math.cos(ramp.uphill) == pytest.approx(-1.0, abs=1e-6)  # rises towards -x
    # its top face, 0.34 / tan(5.5 deg) = 3.53 m long and 1.0 m wide
    assert ramp.area == pytest.approx(0.34 / math.tan(math.radians(5.5)) * 1.0, rel=1e-3)
    assert float(ramp.height_at(np.array([2.2, 3.2]))) == pytest.approx(0.34, abs=1e-3)
    assert multilevel["stair_tread3"].depth == pytest.approx(0.28, abs=1e-6)


@pytest.mark.parametrize(
    "name", ["assembly_station", "assembly_station_2h", "corridor", "open_floor"]
)
def test_flat_shipped_scenes_give_only_the_floor(scenes_dir, name):
    # table, rack and car tops are candidates, but no step of at most 0.19 m reaches them
    model = mujoco.MjModel.from_xml_path(str(scenes_dir / f"{name}.xml"))
    assert names(model) == ["floor"]


def test_a_top_is_a_surface_only_when_a_step_reaches_it():
    table = '<geom name="table" type="box" size="0.6 0.4 0.375" pos="0 0 0.375"/>'
    assert names(scene(table)) == ["floor"]  # 0.75 m above the floor
    stair = (
        '<geom name="low" type="box" size="0.5 0.5 0.075" pos="2 0 0.075"/>'
        '<geom name="high" type="box" size="0.5 0.5 0.15" pos="3 0 0.15"/>'
    )
    assert names(scene(stair)) == ["floor", "low", "high"]  # 0.15 then 0.15


def test_too_small_too_steep_or_hidden_tops_are_no_surfaces():
    small = '<geom name="small" type="box" size="0.1 0.5 0.05" pos="0 0 0.05"/>'  # 0.2 m deep
    steep = '<geom name="steep" type="box" size="1 0.5 0.05" pos="2 0 0.1" euler="0 15 0"/>'
    hidden = (
        '<geom name="outer" type="box" size="1 1 0.075" pos="-2 -2 0.075"/>'
        '<geom name="inner" type="box" size="0.5 0.5 0.05" pos="-2 -2 0.05"/>'
    )
    assert names(scene(small + steep + hidden)) == ["floor", "outer"]


def test_yawed_box_keeps_its_rectangle():
    model = scene(
        '<geom name="pad" type="box" size="0.6 0.4 0.075" pos="1 1 0.075" euler="0 0 30"/>'
    )
    pad = find_walk_surfaces(model, None)[1]
    assert pad.kind == "platform"
    assert pad.area == pytest.approx(1.2 * 0.8, rel=1e-9)
    assert (pad.depth, pad.width) == pytest.approx((0.8, 1.2), abs=1e-9)
    along = np.array([math.cos(math.radians(30)), math.sin(math.radians(30))])  # its local +x
    assert bool(pad.contains(np.array([1.0, 1.0]) + 0.55 * along))
    assert not bool(pad.contains(np.array([1.0, 1.0]) + 0.65 * along))  # beyond its short side


def test_a_yawed_tread_exactly_max_tread_deep_is_a_tread():
    """A two-riser step's 0.37 m tread (``MAX_TREAD`` exactly) yawed as generated hall 710 has
    it: its depth comes out 0.37 m + 3e-16 (before: a "platform", so no step chain over it)."""
    tread = (
        '<geom name="tread" type="box" size="0.1850 0.6720 0.0741" pos="2.8375 -3.8303 0.0741"'
        ' euler="0 0 -160.4690"/>'
    )
    (surface,) = find_walk_surfaces(scene(tread), None)[1:]
    assert surface.depth == pytest.approx(MAX_TREAD, abs=1e-12)
    assert surface.kind == "tread"
    deeper = tread.replace("0.1850", "0.1851")  # 0.3702 m: a platform
    assert find_walk_surfaces(scene(deeper), None)[1].kind == "platform"


def test_a_ramp_at_exactly_the_slope_limit_is_a_ramp():
    """A 3 m slab turned by exactly ``MAX_RAMP_SLOPE`` (10 deg) measures 0.17453292519943317 rad
    from its top face's corners, 2e-16 over it: within ``norms.SLOPE_ROUNDING_SLACK`` a ramp
    (before: no walk surface, as a hall's 0.19 m riser read 0.19000000000000006 m was none
    before ``ROUNDING_SLACK``). 10.001 deg (1.7e-5 rad over) is no walk surface."""
    for deg, ok in ((10.0, True), (10.001, False)):
        th = math.radians(deg)
        z = 1.5 * math.sin(th) - 0.05 * math.cos(th)  # the top face's low edge on the floor
        ramp = (
            f'<geom name="ramp" type="box" size="1.5 0.5 0.05" pos="0 0 {z!r}" euler="0 {-deg} 0"/>'
        )

        surfaces = find_walk_surfaces(scene(ramp), None)
        assert [s.name for s in surfaces] == (["floor", "ramp"] if ok else ["floor"]), deg
        if ok:
            assert surfaces[1].slope == pytest.approx(MAX_RAMP_SLOPE, abs=1e-12)


BEAM_PLATFORM = '<geom name="deck" type="box" size="1 0.5 0.085" pos="0 0 0.085"/>'


def test_a_surface_under_a_low_beam_is_refused():
    # a beam over the whole deck, its underside 1.9 m above it: less than the 2.0 m clear
    # headroom (DIN 18065) anywhere on it
    beam = '<geom name="beam" type="box" size="1.2 0.7 0.1" pos="0 0 2.17"/>'
    assert names(scene(BEAM_PLATFORM + beam)) == ["floor"]
    assert names(scene(BEAM_PLATFORM + beam), SurfaceOptions(min_headroom=1.8)) == ["floor", "deck"]


def test_head_clearance_under_a_beam_depends_on_stature():
    # a 0.2 m beam across the deck, its underside 1.9 m above the deck's top (0.17 m)
    beam = '<geom name="beam" type="box" size="0.1 0.7 0.1" pos="0.5 0 2.17"/>'
    deck = find_walk_surfaces(scene(BEAM_PLATFORM + beam), None)[1]
    under, beside = np.array([0.5, 0.0]), np.array([-0.5, 0.0])
    assert float(deck.free_height(under)) == pytest.approx(1.9, abs=1e-9)
    assert math.isinf(float(deck.free_height(beside)))
    assert not bool(head_fits(deck, under, 1.90))
    assert bool(head_fits(deck, under, 1.60))
    assert bool(head_fits(deck, beside, 1.90))
    assert deck.lowest_ceiling == pytest.approx(1.9, abs=1e-9)
    assert deck.headroom.at(under) == pytest.approx(1.9, abs=1e-9)


def test_options_select_and_check():
    two = (
        '<geom name="pad_a" type="box" size="0.5 0.5 0.075" pos="2 0 0.075" group="1"/>'
        '<geom name="pad_b" type="box" size="0.5 0.5 0.075" pos="-2 0 0.075"/>'
    )
    model = scene(two)
    assert names(model, SurfaceOptions(exclude="_a$")) == ["floor", "pad_b"]
    assert names(model, SurfaceOptions(include="_a$")) == ["floor", "pad_a"]
    assert names(model, SurfaceOptions(groups={1})) == ["floor", "pad_a"]
    with pytest.raises(InputError, match="max_ramp_slope"):
        SurfaceOptions(max_ramp_slope=0.0)
    with pytest.raises(InputError, match="regular expression"):
        SurfaceOptions(include="(")
    with pytest.raises(InputError, match="min_depth"):
        SurfaceOptions(min_depth=-1.0)


def test_without_the_ramp_the_platform_is_still_reached_by_its_step(scenes_dir):
    model = mujoco.MjModel.from_xml_path(str(scenes_dir / "multilevel_station.xml"))
    found = names(model, SurfaceOptions(exclude="ramp"))
    assert "platform" in found and "platform_ramp" not in found


def test_humanoid_prefixes_match_the_workplace():
    assert surfaces_module.HUMANOID_PREFIXES == HUMANOID_PREFIXES


def _wedge_station(scenes_dir, tmp_path):
    """The multi-level station with its ramp (a tilted slab) replaced by a wedge mesh with the
    same top face: from (x 2.2, z 0.34) down 5.5 deg to the floor, 1 m wide (CAD gives ramps
    as solids like this)."""
    import re

    x1 = 2.2 + 0.34 / math.tan(math.radians(5.5))
    v = [
        (2.2, 2.7, 0),
        (x1, 2.7, 0),
        (x1, 3.7, 0),
        (2.2, 3.7, 0),
        (2.2, 2.7, 0.34),
        (2.2, 3.7, 0.34),
    ]
    src = (scenes_dir / "multilevel_station.xml").read_text()
    out = re.sub(
        r'<geom name="platform_ramp" type="box"[^>]*/>',
        '<geom name="platform_ramp" type="mesh" mesh="wedge" material="deck"/>',
        src,
        flags=re.S,
    )
    vertex = " ".join(f"{c:.6f}" for p in v for c in p)
    out = out.replace("<asset>", f'<asset><mesh name="wedge" vertex="{vertex}"/>', 1)
    assert out != src
    path = tmp_path / "wedge_station.xml"
    path.write_text(out)
    return path


def test_a_wedge_mesh_s_sloped_top_is_the_ramp_a_slab_gives(multilevel, scenes_dir, tmp_path):
    """A mesh whose highest vertices are a ridge, not a face (a wedge), has the hull's most
    upward face through its ridge as its top: the station's ramp as a wedge mesh is the same
    ramp as the tilted slab (before: no surface, the wedge an obstacle, the ramp gone)."""
    model = mujoco.MjModel.from_xml_path(str(_wedge_station(scenes_dir, tmp_path)))
    found = {s.name: s for s in find_walk_surfaces(model)}
    slab, wedge = multilevel["platform_ramp"], found["platform_ramp"]
    assert wedge.kind == "ramp"
    assert (wedge.z_low, wedge.z_high) == pytest.approx((slab.z_low, slab.z_high), abs=1e-3)
    assert wedge.slope == pytest.approx(slab.slope, abs=1e-4)
    assert math.cos(wedge.uphill - slab.uphill) == pytest.approx(1.0, abs=1e-9)
    assert wedge.area == pytest.approx(slab.area, rel=1e-3)
    assert set(found) == set(multilevel)


@pytest.mark.slow
def test_a_walk_up_a_wedge_mesh_ramp_takes_it_without_contacts(scenes_dir, tmp_path):
    """The wedge-mesh station's walk from the ramp's foot onto the platform goes up the ramp,
    and its animation touches nothing (the wedge is convex: MuJoCo collides it as it is)."""
    import mjwalk
    from mjwalk.gait.default import default_model

    path = _wedge_station(scenes_dir, tmp_path)
    walk = mjwalk.plan_walk(
        mjwalk.load_workplace(path, cache=False), "stand_ramp", "stand_platform2",
        default_model(), rng=0,
    )  # fmt: skip
    assert [r["kind"] for r in walk.meta["levels"]["route"]] == ["level", "ramp", "level"]
    assert mjwalk.check_collisions(walk, path) == []


ROUND_DAIS = '<geom name="dais" type="cylinder" size="0.9 0.085" pos="2 0 0.085"/>'


@pytest.mark.parametrize("radius", [0.9, 1.5])
def test_a_round_dais_is_reached_across_sides_that_touch_its_rim(radius):
    """A cylinder's top disc is a polygon whose sides are a crossing (0.5 m) or longer and touch
    the rim: a step reaches the dais (before: 32 sides of 0.18-0.29 m each, shorter than a
    crossing, so no contact with the floor and no level)."""
    model = scene(ROUND_DAIS.replace("0.9 0.085", f"{radius} 0.085"))
    dais = find_walk_surfaces(model, None)[1]
    assert dais.name == "dais" and dais.z == pytest.approx(0.17)
    v = np.asarray(dais.footprint.vertices)
    mid = 0.5 * (v + np.roll(v, -1, axis=0)) - [2.0, 0.0]
    assert np.hypot(*mid.T) == pytest.approx(radius, abs=1e-9)  # each side touches the rim
    assert np.hypot(*np.diff(np.vstack([v, v[:1]]), axis=0).T).min() >= 0.5
    assert surfaces_module.disc_sides(radius) == len(v)


@pytest.mark.slow
def test_walks_onto_a_round_dais_touch_nothing(tmp_path):
    """Up a 0.17 m step onto a 0.9 m round dais and back (before: no way up; with inscribed
    sides the toes before a side caught the rim up to 9 mm, and a sole flat on the top gave a
    tilted contact normal at 2e-16 m)."""
    import mjwalk
    from mjwalk.gait.default import default_model

    path = tmp_path / "dais.xml"
    path.write_text(
        '<mujoco><worldbody><geom name="floor" type="plane" size="8 8 0.1"/>'
        f'{ROUND_DAIS}<site name="a" pos="-4 -2 0"/><site name="b" pos="2.1 0.1 0.17"/>'
        "</worldbody></mujoco>"
    )
    wp, model = mjwalk.load_workplace(path, cache=False), default_model()
    for rng in (0, 1):
        for a, b in (("a", "b"), ("b", "a")):
            walk = mjwalk.plan_walk(wp, a, b, model, rng=rng)
            assert [r["kind"] for r in walk.meta["levels"]["route"]] == ["level", "step", "level"]
            assert mjwalk.check_collisions(walk, path) == []
