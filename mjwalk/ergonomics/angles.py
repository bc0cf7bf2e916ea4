"""Body angles the ergonomic methods read, per frame, from the humanoid or from capture.

:func:`angles_from_points` measures them from joint positions (world frame, metres, z up), so
the same code scores mjwalk's humanoid (:func:`angles_from_timeline`: the body origins by
MuJoCo's forward kinematics, compiled over all frames, plus the wrist and forearm hinges read
from ``qpos``) and a capture's own joints (:func:`points_from_take`-style dictionaries).

Frames. The trunk axis runs from the pelvis (hip-joint centre) to the base of the neck (C7);
the pelvis' forward direction is the horizontal normal of the right-to-left hip line (+x of the
humanoid's own frame). Trunk flexion is the trunk axis' inclination from the vertical in the
pelvis' sagittal plane (forward positive), side bend in its frontal plane, twist the horizontal
angle between the shoulder line and the hip line. The neck, the upper arms and the forearms are
measured in the trunk's frame (up: the trunk axis; left: the shoulder line made orthogonal to
it; forward: their cross product). All angles in degrees.

Where a method describes a category by a drawing the continuous angle needs a threshold; these
are stated here, each once: :data:`NEUTRAL_DEG`, :data:`ASYMMETRY_DEG`, :data:`ABDUCTION_PLANE_DEG`,
:data:`WRIST_DEVIATED_DEG`, :data:`TWIST_END_SHARE`, :data:`KNEE_BENT_DEG`, :data:`FOOT_UP`.
The humanoid has no shoulder girdle (no clavicle joint), so a raised shoulder is never
scored (``shoulder_raised`` is False); capture is scored the same way.
"""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from mjwalk.ergonomics.anglejit import (
    KERNEL_POINTS,
    gather,
    point_array,
    trig_arguments,
    z_offsets,
)
from mjwalk.timeline.geomposes import GeomTable, geom_poses, supported

#: A joint within this many degrees of its neutral position counts as neutral ("0 deg", "upright"
#: in RULA and REBA). The methods' worksheets are filled in by eye, to about this resolution;
#: a chosen figure, not a published one.
NEUTRAL_DEG = 5.0
#: Trunk or neck twist and side bend beyond this many degrees count as "twisted" / "side bent"
#: (ISO 11226:2000, 4.2.1 and 4.2.2: axial rotation or lateral flexion of the trunk, and
#: lateral flexion of the head, beyond 10 deg is not acceptable as a static posture).
ASYMMETRY_DEG = 10.0
#: An elevated upper arm (more than 20 deg) whose plane of elevation lies more than this far from
#: the sagittal plane towards the side counts as "abducted" (RULA, REBA +1): half-way between a
#: forward (flexion) and a sideways (abduction) raise.
ABDUCTION_PLANE_DEG = 45.0
#: Radial/ulnar deviation beyond this many degrees counts as "deviated" (RULA, REBA +1).
WRIST_DEVIATED_DEG = 10.0
#: Forearm rotation beyond this share of the joint's range counts as "at or near the end of its
#: range" (RULA wrist twist 2).
TWIST_END_SHARE = 0.75
#: Knee flexion (deg) from which a knee counts as bent (OWAS legs 4/5; REBA's first knee band
#: starts at 30 deg, Hignett & McAtamney 2000).
KNEE_BENT_DEG = 30.0
#: A foot is on the floor when its ankle is at most this high (m) above its lowest height in the
#: motion (a walking step lifts it more, standing lifts it less).
FOOT_UP = 0.05
#: A wrist more than this share of the upper arm's length outward of its shoulder is "out to the
#: side of the body" (RULA lower arm +1).
OUT_TO_SIDE_SHARE = 0.5

SIDES = (0, 1)  # left, right


