"""Geom poses of many humanoid poses at once: MuJoCo's forward kinematics compiled over frames.

The collision broad phase (:func:`mjwalk.timeline.collisions.candidate_frames`) needs the
world position and rotation of every humanoid geom in every frame of a timeline (about 1500
frames per station cycle, twice: the reach clearance check and the cycle's contact report).
One ``mujoco.mj_kinematics`` call per frame costs about 2.5 us, and as much again to set the
pose and copy the result out from Python; :func:`geom_poses` does the same arithmetic as
``mj_kinematics`` (MuJoCo's ``engine_core_smooth.c``: bodies in tree order, free, ball, hinge
and slide joints about their anchors, geoms placed on their bodies) for all frames in one
compiled loop. It agrees with MuJoCo to round-off (about 1e-15 m; tested), which the broad
phase's slack (1 mm) covers. Mocap bodies are not handled (:func:`supported` is False: use
MuJoCo's kinematics). World frame: metres, rotation matrices row-major as MuJoCo's ``xmat``.
"""

from __future__ import annotations

import math
import sys
import threading
import weakref
from dataclasses import dataclass

import mujoco
import numpy as np

from mjwalk._jit import njit

_FREE, _BALL, _SLIDE, _HINGE = (
    int(mujoco.mjtJoint.mjJNT_FREE),
    int(mujoco.mjtJoint.mjJNT_BALL),
    int(mujoco.mjtJoint.mjJNT_SLIDE),
    int(mujoco.mjtJoint.mjJNT_HINGE),
)


def supported(model: mujoco.MjModel) -> bool:
    """Whether :func:`geom_poses` reproduces ``mj_kinematics`` for ``model``.

    Args:
        model: a compiled model.

    Returns:
        True when the model has no mocap bodies.
    """
    return int(model.nmocap) == 0


