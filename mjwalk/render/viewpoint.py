"""Where the tracking camera stands: a clear line of sight to the walker's legs, moving smoothly.

The tracking camera looks at the pelvis from :data:`TRACK_DISTANCE`. Its preferred side is the
walker's left (relative to the walk's start heading), 15 deg above. Benches, racks and pillars
between that position and the walker hide the legs, so :func:`track_view` casts rays
(``mujoco.mj_multiRay``, the humanoid's geom group excluded) from the pelvis, knees and ankles
to candidate camera positions on a sphere around the look-at point, every
:data:`SAMPLE_DT` seconds, and picks per sample the candidate that sees the most of them,
nearest the preferred side, by dynamic programming over the samples with the camera's turn
rate bounded (:data:`MAX_TURN_RATE`), so it moves before a pillar comes between and never
jumps. The chosen angles are interpolated to every frame and smoothed (Gaussian,
:data:`SMOOTH_SIGMA`). Where the preferred position sees everything the camera stays exactly
there (frames identical to the fixed camera's).

Angles in degrees as MuJoCo's free camera takes them: azimuth about +z from +x, elevation
negative looking down; positions in metres, world frame, z up.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import mujoco
import numpy as np
from scipy.ndimage import gaussian_filter1d

from mjwalk.body.humanoid import HUMAN_GROUP
from mjwalk.errors import MjwalkError

if TYPE_CHECKING:
    from mjwalk.timeline.timeline import Timeline

#: Camera distance from the look-at point (m) and its default elevation (deg): the whole
#: 1.75 m body fills about 60 % of a 45 deg field of view.
TRACK_DISTANCE = 3.5
TRACK_ELEVATION = -15.0
#: Look-at height as a fraction of the pelvis height (a little below the pelvis: mid-body).
LOOKAT_HEIGHT = 0.9
#: Candidate cameras: azimuths every AZIMUTH_STEP deg around the walker, at these elevations
#: (steeper views see over benches and car bodies).
AZIMUTH_STEP = 15.0
ELEVATIONS = (-15.0, -35.0, -55.0)
#: Sight-line targets (humanoid bodies, unprefixed) and their weights: the knees and ankles
#: (body origins of shin and foot) are what the tracking camera is for.
TARGETS = ("pelvis", "shin_l", "shin_r", "foot_l", "foot_r")
TARGET_WEIGHTS = (1.0, 1.0, 1.0, 2.0, 2.0)
#: Visibility is sampled every SAMPLE_DT seconds (5 Hz: a walker at 1.4 m/s passes a 0.3 m
#: pillar in about 0.2 s, and the look-ahead of the dynamic programme covers the rest).
SAMPLE_DT = 0.2
#: The fastest the camera turns around the walker (deg/s): 180 deg in 1.5 s, slow enough to
#: follow by eye.
MAX_TURN_RATE = 120.0
#: Gaussian smoothing of the chosen angles (s).
SMOOTH_SIGMA = 0.3
#: Costs of the dynamic programme, in units of one hidden target of weight 1: turning away
#: from the preferred azimuth by 180 deg, one step of elevation (20 deg), and moving the
#: camera by 180 deg between samples. All are below one hidden target, so sight comes first.
COST_AZIMUTH = 0.5
COST_ELEVATION = 0.2
COST_MOVE = 0.3


@dataclass
class TrackView:
    """The tracking camera's angles for every frame of a timeline.

    Attributes:
        azimuth: (F,) degrees, MuJoCo's free-camera azimuth (about +z from +x).
        elevation: (F,) degrees, negative looking down.
        preferred: the preferred azimuth (deg): the walker's left at the start heading.
        sample_frames: (S,) the frames where sight lines were cast.
        visible: (S, len(TARGETS)) which targets the chosen camera sees at those frames.
        visible_preferred: (S, len(TARGETS)) the same from the preferred position.
    """

    azimuth: np.ndarray
    elevation: np.ndarray
    preferred: float
    sample_frames: np.ndarray
    visible: np.ndarray
    visible_preferred: np.ndarray


def preferred_azimuth(timeline: Timeline) -> float:
    """The fixed camera's azimuth (deg): the walker's left side at the start heading.

    Args:
        timeline: the timeline (its first frame's root orientation gives the heading yaw0).

    Returns:
        yaw0 in degrees minus 90.
    """
    r = timeline.jointmap.root
    q = timeline.qpos[0, r + 3 : r + 7]
    yaw0 = 2 * np.arctan2(q[3], q[0])
    return float(np.rad2deg(yaw0)) - 90.0


def camera_positions(lookat: np.ndarray, azimuth, elevation, distance=TRACK_DISTANCE):
    """(..., 3) positions (m) of free cameras looking at ``lookat`` from ``azimuth`` and
    ``elevation`` (deg) at ``distance`` (m), as ``mjv_updateCamera`` places them.

    Args:
        lookat: the look-at point(s), (..., 3), metres (world frame).
        azimuth: azimuths, degrees (broadcast against ``elevation``).
        elevation: elevations, degrees.
        distance: distance from the look-at point, metres.

    Returns:
        ``lookat - distance * (cos el cos az, cos el sin az, sin el)``.
    """
    az, el = np.deg2rad(np.asarray(azimuth, float)), np.deg2rad(np.asarray(elevation, float))
    fwd = np.stack([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)], axis=-1)
    return np.asarray(lookat, float) - distance * fwd


class _SightLines:
    """Ray casts from the humanoid's target bodies to camera positions, humanoid excluded."""

    def __init__(self, timeline: Timeline):
        self.tl = timeline
        self.model = timeline.model
        self.data = mujoco.MjData(self.model)
        prefix = timeline.jointmap.prefix
        ids = [mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_BODY, prefix + t) for t in TARGETS]
        if min(ids) < 0:
            missing = [t for t, i in zip(TARGETS, ids, strict=True) if i < 0]
            raise MjwalkError(f"track_view: the humanoid has no bodies {missing}")
        self.ids = np.array(ids)
        self.group = np.ones(mujoco.mjNGROUP, np.uint8)
        self.group[HUMAN_GROUP] = 0

    def pose(self, frame: int) -> tuple[np.ndarray, np.ndarray]:
        """(look-at point (3,), target positions (T, 3)) at ``frame``."""
        r = self.tl.jointmap.root
        self.data.qpos[:] = self.tl.qpos[frame]
        mujoco.mj_kinematics(self.model, self.data)
        x, y, z = self.tl.qpos[frame, r : r + 3]
        return np.array([x, y, LOOKAT_HEIGHT * z]), self.data.xpos[self.ids].copy()

    def visible(self, targets: np.ndarray, cams: np.ndarray) -> np.ndarray:
        """(T, C) whether the segment from each target to each camera position is clear."""
        n = len(cams)
        geomid = np.empty(n, np.int32)
        dist = np.empty(n, np.float64)
        out = np.empty((len(targets), n), bool)
        for k, p in enumerate(targets):
            vec = cams - p
            length = np.linalg.norm(vec, axis=1)
            mujoco.mj_multiRay(
                self.model,
                self.data,
                p,
                (vec / length[:, None]).ravel(),
                self.group,
                1,
                -1,
                geomid,
                dist,
                None,
                n,
                float(length.max()) + 1.0,
            )
            out[k] = (dist < 0) | (dist > length)
        return out


