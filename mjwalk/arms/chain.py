"""Arm kinematics: segment lengths, chain points, two-link IK, minimum jerk, and the humanoid's
arm joint angles from segment directions.

Frames: the body frame at the shoulder of the moving arm, metres, x forward, y left, z up (the
humanoid's thorax frame in its neutral pose). Angles in radians.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.transform import Rotation

from mjwalk._jit import njit
from mjwalk.anthropometry import ROM_DEG
from mjwalk.arms.anglerows import (
    fill_angles,
    frame_terms,
    hand_terms,
    ik_rows,
    unit_steps,
    upper_x,
)
from mjwalk.arms.anglerows import (
    min_jerk as min_jerk,  # (re-exported: the minimum-jerk profile lives there)
)
from mjwalk.conventions import DEFAULT_STATURE, Side, side_prefix

#: Anthropometric segment lengths as shares of stature H (Winter): upper arm, forearm, hand.
ARM_SEGMENT_SHARES = (0.186, 0.146, 0.108)


#: Reflection through the body's sagittal plane (x-z) in the shoulder frame: multiplies y by -1.
#: The humanoid is left-right symmetric, so a right-arm movement is the left-arm movement to the
#: mirrored target, mirrored back.
MIRROR_Y = np.array([1.0, -1.0, 1.0])

#: Relaxed hand position (m, left shoulder frame, x fwd, y left, z up) where reaches start.
REST_HAND = (0.15, 0.02, -0.60)


def arm_segment_lengths(stature: float = DEFAULT_STATURE, with_hand: bool = True) -> np.ndarray:
    """Upper arm, forearm (and hand) lengths in metres for a person of ``stature`` metres.

    Args:
        stature: body height, metres.
        with_hand: include the hand segment.

    Returns:
        (3,) or (2,) segment lengths, metres.
    """
    shares = ARM_SEGMENT_SHARES if with_hand else ARM_SEGMENT_SHARES[:2]
    return stature * np.asarray(shares)


def end_effector(directions: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    """Hand (end of the chain) position (..., 3), metres from the shoulder.

    Args:
        directions: (..., S, 3) unit segment directions, shoulder frame.
        lengths: (S,) segment lengths, metres.

    Returns:
        (..., 3) position of the chain's end, metres from the shoulder.
    """
    return np.einsum("...sj,s->...j", directions, np.asarray(lengths))


def _dot(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Row-wise dot products (n,) of (n, 3) arrays, summed left to right like ``u @ v``."""
    return u[:, 0] * v[:, 0] + u[:, 1] * v[:, 1] + u[:, 2] * v[:, 2]


