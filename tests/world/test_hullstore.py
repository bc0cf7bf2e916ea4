"""mjwalk.world.hullstore: 3-D hull edges kept in memory and, by the cache policy, on disk."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest
from scipy.spatial import ConvexHull

from mjwalk.world import footprint as fpmod
from mjwalk.world import hullstore
from mjwalk.world.footprint import geom_footprint
from mjwalk.world.hullstore import DISK_HULL_POINTS, hull_edges, pack, point_hull_edges, unpack
from mjwalk.world.levelview import level_view
from mjwalk.world.workplace import WorkplaceOptions, workplace_from_model

#: A platform reached by a step, a sloped pipe (a capsule: 12 544 points) and a ball lamp over
#: the floor (6 272 points) cut by the floor's band and by the platform's view's band, and a box.
SCENE = """<mujoco><worldbody>
  <geom name="floor" type="plane" size="4 3 0.1"/>
  <geom name="step_s" type="box" pos="1.5 0 0.085" size="0.15 0.5 0.085"/>
  <geom name="platform_p" type="box" pos="2.65 0 0.17" size="1.0 1.0 0.17"/>
  <geom name="pipe" type="capsule" size="0.05" fromto="-2 -1.5 0.1 -1 -1.2 2.1"/>
  <geom name="lamp" type="sphere" pos="-2 1.5 1.9" size="0.2"/>
  <geom name="crate" type="box" size="0.2 0.2 0.2" pos="-1 1 0.5" euler="20 30 0"/>
  <site name="a" pos="-3 0 0"/><site name="b" pos="2.8 0 0.34"/>
