"""mjwalk.scan.register: the free-space clash that verifies an alignment, the choice among the
refined hypotheses, and the report line (the alignment itself, with Open3D, is exercised in
test_merge.py)."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import ScanError
from mjwalk.scan.register import AMBIGUITY, MAX_CLASH, Alignment, choose, clash


def _floor_with_post(post_x: float) -> np.ndarray:
    gx, gy = np.meshgrid(np.arange(0, 4, 0.03), np.arange(0, 4, 0.03))
    floor = np.column_stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)])
    far = np.hypot(floor[:, 0] - post_x, floor[:, 1] - 2.0) > 0.4
    px, pz = np.meshgrid(np.arange(post_x - 0.2, post_x + 0.2, 0.02), np.arange(0.1, 1.0, 0.02))
    post = np.column_stack([px.ravel(), np.full(px.size, 2.0), pz.ravel()])
    return np.vstack([floor[far], post])


def test_a_cloud_does_not_clash_with_itself_but_a_post_on_seen_floor_does():
    a = _floor_with_post(1.0)
    assert clash(a, a) == 0.0
    moved = _floor_with_post(3.0)  # its post stands where the other saw empty floor
    assert clash(moved, a) > 0.5


def test_alignment_line_names_the_figures():
    line = Alignment(np.eye(4), 0.8123, 0.0042, 0.011, 0.2, "b.ply").line()
    assert line.startswith("b.ply: registered, fitness 0.812")
    assert "RMSE 4.2 mm" in line and "clash 1.1 %" in line


def _pose(x: float, yaw_deg: float = 0.0) -> np.ndarray:
    m = np.eye(4)
    a = np.radians(yaw_deg)
    m[:2, :2] = [[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]]
    m[0, 3] = x
    return m


def test_a_survivor_of_the_free_space_check_is_refused_when_a_refuted_rival_matches_more():
    """The barely-overlapping stations' case in figures (register.py docstring, 4): the best
    match (0.74) is refuted by free space, its twin 1.8 m away passes (0.41, clash 6 %): the
    matched surfaces recur, the scan is refused by name and --poses suggested."""
    refuted = (0.74, 0.018, 0.22, _pose(0.0, 180.0))
    survivor = (0.41, 0.018, 0.063, _pose(1.8))
    with pytest.raises(ScanError) as err:
        choose([refuted, refuted, survivor], "st3.ply")
    msg = str(err.value)
    assert msg.startswith("st3.ply: could not be aligned") and "\n" not in msg
    assert "fitness 0.41" in msg and "fitness 0.74" in msg and "1.80 m" in msg
    assert "--poses" in msg


def test_a_distinctly_best_match_is_kept_whatever_its_refuted_rivals():
    """Right placements keep their fitness lead over refuted ones (stations 0 and 2: the best
    rival 0.60 of the best), the same placement found twice is no rival, and a passing rival
    nearly as good is the symmetric-hall refusal."""
    best = (0.433, 0.019, 0.005, _pose(0.0))
    again = (0.433, 0.019, 0.005, _pose(0.01))
    rival = (0.261, 0.020, 0.62, _pose(0.87, 14.0))
    chosen, runner_up = choose([best, again, rival], "st2.ply")
    assert chosen is best and runner_up == 0.261
    near = (AMBIGUITY * 0.433 + 0.001, 0.02, 2 * MAX_CLASH, _pose(2.0))
    with pytest.raises(ScanError, match="nearly as well"):
        choose([best, near], "st2.ply")
    twin = (0.43, 0.02, 0.0, _pose(3.0, 180.0))
    with pytest.raises(ScanError, match="unambiguously"):
        choose([best, twin], "st2.ply")
