"""REBA, the Rapid Entire Body Assessment (Hignett & McAtamney 2000, Applied Ergonomics 31(2),
201-205): trunk, neck and legs (group A) with the load, upper arm, lower arm and wrist (group B)
with the coupling, Table C and the activity score; the REBA score 1-15 and its risk level.

Part scores follow the paper's Tables 1-7 (angles in degrees, flexion positive); the tables
below are its Tables A, B and C. Provenance (checked 2026-12-01): the paper's own tables could
not be reached; Tables A, B and C equal, cell for cell, the REBA Employee Assessment Worksheet
(based on the paper; as transcribed on scribd, doc. 731952909; the test
``test_reba_tables_match_the_employee_worksheet`` holds that transcription in the worksheet's
own layout; a second transcription of the worksheet in another layout (pdfcoffee.com,
"reba-employee-assessment-worksheet") agrees in every cell of Tables A and B it shows), and the
part-score definitions agree with the authors' own handbook chapter (Hignett & McAtamney, Table
42.2 "Group A Definitions", in Fundamentals and Assessment Tools for Occupational Ergonomics).
Secondary sources only: NOT verified against the paper, and no worked example with published
scores from the paper or the authors' chapter could be reached.
:func:`reba_score` is the published procedure on part scores, vectorised over frames;
:func:`part_scores` reads the part scores from
:class:`~mjwalk.ergonomics.angles.BodyAngles`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mjwalk.ergonomics.angles import KNEE_BENT_DEG, NEUTRAL_DEG, BodyAngles, select_first

#: REBA Table A (Hignett & McAtamney 2000): [trunk 1-5][neck 1-3][legs 1-4] -> score A.
TABLE_A = np.array(
    [
        [[1, 2, 3, 4], [1, 2, 3, 4], [3, 3, 5, 6]],
        [[2, 3, 4, 5], [3, 4, 5, 6], [4, 5, 6, 7]],
        [[2, 4, 5, 6], [4, 5, 6, 7], [5, 6, 7, 8]],
        [[3, 5, 6, 7], [5, 6, 7, 8], [6, 7, 8, 9]],
        [[4, 6, 7, 8], [6, 7, 8, 9], [7, 8, 9, 9]],
    ]
)  # fmt: skip
#: REBA Table B (Hignett & McAtamney 2000): [upper arm 1-6][lower arm 1-2][wrist 1-3] -> B.
TABLE_B = np.array(
    [
        [[1, 2, 2], [1, 2, 3]],
        [[1, 2, 3], [2, 3, 4]],
        [[3, 4, 5], [4, 5, 5]],
        [[4, 5, 5], [5, 6, 7]],
        [[6, 7, 8], [7, 8, 8]],
        [[7, 8, 8], [8, 9, 9]],
    ]
)  # fmt: skip
#: REBA Table C (Hignett & McAtamney 2000): [score A 1-12][score B 1-12] -> score C.
TABLE_C = np.array(
    [
        [1, 1, 1, 2, 3, 3, 4, 5, 6, 7, 7, 7],
        [1, 2, 2, 3, 4, 4, 5, 6, 6, 7, 7, 8],
        [2, 3, 3, 3, 4, 5, 6, 7, 7, 8, 8, 8],
        [3, 4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9],
        [4, 4, 4, 5, 6, 7, 8, 8, 9, 9, 9, 9],
        [6, 6, 6, 7, 8, 8, 9, 9, 10, 10, 10, 10],
        [7, 7, 7, 8, 9, 9, 9, 10, 10, 11, 11, 11],
        [8, 8, 8, 9, 10, 10, 10, 10, 10, 11, 11, 11],
        [9, 9, 9, 10, 10, 10, 11, 11, 11, 12, 12, 12],
        [10, 10, 10, 11, 11, 11, 11, 12, 12, 12, 12, 12],
        [11, 11, 11, 11, 12, 12, 12, 12, 12, 12, 12, 12],
        [12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12, 12],
    ]
)  # fmt: skip
#: Coupling score (Hignett & McAtamney 2000, Table 6): good 0, fair 1, poor 2, unacceptable 3.
COUPLING = {"good": 0, "fair": 1, "poor": 2, "unacceptable": 3}
#: Load/force bounds (kg; Table 3): below 5 kg 0, 5-10 kg 1, above 10 kg 2 (+1 shock).
LOAD_KG = (5.0, 10.0)


@dataclass
class RebaParts:
    """Part scores (int arrays over frames)."""

    trunk: np.ndarray
    neck: np.ndarray
    legs: np.ndarray
    upper_arm: np.ndarray
    lower_arm: np.ndarray
    wrist: np.ndarray


def load_score(load_kg, shock: bool = False):
    """REBA's load/force score (:data:`LOAD_KG`): 0 below 5 kg, 1 for 5-10 kg, 2 above 10 kg,
    +1 with shock.

    Args:
        load_kg: the load, kg (scalar or per frame).
        shock: shock or rapid build-up of force.

    Returns:
        An int for scalars, else an array of scores.
    """
    lo, hi = LOAD_KG
    load = np.asarray(load_kg, dtype=float)
    score = select_first([load > hi, load >= lo], [2, 1], 0) + int(shock)
    return int(score) if score.ndim == 0 else score


def reba_score(parts: RebaParts, load=0, coupling=0, activity=0) -> np.ndarray:
    """The REBA score 1-15 from the part scores (the published tables, vectorised).

    Score A is Table A of the trunk, neck and legs scores, B Table B of the upper arm, lower
    arm and wrist scores; the REBA score is Table C of :math:`A + load` and
    :math:`B + coupling` (each clipped to 1-12) plus the activity score. Part scores beyond a
    table's range are clipped into it.

    Args:
        parts: the part scores (ints, scalars or per-frame arrays of one shape).
        load: load/force score 0-3 (:func:`load_score`).
        coupling: coupling score 0-3 (:data:`COUPLING`).
        activity: activity score 0-3.

    Returns:
        The REBA scores, shaped like the part scores.
    """
    a = TABLE_A[
        np.clip(np.asarray(parts.trunk), 1, 5) - 1,
        np.clip(np.asarray(parts.neck), 1, 3) - 1,
        np.clip(np.asarray(parts.legs), 1, 4) - 1,
    ]
    b = TABLE_B[
        np.clip(np.asarray(parts.upper_arm), 1, 6) - 1,
        np.clip(np.asarray(parts.lower_arm), 1, 2) - 1,
        np.clip(np.asarray(parts.wrist), 1, 3) - 1,
    ]
    c = TABLE_C[np.clip(a + load, 1, 12) - 1, np.clip(b + coupling, 1, 12) - 1]
    return c + activity


def risk_level(score) -> np.ndarray:
    """REBA action level 0-4 (1 negligible; 2-3 low; 4-7 medium; 8-10 high; 11+ very high).

    Args:
        score: REBA scores (scalar or array).

    Returns:
        The levels 0-4, shaped like ``score``.
    """
    s = np.asarray(score)
    if s.ndim == 0:  # one score (the report's per task and run): no five temporary arrays
        v = s.item()
        return np.asarray(0 if v <= 1 else 1 if v <= 3 else 2 if v <= 7 else 3 if v <= 10 else 4)
    return select_first([s <= 1, s <= 3, s <= 7, s <= 10], [0, 1, 2, 3], 4)


def body_parts(ang: BodyAngles) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """REBA's trunk, neck and legs scores of every frame (the same for either arm).

    Args:
        ang: the body angles of F frames.

    Returns:
        (trunk, neck, legs), each (F,) ints.
    """
    tf = ang.trunk_flexion
    # upright 1; 0-20 deg flexion or extension 2; 20-60 flexion or > 20 extension 3; > 60 4
    trunk = select_first([np.abs(tf) <= NEUTRAL_DEG, np.abs(tf) <= 20, tf <= 60], [1, 2, 3], 4)
    trunk = trunk + (ang.trunk_twisted | ang.trunk_side_bent)
    nf = ang.neck_flexion
    neck = np.where((nf >= -NEUTRAL_DEG) & (nf <= 20), 1, 2) + (
        ang.neck_twisted | ang.neck_side_bent
    )
    legs = np.where(ang.legs_supported, 1, 2)
    # the knees of the legs that bear weight (both when both feet are down)
    kf = np.where(ang.feet_down, ang.knee_flexion, 0.0).max(axis=1)
    kf = np.where(ang.walking, 0.0, kf)
    legs = legs + select_first([kf > 60, kf >= KNEE_BENT_DEG], [2, 1], 0)
    return trunk.astype(int), neck.astype(int), legs.astype(int)


def part_scores(ang: BodyAngles, side: int, body: tuple | None = None) -> RebaParts:
    """REBA part scores of every frame for one arm (thresholds in
    :mod:`mjwalk.ergonomics.angles`).

    Args:
        ang: the body angles of F frames.
        side: the arm, 0 left, 1 right.
        body: :func:`body_parts` of ``ang``, if already computed (both arms share them).

    Returns:
        The :class:`RebaParts`, each (F,).
    """
    trunk, neck, legs = body if body is not None else body_parts(ang)
    ua_ang = ang.upper_arm_angle[:, side]
    ua = select_first([ua_ang > 90, ua_ang > 45, (ua_ang > 20) | (ua_ang < -20)], [4, 3, 2], 1)
    ua = ua + ang.arm_abducted[:, side] + ang.shoulder_raised[:, side]
    el = ang.elbow_flexion[:, side]
    la = np.where((el >= 60) & (el <= 100), 1, 2)
    wf = np.abs(ang.wrist_flexion[:, side])
    wr = np.where(wf <= 15, 1, 2) + (ang.wrist_deviated[:, side] | ang.wrist_twist_end[:, side])
    return RebaParts(trunk, neck, legs, ua.astype(int), la.astype(int), wr.astype(int))


def reba(
    ang: BodyAngles, side: int, load_kg: float = 0.0, coupling: str = "good",
    static: bool = False, repeated: bool = False,
) -> np.ndarray:  # fmt: skip
    """REBA scores of one arm with the load in that hand, the coupling of its grip and the
    activity (+1 static > 1 min, +1 repeated > 4 times a minute).

    Args:
        ang: the body angles of F frames.
        side: the arm, 0 left, 1 right.
        load_kg: the load in that hand, kg.
        coupling: the grip's coupling, a key of :data:`COUPLING`.
        static: the posture is held longer than a minute.
        repeated: the posture is repeated more than 4 times a minute.

    Returns:
        (F,) REBA scores.
    """
    activity = int(static) + int(repeated)
    return parts_score(part_scores(ang, side), load_score(load_kg), COUPLING[coupling], activity)


def parts_score(p: RebaParts, load=0, coupling=0, activity=0) -> np.ndarray:
    """REBA scores of one side's part scores (:func:`reba_score`).

    Args:
        p: the part scores.
        load: load/force score (scalar or per frame).
        coupling: coupling score (scalar or per frame).
        activity: activity score (scalar or per frame).

    Returns:
        (F,) REBA scores.
    """
    return reba_score(p, load, coupling, activity)
