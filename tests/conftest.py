"""Shared fixtures: scene paths and the optional real-capture folder."""

from __future__ import annotations

import itertools
import math
import os
from pathlib import Path

import pytest

os.environ.setdefault("MUJOCO_GL", "egl")

ROOT = Path(__file__).resolve().parents[1]
SCENES = ROOT / "scenes"
#: ``$MJWALK_SHARED_DATA`` overrides (e.g. when the project is checked out elsewhere).
SHARED_DATA = Path(os.environ.get("MJWALK_SHARED_DATA", ROOT.parent / "shared" / "data"))


#: Test files run first, in this order (the rest follow, most tests first, as pytest-xdist's
#: ``--dist loadfile`` orders them by default; pyproject's ``--no-loadscope-reorder`` keeps this
#: order). On a fresh clone numba compiles the planner, arm and animation kernels on their first
#: call (``mjwalk/_jit.py``: about 80 s CPU) and the two workers compiled the same kernels at
#: once when both began with a walking test (test_population and test_legheights: 90 and 82 s
#: CPU cold against 9 and 6 s warm). The first file compiles them in one worker while the other
#: runs other files first, and finds them cached afterwards (``mjwalk/_jit.py``'s compile lock
#: makes a worker that needs a kernel being compiled wait for it instead of compiling it again).
#: Run alone on a cold cache (session 31), the layout's AST checks, the gait corpus, the mocap
#: invariances and BVH reader, the stair gait and the footfall walk compiled no kernel; the gait
#: model and the scan writers compile a few.
FIRST_FILES = (
    "tests/cycle/test_population.py",
    "tests/project/test_layout.py",
    "tests/gait/test_corpus.py",
    "tests/mocap/test_invariance.py",
    "tests/mocap/test_bvh.py",
    "tests/gait/test_stairs.py",
    "tests/plan/test_footfallwalk.py",
    "tests/gait/test_model.py",
    "tests/scan/test_scanramps.py",
    "tests/scan/test_scanpits.py",
)


def pytest_collection_modifyitems(config, items):
    """Orders the test files (each kept whole, its tests in their order): :data:`FIRST_FILES`
    first, then the others with the most tests first."""
    del config
    files = [item.nodeid.split("::", 1)[0] for item in items]
    counts: dict[str, int] = {}
    for f in files:
        counts[f] = counts.get(f, 0) + 1
    first = {f: k for k, f in enumerate(FIRST_FILES)}
    place = {f: k for k, f in enumerate(dict.fromkeys(files))}

    def key(k: int) -> tuple[int, int, int, int]:
        f = files[k]
        return (first.get(f, len(first)), -counts[f], place[f], k)

    items[:] = [items[k] for k in sorted(range(len(items)), key=key)]


@pytest.fixture(scope="session")
def scenes_dir() -> Path:
    return SCENES


@pytest.fixture(scope="session")
def shared_data() -> Path:
    if not SHARED_DATA.is_dir():
        pytest.skip("../shared/data (real motion capture) is not present on this machine")
    return SHARED_DATA


@pytest.fixture
def caged_station(tmp_path):
    """The station with the point (3.0, 0.9) walled in by four boxes: an unreachable goal."""
    from mjwalk.world import load_workplace

    text = (SCENES / "assembly_station.xml").read_text()
    cage = """
    <geom name="cage_n" type="box" size="0.6 0.05 1" pos="3.0 1.5 1"/>
    <geom name="cage_s" type="box" size="0.6 0.05 1" pos="3.0 0.3 1"/>
    <geom name="cage_w" type="box" size="0.05 0.6 1" pos="2.45 0.9 1"/>
    <geom name="cage_e" type="box" size="0.05 0.6 1" pos="3.55 0.9 1"/>
  </worldbody>"""
    path = tmp_path / "caged.xml"
    path.write_text(text.replace("</worldbody>", cage))
    return load_workplace(path)


#: A shelf at 0.7 m in rack 1 (under its shelf at 1.0 m) and a pick site on it, 30 cm into the
#: rack: a compartment 26 cm high at knuckle height, below a standing reach. (20 cm into it
#: until the default reach model's working area grew to a top shelf: its reach from a stooping
#: shoulder then cleared the upper shelf by 6 mm.)
LOW_COMPARTMENT = (
    '<geom name="rack1_shelf_mid" type="box" size="0.4 0.25 0.02" pos="0 0 0.7" '
    'material="shelf"/>\n      <site name="rack1_low" pos="0.1 -0.05 0.76" size="0.02"/>\n      '
)


