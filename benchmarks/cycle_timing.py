"""Time animated station cycles with whichever mjwalk is first on PYTHONPATH (a helper of
``bench_cycle.py --anim``, run in a subprocess once per code tree, so the baseline commit and
the working tree are timed alike).

Run: PYTHONPATH=<tree> python3 benchmarks/cycle_timing.py --cycles 5 --jobs 1 2 --out poses.npz

Prints one JSON line: per-cycle wall and CPU seconds of ``simulate_cycle`` (plan + legs + arms
+ collision check) on seeds 0..cycles-1 after one warm-up cycle (models loaded, compiled code
cached), the split of the first measured cycles by stage (legs, arm reach, collisions,
planning, ergonomics), and cycles per second of ``simulate_cycles`` for each ``--jobs``.
``--out`` saves the cycles' poses (qpos per frame) and contacts for comparison between trees.
"""

from __future__ import annotations

import argparse
import json
import os
import time
from collections import Counter
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def _timed(acc: Counter, label: str, mod, name: str) -> None:
    """Wrap ``mod.name`` so its wall time adds to ``acc[label]``."""
    f = getattr(mod, name)

    def g(*a, **k):
        t0 = time.perf_counter()
        try:
            return f(*a, **k)
        finally:
            acc[label] += time.perf_counter() - t0

    setattr(mod, name, g)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cycles", type=int, default=5)
    ap.add_argument("--jobs", type=int, nargs="*", default=[])
    ap.add_argument("--runs", type=int, default=20, help="cycles per simulate_cycles rate")
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args()
    import mjwalk
    import mjwalk.arms.reach as reach
    import mjwalk.body.legs as legs
    import mjwalk.cycle.simulate as sim
    from mjwalk.cycle.spec import load_cycle_spec
    from mjwalk.plan.hybrid import HybridPlanner

    # the station of the timed tree itself (a baseline tree may not read this tree's file)
    spec_path = Path(reach.__file__).resolve().parents[2] / "scenes" / "assembly_station.toml"
    ctx = sim.prepare(load_cycle_spec(spec_path))
    sim.simulate_cycle(ctx, 99)  # warm-up: models, compiled code
    wall, cpu, poses, contacts = [], [], {}, {}
    for k in range(args.cycles):
        t0, c0 = time.perf_counter(), time.process_time()
        r = sim.simulate_cycle(ctx, k, keep_timeline=True)
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
        poses[f"qpos{k}"] = r.timeline.qpos
        contacts[k] = [(c.time, c.body_part, c.scene_geom, c.depth) for c in r.collisions]
    acc: Counter = Counter()
    _timed(acc, "legs", legs, "legs_from_walk")
    _timed(acc, "reach", reach, "reach_for_side")
    _timed(
        acc,
        "arm angles",
        __import__("mjwalk.timeline.reachscene").timeline.reachscene,
        "arm_joint_angles",
    )  # fmt: skip  (moved from mjwalk.arms.kinematics)
    _timed(acc, "collisions", sim, "collision_report")
    _timed(acc, "ergonomics", sim, "cycle_ergonomics")  # RULA/REBA/OWAS/NIOSH/ISO 11226
    _timed(acc, "planning", HybridPlanner, "plan")
    n_split = min(3, args.cycles)
    t0 = time.perf_counter()
    for k in range(n_split):
        sim.simulate_cycle(ctx, k)
    total = time.perf_counter() - t0
    split = {k: v / total for k, v in acc.items()}
    rates = {}
    for jobs in args.jobs:
        sim.simulate_cycles(spec_path, 2 * jobs, seed=99, n_jobs=jobs)  # start the workers
        t0 = time.perf_counter()
        sim.simulate_cycles(spec_path, args.runs, seed=0, n_jobs=jobs)
        rates[jobs] = args.runs / (time.perf_counter() - t0)
    if args.out is not None:
        np.savez(args.out, **poses)
    print(
        json.dumps(
            {
                "mjwalk": str(Path(mjwalk.__file__).parent),
                "wall": wall,
                "cpu": cpu,
                "split": split,
                "rates": rates,
                "contacts": contacts,
                "load": os.getloadavg()[0],
            }
        )
    )


if __name__ == "__main__":
    main()
