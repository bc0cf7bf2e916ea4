"""mjwalk.timeline.geomposes: the compiled forward kinematics of geoms against MuJoCo's, and the
models it supports."""

from __future__ import annotations

import mujoco
import numpy as np

from mjwalk.body.humanoid import humanoid_model
from mjwalk.timeline.geomposes import POOLED_MIN, body_poses, geom_poses, supported

CHAIN = """<mujoco><worldbody>
<body name="a" pos=".1 .2 1"><freejoint/><geom type="box" size=".1 .2 .3" pos=".05 0 0"/>
 <body name="b" pos="0 .3 .1" euler="10 20 30"><joint type="hinge" axis="0 .6 .8" ref="15"/>
  <geom type="capsule" size=".05 .2" pos=".1 0 0" euler="30 0 10"/></body></body>
</worldbody></mujoco>"""


def test_geom_poses_of_a_free_body_and_a_hinge_match_mj_kinematics():
    m = mujoco.MjModel.from_xml_string(CHAIN)
    assert supported(m)
    qpos = m.qpos0 + np.random.default_rng(3).normal(scale=0.5, size=(6, m.nq))
    xpos, xmat = geom_poses(m, qpos, np.array([1, 0]))
    assert xpos.shape == (6, 2, 3) and xmat.shape == (6, 2, 9)
    d = mujoco.MjData(m)
    for f, q in enumerate(qpos):
        d.qpos[:] = q
        mujoco.mj_kinematics(m, d)
        np.testing.assert_allclose(xpos[f], d.geom_xpos[[1, 0]], atol=1e-12)
        np.testing.assert_allclose(xmat[f], d.geom_xmat[[1, 0]], atol=1e-12)


def test_mocap_bodies_are_not_supported():
    mocap = '<mujoco><worldbody><body mocap="true"><geom size=".1"/></body></worldbody></mujoco>'
    assert not supported(mujoco.MjModel.from_xml_string(mocap))


def test_body_poses_match_mj_kinematics():
    """body_poses gives the bodies' xpos and xmat as mj_kinematics leaves them (round-off)."""
    m = mujoco.MjModel.from_xml_string(CHAIN)
    qpos = m.qpos0 + np.random.default_rng(4).normal(scale=0.5, size=(5, m.nq))
    xpos, xmat = body_poses(m, qpos, np.array([2, 1]))
    assert xpos.shape == (5, 2, 3) and xmat.shape == (5, 2, 9)
    d = mujoco.MjData(m)
    for f, q in enumerate(qpos):
        d.qpos[:] = q
        mujoco.mj_kinematics(m, d)
        np.testing.assert_allclose(xpos[f], d.xpos[[2, 1]], atol=1e-12)
        np.testing.assert_allclose(xmat[f], d.xmat[[2, 1]], atol=1e-12)


def test_bodies_that_did_not_move_keep_the_same_numbers():
    """Frames where only the hinge moves, or nothing does, give exactly the poses each frame
    gives alone (the kernel reuses the unmoved bodies' poses), for a subset of geoms too."""
    m = mujoco.MjModel.from_xml_string(CHAIN)
    rng = np.random.default_rng(6)
    qpos = np.repeat(m.qpos0[None] + rng.normal(scale=0.5, size=(1, m.nq)), 6, axis=0)
    qpos[2:4, 7] += [0.3, 0.6]  # the hinge turns, the free body stays
    qpos[5, :3] += 0.1  # the free body moves
    for geoms in (np.array([0, 1]), np.array([1])):
        xpos, xmat = geom_poses(m, qpos, geoms)
        for f, q in enumerate(qpos):
            alone = geom_poses(m, q[None], geoms)
            assert np.array_equal(xpos[f], alone[0][0]) and np.array_equal(xmat[f], alone[1][0])


def test_the_kept_tree_gives_the_same_numbers_and_follows_a_moved_body():
    """The model's ids and chains are kept between calls: a second call, one for another set
    of geoms in between, and a call after the model's body offset changed give what a fresh
    model gives (the float arrays are read at each call)."""
    m = mujoco.MjModel.from_xml_string(CHAIN)
    qpos = m.qpos0 + np.random.default_rng(7).normal(scale=0.5, size=(4, m.nq))
    first = geom_poses(m, qpos, np.array([0, 1]))
    geom_poses(m, qpos, np.array([0]))
    again = geom_poses(m, qpos, np.array([0, 1]))
    for a, b in zip(first, again, strict=True):
        assert np.array_equal(a, b)
    m.body_pos[2] += 0.05  # the hinged body moved on its parent
    fresh = mujoco.MjModel.from_xml_string(CHAIN)
    fresh.body_pos[2] += 0.05
    for a, b in zip(
        geom_poses(m, qpos, np.array([1])), geom_poses(fresh, qpos, np.array([1])), strict=True
    ):
        assert np.array_equal(a, b)