@pytest.fixture(scope="session")
def low_compartment(tmp_path_factory) -> Path:
    """The cycle file of a left-hand pick from the station's rack 1 at :data:`LOW_COMPARTMENT`
    (the scene beside it)."""
    folder = tmp_path_factory.mktemp("low_compartment")
    xml = (SCENES / "assembly_station.xml").read_text()
    mark = '<site name="stand_rack1"'
    assert mark in xml
    (folder / "low.xml").write_text(xml.replace(mark, LOW_COMPARTMENT + mark, 1))
    (folder / "low.toml").write_text(
        'name = "low compartment"\nscene = "low.xml"\nstart = "stand_rack1"\n'
        "[humanoid]\nstature = 1.75\n"
        '[[task]]\nkind = "pick"\nsite = "rack1_low"\nhand = "left"\n'
    )
    return folder / "low.toml"


#: An 8 x 6 m hall whose floor is four boxes round a 2 x 2 m opening (x in [-1, 1], y in
#: [-0.5, 1.5]) over a plane 0.51 m down; a stair of three 0.17 m risers and 0.28 m treads
#: descends along +x from the opening's edge at x = -1.
_PIT_XML = """<mujoco model="pit"><worldbody>
<geom name="floor" type="plane" pos="0 0 -0.51" size="4 3 0.05"/>
<geom name="floor_0" type="box" pos="0 -1.75 -0.255" size="4 1.25 0.255"/>
<geom name="floor_1" type="box" pos="0 2.25 -0.255" size="4 0.75 0.255"/>
<geom name="floor_2" type="box" pos="-2.5 0.5 -0.255" size="1.5 1 0.255"/>
<geom name="floor_3" type="box" pos="2.5 0.5 -0.255" size="1.5 1 0.255"/>
<geom name="s1" type="box" pos="-0.86 0.5 -0.34" size="0.14 1 0.17"/>
<geom name="s2" type="box" pos="-0.58 0.5 -0.425" size="0.14 1 0.085"/>
<geom name="rack" type="box" pos="3 -2.5 1.0" size="0.5 0.4 1.0"/>
<site name="floor_a" pos="-3 -2 0"/>
<site name="pit_b" pos="0.5 0.5 -0.51"/>
</worldbody></mujoco>"""


@pytest.fixture(scope="session")
def pit_xml() -> str:
    """An MJCF hall with a pit under a floor of boxes and a stair down into it (the world's
    floor-with-openings tests and the level planner's walk into a pit share it)."""
    return _PIT_XML


def _pit_ramp_xml() -> str:
    """:func:`pit_ramp_xml`'s text: the ramp box placed so its top face runs from the opening's
    west rim (x = -2, z = 0) down to the pit's bottom at x = 1.2 (z = -0.51)."""
    import math

    run, depth, t = 3.2, 0.51, 0.05
    ang = math.atan2(depth, run)
    cx, cz = -2.0 + run / 2 + t * math.sin(ang), -depth / 2 - t * math.cos(ang)
    half = math.hypot(run, depth) / 2
    return f"""<mujoco model="pit_ramp"><worldbody>
<geom name="floor" type="plane" pos="0 0 -0.51" size="5 3 0.05"/>
<geom name="floor_0" type="box" pos="0 -1.75 -0.255" size="5 1.25 0.255"/>
<geom name="floor_1" type="box" pos="0 2.25 -0.255" size="5 0.75 0.255"/>
<geom name="floor_2" type="box" pos="-3.5 0.5 -0.255" size="1.5 1 0.255"/>
<geom name="floor_3" type="box" pos="3.5 0.5 -0.255" size="1.5 1 0.255"/>
<geom name="ramp" type="box" pos="{cx:.5f} 0.5 {cz:.5f}" euler="0 {math.degrees(ang):.5f} 0"
 size="{half:.5f} 1 {t}"/>
<site name="floor_a" pos="-4 -2 0"/>
<site name="pit_b" pos="1.6 0.5 -0.51"/>
</worldbody></mujoco>"""


@pytest.fixture(scope="session")
def pit_ramp_xml() -> str:
    """An MJCF hall (10 x 6 m) whose floor is four boxes round a 4 x 2 m opening (x in [-2, 2],
    y in [-0.5, 1.5]) over a plane 0.51 m down, reached by a ramp of 9.06 deg (0.51 m over a
    3.2 m run, within norms.MAX_RAMP_SLOPE's 10 deg) the opening's width, descending along +x
    from its west rim."""
    return _pit_ramp_xml()


