"""The ``Walker``: one operator's gait, the figures the step model is conditioned on.

A walker is described by its stature and its preferred (self-selected, comfortable) straight-walk
pace: speed in metres per second and cadence in steps per minute. Their ratio is the preferred
step length, ``speed * 60 / cadence`` metres (one step = heel strike to the other foot's heel
strike). Optional figures (step width) default to values that scale with stature.

The step model samples steps *for a walker* (see :meth:`mjwalk.gait.model.StepModel`); the cycle
simulation draws one walker per run from a population (``mjwalk.cycle``) and scales handling
times by :attr:`Walker.pace`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from mjwalk.errors import MjwalkError

#: Reference pace of an adult at comfortable speed, the unit of :attr:`Walker.pace`: 1.37 m/s
#: (82 m/min) at 113 steps/min, Perry & Burnfield, *Gait Analysis: Normal and Pathological
#: Function*, 2nd ed. (2010), ch. 1 (free-walking adults, both sexes pooled).
REFERENCE_SPEED = 1.37
REFERENCE_CADENCE = 113.0

#: Plausibility bounds for a walker's figures (checked on construction): slower than 0.3 m/s or
#: faster than 2.5 m/s is not walking; cadence outside 60-180 steps/min neither.
SPEED_RANGE = (0.3, 2.5)
CADENCE_RANGE = (60.0, 180.0)
STATURE_RANGE = (1.2, 2.2)


class WalkerError(MjwalkError):
    """A walker's figures are missing, not finite, or outside human ranges."""


@dataclass(frozen=True)
class Walker:
    """One operator's gait.

    Attributes:
        stature: body height, metres.
        speed: preferred straight-walk speed, metres per second.
        cadence: preferred cadence, steps per minute.
        step_width: lateral distance between the ankle centres, metres (``None``: the model's
            default for the stature).
        group: a label for reports (e.g. the preset or population group it was drawn from).
    """

    stature: float = 1.75
    speed: float = REFERENCE_SPEED
    cadence: float = REFERENCE_CADENCE
    step_width: float | None = None
    group: str = "custom"

    def __post_init__(self) -> None:
        for name, (lo, hi) in (
            ("stature", STATURE_RANGE),
            ("speed", SPEED_RANGE),
            ("cadence", CADENCE_RANGE),
        ):
            value = getattr(self, name)
            if not isinstance(value, int | float) or not math.isfinite(value):
                raise WalkerError(f"walker {name} must be a finite number, got {value!r}")
            if not lo <= value <= hi:
                raise WalkerError(
                    f"walker {name} {value:g} is outside the human range {lo:g}-{hi:g}"
                )
        if self.step_width is not None and not (
            math.isfinite(self.step_width) and 0.0 <= self.step_width <= 0.4
        ):
            raise WalkerError(f"walker step_width {self.step_width!r} must be within 0-0.4 m")

    @property
    def step_length(self) -> float:
        """Preferred step length (pelvis advance per step), metres."""
        return self.speed * 60.0 / self.cadence

    @property
    def step_duration(self) -> float:
        """Preferred step duration (heel strike to heel strike), seconds."""
        return 60.0 / self.cadence

    @property
    def pace(self) -> float:
        """Speed relative to the reference adult (1.0 = :data:`REFERENCE_SPEED`); handling
        times are divided by it."""
        return self.speed / REFERENCE_SPEED

    def with_(self, **changes) -> Walker:
        """A copy with some figures changed (validated again)."""
        return replace(self, **changes)
