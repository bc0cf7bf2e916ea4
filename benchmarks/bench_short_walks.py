"""Short walks to a tight goal area: do they wander? (issues 3/4/7)

Run from the repository root: ``python3 benchmarks/bench_short_walks.py [--runs 100]``.

Plans ``--runs`` seeded walks (walk k from ``SeedSequence(seed).spawn``) with the hybrid A*
exactly as the assembly-cycle simulation plans them (``mjwalk.cycle.simulate``: goal area
``GOAL_TOLERANCE`` = 0.1 m, the cycle's body radius) in ``scenes/assembly_station.xml`` and
prints, per start/goal pair, the median and inter-quartile range of the walk length (metres),
the median number of steps and node expansions, how many walks end with a closing step
(``StepModel.sample_stop``) and how many plans failed:

* ``T5``: stand_rack2 -> stand_rack3 (1.1 m straight line), started exactly at stand_rack2;
* the station's other routes T1-T4 for comparison.

Target (issue 3/4/7): T5 median <= 1.5 m and IQR <= 0.5 m. The route T5 *as the cycle plays it*
(started where T4 ended, near but not at stand_rack2) is in the report of
``python3 -m mjwalk simulate scenes/assembly_station.toml --runs 50 --out DIR``.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from bench_planner import ROUTES  # the station routes T1..T5 (scenes/assembly_station.toml)

from mjwalk.cycle.simulate import GOAL_TOLERANCE
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import PlanningError
from mjwalk.gait.default import default_model, default_model_path
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.options import PlannerOptions
from mjwalk.world import load_workplace

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=100)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--routes", default="T5,T1,T2,T3,T4", help="comma-separated route names")
    args = ap.parse_args()
    spec = load_cycle_spec(ROOT / "scenes" / "assembly_station.toml")
    wp = load_workplace(ROOT / "scenes" / "assembly_station.xml")
    model = default_model()
    print(f"model {default_model_path().name}; goal area {GOAL_TOLERANCE} m, radius {spec.radius}")
    print(
        f"{'route':6}{'line [m]':>9}{'length 50th [m]':>16}{'IQR [m]':>9}{'q25':>7}{'q75':>7}"
        f"{'max':>7}{'steps':>7}{'expansions':>11}{'closing':>9}{'failed':>8}"
    )
    for name in args.routes.split(","):
        a, b = ROUTES[name]
        planner = HybridPlanner(
            wp, b, model, PlannerOptions(radius=spec.radius, goal_tolerance=GOAL_TOLERANCE)
        )
        streams = np.random.SeedSequence(args.seed).spawn(args.runs)
        walks, failed = [], 0
        for s in streams:
            try:
                walks.append(planner.plan(a, np.random.default_rng(s)))
            except PlanningError:
                failed += 1
        line = float(np.hypot(*(wp.point(b) - wp.point(a))))
        lengths = np.array([w.length for w in walks])
        q25, q50, q75 = np.percentile(lengths, [25, 50, 75])
        steps = np.median([len(w.steps) for w in walks])
        exp = np.median([w.meta["expansions"] for w in walks])
        closing = sum(bool(w.meta.get("closing_step")) for w in walks)
        print(
            f"{name:6}{line:9.2f}{q50:16.2f}{q75 - q25:9.2f}{q25:7.2f}{q75:7.2f}"
            f"{lengths.max():7.2f}{steps:7.0f}{exp:11.0f}{closing:9d}{failed:8d}"
        )


if __name__ == "__main__":
    main()
