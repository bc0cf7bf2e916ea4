"""What the continuous exposure method (:mod:`mjwalk.ergonomics.exposure`) adds to an animated
station cycle, measured in one process.

Simulates ``--cycles`` station cycles (scenes/assembly_station.toml, seeds 0..n-1, after one
warm-up), times each whole ``simulate_cycle`` (plan, legs, arms, collisions, all ergonomic
methods) and, on the same cycle's body angles, the exposure method's three hooks alone
(``per_frame``, ``per_task`` for every task, ``per_run``; the body angles are shared with the
other methods, so they are not counted) repeated ``--repeat`` times; prints the medians and the
share the method adds to a cycle without it.

Run: MUJOCO_GL=egl PYTHONPATH=. python3 benchmarks/bench_exposure_cost.py [--cycles 3]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from mjwalk.cycle import simulate as sim
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.ergonomics.angles import angles_from_timeline
from mjwalk.ergonomics.exposure import ExposureScore
from mjwalk.ergonomics.score import TaskSpan, score_context

ROOT = Path(__file__).resolve().parents[1]


def _exposure_seconds(result, repeat: int) -> float:
    """Median wall seconds of the exposure hooks on one cycle's timeline."""
    ang = angles_from_timeline(result.timeline)
    fps = result.timeline.fps
    spans = [
        TaskSpan(i, t.kind, round(t.start * fps), round(t.end * fps))
        for i, t in enumerate(result.tasks)
    ]
    ctx = score_context(ang, spans, result.cycle_time, fps)
    sc = ExposureScore()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f = sc.per_frame(ang, ctx)
        for sp in spans:
            if sp.end > sp.start:
                sc.per_task(f, sp, ctx)
        sc.per_run(f, ang, ctx)
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cycles", type=int, default=3)
    ap.add_argument("--repeat", type=int, default=5)
    a = ap.parse_args()
    ctx = sim.prepare(load_cycle_spec(ROOT / "scenes" / "assembly_station.toml"))
    sim.simulate_cycle(ctx, 99)  # warm-up
    cycle, expo = [], []
    for k in range(a.cycles):
        t0 = time.perf_counter()
        r = sim.simulate_cycle(ctx, k, keep_timeline=True)
        cycle.append(time.perf_counter() - t0)
        expo.append(_exposure_seconds(r, a.repeat))
    c, e = float(np.median(cycle)), float(np.median(expo))
    print(f"{a.cycles} station cycles: median cycle {c:.2f} s wall (exposure included)")
    print(f"exposure method alone: median {1000 * e:.1f} ms per cycle")
    print(f"added to a cycle without it: {100 * e / max(c - e, 1e-9):.2f} %")


if __name__ == "__main__":
    main()