def _open_stair_xml(overlap: float) -> str:
    """:func:`open_stair_xml`'s scene for one overlap (m)."""
    going, r, th = OPEN_STAIR_GOING, 0.17, 0.04
    geoms = [
        f'<geom name="tread{i}" type="box" size="{(going + overlap) / 2:.4f} 0.5 {th / 2}" '
        f'pos="{i * going + (going + overlap) / 2:.4f} 0 {(i + 1) * r - th / 2:.4f}"/>'
        for i in range(5)
    ]
    x = 5 * going
    geoms.append(f'<geom name="deck" type="box" size="1.5 1.5 0.05" pos="{x + 1.5} 0 0.97"/>')
    geoms += [
        f'<geom name="post{k}" type="box" size="0.05 0.05 0.46" pos="{x + px} {py} 0.46"/>'
        for k, (px, py) in enumerate([(0.1, -1.4), (0.1, 1.4), (2.9, -1.4), (2.9, 1.4)])
    ]
    return (
        '<mujoco><worldbody><geom name="floor" type="plane" size="8 6 0.1"/>'
        + "".join(geoms)
        + f'<site name="a" pos="-2 0 0"/><site name="b" pos="{x + 1.5} 0 1.02"/>'
        "</worldbody></mujoco>"
    )


#: The open stair's going (nosing to nosing), metres.
OPEN_STAIR_GOING = 0.27


@pytest.fixture(scope="session")
def open_stair_xml():
    """An open steel stair (no risers), as a function of the overlap (m): five 0.04 m thick
    treads, each ``overlap`` deeper than the 0.27 m going so that it reaches back under the
    next one's nosing (DIN 18065 §6.6's Unterschneidung, at least 30 mm without risers),
    risers 0.17, up to a 1.02 m deck on four posts; sites ``a`` on the floor, ``b`` on the
    deck (the level planner's and the scan's open-stair tests share it)."""
    return _open_stair_xml


def _box(name: str, x0: float, x1: float, y0: float, y1: float, z1: float) -> str:
    """A box geom from the floor (z 0) up to ``z1`` over [x0, x1] x [y0, y1], metres."""
    return (
        f'<geom name="{name}" type="box" size="{(x1 - x0) / 2:.4f} {(y1 - y0) / 2:.4f} '
        f'{z1 / 2:.4f}" pos="{(x0 + x1) / 2:.4f} {(y0 + y1) / 2:.4f} {z1 / 2:.4f}"/>'
    )


@pytest.fixture(scope="session")
def dogleg_xml() -> str:
    """A dog-leg (half-turn) stair to a 1.36 m mezzanine: a flight of four 0.17 m risers and
    0.28 m treads up +y (x 0..1) to a 1.2 m deep landing at 0.68 m, then a second flight of four
    back down -y (x 1.1..2.1) onto the mezzanine (x 1.1..4.5, y -3..0), a wall between the
    flights and round the landing (DIN 18065 §6.3: a landing at least as deep as the stair is
    wide); sites ``floor`` (-2, -1.5, 0), ``landing`` on the landing, ``mezz`` (3.5, -2, 1.36)."""
    geoms = [_box(f"a{i}", 0.0, 1.0, 0.28 * (i - 1), 0.28 * i, 0.17 * i) for i in (1, 2, 3)]
    geoms += [_box(f"b{j}", 1.1, 2.1, 0.28 * (7 - j), 0.28 * (8 - j), 0.17 * j) for j in (5, 6, 7)]
    geoms += [
        _box("landing", 0.0, 2.1, 0.84, 2.04, 0.68),
        _box("mezzanine", 1.1, 4.5, -3.0, 0.0, 1.36),
        _box("wall_mid", 1.0, 1.1, 0.0, 0.84, 2.0),
        _box("wall_west", -0.05, 0.0, 0.0, 2.04, 1.9),
        _box("wall_back", -0.05, 2.15, 2.04, 2.09, 1.9),
        _box("wall_east", 2.1, 2.15, 0.0, 2.04, 2.2),
    ]
    return (
        '<mujoco><worldbody><geom name="floor" type="plane" size="6 6 0.1"/>'
        + "".join(geoms)
        + '<site name="floor" pos="-2 -1.5 0"/><site name="landing" pos="1.05 1.5 0.68"/>'
        '<site name="mezz" pos="3.5 -2 1.36"/></worldbody></mujoco>'
    )


