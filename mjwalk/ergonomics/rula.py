"""RULA, the Rapid Upper Limb Assessment (McAtamney & Corlett 1993, Applied Ergonomics 24(2),
91-99): posture scores of the arm and wrist (group A) and of the neck, trunk and legs (group B),
the muscle-use and force/load terms, the grand score 1-7 and its action level 1-4.

The part scores follow the paper's Figures 1-3 (angles in degrees, flexion positive); the three
tables are the paper's Tables 1 and 2 and its grand-score table ("Table A", "Table B", "Table C"
of the score sheet). Provenance (checked 2026-12-01): OCR excerpts of the paper's text
(th4.ilovetranslation.com pages hZeRv4cNDav, vCKe8TzaeWW) confirm the neck, trunk and legs
scores, the force/load score (2 for 2-10 kg static or repeated or > 10 kg intermittent, 3 for >
10 kg static or repeated or any shock) and the meaning of grand scores 1-2, 3-4 and 5-6 as coded
here; the paper's tables themselves could not be reached; Tables A, B and C here agree cell for
cell with several independent public implementations (found by exact-row search of public code).
One circulating worksheet (the "RULA Employee Assessment Worksheet", as transcribed on scribd,
doc. 36693774) prints 7 in Table A at upper arm 6, lower arm 2, wrist 1, no twist, where every
implementation found (and this table) has 8. The table is left as the majority has it (both
values keep it monotone); it is NOT verified against the paper. The cell changes a score only
for that part-score combination (score A 8 vs 7). No worked example with published scores from
the paper itself could be reached, so none is tested.
:func:`grand_score` is the published procedure on part scores, vectorised over frames;
:func:`part_scores` reads the part scores from
:class:`~mjwalk.ergonomics.angles.BodyAngles` (the thresholds a continuous angle needs where the
paper shows a drawing are stated in :mod:`mjwalk.ergonomics.angles`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mjwalk.ergonomics.angles import NEUTRAL_DEG, BodyAngles, select_first

#: RULA Table A (McAtamney & Corlett 1993, Table 1): [upper arm 1-6][lower arm 1-3][wrist 1-4]
#: [wrist twist 1-2] -> posture score A.
TABLE_A = np.array(
    [
        [[[1, 2], [2, 2], [2, 3], [3, 3]], [[2, 2], [2, 2], [3, 3], [3, 3]], [[2, 3], [3, 3], [3, 3], [4, 4]]],  # noqa: E501
        [[[2, 3], [3, 3], [3, 4], [4, 4]], [[3, 3], [3, 3], [3, 4], [4, 4]], [[3, 4], [4, 4], [4, 4], [5, 5]]],  # noqa: E501
        [[[3, 3], [4, 4], [4, 4], [5, 5]], [[3, 4], [4, 4], [4, 4], [5, 5]], [[4, 4], [4, 4], [4, 5], [5, 5]]],  # noqa: E501
        [[[4, 4], [4, 4], [4, 5], [5, 5]], [[4, 4], [4, 4], [4, 5], [5, 5]], [[4, 4], [4, 5], [5, 5], [6, 6]]],  # noqa: E501
        [[[5, 5], [5, 5], [5, 6], [6, 7]], [[5, 6], [6, 6], [6, 7], [7, 7]], [[6, 6], [6, 7], [7, 7], [7, 8]]],  # noqa: E501
        [[[7, 7], [7, 7], [7, 8], [8, 9]], [[8, 8], [8, 8], [8, 9], [9, 9]], [[9, 9], [9, 9], [9, 9], [9, 9]]],  # noqa: E501
    ]
)  # fmt: skip
#: RULA Table B (McAtamney & Corlett 1993, Table 2): [neck 1-6][trunk 1-6][legs 1-2] -> B.
TABLE_B = np.array(
    [
        [[1, 3], [2, 3], [3, 4], [5, 5], [6, 6], [7, 7]],
        [[2, 3], [2, 3], [4, 5], [5, 5], [6, 7], [7, 7]],
        [[3, 3], [3, 4], [4, 5], [5, 6], [6, 7], [7, 7]],
        [[5, 5], [5, 6], [6, 7], [7, 7], [7, 7], [8, 8]],
        [[7, 7], [7, 7], [7, 8], [8, 8], [8, 8], [8, 8]],
        [[8, 8], [8, 8], [8, 8], [8, 9], [9, 9], [9, 9]],
    ]
)  # fmt: skip
#: RULA Table C (McAtamney & Corlett 1993, Table 3): [score C 1-8+][score D 1-7+] -> grand score.
TABLE_C = np.array(
    [
        [1, 2, 3, 3, 4, 5, 5],
        [2, 2, 3, 4, 4, 5, 5],
        [3, 3, 3, 4, 4, 5, 6],
        [3, 3, 3, 4, 5, 6, 6],
        [4, 4, 4, 5, 6, 7, 7],
        [4, 4, 5, 6, 6, 7, 7],
        [5, 5, 6, 6, 7, 7, 7],
        [5, 5, 6, 7, 7, 7, 7],
    ]
)  # fmt: skip

#: Force/load bounds (kg) of the force score (McAtamney & Corlett 1993, Fig. 2): below 2 kg
#: intermittent 0; 2-10 kg intermittent 1; 2-10 kg static or repeated 2; 10 kg or more static
#: or repeated, or shock, 3.
FORCE_KG = (2.0, 10.0)


@dataclass
class RulaParts:
    """Part scores (arrays over frames; ints) of one side's arm and the body."""

    upper_arm: np.ndarray
    lower_arm: np.ndarray
    wrist: np.ndarray
    wrist_twist: np.ndarray
    neck: np.ndarray
    trunk: np.ndarray
    legs: np.ndarray


