"""Humanoid-vs-scene contacts of a timeline by MuJoCo's collision detection, and playback.

:func:`collision_report` runs MuJoCo collision detection on every frame of a
:class:`~mjwalk.timeline.timeline.Timeline`; :func:`check_collisions` does the same for a
simulated cycle, a timeline or a walk played in a scene. World frame: metres, seconds, z up.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import mujoco
import numpy as np

from mjwalk.body.humanoid import HUMAN_GROUP
from mjwalk.errors import MjwalkError
from mjwalk.plan.walkpath import WalkPath
from mjwalk.timeline.timeline import Timeline


@dataclass
class Contact:
    """One humanoid-vs-scene contact in one frame.

    Attributes:
        time: frame time in seconds.
        body_part: the humanoid geom (unprefixed name, e.g. ``"forearm_r"``).
        scene_geom: the scene geom's name (or ``"geom#<id>"`` when unnamed).
        depth: penetration depth in metres (>= 0 means overlapping).
        pos: (3,) contact point in world coordinates, metres.
    """

    time: float
    body_part: str
    scene_geom: str
    depth: float
    pos: np.ndarray


def iter_frames(timeline: Timeline, data: mujoco.MjData | None = None) -> Iterator[mujoco.MjData]:
    """Play the timeline: set each frame's qpos, run forward kinematics, yield the MjData."""
    model = timeline.model
    data = data if data is not None else mujoco.MjData(model)
    for q in timeline.qpos:
        data.qpos[:] = q
        mujoco.mj_kinematics(model, data)
        yield data


def collision_report(timeline: Timeline, floor_tolerance: float = 0.01) -> list[Contact]:
    """Humanoid-vs-scene contacts of every frame by MuJoCo collision detection.

    Only pairs of one humanoid geom (group 5) and one scene geom count. Contacts with the floor
    (the geom named ``"floor"`` or any plane) are left out unless they penetrate deeper than
    ``floor_tolerance`` metres, so ordinary foot contact is not reported.

    Returns:
        contacts in time order (one per geom pair and frame), depth in metres.
    """
    model = timeline.model
    data = mujoco.MjData(model)
    human = model.geom_group == HUMAN_GROUP
    plen = len(timeline.jointmap.prefix)
    names = [
        mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom#{g}"
        for g in range(model.ngeom)
    ]
    floorish = np.array(
        [
            n == "floor" or model.geom_type[g] == mujoco.mjtGeom.mjGEOM_PLANE
            for g, n in enumerate(names)
        ]
    )
    out: list[Contact] = []
    for i, q in enumerate(timeline.qpos):
        data.qpos[:] = q
        mujoco.mj_kinematics(model, data)
        mujoco.mj_collision(model, data)
        n = data.ncon
        if n == 0:
            continue
        con = data.contact  # struct-of-arrays view: filter in numpy, loop over the few left
        g = np.asarray(con.geom[:n]).astype(int)
        depth = -np.asarray(con.dist[:n])
        h1, h2 = human[g[:, 0]], human[g[:, 1]]
        hg = np.where(h1, g[:, 0], g[:, 1])
        sg = np.where(h1, g[:, 1], g[:, 0])
        keep = (h1 != h2) & ~(floorish[sg] & (depth <= floor_tolerance))
        best: dict[tuple[int, int], tuple[float, np.ndarray]] = {}
        for k in np.flatnonzero(keep):
            key = (int(hg[k]), int(sg[k]))
            if depth[k] > best.get(key, (-np.inf,))[0]:
                best[key] = (float(depth[k]), np.array(con.pos[k]))
        for (h, s), (d, pos) in best.items():
            out.append(Contact(float(timeline.t[i]), names[h][plen:], names[s], d, pos))
    return out


def check_collisions(
    result_or_timeline, scene: str | Path | None = None, *, force: bool = False
) -> list[Contact]:
    """Every humanoid-vs-scene contact of a simulated cycle (or of a Timeline, or of a WalkPath
    played in ``scene``): time (s), body part, scene geom, depth (m), by MuJoCo's collision
    detection. A CycleResult must have been simulated with ``keep_timeline=True``. A WalkPath
    planned in another scene (other obstacle geometry) raises SceneError unless ``force``."""
    from mjwalk.timeline.frames import timeline_from_walk
    from mjwalk.world.workplace import shared_workplace

    obj = result_or_timeline
    if not isinstance(obj, Timeline | WalkPath) and hasattr(obj, "timeline"):  # a CycleResult
        if obj.timeline is None:
            raise MjwalkError(
                "check_collisions: the result has no timeline; simulate with keep_timeline=True"
            )
        obj = obj.timeline
    if isinstance(obj, WalkPath):
        if scene is None:
            raise MjwalkError("check_collisions: a WalkPath needs the scene it is played in")
        obj.check_scene(shared_workplace(scene), force=force)
        obj = timeline_from_walk(obj, scene)
    if not isinstance(obj, Timeline):
        raise MjwalkError(f"check_collisions: cannot check a {type(obj).__name__}")
    return collision_report(obj)
