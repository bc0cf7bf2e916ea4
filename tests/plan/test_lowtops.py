"""Low tops on the floor (mjwalk.plan.lowtops): a mat, a cable bridge, a floor plate are found
and the walks over them stand and swing on them; floor tape (flush) and obstacles are not."""

from __future__ import annotations

import math
from pathlib import Path

import mujoco
import numpy as np
import pytest

from mjwalk.plan.lowtops import is_low, low_tops
from mjwalk.plan.rampside import LOW_KEY, META_KEY, head_heights

BRIDGE_MESH = (
    '<asset><mesh name="bridge" vertex="-0.15 -1 0  0.15 -1 0  -0.05 -1 0.04  0.05 -1 0.04  '
    '-0.15 1 0  0.15 1 0  -0.05 1 0.04  0.05 1 0.04"/></asset>'
)


def station(mat: float = 0.015, tape: bool = False, bridge: bool = False) -> str:
    """An assembly station: a bench, before it a 1.5 x 0.9 m mat ``mat`` m thick with the
    site ``b`` on it; floor tape 2 mm thick (``tape``); a 4 cm cable bridge across the way
    from ``a`` (``bridge``); sites ``a`` 3-5 m away and ``c``."""
    g = ['<geom name="bench" type="box" size="1.0 0.4 0.45" pos="0 2 0.45"/>']
    if mat:
        g.append(f'<geom name="mat" type="box" size="0.75 0.45 {mat / 2}" pos="0 1.1 {mat / 2}"/>')
    if tape:
        g.append('<geom name="tape" type="box" size="4 0.025 0.0015" pos="0 -0.5 0.0015"/>')
    if bridge:
        g.append('<geom name="cablebridge" type="mesh" mesh="bridge" pos="2.5 -1.5 0"/>')
    return f"""<mujoco model="station">{BRIDGE_MESH if bridge else ""}<worldbody>
<geom name="floor" type="plane" size="8 8 0.1"/>
{chr(10).join(g)}
<site name="b" pos="0 1.1 {mat}" euler="0 0 90"/>
<site name="a" pos="5 -1.5 0"/><site name="c" pos="-4 -1 0"/></worldbody></mujoco>"""


def _tops(xml: str) -> dict[str, dict]:
    model = mujoco.MjModel.from_xml_string(xml)
    return {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, p[LOW_KEY]): p
            for p in low_tops(model, 0.0, 0.05)}  # fmt: skip


def test_a_mat_and_a_cable_bridge_are_low_tops_and_tape_and_a_bench_are_not():
    """The 15 mm mat's top is its box's (1.5 x 0.9 m, 15 mm up); the 4 cm bridge's is its
    mesh's bounding box (0.3 x 2 m); the 3 mm tape is flush floor and the bench an obstacle."""
    tops = _tops(station(tape=True, bridge=True))
    assert set(tops) == {"mat", "cablebridge"}
    mat = tops["mat"]
    assert mat["z"] == pytest.approx(0.015)
    assert (mat["run"], 2 * mat["half_width"]) == pytest.approx((1.5, 0.9))
    assert mat["slope"] == 0.0
    bridge = tops["cablebridge"]
    assert bridge["z"] == pytest.approx(0.04)
    assert (bridge["run"], 2 * bridge["half_width"]) == pytest.approx((0.3, 2.0))


def test_a_turned_mat_s_top_is_turned_with_it_and_has_no_level_past_it():
    """A mat turned 30 deg about z keeps its own rectangle; past its far edge lies floor
    (a ramp's plane has the level its head meets there, a low top none)."""
    xml = station(mat=0.0).replace(
        "</worldbody>",
        '<geom name="mat" type="box" size="0.75 0.45 0.01" pos="1 1 0.01" euler="0 0 30"/>'
        "</worldbody>",
    )
    mat = _tops(xml)["mat"]
    assert math.cos(mat["uphill"] - math.radians(30)) == pytest.approx(1.0, abs=1e-9)
    assert (mat["run"], mat["half_width"], mat["z"]) == pytest.approx((1.5, 0.45, 0.02))
    assert np.all(head_heights(mat, np.array([[3.0, 2.0], [1.0, 1.0]])) == -np.inf)


