"""What scoring a cycle gives: per task the peaks of the posture scores (:class:`TaskErgonomics`),
per run those with the lifts, the static holdings and the frame-by-frame scores
(:class:`RunErgonomics`; what every run keeps, without its timeline).

The built-in methods (:data:`mjwalk.ergonomics.registry.SCORES`) fill the named fields; a method
registered beside them puts its values in ``extra`` under the names it gives them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mjwalk.ergonomics import iso11226, niosh, reba, rula


@dataclass
class TaskErgonomics:
    """The peaks of one task: RULA 1-7, REBA 1-15, OWAS action category 1-4, the time of the
    RULA peak (s from the cycle's start), the body parts that drive the RULA and REBA peaks,
    the RULA peak's arm ("left"/"right") and the task's highest RULA upper-arm score;
    ``reach``: the task is a reach (:attr:`~mjwalk.ergonomics.score.TaskSpan.reach`; left out
    of :meth:`RunErgonomics.summary`); ``extra``: the task's values of the registered methods
    that have no field here, by name."""

    index: int
    kind: str
    site: str | None
    rula: int
    reba: int
    owas: int
    rula_time: float
    rula_driver: str
    reba_driver: str
    side: str
    upper_arm: int
    reach: bool = False
    extra: dict[str, Any] = field(default_factory=dict)


@dataclass
class RunErgonomics:
    """The ergonomics of one simulated cycle (kept by every run; no timeline).

    Attributes:
        tasks: per task peaks (:class:`TaskErgonomics`).
        lifts: the NIOSH lifts (:class:`~mjwalk.ergonomics.niosh.Lift`) of parts with a mass.
        holdings: ISO 11226's worst static holding of the trunk and of each upper arm.
        fps: frame rate of the per-frame scores, frames/s.
        rula, reba: (F,) per-frame scores (int8) at ``fps``.
        extra: the run's values of the registered methods that have no field here, by name.
    """

    tasks: list[TaskErgonomics]
    lifts: list[niosh.Lift]
    holdings: list[iso11226.Holding]
    fps: float
    rula: np.ndarray = field(repr=False)
    reba: np.ndarray = field(repr=False)
    extra: dict[str, Any] = field(default_factory=dict, repr=False)

    @property
    def rula_peak(self) -> int:
        """The cycle's highest RULA grand score (1-7; 1 without frames)."""
        return int(self.rula.max(initial=1))

    @property
    def reba_peak(self) -> int:
        """The cycle's highest REBA score (1-15; 1 without frames)."""
        return int(self.reba.max(initial=1))

    @property
    def owas_peak(self) -> int:
        """The highest OWAS action category of the cycle's tasks (1-4; 1 without tasks)."""
        return max((t.owas for t in self.tasks), default=1)

    @property
    def max_li(self) -> float | None:
        """The highest lifting index of the lifts that have one (0.0 without lifts; None when
        no lift has one: see :attr:`~mjwalk.ergonomics.niosh.Lift.reason`)."""
        lis = [lf.li for lf in self.lifts if lf.li is not None]
        return max(lis) if lis else (None if self.lifts else 0.0)

    @property
    def lifts_without_li(self) -> list[niosh.Lift]:
        """The lifts the NIOSH equation gives no index (RWL 0; each says why)."""
        return [lf for lf in self.lifts if lf.li is None]

    def summary(self) -> dict:
        """Plain data (JSON-ready) without the per-frame scores.

        Returns:
            The peaks and levels, each task's peaks (with its ``extra`` values), the lifts and
            the holdings.
        """
        return {
            "rula_peak": self.rula_peak,
            "rula_action_level": int(rula.action_level(self.rula_peak)),
            "reba_peak": self.reba_peak,
            "reba_risk_level": int(reba.risk_level(self.reba_peak)),
            "owas_peak": self.owas_peak,
            "max_lifting_index": self.max_li,
            "tasks": [
                {**{k: v for k, v in vars(t).items() if k not in ("reach", "extra")}, **t.extra}
                for t in self.tasks
            ],
            "lifts": [vars(lf) for lf in self.lifts],
            "iso11226": [vars(h) for h in self.holdings],
        }
