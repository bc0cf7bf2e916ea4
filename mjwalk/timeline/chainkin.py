"""The poses of a few bodies by MuJoCo's own forward kinematics arithmetic, compiled over frames
(issue 50): ``mj_kinematics`` of the bodies on the way from the world to them, operation for
operation, so the numbers are MuJoCo's to the bit.

:func:`mjwalk.timeline.parts.hand_poses` needs the hands' poses in some 1500 frames a station
cycle. One ``mujoco.mj_kinematics`` call per frame computes all 53 bodies and 80 geoms of the
scene (the 30 finger bodies among them) and costs, with setting the pose and copying the
results out from Python, about 5 us; the hands hang on 9 bodies. :func:`chain_poses` places
only those, in one compiled loop over the frames.

The arithmetic is MuJoCo 4.0.1's ``mj_kinematics`` (``engine_core_smooth.c``: a body's
position and quaternion from its parent's, its hinges applied about their anchors, the
quaternion normalised and turned into ``xmat``; a geom placed on its body by
``mj_local2Global``), with the operation order of the compiled library, not of its C source
where the two differ: the shipped ``libmujoco.so.4.0.1`` computes ``mju_quat2Mat``'s diagonal
as ``(q00 - q22) + (q11 - q33)``, ``(q00 + q22) - (q11 + q33)`` and ``(q00 - q22) - (q11 - q33)``
(read from its machine code; the source's left-to-right sum differs in the last bit for about
40 % of quaternions), and ``mju_normalize4``'s norm as ``sqrt((q0^2 + q1^2) + (q2^2 + q3^2))``.
Where a quaternion would be rescaled (its norm off 1 by more than MuJoCo's ``mjMINVAL``), the
frame is flagged instead and its caller asks ``mj_kinematics`` (one such path less to match).
:func:`supported` says which models and bodies this covers (free root, hinge joints, no mocap
bodies; geoms at their body's origin or offset without rotation). Tests compare every frame of
station cycles with ``mj_kinematics`` bit for bit (tests/timeline/test_parts.py,
tests/timeline/test_chainkin.py). A MuJoCo built or released otherwise may compute in another
order: the first time a process asks, :func:`supported` compares the kernel with
``mj_kinematics`` on :data:`CHECK_POSES` seeded poses of that model and, on any difference,
declines every model for the rest of the process (the callers then use ``mj_kinematics``:
the same results, at its cost).

World frame: metres, rotation matrices row-major as MuJoCo's ``xmat``.
"""

from __future__ import annotations

import math
import weakref

import mujoco
import numpy as np

from mjwalk._jit import njit

_FREE = int(mujoco.mjtJoint.mjJNT_FREE)
_HINGE = int(mujoco.mjtJoint.mjJNT_HINGE)
#: MuJoCo's ``mjMINVAL`` (mjmodel.h): a quaternion whose norm is within it of 1 is left as is.
MINVAL = 1e-15
#: ``mjtSameFrame``: a geom at its body's origin (copied), or offset without rotation.
_SAME_BODY = int(mujoco.mjtSameFrame.mjSAMEFRAME_BODY)
_SAME_BODYROT = int(mujoco.mjtSameFrame.mjSAMEFRAME_BODYROT)


def _chain(model: mujoco.MjModel, bodies: np.ndarray) -> np.ndarray:
    """The bodies ``bodies`` hang on, themselves included, in tree order (int64)."""
    parent = model.body_parentid
    need: set[int] = set()
    for b in np.asarray(bodies, dtype=np.int64).tolist():
        while b > 0 and b not in need:
            need.add(b)
            b = int(parent[b])
    return np.array(sorted(need), dtype=np.int64)


def supported(model: mujoco.MjModel, bodies: np.ndarray, geoms: np.ndarray) -> bool:
    """Whether :func:`chain_poses` reproduces ``mj_kinematics`` for these bodies and geoms.

    Args:
        model: a compiled model.
        bodies: (B,) body ids.
        geoms: (G,) geom ids.

    Returns:
        True when the model has no mocap bodies, every body on the chain has either one free
        joint (a root on the world) or only hinges about its origin (``jnt_pos`` zero), and
        each geom sits at its body's origin or is offset without rotation
        (``mjSAMEFRAME_BODY`` / ``mjSAMEFRAME_BODYROT``), and this process's MuJoCo gave the
        kernel's bits on :data:`CHECK_POSES` seeded poses the first time it was asked.
    """
    key = (
        np.asarray(bodies, dtype=np.int64).tobytes(),
        np.asarray(geoms, dtype=np.int64).tobytes(),
    )
    kept = _KEPT.setdefault(model, {})
    if key not in kept:
        kept[key] = _supported(model, bodies, geoms) and _library_agrees(model, bodies, geoms)
    return kept[key]


