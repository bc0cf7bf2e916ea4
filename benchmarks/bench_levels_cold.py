"""Cold start of a scene on several levels: each run a fresh process (issue 47's cost target).

Run: PYTHONPATH=. python3 benchmarks/bench_levels_cold.py [--runs 5] [--fresh-cache]
     [--no-cache] [--walk stand_rack1 stand_mezz_rack]

Each run starts a new Python process that loads the default step model, then times (CPU,
``time.process_time``) ``load_workplace`` of the scene, the first ``plan_walk`` in it (levels,
level views, crossings, numba kernels first used by a level walk loaded from numba's cache) and
the same walk again (warm). The same for the station's flat twin (``bench_levels.flat_twin``:
its levels flattened, the same sites and floor) in its own fresh process, alternating, so the
ratio of first plans says what a level scene's set-up costs over a flat scene's. Medians over
``--runs``.

``--fresh-cache`` points each process at an empty workplace cache (``$MJWALK_CACHE_DIR``, a new
temporary folder; the trained models stay where they are): what the very first run on a scene
costs. Without it the workplace cache is the user's own: what every later run costs.
``--no-cache`` loads the scenes with ``cache=False`` (nothing read from or written to the
workplace cache, whatever it holds).

Session 30 (cut3: hulls kept by the cache policy, headroom maps searched by box; 7b1da36 and the
branch alternated, fresh processes, CPU, medians of 9 pairs, same child as here): workplace cache
kept, levels load / first plan 329 / 593 -> 280 / 406 ms, flat twin 339 / 273 -> 272 / 223 ms,
ratio of first plans 2.10 -> 1.73 (load + first plan 1.41 -> 1.30); cache=False levels 357 / 621
-> 325 / 514, twin 397 / 285 -> 369 / 224 (the twin gains as much from the headroom maps; ratio
1.92 -> 2.35). Noisy: this script's own medians of 4 runs varied 1.5-1.9 between two rounds.

Session 31 (views47: level views' fields, and so their occupancy grids, kept in the workplace
cache; 261f168 and the branch alternated, fresh processes, CPU, medians of 7 pairs, this
script's child, load average 9.3-9.9 on 2 cores): workplace cache kept, levels first plan 365
-> 304 ms, twin 210 -> 211, ratio of first plans 1.74 -> 1.44 (per-pair median 1.72 -> 1.39;
load + first plan 1.32 -> 1.21); cache=False unchanged (nothing stored): levels 519 / 543,
twin 218 / 220, ratio 2.38 / 2.46 (noise).

The child processes use only mjwalk's public API, so the script runs against any tree
(``cd`` to it and set ``PYTHONPATH=.``).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

CHILD = """
import json, sys, time
from pathlib import Path
from mjwalk.world import load_workplace
from mjwalk.gait.default import default_model
from mjwalk.plan.walks import plan_walk
scene, a, b, cache = sys.argv[1:5]
model = default_model(progress=False)
t0 = time.process_time()
wp = load_workplace(Path(scene), cache=False if cache == "off" else None)
t1 = time.process_time()
w = plan_walk(wp, a, b, model, rng=1)
t2 = time.process_time()
plan_walk(wp, a, b, model, rng=2)
t3 = time.process_time()
print(json.dumps({"load": t1 - t0, "first": t2 - t1, "warm": t3 - t2, "length": w.length}))
"""


def run_child(scene: Path, a: str, b: str, fresh_cache: bool, cache: str) -> dict[str, float]:
    """One fresh process's figures (CPU seconds: load, first plan, warm plan; metres); ``cache``
    "off" loads with ``cache=False``, else the default policy."""
    env = dict(os.environ)
    with tempfile.TemporaryDirectory() as tmp:
        if fresh_cache:
            env["MJWALK_CACHE_DIR"] = tmp
        out = subprocess.run(
            [sys.executable, "-W", "ignore", "-c", CHILD, str(scene), a, b, cache],
            capture_output=True, text=True, env=env, check=False,
        )  # fmt: skip
    if out.returncode:
        raise SystemExit(f"child failed:\n{out.stderr}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    """Print the medians of the level scene's and its flat twin's cold start."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--walk", nargs=2, default=["stand_rack1", "stand_mezz_rack"])
    ap.add_argument("--fresh-cache", action="store_true", help="an empty workplace cache per run")
    ap.add_argument("--no-cache", action="store_true", help="load with cache=False")
    args = ap.parse_args()
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from bench_levels import SCENES, flat_twin  # deferred: after the path to benchmarks/

    scene = SCENES / "multilevel_station.xml"
    rows: dict[str, list[dict[str, float]]] = {"levels": [], "twin": []}
    with tempfile.TemporaryDirectory() as tmp:
        twin = flat_twin(scene, Path(tmp) / "flat_twin.xml")
        policy = "off" if args.no_cache else "default"
        run_child(scene, *args.walk, args.fresh_cache, policy)  # warm-up: numba, file cache
        run_child(twin, *args.walk, args.fresh_cache, policy)
        for _ in range(args.runs):
            rows["levels"].append(run_child(scene, *args.walk, args.fresh_cache, policy))
            rows["twin"].append(run_child(twin, *args.walk, args.fresh_cache, policy))
    med = {
        side: {k: statistics.median(r[k] for r in runs) for k in runs[0]}
        for side, runs in rows.items()
    }
    cache = "empty workplace cache" if args.fresh_cache else "workplace cache kept"
    cache += ", cache=False" if args.no_cache else ""
    print(f"{args.walk[0]} -> {args.walk[1]}, {args.runs} fresh processes each ({cache}), CPU ms:")
    print(f"{'scene':8} {'load':>7} {'first plan':>11} {'warm':>7} {'length m':>9}")
    for side, m in med.items():
        print(
            f"{side:8} {1000 * m['load']:7.1f} {1000 * m['first']:11.1f} {1000 * m['warm']:7.1f} "
            f"{m['length']:9.2f}"
        )
    lv, tw = med["levels"], med["twin"]
    print(
        f"cold ratio (first plan) {lv['first'] / tw['first']:.2f}, "
        f"load + first plan {(lv['load'] + lv['first']) / (tw['load'] + tw['first']):.2f}, "
        f"warm {lv['warm'] / tw['warm']:.2f}"
    )


if __name__ == "__main__":
    main()