def sight_lines(timeline: Timeline, frames, azimuth, elevation) -> np.ndarray:
    """(len(frames), len(TARGETS)) whether a tracking camera at ``azimuth``/``elevation``
    (deg, scalars or per frame of ``frames``) sees each target body at those frames.

    Args:
        timeline: the timeline.
        frames: the frame indices.
        azimuth: camera azimuth(s), degrees.
        elevation: camera elevation(s), degrees.

    Returns:
        Booleans, True where the ray from the target body to the camera is clear (the
        humanoid's own geoms excluded).
    """
    sl = _SightLines(timeline)
    frames = np.asarray(frames, int)
    az = np.broadcast_to(np.asarray(azimuth, float), frames.shape)
    el = np.broadcast_to(np.asarray(elevation, float), frames.shape)
    out = np.empty((len(frames), len(TARGETS)), bool)
    for k, f in enumerate(frames):
        lookat, targets = sl.pose(int(f))
        out[k] = sl.visible(targets, camera_positions(lookat, az[k], el[k])[None])[:, 0]
    return out


def track_view(timeline: Timeline) -> TrackView:
    """The tracking camera's angles for every frame: a clear view of the legs, moving smoothly.

    See the module docstring for the method. Costs about 5 ray casts per candidate camera
    (72) every 0.2 s of timeline, a fraction of a second for a minute-long cycle.

    Args:
        timeline: the timeline to film.

    Returns:
        The angles per frame, the preferred azimuth, and the sight lines at the sample frames
        for the chosen and the preferred camera.
    """
    n = timeline.n_frames
    pref = preferred_azimuth(timeline)
    step = max(1, round(SAMPLE_DT * timeline.fps))
    samples = np.unique(np.append(np.arange(0, n, step), n - 1))
    offsets = np.arange(0.0, 360.0, AZIMUTH_STEP)
    offsets = np.where(offsets > 180.0, offsets - 360.0, offsets)  # 0, 15, ..., -15
    d_az, el = np.meshgrid(offsets, np.asarray(ELEVATIONS, float), indexing="xy")
    d_az, el = d_az.ravel(), el.ravel()  # candidate c: (pref + d_az[c], el[c])
    sl = _SightLines(timeline)
    vis = np.empty((len(samples), len(TARGETS), len(d_az)), bool)
    for k, f in enumerate(samples):
        lookat, targets = sl.pose(int(f))
        vis[k] = sl.visible(targets, camera_positions(lookat, pref + d_az, el))
    w = np.asarray(TARGET_WEIGHTS)
    hidden = np.einsum("t,stc->sc", w, ~vis)  # (S, C)
    unary = (
        hidden
        + COST_AZIMUTH * np.abs(d_az) / 180.0
        + COST_ELEVATION * np.abs(el - TRACK_ELEVATION) / 20.0
    )
    # moves between consecutive samples: azimuth and elevation change, bounded by the turn rate
    dt = SAMPLE_DT if len(samples) < 2 else float(np.diff(samples).max()) / timeline.fps
    da = np.abs((d_az[:, None] - d_az[None, :] + 180.0) % 360.0 - 180.0)
    de = np.abs(el[:, None] - el[None, :])
    move = COST_MOVE * (da + de) / 180.0
    move[da + de > MAX_TURN_RATE * dt + 1e-9] = np.inf
    cost = unary[0].copy()
    back = np.empty((len(samples), len(d_az)), int)
    for k in range(1, len(samples)):
        total = cost[:, None] + move  # from c (rows) to c' (columns)
        back[k] = np.argmin(total, axis=0)
        cost = total[back[k], np.arange(len(d_az))] + unary[k]
    path = np.empty(len(samples), int)
    path[-1] = int(np.argmin(cost))
    for k in range(len(samples) - 1, 0, -1):
        path[k - 1] = back[k, path[k]]
    # azimuth offsets unwrapped along the path (steps are < 180 deg), interpolated, smoothed
    chosen = np.rad2deg(np.unwrap(np.deg2rad(d_az[path])))
    frames = np.arange(n)
    sigma = SMOOTH_SIGMA * timeline.fps
    if np.any(chosen != 0.0):
        az_off = gaussian_filter1d(np.interp(frames, samples, chosen), sigma, mode="nearest")
    else:
        az_off = np.zeros(n)
    if np.any(el[path] != TRACK_ELEVATION):
        el_off = np.interp(frames, samples, el[path] - TRACK_ELEVATION)
        el_off = gaussian_filter1d(el_off, sigma, mode="nearest")
    else:
        el_off = np.zeros(n)
    azimuth = pref + az_off
    elevation = TRACK_ELEVATION + el_off
    pref_c = int(np.flatnonzero((d_az == 0.0) & (el == TRACK_ELEVATION))[0])
    return TrackView(
        azimuth=azimuth,
        elevation=elevation,
        preferred=pref,
        sample_frames=samples,
        visible=sight_lines(timeline, samples, azimuth[samples], elevation[samples]),
        visible_preferred=vis[:, :, pref_c],
    )


def fixed_view(timeline: Timeline) -> TrackView:
    """The fixed tracking camera (preferred azimuth, default elevation) as a TrackView (the
    camera before sight lines were checked; for comparisons).

    Args:
        timeline: the timeline to film.

    Returns:
        The fixed camera's angles per frame and its sight lines at the sample frames.
    """
    n = timeline.n_frames
    pref = preferred_azimuth(timeline)
    samples = np.arange(0, n, max(1, round(SAMPLE_DT * timeline.fps)))
    vis = sight_lines(timeline, samples, pref, TRACK_ELEVATION)
    return TrackView(
        azimuth=np.full(n, pref),
        elevation=np.full(n, TRACK_ELEVATION),
        preferred=pref,
        sample_frames=samples,
        visible=vis,
        visible_preferred=vis,
    )
