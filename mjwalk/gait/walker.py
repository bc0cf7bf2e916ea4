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
        """A copy with some figures changed (validated again).

        Args:
            **changes: field names and their new values.

        Returns:
            The new walker.
        """
        return replace(self, **changes)

    @classmethod
    def preset(cls, name: str, **changes) -> Walker:
        """The typical (mean) walker of a named :data:`PRESETS` group, with ``changes``.

        Args:
            name: the preset group.
            **changes: fields overriding the preset's means (validated).

        Returns:
            The walker, ``group`` set to ``name``.
        """
        p = get_preset(name)
        base = cls(
            stature=p.stature[0],
            speed=p.speed[0],
            cadence=p.cadence[0],
            step_width=p.step_width,
            group=name,
        )
        return replace(base, **changes) if changes else base


@dataclass(frozen=True)
class WalkerPreset:
    """A group of operators: mean and between-person standard deviation of each figure.

    Attributes:
        stature, speed, cadence: (mean, sd) in metres, metres per second, steps per minute.
        step_width: fixed step width (m), or None for the model's, scaled by stature.
        source: where the figures come from.
    """

    stature: tuple[float, float]
    speed: tuple[float, float]
    cadence: tuple[float, float]
    step_width: float | None
    source: str


#: Named operator groups from published norms of comfortable ("preferred") straight walking.
#: Speeds: Bohannon & Andrews, "Normal walking speed: a descriptive meta-analysis",
#: Physiotherapy 97:182-189 (2011), grand means per decade (m/s): men 20-59 1.36-1.43, women
#: 20-59 1.31-1.39; men 60-79 1.34/1.26, women 60-79 1.24/1.13; 80-99 men 0.97, women 0.94;
#: between-person SD about 0.15-0.22 m/s (the same tables). Cadence: adults 113 steps/min
#: (Perry & Burnfield 2010, ch. 1; between-person SD about 8, ibid.); older adults keep their
#: cadence and shorten the step (Hollman, McDade & Petersen, "Normative spatiotemporal gait
#: parameters in older adults", Gait Posture 34:111-118, 2011: about 110 steps/min at 70-79 and
#: about 104 at 80+ with SD 8-10). Stature: working-age adults, both sexes pooled, mean 1.72 m,
#: SD 0.09 (DIN 33402-2:2020, German adults 18-65: men 1.79 +- 0.07, women 1.66 +- 0.06);
#: older people are about 3-5 cm shorter (same standard, age groups 61-65 and older).
PRESETS: dict[str, WalkerPreset] = {
    "adult": WalkerPreset(
        stature=(1.72, 0.09),
        speed=(1.38, 0.17),
        cadence=(113.0, 8.0),
        step_width=None,
        source="Bohannon & Andrews 2011 (20-59 y); Perry & Burnfield 2010; DIN 33402-2",
    ),
    "older_adult": WalkerPreset(
        stature=(1.69, 0.09),
        speed=(1.24, 0.18),
        cadence=(110.0, 9.0),
        step_width=None,
        source="Bohannon & Andrews 2011 (60-79 y); Hollman et al. 2011; DIN 33402-2",
    ),
    "elderly": WalkerPreset(
        stature=(1.66, 0.09),
        speed=(0.95, 0.20),
        cadence=(104.0, 10.0),
        step_width=None,
        source="Bohannon & Andrews 2011 (80-99 y); Hollman et al. 2011 (80+ y)",
    ),
    # Fatigue after hours of work: the direction of the change is reported (slower, shorter
    # and wider steps: Barbieri et al., "Systematic review of the effects of fatigue on
    # spatiotemporal gait parameters", J Back Musculoskelet Rehabil 26:125-131, 2013); the
    # sizes here (speed -10 %, cadence -4 %, width +1.5 cm about the adult figures) are an
    # ASSUMPTION within the reported ranges: set your own in the cycle file when you have them.
    "fatigued": WalkerPreset(
        stature=(1.72, 0.09),
        speed=(1.24, 0.17),
        cadence=(108.0, 8.0),
        step_width=0.08,
        source="adult figures changed as Barbieri et al. 2013 report (sizes assumed)",
    ),
    # Hurrying (behind takt): "brisk" walking is >= 100 steps/min and faster than comfortable;
    # about 1.6-1.8 m/s at 120-130 steps/min for adults asked to walk fast but not maximal
    # (Bohannon 1997, "Comfortable and maximum walking speed of adults aged 20-79 years",
    # Age Ageing 26:15-19: maximal 1.75-2.53 m/s; Tudor-Locke et al. 2018, Br J Sports Med
    # 52:776: cadence >= 100 moderate, >= 130 vigorous). ASSUMPTION: 1.65 m/s, 124 steps/min.
    "brisk": WalkerPreset(
        stature=(1.72, 0.09),
        speed=(1.65, 0.15),
        cadence=(124.0, 8.0),
        step_width=None,
        source="between Bohannon 1997 comfortable and maximal; Tudor-Locke et al. 2018",
    ),
}


def get_preset(name: str) -> WalkerPreset:
    """The :data:`PRESETS` entry ``name``.

    Args:
        name: preset group name.

    Returns:
        The preset.

    Raises:
        WalkerError: for an unknown name.
    """
    try:
        return PRESETS[name]
    except KeyError:
        raise WalkerError(
            f"unknown walker preset {name!r}; known: {', '.join(sorted(PRESETS))}"
        ) from None
