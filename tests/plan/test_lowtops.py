"""Low tops on the floor (mjwalk.plan.lowtops): a mat, a cable bridge, a floor plate are found
and the walks over them stand and swing on them; floor tape (flush) and obstacles are not."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from mjwalk.plan.lowtops import low_tops
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