def test_a_geom_in_the_obstacle_band_or_off_the_floor_is_no_low_top():
    """A 6 cm plate reaches the 0.05 m obstacle band; a 2 cm plate hung 0.3 m up does not
    lie on the floor."""
    xml = station(mat=0.0).replace(
        "</worldbody>",
        '<geom name="high" type="box" size="0.5 0.5 0.03" pos="2 2 0.03"/>'
        '<geom name="hung" type="box" size="0.5 0.5 0.01" pos="-2 2 0.31"/></worldbody>',
    )
    assert _tops(xml) == {}


@pytest.fixture(scope="module")
def model():
    from mjwalk.gait.default import default_model

    return default_model(progress=False)


def _walk(tmp_path, xml: str, a: str, b: str, model, rng: int):
    import mjwalk

    path = tmp_path / "station.xml"
    path.write_text(xml)
    wp = mjwalk.load_workplace(path, cache=False)
    walk = mjwalk.plan_walk(wp, a, b, model, rng=rng)
    return walk, mjwalk.check_collisions(walk, path)


@pytest.mark.parametrize(("a", "b"), [("a", "b"), ("b", "c")])
def test_walks_onto_and_across_a_mat_touch_nothing(tmp_path, model, a, b):
    """A walk from 5 m away onto the 15 mm mat before the bench, and one from it across its
    edge, stand their feet on the mat's top: no contact (before: 47-115 foot-mat contacts,
    15 mm deep)."""
    _, hits = _walk(tmp_path, station(), a, b, model, rng=0)
    assert hits == [], sorted({(h.body_part, h.scene_geom, round(h.depth, 4)) for h in hits})[:6]


def test_floor_tape_leaves_the_walk_as_it_is(tmp_path, model):
    """3 mm tape is flush floor: the walk across it to ``b`` has no low top under it and
    touches nothing."""
    import mjwalk
    from mjwalk.plan.lowtops import with_low_tops

    walk, hits = _walk(tmp_path, station(mat=0.0, tape=True), "a", "b", model, rng=0)
    wp = mjwalk.load_workplace(tmp_path / "station.xml", cache=False)
    assert with_low_tops(wp, walk, 1.75) is walk
    assert hits == []


def test_a_cable_bridge_is_crossed_with_clearance(tmp_path, model):
    """The walk from ``a`` to ``c`` crosses the 4 cm cable bridge: the bridge is under it,
    and no foot touches it."""
    import mjwalk
    from mjwalk.plan.lowtops import with_low_tops

    walk, hits = _walk(tmp_path, station(mat=0.0, bridge=True), "a", "c", model, rng=0)
    wp = mjwalk.load_workplace(tmp_path / "station.xml", cache=False)
    assert any(LOW_KEY in p for p in with_low_tops(wp, walk, 1.75).meta[META_KEY])
    assert hits == [], sorted({(h.body_part, h.scene_geom, round(h.depth, 4)) for h in hits})[:6]


def test_a_push_off_beside_the_mat_s_corner_touches_nothing(tmp_path, model):
    """The walk off the mat at rng 3 (b -> a) pushes off its right foot beside the mat's corner.
    On the mat47 branch alone, foot_r and toes_r passed 16.6 mm into the mat's side there at
    1.367 s (pitch -44 deg, toes turned +44 deg at the ball). Merged with the rule that a foot
    on a ramp's plane -- a low top is one -- stands on no tread (``StepSurfaces.lift_ramp``: no
    edged swing off it), it touches nothing (that this rule is the cause is not traced further)."""
    _, hits = _walk(tmp_path, station(), "b", "a", model, rng=3)
    assert hits == []


