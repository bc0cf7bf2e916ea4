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
import resource
import statistics
import subprocess
import sys
import time

PLAN = ["plan", "station", "--from", "stand_rack2", "--to", "stand_car1", "--n", "1"]
DEPS = "import numpy, scipy.stats, scipy.spatial, sklearn.decomposition, mujoco, numba, matplotlib"


def timed(cmd: list[str]) -> tuple[list[float], float, list[str], float]:
    """(seconds to each stdout line, seconds to exit, the lines, CPU seconds) of one fresh
    process. CPU seconds (user + system) are what the wall time would be on an idle machine,
    near enough for these single-threaded start-ups; the wall times include waiting for the
    other processes of a shared machine."""
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    stamps, lines = [], []
    for line in proc.stdout:
        stamps.append(time.perf_counter() - t0)
        lines.append(line.rstrip())
    proc.wait()
    total = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
    if proc.returncode:
        raise SystemExit(f"{cmd} failed:\n{proc.stderr.read()}")
    return stamps, total, lines, cpu


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
    base = statistics.median(r[1] for r in rows["baseline: import the dependencies"])
    base_cpu = statistics.median(r[3] for r in rows["baseline: import the dependencies"])
    print(
        f"median of {args.repeat} warm runs; wall seconds (ratio to the baseline's {base:.2f} s) "
        f"and CPU seconds (ratio to its {base_cpu:.2f} s); load average {os.getloadavg()[0]:.1f}"
    )
    for name, runs in rows.items():
        total = statistics.median(r[1] for r in runs)
        cpu = statistics.median(r[3] for r in runs)
        print(
            f"  {name:36s} exit {total:6.2f} s ({total / base:4.2f}x), "
            f"CPU {cpu:5.2f} s ({cpu / base_cpu:4.2f}x)"
        )
        n_lines = min(len(r[0]) for r in runs)
        for k in range(n_lines):
            at = statistics.median(r[0][k] for r in runs)
            print(f"      line {k + 1} at {at:6.2f} s ({at / base:4.2f}x): {runs[0][2][k][:56]}")
    plan = rows["mjwalk plan (grid + 1 walk)"]
    first = statistics.median(r[0][0] for r in plan)
    walk = statistics.median(r[0][1] for r in plan)
    cpu = statistics.median(r[3] for r in plan)
    print(
        f"mjwalk plan: first result (grid route) at {first:.2f} s wall, first walk at "
        f"{walk:.2f} s wall, whole command {cpu:.2f} CPU s; goal < 2 s "
        f"{'met' if cpu < 2 else 'NOT met'} in CPU time"
    )


if __name__ == "__main__":
    main()