@dataclass
class BodyAngles:
    """Body angles of F frames (degrees; arm arrays are (F, 2), left then right).

    Attributes:
        trunk_flexion, trunk_side_bend, trunk_twist: (F,) see the module docstring; side bend
            positive to the left, twist positive when the shoulders turn left of the hips.
        trunk_inclination: (F,) the trunk axis' angle from the vertical (ISO 11226).
        neck_flexion, neck_side_bend, neck_twist: (F,) the head relative to the trunk.
        upper_arm_angle: signed angle of the upper arm from the trunk's downward axis:
            flexion/abduction positive, extension (the arm behind the trunk, raised mainly
            backwards) negative.
        upper_arm_elevation: angle of the upper arm from the vertical (ISO 11226), 0-180.
        upper_arm_plane: the plane of elevation, 0 forward, 90 straight out to the side.
        elbow_flexion: 0 straight.
        wrist_flexion, wrist_deviation, wrist_twist: palmar flexion, ulnar deviation and forearm
            pronation (positive); zero where the source cannot tell (joint positions only).
        twist_range: the forearm rotation's half range (deg), for the twist's "end of range".
        knee_flexion: 0 straight.
        feet_down: whether each foot is on the ground it stands on.
        walking: (F,) frames of a walk (REBA and RULA count walking as supported legs).
        hands: (F, 2, 3) the grip points (palm centres; wrists for capture), world metres; their
            z above the surface the body stands on when the angles are given its ``ground``.
        ankles: (F, 3) mid-point of the ankles, world metres (z as the hands').
        forward: (F, 3) the pelvis' horizontal forward direction.
        shoulder_raised, lower_arm_out: (F, 2) flags measured from positions.
    """

    trunk_flexion: np.ndarray
    trunk_side_bend: np.ndarray
    trunk_twist: np.ndarray
    trunk_inclination: np.ndarray
    neck_flexion: np.ndarray
    neck_side_bend: np.ndarray
    neck_twist: np.ndarray
    upper_arm_angle: np.ndarray
    upper_arm_elevation: np.ndarray
    upper_arm_plane: np.ndarray
    elbow_flexion: np.ndarray
    wrist_flexion: np.ndarray
    wrist_deviation: np.ndarray
    wrist_twist: np.ndarray
    twist_range: float
    knee_flexion: np.ndarray
    feet_down: np.ndarray
    walking: np.ndarray
    hands: np.ndarray
    ankles: np.ndarray
    forward: np.ndarray
    shoulder_raised: np.ndarray
    lower_arm_out: np.ndarray

    @property
    def n_frames(self) -> int:
        return len(self.trunk_flexion)

    @property
    def trunk_twisted(self) -> np.ndarray:
        return np.abs(self.trunk_twist) > ASYMMETRY_DEG

    @property
    def trunk_side_bent(self) -> np.ndarray:
        return np.abs(self.trunk_side_bend) > ASYMMETRY_DEG

    @property
    def neck_twisted(self) -> np.ndarray:
        return np.abs(self.neck_twist) > ASYMMETRY_DEG

    @property
    def neck_side_bent(self) -> np.ndarray:
        return np.abs(self.neck_side_bend) > ASYMMETRY_DEG

    @property
    def arm_abducted(self) -> np.ndarray:
        """(F, 2) the upper arm raised more than 20 deg mainly sideways."""
        return (np.abs(self.upper_arm_angle) > 20) & (self.upper_arm_plane > ABDUCTION_PLANE_DEG)

    @property
    def wrist_deviated(self) -> np.ndarray:
        return np.abs(self.wrist_deviation) > WRIST_DEVIATED_DEG

    @property
    def wrist_twist_end(self) -> np.ndarray:
        return np.abs(self.wrist_twist) > TWIST_END_SHARE * self.twist_range

    @property
    def legs_supported(self) -> np.ndarray:
        """(F,) both feet on the floor, or walking."""
        return self.feet_down.all(axis=1) | self.walking

    def frames(self, sl: slice | np.ndarray) -> BodyAngles:
        """The angles of some frames.

        Args:
            sl: a slice, or an index or boolean mask array over the F frames.

        Returns:
            A :class:`BodyAngles` of the selected frames (``twist_range`` kept).
        """
        kw: dict = {}
        for name in self.__dataclass_fields__:
            v = getattr(self, name)
            kw[name] = v[sl] if isinstance(v, np.ndarray) else v
        return BodyAngles(**kw)


def _deg(x: np.ndarray) -> np.ndarray:
    return np.degrees(x)