def platform(mat: bool = True, tape: bool = False) -> str:
    """The multi-level station's platform (scenes/multilevel_station.xml: 0.34 m, a step block
    of two 0.17 m risers at its west end, a 5.5 deg ramp at its east end) alone on a floor, with
    a 1.2 x 0.7 m mat 15 mm thick on it (``mat``, the site ``p_mat`` on it) and 3 mm tape across
    it at x = -0.6 m (``tape``); sites ``stand_step``/``stand_ramp`` on the floor before the
    step and the ramp, ``p_west``/``p_east`` on the platform either side of the mat."""
    g = []
    if mat:
        g.append('<geom name="mat" type="box" size="0.6 0.35 0.0075" pos="0.6 3.2 0.3475"/>')
    if tape:
        g.append('<geom name="tape" type="box" size="0.025 0.5 0.0015" pos="-0.6 3.2 0.3415"/>')
    return f"""<mujoco model="matplatform"><worldbody>
<geom name="floor" type="plane" pos="0.5 0 0" size="7 4.5 0.05"/>
<geom name="platform" type="box" size="2.2 0.5 0.17" pos="0 3.2 0.17"/>
<geom name="platform_step" type="box" size="0.15 0.4 0.085" pos="-2.35 3.2 0.085"/>
<geom name="platform_ramp" type="box" size="1.773683 0.5 0.05" pos="3.960725 3.2 0.120230"
 euler="0 5.5 0"/>
{chr(10).join(g)}
<site name="stand_step" pos="-3.3 3.2 0"/><site name="stand_ramp" pos="6.6 3.2 0" euler="0 0 180"/>
<site name="p_west" pos="-1.4 3.2 0.34"/><site name="p_east" pos="1.8 3.2 0.34" euler="0 0 180"/>
<site name="p_mat" pos="0.6 3.2 0.355" euler="0 0 -90"/></worldbody></mujoco>"""


def test_a_mat_on_a_platform_is_a_low_top_of_the_platform_and_not_of_the_floor():
    """The 15 mm mat lies on the 0.34 m platform: a low top there (its top 0.355 m above the
    floor), none on the floor; the platform's 3 mm tape is flush with it, no low top."""
    model = mujoco.MjModel.from_xml_string(platform(tape=True))
    name = lambda p: mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, p[LOW_KEY])  # noqa: E731
    assert low_tops(model, 0.0, 0.05) == []
    (mat,) = low_tops(model, 0.0, 0.05, level=0.34)
    assert name(mat) == "mat"
    assert (mat["z"], mat["run"], 2 * mat["half_width"]) == pytest.approx((0.355, 1.2, 0.7))
    assert low_tops(model, 0.0, 0.05, level=0.17) == []  # the step's tread: nothing on it
    assert not is_low(0.34, 0.343, 0.34, 0.05) and is_low(0.34, 0.355, 0.34, 0.05)


@pytest.mark.parametrize(
    ("a", "b"),
    [
        ("stand_step", "p_east"),
        ("stand_ramp", "p_west"),
        ("p_east", "p_west"),
        ("stand_ramp", "p_mat"),
    ],
)
def test_walks_onto_a_platform_across_its_mat_and_onto_it_touch_nothing(tmp_path, model, a, b):
    """Walks onto the platform by its step and by its ramp, and along it, cross the mat on it;
    the last ends on it (a level of its own, 15 mm up, entered by its edge). Their feet stand
    on the mat's top: no contact. Before, the platform's walks stood the feet on the platform's
    top (the soles were looked for at the floor's height only): 74-102 foot and toe contacts
    15 mm deep in the mat per walk at rng 0."""
    walk, hits = _walk(tmp_path, platform(), a, b, model, rng=0)
    assert hits == [], sorted({(h.body_part, h.scene_geom, round(h.depth, 4)) for h in hits})[:6]
    if b != "p_mat":
        import mjwalk
        from mjwalk.plan.lowtops import tops_under

        wp = mjwalk.load_workplace(tmp_path / "station.xml", cache=False)
        assert [p[LOW_KEY] for p in tops_under(wp, walk, 1.75)] == [4]  # the mat, on the platform


