"""Factory scale (issue 18): workplace setup on generated halls, long walks through clutter,
cycles per second.

Run: PYTHONPATH=. python3 benchmarks/bench_scale.py [--sizes 10 40 100] [--walks 20]
     [--lengths 2 4 8 16 32] [--cycles 20] [--skip-setup] [--skip-walks] [--skip-cycles]

(a) Setup per generated hall (``mjwalk.world.generate``: width x width m, 0.4 obstacles per
    m^2 of boxes, cylinders and capsules, seed 0): footprints + clearance field + walk field +
    8- and 16-connected occupancy grids, cold (cache off) and from the disk cache (after one
    build that stores it), each in a fresh process (peak RSS of that process). "before": the
    old code path (``build_clearance_bruteforce`` + ``occupancy_grid_sampled``), 10 m hall only
    (issue 18 measured it at 40 m: 118.6 s for 640 boxes; at 100 m with 40 boxes: 107 s for
    the field, 25-32 s and 63-71 s for the grids, 4.85 GB).
(b) Walk-length scaling on the cluttered 36 x 10 m hall (144 boxes, seed 0): for each length,
    ``--walks`` start/goal pairs that far apart (start and goal 0.5 m clear of every obstacle),
    one hybrid A* walk and one grid A* route each: median expansions, failures, median
    planning time of both and the median of the paired time ratios; the hybrid walks' length
    IQR (relative to the median) and sway share (steps whose largest lateral excursion points
    to the stance foot).
(c) Cycles per second of ``simulate_cycles`` on the station spec with 1 and 2 workers.

(b) times both planners in CPU seconds (``time.process_time``) since branch plan-cost: wall
times on the shared 2-core machine ran 5-30x the CPU time. Measured there (20 walks a length,
CPU): hybrid 2.3 / 2.8 / 5.5 / 12.6 / 13.2 ms at 2 / 4 / 8 / 16 / 32 m (main before it:
3.6 / 3.7 / 6.0 / 14.3 / 14.3 ms, expansions identical), grid A* 0.6 / 0.7 / 0.9 / 1.8 / 3.9 ms:
hybrid/grid 4.1-4.3 / 3.8 / 5.8-6.0 / 6.0-6.4 / 3.6-3.7. The grid A* has been compiled since
64666d3 (6x faster by its own commit's figure); the ratios of issue 48 (1.79 ... 0.45) were
taken against the interpreted grid A*.
Branch plan-speed (footprint distance compiled, per-planner field/sight set-up shared), both
trees alternated on a loaded machine (load 7-8), CPU: hybrid 2.4-2.6 / 2.6-3.0 / 4.8-5.1 /
12.4-12.7 / 13.1-13.2 ms (ae71305) -> 2.2 / 2.3 / 4.8 / 12.6 / 12.6 ms, expansions identical;
the rest is the compiled search (about 16 us an expansion: 5 us the GP draw, the rest the
ten steps' checks), so "at most 1.0x grid A*" is not reached by speed-ups that keep the walks.
Branch plan50 (issue 50: the GP draw and the step checks inlined into the compiled search, the
side gap's room compiled), 8 alternated rounds each on a loaded machine: hybrid medians
3.00 / 3.55 / 8.90 / 15.35 / 26.2 ms (9d56241) -> 2.95 / 3.90 / 8.65 / 11.75 / 21.8 ms, the
same expansions; the paired ratios per round spread 0.6-1.6, wider than the change. Both
trees' planners in one process, alternated (min of 10 rounds, the same 20 walks a length):
2.72 -> 2.59 / 3.85 -> 3.71 / 7.35 -> 7.03 ms a walk at 2 / 4 / 8 m (0.955 / 0.962 / 0.957).
The two inlinings were then reverted (a fresh checkout compiled 29 s longer; decision 106).
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from bench_planner import sways_towards_stance  # the sway measure of the station benchmark

ROOT = Path(__file__).resolve().parents[1]


def setup_one(size: float, mode: str) -> dict:
    """Build one hall's workplace in this process; ``mode`` cold | warm | before."""
    from mjwalk.plan.occupancy import MOVES_16, occupancy_grid_sampled, shared_grid
    from mjwalk.world import load_workplace
    from mjwalk.world.clearance import build_clearance_bruteforce
    from mjwalk.world.generate import generate_hall

    hall = generate_hall(size, seed=0)
    path = Path(tempfile.gettempdir()) / f"mjwalk_bench_hall_{size:g}.xml"
    hall.write(path)
    # load the compiled kernels (numba's cache) on a 3 m hall first: a one-off per process
    t0 = time.perf_counter()
    tiny = generate_hall(3, seed=0).write(Path(tempfile.gettempdir()) / "mjwalk_bench_tiny.xml")
    small = load_workplace(tiny, cache=False)
    shared_grid(small)
    occupancy_grid_sampled(small)
    kernels = time.perf_counter() - t0
    t0 = time.perf_counter()
    if mode == "before":
        wp = load_workplace(path, cache=False)
        wp.clearance = build_clearance_bruteforce(wp.obstacles, wp.floor_bounds)
        wp.walk_field()
        occupancy_grid_sampled(wp)
        occupancy_grid_sampled(wp, moves=MOVES_16)
    else:
        wp = load_workplace(path, cache=mode in ("store", "warm"))
        wp.walk_field()
        shared_grid(wp)
        shared_grid(wp, moves=MOVES_16)
    seconds = time.perf_counter() - t0
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024  # kB -> MB (Linux)
    return {"size": size, "mode": mode, "seconds": seconds, "peak_mb": peak, "kernels": kernels,
            "obstacles": len(wp.obstacles), "nodes": int(np.prod(wp.clearance.shape))}  # fmt: skip


