"""mjwalk.ergonomics.iso11226: maximum holding times of static postures (ISO 11226:2000)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.ergonomics import iso11226


def test_iso11226_holding_times():
    assert iso11226.max_holding_time(10.0) == float("inf")
    assert iso11226.max_holding_time(20.0) == 240.0
    assert iso11226.max_holding_time(60.0) == 60.0
    assert iso11226.max_holding_time(70.0) == 0.0
    fps = 10.0
    ang = np.r_[np.zeros(10), np.full(30, 40.0), np.zeros(10)]  # 3 s at 40 deg: not static
    assert iso11226.holding(ang, fps, "trunk", iso11226.TRUNK_HOLD).held == 0.0
    ang = np.r_[np.zeros(10), np.full(1000, 40.0)]  # 100 s at 40 deg: limit 150 s
    h = iso11226.holding(ang, fps, "trunk", iso11226.TRUNK_HOLD)
    assert h.held == 100.0 and h.limit == pytest.approx(150.0) and h.acceptable
    ang = np.r_[np.zeros(10), np.full(100, 70.0)]  # 10 s beyond 60 deg: not acceptable
    assert not iso11226.holding(ang, fps, "trunk", iso11226.TRUNK_HOLD).acceptable
