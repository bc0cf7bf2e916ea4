"""What the stance-lean check (:func:`mjwalk.plan.stepcheck.stance_lean_ok`) changes in planned
walks: the same seeded walks planned with and without it, in the same process.

Run: PYTHONPATH=. python3 benchmarks/bench_stance_lean.py [--seeds 0-10] [--n 5] [--extra 10]

Walk sets: the leg tests' four routes (tests/body/test_synthesis.py PLANNED_ROUTES: three station
routes and the corridor) for every seed in ``--seeds`` with ``--n`` walks each (seed 0 is the leg
tests' fixture, seeds 1-10 benchmarks/bench_stance_drift.py's set), and ``--extra`` walks
(seed 0) on each of three more routes in three scenes (open floor, corridor to the door, the
station's 8 m walk). For each set: walks that differ (any pelvis sample more than 1e-9 m
apart, or another sample count), planning failures, median and inter-quartile range of the
walk length, node expansions and the planning time ratio (with / without, the plans
interleaved). Without the
check, the number of planned steps that the check would refuse (its stance leg leaning out of
the ankle's or hip's range) is counted as well.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from mjwalk.errors import PlanningError
from mjwalk.gait.default import default_model
from mjwalk.plan import slots, stepcheck
from mjwalk.plan.hybrid import HybridPlanner
from mjwalk.plan.params import KernelParams
from mjwalk.world import load_workplace

ROOT = Path(__file__).resolve().parents[1]
LEG_ROUTES = (  # tests/body/test_synthesis.py PLANNED_ROUTES
    ("assembly_station", "stand_rack2", "stand_car1"),
    ("assembly_station", "stand_car1", "stand_rack3"),
    ("assembly_station", "stand_rack1", "stand_car2"),
    ("corridor", "entry", "exit"),
)
EXTRA_ROUTES = (
    ("open_floor", "west", "east"),
    ("corridor", "entry", "door"),
    ("assembly_station", "-3.6,-1.0", "3.6,0.6"),
)


class _NoLeanParams(KernelParams):
    """The kernel vectors without the stance-lean check (its slots NaN: the kernel skips it)."""

    def vectors(self, stature: float = 1.75):
        par, ipar = super().vectors(stature)
        par[slots.P_HIP_Y] = math.nan
        return par, ipar


class _NoLean(HybridPlanner):
    """The planner without the stance-lean check."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        p = self.params
        self.params = _NoLeanParams(p.options, p.goal, p.discs, p.grid, p.walk_field, p.distance)


def refused_steps(walk, par) -> int:
    """Steps of ``walk`` whose stance leg leans out of range at any 120 Hz pelvis sample
    (:func:`~mjwalk.plan.stepcheck.stance_lean` on the walk's own stance foot and pelvis)."""
    out = 0
    for st in walk.steps:
        sl = slice(st.start, st.end + 1)
        lean = stepcheck.stance_lean(walk.xy[sl], walk.yaw[sl], st.stance, st.side == "right", par)
        out += not stepcheck.lean_in_range(*lean, par)
    return out


def _length(walk) -> float:
    return float(np.linalg.norm(np.diff(walk.xy, axis=0), axis=1).sum())


def run_set(name, jobs, model) -> None:
    """Plan ``jobs`` [(workplace, start, goal, seed, n)] with and without the check."""
    res = {"with": [], "without": []}
    secs = {"with": 0.0, "without": 0.0}
    par = None
    for wp, start, goal, seed, n in jobs:
        planners = {"with": HybridPlanner(wp, goal, model), "without": _NoLean(wp, goal, model)}
        par = planners["with"].params.vectors()[0]
        streams = np.random.SeedSequence(seed).spawn(n)
        for s in streams:
            for key, pl in planners.items():
                t0 = time.perf_counter()
                try:
                    walk = pl.plan(start, np.random.default_rng(s))
                except PlanningError:
                    walk = None
                secs[key] += time.perf_counter() - t0
                res[key].append(walk)
    a, b = res["with"], res["without"]
    changed = sum(
        x is None or y is None or x.xy.shape != y.xy.shape or np.abs(x.xy - y.xy).max() > 1e-9
        for x, y in zip(a, b, strict=True)
    )
    direct = sum(
        x is not None and y is not None and refused_steps(y, par) > 0
        for x, y in zip(a, b, strict=True)
    )
    print(
        f"\n{name}: {len(a)} walks, {changed} changed by the check ({direct} of them planned "
        "without it have a step it refuses; the others differ because a successor refused "
        "during the search changes the search's course)"
    )
    for key, walks in res.items():
        ok = [w for w in walks if w is not None]
        lengths = np.array([_length(w) for w in ok])
        q25, q50, q75 = np.percentile(lengths, [25, 50, 75])
        refused = sum(refused_steps(w, par) for w in ok)
        steps = sum(len(w.steps) for w in ok)
        expansions = sum(w.meta["expansions"] for w in ok)
        print(
            f"  {key:8s} check: failures {len(walks) - len(ok)}, length median {q50:.3f} m, "
            f"IQR {q75 - q25:.3f} m; steps the check refuses {refused} of {steps}; "
            f"expansions {expansions}; planning {secs[key]:.1f} s"
        )
    print(f"  planning time ratio with/without: {secs['with'] / secs['without']:.3f}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", default="0-10", help="seeds of the leg routes, 'a-b' inclusive")
    ap.add_argument("--n", type=int, default=5, help="walks per leg route and seed")
    ap.add_argument("--extra", type=int, default=10, help="walks per extra route (seed 0)")
    a = ap.parse_args()
    s0, s1 = (int(x) for x in a.seeds.split("-"))
    model = default_model(progress=False)
    scenes = {}
    warm = load_workplace(ROOT / "scenes" / "open_floor.xml")  # compile both before timing
    for cls in (HybridPlanner, _NoLean):
        cls(warm, "east", model).plan("west", np.random.default_rng(0))

    def wp(scene):
        if scene not in scenes:
            scenes[scene] = load_workplace(ROOT / "scenes" / f"{scene}.xml")
        return scenes[scene]

    fixture = [(wp(sc), st, go, 0, a.n) for sc, st, go in LEG_ROUTES] if s0 == 0 else []
    if fixture:
        run_set("leg-test fixture (seed 0)", fixture, model)
    rest = [(wp(sc), st, go, seed, a.n) for seed in range(max(s0, 1), s1 + 1)
            for sc, st, go in LEG_ROUTES]  # fmt: skip
    if rest:
        run_set(f"leg routes, seeds {max(s0, 1)}-{s1}", rest, model)
    if a.extra:
        run_set(
            "three more scenes (seed 0)",
            [(wp(sc), st, go, 0, a.extra) for sc, st, go in EXTRA_ROUTES],
            model,
        )


if __name__ == "__main__":
    main()
