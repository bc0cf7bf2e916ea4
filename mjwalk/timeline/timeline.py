"""The ``Timeline``: per-frame poses of the humanoid in a scene, with its gait events.

A :class:`Timeline` holds the compiled scene-with-humanoid model and one ``qpos`` row per video
frame (default 30 fps); :mod:`mjwalk.timeline.frames` builds one from a walk,
:mod:`mjwalk.timeline.reachscene` from a reach, :mod:`mjwalk.cycle.simulate` from a whole cycle.

World frame: metres, seconds, radians, z up, yaw from +x CCW.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field

import mujoco
import numpy as np

from mjwalk.body.humanoid import JointMap
from mjwalk.conventions import DEFAULT_STATURE
from mjwalk.plan.walkpath import WalkPath
from mjwalk.timeline.parts import PartTrack


@dataclass
class Event:
    """Something that happens at a time of the timeline (seconds): ``kind`` like
    ``"heel_strike"``/``"toe_off"``, ``detail`` like ``"left"``."""

    time: float
    kind: str
    detail: str = ""


@dataclass
class Timeline:
    """Per-frame poses of the humanoid in a scene.

    Attributes:
        model: the compiled scene + humanoid model.
        jointmap: where the humanoid's joints live in ``qpos``.
        fps: frames per second (the video rate).
        t: (F,) frame times in seconds from 0.
        qpos: (F, nq) the model's qpos for every frame (root x, y, z in metres, root quaternion
            w, x, y, z; hinge angles in radians).
        events: gait events (heel strikes, toe-offs), in time order.
        contact: (F,) foot contact state, 0 left stance, 1 right stance, 2 double support.
        walk: the WalkPath the timeline was made from (drawn into videos), if any.
        scene: the scene file (or "<MjSpec>") and ``stature`` the humanoid's stature in metres,
            enough to rebuild ``model``.
        meta: free-form provenance (producer, clipped joints, ...).
        parts: scene geoms the hands pick, carry and put down, where each is drawn in every
            frame (:mod:`mjwalk.timeline.parts`); videos move them, collisions ignore them.
    """

    model: mujoco.MjModel
    jointmap: JointMap
    fps: float
    t: np.ndarray
    qpos: np.ndarray
    events: list[Event] = field(default_factory=list)
    contact: np.ndarray | None = None
    walk: WalkPath | None = None
    scene: str = ""
    stature: float = DEFAULT_STATURE
    meta: dict = field(default_factory=dict)
    parts: list[PartTrack] = field(default_factory=list)

    @property
    def n_frames(self) -> int:
        return int(self.qpos.shape[0])

    @property
    def duration(self) -> float:
        return float(self.t[-1]) if len(self.t) else 0.0

    def root(self) -> np.ndarray:
        """The root (pelvis) positions.

        Returns:
            (F, 3) world positions, metres.
        """
        r = self.jointmap.root
        return self.qpos[:, r : r + 3]

    def angle(self, name: str) -> np.ndarray:
        """The angle of one joint in every frame.

        Args:
            name: the joint's unprefixed name, e.g. ``"knee_l"``.

        Returns:
            (F,) angles, radians (metres for a slide joint).
        """
        return self.qpos[:, self.jointmap.adr(name)]


def iter_frames(timeline: Timeline, data: mujoco.MjData | None = None) -> Iterator[mujoco.MjData]:
    """Play the timeline: set each frame's qpos, run forward kinematics, yield the MjData.

    Args:
        timeline: the timeline to play.
        data: an MjData of the timeline's model to play in (default: a new one).

    Yields:
        ``data`` at each frame in turn, after ``mj_kinematics`` (the same object every time).
    """
    model = timeline.model
    data = data if data is not None else mujoco.MjData(model)
    for q in timeline.qpos:
        data.qpos[:] = q
        mujoco.mj_kinematics(model, data)
        yield data
