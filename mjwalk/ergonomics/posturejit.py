"""RULA, REBA and OWAS frame by frame in one compiled pass each (issue 50): the part scores of
:func:`mjwalk.ergonomics.rula.part_scores`, :func:`mjwalk.ergonomics.reba.part_scores` and
:func:`mjwalk.ergonomics.owas.codes` and their tables' scores, per frame, the same integers as
those functions' NumPy code (the same comparisons in the same order, NaN angles included: a
comparison with NaN is false there as here). The thresholds and tables are the methods' own
(passed in from :mod:`mjwalk.ergonomics.angles`, :mod:`~mjwalk.ergonomics.rula`,
:mod:`~mjwalk.ergonomics.reba` and :mod:`~mjwalk.ergonomics.owas`); angles in degrees, loads
in kg.
"""

from __future__ import annotations

import numpy as np

from mjwalk._jit import njit
from mjwalk.ergonomics.angles import (
    ABDUCTION_PLANE_DEG,
    ASYMMETRY_DEG,
    KNEE_BENT_DEG,
    NEUTRAL_DEG,
    TWIST_END_SHARE,
    WRIST_DEVIATED_DEG,
    BodyAngles,
)


@njit
def _clip(x: int, lo: int, hi: int) -> int:
    return lo if x < lo else hi if x > hi else x


@njit
def _upper_arm(a: float, plane: float, raised: bool, abd_deg: float) -> int:
    """RULA's and REBA's upper-arm score (the same bands), with the raised shoulder and the
    abducted arm."""
    s = 4 if a > 90 else 3 if a > 45 else 2 if (a > 20) | (a < -20) else 1
    return s + int(raised) + int((abs(a) > 20) & (plane > abd_deg))


@njit
def rula_kernel(body, arms, flags, loads, thresholds, tables, parts, score):
    """RULA per frame and arm (:func:`mjwalk.ergonomics.rula.part_scores`,
    :func:`~mjwalk.ergonomics.rula.force_score`, :func:`~mjwalk.ergonomics.rula.parts_score`).

    Args:
        body: (5, F) neck flexion, neck twist, neck side bend, trunk flexion, trunk twist; trunk
            side bend follows as row 5 (6 rows in all), degrees.
        arms: (6, F, 2) upper-arm angle, plane, elbow flexion, wrist flexion, deviation and
            twist, degrees.
        flags: (4, F, 2) bool: shoulder raised, lower arm out, feet down, walking (column 0).
        loads: (2, F, 2) the load in each hand (kg) and its muscle use (0/1).
        thresholds: neutral, asymmetry, abduction plane, wrist deviated, twist end (deg), and
            the force bounds (kg).
        tables: (TABLE_A, TABLE_B, TABLE_C) of :mod:`mjwalk.ergonomics.rula`.
        parts: (2, 7, F) int filled: per arm upper arm, lower arm, wrist, wrist twist, neck,
            trunk, legs.
        score: (F, 2) int filled: the grand scores.
    """
    neutral, asym, abd, dev, twist_end, lo, hi = thresholds
    ta, tb, tc = tables
    for f in range(body.shape[1]):
        nf, tf = body[0, f], body[3, f]
        neck = 4 if nf < -neutral else 1 if nf <= 10 else 2 if nf <= 20 else 3
        neck += int(abs(body[1, f]) > asym) + int(abs(body[2, f]) > asym)
        trunk = 1 if abs(tf) <= neutral else 2 if tf <= 20 else 3 if tf <= 60 else 4
        if tf < -neutral:
            trunk = 2
        trunk += int(abs(body[4, f]) > asym) + int(abs(body[5, f]) > asym)
        legs = 1 if (flags[2, f, 0] & flags[2, f, 1]) | flags[3, f, 0] else 2
        for s in range(2):
            ua = _upper_arm(arms[0, f, s], arms[1, f, s], flags[0, f, s], abd)
            el = arms[2, f, s]
            la = (1 if (el >= 60) & (el <= 100) else 2) + int(flags[1, f, s])
            wf = abs(arms[3, f, s])
            wr = (1 if wf <= neutral else 2 if wf <= 15 else 3) + int(abs(arms[4, f, s]) > dev)
            tw = 2 if abs(arms[5, f, s]) > twist_end else 1
            load, muscle = loads[0, f, s], int(loads[1, f, s])
            held = muscle > 0
            force = (3 if held else 2) if load >= hi else (2 if held else 1) if load >= lo else 0
            a = ta[
                _clip(ua, 1, 6) - 1, _clip(la, 1, 3) - 1, _clip(wr, 1, 4) - 1, _clip(tw, 1, 2) - 1
            ]
            b = tb[_clip(neck, 1, 6) - 1, _clip(trunk, 1, 6) - 1, _clip(legs, 1, 2) - 1]
            c = _clip(a + muscle + force, 1, 8) - 1
            d = _clip(b + muscle + force, 1, 7) - 1
            score[f, s] = tc[c, d]
            parts[s, 0, f], parts[s, 1, f], parts[s, 2, f], parts[s, 3, f] = ua, la, wr, tw
            parts[s, 4, f], parts[s, 5, f], parts[s, 6, f] = neck, trunk, legs


