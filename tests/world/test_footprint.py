"""mjwalk.world.footprint: convex footprints, their signed distance, and geom footprints."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from mjwalk.world.footprint import Footprint, geom_footprint, polygon_area


def test_polygon_and_rounded_segment_signed_distances():
    square = Footprint("sq", 0, np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]))
    assert square.is_polygon
    assert square.bounds() == (0.0, 0.0, 1.0, 1.0)
    d = square.signed_distance(np.array([[0.5, 0.5], [2.0, 0.5], [2.0, 2.0]]))
    np.testing.assert_allclose(d, [-0.5, 1.0, np.sqrt(2.0)])
    stadium = Footprint("cap", 1, np.array([[0.0, 0.0], [2.0, 0.0]]), radius=0.5)
    assert not stadium.is_polygon
    assert stadium.bounds() == (-0.5, -0.5, 2.5, 0.5)
    np.testing.assert_allclose(
        stadium.signed_distance(np.array([[1.0, 2.0], [3.0, 0.0]])), [1.5, 0.5]
    )


def _numpy_polygon_distance(p, v):
    """The NumPy signed distance to a convex CCW polygon that the compiled kernel replaced."""
    ab = np.roll(v, -1, axis=0) - v
    length2 = np.einsum("ij,ij->i", ab, ab)
    rel = p[..., None, :] - v
    t = np.clip(np.einsum("...ij,ij->...i", rel, ab) / length2, 0.0, 1.0)
    closest = rel - t[..., None] * ab
    dist = np.sqrt(np.einsum("...ij,...ij->...i", closest, closest).min(axis=-1))
    normal = np.stack([ab[:, 1], -ab[:, 0]], axis=1) / np.sqrt(length2)[:, None]
    line = np.einsum("...ij,ij->...i", rel, normal).max(axis=-1)
    return np.where(line > 0.0, dist, line)


def test_polygon_distance_is_bit_equal_to_the_numpy_arithmetic():
    # seeded: 200 random convex polygons, points inside and out, in several array shapes
    rng = np.random.default_rng(3)
    for _ in range(200):
        k = int(rng.integers(3, 12))
        ang = np.sort(rng.uniform(0.0, 2.0 * np.pi, k))
        v = np.c_[np.cos(ang), np.sin(ang)] * rng.uniform(0.1, 3.0, 2) + rng.uniform(-9, 9, 2)
        fp = Footprint("p", 0, v)
        for shape in [(2,), (1, 2), (7, 2), (3, 5, 2)]:
            pts = v.mean(axis=0) + rng.normal(0.0, 2.0, shape)
            got = fp.signed_distance(pts)
            assert got.shape == shape[:-1]
            assert np.array_equal(got, _numpy_polygon_distance(pts, v))
    # a repeated vertex gives NaN everywhere, as 0/0 did
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 1.0]])
    assert np.isnan(Footprint("d", 0, square).signed_distance(np.array([[0.5, 0.5]]))).all()


def test_box_geom_footprint_is_its_rotated_rectangle():
    xml = """<mujoco><worldbody>
      <geom name="floor" type="plane" size="5 5 0.1"/>
      <geom name="box" type="box" pos="1 2 0.5" size="0.5 0.25 0.5" euler="0 0 90"/>
      <geom name="lamp" type="sphere" pos="0 0 3" size="0.1"/>
    </worldbody></mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    fp = geom_footprint(model, data, 1, 0.05, 2.0)
    assert fp is not None and fp.name == "box" and fp.geom_id == 1
    np.testing.assert_allclose(fp.bounds(), (0.75, 1.5, 1.25, 2.5), atol=1e-9)
    assert geom_footprint(model, data, 2, 0.05, 2.0) is None  # above the band


def test_a_kept_footprint_equals_a_fresh_one_for_every_slab():
    # a sloped capsule (clipped as a tessellated hull): kept answers are bit-equal to fresh ones,
    # whatever the slab, and a slab face beyond the geom shares the entry of any other such face
    # (a slab holding it whole gives its exact stadium, not kept)
    from mjwalk.world import footprint as fpmod

    xml = """<mujoco><worldbody><geom name="pipe" type="capsule" size="0.05"
      fromto="0 0 0.3 1 0.2 0.9"/></worldbody></mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    slabs = [(0.05, 2.0), (0.05, 3.0), (0.4, 0.8), (0.4, 2.5), (1.5, 2.0), (0.0, 0.2)]
    fresh = []
    for z0, z1 in slabs:
        fpmod.clear_memos()
        fresh.append(geom_footprint(model, data, 0, z0, z1))
    fpmod.clear_memos()
    for (z0, z1), want in zip(slabs + slabs, fresh + fresh, strict=True):
        got = geom_footprint(model, data, 0, z0, z1)
        if want is None:
            assert got is None
            continue
        np.testing.assert_array_equal(got.vertices, want.vertices)
        assert got.radius == want.radius
        assert got.is_polygon != got.vertices.flags.writeable  # kept ones read-only
    assert geom_footprint(model, data, 0, 0.4, 2.0) is geom_footprint(model, data, 0, 0.4, 3.0)


def test_polygon_area_either_way_round():
    square = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.5], [0.0, 1.5]])
    assert polygon_area(square) == pytest.approx(3.0)
    assert polygon_area(square[::-1]) == pytest.approx(3.0)
    assert polygon_area(np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])) == pytest.approx(0.5)
