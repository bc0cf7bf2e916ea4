"""mjwalk.scan.regionsteps: regions a step apart whose edges touch, an unseen strip beyond the
lower one's edge counted as its own up to a depth set by its kind (issue 47, scan47h)."""

from __future__ import annotations

import numpy as np

from mjwalk.scan.planefit import RISER_TOL
from mjwalk.scan.regionsteps import region_steps, touching, with_shadow
from mjwalk.scan.scanlevels import Layers, ScanLevel
from mjwalk.world.norms import MAX_RISER

RES = 0.02
NY, NX = 60, 80


def _level(kind: str, height: float, cols: tuple[int, int], peak: int) -> ScanLevel:
    cells = np.zeros((NY, NX), bool)
    cells[5:55, cols[0] : cols[1]] = True
    depth = (cols[1] - cols[0]) * RES
    return ScanLevel(
        0, kind, height, 0.0, 0.0, cells, float(cells.sum()) * RES**2, depth, 1.0, peak
    )


def _regions(gap: int, seen_in_gap: bool = False):
    """A landing (0.60 m, columns 0-29), an unseen strip ``gap`` cells wide, a tread 0.15 m
    higher (0.26 m deep) beyond it; the floor elsewhere (no step from it)."""
    floor = np.zeros((NY, NX), bool)
    floor[56:, :] = True
    landing = _level("platform", 0.60, (0, 30), 1)
    tread = _level("tread", 0.75, (30 + gap, 30 + gap + 13), 2)
    near = np.zeros((3, NY, NX), np.int32)
    near[1][landing.cells] = 3
    near[2][tread.cells] = 3
    band = np.zeros((3, NY, NX), np.int32)
    band[1][tread.cells] = 5  # the tread's points lie in the landing's band
    if seen_in_gap:
        band[1][:, 30 : 30 + gap] = 5  # something seen standing in the strip
    layers = Layers(np.array([0.0, 0.60, 0.75]), near, band, np.zeros((3, NY, NX), np.float32))
    f = ScanLevel(0, "floor", 0.0, 0.0, 0.0, floor, float(floor.sum()) * RES**2, 0.0, 0.0, -1)
    return [f, landing, tread], layers


def test_a_landing_reaches_a_flight_over_its_unseen_strip():
    found, layers = _regions(gap=6)  # 0.12 m unseen before the first riser
    assert not touching(found[1].cells, found[2].cells, RES)
    assert (1, 2) in region_steps(found, layers, RES)


def test_no_step_over_a_strip_deeper_than_a_tread_or_with_something_in_it():
    found, layers = _regions(gap=16)  # 0.32 m: deeper than the least tread and the gap
    assert (1, 2) not in region_steps(found, layers, RES)
    found, layers = _regions(gap=6, seen_in_gap=True)
    assert (1, 2) not in region_steps(found, layers, RES)


def test_a_strip_seen_in_sparse_rows_at_its_height_is_its_own():
    """A tread's back seen at a grazing angle: a row of points at its height, not joined to its
    region, nothing standing there; the strip is still its own up to the next riser."""
    found, layers = _regions(gap=6)
    layers.near[1][:, 33] = 2  # a scan line across the strip, two cells short of the riser
    assert (1, 2) in region_steps(found, layers, RES)


def test_the_floor_keeps_its_cells():
    found, layers = _regions(gap=6)
    assert (with_shadow(found[0], layers, RES) == found[0].cells).all()


def test_a_riser_measured_over_the_limit_within_the_scans_tolerance_is_a_step():
    """A riser measured at 0.1901 m (a true 0.19 m, DIN 18065's largest) is a step; one over
    the limit by more than ``planefit.RISER_TOL`` (0.2 m, 0.25 m) is none."""
    for rise, ok in (
        (0.1901, True),
        (MAX_RISER + RISER_TOL - 1e-4, True),
        (0.20, False),
        (0.25, False),
    ):
        found, layers = _regions(gap=0)
        tread = found[2]
        found[2] = ScanLevel(
            0, "tread", 0.60 + rise, 0.0, 0.0, tread.cells, tread.area, tread.depth, 1.0, 2
        )
        assert ((1, 2) in region_steps(found, layers, RES)) is ok, rise
