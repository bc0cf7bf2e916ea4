"""Walk -> timeline frames: the per-frame humanoid pose of a walk in a scene.

:func:`timeline_from_walk` builds a :class:`~mjwalk.timeline.timeline.Timeline` from a
:class:`~mjwalk.plan.walkpath.WalkPath`: root position and yaw from the path, root height and
legs from the footprints (:mod:`mjwalk.body.legs`), arms and torso from a simple counter-swing or
the contact-switching gait-pose dynamics (:mod:`mjwalk.body.gaitpose`), eased in and out and
kept clear of nearby obstacles (:func:`ease_arms`, :func:`trunk_turn`).

World frame: metres, seconds, radians, z up, yaw from +x CCW.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np

from mjwalk._args import check_fps
from mjwalk.anthropometry import ARM_SWING_ABDUCTION_DEG
from mjwalk.body.humanoid import JointMap, attach_humanoid, shoulder_geometry
from mjwalk.body.legs import LegMotion, legs_from_walk
from mjwalk.body.legs.curves import smoothstep
from mjwalk.body.legs.pelvistilt import pelvis_quat
from mjwalk.body.legs.trunklean import lean_spine
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.errors import MjwalkError
from mjwalk.plan.lowtops import with_low_tops
from mjwalk.plan.rampside import with_ramps_beside
from mjwalk.plan.walkpath import WalkPath
from mjwalk.timeline.timeline import Event, Timeline
from mjwalk.world.workplace import shared_workplace


def yaw_quat(yaw: np.ndarray) -> np.ndarray:
    """Unit quaternions of rotations by ``yaw`` about +z:
    :math:`q = (\\cos(\\psi/2), 0, 0, \\sin(\\psi/2))`.

    Args:
        yaw: (N,) yaw angles, radians (CCW from +x).

    Returns:
        (N, 4) quaternions (w, x, y, z).
    """
    half = np.asarray(yaw, float) / 2
    q = np.zeros((len(half), 4))
    # cos and sin of the contiguous half angles, then placed (NumPy's strided and contiguous
    # loops may differ in the last bit): the numbers np.column_stack of them gave
    q[:, 0] = np.cos(half)
    q[:, 3] = np.sin(half)
    return q


def arm_swing(angles: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Counter-swing of the arms from the leg angles (radians): each shoulder flexes opposite to
    its own hip (the arm swings with the other leg), about 0.45 of the hip excursion, elbows
    slightly bent (15 deg plus a third of the shoulder flexion), arms 6 deg abducted. A cheap
    stand-in for the gait-pose dynamics (:mod:`mjwalk.body.gaitpose`).

    Args:
        angles: the leg joint angles by unprefixed name, each (F,) radians; reads
            ``hip_l_flex`` and ``hip_r_flex``.

    Returns:
        ``shoulder_{l,r}_flex``, ``shoulder_{l,r}_abd`` and ``elbow_{l,r}``, each (F,) radians.
    """
    out = {}
    for s in "lr":
        hip = angles[f"hip_{s}_flex"]
        sh = -0.45 * (hip - np.mean(hip))
        out[f"shoulder_{s}_flex"] = sh
        out[f"shoulder_{s}_abd"] = np.full_like(hip, np.deg2rad(ARM_SWING_ABDUCTION_DEG))
        out[f"elbow_{s}"] = np.deg2rad(15) + np.clip(sh, 0, None) / 3
    return out