def select_first(conditions: list, choices: list, default):
    """``np.select(conditions, choices, default)``: per element the choice of the first true
    condition, else ``default``; the same values and dtype by nested ``np.where`` (about half
    of ``np.select``'s time on a cycle's frames: it broadcasts and stacks its lists first).

    Args:
        conditions: bool arrays (or scalars) of one shape.
        choices: a value (scalar or array) per condition.
        default: the value where no condition holds.

    Returns:
        The selected values, shaped like the conditions.
    """
    out = default
    for cond, choice in zip(reversed(conditions), reversed(choices), strict=True):
        out = np.where(cond, choice, out)
    return out


#: The joints :func:`angles_from_points` reads (each (F, 3), world metres, z up).
POINTS = (
    "pelvis", "neck", "head", "shoulder_l", "shoulder_r", "elbow_l", "elbow_r", "wrist_l",
    "wrist_r", "hip_l", "hip_r", "knee_l", "knee_r", "ankle_l", "ankle_r",
)  # fmt: skip


def angles_from_points(
    p: dict[str, np.ndarray],
    *,
    head_up: np.ndarray | None = None,
    hands: np.ndarray | None = None,
    wrist: np.ndarray | None = None,
    neck_twist: np.ndarray | None = None,
    twist_range: float = 80.0,
    walking: np.ndarray | None = None,
) -> BodyAngles:
    """Body angles of F frames from joint positions (frames as in the module docstring).

    Args:
        p: the joints :data:`POINTS`, each (F, 3), metres, world frame z up.
        head_up: (F, 3) the head's up direction (default: neck -> head).
        hands: (F, 2, 3) the grip points, world metres (default: the wrists).
        wrist: (F, 2, 3) wrist flexion, ulnar deviation and forearm pronation, degrees
            (default zeros: positions alone do not show them).
        neck_twist: (F,) the neck's axial rotation, degrees (default zeros).
        twist_range: the forearm rotation's half range, degrees.
        walking: (F,) frames of a walk (default none).

    Returns:
        The :class:`BodyAngles` of the F frames.
    """
    pts = point_array(p)
    hu = np.asarray(head_up if head_up is not None else p["head"] - p["neck"], dtype=float)
    if hands is None:
        hands = np.stack([p["wrist_l"], p["wrist_r"]], axis=1)
    return _angles(pts, hu, hands, wrist, neck_twist, twist_range, walking)


def _angles(
    pts: np.ndarray,
    head_up: np.ndarray,
    hands: np.ndarray,
    wrist: np.ndarray | None,
    neck_twist: np.ndarray | None,
    twist_range: float,
    walking: np.ndarray | None,
    ground: np.ndarray | None = None,
) -> BodyAngles:
    """:func:`angles_from_points` of the (14, F, 3) points of
    :data:`~mjwalk.ergonomics.anglejit.KERNEL_POINTS`: the compiled arithmetic
    (:func:`~mjwalk.ergonomics.anglejit.trig_arguments`), then NumPy's arc tangents and arc
    cosines of all frames at once. With ``ground`` ((F,) world z of the surface the body stands
    on in each frame) the heights (hands, ankles, the feet's contact) are above it."""
    n = pts.shape[1]
    ys, xs, cs = np.empty((8, n)), np.empty((8, n)), np.empty((9, n))
    fwd, fwd_c, out = np.empty((n, 3)), np.empty((2, n)), np.empty((n, 2), dtype=bool)
    hu = np.ascontiguousarray(head_up, dtype=float)
    trig_arguments(pts, hu, OUT_TO_SIDE_SHARE, ys, xs, cs, fwd, fwd_c, out)
    at = np.arctan2(ys, xs)
    dt, dc = _deg(at), _deg(np.arccos(cs))
    twist = at[2] - at[3]  # the shoulder line's yaw from the hip line's
    plane, elev = dt[6:8], dc[1:3]
    behind = (fwd_c < 0) & (plane <= ABDUCTION_PLANE_DEG)  # raised mainly backwards
    az = pts[12:14, :, 2]  # the ankles' heights
    ankles = 0.5 * (pts[12] + pts[13])
    low = az.min(axis=1, initial=np.inf)[:, None]  # each ankle's lowest in the motion
    if ground is not None:  # heights above the surface stood on (NIOSH's V: Waters et al. 1993)
        up = np.zeros((n, 3))
        up[:, 2] = ground
        az, hands, ankles = az - up[:, 2], hands - up[:, None, :], ankles - up
        low = _lowest_per_ground(az, up[:, 2])
    w = np.zeros((n, 2, 3)) if wrist is None else np.asarray(wrist, dtype=float)
    return BodyAngles(
        trunk_flexion=dt[0],
        trunk_side_bend=dt[1],
        trunk_twist=_deg((twist + np.pi) % (2 * np.pi) - np.pi),
        trunk_inclination=dc[0],
        neck_flexion=dt[4],
        neck_side_bend=dt[5],
        neck_twist=np.zeros(n) if neck_twist is None else np.asarray(neck_twist, dtype=float),
        upper_arm_angle=np.where(behind, -elev, elev).T,
        upper_arm_elevation=dc[3:5].T,
        upper_arm_plane=plane.T,
        elbow_flexion=dc[5:7].T,
        wrist_flexion=w[:, :, 0],
        wrist_deviation=w[:, :, 1],
        wrist_twist=w[:, :, 2],
        twist_range=float(twist_range),
        knee_flexion=dc[7:9].T,
        feet_down=(az <= low + FOOT_UP).T,
        walking=np.zeros(n, dtype=bool) if walking is None else np.asarray(walking, dtype=bool),
        hands=hands,
        ankles=ankles,
        forward=fwd,
        shoulder_raised=np.zeros((n, 2), dtype=bool),
        lower_arm_out=out,
    )


