"""Pace along a walk, planned beside captured (issue 38, deliverable 2).

Run: python3 benchmarks/bench_pace.py [--data ../shared/data] [--walks 30]

1. **Setting off and stopping**: every Bandai straight ``walk`` clip (all four styles, from
   standing to standing) and ``--walks`` planned 9 m walks on open floor from standing to
   standing (the default model, seeds 0..n-1): the distance from setting off to 90 % of the
   steady speed and from the last 90 % to standing, speed averaged over one step
   (:func:`mjwalk.gait.speedprofile.start_stop_distances`): median and IQR.
2. **Slowing in curves**: every Bandai ``walk-turn-left/right`` clip (one turn of about 90 deg)
   and ``--walks`` planned walks round a 90 deg corner, started walking: the speed in the
   curve over the speed on the straight (:func:`mjwalk.gait.speedprofile.curve_speed_ratio`).

The captured figures are the references the tests of the planner quote
(tests/plan/test_hybrid.py); nothing in the planner is fitted to them.

Measured (2026-12-01, after issue 38's guide and detour, 30 walks, 17 s):

==================================  ========================  ========================
figure                              capture (median, IQR)     planned (median, IQR)
==================================  ========================  ========================
speed-up distance [m]               0.62 (0.41-0.77), n 103   0.61 (0.56-0.71)
slow-down distance [m]              0.25 (0.20-0.47)          0.35 (0.32-0.40)
curve / straight speed              0.91 (0.86-0.94), n 250   0.88 (0.85-0.94), n 25
==================================  ========================  ========================
"""

from __future__ import annotations

import argparse
import glob
import os
import time
from pathlib import Path

import numpy as np

from mjwalk.conventions import SAMPLE_RATE_HZ
from mjwalk.gait.default import default_model
from mjwalk.gait.speedprofile import curve_speed_ratio, start_stop_distances
from mjwalk.mocap import load_bvh
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.world import load_workplace

ROOT = Path(__file__).resolve().parents[1]
#: A 90 deg corner (the scene of tests/plan/test_hybrid.py's curve test).
CORNER = (
    '<mujoco model="corner"><worldbody>'
    '<geom name="floor" type="plane" size="6 6 0.05"/>'
    '<geom name="a" type="box" size="3.5 2.25 1" pos="-2.5 3.75 1"/>'
    '<geom name="b" type="box" size="2.0 1.75 1" pos="4 -4.25 1"/>'
    "</worldbody></mujoco>"
)


def standing_to_standing(xy: np.ndarray, fps: float) -> np.ndarray:
    """A planned path with a second of standing before and after (as the clips have)."""
    n = round(fps)
    return np.vstack([np.repeat(xy[:1], n, axis=0), xy, np.repeat(xy[-1:], n, axis=0)])


def q(x) -> str:
    a, b, c = np.nanpercentile(x, [25, 50, 75])
    return f"{b:.2f} ({a:.2f}-{c:.2f}), n {np.sum(np.isfinite(x))}"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    default = Path(os.environ.get("MJWALK_SHARED_DATA", ROOT.parent / "shared" / "data"))
    ap.add_argument("--data", type=Path, default=default)
    ap.add_argument("--walks", type=int, default=30)
    args = ap.parse_args()
    if args.walks < 1:
        ap.error("--walks must be >= 1")
    t0 = time.perf_counter()
    model = default_model()
    wp = load_workplace(ROOT / "scenes" / "open_floor.xml")
    planner = HybridPlanner(wp, (4.5, 0.0), model)
    planned = [
        start_stop_distances(
            standing_to_standing(
                planner.plan((-4.5, 0.0), np.random.default_rng(k)).xy, SAMPLE_RATE_HZ
            ),
            SAMPLE_RATE_HZ,
        )
        for k in range(args.walks)
    ]
    planned_arr = np.array([p for p in planned if p is not None])
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        scene = Path(tmp) / "corner.xml"
        scene.write_text(CORNER)
        corner = HybridPlanner(load_workplace(scene), (2.5, 5.0), model)
        curves = [
            curve_speed_ratio(
                corner.plan((-5.0, 0.5, 0.0), np.random.default_rng(k)).xy, SAMPLE_RATE_HZ
            )
            for k in range(args.walks)
        ]
    bandai = args.data / "bandai-walk"
    cap, cap_curve = None, None
    if bandai.is_dir():
        rows = []
        for f in sorted(glob.glob(str(bandai / "dataset-2_walk_*.bvh"))):
            take = load_bvh(f)
            r = start_stop_distances(take.pelvis[:, :2], take.fps)
            if r is not None:
                rows.append(r)
        cap = np.array(rows)
        cap_curve = []
        for f in sorted(glob.glob(str(bandai / "dataset-2_walk-turn-*.bvh"))):
            take = load_bvh(f)
            cap_curve.append(curve_speed_ratio(take.pelvis[:, :2], take.fps))
    print(f"({time.perf_counter() - t0:.0f} s)")
    print(f"{'figure':34}{'capture (median, IQR)':>30}{'planned (median, IQR)':>30}")
    for k, name in ((0, "speed-up distance [m]"), (1, "slow-down distance [m]")):
        c = q(cap[:, k]) if cap is not None and len(cap) else "(no capture)"
        print(f"{name:34}{c:>30}{q(planned_arr[:, k]):>30}")
    c = q(cap_curve) if cap_curve is not None else "(no capture)"
    print(f"{'curve / straight speed':34}{c:>30}{q(curves):>30}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