def timeline_from_walk(
    walk: WalkPath,
    scene: str | Path | mujoco.MjSpec,
    fps: float = 30.0,
    stature: float = DEFAULT_STATURE,
    arms: str = "swing",
    rng: np.random.Generator | None = None,
) -> Timeline:
    """Build the Timeline of a walk in a scene.

    Args:
        walk: the planned walk (root trajectory at 120 Hz with steps and footprints).
        scene: an MJCF scene file or an MjSpec; the humanoid is attached (the file is not edited).
        fps: frame rate of the timeline (the video rate).
        stature: the humanoid's stature in metres.
        arms: ``"swing"`` (counter-swing from the legs), ``"gaitpose"`` (arms and torso from the
            contact-switching GP dynamics, :mod:`mjwalk.body.gaitpose`; fits its default model
            once per process, ~10 s) or ``"none"`` (arms hang).
        rng: picks the gait-pose rollout's start (``arms="gaitpose"``).

    Returns:
        the Timeline (frames at ``t = 0, 1/fps, ...`` up to the walk's duration).
    """
    fps = check_fps(fps, "timeline_from_walk: fps must be")
    walk.validate("timeline_from_walk: walk")
    model, jm = attach_humanoid(scene, stature)
    floor_z = 0.0  # an MjSpec's floor: at z = 0
    if not isinstance(scene, mujoco.MjSpec):  # feet on a ramp's low end the walk cuts past
        wp = shared_workplace(scene)
        walk, floor_z = with_ramps_beside(wp, walk, stature), wp.floor_z
        walk = with_low_tops(wp, walk, stature)  # and on a mat or cable bridge under it
    legs = legs_from_walk(walk, stature)
    t = np.arange(0.0, walk.duration + 1e-9, 1.0 / fps)
    qpos = frames_from_legs(model, jm, legs, t, stature, arms, rng)
    qpos[:, jm.root + 2] += floor_z  # the walk's heights are above the floor
    if arms != "none":
        room, away = room_in_scene(scene, qpos[:, jm.root : jm.root + 2])
        rest = jm.neutral_qpos(model, stature)
        clearance = None if room is None else Clearance(room, away)
        ease_arms(qpos, t, walk.duration, jm, rest, clearance, stature=stature)
    events = []
    for st in walk.steps:
        side = st.side
        events.append(Event(float(walk.t[st.start]), "toe_off", side))
        events.append(Event(float(walk.t[st.end]), "heel_strike", side))
    events.sort(key=lambda e: e.time)
    contact = np.interp(t, legs.t, legs.contact).round().astype(int)
    return Timeline(
        model=model,
        jointmap=jm,
        fps=float(fps),
        t=t,
        qpos=qpos,
        events=events,
        contact=contact,
        walk=walk,
        scene=str(scene) if not isinstance(scene, mujoco.MjSpec) else "<MjSpec>",
        stature=stature,
    )


#: Seconds over which the arm swing (or a carrying posture) fades in and out of a walk.
ARM_EASE = 0.6
#: The arms swing fully with at least ARM_ROOM[1] metres of room around the pelvis (distance to
#: the nearest obstacle footprint), not at all below ARM_ROOM[0]: people keep their arms in
#: when they pass close to a rack, a wall or a car. The figures are for the reference stature
#: (DEFAULT_STATURE, 1.75 m) and scale with the operator's (:func:`arm_room`): every segment of
#: the humanoid scales with stature, so the hand's reach from the pelvis does too (the carrying
#: hand's lowest margin over the ramp, the fingertips' horizontal distance from the pelvis
#: against the room, is 3.6 cm at 1.75 m; with the ramp in fixed metres it was -0.4 cm at 1.90 m
#: and -3.7 cm at 2.02 m, where the fingers met the car in runs 732 and 1238 of the 2000-run
#: batch: tests/timeline/test_frames.py).
ARM_ROOM = (0.35, 0.6)
#: Carrying posture of the hand that holds a part (radians): upper arm slightly back, elbow
#: flexed 105 degrees, so the part is held close in front of the trunk.
CARRY_POSE = {"shoulder_flex": -0.15, "shoulder_abd": 0.12, "elbow": 1.83}


#: Forearm pronation (radians) of a hanging arm where there is no room for the swing: the palm
#: turns towards the thigh and the thumb forward, so the hand stays inside the shoulders.
TUCK_PRONATION = np.deg2rad(45.0)
#: Clearance (m) kept between the shoulders and the nearest obstacle by turning the trunk.
SHOULDER_MARGIN = 0.01
#: The spine's flexion joints a stair ascent's trunk lean bends (:func:`lean_spine`'s order).
TRUNK_JOINTS = ("lumbar_flex", "thoracic_flex")
#: Largest trunk rotation against the pelvis (radians): lumbar (5 deg range) plus thoracic.
TRUNK_TURN = np.deg2rad(38.0)
#: Seconds over which the trunk rotation is smoothed (a centred moving average).
TRUNK_SMOOTH = 0.3


