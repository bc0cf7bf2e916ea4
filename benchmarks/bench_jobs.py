"""How ``mjwalk simulate --jobs`` scales across processes, and where it falls short (issue 50
item 3: ``--jobs 2`` on two cores at least 1.8x one job's rate).

Run: python3 benchmarks/bench_jobs.py [--runs 40] [--rounds 1] [--against /work/main]

Prints, in one run with the job counts alternating (1, 2, 1, 2, ...): the wall time and rate
of the whole command ``python3 -m mjwalk simulate scenes/assembly_station.toml --runs N
--jobs J --quiet`` (start-up, batch and report), the rate of the batch alone
(``simulate_cycles`` on started workers), and the costs outside the cycles: a fresh
process's import and model loading (``context_of``, what every worker pays once), the
first batch on new workers (their start-up), and the pickled size of one run's result (what
goes back from a worker per run). The machine's load average is printed beside them: on a
machine shared with other work two workers cannot reach two cores' rate, so the command's CPU
seconds (its own and its workers', which the load does not change much) are printed too: what
more than one job's CPU seconds two jobs spend is their start-up. ``--against TREE`` runs the
same command from another checkout (with its own sources), interleaved with this one's.
"""

from __future__ import annotations

import argparse
import os
import pickle
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "scenes" / "assembly_station.toml"


def _cli(runs: int, jobs: int, tree: Path = ROOT) -> tuple[float, float]:
    """Wall and CPU seconds (the command's and its workers') of ``mjwalk simulate`` in ``tree``."""
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [sys.executable, "-m", "mjwalk", "simulate", str(SPEC), "--runs", str(runs)]
        cmd += ["--jobs", str(jobs), "--quiet", "--out", tmp]
        env = {**os.environ, "PYTHONPATH": str(tree)}
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, cwd=tree, capture_output=True, env=env)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
        return wall, cpu


def _fresh_context() -> float:
    """Seconds a fresh process takes to import mjwalk and load the station's context."""
    code = (
        "import time; t0 = time.perf_counter(); "
        "from mjwalk.cycle.context import context_of; "
        f"context_of({str(SPEC)!r}); print(time.perf_counter() - t0)"
    )
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
    return float(out.stdout.strip().splitlines()[-1])


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=40)
    ap.add_argument("--rounds", type=int, default=1)
    ap.add_argument("--against", type=Path, default=None, help="another checkout to compare")
    args = ap.parse_args()
    from mjwalk.cycle.simulate import simulate_cycles

    print(f"load average at the start: {os.getloadavg()[0]:.1f} (2 cores)")
    print(f"fresh process, import + station context: {_fresh_context():.2f} s")
    trees = {"this tree": ROOT}
    if args.against is not None:
        trees["against"] = args.against.resolve()
    cli: dict[tuple[str, int], list[tuple[float, float]]] = {}
    for _ in range(args.rounds):
        for jobs in (1, 2):
            for name, tree in trees.items():
                cli.setdefault((name, jobs), []).append(_cli(args.runs, jobs, tree))
    for name in trees:
        (w1, c1), (w2, c2) = (min(cli[(name, j)]) for j in (1, 2))
        print(
            f"{name}: mjwalk simulate --runs {args.runs}: 1 job {w1:.1f} s wall, {c1:.1f} s CPU; "
            f"2 jobs {w2:.1f} s wall, {c2:.1f} s CPU; 2 jobs / 1 job {w1 / w2:.2f}x "
            f"(goal >= 1.8x); extra CPU of 2 jobs {c2 - c1:+.1f} s"
        )
    batch: dict[int, list[float]] = {1: [], 2: []}
    for _ in range(args.rounds):
        for jobs in (1, 2):
            t0 = time.perf_counter()
            simulate_cycles(SPEC, 2 * jobs, seed=99, n_jobs=jobs)  # start (or reuse) workers
            first = time.perf_counter() - t0
            t0 = time.perf_counter()
            results = simulate_cycles(SPEC, args.runs, seed=0, n_jobs=jobs)
            batch[jobs].append(time.perf_counter() - t0)
            print(f"  {jobs} job(s): first batch of {2 * jobs} runs {first:.2f} s (start-up)")
    size = len(pickle.dumps(results[0]))
    for jobs in (1, 2):
        b = min(batch[jobs])
        print(f"{jobs} job(s): batch alone {args.runs / b:.2f} cycles/s")
    print(f"2 jobs / 1 job: batch alone {min(batch[1]) / min(batch[2]):.2f}x (goal >= 1.8x)")
    print(f"one run's result, pickled: {size / 1024:.1f} KiB")
    print(f"load average at the end: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