def geom_poses(
    model: mujoco.MjModel, qpos: np.ndarray, geoms: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Geom poses in many frames, as ``mj_kinematics`` would leave them in ``geom_xpos`` and
    ``geom_xmat`` (to round-off), compiled over all frames.

    Args:
        model: a compiled model (:func:`supported`).
        qpos: (F, nq) poses.
        geoms: (G,) geom ids.

    Returns:
        ``(xpos, xmat)``: (F, G, 3) world positions, metres, and (F, G, 9) rotation matrices
        (row-major).
    """
    geoms = np.asarray(geoms, dtype=np.int64)
    bodies = model.geom_bodyid[geoms].astype(np.int64)
    return _frames_on_bodies(model, qpos, bodies, model.geom_pos[geoms], model.geom_quat[geoms])


@dataclass(frozen=True)
class GeomTable:
    """:func:`geom_poses` of some geoms in every frame of a timeline, computed once for the
    stages that read the same kinematics (a cycle's contact check and its ergonomics): a
    geom's pose in a frame depends on that frame's pose alone (the kernel's reuse of the
    frame before copies the numbers it would compute), so a column, or a row, of the table
    is bit for bit what :func:`geom_poses` gives for that geom, or those frames, alone.

    Attributes:
        geoms: (G,) the geom ids, ascending.
        xpos: (F, G, 3) world positions, metres.
        xmat: (F, G, 9) rotation matrices (row-major).
    """

    geoms: np.ndarray
    xpos: np.ndarray
    xmat: np.ndarray

    def columns(self, geoms: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
        """The poses of ``geoms`` (G',) in every frame, or None when one is not in the table.

        Args:
            geoms: geom ids.

        Returns:
            ``(xpos, xmat)``: (F, G', 3) and (F, G', 9), or None.
        """
        geoms = np.asarray(geoms, dtype=np.int64)
        if not np.isin(geoms, self.geoms).all():
            return None
        col = np.searchsorted(self.geoms, geoms)
        if np.array_equal(col, np.arange(len(self.geoms))):
            return self.xpos, self.xmat
        return _gathered(self.xpos, col), _gathered(self.xmat, col)


def _gathered(table: np.ndarray, col: np.ndarray) -> np.ndarray:
    """``table[:, col]`` of a (F, G, k) table: the same numbers in the same memory layout as
    NumPy's advanced indexing gives ((F, G', k) strided over a (G', F, k) block, so the
    readers' own loops, and their floats, are those they had), copied in one compiled pass
    along the frames (NumPy's gather read each column at the table's row stride: about 2 ms
    of a station cycle's ergonomics, 4x this)."""
    out = _gather_columns(np.ascontiguousarray(table), np.asarray(col, dtype=np.int64))
    return out.transpose(1, 0, 2)


@njit
def _gather_columns(table, col):
    """(G', F, k): ``table`` (F, G, k) columns ``col`` (G',), block by block."""
    n_f, n_c, n_k = table.shape[0], col.shape[0], table.shape[2]
    out = np.empty((n_c, n_f, n_k))
    for f in range(n_f):
        for i in range(n_c):
            c = col[i]
            for j in range(n_k):
                out[i, f, j] = table[f, c, j]
    return out


def geom_table(model: mujoco.MjModel, qpos: np.ndarray, geoms: np.ndarray) -> GeomTable:
    """The :class:`GeomTable` of ``geoms`` in every frame of ``qpos`` (:func:`geom_poses`).

    Args:
        model: a compiled model (:func:`supported`).
        qpos: (F, nq) poses.
        geoms: (G,) geom ids.

    Returns:
        The table, its geoms in ascending order.
    """
    ids = np.unique(np.asarray(geoms, dtype=np.int64))
    xpos, xmat = geom_poses(model, qpos, ids)
    return GeomTable(ids, xpos, xmat)


def _frames_on_bodies(
    model: mujoco.MjModel, qpos: np.ndarray, bodies: np.ndarray, pos: np.ndarray, quat: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """World poses of frames fixed on bodies (``pos``/``quat`` in each body's frame), in every
    frame of ``qpos``, by the compiled kernel."""
    qpos = np.ascontiguousarray(qpos, dtype=float).reshape(-1, model.nq)
    parent, jntadr, jntnum, jnt_type, jnt_qposadr, chains = _tree(model)
    out_pos, out_mat = _outputs(len(qpos), len(bodies))
    return _geom_poses(
        qpos,
        model.qpos0,
        parent,
        jntadr,
        jntnum,
        model.body_pos,
        model.body_quat,
        jnt_type,
        jnt_qposadr,
        model.jnt_axis,
        model.jnt_pos,
        bodies,
        pos,
        quat,
        _chains(model, bodies, chains),
        out_pos,
        out_mat,
    )


#: Outputs of at least this many numbers (a station cycle's whole timeline: some 2700 frames
#: of 49 geoms, 12 numbers each, 12.6 MB) are written into memory this process keeps
#: (:func:`_outputs`): fresh memory that large is mapped from the system page by page on
#: first write, about 2000 page faults and 2-3 ms of CPU a station cycle (counted with
#: ``getrusage``'s ``ru_minflt``: 1960 a cycle, 1700 of them in the table's kernel call).
#: Smaller outputs come from NumPy's allocator as before.
POOLED_MIN = 1 << 18
#: [positions, rotations] (flat float64) of the last pooled output, and its lock.
_POOL: list[np.ndarray] = []
_POOL_LOCK = threading.Lock()


def _outputs(n_f: int, n_g: int) -> tuple[np.ndarray, np.ndarray]:
    """Uninitialised (n_f, n_g, 3) and (n_f * n_g, 9) arrays for :func:`_geom_poses` (which
    writes every number before it reads one). Large ones are views of the kept buffers when
    nothing else holds them any more (no array or view of the last output is alive: a view
    holds its base, so its reference count says so), else new buffers that are kept instead;
    nothing alive is ever written over."""
    n = n_f * n_g
    if 12 * n < POOLED_MIN:
        return np.empty((n_f, n_g, 3)), np.empty((n, 9))
    with _POOL_LOCK:
        # two references to a free buffer: the pool's and getrefcount's argument
        free = bool(_POOL) and sys.getrefcount(_POOL[0]) == sys.getrefcount(_POOL[1]) == 2
        if not (free and _POOL[0].size >= 3 * n):  # room for a quarter more: grown seldom
            room = n + n // 4
            _POOL[:] = [np.empty(3 * room), np.empty(9 * room)]
        pos, mat = _POOL
        return pos[: 3 * n].reshape(n_f, n_g, 3), mat[: 9 * n].reshape(n, 9)


#: Per model: :func:`_tree`'s id arrays and :func:`_chains`' masks (a cycle asks for the same
#: model's poses some fifty times; converting its ids and walking its tree each time cost
#: about 20 us a call).
_KEPT: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _tree(model: mujoco.MjModel) -> tuple:
    """The tree's ids as int64 (parents, each body's first joint and joint count, the joints'
    types and qpos addresses) and a dict for :func:`_chains`, kept per model (a compiled
    model's tree does not change; its float arrays are read live at each call)."""
    kept = _KEPT.get(model)
    if kept is None:
        ids = [
            model.body_parentid,
            model.body_jntadr,
            model.body_jntnum,
            model.jnt_type,
            model.jnt_qposadr,
        ]
        kept = _KEPT[model] = (*[a.astype(np.int64) for a in ids], {})
    return kept


def body_poses(
    model: mujoco.MjModel, qpos: np.ndarray, bodies: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Body poses in many frames, as ``mj_kinematics`` would leave them in ``xpos`` and
    ``xmat`` (to round-off), compiled over all frames (:func:`geom_poses` with a frame at each
    body's origin).

    Args:
        model: a compiled model (:func:`supported`).
        qpos: (F, nq) poses.
        bodies: (B,) body ids.

    Returns:
        ``(xpos, xmat)``: (F, B, 3) world positions, metres, and (F, B, 9) rotation matrices
        (row-major).
    """
    bodies = np.asarray(bodies, dtype=np.int64)
    here = np.zeros((len(bodies), 4))
    here[:, 0] = 1.0  # the identity rotation: the body's own frame
    return _frames_on_bodies(model, qpos, bodies, np.zeros((len(bodies), 3)), here)


def _chains(model: mujoco.MjModel, bodies: np.ndarray, kept: dict | None = None) -> np.ndarray:
    """(nbody,) bool: ``bodies`` and every body above them (the bodies whose poses they
    need; the kernel skips the others), kept in ``kept`` by ``bodies`` (read-only)."""
    key = np.asarray(bodies, dtype=np.int64).tobytes()
    if kept is not None and key in kept:
        return kept[key]
    parent = model.body_parentid.tolist()
    need = [False] * model.nbody
    for b in np.asarray(bodies, dtype=np.int64).tolist():
        while b > 0 and not need[b]:
            need[b] = True
            b = parent[b]
    out = np.array(need, dtype=np.bool_)
    out.setflags(write=False)
    if kept is not None:
        kept[key] = out
    return out


@njit
def _mul_quat(a0, a1, a2, a3, b0, b1, b2, b3):
    """The quaternion product a * b (w, x, y, z)."""
    return (
        a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
        a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
        a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
        a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0,
    )


@njit
def _normalize4(q0, q1, q2, q3):
    """The unit quaternion (MuJoCo's ``mju_normalize4``: the identity when ~zero)."""
    n = math.sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3)
    if n < 1e-15:
        return 1.0, 0.0, 0.0, 0.0
    return q0 / n, q1 / n, q2 / n, q3 / n


@njit
def _quat2mat(q0, q1, q2, q3, out, k):
    """Row-major rotation matrix of the unit quaternion ``q`` into row ``k`` of ``out``."""
    q00, q01, q02, q03 = q0 * q0, q0 * q1, q0 * q2, q0 * q3
    q11, q12, q13 = q1 * q1, q1 * q2, q1 * q3
    q22, q23, q33 = q2 * q2, q2 * q3, q3 * q3
    out[k, 0] = q00 + q11 - q22 - q33
    out[k, 4] = q00 - q11 + q22 - q33
    out[k, 8] = q00 - q11 - q22 + q33
    out[k, 1] = 2.0 * (q12 - q03)
    out[k, 2] = 2.0 * (q13 + q02)
    out[k, 3] = 2.0 * (q12 + q03)
    out[k, 5] = 2.0 * (q23 - q01)
    out[k, 6] = 2.0 * (q13 - q02)
    out[k, 7] = 2.0 * (q23 + q01)


@njit
def _rot(mat, k, v0, v1, v2):
    """Row ``k`` of ``mat`` (row-major 3x3 rotations) times the vector v."""
    return (
        mat[k, 0] * v0 + mat[k, 1] * v1 + mat[k, 2] * v2,
        mat[k, 3] * v0 + mat[k, 4] * v1 + mat[k, 5] * v2,
        mat[k, 6] * v0 + mat[k, 7] * v1 + mat[k, 8] * v2,
    )


@njit
def _geom_poses(
    qpos,
    qpos0,
    parent,
    jntadr,
    jntnum,
    body_pos,
    body_quat,
    jnt_type,
    jnt_qposadr,
    jnt_axis,
    jnt_pos,
    gbody,
    gpos,
    gquat,
    need,
    out_pos,
    out_mat,
):
    """The kernel of :func:`geom_poses` (model arrays as MuJoCo names them), written into
    ``out_pos`` (F, G, 3) and ``out_mat`` (F * G, 9) (every number, whatever they held before).
    Only the bodies in ``need`` are placed, and a body whose joints and parent did not move
    since the frame before keeps its pose (and its geoms theirs): the same numbers, not
    computed again; a frame whose whole pose repeats the one before (a hold: about a third of
    a station cycle's frames) copies that frame's rows at once."""
    n_f, n_b, n_g = qpos.shape[0], parent.shape[0], gbody.shape[0]
    xpos = np.zeros((n_b, 3))
    xquat = np.zeros((n_b, 4))
    xmat = np.zeros((n_b, 9))
    mt = np.empty((1, 9))
    last = np.full(jnt_type.shape[0], np.nan)  # a hinge's angle in the frame before
    sin_h = np.zeros(jnt_type.shape[0])
    cos_h = np.zeros(jnt_type.shape[0])
    moved = np.ones(n_b, dtype=np.bool_)  # the body's pose changed in this frame
    moved[0] = False
    xquat[0, 0] = 1.0
    xmat[0, 0] = xmat[0, 4] = xmat[0, 8] = 1.0
    n_q = qpos.shape[1]
    for f in range(n_f):
        if f > 0:  # a pose equal to the one before: every geom where it was, copied at once
            same = True
            for i in range(n_q):
                if qpos[f, i] != qpos[f - 1, i]:
                    same = False
                    break
            if same:
                moved[:] = False
                out_pos[f] = out_pos[f - 1]
                out_mat[f * n_g : (f + 1) * n_g] = out_mat[(f - 1) * n_g : f * n_g]
                continue
        for b in range(1, n_b):
            if not need[b]:
                continue
            ja, jn = jntadr[b], jntnum[b]
            if f > 0:
                mv = moved[parent[b]]
                for j in range(ja, ja + jn):
                    if mv:
                        break
                    a = jnt_qposadr[j]
                    w = 7 if jnt_type[j] == _FREE else (4 if jnt_type[j] == _BALL else 1)
                    for i in range(a, a + w):
                        if qpos[f, i] != qpos[f - 1, i]:
                            mv = True
                            break
                moved[b] = mv
                if not mv:
                    continue
            if jn == 1 and jnt_type[ja] == _FREE:
                a = jnt_qposadr[ja]
                p0, p1, p2 = qpos[f, a], qpos[f, a + 1], qpos[f, a + 2]
                t0, t1, t2, t3 = _normalize4(
                    qpos[f, a + 3], qpos[f, a + 4], qpos[f, a + 5], qpos[f, a + 6]
                )
            else:
                pid = parent[b]
                if pid > 0:
                    p0, p1, p2 = _rot(xmat, pid, body_pos[b, 0], body_pos[b, 1], body_pos[b, 2])
                    p0 += xpos[pid, 0]
                    p1 += xpos[pid, 1]
                    p2 += xpos[pid, 2]
                    t0, t1, t2, t3 = _mul_quat(
                        xquat[pid, 0], xquat[pid, 1], xquat[pid, 2], xquat[pid, 3],
                        body_quat[b, 0], body_quat[b, 1], body_quat[b, 2], body_quat[b, 3],
                    )  # fmt: skip
                else:
                    p0, p1, p2 = body_pos[b, 0], body_pos[b, 1], body_pos[b, 2]
                    t0, t1, t2, t3 = (
                        body_quat[b, 0],
                        body_quat[b, 1],
                        body_quat[b, 2],
                        body_quat[b, 3],
                    )
                for j in range(ja, ja + jn):
                    a = jnt_qposadr[j]
                    t = jnt_type[j]
                    j0, j1, j2 = jnt_pos[j, 0], jnt_pos[j, 1], jnt_pos[j, 2]
                    off = j0 != 0.0 or j1 != 0.0 or j2 != 0.0
                    if t == _SLIDE:
                        _quat2mat(t0, t1, t2, t3, mt, 0)
                        x0, x1, x2 = _rot(mt, 0, jnt_axis[j, 0], jnt_axis[j, 1], jnt_axis[j, 2])
                        dq = qpos[f, a] - qpos0[a]
                        p0 += x0 * dq
                        p1 += x1 * dq
                        p2 += x2 * dq
                        continue
                    c0, c1, c2 = p0, p1, p2  # the anchor, about which the joint turns
                    if off:
                        _quat2mat(t0, t1, t2, t3, mt, 0)
                        c0, c1, c2 = _rot(mt, 0, j0, j1, j2)
                        c0 += p0
                        c1 += p1
                        c2 += p2
                    if t == _BALL:
                        l0, l1, l2, l3 = _normalize4(
                            qpos[f, a], qpos[f, a + 1], qpos[f, a + 2], qpos[f, a + 3]
                        )
                    else:  # hinge (the sine and cosine kept while its angle stays)
                        if qpos[f, a] != last[j]:
                            half = 0.5 * (qpos[f, a] - qpos0[a])
                            last[j] = qpos[f, a]
                            sin_h[j], cos_h[j] = math.sin(half), math.cos(half)
                        sn = sin_h[j]
                        l0 = cos_h[j]
                        l1, l2, l3 = jnt_axis[j, 0] * sn, jnt_axis[j, 1] * sn, jnt_axis[j, 2] * sn
                    t0, t1, t2, t3 = _mul_quat(t0, t1, t2, t3, l0, l1, l2, l3)
                    if off:  # (at the body's origin the rotation leaves it in place)
                        _quat2mat(t0, t1, t2, t3, mt, 0)
                        v0, v1, v2 = _rot(mt, 0, j0, j1, j2)
                        p0, p1, p2 = c0 - v0, c1 - v1, c2 - v2
            t0, t1, t2, t3 = _normalize4(t0, t1, t2, t3)
            xpos[b, 0], xpos[b, 1], xpos[b, 2] = p0, p1, p2
            xquat[b, 0], xquat[b, 1], xquat[b, 2], xquat[b, 3] = t0, t1, t2, t3
            _quat2mat(t0, t1, t2, t3, xmat, b)
        for g in range(n_g):
            b = gbody[g]
            if f > 0 and not moved[b]:  # the body, hence the geom, where it was
                for i in range(3):
                    out_pos[f, g, i] = out_pos[f - 1, g, i]
                for i in range(9):
                    out_mat[f * n_g + g, i] = out_mat[(f - 1) * n_g + g, i]
                continue
            v0, v1, v2 = _rot(xmat, b, gpos[g, 0], gpos[g, 1], gpos[g, 2])
            out_pos[f, g, 0] = xpos[b, 0] + v0
            out_pos[f, g, 1] = xpos[b, 1] + v1
            out_pos[f, g, 2] = xpos[b, 2] + v2
            t0, t1, t2, t3 = _mul_quat(
                xquat[b, 0], xquat[b, 1], xquat[b, 2], xquat[b, 3],
                gquat[g, 0], gquat[g, 1], gquat[g, 2], gquat[g, 3],
            )  # fmt: skip
            _quat2mat(t0, t1, t2, t3, out_mat, f * n_g + g)
    return out_pos, out_mat.reshape(n_f, n_g, 9)
