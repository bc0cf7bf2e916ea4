"""A walk's turns on the spot kept clear of the scene: where the turn before the walk (or the
one after it) would bring an arm within :data:`~mjwalk.cycle.standoff.REACH_CLEARANCE` of the
scene, the trunk turns the shoulders away from the nearest obstacle over the turn and the walk
together, as it does in the walk (:func:`~mjwalk.timeline.frames.trunk_turn`).

A turn on the spot (:func:`~mjwalk.cycle.poses.turn_frames`) turns the standing body about the
pelvis, the arms hanging at its sides. The hanging hand reaches as far out as the shoulder:
its thumb, 0.018 H beside the forearm's axis with a 0.006 H radius (0.024 H,
:func:`~mjwalk.body.humanoid.build_humanoid`), as far as the upper arm's 0.024 H radius
(:data:`~mjwalk.anthropometry.UPPER_ARM_RADIUS`), so the shoulder line's half-width
(:func:`~mjwalk.anthropometry.shoulder_geometry`, 0.1535 H: 0.316 m at H = 2.06 m) is the
hanging arm's too. Turned towards a shelf whose front edge is nearer than that, the hand sweeps
into the edge when it is at the hand's height (run 7812 of the station's 10 000-run batch: a
2.06 m operator, 0.316 m from rack 2's shelf, turning from the tool's pick to walk to rack 3;
the right thumb 1.6 mm into the shelf's lower front edge, at 0.98 m). The walk keeps its
shoulders clear by turning the trunk where its room is short; the turn did not. Here the turn's
trunk rotation is computed over the turn and the walk as one stretch, so a passage by an
obstacle that starts in the turn keeps one side into the walk (:func:`~mjwalk.timeline.frames.
turn_sides`) and the trunk does not jump where the turn ends and the walk begins.

Only a turn that is not clear (MuJoCo's collision detection with the arm geoms inflated,
:class:`~mjwalk.cycle.standoff.ArmClearance`, the reach's check) is changed, and the change is
kept only when it leaves the pieces clearer; every other walk's frames are as before.

World frame: metres, z up, yaw in radians from +x; frames at ``fps`` per second.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from mjwalk.timeline.frames import room_and_away, trunk_rotation

if TYPE_CHECKING:
    from mjwalk.cycle.context import CycleContext

#: The trunk's rotation joints, in :func:`~mjwalk.timeline.frames.trunk_rotation`'s order: the
#: lumbar joint to its range first, the thoracic joint the rest.
TRUNK_ROTATION = ("lumbar_rot", "thoracic_rot")


def turn_clear(
    ctx: CycleContext, pieces: list[np.ndarray], turns: tuple[int, ...], fps: float
) -> list[np.ndarray]:
    """A walk's pieces (the turn before it, its frames, the turn after it) with the trunk
    turned clear of the scene where a turn on the spot is not clear.

    Args:
        ctx: the cycle context (model, joint map, workplace, stature and the arms' clearance
            check, ``ctx.clearance``).
        pieces: the pieces' frames, each (n_i, nq), in time order, ``1/fps`` s apart.
        turns: the indices in ``pieces`` of the turns on the spot (the pieces checked).
        fps: frames per second.

    Returns:
        The pieces: the same arrays when every turn is clear (or the trunk's turn does not
        make them clearer), else new arrays whose trunk rotation (``lumbar_rot``,
        ``thoracic_rot``) is the standing pose's plus :func:`~mjwalk.timeline.frames.
        trunk_turn` over all the pieces' frames.
    """
    clear = ctx.clearance
    if all(clear.distance(pieces[i]) == np.inf for i in turns):
        return pieces
    frames = np.vstack(pieces)
    turned = trunk_clear(ctx, frames, fps)
    if clear.distance(turned) <= clear.distance(frames):
        return pieces  # the trunk's turn does not help (an arm over a low top, not beside it)
    ends = np.cumsum([len(p) for p in pieces])[:-1]
    return np.split(turned, ends)


def trunk_clear(ctx: CycleContext, frames: np.ndarray, fps: float) -> np.ndarray:
    """``frames`` with the trunk rotation that keeps the shoulders clear of the nearest
    obstacle (:func:`~mjwalk.timeline.frames.trunk_turn` of the room and the way away from it
    at each frame's pelvis), added to the standing pose's, the lumbar joint taking its range
    first and the thoracic joint the rest, each clipped to its range.

    Args:
        ctx: the cycle context.
        frames: (F, nq) poses, ``1/fps`` s apart.
        fps: frames per second.

    Returns:
        (F, nq) the poses (a new array).
    """
    jm, r = ctx.jointmap, ctx.jointmap.root
    out = np.array(frames, dtype=float)
    room, away = room_and_away(ctx.workplace, out[:, r : r + 2])
    turn = trunk_rotation(out, jm, room, away, ctx.spec.stature, fps)
    rest = jm.neutral_qpos(ctx.model, ctx.spec.stature)
    for joint, part in zip(TRUNK_ROTATION, turn, strict=True):
        k = jm.adr(joint)
        out[:, k] = rest[k] + part
    return out