def trunk_turn(
    yaw: np.ndarray,
    room: np.ndarray,
    away: np.ndarray,
    stature: float = DEFAULT_STATURE,
    fps: float = 30.0,
) -> np.ndarray:
    """Trunk rotation (radians, + CCW about z; (F,)) that keeps the shoulders clear of the
    nearest obstacle in narrow places: people turn their shoulders to pass a wall corner.

    Args:
        yaw: (F,) pelvis yaw, radians.
        room: (F,) distance from the pelvis centre to the nearest obstacle footprint, metres.
        away: (F, 2) unit vectors pointing away from that obstacle (the clearance gradient).
        stature: the humanoid's stature (sets the shoulder width).
        fps: frame rate (for the smoothing).

    The shoulder line (joint centres ``a`` from the trunk axis plus the upper-arm radius ``r``)
    reaches ``a |cos d| + r`` towards an obstacle in a direction ``d`` from it; the trunk turns
    by the least angle that brings this within ``room - SHOULDER_MARGIN``, up to
    :data:`TRUNK_TURN`. Zero where there is room. Over one passage (consecutive frames that
    need a turn) the trunk turns one way only (:func:`turn_sides`): where the shoulder line
    swings through the obstacle's direction the least turn changes side, and a frame-by-frame
    choice threw the trunk 30 degrees and a hanging hand 0.1 m between frames (the 1.88 m
    operator of run 33 of the multilevel_platform batch, whose left palm met the trolley).

    Returns:
        (F,) trunk rotation, radians, within :data:`TRUNK_TURN`.
    """
    a, r = shoulder_geometry(stature)
    c = np.clip((room - SHOULDER_MARGIN - r) / a, 0.0, 1.0)
    need = np.arccos(c)  # least angle between the shoulder line and the obstacle direction
    gamma = np.arctan2(-away[:, 1], -away[:, 0])  # towards the obstacle
    d = np.mod(yaw + np.pi / 2 - gamma + np.pi / 2, np.pi) - np.pi / 2  # axis: fold to +-pi/2
    side = turn_sides(d, need)
    turn = side * np.maximum(need - side * d, 0.0) * (np.abs(d) < need)
    turn = np.clip(turn, -TRUNK_TURN, TRUNK_TURN)
    k = max(1, round(TRUNK_SMOOTH * fps) | 1)
    if k > 1 and len(turn) > k:
        h = k // 2  # (np.pad(turn, h, mode="edge"): the end values repeated)
        pad = np.concatenate((np.full(h, turn[0]), turn, np.full(h, turn[-1])))
        smooth = np.convolve(pad, np.ones(k) / k, mode="valid")
        # smoothing must not undercut the turn a frame needs
        turn = np.where(np.abs(smooth) >= np.abs(turn), smooth, turn)
    return turn


def turn_sides(d: np.ndarray, need: np.ndarray) -> np.ndarray:
    """The side (+1 CCW, -1 CW) the trunk turns to at each frame: one side per passage.

    A passage is a run of consecutive frames whose shoulder line is nearer the obstacle's
    direction than it may be (``|d| < need``). Turning to side ``s`` takes ``need - s d``;
    the passage keeps the side of its first frame's least turn, which is the least turn's
    side at every frame unless the shoulder line swings through the obstacle's direction
    (``d`` changes sign) within the passage: the trunk starts turning away as the obstacle
    comes near and does not turn back through it (taking the other side from the start
    instead threw the trunk 37 degrees through the obstacle's direction as the passage began:
    a thumb met the stair's wall in run 5 of the same batch). Where keeping the side would
    take more than :data:`TRUNK_TURN` the shoulders cannot be kept clear on it, and each
    frame takes its least turn's side as before (run 13: the kept side's 43 degrees, clipped
    and then dropped as the passage ended, put the right arm 3.8 mm into the stair's wall).

    Args:
        d: (F,) angle from the obstacle's direction to the shoulder line, radians, in
            [-pi/2, pi/2).
        need: (F,) least angle the shoulder line must keep from it, radians.

    Returns:
        (F,) +1.0 or -1.0 (the least turn's side, ``sign(d)`` with +1 at 0, outside passages).
    """
    side = np.where(d >= 0, 1.0, -1.0)
    inside = np.abs(d) < need
    edges = np.flatnonzero(np.diff(np.concatenate([[0], inside.astype(np.int8), [0]])))
    for lo, hi in zip(edges[::2], edges[1::2], strict=True):
        s = side[lo]
        if np.all(side[lo:hi] == s) or np.max(need[lo:hi] - s * d[lo:hi]) > TRUNK_TURN:
            continue  # no swing through, or a turn the trunk cannot make: the least turn's side
        side[lo:hi] = s
    return side


