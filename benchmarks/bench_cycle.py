"""Assembly-cycle speed: one cycle, many cycles in parallel, and video rendering.

Run: python3 benchmarks/bench_cycle.py [--runs 1000] [--jobs 2] [--video-seconds 10]

Targets (issue 7): one cycle (plan and animate, no video) in at most 2 s; 1000 cycles in at most
10 minutes on 2 cores; video frames per second reported.
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import numpy as np

from mjwalk.cycle.simulate import prepare, simulate_cycle, simulate_cycles
from mjwalk.cycle.spec import load_cycle_spec

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=1000)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--video-seconds", type=float, default=10.0)
    args = ap.parse_args()
    spec_path = ROOT / "scenes" / "assembly_station.toml"
    spec = load_cycle_spec(spec_path)
    t0 = time.perf_counter()
    ctx = prepare(spec)
    print(f"prepare (scene, models, humanoid): {time.perf_counter() - t0:.2f} s")

    for check in (False, True):
        times = []
        for k in range(5):
            t0 = time.perf_counter()
            r = simulate_cycle(ctx, k, collisions=check)
            times.append(time.perf_counter() - t0)
        label = "with collision check" if check else "plan + animate"
        print(
            f"one cycle ({label}): median {statistics.median(times):.2f} s "
            f"(cycle time {r.cycle_time:.1f} s, {r.timeline is None and 'no video'})"
        )

    t0 = time.perf_counter()
    results = simulate_cycles(spec_path, args.runs, seed=0, n_jobs=args.jobs, progress=True)
    wall = time.perf_counter() - t0
    ct = np.array([r.cycle_time for r in results])
    coll = sum(len(r.collisions) for r in results)
    print(
        f"{args.runs} cycles on {args.jobs} processes (with collision checks): {wall:.1f} s "
        f"({wall / 60:.2f} min; target <= 10 min), {args.runs / wall:.2f} cycles/s"
    )
    print(
        f"  cycle time median {np.median(ct):.1f} s, IQR "
        f"{np.subtract(*np.percentile(ct, [75, 25])):.1f} s; collisions {coll}"
    )

    from mjwalk.render import render_video

    r = simulate_cycle(ctx, 0, keep_timeline=True, collisions=False)
    tl = r.timeline
    n = min(tl.n_frames, int(args.video_seconds * tl.fps))
    tl.qpos, tl.t = tl.qpos[:n], tl.t[:n]
    with tempfile.TemporaryDirectory() as tmp:
        for size in ((640, 480), (320, 240)):
            t0 = time.perf_counter()
            render_video(tl, Path(tmp) / "clip.mp4", camera="track", size=size, progress=False)
            dt = time.perf_counter() - t0
            print(f"video {size[0]}x{size[1]}: {n} frames in {dt:.1f} s = {n / dt:.1f} frames/s")


if __name__ == "__main__":
    main()