def two_link_ik(
    target: np.ndarray, l1: float, l2: float, elbow_hint: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Unit directions (upper arm, forearm) putting the wrist at ``target`` (3,) from the
    shoulder, with the elbow in the plane of the shoulder-wrist axis and ``elbow_hint`` (the
    swivel angle of the hint is kept). Unreachable targets are clamped to the workspace.

    Args:
        target: (3,) wrist position, metres from the shoulder.
        l1: upper arm length, metres.
        l2: forearm length, metres.
        elbow_hint: (3,) direction the elbow bends towards.

    Returns:
        ``(upper, fore)`` (3,) unit directions.
    """
    upper, fore = two_link_ik_rows(np.asarray(target)[None], l1, l2, np.asarray(elbow_hint)[None])
    return upper[0], fore[0]


def two_link_ik_rows(
    target: np.ndarray, l1: float, l2: float, elbow_hint: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`two_link_ik` for many wrist targets (n, 3) and elbow hints (n, 3) at once:
    unit directions (n, 3) of the upper arm and of the forearm.

    Args:
        target: (n, 3) wrist positions, metres from the shoulder.
        l1: upper arm length, metres.
        l2: forearm length, metres.
        elbow_hint: (n, 3) directions the elbows bend towards.

    Returns:
        ``(upper, fore)`` (n, 3) unit directions.
    """
    target = np.ascontiguousarray(target, dtype=float)
    hint = np.ascontiguousarray(elbow_hint, dtype=float)
    upper, fore = np.empty_like(target), np.empty_like(target)
    # (compiled, the NumPy arithmetic it replaced row by row: mjwalk.arms.anglerows; the
    # scalars as that code formed them)
    lo, hi = abs(l1 - l2) + 1e-6, l1 + l2 - 1e-6
    ik_rows(target, hint, l1, l2, lo, hi, l1**2 - l2**2, l1**2, upper, fore)
    return upper, fore


#: Joint names of one arm of the mjwalk humanoid (mjwalk.body.humanoid), in output order.
ARM_JOINTS = (
    "shoulder_flex",
    "shoulder_abd",
    "shoulder_rot",
    "elbow",
    "forearm_pron",
    "wrist_flex",
    "wrist_dev",
)


def arm_joint(name: str, side: Side) -> str:
    """The humanoid's joint of ``side``'s arm for an :data:`ARM_JOINTS` name
    (``"shoulder_flex"`` -> ``"shoulder_l_flex"``).

    Args:
        name: an :data:`ARM_JOINTS` name.
        side: "left" or "right".

    Returns:
        the humanoid joint name.
    """
    part, *rest = name.split("_")
    return "_".join([part, side_prefix(side), *rest])


#: The humanoid's arm joint names per side, in :data:`ARM_JOINTS` order (built once: the
#: per-frame code asks for them in every call).
ARM_JOINT_NAMES: dict[str, tuple[str, ...]] = {
    side: tuple(arm_joint(name, side) for name in ARM_JOINTS) for side in ("left", "right")
}


def arm_adrs(jm, sides: tuple[Side, ...] = ("left", "right")) -> list[int]:
    """``qpos`` addresses of the :data:`ARM_JOINTS` of ``sides``' arms (jointmap ``jm``).

    Args:
        jm: the humanoid's joint map (:func:`mjwalk.body.humanoid.humanoid_model`).
        sides: arms, in output order.

    Returns:
        7 addresses per side, in :data:`ARM_JOINTS` order.
    """
    return [jm.adr(arm_joint(name, side)) for side in sides for name in ARM_JOINTS]


def arm_joint_angles(
    directions: np.ndarray,
    side: Side = "left",
    roll: np.ndarray | None = None,
    independent: bool = False,
) -> np.ndarray:
    """Humanoid arm joint angles (n, 7) in radians, order :data:`ARM_JOINTS`, from segment
    directions (n, S, 3) in the thorax frame (x forward, y left, z up; S = 2 or 3) and an
    optional forearm roll (n,) (pronation, radians).

    The humanoid's chain (mjwalk.body.humanoid) is R_sh = Ry(-flex) Rx(s abd) Rz(-s rot) with
    the arm along -z, elbow Ry(-elbow), pronation Rz(-s pron), wrist Ry(-flex) Rx(s dev), with
    s = +1 for the left and -1 for the right arm. The upper arm's twist is the one that puts
    the forearm in the elbow's flexion plane; when the elbow is straight it is carried over
    from the previous frame.

    With ``independent`` the rows are not frames of one movement but alternatives (a batch of
    candidate arms): each row gets exactly the angles it gets alone (``n`` = 1): a straight
    elbow's twist starts from x, and the angles are not unwrapped across rows.

    Args:
        directions: (n, S, 3) unit segment directions, thorax frame.
        side: "left" or "right".
        roll: (n,) forearm pronation, radians, or None (0).
        independent: the rows are alternatives, each solved as if alone.

    Returns:
        (n, 7) joint angles, radians, :data:`ARM_JOINTS` order.
    """
    s = 1.0 if side == "left" else -1.0
    U = np.ascontiguousarray(directions, dtype=float)
    n = len(U)
    q = np.zeros((n, 7))
    # (the sums, products and clips compiled, the NumPy arithmetic they replaced row by row,
    # the inverse trigonometric functions NumPy's: mjwalk.arms.anglerows)
    # the upper arm's x axis: the forearm's part perpendicular to the upper arm (all frames
    # at once); where the elbow is straight it is carried over from the previous frame
    x, straight = np.empty((n, 3)), np.empty(n, dtype=np.bool_)
    upper_x(U, x, straight)
    if straight.any():
        z = -U[:, 0]
        for t in np.flatnonzero(straight):  # rare, and each depends on the frame before
            xt = x[t - 1] if t > 0 and not independent else np.array([1.0, 0.0, 0.0])
            xt = xt - (xt @ z[t]) * z[t]
            x[t] = xt / np.linalg.norm(xt)
    y, terms, lock = np.empty((n, 3)), np.empty((6, n)), np.empty(n, dtype=np.bool_)
    frame_terms(U, x, y, terms, lock, _GIMBAL)
    # the shoulder frame R_sh = [x y z] (z = -upper arm) as intrinsic Y-X-Z angles
    # (scipy's ``as_euler("YXZ")`` written out; near gimbal lock scipy decomposes those frames)
    b = np.arcsin(terms[0])
    a = np.arctan2(terms[1], terms[2])
    c = np.arctan2(terms[3], terms[4])
    if lock.any():
        r_sh = np.stack([x, y, -U[:, 0]], axis=-1)  # (n, 3, 3), columns x, y, z
        a[lock], b[lock], c[lock] = Rotation.from_matrix(r_sh[lock]).as_euler("YXZ").T
    a, b, c = _shoulder_branch(a, b, c, s)
    elbow = np.arccos(terms[5])
    pron = np.zeros(n) if roll is None else np.asarray(roll, dtype=float)[:n]
    fill_angles(q, a, b, c, elbow, np.ascontiguousarray(pron), s, n > 1 and not independent)
    if U.shape[1] > 2:
        # the hand in the forearm frame R_sh Ry(-elbow) Rz(-s pron): rotate back step by step
        wrist = np.empty((3, n))
        ce, se = np.cos(-elbow), np.sin(-elbow)
        cp, sp = np.cos(-s * pron), np.sin(-s * pron)
        hand_terms(U, x, y, ce, se, np.ascontiguousarray(cp), np.ascontiguousarray(sp), wrist)
        q[:, 5] = np.arctan2(wrist[1], wrist[2])
        q[:, 6] = s * np.arcsin(wrist[0])
    return q


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Row-wise cross products (n, 3) of (n, 3) arrays: the products and differences of
    ``np.cross``, without its axis handling (called per frame)."""
    out = np.empty_like(u)
    out[:, 0] = u[:, 1] * v[:, 2] - u[:, 2] * v[:, 1]
    out[:, 1] = u[:, 2] * v[:, 0] - u[:, 0] * v[:, 2]
    out[:, 2] = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
    return out


def hand_directions(
    u1: np.ndarray, u2: np.ndarray, flex: np.ndarray, dev: np.ndarray, side: Side = "left"
) -> np.ndarray:
    """Unit hand directions (n, 3) of arms with upper arm ``u1`` and forearm ``u2`` (n, 3; thorax
    frame) and the wrist at ``flex`` / ``dev`` (n,), radians, no forearm pronation: the inverse
    of the wrist part of :func:`arm_joint_angles` (``arm_joint_angles`` of the result gives
    ``flex`` and ``dev`` back, for |dev| < 90 deg and a bent elbow).

    Args:
        u1: (n, 3) unit upper-arm directions, thorax frame.
        u2: (n, 3) unit forearm directions.
        flex: (n,) wrist flexion, radians.
        dev: (n,) wrist deviation, radians.
        side: "left" or "right".

    Returns:
        (n, 3) unit hand directions, thorax frame.
    """
    s = 1.0 if side == "left" else -1.0
    u1 = np.asarray(u1, dtype=float)
    u2 = np.asarray(u2, dtype=float)
    # the forearm frame: z along -u2, x in the elbow's plane (towards the side the forearm
    # bends to), y = z x x; R_sh Ry(-elbow) of arm_joint_angles
    x = u2 - _dot(u2, u1)[:, None] * u1
    x /= np.maximum(np.linalg.norm(x, axis=1, keepdims=True), 1e-12)
    elbow = np.arccos(np.clip(_dot(u1, u2), -1, 1))
    ce, se = np.cos(elbow), np.sin(elbow)
    xf = ce[:, None] * x - se[:, None] * u1  # the upper arm frame's x turned with the elbow
    zf = -u2
    yf = np.cross(zf, xf)
    beta = s * np.asarray(dev, dtype=float)
    f = np.asarray(flex, dtype=float)
    cb = np.cos(beta)
    h = (cb * np.sin(f))[:, None] * xf + np.sin(beta)[:, None] * yf - (cb * np.cos(f))[:, None] * zf
    return h / np.linalg.norm(h, axis=1, keepdims=True)


#: |sin| of the middle YXZ angle above which a frame is decomposed by scipy (gimbal lock: the
#: first and third angles are not separable there; scipy's convention picks them).
_GIMBAL = 1.0 - 1e-7


#: The shoulder's ranges in radians (:data:`mjwalk.anthropometry.ROM_DEG`), converted once.
_SHOULDER_RANGES = {
    name: np.radians(ROM_DEG[name]) for name in ("shoulder_flex", "shoulder_abd", "shoulder_rot")
}


def _shoulder_branch(a: np.ndarray, b: np.ndarray, c: np.ndarray, s: float):
    """The shoulder's Y-X-Z angles (a, b, c) as :func:`arm_joint_angles` decomposes its frame (``b``
    within +-90 deg), or per frame the other set for the same rotation, ``(a + pi, sign(b) pi - b, c
    + pi)``, where that one keeps the joints within their ranges and this one does not: an arm
    raised sideways above the shoulder (abduction beyond 90 deg) is ``b`` = 120 deg with no flexion
    or rotation, which the first set writes as 60 deg with flexion and rotation of 180 deg, beyond
    their ranges (the clipped pose then pointed the arm backwards: a reach to a top shelf ended 1.3
    m off). Ranges: :data:`mjwalk.anthropometry.ROM_DEG`; ``s`` +1 for the left arm, -1 for the
    right (compiled: :func:`_shoulder_branch_rows`)."""
    a = np.ascontiguousarray(a, dtype=float)
    b = np.ascontiguousarray(b, dtype=float)
    c = np.ascontiguousarray(c, dtype=float)
    out = np.empty((3, len(a)))
    _shoulder_branch_rows(a, b, c, float(s), _SHOULDER_LIMITS, out)
    return out[0], out[1], out[2]


#: (lo, hi) of shoulder flexion, abduction and rotation, radians (:data:`_SHOULDER_RANGES`).
_SHOULDER_LIMITS = np.array(
    [_SHOULDER_RANGES[k] for k in ("shoulder_flex", "shoulder_abd", "shoulder_rot")]
)


@njit
def _beyond(v, lo, hi):
    """Radians of ``v`` beyond (lo, hi): ``np.maximum(lo - v, 0) + np.maximum(v - hi, 0)``
    (a NaN carried through as np.maximum carries it)."""
    d0, d1 = lo - v, v - hi
    m0 = d0 if d0 > 0.0 or d0 != d0 else 0.0
    m1 = d1 if d1 > 0.0 or d1 != d1 else 0.0
    return m0 + m1


@njit
def _shoulder_excess(a, b, c, s, lim):
    """Radians beyond the ranges ``lim`` (3, 2) of flexion -a, abduction s b and rotation
    -s c, summed in that order from 0 (the NumPy sums of the excess this replaced)."""
    out = 0.0
    out += _beyond(-a, lim[0, 0], lim[0, 1])
    out += _beyond(s * b, lim[1, 0], lim[1, 1])
    out += _beyond(-s * c, lim[2, 0], lim[2, 1])
    return out


@njit
def _shoulder_branch_rows(a, b, c, s, lim, out):
    """:func:`_shoulder_branch` per row into ``out`` (3, n): the NumPy arithmetic it replaced,
    row by row in the same order (wrap: ``(x + pi) % 2 pi - pi``, Python's and NumPy's float
    remainder alike)."""
    pi = np.pi
    for i in range(a.shape[0]):
        a2 = ((a[i] + pi) + pi) % (2.0 * pi) - pi  # wrap(a + pi)
        b2 = (pi if b[i] >= 0.0 else -pi) - b[i]
        c2 = ((c[i] + pi) + pi) % (2.0 * pi) - pi
        other = (
            _shoulder_excess(a2, b2, c2, s, lim) < _shoulder_excess(a[i], b[i], c[i], s, lim) - 1e-9
        )
        out[0, i] = a2 if other else a[i]
        out[1, i] = b2 if other else b[i]
        out[2, i] = c2 if other else c[i]


#: Halvings of the blend in :func:`wrist_in_range`'s least-turn search: the hand's direction
#: to within 2^-16 of the clipping passes' turn (under 0.01 deg for turns up to 180 deg).
WRIST_BISECTIONS = 16


def wrist_in_range(
    end: np.ndarray,
    hand_dir: np.ndarray,
    lengths: np.ndarray,
    elbow_hint: np.ndarray,
    limits: np.ndarray,
    side: Side = "left",
    iterations: int = 6,
) -> np.ndarray:
    """Arm directions (n, 3, 3) (upper arm, forearm, hand; unit, thorax frame) putting the
    hand's end on ``end`` (n, 3) m with the hand along ``hand_dir`` (n, 3) as far as the wrist's
    range allows: where the two-link arm solved for that hand (elbow towards ``elbow_hint``
    (n, 3)) would bend the wrist beyond ``limits`` ((2, 2) radians: (lo, hi) of flexion and of
    deviation, :data:`ARM_JOINTS` order), the hand turns only as far as the limit: the wrist
    angles are clipped to the range (:func:`hand_directions`) and the arm re-solved for that
    hand, ``iterations`` times at most, which brings the wrist into range but, as the forearm
    moves with the wrist, turns the hand further than it needs (generated reaches: a median
    39.5 deg where 21.9 do); then the least turn is found by bisection along the arc from
    ``hand_dir`` to that hand (:data:`WRIST_BISECTIONS` halvings; the wrist's angles vary
    continuously along it, so the wrist ends on its range's edge). ``lengths``: (3,) upper arm,
    forearm, hand (m).

    Args:
        end: (n, 3) hand-end targets, metres from the shoulder.
        hand_dir: (n, 3) wanted unit hand directions.
        lengths: (3,) upper arm, forearm, hand lengths, metres.
        elbow_hint: (n, 3) directions the elbows bend towards.
        limits: (2, 2) wrist flexion and deviation ranges (lo, hi), radians.
        side: "left" or "right".
        iterations: bisection rounds of the re-solve (0: no turn).

    Returns:
        (n, 3, 3) unit directions of upper arm, forearm and hand.
    """
    end = np.asarray(end, dtype=float)
    want = np.asarray(hand_dir, dtype=float)
    lo, hi = np.asarray(limits, dtype=float).T

    def solve(hd: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        u1, u2 = two_link_ik_rows(end - lengths[2] * hd, lengths[0], lengths[1], elbow_hint)
        q = arm_joint_angles(np.stack([u1, u2, hd], axis=1), side)[:, 5:7]
        return u1, u2, ((q >= lo - 1e-9) & (q <= hi + 1e-9)).all(axis=1)

    hd = want.copy()
    u1, u2, ok = solve(hd)
    wanted_ok = ok
    for _ in range(iterations):
        if ok.all():
            break
        q = np.clip(arm_joint_angles(np.stack([u1, u2, hd], axis=1), side)[:, 5:7], lo, hi)
        hd = hand_directions(u1, u2, q[:, 0], q[:, 1], side)
        u1, u2, ok = solve(hd)
    turn = ~wanted_ok & ok  # out of range as wanted, in range after the clipping passes
    if turn.any():
        w, v = want[turn], hd[turn]
        a, b = np.zeros(len(w)), np.ones(len(w))  # in range at b, not at a

        def blend(t: np.ndarray) -> np.ndarray:
            h = (1.0 - t)[:, None] * w + t[:, None] * v
            return h / np.maximum(np.linalg.norm(h, axis=1, keepdims=True), 1e-12)

        sub_end, sub_hint = end[turn], np.asarray(elbow_hint, dtype=float)[turn]
        for _ in range(WRIST_BISECTIONS):
            m = 0.5 * (a + b)
            h = blend(m)
            s1, s2 = two_link_ik_rows(sub_end - lengths[2] * h, lengths[0], lengths[1], sub_hint)
            q = arm_joint_angles(np.stack([s1, s2, h], axis=1), side)[:, 5:7]
            inside = ((q >= lo - 1e-9) & (q <= hi + 1e-9)).all(axis=1)
            b = np.where(inside, m, b)
            a = np.where(inside, a, m)
        hd[turn] = blend(b)
        u1, u2, _ = solve(hd)
    return np.stack([u1, u2, hd], axis=1)


def arm_ranges(jm, side: Side) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The limits (7,) (radians) and ``qpos`` addresses (7,) of ``side``'s :data:`ARM_JOINTS`
    in ``jm``, looked up once per joint map (and new ``range`` array); do not write into them.

    Args:
        jm: the humanoid's joint map.
        side: "left" or "right".

    Returns:
        ``(lo, hi, adr)``: float, float and int64 arrays in :data:`ARM_JOINTS` order.
    """
    kept = jm.__dict__.setdefault("_arm_ranges", {})
    hit = kept.get(side)
    if hit is None or hit[0] is not jm.range or hit[1] is not jm.qposadr:
        idx = [jm.index(jn) for jn in ARM_JOINT_NAMES[side]]
        hit = kept[side] = (
            jm.range,
            jm.qposadr,
            np.ascontiguousarray(jm.range[idx, 0], dtype=float),
            np.ascontiguousarray(jm.range[idx, 1], dtype=float),
            np.ascontiguousarray(jm.qposadr[idx], dtype=np.int64),
        )
    return hit[2], hit[3], hit[4]


def arm_frames(
    q0: np.ndarray, jm, q: np.ndarray, side: Side, times: np.ndarray
) -> tuple[np.ndarray, list[str]]:
    """Poses (len(times), nq): ``q0`` with one arm's joint angles ``q`` (n, 7), order
    :data:`ARM_JOINTS`, radians) sampled evenly over [0, 1], interpolated at ``times`` in [0, 1]
    and clipped to the humanoid's joint ranges; and the names of the joints that were clipped.

    Args:
        q0: (nq,) base pose.
        jm: the humanoid's joint map.
        q: (n, 7) joint angles, radians, :data:`ARM_JOINTS` order.
        side: "left" or "right".
        times: (m,) normalized times in [0, 1].

    Returns:
        ``(poses, clipped)``: (m, nq) poses and the names of the clipped joints.
    """
    names = ARM_JOINT_NAMES[side]
    lo, hi, adr = arm_ranges(jm, side)
    src = unit_steps(len(q))
    times = np.ascontiguousarray(times, dtype=float).reshape(-1)
    out = np.repeat(np.asarray(q0)[None], len(times), axis=0)
    bad = np.zeros(len(names), dtype=np.bool_)
    # (compiled: np.interp per joint, np.clip and _outside's test, the same numbers)
    _arm_rows(np.ascontiguousarray(q, dtype=float), src, times, adr, lo, hi, out, bad)
    return out, [names[k] for k in np.flatnonzero(bad)]


@njit
def _interp_slot(x, xp):
    """Where ``np.interp(x, xp, fp)`` takes its value at one point ``x`` (xp increasing, at
    least one point), for any ``fp``: ``(j, how)``, how 0: between samples j and j + 1, 1:
    sample j's own value (the ends, a sample's own time, the one-point case), 2: ``x`` itself
    (a NaN time). NumPy's cases, in its order."""
    n = xp.shape[0]
    if n == 1:  # (NumPy's one-point case: its value everywhere, a NaN time too)
        return 0, 1
    if x != x:
        return 0, 2
    if x < xp[0]:
        return 0, 1
    if x > xp[n - 1]:
        return n - 1, 1
    lo, hi = 0, n - 1  # the last j with xp[j] <= x
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if xp[mid] <= x:
            lo = mid
        else:
            hi = mid
    j = n - 1 if x >= xp[n - 1] else lo
    if j == n - 1 or xp[j] == x:
        return j, 1
    return j, 0


@njit
def _arm_rows(q, src, times, adr, lo, hi, out, bad):
    """:func:`arm_frames`' joints into ``out`` (m, nq) at columns ``adr``: each of ``q``'s
    (n, 7) columns interpolated at ``times`` (m,) over ``src`` as ``np.interp`` interpolates
    (:func:`_interp_slot`, found once per time for all columns; NumPy's arithmetic, a NaN
    retried from the right end of the interval), clipped to (``lo``, ``hi``) as np.clip
    clips (a NaN kept); ``bad`` (7,) set where a joint lies beyond its range by over 1e-6 rad
    (:func:`_outside`). (A row at a time: about 30x faster than a column at a time, the same
    numbers.)"""
    for t in range(times.shape[0]):
        x = times[t]
        j, how = _interp_slot(x, src)
        for k in range(q.shape[1]):
            if how == 1:
                v = q[j, k]
            elif how == 2:
                v = x
            else:
                slope = (q[j + 1, k] - q[j, k]) / (src[j + 1] - src[j])
                v = slope * (x - src[j]) + q[j, k]
                if v != v:
                    v = slope * (x - src[j + 1]) + q[j + 1, k]
                    if v != v and q[j, k] == q[j + 1, k]:
                        v = q[j, k]
            lo_k, hi_k = lo[k], hi[k]
            if v < lo_k - 1e-6 or v > hi_k + 1e-6:
                bad[k] = True
            c = v if v != v or v > lo_k else lo_k
            out[t, adr[k]] = c if c != c or c < hi_k else hi_k


def clipped_joints(jm, q: np.ndarray, side: Side) -> list[str]:
    """The joints of ``side``'s arm whose angles in ``q`` lie beyond the humanoid's ranges (by
    more than 1e-6 rad): the joints :func:`arm_frames` clips, without building the poses.

    Args:
        jm: the humanoid's joint map.
        q: (n, 7) joint angles, radians, :data:`ARM_JOINTS` order.
        side: "left" or "right".

    Returns:
        The clipped joints' names, :data:`ARM_JOINTS` order.
    """
    lo, hi, _ = arm_ranges(jm, side)
    return _outside(np.asarray(q, dtype=float), lo, hi, ARM_JOINT_NAMES[side])


def rows_in_range(jm, q: np.ndarray, side: Side) -> np.ndarray:
    """Per row of ``q``, whether every joint of ``side``'s arm lies within the humanoid's
    ranges (to 1e-6 rad): the rows :func:`clipped_joints` finds nothing to clip in.

    Args:
        jm: the humanoid's joint map.
        q: (n, 7) joint angles, radians, :data:`ARM_JOINTS` order.
        side: "left" or "right".

    Returns:
        (n,) bool.
    """
    lo, hi, _ = arm_ranges(jm, side)
    qi = np.asarray(q, dtype=float)
    return np.asarray(~((qi < lo - 1e-6) | (qi > hi + 1e-6)).any(axis=1))


def _outside(qi: np.ndarray, lo: np.ndarray, hi: np.ndarray, names) -> list[str]:
    """``names`` of the columns of ``qi`` (n, 7) with a value beyond (lo, hi) by over 1e-6."""
    bad = ((qi < lo - 1e-6) | (qi > hi + 1e-6)).any(axis=0)
    return [names[k] for k in np.flatnonzero(bad)]
