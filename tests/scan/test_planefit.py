"""mjwalk.scan.planefit: trimmed plane fits, and a level's flat part when a ramp's strip joins
its edge (issue 47)."""

from __future__ import annotations

import math

import mujoco
import numpy as np
import pytest

from mjwalk.scan import build_scene
from mjwalk.scan.obstacles import FloorPlan
from mjwalk.scan.planefit import fit_plane, flat_cells, flat_part
from mjwalk.scan.raycast import synthetic_scan
from mjwalk.world.norms import HORIZONTAL_SLOPE

RES = 0.02


def _plan(nx: int = 100, ny: int = 80) -> FloorPlan:
    z = np.zeros((ny, nx), bool)
    return FloorPlan(-0.5, 0.0, RES, ~z, np.zeros((ny, nx), np.int64), np.zeros(1), z,
                     (-0.5, 0.0, -0.5 + nx * RES, ny * RES), 0)  # fmt: skip


def _deck_and_strip(seed: int = 0) -> np.ndarray:
    """A deck's part 0.17 m high (x 0..1.2, y 0..1.5, 3300 points a square metre) and, before
    its edge, the 0.23 m of an 8.7 deg ramp's top that lie within 3 cm of a candidate height
    6 mm under the deck, scanned denser (8700 a square metre: nearer a scanner), as in hall 17
    of bench_unseen; 5 mm range noise."""
    rng = np.random.default_rng(seed)
    deck = np.column_stack([rng.uniform(0, 1.2, 6000), rng.uniform(0, 1.5, 6000)])
    strip = np.column_stack([rng.uniform(-0.23, 0, 3000), rng.uniform(0, 1.5, 3000)])
    z = np.concatenate([np.full(len(deck), 0.17), 0.17 + math.tan(math.radians(8.7)) * strip[:, 0]])
    xy = np.vstack([deck, strip])
    return np.column_stack([xy, z + rng.normal(0, 0.005, len(z))])


def _cells(p: np.ndarray, plan: FloorPlan) -> np.ndarray:
    cells = np.zeros(plan.floor.shape, bool)
    cells[((p[:, 1] - plan.y0) / RES).astype(int), ((p[:, 0] - plan.x0) / RES).astype(int)] = True
    return cells


def test_fit_plane_of_a_level_with_a_ramps_strip_is_tilted_its_flat_part_is_not():
    p, plan = _deck_and_strip(), _plan()
    h, _, slope, err = fit_plane(p)
    assert slope > HORIZONTAL_SLOPE + 3 * err  # the strip tilts the whole region's plane
    got = flat_part(p, _cells(p, plan), plan)
    assert got is not None
    cells, (h, _, slope, err), q = got
    assert slope <= HORIZONTAL_SLOPE + 3 * err
    assert h == pytest.approx(0.17, abs=0.003)
    xs = plan.x0 + (np.nonzero(cells)[1] + 0.5) * RES
    # the ramp's top within 3 noise of the deck (1.5 cm of climb, 10 cm) and a noisy cell more
    assert xs.min() >= -0.17
    assert cells.sum() * RES**2 == pytest.approx(1.2 * 1.5, rel=0.1)
    assert len(q) >= 0.95 * 6000


def test_flat_cells_of_a_flat_surface_are_all_its_cells():
    rng = np.random.default_rng(1)
    p = np.column_stack([rng.uniform(0, 1, 5000), rng.uniform(0, 1, 5000),
                         0.3 + rng.normal(0, 0.005, 5000)])  # fmt: skip
    plan = _plan()
    assert (flat_cells(p, plan) == _cells(p, plan)).mean() > 0.99
    assert flat_part(p[:2], _cells(p, plan), plan) is None


def _ramp(x_top: float, h: float, deg: float, width: float) -> tuple[str, float]:
    """A 0.1 m slab whose top rises towards -x from the floor to ``h`` at ``x_top``; its run."""
    th = math.radians(deg)
    run = h / math.tan(th)
    x, z = x_top + 0.5 * run - 0.05 * math.sin(th), 0.5 * h - 0.05 * math.cos(th)
    half = 0.5 * run / math.cos(th)
    geom = (f'<geom name="ramp" type="box" pos="{x:.6f} 0 {z:.6f}" '
            f'size="{half:.6f} {width / 2} 0.05" euler="0 {deg} 0"/>')  # fmt: skip
    return geom, run


def test_a_low_deck_reached_by_a_steep_ramp_keeps_its_level_and_its_ramp():
    """A 0.17 m deck (x -2.4..-0.5) reached by an 8.7 deg ramp (hall 17 of bench_unseen): the
    ramp's top joins the deck's region at the candidate height and tilted its plane, so the
    deck's scanned part by the ramp was no level and the ramp met none. Seeded synthetic scan
    (0.4 deg rays, 5 mm noise), scanners at the ramp's foot, over the deck and aside."""
    ramp, run = _ramp(-0.5, 0.17, 8.7, 1.375)
    xml = f"""<mujoco><worldbody>
  <geom name="floor" type="plane" size="6 4 0.05"/>
  <geom name="deck" type="box" pos="-1.45 0 0.085" size="0.95 0.745 0.085"/>
  {ramp}
</worldbody></mujoco>"""
    scanners = [(-0.5 + run + 1.0, 0.0, 1.6), (-1.45, 0.0, 0.17 + 1.6), (2.5, 2.5, 1.6)]
    scan = synthetic_scan(
        mujoco.MjModel.from_xml_string(xml), scanners, step_deg=0.4, noise=0.005, seed=3
    )
    lp = build_scene(scan.points, source="low deck").levels
    assert lp is not None
    assert all(abs(h - 0.17) <= 0.01 for h in lp.heights[1:])
    ramps = [k for k in lp.links if k.kind == "ramp"]
    assert len(ramps) == 1 and ramps[0].lower == 0
    assert lp.heights[ramps[0].upper] == pytest.approx(0.17, abs=0.01)
    assert math.degrees(ramps[0].slope) == pytest.approx(8.7, abs=0.5)