def force_score(load_kg, static_or_repeated, shock: bool = False):
    """RULA's force/load score 0-3 of a load held in the hands.

    Args:
        load_kg: the load, kg (scalar or per frame).
        static_or_repeated: the load is held static or repeated (scalar or per frame).
        shock: shock or rapid build-up of force (3 throughout).

    Returns:
        An int for scalars, else an array of scores shaped like the inputs.
    """
    lo, hi = FORCE_KG
    load = np.asarray(load_kg, dtype=float)
    held = np.asarray(static_or_repeated, dtype=bool)
    # >= 10 kg intermittent: the paper gives 2, static or repeated 3
    score = select_first([load >= hi, load >= lo], [np.where(held, 3, 2), np.where(held, 2, 1)], 0)
    if shock:
        score = np.full_like(score, 3)
    return int(score) if score.ndim == 0 else score


def grand_score(parts: RulaParts, muscle_a=0, force_a=0, muscle_b=0, force_b=0) -> np.ndarray:
    """RULA's grand score 1-7 from the part scores (the published tables, vectorised).

    Score A is Table A of the arm and wrist scores, B Table B of the neck, trunk and legs
    scores; the grand score is Table C of :math:`C = A + m_A + f_A` (clipped to 1-8) and
    :math:`D = B + m_B + f_B` (clipped to 1-7). Part scores beyond a table's range are
    clipped into it.

    Args:
        parts: the part scores (ints, scalars or per-frame arrays of one shape).
        muscle_a: muscle-use score (0/1) of group A, the arm and wrist.
        force_a: force/load score (0-3) of group A.
        muscle_b: muscle-use score (0/1) of group B, the neck, trunk and legs.
        force_b: force/load score (0-3) of group B.

    Returns:
        The grand scores 1-7, shaped like the part scores.
    """
    ua = np.clip(np.asarray(parts.upper_arm), 1, 6) - 1
    la = np.clip(np.asarray(parts.lower_arm), 1, 3) - 1
    wr = np.clip(np.asarray(parts.wrist), 1, 4) - 1
    tw = np.clip(np.asarray(parts.wrist_twist), 1, 2) - 1
    a = TABLE_A[ua, la, wr, tw]
    b = TABLE_B[
        np.clip(np.asarray(parts.neck), 1, 6) - 1,
        np.clip(np.asarray(parts.trunk), 1, 6) - 1,
        np.clip(np.asarray(parts.legs), 1, 2) - 1,
    ]
    c = np.clip(a + muscle_a + force_a, 1, 8) - 1
    d = np.clip(b + muscle_b + force_b, 1, 7) - 1
    return TABLE_C[c, d]