def test_tape_on_a_platform_leaves_the_walk_as_it_is(tmp_path, model):
    """3 mm tape across the platform is the platform's floor: the walk along the platform over
    it has no low top under it and touches nothing (before: 8-14 foot contacts 3 mm deep in
    the tape per walk, it was no floor but the floor's)."""
    import mjwalk
    from mjwalk.plan.lowtops import with_low_tops

    walk, hits = _walk(tmp_path, platform(mat=False, tape=True), "p_west", "p_east", model, rng=0)
    wp = mjwalk.load_workplace(tmp_path / "station.xml", cache=False)
    assert with_low_tops(wp, walk, 1.75) is walk
    assert hits == [], sorted({(h.body_part, h.scene_geom, round(h.depth, 4)) for h in hits})[:6]


def mezzanine() -> str:
    """A mezzanine deck 2.34 m high on four columns (x 1-4.5, y -3.5..-0.5), reached by a
    straight stair of 13 risers of 0.18 m and 0.28 m treads (step rule 0.64 m) from the west,
    over a 1.5 x 1 m floor mat 15 mm thick (x 2-3.5, y -2.5..-1.5) under the deck, with 2.24 m
    clear under it; a 0.34 m platform by a step block with a mat on the floor before its step.
    Sites: ``mez_w``/``mez_e`` on the deck either side of the mat's outline, ``floor_s``/
    ``floor_n`` on the floor south and north of the deck, ``stand_stair`` before the stair,
    ``on_stepmat`` on the mat before the step, ``plat`` on the platform."""
    r, t, n = 0.18, 0.28, 13
    treads = [
        f'<geom name="tread{k}" type="box" size="{t / 2} 0.5 {r * k / 2:.4f}" '
        f'pos="{1 - (n - k) * t + t / 2:.4f} -2 {r * k / 2:.4f}"/>'
        for k in range(1, n)
    ]
    h = (r * n - 0.1) / 2
    corners = [(1.1, -3.4), (4.4, -3.4), (1.1, -0.6), (4.4, -0.6)]
    cols = [f'<geom name="col{i}" type="box" size="0.08 0.08 {h:.4f}" pos="{x} {y} {h:.4f}"/>'
            for i, (x, y) in enumerate(corners)]  # fmt: skip
    return f"""<mujoco model="matmezz"><worldbody>
<geom name="floor" type="plane" size="8 8 0.1"/>
<geom name="platform" type="box" size="1.5 0.5 0.17" pos="0 3.2 0.17"/>
<geom name="platform_step" type="box" size="0.15 0.4 0.085" pos="-1.65 3.2 0.085"/>
<geom name="stepmat" type="box" size="0.45 0.5 0.0075" pos="-2.25 3.2 0.0075"/>
<geom name="deck" type="box" size="1.75 1.5 0.05" pos="2.75 -2 {r * n - 0.05:.4f}"/>
{"".join(cols)}{"".join(treads)}
<geom name="mat" type="box" size="0.75 0.5 0.0075" pos="2.75 -2 0.0075"/>
<site name="stand_step" pos="-3.3 3.2 0"/><site name="on_stepmat" pos="-2.3 3.2 0.015"/>
<site name="plat" pos="0.8 3.2 0.34" euler="0 0 180"/><site name="stand_stair" pos="-3.0 -2 0"/>
<site name="mez_w" pos="1.5 -2 {r * n}"/><site name="mez_e" pos="4.0 -2 {r * n}" euler="0 0 180"/>
<site name="floor_s" pos="2.75 -4.3 0" euler="0 0 90"/><site name="floor_n" pos="2.75 0.3 0"/>
</worldbody></mujoco>"""


