"""Tests of mjwalk.scan.minrect: the minimum-area rectangle of a region of cells."""

import math

import numpy as np
import pytest

from mjwalk.scan.minrect import min_rectangle, rectangle_size


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
