"""CPU time per animated station cycle by stage, a baseline commit against this tree, in
alternating rounds (issue 50: the stages' costs on a machine shared with other work).

Run: python3 benchmarks/bench_stage_cpu.py --baseline 879469c [--rounds 4] [--cycles 10]

Each stage's exclusive time is the process's CPU time (``time.process_time``), as in
``cycle_timing.py``'s split (the same stage table, the same wrapping and clock:
:func:`cycle_timing.install`, :class:`cycle_timing.StageClock`), of several alternating fresh
processes per tree, since a busy machine's swings exceed one process's noise. Each round
runs one fresh subprocess per tree (the baseline exported
as ``bench_cycle.py`` exports it), which prepares the station cycle, runs one warm-up cycle and
then ``--cycles`` cycles on seeds 0.. with the stages wrapped. Prints per stage the median over
the rounds of the CPU ms per cycle in each tree and their ratio (stages of at least 1 ms).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _child(cycles: int) -> None:
    """In the timed tree: the stages' CPU ms per cycle as one JSON line."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import cycle_timing as ct

    import mjwalk
    import mjwalk.cycle.simulate as sim
    from mjwalk.cycle.spec import load_cycle_spec

    spec_path = Path(mjwalk.__file__).resolve().parents[1] / "scenes" / "assembly_station.toml"
    ctx = sim.prepare(load_cycle_spec(spec_path))
    sim.simulate_cycle(ctx, 99)  # warm-up: models, compiled code
    clock = ct.StageClock()  # CPU time
    ct.install(clock)
    clock.acc.clear()
    c0 = time.process_time()
    for k in range(cycles):
        sim.simulate_cycle(ctx, k)
    out = {k: 1e3 * v / cycles for k, v in clock.acc.items()}
    out["cycle (all stages)"] = 1e3 * (time.process_time() - c0) / cycles
    print(json.dumps(out))


def alternate_children(
    script: str, trees: dict[str, Path], rounds: int, cycles: int
) -> dict[str, list[dict]]:
    """Run ``script --child --cycles N`` once per tree and round, each tree first in every
    other round, with that tree first on PYTHONPATH; the last JSON line each child prints,
    per tree name (a child that fails ends the benchmark with its message)."""
    res: dict[str, list[dict]] = {k: [] for k in trees}
    names = list(trees)
    for r in range(rounds):
        for name in names if r % 2 == 0 else names[::-1]:
            env = {**os.environ, "PYTHONPATH": str(trees[name])}
            cmd = [sys.executable, script, "--child", "--cycles", str(cycles)]
            run = subprocess.run(cmd, env=env, capture_output=True, text=True, cwd=ROOT)
            if run.returncode != 0:
                sys.exit(f"the {name} tree failed:\n{run.stderr[-3000:]}")
            res[name].append(json.loads(run.stdout.strip().splitlines()[-1]))
    return res


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", default="879469c", help="commit timed as the old code")
    ap.add_argument("--rounds", type=int, default=4)
    ap.add_argument("--cycles", type=int, default=10, help="cycles timed per subprocess")
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child:
        _child(args.cycles)
        return
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_cycle import baseline_tree

    trees = {"old": baseline_tree(args.baseline), "new": ROOT}
    res = alternate_children(__file__, trees, args.rounds, args.cycles)
    print(
        f"CPU ms per animated station cycle, median of {args.rounds} rounds of {args.cycles} "
        f"cycles: baseline {args.baseline} (old) vs this tree (new); load {os.getloadavg()[0]:.1f}"
    )
    stages = sorted(
        {k for d in res["old"] + res["new"] for k in d},
        key=lambda k: -statistics.median(d.get(k, 0.0) for d in res["old"]),
    )
    for st in stages:
        old = statistics.median(d.get(st, 0.0) for d in res["old"])
        new = statistics.median(d.get(st, 0.0) for d in res["new"])
        if max(old, new) >= 1.0:
            print(f"  {st:<24} {old:7.2f} -> {new:7.2f} ms  ({new / old if old else 0:.3f})")


if __name__ == "__main__":
    main()