@njit
def reba_kernel(body, arms, knee, flags, loads, thresholds, tables, parts, score):
    """REBA per frame and side (:func:`mjwalk.ergonomics.reba.body_parts`,
    :func:`~mjwalk.ergonomics.reba.part_scores`, :func:`~mjwalk.ergonomics.reba.load_score`,
    :func:`~mjwalk.ergonomics.reba.parts_score`).

    Args:
        body: (6, F) as :func:`rula_kernel`'s.
        arms: (6, F, 2) as :func:`rula_kernel`'s.
        knee: (F, 2) knee flexion, degrees.
        flags: (4, F, 2) as :func:`rula_kernel`'s.
        loads: (3, F, 2) the load in each hand (kg), its coupling score and its activity.
        thresholds: neutral, asymmetry, abduction plane, wrist deviated, twist end, knee bent
            (deg), and the load bounds (kg).
        tables: (TABLE_A, TABLE_B, TABLE_C) of :mod:`mjwalk.ergonomics.reba`.
        parts: (2, 6, F) int filled: per side trunk, neck, legs, upper arm, lower arm, wrist.
        score: (F, 2) int filled: the REBA scores.
    """
    neutral, asym, abd, dev, twist_end, bent, lo, hi = thresholds
    ta, tb, tc = tables
    for f in range(body.shape[1]):
        nf, tf = body[0, f], body[3, f]
        trunk = 1 if abs(tf) <= neutral else 2 if abs(tf) <= 20 else 3 if tf <= 60 else 4
        trunk += int((abs(body[4, f]) > asym) | (abs(body[5, f]) > asym))
        neck = 1 if (nf >= -neutral) & (nf <= 20) else 2
        neck += int((abs(body[1, f]) > asym) | (abs(body[2, f]) > asym))
        down0, down1, walking = flags[2, f, 0], flags[2, f, 1], flags[3, f, 0]
        legs = 1 if (down0 & down1) | walking else 2
        k0 = knee[f, 0] if down0 else 0.0
        k1 = knee[f, 1] if down1 else 0.0
        kf = k1 if (k1 > k0) | (k1 != k1) else k0  # NumPy's max: NaN wins
        if walking:
            kf = 0.0
        legs += 2 if kf > 60 else 1 if kf >= bent else 0
        for s in range(2):
            ua = _upper_arm(arms[0, f, s], arms[1, f, s], flags[0, f, s], abd)
            el = arms[2, f, s]
            la = 1 if (el >= 60) & (el <= 100) else 2
            wr = 1 if abs(arms[3, f, s]) <= 15 else 2
            wr += int((abs(arms[4, f, s]) > dev) | (abs(arms[5, f, s]) > twist_end))
            load = loads[0, f, s]
            ls = 2 if load > hi else 1 if load >= lo else 0
            a = ta[_clip(trunk, 1, 5) - 1, _clip(neck, 1, 3) - 1, _clip(legs, 1, 4) - 1]
            b = tb[_clip(ua, 1, 6) - 1, _clip(la, 1, 2) - 1, _clip(wr, 1, 3) - 1]
            c = tc[_clip(a + ls, 1, 12) - 1, _clip(b + int(loads[1, f, s]), 1, 12) - 1]
            score[f, s] = c + int(loads[2, f, s])
            parts[s, 0, f], parts[s, 1, f], parts[s, 2, f] = trunk, neck, legs
            parts[s, 3, f], parts[s, 4, f], parts[s, 5, f] = ua, la, wr


