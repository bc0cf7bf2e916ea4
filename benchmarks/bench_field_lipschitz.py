"""The walk field's Lipschitz constant on the shipped scenes (``docs/decisions/111``).

Run: PYTHONPATH=. python3 benchmarks/bench_field_lipschitz.py [--points 200000]

Per scene and level (:func:`mjwalk.cycle.levelsite.level_workplace`): the walk field's size,
its largest node difference over the spacing (1 for nodes that hold a distance),
:attr:`~mjwalk.world.clearance.ClearanceField.lipschitz` (the largest gradient norm of the
bilinear lookup, at a cell's corner) and where it is reached, the share of cells whose
gradient exceeds 1 somewhere, the largest central-difference gradient over ``--points``
random points (h = 1 um: it approaches the constant from below, random points rarely lie at a
corner) and the CPU time of computing the constant. The planner's leg and toe-approach probes
(:mod:`mjwalk.plan.stepgeom`) use the constant; they had taken it as 1.

Measured (main fed66aa + branch lipschitz): every shipped scene and level has the constant
sqrt(2) (1.414214), its nodes' differences at most one spacing; in the station 25 % of the
cells are steeper than 1 somewhere (the floor's corners, the edge distance min(x, y), and the
obstacles' corners); random points reach 1.36-1.41; 0.1-15 ms a field (CPU, the first one
loading the scene's cached arrays).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from mjwalk.cycle.levelsite import level_workplace
from mjwalk.world import load_workplace

SCENES = Path(__file__).resolve().parents[1] / "scenes"
NAMES = (
    "assembly_station",
    "assembly_station_2h",
    "corridor",
    "open_floor",
    "multilevel_station",
    "pit_station",
    "shelving_station",
)


def cell_slopes(values: np.ndarray, res: float) -> np.ndarray:
    """Per cell, the largest gradient norm of the bilinear lookup (at one of its corners)."""
    dx = np.abs(np.diff(values, axis=1))
    dy = np.abs(np.diff(values, axis=0))
    gx = np.maximum(dx[:-1, :], dx[1:, :])
    gy = np.maximum(dy[:, :-1], dy[:, 1:])
    return np.sqrt(gx * gx + gy * gy) / res


def sampled_slope(field, n: int, rng: np.random.Generator) -> float:
    """The largest central-difference gradient norm over ``n`` random points of the field."""
    ny, nx = field.values.shape
    p = np.stack(
        [
            field.x0 + rng.uniform(0, (nx - 1) * field.resolution, n),
            field.y0 + rng.uniform(0, (ny - 1) * field.resolution, n),
        ],
        axis=-1,
    )
    h = 1e-6
    gx = (field(p + [h, 0.0]) - field(p - [h, 0.0])) / (2 * h)
    gy = (field(p + [0.0, h]) - field(p - [0.0, h])) / (2 * h)
    return float(np.hypot(gx, gy).max())


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=200_000)
    args = ap.parse_args()
    rng = np.random.default_rng(0)
    print(
        f"{'scene':<20}{'level':>6}{'nodes':>12}{'node diff':>10}{'lipschitz':>11}"
        f"{'at (x, y) m':>18}{'cells > 1':>10}{'sampled':>9}{'ms':>6}"
    )
    for name in NAMES:
        wp = load_workplace(SCENES / f"{name}.xml")
        for level in range(len(wp.levels.levels)):
            f = level_workplace(wp, level).walk_field()
            v, res = f.values, f.resolution
            t0 = time.process_time()
            lip = f.lipschitz
            ms = 1000 * (time.process_time() - t0)
            slopes = cell_slopes(v, res)
            j, i = np.unravel_index(int(np.argmax(slopes)), slopes.shape)
            node = max(np.abs(np.diff(v, axis=1)).max(), np.abs(np.diff(v, axis=0)).max()) / res
            at = f"({f.x0 + i * res:.2f}, {f.y0 + j * res:.2f})"
            print(
                f"{name:<20}{level:>6}{v.shape[0]:>6}x{v.shape[1]:<5}{node:>10.6f}{lip:>11.6f}"
                f"{at:>18}{100 * np.mean(slopes > 1 + 1e-9):>9.1f}%"
                f"{sampled_slope(f, args.points, rng):>9.4f}{ms:>6.1f}"
            )


if __name__ == "__main__":
    main()
