"""Humanoid-vs-scene contacts of planned walks played back (issue 5) and of simulated station
cycles (issues 7 and 45), by MuJoCo collision detection (feet count when > 1 cm into the floor).

Run: python benchmarks/bench_contacts.py [--walks 20] [--cycles 40] [--seeds 0] [--jobs 1]
     [--cycle scenes/assembly_station.toml ...]

Issue 45 (run 32 of seed 0: the left toes brushed rack 1's upright one frame before the walk's
last step landed, the foot coming in ~30 degrees off its heading; the planner now probes that
approach, ``mjwalk.plan.stepgeom.toe_approach_clear``), ``--walks 0 --cycles 100``, one process:
  station, ``--seeds 0 1 2 3 4`` (500 cycles): before 14 contacts in 11 runs (all a foot
  against rack1_frame_l, up to 2.1 cm deep; seed 0 run 32 and seed 3 run 83 checked frame by
  frame: one frame before the walk to rack 1 lands its last step); after 0.
  two-handed box (assembly_station_2h.toml), ``--seeds 0 1 2`` (300 cycles): 0 before and after.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from mjwalk.cycle.simulate import simulate_cycles
from mjwalk.gait.default import default_model
from mjwalk.plan.walks import plan_walks
from mjwalk.timeline import collision_report, timeline_from_walk
from mjwalk.world import load_workplace

SCENES = Path(__file__).parents[1] / "scenes"


def corridor(walks: int, seed: int) -> None:
    """Plan ``walks`` walks per corridor route and report those that touch the scene."""
    scene = SCENES / "corridor.xml"
    wp = load_workplace(scene)
    model = default_model(progress=False)
    paths = []
    for start, goal in (("entry", "door"), ("door", "exit")):
        paths += plan_walks(wp, start, goal, model, n=walks, seed=seed)
    t0 = time.perf_counter()
    bad = 0
    for k, w in enumerate(paths):
        c = collision_report(timeline_from_walk(w, scene))
        if c:
            bad += 1
            worst = max(c, key=lambda x: x.depth)
            print(
                f"  corridor walk {k}: {worst.body_part} / {worst.scene_geom} {worst.depth:.4f} m"
            )
    dt = time.perf_counter() - t0
    print(f"corridor: {bad} of {len(paths)} planned walks touch the scene ({dt:.1f} s)")


def cycles(spec: Path, runs: int, seed: int, jobs: int) -> tuple[int, int, int]:
    """Simulate ``runs`` cycles of ``spec`` from ``seed``; print each contact. Returns (cycles,
    runs with contacts, contacts)."""
    t0 = time.perf_counter()
    res = simulate_cycles(spec, runs=runs, seed=seed, n_jobs=jobs)
    dt = time.perf_counter() - t0
    total = 0
    for r in res:
        for c in r.collisions:
            total += 1
            print(
                f"  {spec.name} seed {seed} run {r.run}: t {c.time:.2f} s {c.body_part} / "
                f"{c.scene_geom} {c.depth:.4f}"
            )
    n = sum(1 for r in res if r.collisions)
    print(f"{spec.name} seed {seed}: {n} of {len(res)} runs with contacts, {total} ({dt:.1f} s)")
    backs = [a.step_back for r in res for a in r.arms]
    moved = [b for b in backs if b > 0]
    print(
        f"  reaches that stepped back to clear the scene (mjwalk.cycle.standoff): {len(moved)}"
        f" of {len(backs)}" + (f", largest {max(moved):.2f} m" if moved else ""),
        flush=True,
    )
    return len(res), n, total


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--walks", type=int, default=20, help="walks per corridor route (0: none)")
    ap.add_argument("--cycles", type=int, default=40, help="runs per cycle file and seed")
    ap.add_argument("--seed", type=int, default=None, help="one seed (the same as --seeds S)")
    ap.add_argument("--seeds", type=int, nargs="+", default=[0], help="seeds of the cycles")
    ap.add_argument(
        "--cycle",
        type=Path,
        nargs="+",
        default=[SCENES / "assembly_station.toml"],
        help="cycle files (default: the station)",
    )
    ap.add_argument("--jobs", type=int, default=1, help="processes for the cycles (-1: all)")
    a = ap.parse_args()
    seeds = [a.seed] if a.seed is not None else a.seeds
    if a.walks > 0:
        corridor(a.walks, seeds[0])
    done = bad = total = 0
    for spec in a.cycle:
        for seed in seeds:
            c, n, k = cycles(spec, a.cycles, seed, a.jobs)
            done, bad, total = done + c, bad + n, total + k
    print(f"all cycles: {bad} of {done} runs with contacts, {total} contacts")


if __name__ == "__main__":
    main()
