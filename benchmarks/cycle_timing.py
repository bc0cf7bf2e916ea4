"""Time animated station cycles with whichever mjwalk is first on PYTHONPATH (a helper of
``bench_cycle.py --anim``, run in a subprocess once per code tree, so the baseline commit and
the working tree are timed alike by this one script).

Run: PYTHONPATH=<tree> python3 benchmarks/cycle_timing.py --cycles 5 --jobs 1 2 --out poses.npz
     PYTHONPATH=. python3 benchmarks/cycle_timing.py --cycles 3 --table [--profile out.prof]

Prints one JSON line (``--table``: also a readable table on stderr): per-cycle wall and CPU
seconds of ``simulate_cycle`` (plan + legs + arms + collision check + ergonomics) on seeds
0..cycles-1 after one warm-up cycle (models loaded, compiled code cached); the split of the
split cycles' CPU time by stage (``split``, ``split_seconds`` CPU per cycle), and of an
in-process ``simulate_cycles`` batch (``batch_split``, ``batch_seconds``: its work around the
cycles, ``batch: outside the cycles``, counted too); cycles per second of ``simulate_cycles``
for each ``--jobs``.
``--out`` saves the cycles' poses (qpos per frame) and contacts for comparison between trees.

The split is exclusive: every function of :data:`STAGES` is wrapped wherever the loaded mjwalk
modules bind it (its own module and every module that imported it by name, classes' methods on
the class), and each moment of a cycle counts to the innermost wrapped call running then (the
arm angles inside the wrist fit inside a reach count as arm angles, the rest of the reach as
reach frames). What no stage claims counts to the cycle's own loop (``cycle loop``), so the
shares add up to 1. A name the timed tree lacks (an older tree, a renamed function) is skipped,
so the same script times trees of different layouts; ``missing`` lists them.
"""

from __future__ import annotations

import argparse
import functools
import importlib
import json
import os
import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np

#: (stage, "module:qualname" candidates), from the outside in; the innermost running call wins.
#: Candidates a tree lacks are skipped (older trees had other module names).
STAGES: list[tuple[str, list[str]]] = [
    # outermost: a batch's own work between and around its cycles (workers, seeds, results)
    ("batch: outside the cycles", ["mjwalk.cycle.simulate:simulate_cycles"]),
    ("batch: per-run context", ["mjwalk.cycle.context:context_of"]),
    ("cycle loop", ["mjwalk.cycle.simulate:simulate_cycle"]),
    (
        "operator and start",
        [
            "mjwalk.cycle.simulate:_start",
            "mjwalk.cycle.context:operator_context",
            "mjwalk.cycle.walking:cycle_start",
        ],
    ),
    ("standing pose", ["mjwalk.cycle.poses:standing_pose", "mjwalk.cycle.simulate:_standing"]),
    ("walk spot", ["mjwalk.cycle.walking:plan_task_walk"]),
    ("planning", ["mjwalk.plan.hybrid:HybridPlanner.plan"]),
    (
        "walk baselines",
        ["mjwalk.plan.grid:plan_grid", "mjwalk.cycle.context:CycleContext.baseline"],
    ),
    ("turns", ["mjwalk.cycle.poses:turn_frames", "mjwalk.cycle.simulate:_turn_frames"]),
    ("walk frames", ["mjwalk.cycle.poses:walk_frames", "mjwalk.cycle.simulate:_walk_frames"]),
    ("legs", ["mjwalk.body.legs.synthesis:legs_from_walk"]),
    ("reach spot", ["mjwalk.cycle.reachspot:reach_task", "mjwalk.cycle.simulate:_reach_task"]),
    ("arm clearance", ["mjwalk.cycle.standoff:ArmClearance.distance"]),
    ("reach frames", ["mjwalk.cycle.reaching:reach_frames"]),
    (
        "crouch and lean",
        [
            "mjwalk.cycle.crouch:crouch_frames",
            "mjwalk.cycle.crouch:crouch_pose",
            "mjwalk.cycle.reaching:leaning",
            "mjwalk.cycle.reaching:plumb_arms",
        ],
    ),
    ("arm reach", ["mjwalk.arms.reach:reach_for_side"]),
    ("wrist fit", ["mjwalk.cycle.reaching:_wrist_feasible"]),
    ("hand path", ["mjwalk.cycle.reaching:_hand_path"]),
    ("arm frames", ["mjwalk.arms.chain:arm_frames", "mjwalk.arms.kinematics:arm_frames"]),
    (
        "arm angles",
        ["mjwalk.arms.chain:arm_joint_angles", "mjwalk.arms.kinematics:arm_joint_angles"],
    ),
    (
        "timeline assembly",
        ["mjwalk.cycle.simulate:_timeline", "mjwalk.cycle.simulate:combined_walk"],
    ),
    ("result assembly", ["mjwalk.cycle.simulate:_finish"]),
    ("part tracks", ["mjwalk.timeline.parts:part_tracks"]),
    ("shared kinematics", ["mjwalk.timeline.geomposes:geom_table"]),
    ("collisions", ["mjwalk.timeline.collisions:collision_report"]),
    ("ergonomics", ["mjwalk.cycle.simulate:cycle_ergonomics"]),
    ("ergonomics: angles", ["mjwalk.ergonomics.angles:angles_from_timeline"]),
    ("ergonomics: scores", ["mjwalk.ergonomics.assess:assess_cycle"]),
]