def action_level(score) -> np.ndarray:
    """RULA action level 1-4 of grand scores (1-2: acceptable; 3-4: investigate further;
    5-6: investigate and change soon; 7: investigate and change immediately).

    Args:
        score: grand scores 1-7 (scalar or array).

    Returns:
        The action levels, shaped like ``score``.
    """
    s = np.asarray(score)
    if s.ndim == 0:  # one score (the report's per task and run): no four temporary arrays
        v = s.item()
        return np.asarray(1 if v <= 2 else 2 if v <= 4 else 3 if v <= 6 else 4)
    return select_first([s <= 2, s <= 4, s <= 6], [1, 2, 3], 4)


def body_parts(ang: BodyAngles) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """RULA's neck, trunk and legs scores of every frame (the same for either arm).

    Args:
        ang: the body angles of F frames.

    Returns:
        (neck, trunk, legs), each (F,) ints.
    """
    nf = ang.neck_flexion
    neck = select_first([nf < -NEUTRAL_DEG, nf <= 10, nf <= 20], [4, 1, 2], 3)
    neck = neck + ang.neck_twisted + ang.neck_side_bent
    tf = ang.trunk_flexion
    trunk = select_first([np.abs(tf) <= NEUTRAL_DEG, tf <= 20, tf <= 60], [1, 2, 3], 4)
    trunk = np.where(tf < -NEUTRAL_DEG, 2, trunk)  # extension: scored as the 0-20 band
    trunk = trunk + ang.trunk_twisted + ang.trunk_side_bent
    return neck.astype(int), trunk.astype(int), np.where(ang.legs_supported, 1, 2)


def part_scores(ang: BodyAngles, side: int, body: tuple | None = None) -> RulaParts:
    """RULA part scores of every frame for one arm (thresholds in
    :mod:`mjwalk.ergonomics.angles`).

    Args:
        ang: the body angles of F frames.
        side: the arm, 0 left, 1 right.
        body: :func:`body_parts` of ``ang``, if already computed (both arms share them).

    Returns:
        The :class:`RulaParts`, each (F,).
    """
    ua_ang = ang.upper_arm_angle[:, side]
    ua = select_first([ua_ang > 90, ua_ang > 45, (ua_ang > 20) | (ua_ang < -20)], [4, 3, 2], 1)
    ua = ua + ang.shoulder_raised[:, side] + ang.arm_abducted[:, side]
    el = ang.elbow_flexion[:, side]
    la = np.where((el >= 60) & (el <= 100), 1, 2) + ang.lower_arm_out[:, side]
    wf = np.abs(ang.wrist_flexion[:, side])
    wr = select_first([wf <= NEUTRAL_DEG, wf <= 15], [1, 2], 3) + ang.wrist_deviated[:, side]
    tw = np.where(ang.wrist_twist_end[:, side], 2, 1)
    neck, trunk, legs = body if body is not None else body_parts(ang)
    return RulaParts(ua.astype(int), la.astype(int), wr.astype(int), tw, neck, trunk, legs)


def rula(
    ang: BodyAngles, side: int, load_kg: float = 0.0, static: bool = False,
    repeated: bool = False,
) -> np.ndarray:  # fmt: skip
    """RULA grand scores of one arm with the load in that hand. Muscle use is +1 when the
    posture is static (held > 1 min) or repeated (4 times a minute or more), in both groups as
    the paper's worksheet does.

    Args:
        ang: the body angles of F frames.
        side: the arm, 0 left, 1 right.
        load_kg: the load in that hand, kg.
        static: the posture is held longer than a minute.
        repeated: the posture is repeated 4 times a minute or more.

    Returns:
        (F,) grand scores 1-7.
    """
    muscle = int(static or repeated)
    return parts_score(part_scores(ang, side), muscle, force_score(load_kg, muscle))


def parts_score(p: RulaParts, muscle, force) -> np.ndarray:
    """RULA grand scores of one arm's part scores with the same muscle-use and force scores in
    the arm-and-wrist and the neck-trunk-legs groups, as the worksheet applies them.

    Args:
        p: the part scores.
        muscle: muscle-use score 0/1 (scalar or per frame).
        force: force/load score 0-3 (scalar or per frame).

    Returns:
        (F,) grand scores 1-7.
    """
    return grand_score(p, muscle, force, muscle, force)
