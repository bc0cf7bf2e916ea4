"""CPU cost of scoring an animated station cycle (body angles and every ergonomic method), with
whichever mjwalk is first on PYTHONPATH, so two trees are compared by running it in each.

Simulates ``--cycles`` station cycles (scenes/assembly_station.toml, seeds 0..n-1, after one
warm-up) and measures the process CPU time (not wall time: the machine is shared) of each whole
``simulate_cycle`` and, on the same cycle's timeline, of ``angles_from_timeline`` and
``assess_cycle`` (median of ``--repeat``); prints the medians and scoring's share of a cycle.

First runs 2026-12-04, load average 8-9, four runs each (``--cycles 5``): 5553d3d 12.0-13.6 ms,
7.0-7.4 % of a cycle; i49-ergo 8.8-9.8 ms, 4.6-5.8 % (body angles 8.6-9.8 -> 5.7-6.4 ms; the
compiled forward kinematics, mjwalk/timeline/geomposes.py, is about 4 ms of them; methods
3.3-3.8 -> 3.1-3.3 ms).

Run: MUJOCO_GL=egl PYTHONPATH=<tree> python3 benchmarks/bench_scoring_cost.py [--cycles 5]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from mjwalk.cycle import simulate as sim
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.ergonomics.angles import angles_from_timeline
from mjwalk.ergonomics.assess import assess_cycle
from mjwalk.ergonomics.score import TaskSpan

ROOT = Path(__file__).resolve().parents[1]


def _scoring_cpu(result, repeat: int) -> tuple[float, float]:
    """Median CPU seconds of the body angles and of all methods on one cycle."""
    fps = result.timeline.fps
    spans = [
        TaskSpan(i, t.kind, round(t.start * fps), round(t.end * fps))
        for i, t in enumerate(result.tasks)
    ]
    ang_t, score_t = [], []
    for _ in range(repeat):
        t0 = time.process_time()
        ang = angles_from_timeline(result.timeline)
        t1 = time.process_time()
        assess_cycle(ang, spans, result.cycle_time, fps)
        ang_t.append(t1 - t0)
        score_t.append(time.process_time() - t1)
    return float(np.median(ang_t)), float(np.median(score_t))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cycles", type=int, default=5)
    ap.add_argument("--repeat", type=int, default=5)
    a = ap.parse_args()
    ctx = sim.prepare(load_cycle_spec(ROOT / "scenes" / "assembly_station.toml"))
    sim.simulate_cycle(ctx, 99)  # warm-up: models loaded, kernels compiled
    cycle, angles, scores = [], [], []
    for k in range(a.cycles):
        t0 = time.process_time()
        r = sim.simulate_cycle(ctx, k, keep_timeline=True)
        cycle.append(time.process_time() - t0)
        x, y = _scoring_cpu(r, a.repeat)
        angles.append(x)
        scores.append(y)
    c, x, y = (1000 * float(np.median(v)) for v in (cycle, angles, scores))
    print(f"{a.cycles} station cycles, median CPU: cycle {c:.0f} ms (scoring included)")
    print(f"body angles {x:.1f} ms, methods {y:.1f} ms, scoring {x + y:.1f} ms")
    print(f"scoring's share of a cycle: {100 * (x + y) / c:.1f} %")


if __name__ == "__main__":
    main()
