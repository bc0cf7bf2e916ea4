"""Where a reach aims: the hand's target on a work site and the pre-grasp approach to it,
shared by the stand zones of the walks (:mod:`mjwalk.cycle.walking`) and the reaches
(:mod:`mjwalk.cycle.reaching`, :mod:`mjwalk.cycle.holding`). World frame: metres, z up."""

from __future__ import annotations

import math

import mujoco
import numpy as np

from mjwalk.arms.chain import arm_segment_lengths
from mjwalk.body.humanoid import HUMAN_GROUP
from mjwalk.cycle.types import TASK_KINDS

#: The hand stops this far above a pick/place site (m) and this far in front of a fasten site.
PICK_CLEARANCE = 0.06
FASTEN_STANDOFF = 0.13
#: The pre-grasp point: this far back towards the operator and (shelf work) up from the target.
APPROACH_BACK = 0.15
APPROACH_UP = 0.10
#: Visual-only geoms a ray passes through at most while measuring a target's headroom.
HEADROOM_HITS = 8


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

    Returns:
        (3,) the offset of the pre-grasp point from the target, world frame (m):
        :data:`APPROACH_BACK` horizontally, then up (0 for a fasten).
    """
    surface = TASK_KINDS[kind].approach == "surface"
    if facing is not None and not surface:
        d = -np.array([math.cos(facing), math.sin(facing)])
    else:
        d = np.array([x, y]) - site_pos[:2]
        d /= max(np.linalg.norm(d), 1e-9)
    up = 0.0 if surface else min(APPROACH_UP, rise)
    return np.r_[APPROACH_BACK * d, up]


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
    m = model
    mujoco.mj_kinematics(m, data)  # the scene's geoms in place (the humanoid's do not count)
    groups = np.ones(6, dtype=np.uint8)
    groups[HUMAN_GROUP] = 0
    up = np.array([0.0, 0.0, 1.0])
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