def run_setup(sizes: list[float]) -> None:
    print("(a) workplace setup: footprints, clearance + walk field, 8- and 16-move grids")
    print(f"{'hall':>8} {'obstacles':>9} {'nodes':>11} {'mode':>7} {'seconds':>8} {'peak MB':>8}")
    with tempfile.TemporaryDirectory() as cache:
        env = {**__import__("os").environ, "MJWALK_CACHE": cache}  # workplaces in cache/workplaces
        for size in sizes:
            modes = ["cold", "store", "warm"] + (["before"] if size <= 10 else [])
            res = {}
            for mode in modes:
                out = subprocess.run(
                    [sys.executable, __file__, "--setup-one", str(size), mode],
                    capture_output=True, text=True, env=env, check=True,
                )  # fmt: skip
                r = json.loads(out.stdout.strip().splitlines()[-1])
                res[mode] = r
                if mode == "store":  # the first cached build: builds and writes the files
                    continue
                print(
                    f"{size:>6g} m {r['obstacles']:>9d} {r['nodes']:>11d} {mode:>7} "
                    f"{r['seconds']:>8.2f} {r['peak_mb']:>8.0f}"
                )
            if "before" in res:
                print(
                    f"  RATIO before/cold: {res['before']['seconds'] / res['cold']['seconds']:.1f}"
                )
    print("  (seconds exclude loading the compiled kernels, once per process: 1-4 s; peak MB")
    print("  includes the interpreter, MuJoCo and numba: about 250 MB at 0 nodes; warm: the")
    print("  arrays mapped from the disk cache, as a second worker gets them)")


def _pairs(hall, length: float, n: int, rng: np.random.Generator) -> list:
    """``n`` (start, goal) pairs ``length`` metres apart across the 36 x 10 m hall, both 0.5 m
    clear of every obstacle's bounding circle."""
    pairs = []
    c = hall.circles
    while len(pairs) < n:
        a = rng.uniform([-17.5, -4.5], [17.5 - length, 4.5])
        ang = rng.uniform(-0.25, 0.25)
        b = a + length * np.array([np.cos(ang), np.sin(ang)])
        if abs(b[1]) > 4.5 or b[0] > 17.5:
            continue
        if min(np.min(np.hypot(*(c[:, :2] - p).T) - c[:, 2]) for p in (a, b)) < 0.5:
            continue
        pairs.append((a, b))
    return pairs


