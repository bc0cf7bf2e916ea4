"""How ``mjwalk simulate --jobs`` scales across processes, and where it falls short (issue 50
item 3: ``--jobs 2`` on two cores at least 1.8x one job's rate).

Run: python3 benchmarks/bench_jobs.py [--runs 40] [--rounds 1]

Prints, in one run with the job counts alternating (1, 2, 1, 2, ...): the wall time and rate
of the whole command ``python3 -m mjwalk simulate scenes/assembly_station.toml --runs N
--jobs J --quiet`` (start-up, batch and report), the rate of the batch alone
(``simulate_cycles`` on started workers), and the costs outside the cycles: a fresh
process's import and model loading (``context_of``, what every worker pays once), the
first batch on new workers (their start-up), and the pickled size of one run's result (what
goes back from a worker per run). The machine's load average is printed beside them: on a
machine shared with other work two workers cannot reach two cores' rate.
"""

from __future__ import annotations

import argparse
import os
import pickle
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SPEC = ROOT / "scenes" / "assembly_station.toml"


def _cli(runs: int, jobs: int) -> float:
    """Wall seconds of the whole ``mjwalk simulate`` command."""
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [sys.executable, "-m", "mjwalk", "simulate", str(SPEC), "--runs", str(runs)]
        cmd += ["--jobs", str(jobs), "--quiet", "--out", tmp]
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, cwd=ROOT, capture_output=True)
        return time.perf_counter() - t0


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
    args = ap.parse_args()
    from mjwalk.cycle.simulate import simulate_cycles

    print(f"load average at the start: {os.getloadavg()[0]:.1f} (2 cores)")
    print(f"fresh process, import + station context: {_fresh_context():.2f} s")
    cli: dict[int, list[float]] = {1: [], 2: []}
    batch: dict[int, list[float]] = {1: [], 2: []}
    for _ in range(args.rounds):
        for jobs in (1, 2):
            cli[jobs].append(_cli(args.runs, jobs))
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
        w, b = min(cli[jobs]), min(batch[jobs])
        print(
            f"{jobs} job(s): mjwalk simulate --runs {args.runs}: {w:.1f} s, "
            f"{args.runs / w:.2f} cycles/s; batch alone {args.runs / b:.2f} cycles/s"
        )
    print(
        f"2 jobs / 1 job: command {min(cli[1]) / min(cli[2]):.2f}x, batch alone "
        f"{min(batch[1]) / min(batch[2]):.2f}x (goal >= 1.8x)"
    )
    print(f"one run's result, pickled: {size / 1024:.1f} KiB")
    print(f"load average at the end: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
