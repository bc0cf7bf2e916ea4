"""Clearance-field build time and grid-A* plan time on the station scene.

Run: python3 benchmarks/bench_world.py
"""

from __future__ import annotations

import statistics
import time
from pathlib import Path

from mjwalk.plan.grid import plan_grid
from mjwalk.plan.occupancy import occupancy_grid
from mjwalk.world import load_model, workplace_from_model

ROOT = Path(__file__).resolve().parents[1]
ROUTES = [
    ("stand_rack2", "stand_car1"),
    ("stand_car1", "stand_rack3"),
    ("stand_car2", "stand_rack1"),
    ("stand_car3", "stand_rack2"),
    ("stand_rack2", "stand_rack3"),
]


def main() -> None:
    path = ROOT / "scenes" / "assembly_station.xml"
    model = load_model(path)
    times = []
    for _ in range(5):
        t0 = time.perf_counter()
        wp = workplace_from_model(model, source=path)
        times.append(time.perf_counter() - t0)
    ny, nx = wp.clearance.shape
    print(
        f"clearance field: {nx} x {ny} nodes at {wp.clearance.resolution} m, "
        f"{len(wp.obstacles)} obstacle geoms"
    )
    print(f"  build (incl. footprints): median {1000 * statistics.median(times):.1f} ms")
    t0 = time.perf_counter()
    grid = occupancy_grid(wp)
    print(f"occupancy grid (0.08 m cells, 8 moves): {1000 * (time.perf_counter() - t0):.1f} ms")
    for a, b in ROUTES:
        runs = []
        for _ in range(5):
            route = plan_grid(wp, a, b, grid=grid)
            runs.append(route.meta["seconds"])
        print(
            f"grid A* {a:>12} -> {b:<12} length {route.length:5.2f} m  "
            f"{route.meta['expansions']:4d} expansions  "
            f"median {1000 * statistics.median(runs):6.2f} ms"
        )
    t0 = time.perf_counter()
    route = plan_grid(wp, "-3.5,-2.5", "3.5,2.7")
    print(
        f"grid A* corner to corner (incl. grid build): length {route.length:.2f} m, "
        f"{1000 * (time.perf_counter() - t0):.1f} ms"
    )


if __name__ == "__main__":
    main()
