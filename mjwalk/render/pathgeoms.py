"""The planned path and footprints drawn into a video frame: flat boxes computed once per
timeline (:func:`path_geoms`) and added to each frame's scene as user geoms
(:func:`add_path_geoms`)."""

from __future__ import annotations

import mujoco
import numpy as np

from mjwalk.timeline.timeline import Timeline

#: Colour of the drawn path (RGBA) and of the drawn footprints (left, right).
PATH_RGBA = np.array([1.0, 0.55, 0.0, 1.0], dtype=np.float32)
FOOT_RGBA = (
    np.array([0.9, 0.2, 0.2, 0.9], dtype=np.float32),
    np.array([0.2, 0.4, 0.95, 0.9], dtype=np.float32),
)


def _yaw_mat(yaw: np.ndarray) -> np.ndarray:
    """(N, 9) row-major rotation matrices about z by ``yaw`` (radians)."""
    c, s = np.cos(yaw), np.sin(yaw)
    z, o = np.zeros_like(c), np.ones_like(c)
    return np.column_stack([c, -s, z, s, c, z, z, z, o])


def path_geoms(timeline: Timeline, width: float = 0.02, spacing: float = 0.05) -> list[tuple]:
    """The planned path and footprints as flat boxes, ``(size, pos, mat, rgba)`` per geom.

    The path is resampled every ``spacing`` metres of arc length (at most 400 segments), each
    segment a box ``width`` wide and 2 mm thick lying 3 mm above the floor; each footprint a
    0.24 x 0.09 m box. Flat boxes have 12 triangles where capsules have hundreds, and the list is
    computed once per timeline: drawing it costs about 1 ms per frame instead of about 10 ms.

    Args:
        timeline: the timeline; its ``walk`` (None: no geoms) gives path and footprints.
        width: the path's width, metres.
        spacing: arc length between path samples, metres.

    Returns:
        One ``(size (3,), pos (3,), mat (9,), rgba (4,))`` per box: half-sizes and position in
        metres (world frame), row-major rotation.
    """
    walk = timeline.walk
    if walk is None:
        return []
    pts = np.asarray(walk.xy, dtype=float)
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    geoms: list[tuple] = []
    if arc[-1] > 1e-6:
        n = int(np.clip(np.ceil(arc[-1] / spacing), 1, 400))
        s = np.linspace(0.0, arc[-1], n + 1)
        xy = np.column_stack([np.interp(s, arc, pts[:, 0]), np.interp(s, arc, pts[:, 1])])
        a, b = xy[:-1], xy[1:]
        d = b - a
        half = 0.5 * np.linalg.norm(d, axis=1) + 0.5 * width  # overlap hides the joints
        mid = 0.5 * (a + b)
        mats = _yaw_mat(np.arctan2(d[:, 1], d[:, 0]))
        for k in range(len(a)):
            geoms.append(
                (
                    np.array([half[k], 0.5 * width, 0.001]),
                    np.array([mid[k, 0], mid[k, 1], 0.003]),
                    mats[k],
                    PATH_RGBA,
                )
            )
    for st in walk.steps:
        x, y, yaw = st.foot
        c, s_ = np.cos(yaw), np.sin(yaw)
        geoms.append(
            (
                np.array([0.12, 0.045, 0.002]),
                np.array([x + 0.03 * c, y + 0.03 * s_, 0.002]),
                _yaw_mat(np.array([yaw]))[0],
                FOOT_RGBA[st.side == "right"],
            )
        )
    return geoms


def add_path_geoms(scn: mujoco.MjvScene, geoms: list[tuple]) -> None:
    """Append precomputed :func:`path_geoms` to the scene as user geoms (as many as fit).

    Args:
        scn: the scene, after ``mjv_updateScene``.
        geoms: :func:`path_geoms`'s boxes.
    """
    box = mujoco.mjtGeom.mjGEOM_BOX
    for size, pos, mat, rgba in geoms:
        if scn.ngeom >= scn.maxgeom:
            break
        mujoco.mjv_initGeom(scn.geoms[scn.ngeom], box, size, pos, mat, rgba)
        scn.ngeom += 1