@dataclass(frozen=True)
class Clearance:
    """The room around the pelvis positions of a walk's frames.

    Attributes:
        room: (F,) metres from the pelvis to the nearest obstacle.
        away: (F, 2) unit vectors (world x, y) away from the nearest obstacle, or None.
    """

    room: np.ndarray
    away: np.ndarray | None = None


@dataclass(frozen=True)
class Carry:
    """What the hands hold during a walk.

    Attributes:
        hands: "left", "right" or "both": the hands in the carrying posture.
        abduction: shoulder abduction (radians) of a two-handed carry (None: :data:`CARRY_POSE`).
    """

    hands: str
    abduction: float | None = None


def arm_room(stature: float) -> tuple[float, float]:
    """The room around the pelvis (metres to the nearest obstacle footprint) below which the
    arms start keeping in, and below which they hang: :data:`ARM_ROOM` scaled from the
    reference stature to ``stature`` (the humanoid's arm scales with stature).

    Args:
        stature: the humanoid's stature, metres.

    Returns:
        ``(none, full)``: metres of room at which the swing is nil and full.
    """
    scale = stature / DEFAULT_STATURE
    return ARM_ROOM[0] * scale, ARM_ROOM[1] * scale


def ease_arms(
    qpos: np.ndarray,
    t: np.ndarray,
    duration: float,
    jm: JointMap,
    rest: np.ndarray,
    clearance: Clearance | None = None,
    carry: Carry | None = None,
    stature: float = DEFAULT_STATURE,
) -> np.ndarray:
    """Shape the arm motion of walking frames ``qpos`` (F, nq) in place and return it.

    The swing (or, for a one-handed ``carry``, that hand's carrying posture) fades in over
    the first and out over the last :data:`ARM_EASE` seconds, so the arms hang at rest when the
    walker stops, and shrinks where the clearance's room falls below :data:`ARM_ROOM` (scaled
    to the stature, :func:`arm_room`); there
    the hanging hands turn their thumbs forward (:data:`TUCK_PRONATION`). For a carry with
    both hands both arms hold the carrying posture, with the carry's shoulder abduction when
    given, over the whole walk without fading or shrinking: the hands stay on a two-handed
    part's grips, which they took before the walk and leave after it. With the clearance's
    ``away`` the trunk also turns its shoulders clear of the obstacle (:func:`trunk_turn`).

    Args:
        qpos: (F, nq) the walk's frames, edited in place.
        t: (F,) frame times, seconds from the walk's start.
        duration: the walk's duration, seconds.
        jm: the humanoid's joint map.
        rest: (nq,) the standing pose the arms hang in.
        clearance: room and away directions at the frames (None: no obstacle term).
        carry: what the hands hold (None: both arms swing).
        stature: the humanoid's stature, metres (its shoulder width for the trunk turn).

    Returns:
        ``qpos``, shaped.
    """
    room = None if clearance is None else clearance.room
    away = None if clearance is None else clearance.away
    carry_abd = None if carry is None else carry.abduction
    hands = None if carry is None else carry.hands
    w = np.clip(np.minimum(t, duration - t) / ARM_EASE, 0.0, 1.0)
    tight = np.zeros(len(t))
    if room is not None:
        none, full = arm_room(stature)
        free = np.clip((room - none) / (full - none), 0.0, 1.0)
        w = np.minimum(w, free)
        tight = 1.0 - free
        tight = smoothstep(tight)
    w = smoothstep(w)
    ease = np.clip(np.minimum(t, duration - t) / ARM_EASE, 0.0, 1.0)
    ease = smoothstep(ease)
    for side in "lr":
        for joint in (f"shoulder_{side}_flex", f"shoulder_{side}_abd", f"elbow_{side}"):
            k = jm.adr(joint)
            target = qpos[:, k]
            holds = hands is not None and (hands == "both" or side == hands[0])
            if holds:
                name = joint.replace(f"_{side}", "")
                pose = CARRY_POSE[name]
                if hands == "both" and carry_abd is not None and name == "shoulder_abd":
                    pose = carry_abd
                target = np.full_like(target, pose)
            wk = np.ones_like(w) if hands == "both" else w
            qpos[:, k] = rest[k] + wk * (target - rest[k])
        if hands is None or not (hands == "both" or side == hands[0]):
            # the tuck narrows a swinging arm: it eases in and out with the swing (a hanging
            # arm at the start and the end of the walk is the standing pose, untucked)
            k = jm.adr(f"forearm_{side}_pron")
            qpos[:, k] = qpos[:, k] + tight * ease * (TUCK_PRONATION - qpos[:, k])
    if room is not None and away is not None:
        fps = 1.0 / float(_median(np.diff(t))) if len(t) > 1 else 30.0
        lumbar, thoracic = trunk_rotation(qpos, jm, room, away, stature, fps)
        qpos[:, jm.adr("lumbar_rot")] += lumbar
        qpos[:, jm.adr("thoracic_rot")] += thoracic
    return qpos


