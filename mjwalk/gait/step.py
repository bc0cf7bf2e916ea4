"""The ``Step``: one aligned left or right step, the atom of the step model (agethen2018 §3.3)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mjwalk.conventions import Side


@dataclass
class Step:
    """One step cut from a take between two foot-contact key frames, in its local frame.

    The local frame starts at the pelvis position of the first sample with the pelvis heading
    +y (agethen2018 §3.3): x to the walker's right, y forward, metres; yaw in radians,
    counter-clockwise, 0 = +y (the start heading).

    Attributes:
        side: the foot that swings during this step and lands at its end ("left" or "right").
        fps: sampling rate of ``pelvis`` and ``yaw`` (120 Hz).
        pelvis: (K, 2) pelvis x, y in metres; ``pelvis[0] == (0, 0)``.
        yaw: (K,) pelvis yaw relative to the start heading, radians; ``yaw[0] == 0``.
        footprint: (3,) landing foot (the swing foot at the end) x, y in metres and yaw, radians.
        stance: (3,) stance foot (the other foot) x, y and yaw during the step.
        take: name of the source take.
        index: index of the step within its take; steps ``i`` and ``i + 1`` of the same take
            with alternating sides are a captured transition.
        meta: provenance (subject id, protocol, ...).
    """

    side: Side
    fps: float
    pelvis: np.ndarray
    yaw: np.ndarray
    footprint: np.ndarray
    stance: np.ndarray
    take: str = ""
    index: int = 0
    meta: dict = field(default_factory=dict)

    @property
    def n_samples(self) -> int:
        return int(self.pelvis.shape[0])

    @property
    def duration(self) -> float:
        """Step duration in seconds."""
        return (self.n_samples - 1) / self.fps

    @property
    def length(self) -> float:
        """Straight-line pelvis displacement over the step, metres."""
        return float(np.hypot(*self.pelvis[-1]))

    @property
    def end_yaw(self) -> float:
        """Pelvis yaw at the end of the step relative to its start, radians."""
        return float(self.yaw[-1])
