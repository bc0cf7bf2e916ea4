"""Leg kinematics of the humanoid: analytic IK and FK of one leg in the pelvis frame, the foot's
lowest point (the foot rolling about its heel or ball on a footprint is
:mod:`~mjwalk.body.legs.footpivot`).

Pelvis frame: x forward, y left, z up, pelvis upright. World frame: metres, z up, yaw from +x
CCW. Footprint ``(x, y, yaw)``: the floor point under the ankle joint with the foot flat, and the
foot's heading. The public functions take ``side`` "left" / "right"; the helpers the synthesis
loops over (:func:`hip_world`, :func:`leg_ik_world`) the joint-name letter "l" / "r". Angles in
radians.
"""

from __future__ import annotations

import functools
import itertools
import math

import numpy as np

from mjwalk._jit import njit, njit_inline
from mjwalk.body.humanoid import ROM_DEG, LegGeometry
from mjwalk.body.legs.footpivot import ball_offset
from mjwalk.boundedmemo import Memo
from mjwalk.conventions import Side, side_of_prefix, side_prefix

#: Smallest knee flexion the IK uses when a leg must stretch (radians): never lock the knee.
KNEE_MIN = np.deg2rad(2.0)

LEG_JOINTS = (
    "hip_{}_rot",
    "hip_{}_flex",
    "hip_{}_abd",
    "knee_{}",
    "ankle_{}_flex",
    "ankle_{}_inv",
    "toe_{}",
)


