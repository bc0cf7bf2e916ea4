"""Obstacles ruled out by bounds before the exact distances (issue 50): the bounds hold, the
pack follows the workplace's footprints, and ``sides.intruding`` / ``sides.side_gap`` give
exactly the answers of asking every obstacle (the code they replaced, kept here)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.plan.detour import abreast
from mjwalk.plan.guide import densify, first_below, minimum_jerk_guide
from mjwalk.plan.nearcut import MARGIN, gap_candidates, gap_room, intruding_candidates, pack
from mjwalk.plan.sides import GAP_OPEN, boxes_meeting, intruding, obstacle_bounds, side_gap
from mjwalk.world import load_workplace
from mjwalk.world.footprint import Footprint


@pytest.fixture(scope="module")
def hall(tmp_path_factory):
    """A 10 x 8 m hall with boxes (one turned), round pillars and a lying capsule."""
    scene = tmp_path_factory.mktemp("nearcut") / "hall.xml"
    geoms = [
        '<geom name="floor" type="plane" size="5 4 0.05"/>',
        '<geom name="bench" type="box" size="0.8 0.3 0.45" pos="-2 1.5 0.45"/>',
        '<geom name="crate" type="box" size="0.3 0.3 0.5" pos="0.5 -0.4 0.5" euler="0 0 30"/>',
        '<geom name="wall" type="box" size="3 0.1 1" pos="0 3.2 1"/>',
        '<geom name="pillar" type="cylinder" size="0.2 1" pos="2 1 1"/>',
        '<geom name="post" type="cylinder" size="0.1 1" pos="-0.8 -1.8 1"/>',
        '<geom name="pipe" type="capsule" fromto="1.5 -2 0.3 3 -1.2 0.3" size="0.12"/>',
        '<geom name="rack" type="box" size="0.25 0.9 0.9" pos="3.6 -0.2 0.9"/>',
    ]
    scene.write_text(f'<mujoco model="hall"><worldbody>{"".join(geoms)}</worldbody></mujoco>')
    return load_workplace(scene)


def intruding_asking_all(workplace, path, ends, berth):
    """``sides.intruding`` as it was before the bounds (fc03651): every obstacle whose box,
    grown by the berth, holds a path point is asked."""
    pts = np.asarray(path, dtype=float)
    if not workplace.obstacles or first_below(workplace, pts, berth) is None:
        return None
    s, g = (np.asarray(v, dtype=float)[:2] for v in ends)
    length = float(np.hypot(*(g - s)))
    u = (g - s) / length
    dense = densify(pts, 0.1)
    lo, hi = dense.min(axis=0) - berth, dense.max(axis=0) + berth
    ks = boxes_meeting(workplace, (lo[0], lo[1], hi[0], hi[1]))
    b = obstacle_bounds(workplace)[ks]
    reach = berth + 1e-9
    x, y = dense[None, :, 0], dense[None, :, 1]
    grown = (
        (x >= b[:, None, 0] - reach)
        & (x <= b[:, None, 2] + reach)
        & (y >= b[:, None, 1] - reach)
        & (y <= b[:, None, 3] + reach)
    )
    best, first = None, len(dense)
    both = np.stack([s, g])
    for k in ks[grown.any(axis=1)]:
        fp = workplace.obstacles[k]
        along = (np.asarray(fp.vertices, dtype=float) - s) @ u
        if along.min() - fp.radius < -berth or along.max() + fp.radius > length + berth:
            continue
        near = np.flatnonzero(fp.signed_distance(dense[:first]) < berth)
        if not len(near):
            continue
        if float(fp.signed_distance(both).min()) < berth:
            continue
        best, first = fp, int(near[0])
    return best


def side_gap_asking_all(workplace, blocker, route, start, goal):
    """``sides.side_gap`` as it was before the bounds (fc03651)."""
    pts = np.asarray(route, dtype=float)
    s, g = np.asarray(start, dtype=float)[:2], np.asarray(goal, dtype=float)[:2]
    u = (g - s) / max(float(np.hypot(*(g - s))), 1e-12)
    along = (pts - s) @ u
    outline = np.asarray(blocker.vertices, dtype=float)
    reach = float(blocker.radius)
    lo, hi = float(((outline - s) @ u).min()) - reach, float(((outline - s) @ u).max()) + reach
    beside = pts[(along >= lo) & (along <= hi)]
    if len(beside) == 0:
        beside = pts
    own = blocker.signed_distance(beside)
    xmin, ymin, xmax, ymax = (float(v) for v in workplace.floor_bounds)
    other = np.minimum.reduce(
        [beside[:, 0] - xmin, xmax - beside[:, 0], beside[:, 1] - ymin, ymax - beside[:, 1]]
    )
    other = np.minimum(other, GAP_OPEN)
    x0, y0 = beside.min(axis=0) - GAP_OPEN
    x1, y1 = beside.max(axis=0) + GAP_OPEN
    for k in boxes_meeting(workplace, (x0, y0, x1, y1)):
        fp = workplace.obstacles[k]
        if fp is blocker:
            continue
        other = np.minimum(other, fp.signed_distance(beside))
    return float(np.min(own + other))


def random_walk(rng, workplace):
    """A start, a goal and the minimum-jerk path between them with random headings."""
    xmin, ymin, xmax, ymax = workplace.floor_bounds
    while True:
        s = rng.uniform([xmin + 0.3, ymin + 0.3], [xmax - 0.3, ymax - 0.3])
        g = rng.uniform([xmin + 0.3, ymin + 0.3], [xmax - 0.3, ymax - 0.3])
        if np.hypot(*(g - s)) > 0.5:
            break
    h0, h1 = (None if rng.random() < 0.3 else rng.uniform(-np.pi, np.pi) for _ in range(2))
    return s, g, minimum_jerk_guide(s, g, h0, h1)


def test_intruding_answers_as_asking_every_obstacle(hall):
    """600 seeded walks at berths 0.3-0.8 m: the same footprint (or None) as the code that
    asked every obstacle, and some walks of each kind."""
    rng = np.random.default_rng(50)
    found = 0
    for _ in range(600):
        s, g, path = random_walk(rng, hall)
        berth = float(rng.uniform(0.3, 0.8))
        got = intruding(hall, path, (s, g), berth)
        assert got is intruding_asking_all(hall, path, (s, g), berth)
        found += got is not None
    assert 30 < found < 570


def test_side_gap_is_the_gap_of_asking_every_obstacle(hall):
    """Each obstacle passed on either side by seeded walks: the gap to the bit."""
    rng = np.random.default_rng(51)
    for _ in range(200):
        s, g, _path = random_walk(rng, hall)
        blocker = hall.obstacles[int(rng.integers(len(hall.obstacles)))]
        for left in (True, False):
            route = densify(np.array([s, abreast(blocker, s, g, 0.5, left), g]), 0.1)
            assert side_gap(hall, blocker, route, s, g) == side_gap_asking_all(
                hall, blocker, route, s, g
            )


def test_the_bounds_hold_each_footprint_distance(hall):
    """Box distance (outside the box) <= signed distance <= nearest-vertex distance (less a
    segment's radius), so a gap candidate left out lies farther than another's upper bound."""
    rng = np.random.default_rng(52)
    pk = pack(hall)
    pts = rng.uniform([-5.0, -4.0], [5.0, 4.0], size=(400, 2))
    for k, fp in enumerate(hall.obstacles):
        exact = fp.signed_distance(pts)
        b = pk.bounds[k]
        box = np.hypot(
            np.maximum.reduce([b[0] - pts[:, 0], np.zeros(len(pts)), pts[:, 0] - b[2]]),
            np.maximum.reduce([b[1] - pts[:, 1], np.zeros(len(pts)), pts[:, 1] - b[3]]),
        )
        outside = box > 0.0  # (in the box the signed distance may be negative: no bound)
        assert np.all(box[outside] <= exact[outside] + MARGIN)
        v = pk.vertices[pk.first[k] : pk.first[k] + pk.count[k]]
        if fp.radius > 0.0:
            v = v[[0, -1]]
        vertex = np.hypot(*(pts[:, None, :] - v[None]).transpose(2, 0, 1)).min(axis=1)
        assert np.all(exact <= vertex - fp.radius + MARGIN)


def test_gap_candidates_leave_out_only_the_farther_obstacles(hall):
    """Points between two obstacles: both kept; a far obstacle whose box lies beyond the
    nearer one's vertices from every point is left out, and the passed one never comes."""
    names = [fp.name for fp in hall.obstacles]
    pk = pack(hall)
    passed = np.array([n == "bench" for n in names])
    beside = np.array([[1.2, 0.5], [1.3, 0.45]])  # between the crate and the pillar
    other = np.full(2, GAP_OPEN)
    got = {names[k] for k in gap_candidates(pk, beside, other, passed, GAP_OPEN)}
    assert {"crate", "pillar"} <= got
    assert "bench" not in got and "wall" not in got  # the wall is 2.7 m off: farther
    met = {names[k] for k in boxes_meeting(hall, (-0.3, -1.05, 2.8, 1.95))}
    assert got <= met


def test_gap_room_is_the_numpy_room_and_leaves_the_rounded_segments(hall):
    """Points across the hall: the room gap_room gives, lowered by the rounded segments it
    hands back, is to the bit the NumPy room of asking every obstacle (floor edges, the cap,
    every other footprint's signed distance); only rounded segments are handed back."""
    rng = np.random.default_rng(53)
    pk = pack(hall)
    floor = np.asarray(hall.floor_bounds, dtype=float)
    for _ in range(50):
        beside = rng.uniform([-4.5, -3.5], [4.5, 3.5], size=(int(rng.integers(1, 30)), 2))
        k_passed = int(rng.integers(len(hall.obstacles)))
        passed = np.arange(len(hall.obstacles)) == k_passed
        room, rounded = gap_room(
            beside, floor, pk.bounds, pk.vertices, pk.first, pk.count, pk.radius, passed, GAP_OPEN
        )
        assert all(hall.obstacles[k].radius > 0.0 for k in rounded)
        for k in rounded:
            room = np.minimum(room, hall.obstacles[k].signed_distance(beside))
        xmin, ymin, xmax, ymax = floor
        want = np.minimum.reduce(
            [beside[:, 0] - xmin, xmax - beside[:, 0], beside[:, 1] - ymin, ymax - beside[:, 1]]
        )
        want = np.minimum(want, GAP_OPEN)
        for k, fp in enumerate(hall.obstacles):
            if k != k_passed:
                want = np.minimum(want, fp.signed_distance(beside))
        assert np.array_equal(room, want)


def test_intruding_candidates_flag_what_bounds_cannot_decide(hall):
    """A walk along the bench that ends 0.36 m from its corner flags the bench's distance
    from the ends as open (the exact distance decides); the crate, 1 m beyond the walk's
    box, is left out."""
    names = [fp.name for fp in hall.obstacles]
    pk = pack(hall)
    s, g = np.array([-4.0, 0.9]), np.array([-1.0, 0.9])  # past the bench's front, 0.3 m off
    dense = densify(np.array([s, g]), 0.1)
    rows = intruding_candidates(pk, dense, np.stack([s, g]), 3.0, (g - s) / 3.0, 0.5)
    by_name = {names[k]: (bool(a), bool(e)) for k, a, e in rows}
    assert by_name["bench"][1] is True
    assert "crate" not in by_name


def test_the_pack_follows_the_workplace_footprints(hall):
    """Kept while the footprints are the same objects; made anew when one is replaced."""
    first = pack(hall)
    assert pack(hall) is first
    assert np.array_equal(first.bounds, obstacle_bounds(hall))
    old = hall.obstacles[0]
    moved = Footprint(old.name, old.geom_id, old.vertices + 10.0, old.radius)
    hall.obstacles[0] = moved
    try:
        again = pack(hall)
        assert again is not first
        assert again.bounds[0][0] == pytest.approx(first.bounds[0][0] + 10.0)
    finally:
        hall.obstacles[0] = old
    assert pack(hall).bounds[0][0] == first.bounds[0][0]
