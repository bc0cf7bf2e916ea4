"""Assembly-cycle speed: one cycle, many cycles in parallel, and video rendering.

Run: python3 benchmarks/bench_cycle.py [--runs 1000] [--jobs 2] [--video-seconds 10]
     python3 benchmarks/bench_cycle.py --anim [--baseline b7c2bc5] [--cycles 5] [--rate-runs 20]

Targets (issue 7): one cycle (plan and animate, no video) in at most 2 s; 1000 cycles in at most
10 minutes on 2 cores; video frames per second reported.

``--anim`` (issue 18 item 3, animation at scale; goal <= 0.1 s per animated cycle): one
animated station cycle (plan + legs + arms + collision check) timed with the baseline commit
(default b7c2bc5, the tree issue 50 measures against) and with this tree, each in a fresh
subprocess running this tree's ``benchmarks/cycle_timing.py``, which skips the stage names a
tree lacks (the baseline exported once with ``git archive`` of ``mjwalk/`` and ``scenes/`` to
``~/.cache/mjwalk/bench-baseline-<sha>``, its compiled code cached there), in alternating
rounds (old, new, old, new); prints wall and CPU seconds per cycle, the exclusive split by
stage of a cycle and of a batch, cycles/s of ``simulate_cycles`` with 1 and 2 workers, the
old/new ratios, and how far the new poses are from the old ones (max |qpos difference|
over the same seeds) and whether the same contacts were found.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from mjwalk.cycle.simulate import prepare, simulate_cycle, simulate_cycles
from mjwalk.cycle.spec import load_cycle_spec

ROOT = Path(__file__).resolve().parents[1]


def baseline_tree(rev: str) -> Path:
    """The mjwalk package of commit ``rev`` exported to a cache directory (once per commit)."""
    sha = subprocess.run(
        ["git", "-C", str(ROOT), "rev-parse", rev], capture_output=True, text=True, check=True
    ).stdout.strip()
    tree = Path.home() / ".cache" / "mjwalk" / f"bench-baseline-{sha[:12]}"
    if not (tree / "scenes").is_dir():  # the package and the scenes it reads
        tree.mkdir(parents=True, exist_ok=True)
        archive = subprocess.run(
            ["git", "-C", str(ROOT), "archive", sha, "mjwalk", "scenes"],
            capture_output=True,
            check=True,
        ).stdout
        subprocess.run(["tar", "-x", "-C", str(tree)], input=archive, check=True)
    return tree


def _time_tree(tree: Path, cycles: int, jobs: list[int], runs: int, out: Path) -> dict:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    cmd = [sys.executable, str(ROOT / "benchmarks" / "cycle_timing.py"), "--cycles", str(cycles)]
    cmd += ["--runs", str(runs), "--out", str(out), "--jobs", *map(str, jobs)]
    res = subprocess.run(cmd, env=env, capture_output=True, text=True, check=False, cwd=ROOT)
    if res.returncode != 0:  # the timed tree's own traceback, not only the exit code
        sys.exit(f"cycle_timing.py failed for {tree}:\n{res.stderr[-3000:]}")
    return json.loads(res.stdout.strip().splitlines()[-1])


def animation_old_vs_new(rev: str, cycles: int, runs: int) -> None:
    """Seconds per animated station cycle, baseline ``rev`` vs this tree (see the module doc)."""
    old_tree = baseline_tree(rev)
    print(f"animated station cycle: baseline {rev} ({old_tree}) vs this tree ({ROOT})")
    res: dict[str, list[dict]] = {"old": [], "new": []}
    with tempfile.TemporaryDirectory() as tmp:
        for rnd in range(2):
            for name, tree in (("old", old_tree), ("new", ROOT)):
                jobs = [1, 2] if rnd == 1 else []
                out = Path(tmp) / f"{name}{rnd}.npz"
                res[name].append(_time_tree(tree, cycles, jobs, runs, out))
        old_q, new_q = np.load(Path(tmp) / "old0.npz"), np.load(Path(tmp) / "new0.npz")
        shapes = all(old_q[k].shape == new_q[k].shape for k in old_q.files)
        # (cycles whose frame counts differ, e.g. other walks, have no pose difference)
        dq = max(
            (float(np.abs(old_q[k] - new_q[k]).max()) for k in old_q.files
             if old_q[k].shape == new_q[k].shape),
            default=float("nan"),
        )  # fmt: skip
    med, rate1 = {}, {}
    for name, runs_ in res.items():
        wall = [t for r in runs_ for t in r["wall"]]
        cpu = [t for r in runs_ for t in r["cpu"]]
        med[name] = statistics.median(wall)
        rates = runs_[1]["rates"]
        rate1[name] = rates.get("1", float("nan"))
        print(
            f"  {name}: median {med[name]:.3f} s wall, {statistics.median(cpu):.3f} s CPU per "
            f"cycle ({len(wall)} cycles; load average {runs_[0]['load']:.1f}, "
            f"{runs_[1]['load']:.1f})"
        )
        print(
            "      simulate_cycles: "
            + ", ".join(f"{j} worker(s) {v:.2f} cycles/s" for j, v in rates.items())
        )
        for key, title in (("split", "animated cycle"), ("batch_split", "simulate_cycles")):
            split = runs_[0].get(key, {})
            print(
                f"      split of the {title}: "
                + ", ".join(f"{k} {100 * v:.0f} %" for k, v in split.items() if v >= 0.005)
            )
        if runs_[0].get("missing"):
            print(f"      (stages this tree lacks: {len(runs_[0]['missing'])} names)")
    print(
        f"  old/new: {med['old'] / med['new']:.2f}x faster per cycle (goal <= 0.1 s); "
        f"new/old batch rate (1 worker) {rate1['new'] / rate1['old']:.2f}x"
    )
    same = [r["contacts"] for r in res["old"]] == [r["contacts"] for r in res["new"]]
    print(
        f"  poses: max |qpos new - old| {dq:.2e} (rad / m) over {cycles} cycles, same frame "
        f"counts {shapes}; same contacts {same}"
    )


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=1000)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--video-seconds", type=float, default=10.0)
    ap.add_argument("--anim", action="store_true", help="only the old-vs-new animation section")
    ap.add_argument("--baseline", default="b7c2bc5", help="commit timed as the old code")
    ap.add_argument("--cycles", type=int, default=5, help="--anim: cycles timed per round")
    ap.add_argument("--rate-runs", type=int, default=20, help="--anim: cycles per rate")
    args = ap.parse_args()
    if args.anim:
        animation_old_vs_new(args.baseline, args.cycles, args.rate_runs)
        return
    spec_path = ROOT / "scenes" / "assembly_station.toml"
    spec = load_cycle_spec(spec_path)
    t0 = time.perf_counter()
    ctx = prepare(spec)
    print(f"prepare (scene, models, humanoid): {time.perf_counter() - t0:.2f} s")

    for check in (False, True):
        times = []
        for k in range(5):
            t0 = time.perf_counter()
            r = simulate_cycle(ctx, k, collisions=check)
            times.append(time.perf_counter() - t0)
        label = "with collision check" if check else "plan + animate"
        print(
            f"one cycle ({label}): median {statistics.median(times):.2f} s "
            f"(cycle time {r.cycle_time:.1f} s, {r.timeline is None and 'no video'})"
        )

    t0 = time.perf_counter()
    results = simulate_cycles(spec_path, args.runs, seed=0, n_jobs=args.jobs, progress=True)
    wall = time.perf_counter() - t0
    ct = np.array([r.cycle_time for r in results])
    coll = sum(len(r.collisions) for r in results)
    print(
        f"{args.runs} cycles on {args.jobs} processes (with collision checks): {wall:.1f} s "
        f"({wall / 60:.2f} min; target <= 10 min), {args.runs / wall:.2f} cycles/s"
    )
    print(
        f"  cycle time median {np.median(ct):.1f} s, IQR "
        f"{np.subtract(*np.percentile(ct, [75, 25])):.1f} s; collisions {coll}"
    )

    from mjwalk.render import render_video

    r = simulate_cycle(ctx, 0, keep_timeline=True, collisions=False)
    tl = r.timeline
    n = min(tl.n_frames, int(args.video_seconds * tl.fps))
    tl.qpos, tl.t = tl.qpos[:n], tl.t[:n]
    with tempfile.TemporaryDirectory() as tmp:
        for size in ((640, 480), (320, 240)):
            t0 = time.perf_counter()
            render_video(tl, Path(tmp) / "clip.mp4", camera="track", size=size, progress=False)
            dt = time.perf_counter() - t0
            print(f"video {size[0]}x{size[1]}: {n} frames in {dt:.1f} s = {n / dt:.1f} frames/s")


if __name__ == "__main__":
    main()
