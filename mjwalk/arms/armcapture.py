"""Reach movements from capture: a take's arm joints -> (constraint, directions) training pairs.

One clip becomes one movement of the arm model (Al-Zubi & Sommer §4.1), as
``benchmarks/bench_reach.py`` measures it and as a user trains a
:class:`~mjwalk.arms.reach.ReachModel` on their own clips:

* frame: the moving arm's shoulder at the origin in every frame, axes of the body frame of the
  first frame (x forward, y left, z up; the pelvis yaw of frame 0), metres; a right arm is
  mirrored through the sagittal plane (y -> -y, :data:`~mjwalk.arms.chain.MIRROR_Y`) into
  the left arm's frame: the reach model is a left-arm model, mirrored back for the right arm;
* time alignment: the one movement holding the fastest hand frame, from rest to the first stop
  (5 % of the peak hand speed, :func:`~mjwalk.arms.armrep.movement_span`), optionally before
  the hand's highest point (a raise that is held and creeps upwards while held);
* sampling: the chain shoulder, elbow, wrist at ``n`` equal time intervals (paper: n = 20);
* constraint (9,): start elbow, start hand and end hand positions (metres, shoulder frame): the
  start posture and the end of the reach, what a planner knows before it.

With ``hand=True`` the chain goes on to the end of the hand, three segments like the humanoid's
arm (upper arm, forearm, hand), and the constraint (6,) is the start and end position of the
hand's end: an *endpoint* model, the kind a cycle drives the humanoid with
(:func:`~mjwalk.arms.reach.check_endpoint_model`). The hand's end is the joint in
:data:`HAND_ENDS` (the CMU ``fingers`` bone's end) where the capture has one; where it has none
(the Bandai BVH's hand ``End Site`` lies on the wrist, offset 0; the CMU BVH conversions) the
hand continues the forearm -- a neutral wrist, what capture without hand markers implies --
with the hand's length in Winter's proportion to the forearm (:data:`HAND_TO_FOREARM`). A
cycle's reaches then start where the clips' reaches start
(:attr:`~mjwalk.arms.reach.ReachModel.rest_hand`), and ``[models] reach`` / ``reach_right`` of
a cycle file take the two sides' models (:mod:`mjwalk.cycle.spec`).

Body size: people differ in arm length, and the directions of the segments (what the model
predicts) do not depend on it, but positions do. Each movement's constraint is scaled to one
reference arm (``ArmMovements.lengths``: the clips' mean upper-arm and forearm lengths unless
given), as if the same movement were made by an arm of that length: geometric similarity of
the arm, whose segments are fixed shares of stature (Winter 2009, *Biomechanics and Motor
Control of Human Movement*, Table 4.1; :data:`~mjwalk.arms.chain.ARM_SEGMENT_SHARES`). A
simulated operator's targets are scaled into the model's size the same way
(:mod:`mjwalk.cycle.reaching`), so a tall and a short walker making the same movement give the
same training pair.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from mjwalk.arms.armrep import movement_span, resample_trajectory, segment_directions
from mjwalk.arms.chain import ARM_SEGMENT_SHARES, MIRROR_Y
from mjwalk.conventions import Side
from mjwalk.errors import CaptureError, MjwalkError
from mjwalk.mocap.take import Take

#: Samples per movement (Al-Zubi & Sommer §4.1: n = 20).
N_SAMPLES = 20
#: Fewer frames than this between onset and stop: not a movement (a twitch or a tracking jump).
MIN_FRAMES = 5
#: Less hand travel (start to end, metres) than this: not a reach but a hand held still (the
#: 5 % speed threshold is relative, so a still hand's tracking noise is "a movement" too). The
#: MTM-1 Reach table's shortest class, 3/4 inch or less, is one time for every distance: a
#: finger movement, not an arm's (MTM Association data card; :mod:`mjwalk.cycle.handling`).
MIN_TRAVEL = 0.75 * 0.0254
#: Shoulder, elbow and wrist joint of each arm, per skeleton preset
#: (:data:`mjwalk.mocap.skeletons.SKELETONS`). CMU ASF bones are named after the bone that
#: starts at the joint (``lhumerus`` at the shoulder, ``lradius`` at the elbow, ``lwrist`` at
#: the wrist).
ARM_JOINTS: dict[str, dict[str, tuple[str, str, str]]] = {
    "bandai": {
        "left": ("UpperArm_L", "LowerArm_L", "Hand_L"),
        "right": ("UpperArm_R", "LowerArm_R", "Hand_R"),
    },
    "cmu": {
        "left": ("lhumerus", "lradius", "lwrist"),
        "right": ("rhumerus", "rradius", "rwrist"),
    },
    "cmu_bvh": {
        "left": ("LeftArm", "LeftForeArm", "LeftHand"),
        "right": ("RightArm", "RightForeArm", "RightHand"),
    },
}
#: The end of each arm's hand (the tip of the humanoid's hand segment), per skeleton preset: the
#: Bandai BVH ``End Site`` of the hand joint (offset 0 in the Bandai clips: no hand) and the end
#: of the CMU ASF ``fingers`` bone (:mod:`mjwalk.mocap.asf` names a bone's end ``<bone>_end``).
#: The CMU BVH conversions end their hands in fingers of varying names, so they have none here.
HAND_ENDS: dict[str, dict[str, str]] = {
    "bandai": {"left": "Hand_L_end", "right": "Hand_R_end"},
    "cmu": {"left": "lfingers_end", "right": "rfingers_end"},
}
#: Hand length over forearm length, for a hand the capture does not hold (Winter 2009, Table
#: 4.1: hand 0.108 H, forearm 0.146 H; :data:`~mjwalk.arms.chain.ARM_SEGMENT_SHARES`).
HAND_TO_FOREARM = ARM_SEGMENT_SHARES[2] / ARM_SEGMENT_SHARES[1]
#: A hand-end joint nearer the wrist than this (m, median over the take) is no hand: the
#: capture holds none (a zero-offset ``End Site``). A real hand is 15-20 cm.
MIN_HAND = 0.02


@dataclass
class ArmMovements:
    """Movements of one arm, in the left arm's shoulder frame (metres; module docstring).

    Attributes:
        constraints: (p, 9) start elbow, start hand, end hand positions (m), or with the hand
            (``hand=True``) (p, 6) start and end of the hand's end, scaled to ``lengths``.
        directions: (p, n, S, 3) unit segment directions over time: upper arm and forearm
            (S = 2), and the hand with ``hand=True`` (S = 3).
        lengths: (S,) reference segment lengths (m) the constraints are scaled to.
        scales: (p,) factor each clip's positions were scaled by (reference arm length over the
            clip's; 1 for a clip of the reference size).
        groups: (p,) group of each movement (style or walker: the leave-one-group-out groups).
        names: name of each movement's take.
    """

    constraints: np.ndarray
    directions: np.ndarray
    lengths: np.ndarray
    scales: np.ndarray
    groups: np.ndarray
    names: list[str]

    def __len__(self) -> int:
        return len(self.constraints)


def arm_chain(take: Take, side: Side, skeleton: str = "bandai", hand: bool = False) -> np.ndarray:
    """(T, 3, 3) shoulder, elbow, wrist positions of ``side``'s arm in ``take`` (world, m),
    joint names from :data:`ARM_JOINTS`; with ``hand`` (T, 4, 3), the hand's end last: the
    :data:`HAND_ENDS` joint, or where the take has none (or one on the wrist), the forearm
    continued by :data:`HAND_TO_FOREARM` of its length. A take without the arm's joints raises
    CaptureError naming them.

    Args:
        take: the capture take.
        side: "left" or "right".
        skeleton: key of :data:`ARM_JOINTS` naming the joints.
        hand: append the hand's end.

    Returns:
        (T, 3, 3) or (T, 4, 3) positions, world frame, metres.
    """
    if skeleton not in ARM_JOINTS:
        raise MjwalkError(
            f"arm joints: unknown skeleton {skeleton!r} (choose from {sorted(ARM_JOINTS)})"
        )
    if side not in ("left", "right"):
        raise MjwalkError(f"arm joints: side must be 'left' or 'right', got {side!r}")
    names = ARM_JOINTS[skeleton][side]
    missing = [j for j in names if j not in take.joints]
    if missing:
        raise CaptureError(
            f"{take.name}: no joint {', '.join(missing)} (the {side} arm of the {skeleton} "
            f"skeleton: {', '.join(names)}); joints present: {', '.join(take.joints) or 'none'}"
        )
    chain = np.stack([take.joints[j] for j in names], axis=1)
    if not hand:
        return chain
    wrist = chain[:, 2]
    tip = take.joints.get(HAND_ENDS.get(skeleton, {}).get(side, ""))
    if tip is None or np.median(np.linalg.norm(tip - wrist, axis=1)) < MIN_HAND:
        tip = wrist + HAND_TO_FOREARM * (wrist - chain[:, 1])  # a neutral wrist
    return np.concatenate([chain, np.asarray(tip, dtype=float)[:, None]], axis=1)


def arm_movement(
    chain: np.ndarray,
    yaw: float,
    side: Side = "left",
    n: int = N_SAMPLES,
    until_highest: bool = True,
) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """One movement of an arm ``chain`` (T, 3, 3): shoulder, elbow, wrist positions (world,
    metres, z up) with the body heading ``yaw`` (radians from +x) at the first frame; or (T, 4,
    3) with the hand's end last.

    Returns ``(constraint, directions (n, S, 3), lengths (S,))`` in the left arm's shoulder
    frame (module docstring), unscaled (``lengths`` are this clip's), or None when the clip holds
    no movement of at least :data:`MIN_FRAMES` frames and :data:`MIN_TRAVEL` metres. The
    constraint is (9,) start elbow, start wrist, end wrist for a 3-joint chain and (6,) start
    and end of the hand's end for a 4-joint one; the movement is timed on the chain's last
    joint. ``until_highest``: the movement ends by that joint's highest frame (a raise held and
    creeping upwards while held).

    Args:
        chain: (T, 3, 3) or (T, 4, 3) joint positions, world frame, metres, z up.
        yaw: body heading at the first frame, radians CCW from +x.
        side: the arm; a right arm is mirrored into the left arm's frame.
        n: samples of the movement.
        until_highest: end the movement by the last joint's highest frame.

    Returns:
        ``(constraint, directions, lengths)`` as above, or None.
    """
    P = np.asarray(chain, dtype=float)
    if P.ndim != 3 or P.shape[1:] not in ((3, 3), (4, 3)) or len(P) < 2:
        raise MjwalkError(
            f"arm_movement: need a (T >= 2, 3, 3) arm chain or a (T >= 2, 4, 3) one with the "
            f"hand, got {P.shape}"
        )
    if not np.isfinite(P).all():
        raise CaptureError("arm_movement: the arm chain holds NaN or infinite positions")
    c, s = np.cos(-yaw), np.sin(-yaw)
    rz = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    P = (P - P[:, :1]) @ rz.T  # shoulder at the origin, body frame of frame 0
    if side == "right":
        P = P * MIRROR_Y  # into the left arm's frame
    until = int(np.argmax(P[:, -1, 2])) if until_highest else None
    a, b = movement_span(P[:, -1], until=until)
    if b - a + 1 < MIN_FRAMES:
        return None
    Pn = resample_trajectory(P[a : b + 1], n)
    if np.linalg.norm(Pn[-1, -1] - Pn[0, -1]) < MIN_TRAVEL:
        return None
    lengths = np.linalg.norm(np.diff(P[a], axis=0), axis=1)
    if P.shape[1] == 4:
        return np.r_[Pn[0, 3], Pn[-1, 3]], segment_directions(Pn), lengths
    return np.r_[Pn[0, 1], Pn[0, 2], Pn[-1, 2]], segment_directions(Pn), lengths


def arm_movements(
    takes: Sequence[Take],
    side: Side = "left",
    skeleton: str = "bandai",
    groups: Sequence[str] | None = None,
    lengths: np.ndarray | None = None,
    n: int = N_SAMPLES,
    until_highest: bool = True,
    hand: bool = False,
) -> ArmMovements:
    """The movement of ``side``'s arm in every take (see :func:`arm_movement`; takes without
    one are left out), constraints scaled to the reference arm ``lengths`` (S,) m (default:
    the mean over the clips). ``groups``: one label per take (style or walker). ``hand``: the
    chain goes on to the hand's end and the constraint is its start and end (6,): an endpoint
    model for cycles (module docstring).

    Args:
        takes: capture takes.
        side: "left" or "right".
        skeleton: key of :data:`ARM_JOINTS`.
        groups: one label per take, or None.
        lengths: (S,) reference segment lengths, metres, or None (the mean).
        n: samples per movement.
        until_highest: as in :func:`arm_movement`.
        hand: chain to the hand's end, endpoint constraint (6,).

    Returns:
        the training pairs (:class:`ArmMovements`).
    """
    if groups is not None and len(groups) != len(takes):
        raise MjwalkError(f"arm_movements: {len(groups)} groups for {len(takes)} takes")
    n_seg, n_con = (3, 6) if hand else (2, 9)
    C, U, L, G, names = [], [], [], [], []
    for i, take in enumerate(takes):
        out = arm_movement(
            arm_chain(take, side, skeleton, hand),
            float(take.pelvis_yaw[0]),
            side,
            n,
            until_highest,
        )
        if out is None:
            continue
        C.append(out[0])
        U.append(out[1])
        L.append(out[2])
        G.append("?" if groups is None else str(groups[i]))
        names.append(take.name)
    if not C:
        empty = np.full(n_seg, np.nan) if lengths is None else np.asarray(lengths, dtype=float)
        return ArmMovements(
            np.zeros((0, n_con)),
            np.zeros((0, n, n_seg, 3)),
            empty,
            np.zeros(0),
            np.array([]),
            [],
        )
    ref = np.mean(L, axis=0) if lengths is None else np.asarray(lengths, dtype=float)
    if ref.shape != (n_seg,) or not (ref > 0).all():
        raise MjwalkError(
            f"arm_movements: lengths must be {n_seg} positive segment lengths, got {ref}"
        )
    scales = ref.sum() / np.sum(L, axis=1)
    return ArmMovements(np.array(C) * scales[:, None], np.array(U), ref, scales, np.array(G), names)
