"""CPU cost of the legs (``legs_from_walk``) of recorded station walks, a baseline commit
against this tree, in alternating fresh processes, and whether both give the same bytes
(issue 50).

Run: python3 benchmarks/bench_legs_replay.py --baseline 13e4664 [--cycles 20] [--rounds 4]

This tree records the (walk, stature) pairs of ``--cycles`` animated station cycles
(``simulate_cycle`` on seeds 0.., after one warm-up cycle) to a temporary pickle; then each
round runs one fresh subprocess per tree (the baseline exported as ``bench_cycle.py`` exports
it), which synthesises every recorded walk once (its digest: the SHA-256 of every track's
bytes), then five times more on the CPU clock (``time.process_time``). Prints per tree the
median CPU ms per cycle of each round, the median over the rounds, the ratio, and whether the
digests are equal. The first run of a tree compiles its kernels: each subprocess synthesises
the walks once before timing.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import pickle
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from bench_synthloop import recording_legs, synth_cpu, track_bytes  # the recorded station walks

ROOT = Path(__file__).resolve().parents[1]


def _record(cycles: int, out: Path) -> int:
    """Pickle the (walk, stature) pairs of ``cycles`` station cycles to ``out``; their count."""
    import mjwalk.cycle.simulate as sim
    from mjwalk.cycle.spec import load_cycle_spec

    ctx = sim.prepare(load_cycle_spec(ROOT / "scenes" / "assembly_station.toml"))
    sim.simulate_cycle(ctx, 99)  # warm-up: models, compiled code
    with recording_legs() as seen:
        for k in range(cycles):
            sim.simulate_cycle(ctx, k)
    out.write_bytes(pickle.dumps(seen))
    return len(seen)


def _child(walks_file: Path, cycles: int) -> None:
    """In the timed tree: the walks' digest and CPU ms per cycle of five passes, one JSON line."""
    from mjwalk.body.legs import synthesis as syn

    walks = pickle.loads(walks_file.read_bytes())
    h = hashlib.sha256()
    for walk, stature in walks:
        for b in track_bytes(syn.legs_from_walk(walk, stature)):
            h.update(b)
    ms = [1e3 * synth_cpu(walks) / cycles for _ in range(5)]
    print(json.dumps({"digest": h.hexdigest(), "ms": statistics.median(ms)}))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", default="13e4664", help="commit timed as the old code")
    ap.add_argument("--cycles", type=int, default=20)
    ap.add_argument("--rounds", type=int, default=4)
    ap.add_argument("--child", type=Path, default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.child is not None:
        _child(args.child, args.cycles)
        return
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_cycle import baseline_tree

    trees = {"old": baseline_tree(args.baseline), "new": ROOT}
    with tempfile.TemporaryDirectory() as tmp:
        walks_file = Path(tmp) / "walks.pkl"
        n = _record(args.cycles, walks_file)
        res: dict[str, list[dict]] = {k: [] for k in trees}
        for r in range(args.rounds):
            for name in ("old", "new") if r % 2 == 0 else ("new", "old"):
                env = {**os.environ, "PYTHONPATH": str(trees[name])}
                cmd = [sys.executable, __file__, "--child", str(walks_file)]
                cmd += ["--cycles", str(args.cycles)]
                run = subprocess.run(cmd, env=env, capture_output=True, text=True, cwd=ROOT)
                if run.returncode != 0:
                    sys.exit(f"the {name} tree failed:\n{run.stderr[-3000:]}")
                res[name].append(json.loads(run.stdout.strip().splitlines()[-1]))
    print(
        f"legs of {n} walks ({args.cycles} station cycles), CPU ms a cycle, median of 5 passes "
        f"per round: baseline {args.baseline} (old) vs this tree (new); "
        f"load {os.getloadavg()[0]:.1f}"
    )
    med = {}
    for name in trees:
        rounds = [d["ms"] for d in res[name]]
        med[name] = statistics.median(rounds)
        print(f"  {name}: rounds {', '.join(f'{v:.2f}' for v in rounds)}; median {med[name]:.2f}")
    same = len({d["digest"] for d in res["old"] + res["new"]}) == 1
    print(f"  new/old {med['new'] / med['old']:.3f}; same bytes in both trees: {same}")


if __name__ == "__main__":
    main()
