"""CPU time of a station cycle's reach tasks alone, replayed, and their results for a
byte-for-byte comparison between trees (issue 50: the arms' share of the animated cycle).

Run: PYTHONPATH=<tree> python3 benchmarks/bench_reach_replay.py [--cycles 10] [--reps 7]
     [--out reaches.npz] [--compare other.npz]

Runs ``--cycles`` station cycles (seeds 0..) after one warm-up cycle, recording the arguments
of every :func:`mjwalk.cycle.reachspot.reach_task` call (14 a cycle), then calls them again
``--reps`` times and prints one JSON line: the CPU ms a cycle of each repetition
(``time.process_time``), their median and least, and the calls a cycle. The reach tasks (turn
toward the target, stand-off search with its arm clearance, the reach's frames) are about a
fifth of a cycle; replaying only them resolves changes of a few per cent of that, which the
whole cycle's spread (about 8 %) hides. ``--out`` saves every replayed reach's turn, frames and
numbers (spot, step, turn time, hand error, clearance, grip width); ``--compare`` reports which
of them differ from another tree's file (none: the reaches are bit-identical). Alternate the
trees in fresh processes to compare their times on a shared machine.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np


def _record(cycles: int):
    """The station's context and the (args, kwargs) of its reach tasks in ``cycles`` cycles."""
    import mjwalk
    import mjwalk.cycle.actions.reach_for as reach_for
    import mjwalk.cycle.simulate as sim
    from mjwalk.cycle.spec import load_cycle_spec

    spec_path = Path(mjwalk.__file__).resolve().parents[1] / "scenes" / "assembly_station.toml"
    ctx = sim.prepare(load_cycle_spec(spec_path))
    sim.simulate_cycle(ctx, 99)  # warm-up: models, compiled code
    calls: list = []
    task = reach_for.reach_task

    def spy(*a, **k):
        calls.append((a, k))
        return task(*a, **k)

    reach_for.reach_task = spy  # type: ignore[assignment]
    try:
        for seed in range(cycles):
            sim.simulate_cycle(ctx, seed)
    finally:
        reach_for.reach_task = task  # type: ignore[assignment]
    return task, calls


def _arrays(results) -> dict[str, np.ndarray]:
    """Each reach's turn, frames and numbers, by its index."""
    out = {}
    for i, r in enumerate(results):
        out[f"turn{i}"] = r.turn
        out[f"frames{i}"] = r.frames
        width = -1.0 if r.width is None else r.width
        numbers = [r.x, r.y, r.yaw, r.step_back, r.turn_time, r.error, r.distance, width]
        out[f"numbers{i}"] = np.array(numbers, dtype=float)
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cycles", type=int, default=10)
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--out", type=Path, default=None)
    ap.add_argument("--compare", type=Path, default=None)
    args = ap.parse_args()
    task, calls = _record(args.cycles)
    arrays = _arrays([task(*a, **k) for a, k in calls])
    if args.out is not None:
        np.savez(args.out, **arrays)
    differ = None
    if args.compare is not None:
        other = np.load(args.compare)
        names = sorted(set(other.files) | set(arrays))
        differ = [
            n
            for n in names
            if n not in other.files
            or n not in arrays
            or other[n].shape != arrays[n].shape
            or not np.array_equal(other[n], arrays[n])
        ]
    ms = []
    for _ in range(args.reps):
        c0 = time.process_time()
        for a, k in calls:
            task(*a, **k)
        ms.append(1e3 * (time.process_time() - c0) / args.cycles)
    report = {
        "calls_per_cycle": len(calls) / args.cycles,
        "cpu_ms_per_cycle": ms,
        "median": float(np.median(ms)),
        "least": float(np.min(ms)),
        "differ": differ,
    }
    print(json.dumps(report))


if __name__ == "__main__":
    main()