#: Seeded poses on which the kernel is compared with this process's ``mj_kinematics`` once
#: (a differing operation order shows in the last bit of ~40 % of quaternions: 64 poses miss
#: it with odds far below 1e-9).
CHECK_POSES = 64
#: Whether this process's MuJoCo computes as :func:`chain_poses` does (None: not asked yet).
_LIBRARY_AGREES: bool | None = None


def _library_agrees(model: mujoco.MjModel, bodies: np.ndarray, geoms: np.ndarray) -> bool:
    """Whether :func:`chain_poses` gives ``mj_kinematics``' bits on seeded poses of ``model``
    (hinges turned up to 1 rad from ``qpos0``, a free root moved and turned about z); checked
    once per process."""
    global _LIBRARY_AGREES
    if _LIBRARY_AGREES is None:
        bodies, geoms = np.asarray(bodies, dtype=np.int64), np.asarray(geoms, dtype=np.int64)
        rng = np.random.default_rng(0)
        q = np.tile(model.qpos0, (CHECK_POSES, 1))
        for j in range(model.njnt):
            a = int(model.jnt_qposadr[j])
            if int(model.jnt_type[j]) == _HINGE:
                q[:, a] += rng.uniform(-1.0, 1.0, CHECK_POSES)
            elif int(model.jnt_type[j]) == _FREE:
                q[:, a : a + 3] += rng.uniform(-1.0, 1.0, (CHECK_POSES, 3))
                half = rng.uniform(-np.pi, np.pi, CHECK_POSES) / 2
                q[:, a + 3 : a + 7] = np.stack(
                    [np.cos(half), 0 * half, 0 * half, np.sin(half)], axis=1
                )
        frames = np.arange(CHECK_POSES)
        xpos, xmat, gpos, exact = chain_poses(model, q, frames, bodies, geoms)
        data = mujoco.MjData(model)
        same = True
        for f in np.flatnonzero(exact).tolist():
            data.qpos[:] = q[f]
            mujoco.mj_kinematics(model, data)
            same = same and all(
                np.array_equal(a.view(np.uint64), np.ascontiguousarray(b).view(np.uint64))
                for a, b in (
                    (xpos[f], data.xpos[bodies]),
                    (xmat[f], data.xmat[bodies]),
                    (gpos[f], data.geom_xpos[geoms]),
                )
            )
        _LIBRARY_AGREES = same and bool(exact.any())
    return _LIBRARY_AGREES


def _supported(model: mujoco.MjModel, bodies: np.ndarray, geoms: np.ndarray) -> bool:
    """:func:`supported`, worked out."""
    if int(model.nmocap) != 0:
        return False
    for b in _chain(model, bodies).tolist():
        js = range(model.body_jntadr[b], model.body_jntadr[b] + model.body_jntnum[b])
        types = [int(model.jnt_type[j]) for j in js]
        free = types == [_FREE] and int(model.body_parentid[b]) == 0
        hinges = all(
            t == _HINGE and not model.jnt_pos[j].any() for t, j in zip(types, js, strict=True)
        )
        if not free and not hinges:
            return False
    same = model.geom_sameframe[np.asarray(geoms, dtype=np.int64)]
    return bool(np.isin(same, (_SAME_BODY, _SAME_BODYROT)).all())


#: Per model: by bodies, the chain and the id arrays as int64; by (bodies, geoms), whether
#: :func:`supported` holds (read-only model structure; a cycle asks some 30 times).
_KEPT: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _ids(model: mujoco.MjModel, bodies: np.ndarray) -> tuple:
    """The chain of ``bodies`` and the model's tree ids as int64, kept per model."""
    kept = _KEPT.setdefault(model, {})
    key = np.asarray(bodies, dtype=np.int64).tobytes()
    if key not in kept:
        ids = (model.body_parentid, model.body_jntadr, model.body_jntnum, model.jnt_qposadr)
        free = np.zeros(model.nbody, dtype=np.bool_)
        for b in range(1, model.nbody):
            ja, jn = model.body_jntadr[b], model.body_jntnum[b]
            free[b] = jn == 1 and int(model.jnt_type[ja]) == _FREE
        kept[key] = (_chain(model, bodies), *[a.astype(np.int64) for a in ids], free)
    return kept[key]