def _lowest_per_ground(az: np.ndarray, ground: np.ndarray) -> np.ndarray:
    """(2, F) each ankle's lowest height above the ground ``az`` (2, F) among the frames on the
    same ground as each frame (``ground`` (F,), world z): :data:`FOOT_UP`'s "lowest in the
    motion" taken on each surface stood on, so a stair's frames (the pelvis over a tread, the
    trailing foot on the one below) do not lower the floor's or a platform's."""
    levels, at = np.unique(ground, return_inverse=True)
    low = np.full((2, len(levels)), np.inf)
    for side in range(2):
        np.minimum.at(low[side], at, az[side])
    return low[:, at]


#: Humanoid body -> the joint position it stands for (the body's origin is the joint).
_BODY_POINTS = {
    "pelvis": "pelvis", "neck": "neck", "upper_arm_l": "shoulder_l", "upper_arm_r": "shoulder_r",
    "forearm_l": "elbow_l", "forearm_r": "elbow_r", "hand_l": "wrist_l", "hand_r": "wrist_r",
    "thigh_l": "hip_l", "thigh_r": "hip_r", "shin_l": "knee_l", "shin_r": "knee_r",
    "foot_l": "ankle_l", "foot_r": "ankle_r",
}  # fmt: skip
#: The humanoid body of each joint of :data:`_BODY_POINTS`.
_POINT_BODIES = {v: k for k, v in _BODY_POINTS.items()}


def body_frames(
    model, jointmap, qpos: np.ndarray, bodies: list[str], table: GeomTable | None = None
):
    """World poses of humanoid bodies: MuJoCo's forward kinematics compiled over frames
    (:func:`mjwalk.timeline.geomposes.geom_poses`) on each body's first geom, the geom's own
    offset undone, :math:`R_{body} = R_{geom} R_{local}^T`, :math:`p_{body} = p_{geom} -
    R_{body} p_{local}` (``mj_kinematics`` frame by frame for models it does not support).

    Args:
        model: the compiled model with the humanoid.
        jointmap: the humanoid's joint map (its prefix names the bodies).
        qpos: (F, nq) poses.
        bodies: B unprefixed body names.
        table: the geom poses of every frame of ``qpos``, if already computed (read when it
            holds the bodies' first geoms: the same numbers as computing them here).

    Returns:
        ``(pos, rot)``: (F, B, 3) world positions, metres, and (F, B, 3, 3) rotations.
    """
    prefix = jointmap.prefix
    bids = [mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, prefix + b) for b in bodies]
    qpos = np.asarray(qpos, dtype=float).reshape(-1, model.nq)
    if not supported(model):
        data = mujoco.MjData(model)
        pos = np.empty((len(qpos), len(bids), 3))
        rot = np.empty((len(qpos), len(bids), 3, 3))
        for f, q in enumerate(qpos):
            data.qpos[:] = q
            mujoco.mj_kinematics(model, data)
            pos[f] = data.xpos[bids]
            rot[f] = data.xmat[bids].reshape(-1, 3, 3)
        return pos, rot
    gids = np.array([int(model.body_geomadr[b]) for b in bids])
    shared = table.columns(gids) if table is not None and len(table.xpos) == len(qpos) else None
    gpos, gmat = shared if shared is not None else geom_poses(model, qpos, gids)
    n = len(qpos)
    rot = gmat.reshape(n, len(gids), 3, 3)  # R_body = R_geom R_local^T, in place below
    pos = np.empty_like(gpos)
    m = np.empty(9)
    # one (3F x 3) product per body, not F stacked 3x3 products (numpy's stacked matmul costs
    # about 3x more: benchmarks/cycle_timing.py, "ergonomics: angles"); the same sums, so the
    # same floats
    for k, g in enumerate(gids):
        r = np.ascontiguousarray(rot[:, k]).reshape(3 * n, 3)
        if np.any(model.geom_quat[g] != (1.0, 0.0, 0.0, 0.0)):  # R_local is not the identity
            mujoco.mju_quat2Mat(m, model.geom_quat[g])
            r = r @ m.reshape(3, 3).T
            rot[:, k] = r.reshape(n, 3, 3)
        pos[:, k] = gpos[:, k] - (r @ model.geom_pos[g]).reshape(n, 3)
    return pos, rot


