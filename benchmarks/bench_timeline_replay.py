"""CPU cost of a station cycle's timeline stages after the plan -- the part tracks, the shared
kinematics, the contact checks, the arms' clearance broad phase and the ergonomics -- a
baseline commit against this tree, in alternating fresh processes, and whether both give the
same bytes (issue 50).

Run: python3 benchmarks/bench_timeline_replay.py --baseline fc03651 [--cycles 10] [--rounds 4]
     PYTHONPATH=. python3 benchmarks/bench_timeline_replay.py --baseline fc03651 --same-process

``--same-process``: one process records the cycles with this tree, loads the baseline's own
``mjwalk/timeline/parts.py`` and ``collisions.py`` beside this tree's (under other module
names: valid while the modules they import are the same in both trees) and replays the calls
of ``part_tracks``, ``collision_report`` and ``candidate_frames`` with both, interleaved,
``--rounds`` rounds of five passes (CPU clock); prints the medians, the ratio and whether
every result has the same bytes.

Each round runs one fresh subprocess per tree (the baseline exported as ``bench_cycle.py``
exports it). The subprocess simulates ``--cycles`` animated station cycles (``simulate_cycle``
with ``keep_timeline=True`` on seeds 0.., after one warm-up cycle) and records every call of
the timed functions where the cycle code binds them (``part_tracks``, ``geom_table``,
``collision_report`` and ``cycle_ergonomics`` in ``mjwalk.cycle.simulate``,
``collision_report`` in ``mjwalk.cycle.poses``, ``candidate_frames`` in
``mjwalk.cycle.standoff``); then it replays each recorded call once for the digest (the
SHA-256 of every result's bytes) and five times more on the CPU clock
(``time.process_time``). Prints per stage and tree the median CPU ms per cycle of each round,
the median over the rounds, the ratio, and whether the digests are equal.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import pickle
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

#: stage -> (module, name) of the recorded function, where the cycle code calls it.
TIMED = {
    "part tracks": [("mjwalk.cycle.simulate", "part_tracks")],
    "shared kinematics": [("mjwalk.cycle.simulate", "geom_table")],
    "collisions": [
        ("mjwalk.cycle.simulate", "collision_report"),
        ("mjwalk.cycle.poses", "collision_report"),
    ],
    "clearance broad phase": [("mjwalk.cycle.standoff", "candidate_frames")],
    "ergonomics": [("mjwalk.cycle.simulate", "cycle_ergonomics")],
}


def _digest(h, out) -> None:
    """Feed the bytes of a timed function's result into ``h``."""
    if isinstance(out, np.ndarray):
        h.update(out.tobytes())
    elif isinstance(out, list):
        for o in out:
            if hasattr(o, "pos") and hasattr(o, "mat"):  # a PartTrack
                h.update(repr((o.geom, o.grasp, o.release)).encode())
                h.update(o.pos.tobytes() + o.mat.tobytes())
            else:  # a Contact
                h.update(repr((o.time, o.body_part, o.scene_geom, o.depth)).encode())
                h.update(o.pos.tobytes())
    elif hasattr(out, "xpos"):  # a GeomTable
        h.update(out.geoms.tobytes() + out.xpos.tobytes() + out.xmat.tobytes())
    else:  # the ergonomics
        h.update(pickle.dumps(out))


def _recorded_calls(sim, ctx, cycles: int, bound: dict[str, list]) -> dict[str, list]:
    """Station cycles 0..cycles-1 of ``ctx`` with each stage's functions wrapped where the
    cycle code calls them (``bound``: stage -> [(module, name)]): per stage, the calls made,
    as (function, args, kwargs). The wrappers are removed afterwards."""
    import importlib

    calls: dict[str, list] = {k: [] for k in bound}
    originals = []
    for stage, where in bound.items():
        for mod_name, name in where:
            mod = importlib.import_module(mod_name)
            f = getattr(mod, name)
            originals.append((mod, name, f))

            def rec(*a, _f=f, _stage=stage, **k):
                calls[_stage].append((_f, a, k))
                return _f(*a, **k)

            setattr(mod, name, rec)
    try:
        for k in range(cycles):
            sim.simulate_cycle(ctx, k, keep_timeline=True)
    finally:
        for mod, name, f in originals:
            setattr(mod, name, f)
    return calls


def _child(cycles: int) -> None:
    """In the timed tree: record, replay once for the digest, time five passes; a JSON line."""

    import mjwalk.cycle.simulate as sim
    from mjwalk.cycle.spec import load_cycle_spec

    ctx = sim.prepare(load_cycle_spec(ROOT / "scenes" / "assembly_station.toml"))
    sim.simulate_cycle(ctx, 99, keep_timeline=True)  # warm-up: models, compiled code
    calls = _recorded_calls(sim, ctx, cycles, TIMED)
    h = hashlib.sha256()
    res = {}
    for stage, seen in calls.items():
        for f, a, k in seen:
            _digest(h, f(*a, **k))
        passes = []
        for _ in range(5):
            t0 = time.process_time()
            for f, a, k in seen:
                f(*a, **k)
            passes.append(1e3 * (time.process_time() - t0) / cycles)
        res[stage] = statistics.median(passes)
    res["calls"] = {s: len(c) for s, c in calls.items()}
    print(json.dumps({"digest": h.hexdigest(), "ms": res}))


