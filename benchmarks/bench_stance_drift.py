"""Stance-foot drift of planned walks played back (issue 5's leg test over many walks): the
share of walks whose stance foot's contact point (heel while flat or toes up, ball while flat
or heel up, by MuJoCo forward kinematics) drifts more than 1 cm over a stance, and the worst.

Run: python benchmarks/bench_stance_drift.py [--seeds 1-10] [--n 5] [--compare OLD_LEGS.py]

``--compare`` loads another version of ``mjwalk/body/legs.py`` (e.g. ``git show
REV:mjwalk/body/legs.py > /tmp/legs_old.py``) and measures it on the same walks.
"""

from __future__ import annotations

import argparse
import importlib.util
import sys
from pathlib import Path

import numpy as np
from bench_stance_lean import LEG_ROUTES as PLANNED_ROUTES  # tests/body/test_synthesis.py's routes

from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.footcheck import foot_points as _fk_feet
from mjwalk.body.legs.footcheck import stance_drift
from mjwalk.gait.default import default_model
from mjwalk.plan.walks import plan_walks
from mjwalk.world import load_workplace

ROOT = Path(__file__).parents[1]


def _load(path: str):
    spec = importlib.util.spec_from_file_location("legs_compare", path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # dataclasses look their module up
    spec.loader.exec_module(mod)
    return mod.legs_from_walk


def _step_drifts(walk, pts, pitch) -> list[float]:
    return [stance_drift(type("W", (), {"steps": [st]}), pts, pitch) for st in walk.steps]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", default="1-10", help="plan seeds, 'a-b' inclusive")
    ap.add_argument("--n", type=int, default=5, help="walks per route and seed")
    ap.add_argument("--compare", default=None, help="another legs.py to measure as well")
    a = ap.parse_args()
    s0, s1 = (int(x) for x in a.seeds.split("-"))
    model = default_model(progress=False)
    versions = {"this": legs_from_walk}
    if a.compare:
        versions["compare"] = _load(a.compare)
    worst = {k: [] for k in versions}
    for scene, start, goal in PLANNED_ROUTES:
        wp = load_workplace(ROOT / "scenes" / f"{scene}.xml")
        for seed in range(s0, s1 + 1):
            for j, walk in enumerate(plan_walks(wp, start, goal, model, n=a.n, seed=seed)):
                for name, fn in versions.items():
                    pts, pitch, _ = _fk_feet(fn(walk))
                    d = _step_drifts(walk, pts, pitch)
                    worst[name].append(max(d))
                    if max(d) > 0.01:
                        bad = [(k, round(float(x) * 100, 1)) for k, x in enumerate(d) if x > 0.01]
                        print(f"{name}: {scene} {start}->{goal} seed {seed} walk {j}: {bad} cm")
    for name, w in worst.items():
        w = np.array(w)
        print(
            f"{name}: {len(w)} walks, drift > 1 cm in {int((w > 0.01).sum())} "
            f"({100 * (w > 0.01).mean():.1f} %), > 5 cm in {int((w > 0.05).sum())}, "
            f"worst {100 * w.max():.1f} cm, median {100 * np.median(w):.2f} cm"
        )


if __name__ == "__main__":
    main()