def test_geom_table_columns_and_rows_are_geom_poses_bit_for_bit():
    """A table of several geoms over all frames (holds repeated) gives, for any of its geoms or
    frames, the very numbers geom_poses computes for those alone; a geom it lacks: None."""
    from mjwalk.body.humanoid import humanoid_model
    from mjwalk.timeline.geomposes import geom_table

    m, _ = humanoid_model()
    rng = np.random.default_rng(5)
    qpos = np.repeat(m.qpos0 + rng.normal(scale=0.3, size=(12, m.nq)), 3, axis=0)
    qpos[::4, 7:] += 0.01  # some frames move the limbs only
    geoms = np.arange(0, m.ngeom, 2)
    table = geom_table(m, qpos, geoms[::-1])
    assert table.geoms.tolist() == sorted(geoms.tolist())
    for some in (geoms, geoms[[3, 1, 7]], geoms[-1:]):
        got, want = table.columns(some), geom_poses(m, qpos, some)
        assert got is not None
        assert all(a.tobytes() == b.tobytes() for a, b in zip(got, want, strict=True))
    rows = np.array([1, 2, 5, 6, 17, 30])  # with repeats and gaps
    alone = geom_poses(m, qpos[rows], geoms)
    assert table.xpos[rows].tobytes() == alone[0].tobytes()
    assert table.xmat[rows].tobytes() == alone[1].tobytes()
    assert table.columns(np.array([1])) is None


def test_table_columns_keep_the_layout_of_numpy_indexing():
    """A subset of a table's columns is a copy laid out as ``xpos[:, col]`` lays it out (a
    (G', F, k) block seen as (F, G', k)): the readers' strided loops, and their last bits,
    stay those they had with NumPy's indexing."""
    from mjwalk.timeline.geomposes import GeomTable

    rng = np.random.default_rng(3)
    xpos, xmat = rng.random((40, 9, 3)), rng.random((40, 9, 9))
    table = GeomTable(np.arange(9) * 3 + 2, xpos, xmat)
    col = np.array([7, 0, 4])
    got = table.columns(table.geoms[col])
    assert got is not None
    for a, full in zip(got, (xpos, xmat), strict=True):
        want = full[:, col]
        assert a.shape == want.shape and a.strides == want.strides
        assert np.array_equal(a, want) and not np.shares_memory(a, full)


def test_large_outputs_reuse_memory_only_when_nothing_holds_it():
    """Outputs of at least POOLED_MIN numbers are written into kept memory: a result (or a view
    of it) still held is never written over by a later call, and once dropped its memory
    serves the next call, whose numbers are those of a fresh computation."""
    m, _ = humanoid_model()
    geoms = np.arange(m.ngeom)
    n = POOLED_MIN // (12 * len(geoms)) + 5  # frames enough to be pooled
    rng = np.random.default_rng(8)
    qa = m.qpos0 + rng.normal(scale=0.3, size=(n, m.nq))
    qb = m.qpos0 + rng.normal(scale=0.3, size=(n, m.nq))
    first = geom_poses(m, qa, geoms)
    kept = [a.copy() for a in first]
    view = first[1][3:7]
    del first
    second = geom_poses(m, qb, geoms)  # the view holds the first's memory
    assert not np.shares_memory(view, second[1])
    assert np.array_equal(view, kept[1][3:7])
    del view
    where = second[0].__array_interface__["data"][0]
    want = [a.copy() for a in second]
    del second
    third = geom_poses(m, qa, geoms)  # the second's memory, free again
    assert third[0].__array_interface__["data"][0] == where
    assert all(a.tobytes() == b.tobytes() for a, b in zip(third, kept, strict=True))
    assert all(
        a.tobytes() == b.tobytes() for a, b in zip(geom_poses(m, qb, geoms), want, strict=True)
    )
