"""Humanoid-vs-scene contacts of planned walks played back (issue 5) and of simulated station
cycles (issue 7), by MuJoCo collision detection (feet count when > 1 cm into the floor).

Run: python benchmarks/bench_contacts.py [--walks 20] [--cycles 40] [--seed 0] [--jobs 1]
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


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--walks", type=int, default=20, help="walks per corridor route")
    ap.add_argument("--cycles", type=int, default=40)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--jobs", type=int, default=1, help="processes for the cycles (-1: all)")
    a = ap.parse_args()
    scene = SCENES / "corridor.xml"
    wp = load_workplace(scene)
    model = default_model(progress=False)
    walks = []
    for start, goal in (("entry", "door"), ("door", "exit")):
        walks += plan_walks(wp, start, goal, model, n=a.walks, seed=a.seed)
    t0 = time.perf_counter()
    bad = 0
    for k, w in enumerate(walks):
        c = collision_report(timeline_from_walk(w, scene))
        if c:
            bad += 1
            worst = max(c, key=lambda x: x.depth)
            print(
                f"  corridor walk {k}: {worst.body_part} / {worst.scene_geom} {worst.depth:.4f} m"
            )
    dt = time.perf_counter() - t0
    print(f"corridor: {bad} of {len(walks)} planned walks touch the scene ({dt:.1f} s)")
    t0 = time.perf_counter()
    res = simulate_cycles(
        SCENES / "assembly_station.toml", runs=a.cycles, seed=a.seed, n_jobs=a.jobs
    )
    dt = time.perf_counter() - t0
    for r in res:
        for c in r.collisions:
            print(
                f"  cycle run {r.run}: t {c.time:.2f} s {c.body_part} / {c.scene_geom} "
                f"{c.depth:.4f}"
            )
    n = sum(1 for r in res if r.collisions)
    print(f"station cycles: {n} of {len(res)} runs with contacts ({dt:.1f} s)")
    backs = [a.step_back for r in res for a in r.arms]
    moved = [b for b in backs if b > 0]
    print(
        f"  reaches that stepped back to clear the scene (mjwalk.cycle.standoff): {len(moved)}"
        f" of {len(backs)}" + (f", largest {max(moved):.2f} m" if moved else "")
    )


if __name__ == "__main__":
    main()