def _palm_offset(model, jointmap, tag: str) -> np.ndarray:
    """The palm's centre in the hand body's frame (zeros without a palm geom), metres."""
    g = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, jointmap.prefix + f"palm_{tag}")
    return model.geom_pos[g] if g >= 0 else np.zeros(3)


def _humanoid_points(
    model, jointmap, qpos: np.ndarray, table: GeomTable | None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The joints of :func:`angles_from_qpos` as (14, F, 3) points in the order of
    :data:`~mjwalk.ergonomics.anglejit.KERNEL_POINTS`, the head's up (F, 3) and the palms'
    centres (F, 2, 3): :func:`body_frames`' numbers, read from the geom poses without copying
    the table's columns; a body whose first geom sits on its z axis unrotated (all but the
    pelvis, the neck and the feet) by one compiled pass (:func:`~mjwalk.ergonomics.anglejit.
    z_offsets`), the others by :func:`body_frames`' own NumPy products."""
    bodies = list(_BODY_POINTS)
    qpos = np.asarray(qpos, dtype=float).reshape(-1, model.nq)
    n = len(qpos)
    if not supported(model):
        pos, rot = body_frames(model, jointmap, qpos, bodies, table)
        pts = np.stack([pos[:, bodies.index(_POINT_BODIES[k])] for k in KERNEL_POINTS])
        hands = np.stack(
            [pos[:, bodies.index(f"hand_{t}")] + rot[:, bodies.index(f"hand_{t}")]
             @ _palm_offset(model, jointmap, t) for t in ("l", "r")], axis=1,
        )  # fmt: skip
        return pts, rot[:, bodies.index("neck"), :, 2], hands
    pre = jointmap.prefix
    gids = np.array(
        [model.body_geomadr[mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, pre + b)]
         for b in bodies], dtype=np.int64,
    )  # fmt: skip
    cols = None
    if table is not None and len(table.xpos) == n:  # the table's columns, if it has them all
        c = np.minimum(np.searchsorted(table.geoms, gids), len(table.geoms) - 1)
        if np.array_equal(table.geoms[c], gids):
            cols, xpos, xmat = c, table.xpos, table.xmat
    if cols is None:
        (xpos, xmat), cols = geom_poses(model, qpos, gids), np.arange(len(gids))
    pts = np.empty((len(KERNEL_POINTS), n, 3))
    unrotated = ~np.any(model.geom_quat[gids] != (1.0, 0.0, 0.0, 0.0), axis=1)
    on_z = unrotated & (model.geom_pos[gids, 0] == 0.0) & (model.geom_pos[gids, 1] == 0.0)
    ks = np.array([KERNEL_POINTS.index(_BODY_POINTS[b]) for b in bodies])
    out = np.empty((int(on_z.sum()), n, 3))
    z_offsets(xpos, xmat, cols[on_z], model.geom_pos[gids[on_z], 2], out)
    pts[ks[on_z]] = out
    other = np.flatnonzero(~on_z)
    gpos, gmat = np.empty((len(other), n, 3)), np.empty((len(other), n, 9))
    gather(xpos, xmat, cols[other], gpos, gmat)
    rots: dict[str, np.ndarray] = {}
    for j, gp, gm in zip(other, gpos, gmat, strict=True):
        g = gids[j]
        r = gm.reshape(3 * n, 3)  # body_frames' products, on the same numbers
        if not unrotated[j]:
            m = np.empty(9)
            mujoco.mju_quat2Mat(m, model.geom_quat[g])
            r = r @ m.reshape(3, 3).T
        rots[bodies[j]] = r.reshape(n, 3, 3)
        pts[ks[j]] = gp - (r @ model.geom_pos[g]).reshape(n, 3)
    for j in np.flatnonzero(on_z):
        rots[bodies[j]] = xmat[:, cols[j]].reshape(n, 3, 3)
    hands = np.empty((n, 2, 3))
    for s, t in enumerate(("l", "r")):
        off, r = _palm_offset(model, jointmap, t), rots[f"hand_{t}"]
        wrist_pt = pts[KERNEL_POINTS.index(f"wrist_{t}")]
        hands[:, s] = wrist_pt + (r[:, :, 2] * off[2] if off[0] == off[1] == 0.0 else r @ off)
    return pts, rots["neck"][:, :, 2], hands


