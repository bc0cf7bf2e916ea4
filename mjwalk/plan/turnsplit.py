"""How a walker who stands facing away from the way splits the turn into the walk (issue 48,
station spread): part on the spot, the rest along the first steps.

People do not finish a large turn on the spot and then walk straight off: a direction change
is planned in the step before it and carried out with that step's foot placement (Patla,
Prentice, Robinson & Neufeld 1991, J Exp Psychol Hum Percept Perform 17: 603-634: changes of
30 and 60 degrees made within one step when cued a step ahead), and a turn's last step is the
walk's first, turned about the outside foot (a step turn) or the inside one (a spin turn,
Hase & Stein 1999, J Neurophysiol 81: 2914-2922). Young adults turn 180 degrees as one pivot,
older ones in more, smaller steps (Thigpen et al. 2000, Phys Ther 80: 1174-1187), and the same
person's turns vary (Meinhart-Shibata et al. 2005, Gait Posture 22: 119-125: older women's
maximum pelvic rotation rate 82 % more variable than young women's).

The model (:func:`residual_turn`, :func:`starter_frames`): of a turn larger than
:data:`WALKING_TURN_MAX`, the walker turns on the spot all but a residual drawn per walk
uniformly between :data:`WALKING_TURN_MIN` and :data:`WALKING_TURN_MAX` (Patla et al.'s two
one-step direction changes), and sets off that far from the way to the goal: the planner's
steps turn the rest as they walk (their heading term, :mod:`mjwalk.plan.stepcost`), so the walk
bends out from the work it turned away from. A uniform draw between the two cited changes is
my own modelling step (no published distribution of the split was found). A turn within
:data:`WALKING_TURN_MAX` is left to the search, as before (the walker may set off anywhere
within :data:`~mjwalk.plan.options.START_SPREAD` of the downhill heading).

A split that makes the walk loop (longer than :data:`~mjwalk.plan.options.WANDER_FACTOR` times
its route: set off that far from the way, the walk bends round to arrive) is made wholly on the
spot when the walk is searched again (:meth:`~mjwalk.plan.hybrid.HybridPlanner.plan`), as
after a dead end: the split is a one-step direction change carried into the walk (Patla et al.
1991), not a loop, and people make a turn of up to 180 degrees in place (the 180 degree turns
of Thigpen et al. 2000 above, one pivot in young adults).
"""

from __future__ import annotations

import math

import numpy as np

#: Smallest and largest part (radians) of a standing walker's turn made along the first
#: steps rather than on the spot: the 30 and 60 degree direction changes people made within
#: one step when cued a step ahead (Patla et al. 1991).
WALKING_TURN_MIN = math.radians(30.0)
WALKING_TURN_MAX = math.radians(60.0)
#: Least part (radians) of the turn made on the spot: the walker stands at the work it faced
#: (within reach of it), so the first step goes no nearer it than square to it; a turn within
#: this is left to the search as before.
AWAY_FROM_WORK = math.pi / 2.0
#: Spread (radians, either way) of the starters' headings about the split: one of the 72
#: heading directions the planner's downhill heading is chosen from (5 degrees), twice, so
#: the starters still sample the room ahead (a starter blocked at one heading has neighbours).
STARTER_SPREAD = math.radians(10.0)


def wrap(angle: float) -> float:
    """``angle`` wrapped into [-pi, pi).

    Args:
        angle: an angle, radians.

    Returns:
        The same direction, radians in [-pi, pi).
    """
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def residual_turn(rng: np.random.Generator) -> float:
    """The part of a large turn a walker makes along the first steps (radians, positive):
    uniform between :data:`WALKING_TURN_MIN` and :data:`WALKING_TURN_MAX` (Patla et al. 1991).

    Args:
        rng: the walk's generator (one draw).

    Returns:
        The residual turn, radians.
    """
    return float(rng.uniform(WALKING_TURN_MIN, WALKING_TURN_MAX))


def starter_frames(
    facing: float,
    heading: float,
    n: int,
    rng: np.random.Generator,
    work: float | None = None,
) -> np.ndarray | None:
    """The first steps' headings of a walker standing at ``facing`` who means to walk off along
    ``heading``: None when the turn between them is within :data:`AWAY_FROM_WORK` (the
    search chooses as before); else ``n`` headings the turn's on-the-spot part away from
    ``facing`` (all of the turn but :func:`residual_turn`, and at least as far as square to
    the work's front ``work`` on the turn's side, never past ``heading``), each within
    :data:`STARTER_SPREAD` of it.

    Args:
        facing: the heading the walker stands at, radians from +x CCW.
        heading: the heading towards the goal (the planner's downhill heading), radians.
        n: how many starters.
        rng: the walk's generator (draws only for a turn larger than AWAY_FROM_WORK).
        work: the heading square to the front of the work the walker stands at (a stand
            site's yaw), radians; None: ``facing`` (the walker faces its work squarely).

    Returns:
        (n,) headings, radians, or None.
    """
    turn = wrap(heading - facing)
    if abs(turn) <= AWAY_FROM_WORK:
        return None
    side = math.copysign(1.0, turn)
    square = AWAY_FROM_WORK  # the on-the-spot turn to square to the work's front
    if work is not None and work != facing:
        square = side * wrap(work + side * AWAY_FROM_WORK - facing)
    on_spot = min(max(abs(turn) - residual_turn(rng), square), abs(turn))
    return facing + side * on_spot + rng.uniform(-STARTER_SPREAD, STARTER_SPREAD, n)
