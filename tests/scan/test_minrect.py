"""Tests of mjwalk.scan.minrect: the minimum-area rectangle of a region of cells."""

import math

import numpy as np
import pytest

from mjwalk.scan.minrect import common_axis, min_rectangle, principal_axis, rectangle_size


def test_min_rectangle_of_a_turned_region():
    res, ang = 0.02, math.radians(30)
    gx, gy = np.meshgrid((np.arange(200) + 0.5) * res, (np.arange(200) + 0.5) * res)
    u = (gx - 2) * math.cos(ang) + (gy - 2) * math.sin(ang)
    v = -(gx - 2) * math.sin(ang) + (gy - 2) * math.cos(ang)
    cells = (np.abs(u) <= 0.6) & (np.abs(v) <= 0.2)
    depth, width = rectangle_size(min_rectangle(cells, 0.0, 0.0, res))
    assert depth == pytest.approx(0.4, abs=2 * res) and width == pytest.approx(1.2, abs=2 * res)


def test_a_line_of_cells_gets_a_rectangle_half_a_cell_wide():
    cells = np.zeros((10, 40), bool)
    cells[5, 3:33] = True
    depth, width = rectangle_size(min_rectangle(cells, 0.0, 0.0, 0.02))
    assert depth == pytest.approx(0.01, abs=1e-9) and width == pytest.approx(0.58, abs=1e-9)


def test_common_axis_is_the_one_most_treads_share():
    """Three grid-aligned treads 1.52 m by 0.32 m and a fourth drawn 1.2 deg off (generated
    hall 1069's top tread, as its cells read): the fourth's own rectangle tips, the common axis
    of the four is the grid's."""
    res = 0.02
    gx, gy = np.meshgrid((np.arange(120) + 0.5) * res, (np.arange(100) + 0.5) * res)
    cells = [(np.abs(gx - 0.3 - 0.34 * k) <= 0.16) & (np.abs(gy - 1.0) <= 0.76) for k in range(3)]
    a = math.radians(1.2)
    u = (gx - 1.32) * math.cos(a) + (gy - 1.0) * math.sin(a)
    v = -(gx - 1.32) * math.sin(a) + (gy - 1.0) * math.cos(a)
    cells.append((np.abs(u) <= 0.16) & (np.abs(v) <= 0.76))
    r = min_rectangle(cells[3], 0.0, 0.0, res)
    own = (r[1] - r[0]) / np.hypot(*(r[1] - r[0]))
    ax = common_axis(cells, 0.0, 0.0, res)
    assert abs(ax[0] * ax[1]) < 1e-12  # along x or y
    assert abs(own[0] * own[1]) > math.sin(math.radians(0.5)) / 2, own  # tipped


def test_principal_axis_reads_a_long_region_from_all_its_cells():
    """A tread 1.04 m by 0.27 m turned 1.0 deg on a 2 cm grid: its cells' second moments give
    its long axis within 0.3 deg (pooled with a second tread alike), the moments' ratio about
    (1.04 / 0.27)**2; a square's ratio is about 1 (no axis)."""
    res = 0.02
    gx, gy = np.meshgrid((np.arange(150) + 0.5) * res, (np.arange(150) + 0.5) * res)
    a = math.radians(1.0)

    def turned(cx: float, half: tuple[float, float]) -> np.ndarray:
        u = (gx - cx) * math.cos(a) + (gy - 1.5) * math.sin(a)
        v = -(gx - cx) * math.sin(a) + (gy - 1.5) * math.cos(a)
        return (np.abs(u) <= half[0]) & (np.abs(v) <= half[1])

    treads = [turned(1.0, (0.135, 0.52)), turned(1.27, (0.135, 0.52))]
    axis, ratio, own = principal_axis(treads, 0.0, 0.0, res)
    across = np.array([-math.sin(a), math.cos(a)])
    assert abs(float(axis @ across)) >= math.cos(math.radians(0.3))
    assert len(own) == 2
    assert 0.8 * (1.04 / 0.27) ** 2 <= ratio <= 1.2 * (1.04 / 0.27) ** 2
    _, square, _ = principal_axis([turned(1.5, (0.595, 0.595))], 0.0, 0.0, res)
    assert square == pytest.approx(1.0, abs=0.1)