def angles_from_timeline(
    timeline,
    walking: np.ndarray | None = None,
    table: GeomTable | None = None,
    ground: np.ndarray | None = None,
) -> BodyAngles:
    """Body angles of every frame of a humanoid :class:`~mjwalk.timeline.timeline.Timeline`.
    The wrists' flexion and deviation, the forearms' pronation and the neck's rotation are the
    humanoid's own hinge angles.

    Args:
        timeline: the humanoid's timeline.
        walking: (F,) frames of a walk (default none).
        table: the humanoid's geom poses in every frame, if already computed
            (:func:`body_frames`).
        ground: (F,) world z (m) of the surface the body stands on in each frame (a platform's
            top under the feet at a raised station); the hands', the ankles' and the feet's
            heights are measured above it (NIOSH's V is the hands' height above the floor the
            worker stands on, Waters et al. 1993). None: world z.

    Returns:
        The :class:`BodyAngles` of its F frames.
    """
    return angles_from_qpos(
        timeline.model, timeline.jointmap, timeline.qpos, walking, table, ground
    )


def angles_from_qpos(
    model,
    jointmap,
    qpos: np.ndarray,
    walking=None,
    table: GeomTable | None = None,
    ground: np.ndarray | None = None,
) -> BodyAngles:
    """:func:`angles_from_timeline` for poses of a model: joint positions from the bodies'
    origins, the head's up the neck body's z, the grip points the palms' centres.

    Args:
        model: the compiled model with the humanoid.
        jointmap: the humanoid's joint map.
        qpos: (F, nq) poses.
        walking: (F,) frames of a walk (default none).
        table: the geom poses of every frame of ``qpos``, if already computed
            (:func:`body_frames`).
        ground: (F,) world z of the surface stood on in each frame (:func:`angles_from_timeline`);
            None: heights are world z.

    Returns:
        The :class:`BodyAngles` of the F frames.
    """
    pts, head_up, hands = _humanoid_points(model, jointmap, qpos, table)
    q = np.asarray(qpos).reshape(-1, model.nq)
    hinges = [f"{j}_{t}_{a}" for t in ("l", "r") for j, a in (("wrist", "flex"), ("wrist", "dev"),
                                                               ("forearm", "pron"))]  # fmt: skip
    adr = [jointmap.adr(h) for h in (*hinges, "neck_rot")]
    deg = np.degrees(q[:, adr])  # one gather: the same degrees, elementwise
    wrist = deg[:, :6].reshape(-1, 2, 3)  # (F, side, flexion / deviation / pronation)
    lo, hi = jointmap.limits("forearm_l_pron")
    return _angles(
        pts,
        head_up,
        hands,
        wrist,
        deg[:, 6],
        float(np.degrees(max(abs(lo), abs(hi)))),
        walking,
        None if ground is None else np.asarray(ground, dtype=float),
    )