class StageClock:
    """Exclusive CPU time (``time.process_time``) per stage: a stack of the running wrapped
    calls; the time between two events counts to the stage on top. CPU time, not wall time: on
    a loaded machine the wall clock also counts the time other processes held the core."""

    def __init__(self) -> None:
        self.acc: Counter = Counter()
        self.stack: list[str] = []
        self.last = 0.0
        self.on = True

    def _switch(self) -> float:
        now = time.process_time()
        if self.stack:
            self.acc[self.stack[-1]] += now - self.last
        self.last = now
        return now

    def wrap(self, label: str, f):
        clock = self

        @functools.wraps(f)
        def g(*a, **k):
            if not clock.on:
                return f(*a, **k)
            clock._switch()
            clock.stack.append(label)
            try:
                return f(*a, **k)
            finally:
                clock._switch()
                clock.stack.pop()

        g.__wrapped_stage__ = label  # type: ignore[attr-defined]
        return g


def _resolve(target: str):
    """(owner, attribute name, object) of ``"module:qualname"``, or None where it is absent."""
    mod_name, qual = target.split(":")
    try:
        owner = importlib.import_module(mod_name)
    except ImportError:
        return None
    *path, name = qual.split(".")
    for part in path:
        owner = getattr(owner, part, None)
        if owner is None:
            return None
    obj = getattr(owner, name, None)
    if obj is None or type(obj).__name__ in ("CPUDispatcher", "Dispatcher"):
        return None  # absent, or compiled (called from compiled code too: left alone)
    return owner, name, obj


def install(clock: StageClock) -> tuple[list[str], list[str]]:
    """Wrap every stage function wherever the loaded mjwalk modules bind it. Returns the
    targets wrapped and those the tree lacks."""
    found, missing = [], []
    for label, targets in STAGES:
        for target in targets:
            hit = _resolve(target)
            if hit is None:
                missing.append(target)
                continue
            owner, name, obj = hit
            g = clock.wrap(label, obj)
            found.append(target)
            if isinstance(owner, type):  # a method: on its class
                setattr(owner, name, g)
                continue
            for mod_name, mod in list(sys.modules.items()):
                if mod_name.startswith("mjwalk") and mod is not None:
                    for attr, val in list(vars(mod).items()):
                        if val is obj:
                            setattr(mod, attr, g)
    return found, missing


def _shares(acc: Counter) -> dict[str, float]:
    total = sum(acc.values())
    return {k: v / total for k, v in sorted(acc.items(), key=lambda kv: -kv[1])}


def _table(title: str, shares: dict[str, float], per: float) -> str:
    lines = [f"{title} ({per * 1e3:.1f} ms CPU per cycle):"]
    lines += [f"  {k:<24} {100 * v:5.1f} %  {v * per * 1e3:6.1f} ms" for k, v in shares.items()]
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cycles", type=int, default=5)
    ap.add_argument("--jobs", type=int, nargs="*", default=[])
    ap.add_argument("--runs", type=int, default=20, help="cycles per simulate_cycles rate")
    ap.add_argument("--split-cycles", type=int, default=3, help="cycles timed by stage")
    ap.add_argument("--out", type=Path, default=None)
    ap.add_argument("--table", action="store_true", help="also print the split as a table")
    ap.add_argument("--profile", type=Path, default=None, help="cProfile of the split cycles")
    args = ap.parse_args()
    import mjwalk
    import mjwalk.cycle.simulate as sim
    from mjwalk.cycle.spec import load_cycle_spec

    # the station of the timed tree itself (a baseline tree may not read this tree's file)
    spec_path = Path(mjwalk.__file__).resolve().parents[1] / "scenes" / "assembly_station.toml"
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
    # rates first (unwrapped code), then the splits
    rates = {}
    for jobs in args.jobs:
        sim.simulate_cycles(spec_path, 2 * jobs, seed=99, n_jobs=jobs)  # start the workers
        t0 = time.perf_counter()
        sim.simulate_cycles(spec_path, args.runs, seed=0, n_jobs=jobs)
        rates[jobs] = args.runs / (time.perf_counter() - t0)
    clock = StageClock()
    _found, missing = install(clock)
    n_split = max(1, args.split_cycles)
    prof = None
    if args.profile is not None:
        import cProfile  # deferred: only with --profile

        prof = cProfile.Profile()
        prof.enable()
    t0 = time.process_time()
    for k in range(n_split):
        sim.simulate_cycle(ctx, k, keep_timeline=True)  # as the timed cycles: part tracks too
    per_cycle = (time.process_time() - t0) / n_split
    if prof is not None:
        prof.disable()
        prof.dump_stats(args.profile)
    split = _shares(clock.acc)
    clock.acc.clear()
    t0 = time.process_time()
    sim.simulate_cycles(spec_path, n_split, seed=0, n_jobs=1)  # in this process: wrapped too
    per_batch = (time.process_time() - t0) / n_split
    batch_split = _shares(clock.acc)
    if args.out is not None:
        np.savez(args.out, **poses)
    if args.table:
        print(_table("animated cycle, by stage", split, per_cycle), file=sys.stderr)
        print(_table("simulate_cycles, 1 job, by stage", batch_split, per_batch), file=sys.stderr)
        if missing:
            print(f"not in this tree: {', '.join(missing)}", file=sys.stderr)
    print(
        json.dumps(
            {
                "mjwalk": str(Path(mjwalk.__file__).parent),
                "wall": wall,
                "cpu": cpu,
                "split": split,
                "batch_split": batch_split,
                "split_seconds": per_cycle,
                "batch_seconds": per_batch,
                "rates": rates,
                "contacts": contacts,
                "missing": missing,
                "load": os.getloadavg()[0],
            }
        )
    )


if __name__ == "__main__":
    main()
