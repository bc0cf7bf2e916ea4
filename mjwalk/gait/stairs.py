"""Stair gait: how long a walker takes per step up or down a stair, and how fast the flight goes.

A stair is its riser (rise per step) and tread (going per step), :class:`StairGeometry`. A walker
(:class:`~mjwalk.gait.walker.Walker`) on it gets a :class:`StairGait` from :func:`stair_gait`: the
time per step, the cadence, the stance / swing / double-support times of each step and the
horizontal, vertical and along-the-slope speeds; :meth:`StairGait.flight` times a flight of a
given number of risers (:class:`StairFlight`). Nothing here is random: the variation between
walkers comes from the walker's own figures.

The model, and where each part comes from:

- **One tread per step** (step-over-step, the default pattern): each step lands on the next
  tread, so a step advances one tread horizontally and one riser vertically, and a flight of
  ``n`` risers takes ``n`` steps (the last lands on the landing). The slower *step-to* pattern
  (both feet on every tread) is :data:`STEP_TO`: two steps per tread.
- **Time per step does not depend on the stair's pitch**: Riener, Rabuffetti & Frigo, "Stair
  ascent and descent at different inclinations", Gait Posture 15:32-44 (2002), abstract:
  "Temporal gait cycle parameters ... were not significantly affected by staircase inclination"
  (24, 30 and 42 deg; verified here). The speeds follow from the geometry: a steeper or
  deeper stair changes the speed through the length of a step, not through its time, as
  Fujiyama & Tyler report speeds depending on the gradient ("Free walking speeds on stairs:
  effects of stair gradients and obesity of pedestrians", Pedestrian and Evacuation Dynamics
  2008, Springer 2010, abstract, verified here).
- **The walker's relative pace carries over**: the time per step is the reference adult's
  (:data:`ASCENT_STEP_TIME`, :data:`DESCENT_STEP_TIME`) divided by the walker's level-speed
  ratio :attr:`Walker.pace <mjwalk.gait.walker.Walker.pace>` (speed over the reference adult's
  1.37 m/s). Fujiyama & Tyler, "Predicting the walking speed of pedestrians on stairs",
  Transportation Planning and Technology 33(2):177-202 (2010) predict stair speed from the
  pedestrian's own capacities (leg extensor power, weight) and the gradient (abstract verified
  here); their level walking speed stands in for those capacities here, an ASSUMPTION (the
  walker carries no strength figure). Older and fatigued walkers are slower on stairs because
  they are slower on the level (PRESETS, Bohannon & Andrews 2011; Barbieri et al. 2013), as
  stair studies report (older adults slower up and down: Mian et al., Gait Posture 2007, and
  the Frontiers 2020 study of goings 175-325 mm, abstracts verified here).

Units: metres, seconds, radians; speeds in metres per second, cadence in steps per second.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

from mjwalk.errors import InputError
from mjwalk.gait.walker import Walker

Direction = Literal["up", "down"]
Pattern = Literal["step_over_step", "step_to"]
DIRECTIONS: tuple[Direction, ...] = ("up", "down")
#: One tread per step, the feet passing each other (the usual adult pattern).
STEP_OVER_STEP: Pattern = "step_over_step"
#: Both feet on every tread (lead foot up, trailing foot beside it): two steps per tread, the
#: pattern older people and people with knee pain fall back on (Startzell et al., "Stair
#: negotiation in older people: a review", J Am Geriatr Soc 48:567-580, 2000; NOT verified
#: here). ASSUMPTION: each of its steps takes the step-over-step step time, so a flight takes
#: twice as long.
STEP_TO: Pattern = "step_to"
PATTERNS: tuple[Pattern, ...] = (STEP_OVER_STEP, STEP_TO)

# --------------------------------------------------------------------------- reference walker
#: Time per step of the reference adult (:data:`~mjwalk.gait.walker.REFERENCE_SPEED` on the
#: level) going up a stair, seconds (cadence 103 steps/min). Chosen so that on a 0.17/0.28 m
#: stair the speed along the slope, 0.3276 m / 0.58 s = 0.565 m/s, sits in the middle of
#: Fruin's range of upward stair speeds over age and sex groups, 0.485 (women over 50) to
#: 0.67 m/s (men under 30): Fruin, "Pedestrian Planning and Design" (1971), as PD 7974-6
#: quotes it (verified here through that quote; Fruin observed a 7 in / 11.25 in and a
#: 6 in / 12 in stair).
ASCENT_STEP_TIME = 0.58
#: Time per step of the reference adult going down, seconds (cadence 130 steps/min): speed
#: along a 0.17/0.28 m stair 0.3276 m / 0.46 s = 0.71 m/s, in the lower half of Fruin's
#: downward range 0.595 (women over 50) to 1.01 m/s (men under 30) (Fruin 1971 via PD 7974-6,
#: verified through that quote). Descent is faster than ascent, as Fruin's figures are for
#: every group.
DESCENT_STEP_TIME = 0.46
#: Fruin's (1971) ranges of group-mean stair speeds along the slope, m/s (via PD 7974-6,
#: verified through that quote): the norms the tests and the benchmark hold the adult
#: profiles to.
FRUIN_UP_SPEED = (0.485, 0.67)
FRUIN_DOWN_SPEED = (0.595, 1.01)
#: Stair times of adults of 70 and over (Oh-Park, Wang & Verghese, "Stair negotiation time in
#: community-dwelling older adults", Arch Phys Med Rehabil 92:2006-2011, 2011, Table 2,
#: verified here): group means for 3 steps from standing, 2.09-3.22 s up and 1.98-3.69 s down
#: over age groups 70-74 to 85+ and both sexes; per step (divided by 3, the start included)
#: the ranges below, seconds. The norm the elderly profile is held to.
OH_PARK_UP_STEP_TIME = (2.09 / 3.0, 3.22 / 3.0)
OH_PARK_DOWN_STEP_TIME = (1.98 / 3.0, 3.69 / 3.0)

#: Share of the stride each foot is on the ground (stance), per direction: stair ascent 66 %
#: stance / 34 % swing, descent 60 % / 40 % (McFadyen & Winter, "An integrated biomechanical
#: analysis of normal stair ascent and descent", J Biomech 21:733-744, 1988, as a review quotes
#: it; the quote is verified here, the original not). Beaulieu, Pelland & Robertson, Gait
#: Posture 27:564-571 (2008) measured 65:35 to 70:30 for forward descent (abstract verified
#: here): the descent share is the less certain one. The shares do not vary with the walker
#: here (no cited figure for that).
STANCE_SHARE = {"up": 0.66, "down": 0.60}

# --------------------------------------------------------------------------- geometry limits
#: A tread shallower than this cannot hold a foot for walking, metres: the Austrian workplace
#: ordinance (AStV section 5(5)) allows fixed service stairs down to a 15 cm tread (verified
#: here); below it, :class:`StairGeometry` refuses the stair.
MIN_TREAD = 0.15
#: Steeper than this is a ladder, not a stair, radians: AStV section 5(5) allows service stairs
#: up to 60 deg (verified here).
MAX_PITCH = math.radians(60.0)
#: The usual workplace stair (ASR A1.8 "Verkehrswege", section 4.5, and DIN 18065): riser
#: 0.14-0.19 m, tread 0.26-0.32 m, step rule 2 riser + tread = 0.59-0.65 m. NOT verified here
#: beyond secondary pages (riser 14-19 cm and tread 21-37 cm for DIN 18065, step measure
#: 63-65 cm; AStV section 5(2): riser at most 18 cm, tread at least 26 cm, verified).
#: :attr:`StairGeometry.in_workplace_norm` tells a stair inside them; the gait is given for
#: any stair the checks accept.
NORM_RISER = (0.14, 0.19)
NORM_TREAD = (0.26, 0.32)
NORM_STEP_RULE = (0.59, 0.65)
#: Riener et al. (2002) measured pitches 24-42 deg: the range where the step time's
#: independence of pitch is measured (outside it, it is extrapolated).
MEASURED_PITCH = (math.radians(24.0), math.radians(42.0))


@dataclass(frozen=True)
class StairGeometry:
    """One regular stair: every step the same.

    Attributes:
        riser: rise per step, metres (> 0).
        tread: going per step (nosing to nosing, horizontal), metres (>= :data:`MIN_TREAD`).
    """

    riser: float
    tread: float

    def __post_init__(self) -> None:
        for name in ("riser", "tread"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise InputError(f"stair {name} must be a number of metres, got {value!r}")
            if not math.isfinite(value) or value <= 0.0:
                raise InputError(f"stair {name} must be a finite length > 0 m, got {value!r}")
        if self.tread < MIN_TREAD:
            raise InputError(
                f"stair tread {self.tread:g} m is too shallow for a foot (at least {MIN_TREAD:g} m)"
            )
        if self.pitch > MAX_PITCH:
            raise InputError(
                f"stair riser {self.riser:g} m over tread {self.tread:g} m is "
                f"{math.degrees(self.pitch):.0f} deg steep, a ladder (at most "
                f"{math.degrees(MAX_PITCH):.0f} deg)"
            )

    @property
    def pitch(self) -> float:
        """The stair's angle to the horizontal, radians."""
        return math.atan2(self.riser, self.tread)

    @property
    def slope_length(self) -> float:
        """The length of one step along the slope (nosing to nosing), metres."""
        return math.hypot(self.riser, self.tread)

    @property
    def step_rule(self) -> float:
        """2 risers + 1 tread, metres (the step measure of DIN 18065 / ASR A1.8)."""
        return 2.0 * self.riser + self.tread

    @property
    def in_workplace_norm(self) -> bool:
        """Whether riser, tread and step rule lie in the workplace ranges (:data:`NORM_RISER`,
        :data:`NORM_TREAD`, :data:`NORM_STEP_RULE`)."""
        return (
            NORM_RISER[0] <= self.riser <= NORM_RISER[1]
            and NORM_TREAD[0] <= self.tread <= NORM_TREAD[1]
            and NORM_STEP_RULE[0] <= self.step_rule <= NORM_STEP_RULE[1]
        )


