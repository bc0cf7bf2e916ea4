"""Workplaces: obstacle selection, clearance field against MuJoCo's own geometry, bad scenes."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk import InputError, SceneError, WorkplaceOptions
from mjwalk.world import load_model, load_workplace, workplace_from_model
from mjwalk.world.probe import ClearanceProbe, covered
from mjwalk.world.workplace import HUMANOID_PREFIXES, MAX_RESOLUTION

SCENE_NAMES = ["assembly_station", "corridor", "open_floor"]


@pytest.fixture(scope="module", params=SCENE_NAMES)
def scene(request, scenes_dir):
    path = scenes_dir / f"{request.param}.xml"
    return path, load_workplace(path)


def test_clearance_matches_mujoco_geometry(scene):
    """At 600 random floor points the field agrees with mj_geomDistance within 1 cm outside the
    obstacles, and says 'inside' exactly where a vertical line meets a geom (mju_rayGeom)."""
    path, wp = scene
    rng = np.random.default_rng(1)
    xmin, ymin, xmax, ymax = wp.floor_bounds
    pts = rng.uniform([xmin, ymin], [xmax, ymax], size=(600, 2))
    field = wp.clearance(pts)
    probe = ClearanceProbe(path)  # every non-plane geom of the file, independently of mjwalk
    if not probe.geoms:  # the open floor: nothing anywhere
        assert not wp.obstacles
        assert np.all(field > 10.0)
        return
    ref = probe.clearance(pts)
    outside = field > 0.01
    assert outside.sum() > 300
    np.testing.assert_allclose(field[outside], ref[outside], atol=0.01)
    inside = covered(probe, pts)
    assert not np.any(inside & (field > 0.01))
    assert not np.any(~inside & (field < -0.01))


def test_rotated_geoms_near_their_surface(scenes_dir):
    """Points sampled close around the rotated box, cylinder, capsules and ellipsoid."""
    path = scenes_dir / "assembly_station.xml"
    wp = load_workplace(path)
    probe = ClearanceProbe(path)
    rng = np.random.default_rng(2)
    for name in ["trolley", "rack1_shelf", "pillar", "bin", "wheel_fl", "car_bumper_rear"]:
        fp = wp.footprint(name)
        lo = np.array(fp.bounds()[:2]) - 0.3
        hi = np.array(fp.bounds()[2:]) + 0.3
        pts = rng.uniform(lo, hi, size=(200, 2))
        pts = pts[wp.on_floor(pts)]
        field = wp.clearance(pts)
        ref = probe.clearance(pts)
        ok = field > 0.01
        np.testing.assert_allclose(field[ok], ref[ok], atol=0.01, err_msg=name)


def test_obstacle_selection(scenes_dir):
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    names = {f.name for f in wp.obstacles}
    assert "floor" not in names
    assert {"car_body", "trolley", "pillar", "bin", "rack2_shelf", "wheel_fl"} <= names
    only_car = load_workplace(scenes_dir / "assembly_station.xml", include=r"^car_")
    assert {f.name for f in only_car.obstacles} == {n for n in names if n.startswith("car_")}
    no_racks = load_workplace(scenes_dir / "assembly_station.xml", exclude=r"^rack")
    assert not any(f.name.startswith("rack") for f in no_racks.obstacles)
    # The shorthand keywords and the options object select the same obstacles.
    via_options = load_workplace(
        scenes_dir / "assembly_station.xml", WorkplaceOptions(exclude=r"^rack")
    )
    assert [f.name for f in via_options.obstacles] == [f.name for f in no_racks.obstacles]
    # Something overhead (above 2 m) is not an obstacle; something low (below 5 cm) neither.
    assert wp.clearance.resolution <= 0.02


def test_height_band_and_humanoid_excluded(tmp_path):
    xml = """<mujoco><worldbody>
      <geom name="floor" type="plane" size="3 3 .1"/>
      <geom name="beam" type="box" size="1 .1 .1" pos="0 0 2.5"/>
      <geom name="mat" type="box" size="1 1 .01" pos="0 0 .01"/>
      <geom name="post" type="box" size=".1 .1 1" pos="1 1 1"/>
      <body name="human/pelvis" pos="-1 -1 1">
        <geom name="torso" type="capsule" size=".1 .3"/>
      </body>
    </worldbody></mujoco>"""
    f = tmp_path / "s.xml"
    f.write_text(xml)
    wp = load_workplace(f)
    assert [o.name for o in wp.obstacles] == ["post"]


def test_stations_from_sites(scenes_dir):
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    for name in [
        "stand_rack1",
        "stand_rack2",
        "stand_rack3",
        "stand_car1",
        "rack2_screw1",
        "car_screw1",
        "rack2_tool",
    ]:
        assert name in wp.stations
    s = wp.station("stand_rack2")
    assert s.yaw == pytest.approx(-np.pi / 2)  # facing the rack (towards -y)
    assert wp.station("rack2_screw1").pos[2] > 0.9  # screws on a shelf at working height
    assert wp.clearance(wp.station("stand_rack2").xy[None])[0] > 0.25
    with pytest.raises(SceneError, match="stand_rack4"):
        wp.station("stand_rack4")


def test_bilinear_lookup_is_vectorized(scenes_dir):
    wp = load_workplace(scenes_dir / "corridor.xml")
    pts = np.zeros((4, 5, 2))
    assert wp.clearance(pts).shape == (4, 5)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        (None, "not found"),
        ("<mujoco><worldbody><geom type='box' size='1 1 1'", "not a valid MJCF"),
        (
            "<mujoco><worldbody><geom name='b' type='box' size='.3 .3 1'/></worldbody></mujoco>",
            "no floor",
        ),
        (
            "<mujoco><worldbody><geom type='plane' size='1 1 .1'/><geom type='bogus'/>"
            "</worldbody></mujoco>",
            "not a valid MJCF",
        ),
    ],
)
def test_bad_scenes(tmp_path, text, match):
    f = tmp_path / "bad.xml"
    if text is not None:
        f.write_text(text)
    with pytest.raises(SceneError, match=match) as info:
        load_workplace(f)
    assert "bad.xml" in str(info.value)


@pytest.mark.parametrize(
    "floor",
    [
        "<geom name='hall' type='plane' pos='0 0 0.5' size='4 4 .1'/>",
        "<geom name='hall' type='box' pos='0 0 0.45' size='4 4 .05'/>",
    ],
)
def test_a_floor_off_z0_is_the_floor_at_its_height(tmp_path, floor):
    """A floor plane or slab top at z = 0.5 m: the workplace's floor is there (the planners'
    heights are above it, the body plays back at floor_z plus them), its obstacle band too."""
    f = tmp_path / "lifted.xml"
    crate = "<geom name='crate' type='box' size='.3 .3 .5' pos='1 1 1'/>"
    f.write_text(f"<mujoco><worldbody>{floor}{crate}</worldbody></mujoco>")
    wp = load_workplace(f)
    assert wp.floor == "hall" and wp.floor_z == pytest.approx(0.5, abs=1e-12)
    assert wp.floor_bounds == (-4.0, -4.0, 4.0, 4.0) and [o.name for o in wp.obstacles] == ["crate"]
    assert [lv.height for lv in wp.levels.levels] == [pytest.approx(0.5, abs=1e-12)]


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"resolution": 0.0}, "clearance resolution 0.0 m must be in (0, 0.02]"),
        ({"resolution": 0.05}, "clearance resolution 0.05 m must be in (0, 0.02]"),
        ({"z_range": (2.0, 0.05)}, "obstacle z_range (2.0, 0.05) m must be finite, low < high"),
        ({"z_range": (0.05, float("nan"))}, "must be finite, low < high"),
        ({"include": "rack("}, "include='rack(' is not a regular expression"),
        ({"exclude": "[x"}, "exclude='[x' is not a regular expression"),
    ],
)
def test_options_refuse_bad_values(changes, message):
    with pytest.raises(InputError) as err:
        WorkplaceOptions(**changes)
    assert message in str(err.value)
    assert "\n" not in str(err.value)


def test_options_object_is_what_both_loaders_read(scenes_dir):
    path = scenes_dir / "assembly_station.xml"
    options = WorkplaceOptions(z_range=(0.05, 1.0), resolution=0.01, cache=False)
    loaded = load_workplace(path, options)
    built = workplace_from_model(load_model(path), source=path, options=options)
    assert loaded.clearance.resolution == built.clearance.resolution == 0.01
    assert loaded.z_range == (0.05, 1.0)
    assert loaded.fingerprint == built.fingerprint
    assert loaded.fingerprint != load_workplace(path).fingerprint  # the band changed footprints
    with pytest.raises(InputError, match="not both"):
        load_workplace(path, options, include=r"^car_")
    with pytest.raises(AttributeError):
        options.cache = True  # type: ignore[misc]


def test_default_options_are_the_documented_constants():
    opts = WorkplaceOptions()
    assert opts.resolution == MAX_RESOLUTION == 0.02
    assert opts.humanoid_prefixes == HUMANOID_PREFIXES == ("human",)