</worldbody></mujoco>"""


@pytest.fixture
def cache_root(tmp_path, monkeypatch):
    """An empty workplace cache (``$MJWALK_CACHE_DIR``: the workplaces' folder alone)."""
    folder = tmp_path / "workplaces"
    monkeypatch.setenv("MJWALK_CACHE_DIR", str(folder))
    fpmod.clear_memos()
    yield folder
    fpmod.clear_memos()


def _prepare(cache):
    """The scene loaded with the policy ``cache``, its levels and the platform's view."""
    model = mujoco.MjModel.from_xml_string(SCENE)
    wp = workplace_from_model(model, options=WorkplaceOptions(cache=cache))
    top = wp.levels.levels[-1].index
    view = level_view(wp, top, 1.9)
    return wp, view


def _summary(wp, view):
    """Everything the hulls feed: the obstacles of the workplace and of the view, the fields and
    the surfaces' headroom."""
    out = []
    for w in (wp, view):
        out += [(f.name, f.vertices.tobytes(), f.radius) for f in w.obstacles]
        out.append(w.clearance.values.tobytes())
    for s in wp.levels.surfaces:
        out.append((s.name, np.asarray(s.footprint.vertices).tobytes()))
    return out


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_a_policy_of_no_cache_writes_nothing(cache_root):
    # cache=False: the scene, its levels and a level's view are prepared with no file written
    # (the ball's and the pipe's hulls are big enough to be stored otherwise)
    _prepare(False)
    assert not cache_root.exists() or not any(cache_root.iterdir())
    # the default on this small scene (its 0.02 m field has < AUTO_NODES nodes): the workplace's
    # field not stored, the big hulls are (the box's and the step's are left to qhull), and so
    # is the platform's view's field (mjwalk.world.levelview)
    fpmod.clear_memos()
    _prepare(None)
    stored = sorted(p.name.split("-", 1)[1] for p in cache_root.iterdir())
    assert stored.count("levelview.npy") == 1
    assert set(stored) == {"hulledges.npy", "levelview.npy"}
    for p in cache_root.glob("*-hulledges.npy"):
        assert np.load(p)[0, 0] >= DISK_HULL_POINTS


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_stored_hulls_give_the_same_workplace_bit_for_bit(cache_root, monkeypatch):
    # without the cache, with hulls written (first run) and with them read back (later run,
    # qhull not asked for a big hull): the same obstacles, fields and surfaces, bit for bit
    plain = _summary(*_prepare(False))
    fpmod.clear_memos()
    written = _summary(*_prepare(None))
    asked = []
    real = hullstore._qhull_edges  # counted, not tested

    def counting(points):
        asked.append(len(points))
        return real(points)

    monkeypatch.setattr(hullstore, "_qhull_edges", counting)
    fpmod.clear_memos()
    read = _summary(*_prepare(None))
    assert all(n < DISK_HULL_POINTS for n in asked)
    assert written == plain
    assert read == plain


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
@pytest.mark.parametrize("damage", ["truncated", "flipped", "foreign"])
def test_a_damaged_hull_file_is_rebuilt(cache_root, damage):
    # a sloped capsule's points: a file cut short, a flipped edge byte or another hull's edges
    # under this key are each refused, the hull rebuilt by qhull and the file written anew
    xml = """<mujoco><worldbody><geom name="pipe" type="capsule" size="0.05"
      fromto="0 0 0.3 1 0.2 0.9"/></worldbody></mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    want = geom_footprint(model, data, 0, 0.4, 0.8, disk=True)
    (path,) = cache_root.iterdir()
    good = path.read_bytes()
    if damage == "truncated":
        path.write_bytes(good[: len(good) // 2])
    elif damage == "flipped":
        raw = bytearray(good)
        raw[-3] ^= 0x10  # in the last edge's high index
        path.write_bytes(bytes(raw))
    else:
        other = np.random.default_rng(1).normal(size=(DISK_HULL_POINTS, 3))
        np.save(path, pack(hull_edges(ConvexHull(other).simplices), 12544, "another key"))
    fpmod.clear_memos()
    got = geom_footprint(model, data, 0, 0.4, 0.8, disk=True)
    assert want is not None and got is not None
    np.testing.assert_array_equal(got.vertices, want.vertices)
    assert path.read_bytes() == good  # written again, whole


def test_point_hull_edges_are_qhulls_from_memory_and_from_disk(cache_root):
    rng = np.random.default_rng(47)
    points = rng.normal(size=(2 * DISK_HULL_POINTS, 3))
    want = hull_edges(ConvexHull(points).simplices)
    np.testing.assert_array_equal(point_hull_edges(points, disk=False), want)
    assert not cache_root.exists()  # not allowed on disk: memory only
    hullstore.clear_memo()
    np.testing.assert_array_equal(point_hull_edges(points, disk=True), want)
    hullstore.clear_memo()
    got = point_hull_edges(points, disk=True)  # read back
    np.testing.assert_array_equal(got, want)
    assert got.dtype == np.int64
    small = rng.normal(size=(DISK_HULL_POINTS - 1, 3))
    point_hull_edges(small, disk=True)
    assert len(list(cache_root.iterdir())) == 1  # a small hull is left to qhull


def test_unpack_refuses_another_point_count_key_or_checksum():
    edges = np.array([[0, 1], [0, 2], [1, 2]], dtype=np.int64)
    stored = pack(edges, 3, "k")
    np.testing.assert_array_equal(unpack(stored, 3, "k"), edges)
    assert unpack(stored, 4, "k") is None
    assert unpack(stored, 3, "another key") is None
    bad = stored.copy()
    bad[2, 1] = 0
    assert unpack(bad, 3, "k") is None
    assert unpack(stored.astype(np.int32), 3, "k") is None
    assert unpack(np.empty((0, 2), dtype=np.int64), 3, "k") is None


def test_hull_edges_are_the_sorted_set_of_the_triangles_sides():
    # seeded: the one-pass edges equal the old Python loop's sorted set of (low, high) pairs
    rng = np.random.default_rng(47)
    for n in (4, 9, 200, 2000):
        hull = ConvexHull(rng.normal(size=(n, 3)))
        edges = set()
        for simplex in hull.simplices:
            for i in range(3):
                a, b = simplex[i], simplex[(i + 1) % 3]
                edges.add((min(a, b), max(a, b)))
        np.testing.assert_array_equal(hull_edges(hull.simplices), np.array(sorted(edges)))