def _median(x: np.ndarray) -> float:
    """``np.median`` of a 1-D float array without NaN, as it computes it (the middle value,
    or the mean of the middle two: their sum halved), without its wrapper's cost."""
    s, h = np.sort(x), len(x) // 2
    return float(s[h]) if len(x) % 2 else float((s[h - 1] + s[h]) / 2.0)


def trunk_rotation(
    qpos: np.ndarray,
    jm: JointMap,
    room: np.ndarray,
    away: np.ndarray,
    stature: float,
    fps: float,
) -> tuple[np.ndarray, np.ndarray]:
    """The trunk's rotation that turns the shoulders clear of the nearest obstacle at frames
    ``qpos`` (:func:`trunk_turn` at each frame's pelvis yaw), the lumbar joint taking its
    range first and the thoracic joint the rest, each clipped to its range.

    Args:
        qpos: (F, nq) the frames (their root's yaw is read).
        jm: the humanoid's joint map.
        room: (F,) the room at each frame's pelvis, metres (:func:`room_and_away`).
        away: (F, 2) the unit direction away from the nearest obstacle, world x, y.
        stature: the humanoid's stature, metres.
        fps: frames per second.

    Returns:
        ``(lumbar, thoracic)``: (F,) each, radians, to add to the pose's own.
    """
    yaw = 2.0 * np.arctan2(qpos[:, jm.root + 6], qpos[:, jm.root + 3])
    turn = trunk_turn(yaw, room, away, stature, fps)
    lumbar = np.clip(turn, *jm.limits("lumbar_rot"))
    return lumbar, np.clip(turn - lumbar, *jm.limits("thoracic_rot"))


def room_and_away(workplace, xy: np.ndarray, h: float = 0.02) -> tuple[np.ndarray, np.ndarray]:
    """Clearance at pelvis positions and the directions away from the nearest obstacle
    (central differences of the clearance field).

    Args:
        workplace: the scene's :class:`~mjwalk.world.workplace.Workplace`.
        xy: (F, 2) pelvis positions, world metres.
        h: the differences' step, metres.

    Returns:
        ``(room, away)``: (F,) clearance in metres and (F, 2) unit vectors away from the
        nearest obstacle (+x where the gradient vanishes).
    """
    xy = np.asarray(xy, float)
    ex, ey = np.array([h, 0.0]), np.array([0.0, h])
    # the five lookups in one call (the field is looked up point by point: the same numbers)
    c = workplace.clearance(np.stack([xy, xy + ex, xy - ex, xy + ey, xy - ey]))
    room = c[0]
    g = np.column_stack([c[1] - c[2], c[3] - c[4]])
    n = np.linalg.norm(g, axis=1, keepdims=True)
    return room, np.where(n > 1e-12, g / np.maximum(n, 1e-12), [1.0, 0.0])