def chain_poses(
    model: mujoco.MjModel,
    qpos: np.ndarray,
    frames: np.ndarray,
    bodies: np.ndarray,
    geoms: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Body and geom poses in some frames, as ``mj_kinematics`` leaves them in ``xpos``,
    ``xmat`` and ``geom_xpos`` (bit for bit; :func:`supported` must hold).

    Args:
        model: a compiled model.
        qpos: (F, nq) poses.
        frames: (K,) the frames to compute (int).
        bodies: (B,) body ids.
        geoms: (G,) geom ids.

    Returns:
        ``(xpos, xmat, gpos, exact)``: (K, B, 3) positions (m) and (K, B, 9) row-major
        rotations of the bodies, (K, G, 3) the geoms' positions, and (K,) bool: False where a
        quaternion would have been rescaled (those frames' rows are not MuJoCo's: ask
        ``mj_kinematics``).
    """
    chain, parent, jntadr, jntnum, qposadr, free = _ids(model, bodies)
    geoms = np.asarray(geoms, dtype=np.int64)
    k, nb, ng = len(frames), len(bodies), len(geoms)
    xpos, xmat = np.empty((k, nb, 3)), np.empty((k, nb, 9))
    gpos, exact = np.empty((k, ng, 3)), np.ones(k, dtype=np.bool_)
    _chain_kernel(
        np.ascontiguousarray(qpos, dtype=float),
        np.asarray(frames, dtype=np.int64),
        chain, parent, jntadr, jntnum, qposadr, model.jnt_axis, model.qpos0,
        model.body_pos, model.body_quat, free, np.asarray(bodies, dtype=np.int64),
        model.geom_bodyid[geoms].astype(np.int64), model.geom_pos[geoms],
        (model.geom_sameframe[geoms] == _SAME_BODY), xpos, xmat, gpos, exact,
    )  # fmt: skip
    return xpos, xmat, gpos, exact


@njit
def _unit(q0, q1, q2, q3):
    """Whether ``mju_normalize4`` leaves the quaternion as it is (its norm within
    :data:`MINVAL` of 1; the compiled library's sum order)."""
    n = math.sqrt((q0 * q0 + q1 * q1) + (q2 * q2 + q3 * q3))
    return not (n < MINVAL) and not (abs(n - 1.0) > MINVAL)


@njit
def _mul_quat(a0, a1, a2, a3, b0, b1, b2, b3):
    """``mji_mulQuat`` (a * b), as inlined in ``mj_kinematics``."""
    return (
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


@njit
def _quat2mat(q0, q1, q2, q3, out, i):
    """``mju_quat2Mat`` into ``out[i]`` (the library's diagonal order; the identity for the
    null quaternion)."""
    if q0 == 1 and q1 == 0 and q2 == 0 and q3 == 0:
        for m in range(9):
            out[i, m] = 0.0
        out[i, 0] = out[i, 4] = out[i, 8] = 1.0
        return
    q00, q01, q02, q03 = q0 * q0, q0 * q1, q0 * q2, q0 * q3
    q11, q12, q13 = q1 * q1, q1 * q2, q1 * q3
    q22, q23, q33 = q2 * q2, q2 * q3, q3 * q3
    out[i, 0] = (q00 - q22) + (q11 - q33)
    out[i, 4] = (q00 + q22) - (q11 + q33)
    out[i, 8] = (q00 - q22) - (q11 - q33)
    out[i, 1] = 2 * (q12 - q03)
    out[i, 2] = 2 * (q13 + q02)
    out[i, 3] = 2 * (q12 + q03)
    out[i, 5] = 2 * (q23 - q01)
    out[i, 6] = 2 * (q13 - q02)
    out[i, 7] = 2 * (q23 + q01)


@njit
def _mat_vec(mat, i, v0, v1, v2):
    """``mji_mulMatVec3``: row-major ``mat[i]`` times v."""
    return (
        mat[i, 0] * v0 + mat[i, 1] * v1 + mat[i, 2] * v2,
        mat[i, 3] * v0 + mat[i, 4] * v1 + mat[i, 5] * v2,
        mat[i, 6] * v0 + mat[i, 7] * v1 + mat[i, 8] * v2,
    )


@njit
def _chain_kernel(
    qpos, frames, chain, parent, jntadr, jntnum, qposadr, jnt_axis, qpos0, body_pos, body_quat,
    free, bodies, gbody, gpos_local, g_at_origin, out_xpos, out_xmat, out_gpos, exact,
):  # fmt: skip
    """The kernel of :func:`chain_poses` (model arrays as MuJoCo names them; ``free`` (nbody,)
    bool: the body is a root with a free joint). The hinges' anchors are at their bodies'
    origins (:func:`supported`), where ``mj_kinematics``' off-centre correction adds zeros."""
    nb = parent.shape[0]
    xpos = np.zeros((nb, 3))
    xquat = np.zeros((nb, 4))
    xmat = np.zeros((nb, 9))
    xquat[0, 0] = 1.0
    xmat[0, 0] = xmat[0, 4] = xmat[0, 8] = 1.0
    for i in range(frames.shape[0]):
        f = frames[i]
        for b in chain:
            ja = jntadr[b]
            if free[b]:
                a = qposadr[ja]
                p0, p1, p2 = qpos[f, a], qpos[f, a + 1], qpos[f, a + 2]
                t0, t1, t2, t3 = qpos[f, a + 3], qpos[f, a + 4], qpos[f, a + 5], qpos[f, a + 6]
                if not _unit(t0, t1, t2, t3):  # mj_normalizeQuat would rescale it
                    exact[i] = False
            else:
                pid = parent[b]
                v0, v1, v2 = _mat_vec(xmat, pid, body_pos[b, 0], body_pos[b, 1], body_pos[b, 2])
                p0, p1, p2 = xpos[pid, 0] + v0, xpos[pid, 1] + v1, xpos[pid, 2] + v2
                t0, t1, t2, t3 = _mul_quat(
                    xquat[pid, 0], xquat[pid, 1], xquat[pid, 2], xquat[pid, 3],
                    body_quat[b, 0], body_quat[b, 1], body_quat[b, 2], body_quat[b, 3],
                )  # fmt: skip
                for j in range(ja, ja + jntnum[b]):
                    a = qposadr[j]
                    ang = qpos[f, a] - qpos0[a]
                    if ang == 0:  # mju_axisAngle2Quat: the null quaternion
                        l0, l1, l2, l3 = 1.0, 0.0, 0.0, 0.0
                    else:
                        s = math.sin(ang * 0.5)
                        l0 = math.cos(ang * 0.5)
                        l1, l2, l3 = jnt_axis[j, 0] * s, jnt_axis[j, 1] * s, jnt_axis[j, 2] * s
                    t0, t1, t2, t3 = _mul_quat(t0, t1, t2, t3, l0, l1, l2, l3)
            if not _unit(t0, t1, t2, t3):  # mju_normalize4 would rescale it
                exact[i] = False
            xpos[b, 0], xpos[b, 1], xpos[b, 2] = p0, p1, p2
            xquat[b, 0], xquat[b, 1], xquat[b, 2], xquat[b, 3] = t0, t1, t2, t3
            _quat2mat(t0, t1, t2, t3, xmat, b)
        for k in range(bodies.shape[0]):
            b = bodies[k]
            for m in range(3):
                out_xpos[i, k, m] = xpos[b, m]
            for m in range(9):
                out_xmat[i, k, m] = xmat[b, m]
        for k in range(gbody.shape[0]):
            b = gbody[k]
            if g_at_origin[k]:
                for m in range(3):
                    out_gpos[i, k, m] = xpos[b, m]
            else:
                v0, v1, v2 = _mat_vec(xmat, b, gpos_local[k, 0], gpos_local[k, 1], gpos_local[k, 2])
                out_gpos[i, k, 0] = v0 + xpos[b, 0]
                out_gpos[i, k, 1] = v1 + xpos[b, 1]
                out_gpos[i, k, 2] = v2 + xpos[b, 2]
