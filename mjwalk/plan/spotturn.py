"""How many steps on the spot a turn after a crossing takes, and how long each lasts (issue 47):
the one place the body's stepped turn (:func:`mjwalk.plan.stepturn.stepped_turn`) and the
hybrid A*'s cost of that turn (a standing start after a crossing, ``WalkRequest(turn_step=...)``,
:func:`mjwalk.plan.stepcheck.check_into`) both take them from, so the planned walk costs the
turn the animation makes.

A turn within :data:`TURN_PER_STEP` is walked on in the leg's first step (no step on the spot:
it costs nothing beyond that step); a larger one takes the fewest even number of steps on the
spot whose equal parts are each within :data:`TURN_PER_STEP`, each lasting the walker's step
rounded to whole samples (:data:`~mjwalk.conventions.SAMPLE_RATE_HZ`), as it is animated.
The planner charges a starter that time at the walk's pace (metres, as its steps), from the
heading the walker stands at to the walk's first yaw, and adds it after the step's heading
factor (it is time stood turning, not a length walked off the way). Seconds, radians.
"""

from __future__ import annotations

import math

from mjwalk._jit import njit
from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.plan.options import SWING_LIFT_TURN

#: Most the pelvis turns in one step on the spot, radians: the hip's rotation range
#: (``ROM_DEG["hip_rot"]``, 45 deg; :data:`mjwalk.plan.options.SWING_LIFT_TURN`). A foot stands
#: through two steps, so the pelvis leaves it at most this far off its landing heading at
#: lift-off (within the hip's range, no pivot needed) and each swing turns a foot by at most
#: twice this. ASSUMPTION: the range, not a measured turning-step figure, bounds the split (a
#: half turn in four steps).
TURN_PER_STEP = SWING_LIFT_TURN


@njit
def spot_steps(turn: float) -> int:
    """How many steps on the spot make a turn: none within :data:`TURN_PER_STEP` (walked on in
    the leg's first step), else the fewest even number (the leg's first step keeps its foot)
    whose equal parts are each within :data:`TURN_PER_STEP`.

    Args:
        turn: the pelvis's turn, radians (either sign).

    Returns:
        The number of steps (0, 2, 4).
    """
    if abs(turn) <= TURN_PER_STEP:
        return 0
    return 2 * math.ceil(abs(turn) / (2.0 * TURN_PER_STEP) - 1e-9)


def spot_step_samples(step_duration: float) -> int:
    """How many samples one step on the spot lasts: the walker's step, in whole samples.

    Args:
        step_duration: the walker's step duration, seconds
            (:attr:`Walker.step_duration <mjwalk.gait.walker.Walker.step_duration>`).

    Returns:
        Samples at :data:`~mjwalk.conventions.SAMPLE_RATE_HZ`, at least one.
    """
    return max(1, round(step_duration * SAMPLE_RATE_HZ))


def spot_step_time(step_duration: float) -> float:
    """How long one step on the spot lasts as animated (:func:`spot_step_samples`).

    Args:
        step_duration: the walker's step duration, seconds.

    Returns:
        Seconds.
    """
    return spot_step_samples(step_duration) / SAMPLE_RATE_HZ


def spot_turn_time(turn: float, step_duration: float) -> float:
    """How long a turn after a crossing takes on the spot: its steps (:func:`spot_steps`) at
    :func:`spot_step_time` each; 0 for a turn walked on.

    Args:
        turn: the pelvis's turn, radians (either sign).
        step_duration: the walker's step duration, seconds.

    Returns:
        Seconds.
    """
    return spot_steps(turn) * spot_step_time(step_duration)