def rot_z(a: np.ndarray) -> np.ndarray:
    """Rotation matrices about +z by ``a`` (right-handed: +x turns towards +y).

    Args:
        a: angles, radians (any shape S).

    Returns:
        (*S, 3, 3) rotation matrices.
    """
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack(
        [np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2
    )


def rot_y(a: np.ndarray) -> np.ndarray:
    """Rotation matrices about +y by ``a`` (right-handed: +z turns towards +x).

    Args:
        a: angles, radians (any shape S).

    Returns:
        (*S, 3, 3) rotation matrices.
    """
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack(
        [np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2
    )


def rot_x(a: np.ndarray) -> np.ndarray:
    """Rotation matrices about +x by ``a`` (right-handed: +y turns towards +z).

    Args:
        a: angles, radians (any shape S).

    Returns:
        (*S, 3, 3) rotation matrices.
    """
    c, s = np.cos(a), np.sin(a)
    z, o = np.zeros_like(a), np.ones_like(a)
    return np.stack(
        [np.stack([o, z, z], -1), np.stack([z, c, -s], -1), np.stack([z, s, c], -1)], -2
    )


def leg_ik(
    ankle_rel: np.ndarray,
    foot_yaw: np.ndarray,
    foot_pitch: np.ndarray,
    side: Side,
    geom: LegGeometry,
    clip: bool = True,
) -> dict[str, np.ndarray]:
    """Analytic leg IK in the pelvis frame (x forward, y left, z up; pelvis upright).

    Args:
        ankle_rel: (N, 3) ankle position relative to the hip joint centre, metres.
        foot_yaw: (N,) foot heading relative to the pelvis heading, radians (CCW).
        foot_pitch: (N,) foot pitch relative to the floor, radians, + toes up.
        side: "left" or "right".
        geom: the leg lengths.
        clip: clip the angles to the humanoid's ranges (``ROM_DEG``).

    Returns:
        joint name -> (N,) angle in radians (hip rotation/flexion/abduction, knee, ankle
        flexion/inversion), anatomical signs, clipped to the humanoid's ranges if ``clip``.
        Unreachable targets are met as closely as the leg allows (stretched to
        :data:`KNEE_MIN`).
    """
    s = 1.0 if side == "left" else -1.0
    rel = np.ascontiguousarray(np.atleast_2d(np.asarray(ankle_rel, float)))
    n = len(rel)
    fy = np.ascontiguousarray(np.broadcast_to(np.asarray(foot_yaw, float), (n,)))
    fp = np.ascontiguousarray(np.broadcast_to(np.asarray(foot_pitch, float), (n,)))
    out = np.empty((n, 6))
    _leg_ik_rows(rel, fy, fp, s, *ik_lengths(geom), out)
    return named_angles(out, side, clip)


@functools.lru_cache(maxsize=16)
def ik_lengths(geom: LegGeometry) -> tuple[float, float, float, float]:
    """Thigh, shank and the shortest and longest hip-to-ankle distance the IK uses.

    Args:
        geom: the leg lengths.

    Returns:
        (thigh, shank, rmin, rmax) in metres: rmin at the knee's largest flexion, rmax at
        :data:`KNEE_MIN`.
    """
    return _LENGTHS.get(geom, lambda: _ik_lengths(geom))


def _ik_lengths(geom: LegGeometry) -> tuple[float, float, float, float]:
    """:func:`ik_lengths`, computed."""
    rmax = float(geom.span(KNEE_MIN))
    rmin = float(geom.span(np.deg2rad(ROM_DEG["knee"][1])))
    return float(geom.thigh), float(geom.shank), rmin, rmax


#: :func:`ik_lengths` per geometry (the synthesis asks for them hundreds of times a cycle).
_LENGTHS: Memo = Memo(limit=64)


def named_angles(out: np.ndarray, side: Side, clip: bool) -> dict[str, np.ndarray]:
    """The IK's angle rows by joint name.

    Args:
        out: (n, 6) angles, radians (hip rotation, flexion, abduction, knee, ankle flexion,
            inversion).
        side: "left" or "right".
        clip: clip them to the humanoid's ranges (``ROM_DEG``).

    Returns:
        joint name -> (n,) angle, radians (views of ``out`` unless clipped).
    """
    p = side_prefix(side)
    names = [f"hip_{p}_rot", f"hip_{p}_flex", f"hip_{p}_abd", f"knee_{p}"]
    names += [f"ankle_{p}_flex", f"ankle_{p}_inv"]
    res = {}
    for k, name in enumerate(names):
        v = out[:, k]
        if clip:
            lo, hi = np.deg2rad(ROM_DEG[generic_joint(name)])
            v = np.clip(v, lo, hi)
        res[name] = v
    return res


@njit
def _mat3(a, b):
    """3x3 product a @ b of row-major 9-tuples (sums in index order, as NumPy's matmul; tuples
    stay in registers, no allocation per sample)."""
    return (
        a[0] * b[0] + a[1] * b[3] + a[2] * b[6],
        a[0] * b[1] + a[1] * b[4] + a[2] * b[7],
        a[0] * b[2] + a[1] * b[5] + a[2] * b[8],
        a[3] * b[0] + a[4] * b[3] + a[5] * b[6],
        a[3] * b[1] + a[4] * b[4] + a[5] * b[7],
        a[3] * b[2] + a[4] * b[5] + a[5] * b[8],
        a[6] * b[0] + a[7] * b[3] + a[8] * b[6],
        a[6] * b[1] + a[7] * b[4] + a[8] * b[7],
        a[6] * b[2] + a[7] * b[5] + a[8] * b[8],
    )


@njit
def _leg_ik_one(u0, u1, u2, yaw_f, pitch_f, s, L1, L2, rmin, rmax, out):
    """One sample of :func:`leg_ik`: ``(u0, u1, u2)`` the hip-to-ankle vector (pelvis frame),
    the foot's relative yaw and pitch; writes the six angles to ``out`` (6,). The matrices
    are :func:`rot_z`, :func:`rot_y`, :func:`rot_x` as row-major 9-tuples."""
    leg_ik_cs(u0, u1, u2, math.cos(yaw_f), math.sin(yaw_f), pitch_f, s, L1, L2, rmin, rmax, out)


@njit_inline
def leg_ik_cs(u0, u1, u2, cz, sz, pitch_f, s, L1, L2, rmin, rmax, out):
    """:func:`_leg_ik_one` given the cosine ``cz`` and sine ``sz`` of the foot's relative yaw
    (the rest of its arithmetic, in its order).

    Args:
        u0: the hip-to-ankle vector's x in the pelvis frame, metres.
        u1: its y, metres.
        u2: its z, metres.
        cz: the cosine of the foot's yaw relative to the pelvis.
        sz: its sine.
        pitch_f: the foot's pitch to the floor, radians, + toes up.
        s: +1 for the left leg, -1 for the right.
        L1: thigh length, metres.
        L2: shank length, metres.
        rmin: the shortest hip-to-ankle distance, metres (:func:`ik_lengths`).
        rmax: the longest hip-to-ankle distance, metres.
        out: (6,) written: hip rotation, flexion, abduction, knee, ankle flexion, inversion,
            radians, unclipped.

    Returns:
        None (``out`` is written).
    """
    cy, sy = math.cos(-pitch_f), math.sin(-pitch_f)
    rf = _mat3(
        (cz, -sz, 0.0, sz, cz, 0.0, 0.0, 0.0, 1.0), (cy, 0.0, sy, 0.0, 1.0, 0.0, -sy, 0.0, cy)
    )
    v0 = rf[0] * u0 + rf[3] * u1 + rf[6] * u2  # R_f^T (ankle - hip)
    v1 = rf[1] * u0 + rf[4] * u1 + rf[7] * u2
    v2 = rf[2] * u0 + rf[5] * u1 + rf[8] * u2
    r = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
    rc = min(max(r, rmin), rmax)
    ck = (rc**2 - L1**2 - L2**2) / (2 * L1 * L2)
    knee = math.acos(min(max(ck, -1.0), 1.0))
    phi = math.atan2(v1, -v2)
    m = math.hypot(v1, v2)
    a = math.atan2(L1 * math.sin(knee), L1 * math.cos(knee) + L2) - math.atan2(v0, m)
    w = np.fmod(a + math.pi, 2 * math.pi)  # np.mod(a + pi, 2 pi) - pi: into [-pi, pi)
    if w < 0.0:
        w += 2 * math.pi
    a = w - math.pi
    cx, sx = math.cos(phi), math.sin(phi)
    cb, sb = math.cos(a - knee), math.sin(a - knee)
    h = _mat3(
        _mat3(rf, (1.0, 0.0, 0.0, 0.0, cx, -sx, 0.0, sx, cx)),
        (cb, 0.0, sb, 0.0, 1.0, 0.0, -sb, 0.0, cb),
    )
    out[0] = -s * math.atan2(h[3], h[0])
    out[1] = math.asin(min(max(h[6], -1.0), 1.0))
    out[2] = s * math.atan2(h[7], h[8])
    out[3] = knee
    out[4] = a
    out[5] = s * phi


@njit
def _leg_ik_rows(rel, yaw_f, pitch_f, s, L1, L2, rmin, rmax, out):
    """:func:`leg_ik` (unclipped) for every row: rel (n, 3), yaw_f, pitch_f (n,) -> out (n, 6)."""
    for i in range(rel.shape[0]):
        _leg_ik_one(
            rel[i, 0], rel[i, 1], rel[i, 2], yaw_f[i], pitch_f[i], s, L1, L2, rmin, rmax, out[i]
        )


@njit
def _leg_ik_world_rows(ankle, foot_yaw, pitch, root, yaw, sgn, hip_y, L1, L2, rmin, rmax, out):
    """:func:`leg_ik_world` for every row into ``out`` (n, 6): the hip joint centre of an
    upright pelvis (:func:`hip_world`), the ankle target in the pelvis frame, the foot's yaw
    relative to the pelvis wrapped to (-pi, pi], then :func:`_leg_ik_one` (``sgn`` +1 for the
    left leg, -1 for the right)."""
    for i in range(ankle.shape[0]):
        leg_ik_world_row(ankle, foot_yaw, pitch, root, yaw, i, sgn, hip_y, L1, L2, rmin, rmax, out)


@njit
def leg_ik_world_row(ankle, foot_yaw, pitch, root, yaw, i, sgn, hip_y, L1, L2, rmin, rmax, out):
    """Row ``i`` of :func:`_leg_ik_world_rows` (no array views made per row): the ankle
    target relative to the hip, turned into the pelvis frame by :math:`R_z(-yaw)`, and the
    foot yaw relative to the pelvis, through the analytic IK.

    Args:
        ankle: (n, 3) ankle targets, metres, world frame.
        foot_yaw: (n,) foot headings, radians from +x CCW.
        pitch: (n,) foot pitches to the floor, radians, + toes up.
        root: (n, 3) pelvis (root) positions, metres.
        yaw: (n,) pelvis yaws, radians from +x CCW.
        i: the row to solve.
        sgn: +1 for the left leg, -1 for the right.
        hip_y: the hip joint centre's lateral offset from the pelvis centre, metres.
        L1: thigh length, metres.
        L2: shank length, metres.
        rmin: the shortest hip-to-ankle distance, metres (:func:`ik_lengths`).
        rmax: the longest hip-to-ankle distance, metres.
        out: (n, 6) unclipped angles, radians (hip rotation, flexion, abduction, knee, ankle
            flexion, inversion); row ``i`` is written.
    """
    u0, u1, u2, yrel = hip_frame_row(ankle, foot_yaw, root, yaw, i, sgn, hip_y)
    _leg_ik_one(u0, u1, u2, yrel, pitch[i], sgn, L1, L2, rmin, rmax, out[i])


@njit
def hip_frame_row(ankle, foot_yaw, root, yaw, i, sgn, hip_y):
    """Row ``i``'s ankle target seen from its hip in the pelvis frame, and the foot's yaw
    relative to the pelvis: the first half of :func:`leg_ik_world_row` (the ankle flexion of
    ``pitchfit`` starts from the same numbers).

    Args:
        ankle: (n, 3) ankle targets, metres, world frame.
        foot_yaw: (n,) foot headings, radians from +x CCW.
        root: (n, 3) pelvis (root) positions, metres.
        yaw: (n,) pelvis yaws, radians from +x CCW.
        i: the row.
        sgn: +1 for the left leg, -1 for the right.
        hip_y: the hip joint centre's lateral offset from the pelvis centre, metres.

    Returns:
        ``(u0, u1, u2, yrel)``: :math:`R_z(-yaw)` (ankle - hip), metres, pelvis frame (x
        forward, y left, z up), and the foot's yaw less the pelvis's, radians in [-pi, pi].
    """
    cy, sy = math.cos(yaw[i]), math.sin(yaw[i])
    c, sn = math.cos(-yaw[i]), math.sin(-yaw[i])
    u0, u1, u2 = hip_rel(ankle, root, i, sgn * hip_y, cy, sy, c, sn)
    dy = foot_yaw[i] - yaw[i]
    return u0, u1, u2, math.atan2(math.sin(dy), math.cos(dy))


@njit_inline
def hip_rel(ankle, root, i, off, cy, sy, c, sn):
    """Row ``i``'s ankle target relative to its hip, turned into the pelvis frame by
    :math:`R_z(-yaw)` (:func:`hip_frame_row`'s arithmetic, in its order).

    Args:
        ankle: (n, 3) ankle targets, metres, world frame.
        root: (n, 3) pelvis (root) positions, metres.
        i: the row.
        off: the hip joint centre's signed lateral offset, metres (+hip_y left, -hip_y right).
        cy: the cosine of the pelvis yaw.
        sy: its sine.
        c: the cosine of the negative pelvis yaw.
        sn: its sine.

    Returns:
        ``(u0, u1, u2)``: ankle - hip in the pelvis frame (x forward, y left, z up), metres.
    """
    d0 = ankle[i, 0] - (root[i, 0] + off * -sy)
    d1 = ankle[i, 1] - (root[i, 1] + off * cy)
    d2 = ankle[i, 2] - (root[i, 2] + off * 0.0)
    u0 = c * d0 + -sn * d1 + 0.0 * d2  # R_z(-yaw) (ankle - hip)
    u1 = sn * d0 + c * d1 + 0.0 * d2
    u2 = 0.0 * d0 + 0.0 * d1 + 1.0 * d2
    return u0, u1, u2


def leg_fk(angles: dict[str, np.ndarray], side: Side, geom: LegGeometry):
    """Forward kinematics of one leg in the pelvis frame (x forward, y left, z up; pelvis
    upright), the humanoid's joint axes (:func:`~mjwalk.body.humanoid.build_humanoid`).

    Args:
        angles: joint name -> (N,) angles in radians (hip rotation/flexion/abduction, knee,
            ankle flexion/inversion of ``side``).
        side: "left" or "right".
        geom: the leg lengths.

    Returns:
        (ankle (N, 3) relative to the hip joint centre in metres, foot rotation (N, 3, 3)).
    """
    s = 1.0 if side == "left" else -1.0
    a = {k: np.asarray(angles[k.format(side_prefix(side))], float) for k in LEG_JOINTS[:-1]}
    R = rot_z(-s * a["hip_{}_rot"]) @ rot_y(-a["hip_{}_flex"]) @ rot_x(s * a["hip_{}_abd"])
    knee = R[..., 2] * -geom.thigh
    R = R @ rot_y(a["knee_{}"])
    ankle = knee + R[..., 2] * -geom.shank
    R = R @ rot_y(-a["ankle_{}_flex"]) @ rot_x(-s * a["ankle_{}_inv"])
    return ankle, R


def foot_lowest(angles: dict[str, np.ndarray], side: Side, geom: LegGeometry) -> np.ndarray:
    """Height of the lowest point of the foot's collision boxes (sole and toes, as built by
    :func:`~mjwalk.body.humanoid.build_humanoid`) above the hip joint centre, from the leg
    angles; add the hip height for the height above the floor.

    Args:
        angles: joint name -> (N,) angles, radians, the ``side``'s :data:`LEG_JOINTS`
            (``toe_l`` / ``toe_r`` included).
        side: "left" or "right".
        geom: the leg lengths.

    Returns:
        (N,) heights, metres (negative: below the hip).
    """
    ah, ball = geom.ankle_height, ball_offset(geom)
    foot, toes = foot_boxes(geom)
    p = side_prefix(side)
    names = [k.format(p) for k in LEG_JOINTS]
    q = np.ascontiguousarray(np.column_stack([np.asarray(angles[k], float) for k in names]))
    s = 1.0 if side == "left" else -1.0
    return _foot_lowest_rows(q, s, geom.thigh, geom.shank, foot, toes, ball, ah)


@functools.lru_cache(maxsize=16)
def foot_boxes(geom: LegGeometry) -> tuple[np.ndarray, np.ndarray]:
    """The corners of :func:`foot_lowest`'s sole box in the foot frame and of its toes box in
    the toes frame (kept per geometry: not to be changed).

    Args:
        geom: the leg and foot lengths.

    Returns:
        the sole box's corners (8, 3) and the toes box's (8, 3), metres.
    """
    ah, ball, hw = geom.ankle_height, ball_offset(geom), geom.foot_width / 2
    corners = np.array(list(itertools.product((0.0, 1.0), (-hw, hw), (0.0, 1.0))))
    # sole box: x from the heel to the ball, 0.8 ankle heights tall from the sole
    foot = corners * [ball + geom.foot_back, 1.0, 0.8 * ah] + [-geom.foot_back, 0.0, -ah]
    # toes box in the toes frame (origin at the ball on the sole, rotated by the toe angle)
    toes = corners * [geom.foot_front - ball, 1.0, 0.4 * ah]
    return foot, toes


@njit
def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return (c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)


@njit
def _ry(a):
    c, s = math.cos(a), math.sin(a)
    return (c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c)


@njit
def _rx(a):
    c, s = math.cos(a), math.sin(a)
    return (1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)


@njit
def _foot_lowest_rows(q, s, thigh, shank, foot, toes, ball, ah):
    """:func:`foot_lowest` per row of ``q`` (n, 7) = the :data:`LEG_JOINTS` angles: the chain
    of :func:`leg_fk` (same products, same order) and the lowest corner of the sole and toes
    boxes (``foot``, ``toes`` (8, 3) corners in the foot and toes frames)."""
    n = q.shape[0]
    out = np.empty(n)
    for i in range(n):
        out[i] = foot_lowest_row(q[i, 0], q[i, 1], q[i, 2], q[i, 3], q[i, 4], q[i, 5], q[i, 6],
                                 s, thigh, shank, foot, toes, ball, ah)  # fmt: skip
    return out


@njit_inline
def foot_lowest_row(q0, q1, q2, q3, q4, q5, q6, s, thigh, shank, foot, toes, ball, ah):
    """One row of :func:`_foot_lowest_rows` (:func:`foot_lowest`'s arithmetic, in its order).

    Args:
        q0: hip rotation, radians (the :data:`LEG_JOINTS` order).
        q1: hip flexion, radians.
        q2: hip abduction, radians.
        q3: knee flexion, radians.
        q4: ankle flexion, radians.
        q5: ankle inversion, radians.
        q6: toe angle, radians.
        s: +1 for the left leg, -1 for the right.
        thigh: thigh length, metres.
        shank: shank length, metres.
        foot: (8, 3) the sole box's corners in the foot frame (:func:`foot_boxes`), metres.
        toes: (8, 3) the toes box's corners in the toes frame, metres.
        ball: the ball's offset ahead of the ankle, metres.
        ah: the ankle's height above the sole, metres.

    Returns:
        the lowest corner's height above the hip joint centre, metres (negative: below).
    """
    r = _mat3(_mat3(_rz(-s * q0), _ry(-q1)), _rx(s * q2))
    kz = r[8] * -thigh
    r = _mat3(r, _ry(q3))
    az = kz + r[8] * -shank
    r = _mat3(_mat3(r, _ry(-q4)), _rx(-s * q5))
    low = np.inf
    for c in range(foot.shape[0]):
        z = r[6] * foot[c, 0] + r[7] * foot[c, 1] + r[8] * foot[c, 2]
        low = min(low, z)
    t = _ry(-q6)
    for c in range(toes.shape[0]):
        x = t[0] * toes[c, 0] + t[1] * toes[c, 1] + t[2] * toes[c, 2] + ball
        y = t[3] * toes[c, 0] + t[4] * toes[c, 1] + t[5] * toes[c, 2] + 0.0
        zz = t[6] * toes[c, 0] + t[7] * toes[c, 1] + t[8] * toes[c, 2] + -ah
        z = r[6] * x + r[7] * y + r[8] * zz
        low = min(low, z)
    return az + low


def generic_joint(name: str) -> str:
    """A joint name without its side letter, the key of ``ROM_DEG``.

    Args:
        name: a joint name such as ``"hip_l_flex"``.

    Returns:
        the name without the "l"/"r" part, e.g. ``"hip_flex"``.
    """
    return "_".join(p for p in name.split("_") if p not in ("l", "r"))


def hip_world(root: np.ndarray, yaw: np.ndarray, side: str, geom: LegGeometry) -> np.ndarray:
    """World position of the ``side`` hip joint centre of an upright pelvis:
    ``root + s hip_y (-sin yaw, cos yaw, 0)``, s = +1 left, -1 right.

    Args:
        root: (n, 3) pelvis positions, metres.
        yaw: (n,) pelvis yaws, radians from +x CCW.
        side: "l" or "r".
        geom: the leg geometry (``hip_y``).

    Returns:
        (n, 3) hip joint centres, metres.
    """
    sgn = 1.0 if side == "l" else -1.0
    lat = np.column_stack([-np.sin(yaw), np.cos(yaw), np.zeros_like(yaw)])
    return root + sgn * geom.hip_y * lat


def leg_ik_world(ankle, foot_yaw, pitch, root, yaw, side: str, geom: LegGeometry) -> dict:
    """Unclipped :func:`leg_ik` angles of the ``side`` leg for world ankle targets under the
    pelvis (compiled: the synthesis calls it dozens of times per walk).

    Args:
        ankle: (n, 3) ankle targets, metres, world frame.
        foot_yaw: (n,) (or broadcastable) foot headings, radians from +x CCW.
        pitch: (n,) foot pitches to the floor, radians, + toes up.
        root: (n, 3) pelvis (root) positions, metres.
        yaw: (n,) pelvis yaws, radians from +x CCW.
        side: "l" or "r".
        geom: the leg lengths.

    Returns:
        joint name -> (n,) angle, radians (hip rotation/flexion/abduction, knee, ankle
        flexion/inversion), anatomical signs, not clipped.
    """
    ankle = np.ascontiguousarray(ankle, dtype=float)
    root = np.ascontiguousarray(root, dtype=float)
    n = len(ankle)
    out = np.empty((n, 6))
    sgn = 1.0 if side == "l" else -1.0

    def row(v):
        v = np.asarray(v, dtype=float)
        if v.shape == (n,) and v.flags.c_contiguous:
            return v
        return np.ascontiguousarray(np.broadcast_to(v, (n,)))

    _leg_ik_world_rows(
        ankle,
        row(foot_yaw),
        row(pitch),
        root if root.shape == (n, 3) else np.ascontiguousarray(np.broadcast_to(root, (n, 3))),
        row(yaw),
        sgn,
        float(geom.hip_y),
        *ik_lengths(geom),
        out,
    )
    return named_angles(out, side_of_prefix(side), clip=False)
