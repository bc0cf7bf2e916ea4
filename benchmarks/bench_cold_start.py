"""Start-up of ``mjwalk plan``: seconds from launching the process to its first result.

Runs each command ``--repeat`` times as a fresh process (warm: the numba machine code and the
default model are already cached; the first run after an install compiles, see
``mjwalk/_jit.py``) and prints the median seconds to each printed line and to exit, beside a
baseline in the same process: importing mjwalk's dependencies alone (numpy, scipy, sklearn,
mujoco, numba, matplotlib), the floor no mjwalk change can go below. Lines are timestamped as
they arrive (``PYTHONUNBUFFERED``).

    PYTHONPATH=. python3 benchmarks/bench_cold_start.py [--repeat 3]

The goal (issue 17): ``mjwalk plan`` to its first result under 2 s warm.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time

PLAN = ["plan", "station", "--from", "stand_rack2", "--to", "stand_car1", "--n", "1"]
DEPS = "import numpy, scipy.stats, scipy.spatial, sklearn.decomposition, mujoco, numba, matplotlib"


def timed(cmd: list[str]) -> tuple[list[float], float, list[str]]:
    """(seconds to each stdout line, seconds to exit, the lines) of one fresh process."""
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    stamps, lines = [], []
    for line in proc.stdout:
        stamps.append(time.perf_counter() - t0)
        lines.append(line.rstrip())
    proc.wait()
    total = time.perf_counter() - t0
    if proc.returncode:
        raise SystemExit(f"{cmd} failed:\n{proc.stderr.read()}")
    return stamps, total, lines


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    py = sys.executable
    timed([py, "-m", "mjwalk", *PLAN])  # warm the caches (compiles on a fresh checkout)
    rows = {}
    for name, cmd in (
        ("baseline: import the dependencies", [py, "-c", DEPS]),
        ("python -m mjwalk --version", [py, "-m", "mjwalk", "--version"]),
        ("mjwalk plan (grid + 1 walk)", [py, "-m", "mjwalk", *PLAN]),
    ):
        runs = [timed(cmd) for _ in range(args.repeat)]
        rows[name] = runs
    base = statistics.median(t for _, t, _ in rows["baseline: import the dependencies"])
    print(f"median of {args.repeat} warm runs, seconds (ratio to the baseline {base:.2f} s)")
    for name, runs in rows.items():
        total = statistics.median(t for _, t, _ in runs)
        print(f"  {name:38s} exit {total:6.2f} s  ({total / base:4.2f}x)")
        n_lines = min(len(s) for s, _, _ in runs)
        for k in range(n_lines):
            at = statistics.median(s[k] for s, _, _ in runs)
            print(f"      line {k + 1} at {at:6.2f} s ({at / base:4.2f}x): {runs[0][2][k][:60]}")
    plan = rows["mjwalk plan (grid + 1 walk)"]
    first = statistics.median(s[0] for s, _, _ in plan)
    walk = statistics.median(s[1] for s, _, _ in plan)
    print(
        f"first result (grid route) {first:.2f} s, first walk {walk:.2f} s; "
        f"goal < 2 s: {'met' if first < 2 else 'NOT met'} for the first result"
    )


if __name__ == "__main__":
    main()
