"""mjwalk.ergonomics.rula: RULA's published tables (McAtamney & Corlett 1993), the force
score, the action levels and the part scores read from the humanoid's angles."""

from __future__ import annotations

import numpy as np
import pytest
from test_angles import humanoid_angles

from mjwalk.ergonomics import rula
from mjwalk.ergonomics.rula import RulaParts


def monotone(table: np.ndarray) -> bool:
    """Never decreasing along any axis (a property of every published score table: a worse
    part score never lowers the result), which catches most transcription slips."""
    return all(bool((np.diff(table, axis=ax) >= 0).all()) for ax in range(table.ndim))


@pytest.mark.parametrize("table", [rula.TABLE_A, rula.TABLE_B, rula.TABLE_C])
def test_rula_tables_never_decrease(table):
    assert monotone(table)


def test_rula_table_shapes_and_corners():
    assert rula.TABLE_A.shape == (6, 3, 4, 2) and rula.TABLE_B.shape == (6, 6, 2)
    assert rula.TABLE_C.shape == (8, 7)
    # the tables' first and last cells (McAtamney & Corlett 1993)
    assert rula.grand_score(RulaParts(1, 1, 1, 1, 1, 1, 1)) == 1
    assert rula.grand_score(RulaParts(6, 3, 4, 2, 6, 6, 2), 1, 3, 1, 3) == 7


def test_parts_score_adds_muscle_and_force_to_both_groups():
    """parts_score is grand_score with the same muscle-use and force scores in groups A and B;
    part scores beyond a table's range are clipped into it."""
    p = RulaParts(*(np.array([1, 2, 3]) for _ in range(7)))
    assert rula.parts_score(p, 1, 2).tolist() == rula.grand_score(p, 1, 2, 1, 2).tolist()
    # all parts 2: A 3, B 3, C[3][3] = 3; all 3 (twist and legs clipped to 2): A 5, B 5, 6
    assert rula.parts_score(p, 0, 0).tolist() == [1, 3, 6]
    assert rula.grand_score(RulaParts(9, 9, 9, 9, 9, 9, 9)) == rula.grand_score(
        RulaParts(6, 3, 4, 2, 6, 6, 2)
    )


def test_rula_table_a_disputed_cell():
    """Table A at upper arm 6, lower arm 2, wrist 1, no twist: 8 in every independent public
    implementation found, 7 on one circulating worksheet; McAtamney & Corlett 1993 itself was not
    reachable (see mjwalk.ergonomics.rula). Pinned so that a change is deliberate."""
    assert rula.TABLE_A[6 - 1, 2 - 1, 1 - 1, 1 - 1] == 8
    assert rula.TABLE_A[6 - 1, 1 - 1, 1 - 1, 1 - 1] == 7


def test_rula_action_levels_and_force():
    assert list(rula.action_level([1, 2, 3, 4, 5, 6, 7])) == [1, 1, 2, 2, 3, 3, 4]
    # McAtamney & Corlett 1993 Fig. 2: < 2 kg 0; 2-10 kg intermittent 1; 2-10 static or
    # repeated 2; >= 10 kg intermittent 2; >= 10 kg static or repeated 3
    assert rula.force_score(1.0, False) == 0
    assert rula.force_score(5.0, False) == 1
    assert rula.force_score(5.0, True) == 2
    assert rula.force_score(12.0, False) == 2
    assert rula.force_score(12.0, True) == 3


def test_raising_the_arm_never_lowers_the_upper_arm_score():
    """Monotonicity: a higher reach (more shoulder flexion) gives an upper-arm score and a
    RULA score at least as high."""
    ua, score = [], []
    for deg in np.arange(0.0, 180.0, 5.0):
        a = humanoid_angles(shoulder_l_flex=deg, elbow_l=30.0)
        ua.append(int(rula.part_scores(a, 0).upper_arm[0]))
        score.append(int(rula.rula(a, 0)[0]))
    assert ua == sorted(ua) and ua[0] == 1 and ua[-1] == 4
    assert score == sorted(score)


def test_one_score_gets_the_action_level_an_array_of_it_gets():
    """The one-score path (the report's per task and run) agrees with the per-frame one."""
    scores = np.array([0, 1, 2, 2.5, 3, 4, 4.5, 5, 6, 6.5, 7, 9, np.nan])
    levels = rula.action_level(scores)
    for s, level in zip(scores, levels, strict=True):
        one = rula.action_level(s)
        assert one.shape == () and one.dtype == levels.dtype and one == level
