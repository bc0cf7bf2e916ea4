"""MuJoCo's forward kinematics on a chain of bodies, compiled (mjwalk.timeline.chainkin): the
same bits as ``mj_kinematics`` in every frame of a station cycle, and the models it declines."""

from __future__ import annotations

from pathlib import Path

import mujoco
import numpy as np
import pytest

import mjwalk
from mjwalk.cycle.simulate import prepare
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.timeline import chainkin, parts

SCENES = Path(__file__).resolve().parents[2] / "scenes"


@pytest.fixture(scope="module")
def station():
    ctx = prepare(load_cycle_spec(SCENES / "assembly_station.toml"))
    return ctx, mjwalk.simulate_cycle(ctx, rng=1, keep_timeline=True)


def _bits(a: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=np.float64).view(np.uint64)


def test_every_frame_is_mujocos_to_the_bit(station):
    ctx, result = station
    m, prefix = ctx.model, ctx.jointmap.prefix
    bodies = np.array(
        [m.body(f"{prefix}{n}").id for n in ("hand_l", "hand_r", "forearm_l", "thorax", "foot_r")]
    )
    geoms = np.array([int(np.flatnonzero(m.geom_bodyid == b)[0]) for b in bodies[:2]])  # palms
    if not chainkin.supported(m, bodies, geoms):
        # a MuJoCo computing in another order than 4.0.1's: declined, mj_kinematics serves
        assert mujoco.__version__ != "4.0.1"
        pytest.skip(f"MuJoCo {mujoco.__version__} computes in another order: kernel declined")
    q = result.timeline.qpos
    frames = np.arange(0, len(q), 3)
    xpos, xmat, gpos, exact = chainkin.chain_poses(m, q, frames, bodies, geoms)
    assert exact.all()
    d = mujoco.MjData(m)
    for i, f in enumerate(frames.tolist()):
        d.qpos[:] = q[f]
        mujoco.mj_kinematics(m, d)
        assert np.array_equal(_bits(xpos[i]), _bits(d.xpos[bodies]))
        assert np.array_equal(_bits(xmat[i]), _bits(d.xmat[bodies]))
        assert np.array_equal(_bits(gpos[i]), _bits(d.geom_xpos[geoms]))


def test_a_quaternion_mujoco_would_rescale_flags_its_frame(station):
    ctx, result = station
    m = ctx.model
    hand = np.array([m.body(f"{ctx.jointmap.prefix}hand_l").id])
    q = np.array(result.timeline.qpos[:3])
    root = next(j for j in range(m.njnt) if m.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE)
    a = m.jnt_qposadr[root] + 3
    q[1, a : a + 4] *= 1.5  # not a unit quaternion: mj_normalizeQuat would rescale it
    *_, exact = chainkin.chain_poses(m, q, np.arange(3), hand, np.zeros(0, dtype=int))
    assert exact.tolist() == [True, False, True]


def test_models_it_does_not_reproduce_are_declined():
    spec = mujoco.MjSpec()
    b = spec.worldbody.add_body(name="b", pos=[0, 0, 1])
    b.add_joint(type=mujoco.mjtJoint.mjJNT_BALL)
    b.add_geom(size=[0.1, 0, 0], pos=[0.1, 0, 0], quat=[0.5, 0.5, 0.5, 0.5])
    c = b.add_body(name="c", pos=[0, 0, 0.3])
    c.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, axis=[1, 0, 0], pos=[0, 0, 0.1])
    c.add_geom(size=[0.1, 0, 0])
    h = spec.worldbody.add_body(name="h")
    h.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0, 1, 0])
    h.add_geom(size=[0.1, 0, 0])
    m = spec.compile()
    ball, off_centre, hinge = (m.body(n).id for n in ("b", "c", "h"))
    assert not chainkin.supported(m, np.array([ball]), np.zeros(0, dtype=int))
    assert not chainkin.supported(m, np.array([off_centre]), np.zeros(0, dtype=int))
    assert chainkin.supported(m, np.array([hinge]), np.array([2]))
    assert not chainkin.supported(
        m, np.array([hinge]), np.array([0])
    )  # placed off its body's frame


def test_a_library_computing_otherwise_declines_the_kernel(station, monkeypatch):
    """The first question of a process compares the kernel with ``mj_kinematics`` on seeded
    poses; a difference in the last bit (here: a kernel off by one ulp) declines every model,
    and the hands' poses are then ``mj_kinematics``' own."""
    ctx, result = station
    m, jm = ctx.model, ctx.jointmap
    real = chainkin.chain_poses

    def off_by_an_ulp(*args):
        xpos, xmat, gpos, exact = real(*args)
        return np.nextafter(xpos, np.inf), xmat, gpos, exact

    monkeypatch.setattr(chainkin, "chain_poses", off_by_an_ulp)
    monkeypatch.setattr(chainkin, "_LIBRARY_AGREES", None)
    monkeypatch.setattr(chainkin, "_KEPT", type(chainkin._KEPT)())
    hands = np.array([m.body(f"{jm.prefix}hand_{s}").id for s in "lr"])
    palms = np.array([int(np.flatnonzero(m.geom_bodyid == b)[0]) for b in hands])
    assert not chainkin.supported(m, hands, palms)
    q = result.timeline.qpos[::50]
    pos, _, palm = parts.hand_poses(m, jm, q)
    d = mujoco.MjData(m)
    for i, row in enumerate(q):
        d.qpos[:] = row
        mujoco.mj_kinematics(m, d)
        assert np.array_equal(_bits(pos[i]), _bits(d.xpos[hands]))
        assert np.array_equal(_bits(palm[i]), _bits(d.geom_xpos[palms]))
