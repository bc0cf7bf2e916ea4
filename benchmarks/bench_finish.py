"""CPU time of a station cycle's finishing stages (issue 50): the shared geom table, the contact
check, the ergonomics' angles and their scores, replayed on recorded cycles.

Run (once per tree, alternating trees for a comparison in one sitting):
    PYTHONPATH=<tree> python3 benchmarks/bench_finish.py [--cycles 10] [--rounds 3]

Simulates ``--cycles`` station cycles (seeds 0..cycles-1 of batch seed 0, after one warm-up
cycle), keeping what ``simulate._finish`` is given, then times those four stages on them
``--rounds`` times (``time.process_time``: CPU seconds, less sensitive to other processes than
wall time) and prints ms a cycle per stage, with a digest of the contacts and ergonomics of the
first round (equal digests: equal outputs).

Measured 2026-12-05 (kin50f, load 13-17 on 2 cores, three alternating pairs, 10 cycles x 3
rounds): 879469c total 17.70 / 17.13 / 16.92 ms (geom table 3.46-3.63, collisions 3.98-4.08,
angles 4.85-5.20, scores 4.62-4.80); kin50f 16.00 / 15.44 / 15.26 (3.45-3.54, 3.05-3.11,
4.61-4.95, 4.06-4.41); digests equal.
"""

from __future__ import annotations

import argparse
import hashlib
import pickle
import time
from pathlib import Path

import numpy as np

from mjwalk.body.humanoid import HUMAN_GROUP
from mjwalk.cycle import simulate as sim
from mjwalk.cycle.context import context_of
from mjwalk.cycle.seeding import run_generator

SPEC = Path(__file__).resolve().parents[1] / "scenes" / "assembly_station.toml"


def record(cycles: int) -> list[tuple]:
    """The inputs of ``_finish`` of ``cycles`` station cycles: (context, timeline, starts,
    cycle time, spec)."""
    kept: list[tuple] = []
    finish = sim._finish

    def keep(ctx, timeline, starts, result, **kw):
        kept.append((ctx, timeline, list(starts), result.cycle_time, result.spec))
        return finish(ctx, timeline, starts, result, **kw)

    ctx = context_of(SPEC)
    sim.simulate_cycle(ctx, run_generator(0, 999))  # warm: models loaded, kernels compiled
    sim._finish = keep
    try:
        for k in range(cycles):
            sim.simulate_cycle(ctx, run_generator(0, k), run=k)
    finally:
        sim._finish = finish
    return kept


def stages(item: tuple) -> tuple[np.ndarray, list, object]:
    """CPU seconds of the four stages of one recorded cycle, its contacts and ergonomics."""
    ctx, tl, starts, cycle_time, spec = item
    ends = [*starts[1:], len(tl.qpos)]
    spent = [0.0]
    angles = sim.angles_from_timeline

    def timed_angles(*a, **k):
        c = time.process_time()
        out = angles(*a, **k)
        spent[0] += time.process_time() - c
        return out

    c0 = time.process_time()
    table = sim.geom_table(tl.model, tl.qpos, np.flatnonzero(tl.model.geom_group == HUMAN_GROUP))
    c1 = time.process_time()
    contacts = sim.collision_report(tl, data=ctx.scratch(), table=table)
    c2 = time.process_time()
    sim.angles_from_timeline = timed_angles
    try:
        erg = sim.cycle_ergonomics(tl, spec, starts, ends, cycle_time, ctx.workplace, table)
    finally:
        sim.angles_from_timeline = angles
    c3 = time.process_time()
    return np.array([c1 - c0, c2 - c1, spent[0], c3 - c2 - spent[0]]), contacts, erg


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cycles", type=int, default=10)
    ap.add_argument("--rounds", type=int, default=3)
    args = ap.parse_args()
    kept = record(args.cycles)
    total = np.zeros(4)
    digest = hashlib.sha1()
    for rnd in range(args.rounds):
        for item in kept:
            spent, contacts, erg = stages(item)
            total += spent
            if rnd == 0:
                rows = [
                    (c.time, c.body_part, c.scene_geom, c.depth, c.pos.tobytes()) for c in contacts
                ]
                digest.update(pickle.dumps(rows))
                digest.update(pickle.dumps(erg))
    ms = 1e3 * total / (args.rounds * len(kept))
    names = ("geom table", "collisions", "angles", "scores")
    print(
        ", ".join(f"{n} {v:.2f}" for n, v in zip(names, ms, strict=True))
        + f", total {ms.sum():.2f} ms a cycle (CPU); digest {digest.hexdigest()[:16]}"
    )


if __name__ == "__main__":
    main()
