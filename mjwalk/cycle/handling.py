"""Handling times: how long a reach, its return and a task's hold last, for one operator.

Three factors make a handling time (seconds):

1. **Distance** (MTM-1). The reach out lasts the MTM-1 *Reach* time of its distance
   (:func:`reach_tmu`) -- the true path of the hand, as MTM-1 measures a reach, not the straight
   line between its ends: from where the hand is, along the planned movement, onto the target
   (:mod:`mjwalk.cycle.reaching`; 1.25-1.7 times the straight line at the station) -- and the
   return to rest the MTM-1 reach of case E (hand moved to an indefinite location, out of the
   way). The table is the MTM-1 data card (MTM Association for Standards and
   Research; reproduced e.g. in Maynard's Industrial Engineering Handbook, 5th ed., McGraw-Hill
   2001, ch. 5.5, and in Freivalds & Niebel, *Niebel's Methods, Standards, and Work Design*,
   13th ed., 2014, Table 12-1): time measurement units (1 TMU = 1e-5 h = 0.036 s) by distance
   moved in inches, per case: A (object in fixed location or in the other hand), B (single
   object in a location that may vary slightly), C (object jumbled with others, search and
   select), E (to an indefinite location). Beyond 30 in each case adds its last increment per
   inch (the card's rule).
2. **Pace.** The operator's pace (:attr:`mjwalk.gait.walker.Walker.pace`, speed relative to the
   reference adult): every handling time is divided by it (a slower walker is a slower worker).
   This is mjwalk's modelling choice: MTM times are for the trained
   average operator at standard performance, which the reference adult stands for.
3. **Per-task variation.** Each task of each run draws one lognormal factor of median 1 and
   coefficient of variation :data:`TASK_CV` that multiplies its reach, hold and return: manual
   work-element times are positively skewed and well fitted by a lognormal (Dudley, *Work
   Measurement: Some Research Studies*, Macmillan 1968; Knott & Sury, "A study of work-time
   distributions on unpaced tasks", IIE Transactions 19 (1987) 50-55), with coefficients of
   variation of the order of 0.1-0.3 for short repetitive elements (same sources); mjwalk uses
   the middle of that range. A task's ``duration`` in the cycle file is therefore the median of
   its hold for the reference adult.
"""

from __future__ import annotations

import math

import numpy as np

from mjwalk.errors import MjwalkError
from mjwalk.gait.walker import Walker

#: Seconds per time measurement unit (1 TMU = 0.00001 h).
TMU = 0.036
#: The MTM-1 Reach table: distance moved (inches) and TMU per case (A, B, C, E). Distances of
#: 3/4 in or less are 2.0 TMU in every case.
REACH_INCHES = np.array(
    [0.75, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30], dtype=float
)
# fmt: off
REACH_TMU = {
    "A": np.array([2.0, 2.5, 4.0, 5.3, 6.1, 6.5, 7.0, 7.4, 7.9, 8.3, 8.7, 9.6, 10.5, 11.4, 12.3,
                   13.1, 14.0, 14.9, 15.8, 16.7, 17.5]),
    "B": np.array([2.0, 2.5, 4.0, 5.3, 6.4, 7.8, 8.6, 9.3, 10.1, 10.8, 11.5, 12.9, 14.4, 15.8,
                   17.2, 18.6, 20.1, 21.5, 22.9, 24.4, 25.8]),
    "C": np.array([2.0, 3.6, 5.9, 7.3, 8.4, 9.4, 10.1, 10.8, 11.5, 12.2, 12.9, 14.2, 15.6, 17.0,
                   18.4, 19.8, 21.2, 22.5, 23.9, 25.3, 26.7]),
    "E": np.array([2.0, 2.4, 3.8, 5.3, 6.8, 7.4, 8.0, 8.7, 9.3, 9.9, 10.5, 11.8, 13.0, 14.2,
                   15.5, 16.7, 18.0, 19.2, 20.4, 21.7, 22.9]),
}
# fmt: on
#: MTM-1 case of a reach's return (a hand moving to no particular location); the reach's own
#: case is its task kind's (:data:`mjwalk.cycle.types.TASK_KINDS`).
RETURN_CASE = "E"
#: Coefficient of variation of the per-task lognormal factor (see the module docstring).
TASK_CV = 0.2
#: MTM-1 body motions (TMU): "B" bend, stoop or kneel on one knee, and "AB" arise from it
#: (Freivalds & Niebel 2014, *Niebel's Methods, Standards, and Work Design*, 13th ed.,
#: Table 12-1, Body, leg and foot motions: 29.0 and 31.9 TMU).
BODY_MOTION_TMU = {"B": 29.0, "AB": 31.9}
INCH = 0.0254


