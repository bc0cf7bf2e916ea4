"""The compiled step check's parameter vectors: the slots of their floats and integers.

:func:`~mjwalk.plan.stepcheck.check_steps` and :func:`~mjwalk.plan.search.search` take the
planner's options as two flat arrays, a float vector (``P_*`` slots: metres, radians, m/s) and
an integer vector (``I_*`` slots); :func:`params` and :func:`iparams` build them from keyword
slots (:class:`mjwalk.plan.params.KernelParams` fills them for a planner and its walks).
"""

from __future__ import annotations

import functools

import numpy as np

from mjwalk.plan.guide import GUIDE_POINTS

# Slots of the float parameter vector (see :func:`params`).
(
    P_KNEE_LEAD,
    P_KNEE_SIDE,
    P_FOOT_LENGTH,
    P_FOOT_REACH,
    P_LIFT_REACH,
    P_STRIDE,
    P_GOAL_X,
    P_GOAL_Y,
    P_TOLERANCE,
    P_GOAL_YAW,
    P_YAW_TOLERANCE,
    P_WEIGHT,
    P_CORNER_X,
    P_CORNER_Y,
    P_CELL,
    P_FIELD_X0,
    P_FIELD_Y0,
    P_FIELD_RES,
    P_FIELD_LIP,  # the walk field's Lipschitz constant (ClearanceField.lipschitz); nan: sqrt(2)
    P_DIST_X0,
    P_DIST_Y0,
    P_DIST_CELL,
    P_DIST_TOP_X,
    P_DIST_TOP_Y,
    P_KNEE_SHARE0,
    P_KNEE_SHARE1,
    P_STOP_REACH,
    P_POOL_SHARPNESS,
    P_HIP_Y,
    P_LEG_SPAN,
    P_EVERSION,
    P_INVERSION,
    P_ADDUCTION,
    P_ABDUCTION,
    P_FAR_WEIGHT,
    P_FAR_FROM,
    P_LEG_STEP,
    P_LEG_CLEARANCE,
    P_DIST_OFFSET,  # subtracted from the grid bound: a walk's spot lies this far from the goal
    P_PACE,  # the walker's preferred speed (m/s) of the energy cost; nan: length cost only
    P_HEADING_WEIGHT,  # weight of the squared heading error (heading_factor); nan or 0: none
    P_HEADING_FROM,  # the heading term stops this close (m) to the goal point
    P_START_YAW,  # the walker's heading (world radians) before a turn on the spot
    P_TURN_COST,  # cost (m per radian) of a starter's turn on the spot from it; nan: none
    P_TOE_SHARE,  # the chord's share the landing foot's approach is probed over; nan: none
    P_TOE_STEP,  # twice the approach probes' clearance over its guarantee (m; toe_approach_clear)
    P_KNEE_TURN0,  # the swing foot's turned share at the first knee probe (swing_turned)
    P_KNEE_TURN1,  # ... at the second
    P_KNEE_PIVOT,  # the swing hip's offset (m) the foot-yaw knee probes lead from (knee_pivot)
    P_SWING_LIFT_TURN,  # the swing foot's largest lift-off yaw off the pelvis's (radians)
    P_TOE_FRONT,  # the toes' front corners (m) ahead of the landing ankle (toe_corners); nan: none
    P_TOE_SIDE,  # ... and to each side of it
    P_TOE_CLEARANCE,  # the clearance (m) they keep (TOE_CORNER_CLEARANCE)
    P_KNEE_SHARE2,  # the early-swing knee probe's share of the step (options.KNEE_LEAD)
    P_KNEE_TURN2,  # ... and the swing foot's turned share there (swing_turned)
    P_FOOT_ROLL,  # the reach (m) a planted foot's roll adds along its heading (options.foot_reach)
    P_STEP_ADVANCE,  # a step's least advance (m; options.MIN_STEP_ADVANCE); nan: none
    P_GUIDE0,  # the guide's GUIDE_POINTS points, x y each (mjwalk.plan.guide); nan: none
) = range(58)
#: Goal discs: x, y, radius of disc k at P_DISC0 + 3k (see in_goal), after the guide's slots.
P_DISC0 = P_GUIDE0 + 2 * GUIDE_POINTS
#: Most discs the goal area can be cut by (:func:`~mjwalk.plan.stepgeom.in_goal`); their count
#: is I_N_DISCS. A planner takes one fewer (``goal_within``): a walk to a spot keeps the
#: planner's own goal area as one more disc (:meth:`~mjwalk.plan.hybrid.HybridPlanner.plan`).
MAX_GOAL_DISCS = 7
#: The guide's GUIDE_POINTS - 1 segment lengths (m) at P_GUIDE_LEN0 + k, after the discs
#: (:func:`~mjwalk.plan.stepcost.guide_lengths`: made once per walk, not per scored step); nan:
#: no guide.
P_GUIDE_LEN0 = P_DISC0 + 3 * MAX_GOAL_DISCS
N_PARAMS = P_GUIDE_LEN0 + GUIDE_POINTS - 1
# Slots of the integer parameter vector.
(
    I_M,
    I_Q,
    I_KNEE_COL0,
    I_KNEE_COL1,
    I_KNEE_COL2,  # the early-swing knee probe's pelvis sample
    I_SPAN,
    I_BINS,
    I_FIELD_NX,
    I_FIELD_NY,
    I_DIST_NX,
    I_DIJKSTRA,
    I_CHORD,
    I_N_SUCCESSORS,
    I_N_STOPS,
    I_MAX_EXPANSIONS,
    I_NEAR_GOAL_EXPANSIONS,
    I_N_DISCS,
    N_IPARAMS,
) = range(18)


def params(**values) -> np.ndarray:
    """The float parameter vector from keyword slots (``knee_lead=...``, names as P_* lower).

    Args:
        **values: slot values by name (P_* constant names in lower case; unknown: KeyError).

    Returns:
        (:data:`N_PARAMS`,) floats, nan where no value is given.
    """
    slots = [_slot("P_", name) for name in values]
    out = np.full(N_PARAMS, np.nan)
    out[slots] = list(values.values())
    return out


def iparams(**values) -> np.ndarray:
    """The integer parameter vector from keyword slots (names as I_* lower).

    Args:
        **values: slot values by name (I_* constant names in lower case; unknown: KeyError).

    Returns:
        (:data:`N_IPARAMS`,) int64, 0 where no value is given.
    """
    slots = [_slot("I_", name) for name in values]
    out = np.zeros(N_IPARAMS, dtype=np.int64)
    out[slots] = list(values.values())
    return out


@functools.lru_cache(maxsize=256)
def _slot(prefix: str, name: str) -> int:
    """The slot of keyword ``name`` (P_/I_ constants; KeyError for an unknown name)."""
    return globals()[prefix + name.upper()]
