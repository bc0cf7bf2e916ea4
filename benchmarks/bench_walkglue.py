"""CPU cost of a station cycle's walk glue and operator set-up (issue 50): the stages
"operator and start", "walk spot", "walk baselines", "turns", "walk frames", "standing pose"
and "cycle loop" of ``benchmarks/cycle_timing.py``, a baseline commit against this tree, in
alternating fresh processes, and whether both give the same poses.

Run: python3 benchmarks/bench_walkglue.py --baseline fc03651 [--cycles 10] [--rounds 4]

Each round runs one fresh subprocess per tree (the baseline exported as ``bench_cycle.py``
exports it), which prepares the station, runs one warm-up cycle (seed 99) and then the
animated cycles of seeds 0..cycles-1 once each, as ``cycle_timing.py`` times them (every seed
draws an operator of a stature not built yet, so each cycle builds its humanoid), with
``cycle_timing.py``'s stage wrappers on the CPU clock (``time.process_time``, exclusive time
per stage). Prints per tree the median over the rounds of each stage's CPU ms per cycle, the
whole cycle's, the ratios, and whether the poses' digests (SHA-256 of every cycle's qpos
bytes) are equal.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: The stages this benchmark reports (``cycle_timing.STAGES`` labels).
GLUE = (
    "operator and start",
    "walk spot",
    "walk baselines",
    "turns",
    "walk frames",
    "standing pose",
    "cycle loop",
)


def _child(cycles: int) -> None:
    """In the timed tree: CPU ms per cycle of every stage and of the cycle, one JSON line."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import cycle_timing as ct  # the stage list and wrappers

    import mjwalk.cycle.simulate as sim
    from mjwalk.cycle.spec import load_cycle_spec

    ct.time.perf_counter = time.process_time  # the stage clock on the CPU clock
    spec = Path(sim.__file__).resolve().parents[2] / "scenes" / "assembly_station.toml"
    ctx = sim.prepare(load_cycle_spec(spec))
    sim.simulate_cycle(ctx, 99)  # warm-up: models, compiled code
    clock = ct.StageClock()
    ct.install(clock)
    h = hashlib.sha256()
    c0 = time.process_time()
    for k in range(cycles):
        r = sim.simulate_cycle(ctx, k, keep_timeline=True)
        h.update(r.timeline.qpos.tobytes())
    total = time.process_time() - c0
    ms = {k: 1e3 * v / cycles for k, v in clock.acc.items()}
    print(json.dumps({"digest": h.hexdigest(), "ms": ms, "total": 1e3 * total / cycles}))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--baseline", default="fc03651")
    ap.add_argument("--cycles", type=int, default=10)
    ap.add_argument("--rounds", type=int, default=4)
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        _child(args.cycles)
        return
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_cycle import baseline_tree
    from bench_stage_cpu import alternate_children

    trees = {"base": baseline_tree(args.baseline), "branch": ROOT}
    out = alternate_children(__file__, trees, args.rounds, args.cycles)
    med = {
        name: {s: statistics.median(r["ms"].get(s, 0.0) for r in rs) for s in GLUE}
        for name, rs in out.items()
    }
    total = {name: statistics.median(r["total"] for r in rs) for name, rs in out.items()}
    print(f"CPU ms per cycle, median of {args.rounds} rounds x {args.cycles} cycles")
    print(f"  {'stage':<22} {'base':>8} {'branch':>8} {'ratio':>6}")
    for s in GLUE:
        b, n = med["base"][s], med["branch"][s]
        print(f"  {s:<22} {b:8.2f} {n:8.2f} {n / b if b else float('nan'):6.2f}")
    gb, gn = sum(med["base"].values()), sum(med["branch"].values())
    print(f"  {'glue stages':<22} {gb:8.2f} {gn:8.2f} {gn / gb:6.2f}")
    tb, tn = total["base"], total["branch"]
    print(f"  {'whole cycle':<22} {tb:8.2f} {tn:8.2f} {tn / tb:6.2f}")
    digests = {r["digest"] for rs in out.values() for r in rs}
    print(f"  same poses (qpos digests equal): {len(digests) == 1}")


if __name__ == "__main__":
    main()