def run_spread(lengths: list[float], n_pairs: int, n_walks: int, **options) -> None:
    """The spread of repeated walks between the same two points (what the probabilistic
    planner is for): per pair the IQR of ``n_walks`` walk lengths and their sway share."""
    from mjwalk.errors import PlanningError
    from mjwalk.gait.default import default_model
    from mjwalk.plan.hybrid import HybridPlanner
    from mjwalk.plan.options import PlannerOptions
    from mjwalk.world import load_workplace
    from mjwalk.world.generate import generate_hall

    hall = generate_hall(36, 10, kinds=("box",), seed=0)
    with tempfile.TemporaryDirectory() as tmp:
        wp = load_workplace(hall.write(Path(tmp) / "hall36.xml"), cache=False)
    model = default_model()
    rng = np.random.default_rng(8)
    print(f"\n(b2) spread of {n_walks} walks per start/goal pair, {n_pairs} pairs per length")
    print(f"{'L [m]':>6} {'IQR [m] median over pairs':>26} {'sway':>6} {'fail':>5} {'exp':>6}")
    for length in lengths:
        iqrs, sways, fails, exp = [], [], 0, []
        for a, b in _pairs(hall, length, n_pairs, rng):
            planner = HybridPlanner(wp, b, model, PlannerOptions(**options))
            lens = []
            for k in range(n_walks):
                try:
                    w = planner.plan(a, np.random.default_rng(k))
                except PlanningError:
                    fails += 1
                    continue
                lens.append(w.length)
                exp.append(w.meta["expansions"])
                sways += [
                    sways_towards_stance(w.xy[s.start : s.end + 1], s.stance[:2])
                    for s in w.steps[1:]
                ]
            if len(lens) >= 4:
                q25, q75 = np.percentile(lens, [25, 75])
                iqrs.append(q75 - q25)
        print(
            f"{length:>6g} {np.median(iqrs):>26.3f} {np.mean(sways):>6.3f} {fails:>5d} "
            f"{np.median(exp):>6.0f}"
        )


def run_walks(lengths: list[float], n_walks: int, **options) -> None:
    from mjwalk.errors import PlanningError
    from mjwalk.gait.default import default_model
    from mjwalk.plan.grid import plan_grid
    from mjwalk.plan.hybrid import HybridPlanner
    from mjwalk.plan.occupancy import occupancy_grid
    from mjwalk.plan.options import PlannerOptions
    from mjwalk.world import load_workplace
    from mjwalk.world.generate import generate_hall

    hall = generate_hall(36, 10, kinds=("box",), seed=0)
    with tempfile.TemporaryDirectory() as tmp:
        wp = load_workplace(hall.write(Path(tmp) / "hall36.xml"), cache=False)
    model = default_model()
    grid8 = occupancy_grid(wp)
    rng = np.random.default_rng(7)
    print(f"\n(b) walk-length scaling, 36 x 10 m hall, {len(wp.obstacles)} boxes, {n_walks} walks")
    print(
        f"{'L [m]':>6} {'hyb exp':>8} {'fail':>5} {'hyb ms':>8} {'grid ms':>8} {'ratio':>6} "
        f"{'grid exp':>8} {'len IQR/med':>11} {'sway':>6}"
    )
    warm = False
    for length in lengths:
        pairs = _pairs(hall, length, n_walks, rng)
        exp, times, gtimes, gexp, ratios, lens, sways, fails = [], [], [], [], [], [], [], 0
        for k, (a, b) in enumerate(pairs):
            planner = HybridPlanner(wp, b, model, PlannerOptions(**options))
            if not warm:
                planner.plan(a, np.random.default_rng(0))
                warm = True
            t0 = time.process_time()  # CPU time: other jobs on a loaded machine do not count
            try:
                w = planner.plan(a, np.random.default_rng(k))
            except PlanningError:
                fails += 1
                w = None
            t1 = time.process_time()
            route = plan_grid(wp, a, b, grid=grid8)
            t2 = time.process_time()
            gtimes.append(t2 - t1)
            gexp.append(route.meta["expansions"])
            if w is not None:
                exp.append(w.meta["expansions_all"])  # over all its searches
                times.append(t1 - t0)
                ratios.append((t1 - t0) / max(t2 - t1, 1e-6))
                lens.append(w.length / route.length)
                sways += [
                    sways_towards_stance(w.xy[s.start : s.end + 1], s.stance[:2])
                    for s in w.steps[1:]
                ]
        q25, q50, q75 = np.percentile(lens, [25, 50, 75]) if lens else (np.nan,) * 3
        print(
            f"{length:>6g} {np.median(exp) if exp else np.nan:>8.0f} {fails:>5d} "
            f"{1000 * np.median(times) if times else np.nan:>8.1f} "
            f"{1000 * np.median(gtimes):>8.1f} {np.median(ratios) if ratios else np.nan:>6.2f} "
            f"{np.median(gexp):>8.0f} {(q75 - q25) / q50:>11.3f} {np.mean(sways):>6.3f}"
        )
    print("  ratio: median of the paired hybrid/grid planning CPU times (prepared: the grid is")
    print("  built once; the hybrid's per-goal Dijkstra is in neither); hyb exp: over all of a")
    print("  walk's searches (those run dry or looping too). len: walk length over")
    print("  the grid route's length, its IQR over its median (the spread of the walks)")


