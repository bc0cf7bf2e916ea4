"""Reach movements from capture: a take's arm joints -> (constraint, directions) training pairs.

One clip becomes one movement of the arm model (Al-Zubi & Sommer §4.1), as
``benchmarks/bench_reach.py`` measures it and as a user trains a
:class:`~mjwalk.arms.reach.ReachModel` on their own clips:

* frame: the moving arm's shoulder at the origin in every frame, axes of the body frame of the
  first frame (x forward, y left, z up; the pelvis yaw of frame 0), metres; a right arm is
  mirrored through the sagittal plane (y -> -y, :data:`~mjwalk.arms.kinematics.MIRROR_Y`) into
  the left arm's frame: the reach model is a left-arm model, mirrored back for the right arm;
* time alignment: the one movement holding the fastest hand frame, from rest to the first stop
  (5 % of the peak hand speed, :func:`~mjwalk.arms.armrep.movement_span`), optionally before
  the hand's highest point (a raise that is held and creeps upwards while held);
* sampling: the chain shoulder, elbow, wrist at ``n`` equal time intervals (paper: n = 20);
* constraint (9,): start elbow, start hand and end hand positions (metres, shoulder frame): the
  start posture and the end of the reach, what a planner knows before it.

Body size: people differ in arm length, and the directions of the segments (what the model
predicts) do not depend on it, but positions do. Each movement's constraint is scaled to one
reference arm (``ArmMovements.lengths``: the clips' mean upper-arm and forearm lengths unless
given), as if the same movement were made by an arm of that length: geometric similarity of
the arm, whose segments are fixed shares of stature (Winter 2009, *Biomechanics and Motor
Control of Human Movement*, Table 4.1; :data:`~mjwalk.arms.kinematics.ARM_SEGMENT_SHARES`). A
simulated operator's targets are scaled into the model's size the same way
(:mod:`mjwalk.cycle.reaching`), so a tall and a short walker making the same movement give the
same training pair.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from mjwalk.arms.armrep import movement_span, resample_trajectory, segment_directions
from mjwalk.arms.kinematics import MIRROR_Y
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


@dataclass
class ArmMovements:
    """Movements of one arm, in the left arm's shoulder frame (metres; module docstring).

    Attributes:
        constraints: (p, 9) start elbow, start hand, end hand positions (m), scaled to
            ``lengths``.
        directions: (p, n, 2, 3) unit upper-arm and forearm directions over time.
        lengths: (2,) reference upper-arm and forearm lengths (m) the constraints are scaled to.
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


def arm_chain(take: Take, side: Side, skeleton: str = "bandai") -> np.ndarray:
    """(T, 3, 3) shoulder, elbow, wrist positions of ``side``'s arm in ``take`` (world, m),
    joint names from :data:`ARM_JOINTS`; a take without them raises CaptureError naming them."""
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
    return np.stack([take.joints[j] for j in names], axis=1)


def arm_movement(
    chain: np.ndarray,
    yaw: float,
    side: Side = "left",
    n: int = N_SAMPLES,
    until_highest: bool = True,
) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """One movement of an arm ``chain`` (T, 3, 3): shoulder, elbow, wrist positions (world,
    metres, z up) with the body heading ``yaw`` (radians from +x) at the first frame.

    Returns ``(constraint (9,), directions (n, 2, 3), lengths (2,))`` in the left arm's shoulder
    frame (module docstring), unscaled (``lengths`` are this clip's), or None when the clip holds
    no movement of at least :data:`MIN_FRAMES` frames and :data:`MIN_TRAVEL` metres.
    ``until_highest``: the movement ends by the hand's highest frame (a raise held and creeping
    upwards while held).
    """
    P = np.asarray(chain, dtype=float)
    if P.ndim != 3 or P.shape[1:] != (3, 3) or len(P) < 2:
        raise MjwalkError(f"arm_movement: need a (T >= 2, 3, 3) arm chain, got {P.shape}")
    if not np.isfinite(P).all():
        raise CaptureError("arm_movement: the arm chain holds NaN or infinite positions")
    c, s = np.cos(-yaw), np.sin(-yaw)
    rz = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    P = (P - P[:, :1]) @ rz.T  # shoulder at the origin, body frame of frame 0
    if side == "right":
        P = P * MIRROR_Y  # into the left arm's frame
    until = int(np.argmax(P[:, 2, 2])) if until_highest else None
    a, b = movement_span(P[:, 2], until=until)
    if b - a + 1 < MIN_FRAMES:
        return None
    Pn = resample_trajectory(P[a : b + 1], n)
    if np.linalg.norm(Pn[-1, 2] - Pn[0, 2]) < MIN_TRAVEL:
        return None
    lengths = np.linalg.norm(np.diff(P[a], axis=0), axis=1)
    return np.r_[Pn[0, 1], Pn[0, 2], Pn[-1, 2]], segment_directions(Pn), lengths


def arm_movements(
    takes: Sequence[Take],
    side: Side = "left",
    skeleton: str = "bandai",
    groups: Sequence[str] | None = None,
    lengths: np.ndarray | None = None,
    n: int = N_SAMPLES,
    until_highest: bool = True,
) -> ArmMovements:
    """The movement of ``side``'s arm in every take (see :func:`arm_movement`; takes without
    one are left out), constraints scaled to the reference arm ``lengths`` (2,) m (default:
    the mean over the clips). ``groups``: one label per take (style or walker)."""
    if groups is not None and len(groups) != len(takes):
        raise MjwalkError(f"arm_movements: {len(groups)} groups for {len(takes)} takes")
    C, U, L, G, names = [], [], [], [], []
    for i, take in enumerate(takes):
        out = arm_movement(
            arm_chain(take, side, skeleton), float(take.pelvis_yaw[0]), side, n, until_highest
        )
        if out is None:
            continue
        C.append(out[0])
        U.append(out[1])
        L.append(out[2])
        G.append("?" if groups is None else str(groups[i]))
        names.append(take.name)
    if not C:
        empty = np.full(2, np.nan) if lengths is None else np.asarray(lengths, dtype=float)
        return ArmMovements(
            np.zeros((0, 9)), np.zeros((0, n, 2, 3)), empty, np.zeros(0), np.array([]), []
        )
    ref = np.mean(L, axis=0) if lengths is None else np.asarray(lengths, dtype=float)
    if ref.shape != (2,) or not (ref > 0).all():
        raise MjwalkError(f"arm_movements: lengths must be two positive lengths, got {ref}")
    scales = ref.sum() / np.sum(L, axis=1)
    return ArmMovements(np.array(C) * scales[:, None], np.array(U), ref, scales, np.array(G), names)