#: Quarter-turn winders (issue 47), 1.0 m usable width (DIN 18065, buildings in general): the
#: stair rises +x over y -1..0, turns left round the inner corner (0, 0) and rises +y over
#: x 0..1. Each nosing runs from the inner side (y 0 or x 0) to the outer (y -1 or x 1), bottom
#: up. "balanced": the turn spread over five turned treads, each 0.29-0.30 m on the walk line
#: (the middle of the width; ASR A1.8's "particularly safe" tread is 0.29 m; 2R + T <= 0.64 m)
#: and 0.11 m at its narrow end (DIN 18065: >= 0.10 m), a straight 0.29 m tread before and
#: after. "wedges": only three wedge treads in the turn, between a straight 0.29 m tread below
#: and above, each at least 0.11 m at the narrow end: on the walk line they are 0.38-0.43 m
#: (2R + T 0.72-0.77 m), breaking the step rule (three treads cannot turn a 1 m wide stair a
#: quarter: the walk line round the corner is longer than three 0.29 m treads once the narrow
#: ends keep 0.10 m).
_WINDER_NOSINGS = {
    "balanced": [
        ((-0.5861, 0.0), (-0.5861, -1.0)),
        ((-0.2961, 0.0), (-0.2961, -1.0)),
        ((-0.1867, 0.0), (0.1744, -1.0)),
        ((-0.0772, 0.0), (0.656, -1.0)),
        ((0.0, 0.0772), (1.0, -0.656)),
        ((0.0, 0.1867), (1.0, -0.1744)),
        ((0.0, 0.2961), (1.0, 0.2961)),
        ((0.0, 0.5861), (1.0, 0.5861)),
    ],
    "wedges": [
        ((-0.49, 0.0), (-0.49, -1.0)),
        ((-0.2, 0.0), (-0.2, -1.0)),
        ((-0.09, 0.0), (0.5435, -1.0)),
        ((0.0, 0.09), (1.0, -0.5435)),
        ((0.0, 0.2), (1.0, 0.2)),
        ((0.0, 0.49), (1.0, 0.49)),
    ],
}


def _winder_xml(kind: str, riser: float = 0.17) -> str:
    """A quarter-turn winder (``_WINDER_NOSINGS[kind]``) of ``riser`` m risers: one convex
    prism per tread from the floor up to its top, between two nosings (round the outer corner
    (1, -1) where they lie on its two sides; open to the floor at the inner corner), then a
    deck one riser above the last tread; sites ``low`` on the floor and ``high`` on the deck."""
    nosings = _WINDER_NOSINGS[kind]
    meshes, geoms = [], ['<geom name="floor" type="plane" size="6 6 0.1"/>']
    for i, (a, b) in enumerate(itertools.pairwise(nosings), start=1):
        corner = [(1.0, -1.0)] if a[1][1] == -1.0 and b[1][0] == 1.0 else []
        poly = [a[0], a[1], *corner, b[1], b[0]]
        z = riser * i
        vert = " ".join(f"{x:.4f} {y:.4f} {h:.4f}" for h in (0.0, z) for x, y in poly)
        meshes.append(f'<mesh name="tread{i}" vertex="{vert}"/>')
        geoms.append(f'<geom name="tread{i}" type="mesh" mesh="tread{i}"/>')
    top, y0 = riser * len(nosings), nosings[-1][0][1]
    geoms += [
        _box("deck", -1.0, 2.5, y0, 3.0, top),
        '<site name="low" pos="-2.5 -0.5 0"/>',
        f'<site name="high" pos="0.5 2.2 {top:.4f}"/>',
    ]
    return (
        f"<mujoco><asset>{''.join(meshes)}</asset><worldbody>"
        + "".join(geoms)
        + "</worldbody></mujoco>"
    )


@pytest.fixture(scope="session")
def winder_xml():
    """``winder_xml(kind, riser=0.17)``: a quarter-turn winder's MJCF (``_winder_xml``)."""
    return _winder_xml


