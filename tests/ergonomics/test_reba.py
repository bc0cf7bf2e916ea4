"""mjwalk.ergonomics.reba: REBA's published tables (Hignett & McAtamney 2000) against the
employee worksheet, a third-party worked example, the load score and the risk levels."""

from __future__ import annotations

import numpy as np
import pytest
from test_rula import monotone

from mjwalk.ergonomics import reba
from mjwalk.ergonomics.reba import RebaParts


@pytest.mark.parametrize("table", [reba.TABLE_A, reba.TABLE_B, reba.TABLE_C])
def test_reba_tables_never_decrease(table):
    assert monotone(table)


def test_reba_table_shapes_and_corners():
    assert reba.TABLE_A.shape == (5, 3, 4) and reba.TABLE_B.shape == (6, 2, 3)
    assert reba.TABLE_C.shape == (12, 12)
    # the tables' first and last cells (Hignett & McAtamney 2000)
    assert reba.reba_score(RebaParts(1, 1, 1, 1, 1, 1)) == 1
    assert reba.reba_score(RebaParts(5, 3, 4, 6, 2, 3), 3, 3, 3) == 15


def test_parts_score_is_the_reba_score_of_per_frame_parts():
    p = RebaParts(*(np.array([1, 2, 5]) for _ in range(6)))
    assert reba.parts_score(p, 1, 2, 1).tolist() == reba.reba_score(p, 1, 2, 1).tolist()
    assert reba.parts_score(p).shape == (3,)


def test_reba_scores_of_a_third_party_example():
    """NOT a published example: a third-party worked example (rs9000/ergonomics README, 'Pose
    Left' and 'Pose Right'); no worked example of Hignett & McAtamney 2000 or of the authors'
    handbook chapter could be reached (checked 2026-12-01). Neck 2, trunk 2, legs 2, upper arm
    1, lower arm 2, wrist 3 -> score A 4, B 3, C 4, REBA 4; with wrist 2 -> B 2, REBA 4."""
    assert reba.TABLE_A[2 - 1, 2 - 1, 2 - 1] == 4
    assert reba.TABLE_B[1 - 1, 2 - 1, 3 - 1] == 3
    assert reba.reba_score(RebaParts(2, 2, 2, 1, 2, 3)) == 4
    assert reba.TABLE_B[1 - 1, 2 - 1, 2 - 1] == 2
    assert reba.reba_score(RebaParts(2, 2, 2, 1, 2, 2)) == 4


def test_reba_tables_match_the_employee_worksheet():
    """REBA Tables A, B, C in the layout of the REBA Employee Assessment Worksheet (based on
    Hignett & McAtamney 2000; transcription on scribd, doc. 731952909): Table A rows trunk 1-5,
    columns neck 1-3 x legs 1-4; Table B rows upper arm 1-6, columns lower arm 1-2 x wrist 1-3;
    Table C rows score A 1-10 (row 11 as far as the transcription reads). A secondary source:
    it checks the transcription into this module, not the paper."""
    sheet_a = [
        [1, 2, 3, 4, 1, 2, 3, 4, 3, 3, 5, 6],
        [2, 3, 4, 5, 3, 4, 5, 6, 4, 5, 6, 7],
        [2, 4, 5, 6, 4, 5, 6, 7, 5, 6, 7, 8],
        [3, 5, 6, 7, 5, 6, 7, 8, 6, 7, 8, 9],
        [4, 6, 7, 8, 6, 7, 8, 9, 7, 8, 9, 9],
    ]
    sheet_b = [
        [1, 2, 2, 1, 2, 3],
        [1, 2, 3, 2, 3, 4],
        [3, 4, 5, 4, 5, 5],
        [4, 5, 5, 5, 6, 7],
        [6, 7, 8, 7, 8, 8],
        [7, 8, 8, 8, 9, 9],
    ]
    sheet_c = [
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
    ]
    assert reba.TABLE_A.reshape(5, 12).tolist() == sheet_a
    assert reba.TABLE_B.reshape(6, 6).tolist() == sheet_b
    assert reba.TABLE_C[:10].tolist() == sheet_c
    assert reba.TABLE_C[10, :8].tolist() == [11, 11, 11, 11, 12, 12, 12, 12]


def test_reba_risk_levels_and_load():
    assert list(reba.risk_level([1, 2, 3, 4, 7, 8, 10, 11, 15])) == [0, 1, 1, 2, 2, 3, 3, 4, 4]
    assert reba.load_score(4.9) == 0 and reba.load_score(5) == 1 and reba.load_score(11) == 2
    assert reba.load_score(11, shock=True) == 3


def test_one_score_gets_the_level_an_array_of_it_gets():
    """The one-score path (the report's per task and run) agrees with the per-frame one."""
    scores = np.array([0, 1, 1.5, 2, 3, 3.5, 4, 7, 7.5, 8, 10, 10.5, 11, 15, np.nan])
    levels = reba.risk_level(scores)
    for s, level in zip(scores, levels, strict=True):
        one = reba.risk_level(s)
        assert one.shape == () and one.dtype == levels.dtype and one == level