def run_cycles(n: int) -> None:
    from mjwalk.cycle.simulate import simulate_cycles

    spec = ROOT / "scenes" / "assembly_station.toml"
    print(f"\n(c) simulate_cycles on {spec.name}, {n} cycles")
    for jobs in (1, 2):
        # warm-up of this many workers (joblib keeps them): each loads the models and the
        # compiled code once, seconds that 10 000 cycles do not notice but 200 do
        simulate_cycles(spec, 4 * jobs, seed=99, n_jobs=jobs)
        t0 = time.perf_counter()
        # as the CLI runs them: a run whose walk cannot be planned is recorded, not fatal
        out = simulate_cycles(spec, n, seed=0, n_jobs=jobs, on_error="record")
        dt = time.perf_counter() - t0
        failed = sum(r.error is not None for r in out)
        print(
            f"  {jobs} worker(s): {n / dt:.2f} cycles/s ({dt:.1f} s; {failed} of {n} runs "
            f"not plannable); 10 000 cycles: {10_000 / (n / dt) / 60:.1f} min"
        )


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", type=float, nargs="+", default=[10, 40, 100])
    ap.add_argument("--lengths", type=float, nargs="+", default=[2, 4, 8, 16, 32])
    ap.add_argument("--walks", type=int, default=20)
    ap.add_argument("--cycles", type=int, default=20)
    ap.add_argument("--skip-setup", action="store_true")
    ap.add_argument("--skip-walks", action="store_true")
    ap.add_argument("--skip-cycles", action="store_true")
    ap.add_argument("--skip-spread", action="store_true")
    ap.add_argument("--budget", type=int, help="max_expansions (default: the planner's)")
    ap.add_argument("--setup-one", nargs=2, help=argparse.SUPPRESS)
    ap.add_argument("--weight", type=float, help="heuristic_weight (default: the planner's)")
    ap.add_argument("--far-weight", type=float, help="far_weight (0: the search before issue 18)")
    ap.add_argument("--field-sway", action="store_true", help="PlannerOptions.field_sway")
    args = ap.parse_args()
    if args.setup_one:
        print(json.dumps(setup_one(float(args.setup_one[0]), args.setup_one[1])))
        return
    if not args.skip_setup:
        run_setup(args.sizes)
    if not args.skip_walks:
        opts = {} if args.weight is None else {"heuristic_weight": args.weight}
        if args.far_weight is not None:
            opts["far_weight"] = args.far_weight
        if args.budget is not None:
            opts["max_expansions"] = args.budget
        if args.field_sway:
            opts["field_sway"] = True
        run_walks(args.lengths, args.walks, **opts)
        if not args.skip_spread:
            run_spread([4, 8, 16, 32], 4, 10, **opts)
    if not args.skip_cycles:
        run_cycles(args.cycles)


if __name__ == "__main__":
    main()