@dataclass(frozen=True)
class StairFlight:
    """A flight walked by one walker.

    Attributes:
        risers: number of risers climbed or descended.
        steps: number of steps (foot placements) it takes.
        duration: time from the first step's start to the last step's landing, seconds.
        run: horizontal length, metres (risers x tread).
        rise: height change, metres (risers x riser; negative going down).
    """

    risers: int
    steps: int
    duration: float
    run: float
    rise: float


@dataclass(frozen=True)
class StairGait:
    """One walker's gait on one stair in one direction.

    Attributes:
        geometry: the stair.
        direction: "up" or "down".
        pattern: :data:`STEP_OVER_STEP` or :data:`STEP_TO`.
        step_time: time per step (one foot placement), seconds.
        stance_share: share of the stride a foot is on the tread.
    """

    geometry: StairGeometry
    direction: Direction
    pattern: Pattern
    step_time: float
    stance_share: float

    @property
    def steps_per_tread(self) -> int:
        """Steps (foot placements) per tread: 1 step-over-step, 2 step-to."""
        return 1 if self.pattern == STEP_OVER_STEP else 2

    @property
    def cadence(self) -> float:
        """Steps per second."""
        return 1.0 / self.step_time

    @property
    def tread_time(self) -> float:
        """Time per tread gained, seconds."""
        return self.step_time * self.steps_per_tread

    @property
    def stance_time(self) -> float:
        """Time one foot is on a tread per stride (two steps), seconds."""
        return 2.0 * self.step_time * self.stance_share

    @property
    def swing_time(self) -> float:
        """Time one foot swings per stride, seconds."""
        return 2.0 * self.step_time * (1.0 - self.stance_share)

    @property
    def double_support_time(self) -> float:
        """Time both feet are on treads in each step, seconds."""
        return self.step_time * (2.0 * self.stance_share - 1.0)

    @property
    def double_support_share(self) -> float:
        """Share of each step both feet are on treads."""
        return 2.0 * self.stance_share - 1.0

    @property
    def horizontal_speed(self) -> float:
        """Speed over the ground plan, metres per second."""
        return self.geometry.tread / self.tread_time

    @property
    def vertical_speed(self) -> float:
        """Rate of climb, metres per second (negative going down)."""
        sign = 1.0 if self.direction == "up" else -1.0
        return sign * self.geometry.riser / self.tread_time

    @property
    def slope_speed(self) -> float:
        """Speed along the slope of the stair (the pedestrian-model stair speed), m/s."""
        return self.geometry.slope_length / self.tread_time

    def flight(self, risers: int) -> StairFlight:
        """The walk over a flight of ``risers`` risers.

        Args:
            risers: number of risers (>= 1).

        Returns:
            The flight: steps (one or two per riser, the last onto the landing), duration in
            seconds, run and rise in metres.

        Raises:
            InputError: ``risers`` not a whole number >= 1.
        """
        if isinstance(risers, bool) or not isinstance(risers, int) or risers < 1:
            raise InputError(f"a flight needs a whole number of risers >= 1, got {risers!r}")
        steps = risers * self.steps_per_tread
        sign = 1.0 if self.direction == "up" else -1.0
        return StairFlight(
            risers=risers,
            steps=steps,
            duration=steps * self.step_time,
            run=risers * self.geometry.tread,
            rise=sign * risers * self.geometry.riser,
        )


