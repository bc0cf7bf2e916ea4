"""Ramp gait: a walker's speed, step length and cadence on a slope, uphill and downhill.

:func:`slope_gait` gives a :class:`SlopeGait` for a walker (:class:`~mjwalk.gait.walker.Walker`)
on a ramp of a given angle (radians, positive uphill in the walking direction). Nothing here is
random: the variation between walkers comes from the walker's own speed and cadence.

The model, and where each part comes from:

- **Speed**: the walker's level speed times Tobler's hiking function normalised to the level,
  ``exp(-3.5 (|tan a + 0.05| - 0.05))`` (Tobler, "Three presentations on geographical analysis
  and modeling", NCGIA Technical Report 93-1, 1993: ``W = 6 exp(-3.5 |tan a + 0.05|)`` km/h;
  the formula verified here in a public implementation's documentation). Uphill it slows
  (5 deg: 0.74 of the level speed). Downhill Tobler's function peaks 19 % above the level
  speed at -2.9 deg; urban pedestrians on ramps of up to 9 deg shorten their steps going down
  (Sun, Walters, Svensson & Lloyd, "The influence of surface slope on human gait
  characteristics", Ergonomics 39:677-692, 1996, abstract verified here) and a walkway in a
  plant is no hiking trail, so downhill the factor is capped at 1 (ASSUMPTION: no faster than
  on the level).
- **Cadence and step length**: at one speed, people step faster downhill and alike uphill:
  Franz & Kram, "The effects of grade and speed on leg muscle activations during walking",
  Gait Posture 35:143-147 (2012), Table 1 (verified here), stride frequency at 1.25 m/s:
  0.99, 0.98, 0.95 Hz at -9, -6, -3 deg, 0.93 Hz level, 0.91, 0.91, 0.92 Hz at +3, +6, +9 deg
  ("not significantly different when walking uphill"). :data:`GRADE_FREQUENCY` keeps the
  downhill ratios and 1 uphill. A change of speed is shared between cadence and step length
  alike (each by the square root of the speed factor), as a walker's walk ratio (step length
  over cadence) stays constant over speeds (Sekiya & Nagasaki, Gait Posture 7:225-227, 1998;
  NOT verified here). The step length is then speed over cadence.
- **Downhill, no step longer than the legs reach**: the front foot of a step of length ``L``
  (along the surface) down a slope ``a`` lands ``L sin|a|`` below the rear one, so
  ``L sin|a| / 2`` below the pelvis, which holds the mean height of the two feet in double
  support (:mod:`mjwalk.body.legs.legheights`); the leading leg, at its full reach at initial
  contact on the level and landing no more flexed going down (knee flexion at heel strike
  rose with the incline walking up, "but not down": McIntosh, Beatty, Dwan & Vickers, "Gait
  dynamics on an inclined walkway", J Biomech (2006), doi 10.1016/j.jbiomech.2005.07.025,
  0-10 deg, abstract verified here), gets there only with the pelvis lowered by that much
  (measured on synthetic ramp walks down 5.5-9.8 deg, statures 1.59-1.83 m: the leg stage's
  raw deficit is ``L sin|a| / 2`` within 2 mm for steps of 0.45-0.75 m, and up to 3.7 mm over
  it for a 1.45 m walker's 0.98 m step; its lowering adds 2 mm). The pelvis may lower at
  most :data:`~mjwalk.body.legs.stance.REACH_DROP_MAX` (Saunders et al. 1953); so downhill
  the step along the surface is at most ``2 DOWNHILL_DROP / sin|a|``
  (:data:`DOWNHILL_DROP`, :func:`downhill_step_max`; 0.57 m at 9.5 deg, 0.98 m at 5.5 deg),
  people shortening their steps going down as Sun et al. 1996 observed. A step so shortened
  keeps the ramp's cadence and slows the walk (speed = step length times cadence), as the
  cited cadences reach no further: the time per step stays Franz & Kram's.

Units: metres, seconds, radians; cadence in steps per second.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mjwalk.errors import InputError
from mjwalk.gait.walker import Walker

#: Tobler (1993): the exponent's slope factor and the offset of the fastest grade.
TOBLER_RATE = 3.5
TOBLER_OFFSET = 0.05
#: Franz & Kram (2012), Table 1 at 1.25 m/s (verified here): grade (deg) and stride frequency
#: relative to level walking (0.93 Hz), downhill only; uphill the frequencies did not differ
#: significantly from level, so the ratio is 1 there.
GRADE_DEG = (-9.0, -6.0, -3.0, 0.0)
GRADE_FREQUENCY = (0.99 / 0.93, 0.98 / 0.93, 0.95 / 0.93, 1.0)
#: A slope steeper than this (radians, either way) is not walked as a ramp: refused. 20 deg is
#: an ASSUMPTION (the cited gait data reach 9 deg; workplace ramps stay far below it).
MAX_RAMP_ANGLE = math.radians(20.0)
#: The most (m) a downhill step may ask the pelvis to lower for the leading leg to reach its
#: foot (module docstring): the leg stage's limit
#: :data:`~mjwalk.body.legs.stance.REACH_DROP_MAX` (0.05 m, the body's whole vertical travel
#: in a level stride, Saunders, Inman & Eberhart 1953) less its lowering's tolerance, 3 mm
#: (:func:`~mjwalk.body.legs.stance.lower_to_reach` lowers 2 mm past each deficit and stops
#: within 1 mm of the reach). The gait stage cannot import the body's figure;
#: ``tests/gait/test_slope.py`` holds the two together.
DOWNHILL_DROP = 0.05 - 0.003


@dataclass(frozen=True)
class SlopeGait:
    """One walker's gait on one ramp.

    Attributes:
        angle: the ramp's angle in the walking direction, radians (positive uphill).
        speed: walking speed along the surface, metres per second.
        cadence: steps per second.
    """

    angle: float
    speed: float
    cadence: float

    @property
    def step_length(self) -> float:
        """Advance per step along the surface, metres."""
        return self.speed / self.cadence

    @property
    def step_time(self) -> float:
        """Time per step, seconds."""
        return 1.0 / self.cadence

    @property
    def horizontal_speed(self) -> float:
        """Speed over the ground plan, metres per second."""
        return self.speed * math.cos(self.angle)

    @property
    def vertical_speed(self) -> float:
        """Rate of climb, metres per second (negative downhill)."""
        return self.speed * math.sin(self.angle)

    def duration(self, run: float) -> float:
        """Time to cross a horizontal distance ``run`` of the ramp.

        Args:
            run: horizontal length, metres (>= 0).

        Returns:
            Seconds.

        Raises:
            InputError: a negative or non-finite length.
        """
        if not math.isfinite(run) or run < 0.0:
            raise InputError(f"ramp run must be a finite length >= 0 m, got {run!r}")
        return run / self.horizontal_speed

    def steps(self, run: float) -> int:
        """Steps to cross a horizontal distance ``run`` (rounded up).

        Args:
            run: horizontal length, metres (>= 0).

        Returns:
            The number of steps.
        """
        return math.ceil(self.duration(run) * self.cadence - 1e-9)


def speed_factor(angle: float) -> float:
    """Walking speed on a slope over walking speed on the level (Tobler 1993, capped at 1).

    Args:
        angle: slope in the walking direction, radians (positive uphill).

    Returns:
        The factor, at most 1.
    """
    g = math.tan(angle)
    return min(1.0, math.exp(-TOBLER_RATE * (abs(g + TOBLER_OFFSET) - TOBLER_OFFSET)))


def frequency_factor(angle: float) -> float:
    """Step frequency on a slope over the level's at the same speed (Franz & Kram 2012).

    Args:
        angle: slope in the walking direction, radians (positive uphill).

    Returns:
        The factor (> 1 downhill, 1 uphill; held at the -9 deg value beyond it).
    """
    return float(np.interp(math.degrees(angle), GRADE_DEG, GRADE_FREQUENCY))


def downhill_step_max(angle: float) -> float:
    """The longest step (along the surface) a walker takes down a slope: its front foot's
    drop below the pelvis, half the step's fall, kept within :data:`DOWNHILL_DROP` (module
    docstring).

    Args:
        angle: slope in the walking direction, radians (positive uphill).

    Returns:
        Metres; ``inf`` on the level and uphill.
    """
    if angle >= 0.0:
        return math.inf
    return 2.0 * DOWNHILL_DROP / math.sin(-angle)


def slope_gait(walker: Walker, angle: float) -> SlopeGait:
    """A walker's gait on a ramp (module docstring: the model and its sources).

    Args:
        walker: the operator (its level speed and cadence).
        angle: the ramp's slope in the walking direction, radians (positive uphill, 0 level).

    Returns:
        The :class:`SlopeGait`.

    Raises:
        InputError: a non-finite angle, one steeper than :data:`MAX_RAMP_ANGLE`, or a walker
            that is not a Walker.
    """
    if not isinstance(walker, Walker):
        raise InputError(f"slope_gait needs a Walker, got {type(walker).__name__}")
    if isinstance(angle, bool) or not isinstance(angle, int | float) or not math.isfinite(angle):
        raise InputError(f"ramp angle must be a finite number of radians, got {angle!r}")
    if abs(angle) > MAX_RAMP_ANGLE:
        raise InputError(
            f"ramp angle {math.degrees(angle):.1f} deg is steeper than a walkable ramp "
            f"({math.degrees(MAX_RAMP_ANGLE):.0f} deg)"
        )
    f = speed_factor(angle)
    cadence = walker.cadence / 60.0 * math.sqrt(f) * frequency_factor(angle)
    speed = min(walker.speed * f, cadence * downhill_step_max(angle))
    return SlopeGait(angle=float(angle), speed=speed, cadence=cadence)