def reach_tmu(distance: float, case: str = "B") -> float:
    """MTM-1 reach time of a hand movement of ``distance`` metres: the data card's table
    interpolated in inches, extrapolated linearly beyond its last row.

    Args:
        distance: the hand's path, metres (finite, >= 0).
        case: the MTM-1 reach case, "A", "B", "C" or "E".

    Returns:
        The time in TMU (1 TMU = 0.036 s).

    Raises:
        MjwalkError: an unknown case or a negative or non-finite distance.
    """
    if case not in REACH_TMU:
        raise MjwalkError(f"unknown MTM-1 reach case {case!r} (A, B, C or E)")
    if not math.isfinite(distance) or distance < 0:
        raise MjwalkError(f"reach distance must be a finite number >= 0 m, got {distance!r}")
    inches = distance / INCH
    tmu = REACH_TMU[case]
    if inches <= REACH_INCHES[-1]:
        return float(np.interp(inches, REACH_INCHES, tmu))
    slope = (tmu[-1] - tmu[-2]) / (REACH_INCHES[-1] - REACH_INCHES[-2])
    return float(tmu[-1] + slope * (inches - REACH_INCHES[-1]))


def reach_duration(distance: float, walker: Walker | None = None, case: str = "B") -> float:
    r"""Seconds a reach of ``distance`` metres takes ``walker``: the MTM-1 time divided by the
    walker's pace, :math:`t = \mathrm{TMU}(d) \cdot 0.036 / \mathrm{pace}`.

    Args:
        distance: the hand's path, metres.
        walker: the operator; None: the reference adult (pace 1).
        case: the MTM-1 reach case, "A", "B", "C" or "E".

    Returns:
        The duration, seconds.
    """
    pace = 1.0 if walker is None else walker.pace
    return reach_tmu(distance, case) * TMU / pace


def body_motion_duration(motion: str, walker: Walker | None = None) -> float:
    """Seconds the MTM-1 body motion ``motion`` takes ``walker``.

    Args:
        motion: "B" (bend, stoop) or "AB" (arise).
        walker: the operator; None: the reference adult (pace 1).

    Returns:
        The duration, seconds.

    Raises:
        MjwalkError: an unknown motion.
    """
    if motion not in BODY_MOTION_TMU:
        raise MjwalkError(f"unknown MTM-1 body motion {motion!r}; known: {sorted(BODY_MOTION_TMU)}")
    pace = 1.0 if walker is None else walker.pace
    return BODY_MOTION_TMU[motion] * TMU / pace


def task_factor(rng: np.random.Generator, cv: float = TASK_CV) -> float:
    r"""One task's lognormal time factor: median 1, coefficient of variation ``cv``,
    :math:`f = e^{z}` with :math:`z \sim N(0, \sigma^2)`, :math:`\sigma^2 = \ln(1 + cv^2)`.

    Args:
        rng: the generator drawn from (one normal draw).
        cv: the coefficient of variation.

    Returns:
        The factor (> 0).
    """
    sigma = math.sqrt(math.log1p(cv * cv))
    return float(math.exp(rng.normal(0.0, sigma)))