@njit
def owas_kernel(body, elevation, knee, flags, load, thresholds, table, out):
    """OWAS's action category per frame (:func:`mjwalk.ergonomics.owas.codes`,
    :func:`~mjwalk.ergonomics.owas.load_codes`, :func:`~mjwalk.ergonomics.owas.action_category`).

    Args:
        body: (6, F) as :func:`rula_kernel`'s.
        elevation: (F, 2) upper-arm elevation from the vertical, degrees.
        knee: (F, 2) knee flexion, degrees.
        flags: (4, F, 2) as :func:`rula_kernel`'s.
        load: (F, 2) the load in each hand, kg.
        thresholds: back bent, knee bent (deg), and the load bounds (kg).
        table: OWAS's table [back][arms][legs][load].
        out: (F,) int filled: the action categories 1-4.
    """
    back_deg, bent_deg, lo, hi = thresholds
    for f in range(body.shape[1]):
        bent = abs(body[3, f]) >= back_deg
        twisted = (abs(body[4, f]) >= back_deg) | (abs(body[5, f]) >= back_deg)
        back = 4 if bent & twisted else 3 if twisted else 2 if bent else 1
        arms = 1 + int(elevation[f, 0] >= 90.0) + int(elevation[f, 1] >= 90.0)
        d0, d1 = flags[2, f, 0], flags[2, f, 1]
        any_bent = ((knee[f, 0] >= bent_deg) & d0) | ((knee[f, 1] >= bent_deg) & d1)
        if d0 & d1:
            legs = 4 if any_bent else 2
        else:
            legs = 5 if any_bent else 3
        if flags[3, f, 0]:
            legs = 7
        kg = load[f, 0] + load[f, 1]
        code = 1 if kg < lo else 2 if kg <= hi else 3
        out[f] = table[back - 1, arms - 1, legs - 1, code - 1]


def posture_inputs(ang: BodyAngles) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The kernels' angle arrays of some body angles (contiguous copies).

    Args:
        ang: the body angles of F frames.

    Returns:
        ``(body (6, F), arms (6, F, 2), flags (4, F, 2))`` as :func:`rula_kernel` reads them.
    """
    body = np.stack(
        [ang.neck_flexion, ang.neck_twist, ang.neck_side_bend, ang.trunk_flexion,
         ang.trunk_twist, ang.trunk_side_bend]
    ).astype(float, copy=False)  # fmt: skip
    arms = np.stack(
        [ang.upper_arm_angle, ang.upper_arm_plane, ang.elbow_flexion, ang.wrist_flexion,
         ang.wrist_deviation, ang.wrist_twist]
    ).astype(float, copy=False)  # fmt: skip
    walking = np.broadcast_to(np.asarray(ang.walking, dtype=bool)[:, None], (ang.n_frames, 2))
    flags = np.stack([ang.shoulder_raised, ang.lower_arm_out, ang.feet_down, walking]).astype(
        bool, copy=False
    )
    return body, arms, flags


#: The angle thresholds every kernel reads (degrees; :mod:`mjwalk.ergonomics.angles`).
ANGLE_THRESHOLDS = (NEUTRAL_DEG, ASYMMETRY_DEG, ABDUCTION_PLANE_DEG, WRIST_DEVIATED_DEG)


def twist_end(ang: BodyAngles) -> float:
    """The forearm rotation beyond which the twist is at the end of its range.

    Args:
        ang: the body angles (their ``twist_range``).

    Returns:
        Degrees.
    """
    return TWIST_END_SHARE * ang.twist_range


__all__ = [
    "ANGLE_THRESHOLDS",
    "KNEE_BENT_DEG",
    "owas_kernel",
    "posture_inputs",
    "reba_kernel",
    "rula_kernel",
    "twist_end",
]