def reference_step_time(direction: Direction) -> float:
    """The reference adult's time per step on a stair.

    Args:
        direction: "up" or "down".

    Returns:
        :data:`ASCENT_STEP_TIME` or :data:`DESCENT_STEP_TIME`, seconds.

    Raises:
        InputError: an unknown direction.
    """
    if direction not in DIRECTIONS:
        raise InputError(f"stair direction must be 'up' or 'down', got {direction!r}")
    return ASCENT_STEP_TIME if direction == "up" else DESCENT_STEP_TIME


def stair_gait(
    walker: Walker,
    geometry: StairGeometry,
    direction: Direction,
    pattern: Pattern = STEP_OVER_STEP,
) -> StairGait:
    """A walker's gait on a stair (module docstring: the model and its sources).

    Args:
        walker: the operator; its level-walking pace scales the step time.
        geometry: the stair.
        direction: "up" or "down".
        pattern: :data:`STEP_OVER_STEP` (default) or :data:`STEP_TO`.

    Returns:
        The :class:`StairGait`.

    Raises:
        InputError: an unknown direction or pattern, or a walker that is not a Walker.
    """
    if not isinstance(walker, Walker):
        raise InputError(f"stair_gait needs a Walker, got {type(walker).__name__}")
    if not isinstance(geometry, StairGeometry):
        raise InputError(f"stair_gait needs a StairGeometry, got {type(geometry).__name__}")
    if pattern not in PATTERNS:
        raise InputError(f"stair pattern must be one of {', '.join(PATTERNS)}, got {pattern!r}")
    step_time = reference_step_time(direction) / walker.pace
    return StairGait(
        geometry=geometry,
        direction=direction,
        pattern=pattern,
        step_time=step_time,
        stance_share=STANCE_SHARE[direction],
    )