@pytest.mark.parametrize(
    ("a", "b", "under"), [("mez_w", "mez_e", []), ("stand_stair", "mez_e", []),
                          ("floor_s", "floor_n", ["mat"]), ("on_stepmat", "plat", ["stepmat"])],
)  # fmt: skip
def test_a_floor_mat_under_a_mezzanine_and_before_a_step(tmp_path, model, a, b, under):
    """A walk on the mezzanine passes 2.34 m above the floor mat's outline, and up the stair
    onto it: the mat lies on the floor, not on the deck, so it is under none of their soles
    (they stand on the deck). A floor walk under the deck crosses the mat and stands on it; a
    walk from the mat before the platform's step up onto the platform leaves it from its top.
    No contact in any of them. (A deck lower than the walker's head over a floor mat is an
    obstacle of the floor walk, 0.05 m to head height, and no floor footprint lies under it;
    one 0.05 m or less above the floor is the mat's own kind, a low top.)"""
    import mjwalk
    from mjwalk.plan.lowtops import tops_under

    walk, hits = _walk(tmp_path, mezzanine(), a, b, model, rng=0)
    wp = mjwalk.load_workplace(tmp_path / "station.xml", cache=False)
    names = [mujoco.mj_id2name(wp.model, mujoco.mjtObj.mjOBJ_GEOM, p[LOW_KEY])
             for p in tops_under(wp, walk, 1.75)]  # fmt: skip
    assert names == under
    assert hits == [], sorted({(h.body_part, h.scene_geom, round(h.depth, 4)) for h in hits})[:6]


#: The cycle: walk onto the mat, pick a screw there, carry it off the mat to ``{away}`` and
#: place it, walk back to the start.
CYCLE = """name = "work on a mat"
scene = "scene.xml"
start = "{start}"
takt = 60.0

[humanoid]
stature = 1.75

[models]
step = "default"
reach = "default"

[[task]]
kind = "walk"
site = "{on}"

[[task]]
kind = "pick"
site = "screw"
hand = "right"
part = "screw"

[[task]]
kind = "carry"
site = "{away}"
hand = "right"
part = "screw"

[[task]]
kind = "place"
site = "drop"
hand = "right"
part = "screw"

[[task]]
kind = "walk"
site = "{start}"
"""


def _floor(tmp_path: Path) -> Path:
    """The 15 mm floor mat before the bench (:func:`station`), a screw on the
    bench before the mat's site ``b`` and a drop point before ``c``."""
    sites = '<site name="screw" pos="0 1.75 0.95"/><site name="drop" pos="-4.55 -1 0.9"/>'
    (tmp_path / "scene.xml").write_text(station().replace("</worldbody>", sites + "</worldbody>"))
    return tmp_path


def _platform(tmp_path: Path) -> Path:
    """The 15 mm mat and 3 mm tape on the 0.34 m platform (:func:`platform`), a
    screw 0.95 m above the mat before its site ``p_mat`` and a drop point past the ramp."""
    sites = '<site name="screw" pos="0.6 2.65 1.3"/><site name="drop" pos="7.15 3.2 0.95"/>'
    xml = platform(tape=True).replace("</worldbody>", sites + "</worldbody>")
    (tmp_path / "scene.xml").write_text(xml)
    return tmp_path


@pytest.mark.parametrize(
    ("scene", "start", "on", "away"),
    [(_floor, "a", "b", "c"), (_platform, "stand_step", "p_mat", "stand_ramp")],
    ids=["floor", "platform"],
)
def test_a_cycle_with_its_work_on_a_mat_touches_nothing(tmp_path, scene, start, on, away):
    """An animated cycle through the cycle's own walk frames
    (:func:`mjwalk.cycle.poses.walk_frames` stands the feet on the mat's top). Seeded (runs 0
    and 1): the operator walks onto the mat, picks the screw standing on it, carries it off the
    mat and back: 0 contacts. Before, on the floor, 440 and 528 foot and toe contacts 15 mm
    deep in the mat from the walk's last turn to the carry's first: the standing and reaching
    poses stood the feet at the floor's height (:func:`mjwalk.cycle.levelsite.ground_height`
    now stands them on the mat, :func:`mjwalk.plan.lowtops.stand_top`); on the platform,
    17-32 in the walks crossing the mat (base 1bbe2b4, the same walks planned alone)."""
    from mjwalk.cycle.simulate import simulate_cycle
    from mjwalk.cycle.spec import load_cycle_spec

    path = scene(tmp_path)
    (path / "cycle.toml").write_text(CYCLE.format(start=start, on=on, away=away))
    spec = load_cycle_spec(path / "cycle.toml")
    for run in (0, 1):
        r = simulate_cycle(spec, run, run=run, ergonomics=False)
        assert len(r.walks) == 3
        assert r.collisions == [], sorted({(c.body_part, c.scene_geom) for c in r.collisions})
