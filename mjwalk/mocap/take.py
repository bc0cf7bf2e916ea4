"""The ``Take``: one continuous piece of captured (or synthetic) walking."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mjwalk.conventions import SAMPLE_RATE_HZ

#: Sampling rate of every Take and every synthesized trajectory (Hz), as in agethen2018.
TAKE_FPS = SAMPLE_RATE_HZ


@dataclass
class Take:
    """Motion of one walker sampled at ``fps`` (120 Hz), world frame: metres, z up, yaw from +x.

    Attributes:
        name: where it came from (file name or generator id).
        fps: samples per second.
        pelvis: (T, 3) pelvis (hip-centre) position in metres.
        pelvis_yaw: (T,) heading of the pelvis in radians, counter-clockwise from +x, unwrapped.
        ankle_l, ankle_r: (T, 3) ankle joint positions in metres.
        toe_l, toe_r: (T, 3) toe (ball of foot) positions in metres.
        joints: optional extra joint positions by name, each (T, 3) metres (full skeleton FK).
        meta: free-form provenance (subject id, style, protocol, ...).
    """

    name: str
    fps: float
    pelvis: np.ndarray
    pelvis_yaw: np.ndarray
    ankle_l: np.ndarray
    ankle_r: np.ndarray
    toe_l: np.ndarray
    toe_r: np.ndarray
    joints: dict[str, np.ndarray] = field(default_factory=dict)
    meta: dict = field(default_factory=dict)

    @property
    def n_frames(self) -> int:
        return int(self.pelvis.shape[0])

    @property
    def duration(self) -> float:
        """Length of the take in seconds."""
        return (self.n_frames - 1) / self.fps

    @property
    def time(self) -> np.ndarray:
        """(T,) sample times in seconds from 0."""
        return np.arange(self.n_frames) / self.fps
