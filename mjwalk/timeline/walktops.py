"""The walk surfaces of a timeline's scene as its contact check reads them (issue 47): the
geoms whose top faces are walk surfaces other than the floor (:func:`walk_tops`: a sole resting
on one stands), and the heights of the horizontal ones (:func:`level_heights`), on which tape,
markings and inlays within ``norms.LEVEL_TOLERANCE`` are that level's floor
(:func:`mjwalk.world.floor.flush_geoms`), as on the floor. Both only for a scene on several
levels given as an MJCF file; a flat scene's contacts are checked as always. World metres.
"""

from __future__ import annotations

import os
import stat
import weakref
from pathlib import Path

import mujoco
import numpy as np

from mjwalk.timeline.timeline import Timeline
from mjwalk.world.workplace import shared_workplace

#: Per scene file and modification time: the names of its walk tops and its horizontal walk
#: surfaces' heights (None: a scene on one level); the masks of :func:`walk_tops` per model by
#: the same keys.
_SCENES: dict[tuple[str, float], tuple[frozenset[str], tuple[float, ...]] | None] = {}
_TOPS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _scene_levels(timeline: Timeline) -> tuple[tuple, frozenset[str], tuple[float, ...]] | None:
    """The key, walk-top names and surface heights of a timeline's scene on several levels,
    found once per scene version; None for an MjSpec, a scene that is no file or one level."""
    if not timeline.scene or timeline.scene == "<MjSpec>":
        return None
    try:  # one stat: whether it is a file, and its version
        info = os.stat(timeline.scene)
    except (OSError, ValueError):
        return None
    if not stat.S_ISREG(info.st_mode):
        return None
    key = (timeline.scene, info.st_mtime)  # the names per scene version (models vary by stature)
    if key not in _SCENES:
        wp = shared_workplace(Path(timeline.scene))
        plane = mujoco.mjtGeom.mjGEOM_PLANE  # a floor of boxes (round a pit) is walk tops
        top = [
            s.name
            for s in wp.levels.surfaces
            if s.name and (s.kind != "floor" or int(wp.model.geom_type[s.geom_id]) != plane)
        ]
        flat = sorted({float(s.z) for s in wp.levels.surfaces if not s.is_ramp})
        _SCENES[key] = (frozenset(top), tuple(flat)) if wp.levels.links else None
    hit = _SCENES[key]
    return None if hit is None else (key, *hit)


def walk_tops(timeline: Timeline) -> np.ndarray | None:
    """The scene geoms of a timeline's model whose top faces are walk surfaces other than the
    floor (platforms, treads, ramps: :attr:`Workplace.levels
    <mjwalk.world.workplace.Workplace.levels>`), when its scene is an MJCF file on several levels
    (some link between levels); None otherwise (a flat scene, an MjSpec's) as always before.

    Args:
        timeline: the timeline (its ``scene`` file and ``model``).

    Returns:
        (ngeom,) read-only bool mask over the timeline's model, or None.
    """
    found = _scene_levels(timeline)
    if found is None:  # not a file, or a scene on one level
        return None
    key, names, _ = found
    kept = _TOPS.setdefault(timeline.model, {})  # the mask per model and scene version
    if key not in kept:
        m = timeline.model
        own = [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_GEOM, g) for g in range(m.ngeom)]
        kept[key] = np.array([n is not None and n in names for n in own])
        kept[key].setflags(write=False)
    return kept[key]


def level_heights(timeline: Timeline) -> tuple[float, ...]:
    """The world heights of the horizontal walk surfaces of a timeline's scene on several
    levels (floor, platforms, treads, mezzanines; not ramps): those a geom can lie flush on.

    Args:
        timeline: the timeline (its ``scene`` file).

    Returns:
        the heights in rising order, metres; () for a flat scene, an MjSpec's or no file.
    """
    found = _scene_levels(timeline)
    return () if found is None else found[2]
