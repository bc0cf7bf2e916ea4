"""Where a reach aims: the hand's target on a work site and the pre-grasp approach to it,
shared by the stand zones of the walks (:mod:`mjwalk.cycle.walking`) and the reaches
(:mod:`mjwalk.cycle.reaching`, :mod:`mjwalk.cycle.holding`). World frame: metres, z up."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from mjwalk.arms.chain import arm_segment_lengths
from mjwalk.body.humanoid import HUMAN_GROUP
from mjwalk.cycle.standoff import REACH_CLEARANCE
from mjwalk.cycle.types import TASK_KINDS

#: The hand stops this far above a pick/place site (m) and this far in front of a fasten site.
PICK_CLEARANCE = 0.06
FASTEN_STANDOFF = 0.13
#: The pre-grasp point: this far back towards the operator and (shelf work) up from the target.
APPROACH_BACK = 0.15
APPROACH_UP = 0.10
#: Visual-only geoms a ray passes through at most while measuring a target's headroom.
HEADROOM_HITS = 8
#: The farthest (m) :func:`board_run` marches: the whole arm's length, upper arm, forearm and
#: hand, 0.44 H (:data:`mjwalk.anthropometry.SEG`), 0.77 m at H = 1.75 m, rounded up; a
#: board that runs farther in front of its target is no board an arm reaches over.
MAX_BOARD_RUN = 0.8
#: Step (m) of the march back over the board under a shelf target (:func:`board_run`): the
#: board's front edge is found to within it, never nearer the target than it is.
BOARD_STEP = 0.01
#: A point is over the target's board while the surface straight below it is within this
#: (m) of the height below the target: a board is flat (ASSUMPTION: 1 cm, the
#: :data:`~mjwalk.cycle.standoff.REACH_CLEARANCE` the arm keeps; a lower board or the floor
#: past the edge lies decimetres lower).
BOARD_TOLERANCE = 0.01
#: The hand's end stays a hand's length and this much more (m) out of a board's front edge at
#: the pre-grasp point of an approach from out of the board (:func:`edge_back`): the arm's
#: clearance from the scene, :data:`~mjwalk.cycle.standoff.REACH_CLEARANCE`.
EDGE_CLEARANCE = REACH_CLEARANCE


def reach_target(kind: str, site_pos: np.ndarray, x: float, y: float) -> np.ndarray:
    """Where the hand aims for a task at ``site_pos``: :data:`PICK_CLEARANCE` above a pick or
    place site; :data:`FASTEN_STANDOFF` in front of a fasten site, horizontally towards the
    operator.

    Args:
        kind: the task's kind ("pick", "place", "fasten").
        site_pos: (3,) the site, world frame (m).
        x: the operator's position, world frame (m).
        y: the operator's position, world frame (m).

    Returns:
        (3,) the hand's target, world frame (m).
    """
    if TASK_KINDS[kind].approach == "surface":  # in front of the surface, towards the operator
        d = np.array([x, y]) - site_pos[:2]
        d /= max(np.linalg.norm(d), 1e-9)
        return site_pos + np.r_[FASTEN_STANDOFF * d, 0.0]
    return site_pos + np.array([0.0, 0.0, PICK_CLEARANCE])


def approach_offset(
    kind: str,
    site_pos: np.ndarray,
    x: float,
    y: float,
    facing: float | None = None,
    rise: float = APPROACH_UP,
    back: float = APPROACH_BACK,
) -> np.ndarray:
    """Pre-grasp offset: back towards the operator, and up for shelf work (by ``rise``, at most
    :data:`APPROACH_UP`: less under a shelf, :func:`approach_rise`). Shelf work (pick, place)
    at a stand site facing ``facing`` comes in along the site's facing, out of the shelf's
    opening, wherever in the stand zone the operator stands (towards the operator, an oblique
    approach swept the fingers across the rack's frame).

    Args:
        kind: the task's kind ("pick", "place", "fasten").
        site_pos: (3,) the site, world frame (m).
        x: the operator's position, world frame (m).
        y: the operator's position, world frame (m).
        facing: the stand site's facing (radians from +x, counter-clockwise); None: towards
            the operator.
        rise: how far the pre-grasp point may rise above the target (m).
        back: how far the pre-grasp point lies back from the target, horizontally (m):
            :data:`APPROACH_BACK`, or out of the board under a deep target
            (:func:`edge_back`).

    Returns:
        (3,) the offset of the pre-grasp point from the target, world frame (m):
        ``back`` horizontally, then up (0 for a fasten).
    """
    surface = TASK_KINDS[kind].approach == "surface"
    up = 0.0 if surface else min(APPROACH_UP, rise)
    return np.r_[back * approach_back_dir(kind, site_pos, x, y, facing), up]


def approach_back_dir(
    kind: str, site_pos: np.ndarray, x: float, y: float, facing: float | None = None
) -> np.ndarray:
    """The horizontal direction from a target back to its pre-grasp point
    (:func:`approach_offset`): against the stand site's ``facing`` for shelf work, else towards
    the operator.

    Args:
        kind: the task's kind ("pick", "place", "fasten").
        site_pos: (3,) the site, world frame (m).
        x: the operator's position, world frame (m).
        y: the operator's position, world frame (m).
        facing: the stand site's facing (radians from +x, counter-clockwise); None: towards
            the operator.

    Returns:
        (2,) unit vector (x, y), world frame.
    """
    if facing is not None and TASK_KINDS[kind].approach != "surface":
        return -np.array([math.cos(facing), math.sin(facing)])
    d = np.array([x, y]) - site_pos[:2]
    return d / max(float(np.linalg.norm(d)), 1e-9)


def approach_rise(
    model: mujoco.MjModel, data: mujoco.MjData, stature: float, target: np.ndarray
) -> float:
    r"""How far the pre-grasp point may rise above ``target`` for an operator of ``stature``:
    :data:`APPROACH_UP` in the open; under a shelf, only so far that the hand at its
    pre-grasp point still has its own length free above it (the hand may point anywhere from
    level to straight down along its approach, and the wrist's range turns it further where
    the arm comes in steeply: a compartment's upper shelf otherwise took the thumb, palm and
    forearm of a reach into it, 20-30 mm deep), none when the compartment is lower than that:
    :math:`\mathrm{clip}(h - l_{hand}, 0, \mathrm{APPROACH\_UP})`.

    Args:
        model: the scene (with the humanoid).
        data: a scratch MjData of ``model`` (as :func:`headroom`).
        stature: the operator's stature (m).
        target: (3,) the hand's target, world frame (m).

    Returns:
        The rise, metres.
    """
    hand = float(arm_segment_lengths(stature)[2])
    return float(np.clip(headroom(model, data, target) - hand, 0.0, APPROACH_UP))


def headroom(model: mujoco.MjModel, data: mujoco.MjData, point: np.ndarray) -> float:
    """Free height straight up from ``point`` to the first scene geom of ``model`` that collides
    (geoms with neither contype nor conaffinity, and the humanoid's, let the ray through).

    Args:
        model: the scene.
        data: a scratch MjData of ``model``: its kinematics are computed here (the humanoid's
            pose does not count).
        point: (3,) the point, world frame (m).

    Returns:
        The height, metres; ``inf`` when nothing is above.
    """
    mujoco.mj_kinematics(model, data)  # the scene's geoms in place (the humanoid's do not count)
    return _free_run(model, data, point, np.array([0.0, 0.0, 1.0]))


def board_run(
    model: mujoco.MjModel, data: mujoco.MjData, target: np.ndarray, back: np.ndarray
) -> float:
    """How far the board under ``target`` (a shelf's, a bench's top: the first colliding scene
    geom straight below it) reaches from the target towards ``back``: the first point,
    :data:`BOARD_STEP` at a time, over which the surface below lies more than
    :data:`BOARD_TOLERANCE` lower than under the target (past the board's front edge).

    Args:
        model: the scene (with the humanoid: its geoms let the rays through).
        data: a scratch MjData of ``model`` (as :func:`headroom`).
        target: (3,) the hand's target, world frame (m).
        back: (2,) unit direction (x, y) from the target towards the operator.

    Returns:
        Metres from the target (horizontally); 0 with nothing below the target, ``inf`` when
        the board reaches farther than :data:`MAX_BOARD_RUN`.
    """
    mujoco.mj_kinematics(model, data)
    down = np.array([0.0, 0.0, -1.0])
    p = np.asarray(target, dtype=float)
    below = _free_run(model, data, p, down)
    if math.isinf(below):
        return 0.0
    step = np.r_[np.asarray(back, dtype=float), 0.0] * BOARD_STEP
    for k in range(1, round(MAX_BOARD_RUN / BOARD_STEP) + 1):
        if not _free_run(model, data, p + k * step, down) <= below + BOARD_TOLERANCE:
            return k * BOARD_STEP
    return math.inf


def edge_back(run: float, stature: float) -> float:
    """The pre-grasp point's distance back from a target (m, horizontally) that brings the hand
    out of the board under it: the board's run towards the operator (:func:`board_run`), the
    hand's length (:func:`~mjwalk.arms.chain.arm_segment_lengths`) and
    :data:`EDGE_CLEARANCE`, at least :data:`APPROACH_BACK`; :data:`APPROACH_BACK` with no
    board under the target (``run`` 0).
    The reach model brings the hand up to its pre-grasp point pointing anywhere from level to
    straight up, the wrist and forearm trailing below it: with its end a hand's length out of
    the edge, the wrist (within a hand's length of it) and the hand are out of the board
    whichever way the hand points, and the hand comes over the edge along the approach
    (:func:`~mjwalk.cycle.reaching.reach_frames`) instead of the forearm through it.

    Args:
        run: the board's run from the target towards the operator (m).
        stature: the operator's stature (m).

    Returns:
        The distance, metres.
    """
    if run <= 0.0:
        return APPROACH_BACK
    hand = float(arm_segment_lengths(stature)[2])
    return max(APPROACH_BACK, run + hand + EDGE_CLEARANCE)


def _free_run(
    model: mujoco.MjModel, data: mujoco.MjData, point: np.ndarray, direction: np.ndarray
) -> float:
    """Free distance (m) from ``point`` along the unit ``direction`` to the first colliding scene
    geom (kinematics done by the caller); ``inf`` when there is none."""
    m = model
    groups = np.ones(6, dtype=np.uint8)
    groups[HUMAN_GROUP] = 0
    up = np.asarray(direction, dtype=float)
    start = np.asarray(point, dtype=float).copy()
    gid = np.zeros(1, dtype=np.int32)
    travelled = 0.0
    for _ in range(HEADROOM_HITS):
        d = mujoco.mj_ray(m, data, start, up, groups, 1, -1, gid)
        if d < 0:
            return math.inf
        g = int(gid[0])
        if m.geom_contype[g] or m.geom_conaffinity[g]:
            return travelled + float(d)
        travelled += float(d) + 1e-6
        start = start + (float(d) + 1e-6) * up
    return travelled
