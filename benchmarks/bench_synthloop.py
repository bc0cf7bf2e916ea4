"""CPU cost of the legs (``legs_from_walk``) per station cycle with the walk's steps in one
compiled call (``synthesis.COMPILED_STEPS``, issue 50) against step by step, on the same
recorded walks, interleaved, and whether the two give the same bytes.

Run: PYTHONPATH=. python3 benchmarks/bench_synthloop.py [--runs 10] [--rounds 5]

``simulate_cycles`` runs ``--runs`` station cycles (seed 0, 1 job, after 2 warm-up cycles) with
``cycle.poses.legs_from_walk`` wrapped to record each walk and stature; the recorded walks are
then synthesised again ``--rounds`` times each way, alternating, and the CPU seconds
(``time.process_time``) of each way are divided by the runs. Prints the per-cycle ms of both
ways per round, their medians, the ratio, and the number of walks whose tracks differ in any
byte (joint angles, root, yaw, contacts, phases, ankles, pitches).
"""

from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Iterator
from contextlib import contextmanager

from mjwalk.body.legs import synthesis as syn
from mjwalk.cycle import poses
from mjwalk.cycle import simulate as sim

SPEC = "scenes/assembly_station.toml"


@contextmanager
def recording_legs() -> Iterator[list[tuple]]:
    """While open, ``cycle.poses.legs_from_walk`` appends each (walk, stature) it is asked for
    to the list yielded (the cycles' legs themselves are built as before)."""
    seen: list[tuple] = []
    legs0 = poses.legs_from_walk

    def legs(walk, stature=1.75, reference=None):
        seen.append((walk, stature))
        return legs0(walk, stature, reference)

    poses.legs_from_walk = legs
    try:
        yield seen
    finally:
        poses.legs_from_walk = legs0


def _record(runs: int) -> list[tuple]:
    """The (walk, stature) pairs the cycles' legs were built from."""
    with recording_legs() as seen:
        sim.simulate_cycles(SPEC, 2, seed=99, n_jobs=1)  # warm: models, compiled code
        seen.clear()
        sim.simulate_cycles(SPEC, runs, seed=0, n_jobs=1)
    return seen


def track_bytes(m) -> list[bytes]:
    """Every track of a LegMotion, as bytes, in a fixed order."""
    arrays = [m.root, m.yaw, m.contact, m.phase]
    for d in (m.angles, m.ankle, m.pitch):
        arrays += [d[k] for k in sorted(d)]
    return [a.tobytes() for a in arrays]


def synth_cpu(walks: list[tuple]) -> float:
    """CPU seconds of synthesising every walk (with the synthesis's switches as they are set)."""
    t0 = time.process_time()
    for walk, stature in walks:
        syn.legs_from_walk(walk, stature)
    return time.process_time() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=10)
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    walks = _record(args.runs)
    differ = 0
    for walk, stature in walks:
        syn.COMPILED_STEPS = True
        a = track_bytes(syn.legs_from_walk(walk, stature))
        syn.COMPILED_STEPS = False
        differ += a != track_bytes(syn.legs_from_walk(walk, stature))
    steps = sum(len(w.steps) for w, _ in walks)
    print(f"{len(walks)} walks, {steps} steps in {args.runs} cycles; walks differing: {differ}")
    step_ms, loop_ms = [], []
    for r in range(args.rounds):
        first = r % 2 == 0  # alternate which way goes first
        t = {c: 0.0 for c in (first, not first)}
        for c in t:
            syn.COMPILED_STEPS = c
            t[c] = synth_cpu(walks) / args.runs * 1e3
        step_ms.append(t[False])
        loop_ms.append(t[True])
        print(f"round {r}: step by step {t[False]:.2f} ms a cycle, one call {t[True]:.2f}")
    s, c = statistics.median(step_ms), statistics.median(loop_ms)
    print(f"median: step by step {s:.2f} ms a cycle, one call {c:.2f} ms (ratio {c / s:.3f})")
    syn.COMPILED_STEPS = True


if __name__ == "__main__":
    main()