def room_in_scene(scene, xy: np.ndarray) -> tuple[np.ndarray | None, np.ndarray | None]:
    """Room around pelvis positions in ``scene`` and the directions away from the nearest
    obstacle (:func:`room_and_away` of the scene's shared workplace).

    Args:
        scene: an MJCF scene file or an MjSpec.
        xy: (F, 2) pelvis positions, world metres.

    Returns:
        ``(room, away)`` as :func:`room_and_away`; ``(None, None)`` for an in-memory MjSpec.
    """
    if isinstance(scene, mujoco.MjSpec):
        return None, None
    return room_and_away(shared_workplace(scene), xy)


def frames_from_legs(
    model: mujoco.MjModel,
    jm: JointMap,
    legs: LegMotion,
    t: np.ndarray,
    stature: float,
    arms: str,
    rng: np.random.Generator | None,
) -> np.ndarray:
    """The humanoid's poses at times ``t``: root and legs interpolated from ``legs``, arms and
    torso by ``arms``, every angle clipped to its joint range. Up a stair the pelvis is tilted
    by ``legs.meta["pelvis_tilt"]`` (radians, + forward; :mod:`mjwalk.body.legs.pelvistilt`)
    and the lumbar joint flexed by as much the other way, so the trunk keeps its pose; then
    the lumbar and thoracic joints flex by ``legs.meta["trunk_lean"]`` (radians, + forward;
    :mod:`mjwalk.body.legs.trunklean`), so the trunk leans forward by it.

    Args:
        model: the compiled scene with the humanoid.
        jm: the humanoid's joint map.
        legs: the leg motion of a walk.
        t: (F,) frame times, seconds.
        stature: the humanoid's stature, metres.
        arms: "swing", "gaitpose" or "none" (see :func:`timeline_from_walk`).
        rng: picks the gait-pose rollout's start (``arms="gaitpose"``).

    Returns:
        (F, nq) qpos.

    Raises:
        MjwalkError: an unknown ``arms``.
    """
    qpos = np.tile(jm.neutral_qpos(model, stature), (len(t), 1))
    r = jm.root
    for k in range(3):
        qpos[:, r + k] = np.interp(t, legs.t, legs.root[:, k])
    yaw = np.interp(t, legs.t, legs.yaw)
    tilt = legs.meta.get("pelvis_tilt")  # a stair ascent's pelvic tilt (pelvistilt)
    qpos[:, r + 3 : r + 7] = (
        yaw_quat(yaw) if tilt is None else pelvis_quat(yaw, np.interp(t, legs.t, tilt))
    )
    angles = {name: np.interp(t, legs.t, v) for name, v in legs.angles.items()}
    if arms == "swing":
        angles.update(arm_swing(angles))
    elif arms == "gaitpose":
        # deferred: mjwalk.body.gaitpose imports scikit-learn (slow), only for arms="gaitpose"
        from mjwalk.body.gaitpose import upper_body_from_legs

        angles.update(upper_body_from_legs(legs, t, rng=rng))
    elif arms != "none":
        raise MjwalkError(f"timeline_from_walk: arms={arms!r}; use 'swing', 'gaitpose' or 'none'")
    if tilt is not None:  # the lumbar joint takes the pelvis's tilt back (the trunk kept)
        lumbar = angles.get("lumbar_flex", qpos[:, jm.qposadr[jm.index("lumbar_flex")]])
        angles["lumbar_flex"] = lumbar - np.interp(t, legs.t, tilt)
    lean = legs.meta.get("trunk_lean")  # a stair ascent's forward trunk lean (trunklean)
    if lean is not None:
        lumbar, thoracic = (angles.get(j, qpos[:, jm.qposadr[jm.index(j)]]) for j in TRUNK_JOINTS)
        bent = lean_spine(lumbar, thoracic, np.interp(t, legs.t, lean))
        angles.update(zip(TRUNK_JOINTS, bent, strict=True))
    if angles:  # every angle clipped to its range at once (the same clip as one by one)
        idx = np.array([jm.index(name) for name in angles], dtype=np.intp)
        lo, hi = jm.range[idx, 0], jm.range[idx, 1]
        clipped = np.clip(np.array(list(angles.values())), lo[:, None], hi[:, None])
        qpos[:, jm.qposadr[idx]] = clipped.T
    return qpos