def _spiral_xml(turn: float, treads: int, outer: float, riser: float = 0.19) -> str:
    """A spiral stair ("Spindeltreppe", issue 47): ``treads`` wedge treads anticlockwise round a
    0.10 m post at the origin, out to ``outer`` m, over ``turn`` degrees from the first nosing
    (along +x, walked up +y) to the last, ``riser`` m risers; then a deck one riser above the
    last tread beyond the last nosing, and the post (a cylinder) up through it all. Every tread
    is the one wedge mesh (its outer side three points of the circle), 2 m deep, down into the
    floor from its top (no floor open under a tread), turned and raised by its geom's pose:
    MuJoCo's float32 mesh vertices are then alike on every tread, 1 m (exact in float32) off
    its centre, so each riser is the float64 difference of two
    poses (treads of meshes of their own heights came out 0.19000006 m high, over
    ``norms.MAX_RISER`` + ``norms.ROUNDING_SLACK``: no step). Sites ``low`` on the floor before
    the first nosing, ``high`` on the deck past the last."""
    post, step, thick = 0.10, math.radians(turn) / treads, 2.0
    geoms = ['<geom name="floor" type="plane" size="6 6 0.1"/>']

    def at(r: float, th: float) -> tuple[float, float]:
        return r * math.cos(th), r * math.sin(th)

    poly = [at(post, 0.0), at(outer, 0.0), at(outer, 0.5 * step), at(outer, step), at(post, step)]
    vert = " ".join(f"{x:.6f} {y:.6f} {h}" for h in (0.0, thick) for x, y in poly)
    meshes = [f'<mesh name="wedge" vertex="{vert}"/>']
    for i in range(1, treads + 1):
        geoms.append(
            f'<geom name="spiral{i}" type="mesh" mesh="wedge" pos="0 0 {riser * i - thick:.4f}" '
            f'euler="0 0 {math.degrees((i - 1) * step):.6f}"/>'
        )
    last, top = treads * step, riser * (treads + 1)
    (ux, uy), (vx, vy) = at(1.0, last), at(1.0, last + 0.5 * math.pi)  # the deck's frame
    half = 0.5 * (outer + 1.0)
    centre = (half * ux + vx, half * uy + vy)
    deck = (
        f'<geom name="deck" type="box" size="{half:.4f} 1.0 {top / 2:.4f}" '
        f'pos="{centre[0]:.4f} {centre[1]:.4f} {top / 2:.4f}" '
        f'euler="0 0 {math.degrees(last):.4f}"/>'
    )
    high = (0.6 * ux + 1.5 * vx, 0.6 * uy + 1.5 * vy)
    geoms += [
        deck,
        f'<geom name="post" type="cylinder" size="{post} {(top + 1.0) / 2:.4f}" '
        f'pos="0 0 {(top + 1.0) / 2:.4f}"/>',
        '<site name="low" pos="0.6 -2.5 0"/>',
        f'<site name="high" pos="{high[0]:.4f} {high[1]:.4f} {top:.4f}"/>',
    ]
    return (
        f"<mujoco><asset>{''.join(meshes)}</asset><worldbody>"
        + "".join(geoms)
        + "</worldbody></mujoco>"
    )


#: Spiral stairs of 0.19 m risers (DIN 18065:2020 Table 1's and ASR A1.8's largest riser) round
#: a 0.10 m post. The treads narrow to 2 x 0.10 sin(step/2) = 0.04-0.05 m at the post; the part
#: shallower than 0.10 m is no usable width (``norms.USABLE_TREAD_DEPTH``), so the usable width
#: runs from r10 = 0.05 / sin(step/2) to the outer edge and the walk line, its middle, measures a
#: tread of T = 2 r sin(step/2) = 0.05 + outer sin(step/2). "half": seven 25.7 deg treads out to
#: 0.98 m, T = 0.268 m, 2R + T = 0.648 m (within 0.26-0.37 m and 0.59-0.65 m). "quarter": four
#: 22.5 deg treads out to 1.12 m, T = 0.268 m. "steep": three 30 deg treads turning a quarter
#: out to 0.98 m, T = 0.304 m, 2R + T = 0.684 m: over the step rule.
SPIRALS = {"half": (180.0, 7, 0.98), "quarter": (90.0, 4, 1.12), "steep": (90.0, 3, 0.98)}


@pytest.fixture(scope="session")
def spiral_xml():
    """``spiral_xml(kind)``: a spiral stair's MJCF (``_spiral_xml(*SPIRALS[kind])``)."""
    return lambda kind: _spiral_xml(*SPIRALS[kind])


#: Walks on which nothing rises a riser: no stair-ascent pelvic tilt or trunk lean
#: (tests/body/test_pelvistilt.py, test_trunklean.py).
OFF_ASCENT_WALKS = ("stair down", "flat", "ramp up")


@pytest.fixture(params=OFF_ASCENT_WALKS)
def off_ascent_walk(request):
    """A synthetic walk down a 0.17/0.28 m stair, on the floor or up a 5.5 deg ramp."""
    import numpy as np  # only this fixture needs them (the rest are scene paths)

    from mjwalk.plan.synthetic import synthetic_ramp_walk, synthetic_stair_walk, synthetic_walk

    return {
        "stair down": lambda: synthetic_stair_walk(0.17, 0.28, 6, "down"),
        "flat": synthetic_walk,
        "ramp up": lambda: synthetic_ramp_walk(np.radians(5.5)),
    }[request.param]()
