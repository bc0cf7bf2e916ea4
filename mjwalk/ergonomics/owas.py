"""OWAS, the Ovako Working posture Analysing System (Karhu, Kansi & Kuorinka 1977, Applied
Ergonomics 8(4), 199-201): a four-digit posture code (back, arms, legs, load) and its action
category 1-4 from the published classification table (Karhu et al. 1977; the table as reprinted
by Karhu et al. 1981 and in the OWAS manual of the Finnish Institute of Occupational Health).

Codes: back 1 straight, 2 bent forward/backward, 3 twisted or bent sideways, 4 bent and twisted;
arms 1 both below shoulder level, 2 one at or above, 3 both at or above; legs 1 sitting,
2 standing on both straight legs, 3 on one straight leg, 4 on both bent knees, 5 on one bent knee,
6 kneeling, 7 walking; load 1 below 10 kg, 2 10-20 kg, 3 above 20 kg.
"""

from __future__ import annotations

import numpy as np

from mjwalk.ergonomics.angles import KNEE_BENT_DEG, BodyAngles, select_first

#: OWAS action categories: [back 1-4][arms 1-3][legs 1-7][load 1-3] (Karhu et al. 1977).
#: Provenance (checked 2026-12-01): the 1977/1981 papers could not be reached. Of six
#: independent public transcriptions found (exact-row search of public code), four equal this
#: table in all 252 cells; two others differ in two cells: back 3 (twisted), arms 3, legs 7
#: (walking), load 3 -> 2 there (1 here), and back 4, arms 1, legs 3 (one straight leg), load 2
#: -> 3 there (2 here). Kept as the majority has it; those two cells are NOT settled from the
#: primary source.
TABLE = np.array(
    [
        [[[1, 1, 1], [1, 1, 1], [1, 1, 1], [2, 2, 2], [2, 2, 2], [1, 1, 1], [1, 1, 1]],
         [[1, 1, 1], [1, 1, 1], [1, 1, 1], [2, 2, 2], [2, 2, 2], [1, 1, 1], [1, 1, 1]],
         [[1, 1, 1], [1, 1, 1], [1, 1, 1], [2, 2, 3], [2, 2, 3], [1, 1, 1], [1, 1, 2]]],
        [[[2, 2, 3], [2, 2, 3], [2, 2, 3], [3, 3, 3], [3, 3, 3], [2, 2, 2], [2, 3, 3]],
         [[2, 2, 3], [2, 2, 3], [2, 3, 3], [3, 4, 4], [3, 4, 4], [3, 3, 4], [2, 3, 4]],
         [[3, 3, 4], [2, 2, 3], [3, 3, 3], [3, 4, 4], [4, 4, 4], [4, 4, 4], [2, 3, 4]]],
        [[[1, 1, 1], [1, 1, 1], [1, 1, 2], [3, 3, 3], [4, 4, 4], [1, 1, 1], [1, 1, 1]],
         [[2, 2, 3], [1, 1, 1], [1, 1, 2], [4, 4, 4], [4, 4, 4], [3, 3, 3], [1, 1, 1]],
         [[2, 2, 3], [1, 1, 1], [2, 3, 3], [4, 4, 4], [4, 4, 4], [4, 4, 4], [1, 1, 1]]],
        [[[2, 3, 3], [2, 2, 3], [2, 2, 3], [4, 4, 4], [4, 4, 4], [4, 4, 4], [2, 3, 4]],
         [[3, 3, 4], [2, 3, 4], [3, 3, 4], [4, 4, 4], [4, 4, 4], [4, 4, 4], [2, 3, 4]],
         [[4, 4, 4], [2, 3, 4], [3, 3, 4], [4, 4, 4], [4, 4, 4], [4, 4, 4], [2, 3, 4]]],
    ]
)  # fmt: skip
#: Back bent or twisted from this many degrees (trunk flexion/side bend, twist): the bound of
#: ISO 11226's acceptable zone of trunk inclination (0-20 deg), applied to all three.
BACK_DEG = 20.0
#: Load bounds (kg) of the load code (Karhu et al. 1977).
LOAD_KG = (10.0, 20.0)


def action_category(back, arms, legs, load) -> np.ndarray:
    """OWAS action category 1-4 of posture codes: 1 no action, 2 in the near future, 3 as soon
    as possible, 4 immediately (:data:`TABLE`).

    Args:
        back: back code 1-4 (scalar or array).
        arms: arms code 1-3.
        legs: legs code 1-7.
        load: load code 1-3.

    Returns:
        The action categories, shaped like the codes.
    """
    return TABLE[
        np.asarray(back) - 1, np.asarray(arms) - 1, np.asarray(legs) - 1, np.asarray(load) - 1
    ]


def load_code(load_kg: float) -> int:
    """OWAS load code of a load (:data:`LOAD_KG`).

    Args:
        load_kg: the load, kg.

    Returns:
        1 below 10 kg, 2 for 10-20 kg, 3 above 20 kg.
    """
    lo, hi = LOAD_KG
    return 1 if load_kg < lo else 2 if load_kg <= hi else 3


def load_codes(load_kg: np.ndarray) -> np.ndarray:
    """:func:`load_code` of every frame's load at once.

    Args:
        load_kg: (F,) loads, kg.

    Returns:
        (F,) load codes 1-3.
    """
    lo, hi = LOAD_KG
    kg = np.asarray(load_kg, dtype=float)
    return np.where(kg < lo, 1, np.where(kg <= hi, 2, 3))


def codes(ang: BodyAngles, load_kg: float = 0.0) -> np.ndarray:
    """OWAS posture codes of every frame.

    Args:
        ang: the body angles of F frames.
        load_kg: the load handled, kg (the same in every frame).

    Returns:
        (F, 4) codes (back, arms, legs, load).
    """
    bent = np.abs(ang.trunk_flexion) >= BACK_DEG
    twisted = (np.abs(ang.trunk_twist) >= BACK_DEG) | (np.abs(ang.trunk_side_bend) >= BACK_DEG)
    back = select_first([bent & twisted, twisted, bent], [4, 3, 2], 1)
    high = ang.upper_arm_elevation >= 90.0  # the upper arm at or above shoulder level
    arms = 1 + high.sum(axis=1)
    down = ang.feet_down
    bentk = ang.knee_flexion >= KNEE_BENT_DEG
    both = down.all(axis=1)
    legs = np.where(
        both,
        np.where((bentk & down).any(axis=1), 4, 2),
        np.where((bentk & down).any(axis=1), 5, 3),
    )
    legs = np.where(ang.walking, 7, legs)
    load = np.full(ang.n_frames, load_code(load_kg))
    return np.stack([back, arms, legs, load], axis=1)


def owas(ang: BodyAngles, load_kg: float = 0.0) -> np.ndarray:
    """OWAS action categories of every frame (:func:`codes`, :func:`action_category`).

    Args:
        ang: the body angles of F frames.
        load_kg: the load handled, kg.

    Returns:
        (F,) action categories 1-4.
    """
    c = codes(ang, load_kg)
    return action_category(c[:, 0], c[:, 1], c[:, 2], c[:, 3])