def _same_process(baseline: Path, cycles: int, rounds: int) -> None:
    """The in-process A/B of ``--same-process`` (see the module docstring)."""
    import importlib
    import importlib.util

    import mjwalk.cycle.simulate as sim
    from mjwalk.cycle.spec import load_cycle_spec

    old = {}
    for name in ("parts", "collisions"):
        path = baseline / "mjwalk" / "timeline" / f"{name}.py"
        spec = importlib.util.spec_from_file_location(f"baseline_{name}", path)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = mod  # (its dataclasses look their module up)
        spec.loader.exec_module(mod)
        old[name] = mod
    ctx = sim.prepare(load_cycle_spec(ROOT / "scenes" / "assembly_station.toml"))
    sim.simulate_cycle(ctx, 99, keep_timeline=True)
    where = {
        "part tracks": ("parts", "part_tracks", [("mjwalk.cycle.simulate", "part_tracks")]),
        "collisions": (
            "collisions",
            "collision_report",
            [
                ("mjwalk.cycle.simulate", "collision_report"),
                ("mjwalk.cycle.poses", "collision_report"),
            ],
        ),
        "clearance broad phase": (
            "collisions",
            "candidate_frames",
            [("mjwalk.cycle.standoff", "candidate_frames")],
        ),
    }
    calls = _recorded_calls(sim, ctx, cycles, {st: w[2] for st, w in where.items()})
    load = os.getloadavg()[0]
    print(f"same process, {cycles} station cycles, CPU ms a cycle (median of {rounds} rounds "
          f"of 5 passes), baseline {baseline.name} vs this tree; load {load:.1f}")  # fmt: skip
    for stage, (mod_name, name, _) in where.items():
        new_f = getattr(importlib.import_module(f"mjwalk.timeline.{mod_name}"), name)
        fs = {"old": getattr(old[mod_name], name), "new": new_f}
        same = True
        for _, a, k in calls[stage]:
            ho, hn = hashlib.sha256(), hashlib.sha256()
            _digest(ho, fs["old"](*a, **k))
            _digest(hn, fs["new"](*a, **k))
            same &= ho.digest() == hn.digest()
        ms: dict[str, list[float]] = {"old": [], "new": []}
        for r in range(rounds):
            for tree in ("old", "new") if r % 2 == 0 else ("new", "old"):
                t0 = time.process_time()
                for _ in range(5):
                    for _, a, k in calls[stage]:
                        fs[tree](*a, **k)
                ms[tree].append(1e3 * (time.process_time() - t0) / 5 / cycles)
        mo, mn = statistics.median(ms["old"]), statistics.median(ms["new"])
        print(f"  {stage:22s} old {mo:.2f} ms, new {mn:.2f} ms, new/old {mn / mo:.3f}; "
              f"same bytes: {same}")  # fmt: skip


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", default="fc03651", help="commit timed as the old code")
    ap.add_argument("--cycles", type=int, default=10)
    ap.add_argument("--rounds", type=int, default=4)
    ap.add_argument("--same-process", action="store_true", help="in-process A/B (see above)")
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        _child(args.cycles)
        return
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_cycle import baseline_tree
    from bench_stage_cpu import alternate_children

    if args.same_process:
        _same_process(baseline_tree(args.baseline), args.cycles, args.rounds)
        return

    trees = {"old": baseline_tree(args.baseline), "new": ROOT}
    res = alternate_children(__file__, trees, args.rounds, args.cycles)
    print(
        f"timeline stages of {args.cycles} station cycles, CPU ms a cycle, median of 5 passes "
        f"per round: baseline {args.baseline} (old) vs this tree (new); "
        f"load {os.getloadavg()[0]:.1f}; calls {res['new'][0]['ms']['calls']}"
    )
    for stage in TIMED:
        med = {}
        for name in trees:
            rounds = [d["ms"][stage] for d in res[name]]
            med[name] = statistics.median(rounds)
            print(f"  {stage:22s} {name}: {', '.join(f'{v:6.2f}' for v in rounds)}; "
                  f"median {med[name]:.2f}")  # fmt: skip
        print(f"  {stage:22s} new/old {med['new'] / max(med['old'], 1e-9):.3f}")
    old, new = (sum(statistics.median(d["ms"][s] for d in res[n]) for s in TIMED) for n in trees)
    print(f"  all stages: old {old:.2f} ms, new {new:.2f} ms, new/old {new / old:.3f}")
    same = len({d["digest"] for d in res["old"] + res["new"]}) == 1
    print(f"  same bytes in both trees: {same}")


if __name__ == "__main__":
    main()
