"""Where the legs of planned walks jump (a joint changing more than MAX_STEP_DEG between two
120 Hz samples), and whether the stance hip's rotation is behind it.

Run: PYTHONPATH=. python3 benchmarks/bench_leg_jumps.py [--seeds 0-5] [--n 5]

Walks: the leg tests' four routes (tests/body/test_synthesis.py PLANNED_ROUTES: three station
routes and the corridor), ``--n`` walks each for every seed in ``--seeds`` (seed 0 is the leg
tests' fixture: its walk k is the fixture's walk k, route-major). For every step of every walk, the
largest change of any :func:`~mjwalk.body.legs.legs_from_walk` joint angle or of the pelvis yaw
between two samples; for the steps above MAX_STEP_DEG: the joint, whether it belongs to the
stance or the swing leg, the step phase of the jump, the joint's angle just before it, the step
length and the pelvis turn over the step, the stance hip's rotation demand (the largest
``|pelvis yaw - stance foot yaw|`` over the step, which the upright stance leg takes as hip
rotation; ROM_DEG["hip_rot"], AAOS: 45 deg each way) and the swing hip's distance from its
lift-off foot at toe-off. Then how many steps demand more hip rotation than the range and how
many of those jump, and, as a control, the jumps of the jumping walks with the leg
synthesis's spin turns switched off (:func:`mjwalk.body.legs.spin.spin_turns`: its handling
of a pelvis turning further than the stance hip can rotate; unchanged jumps mean that handling
is not what jumps).
"""

from __future__ import annotations

import argparse
from pathlib import Path
from unittest import mock

import numpy as np
from bench_stance_lean import LEG_ROUTES  # tests/body/test_synthesis.py PLANNED_ROUTES

from mjwalk.anthropometry import ROM_DEG, leg_geometry
from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.steps import TOE_OFF
from mjwalk.gait.default import default_model
from mjwalk.plan.walks import plan_walks
from mjwalk.world import load_workplace

ROOT = Path(__file__).resolve().parents[1]
#: tests/body/test_synthesis.py MAX_STEP_DEG: the largest leg-joint change between two 120 Hz
#: samples.
MAX_STEP_DEG = 6.0


def _wrap(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def step_jumps(walk, legs) -> list[dict]:
    """Per step of ``walk``: its largest per-sample change (degrees) of any leg joint or the
    pelvis yaw, where and in which joint, and the step's geometry (see the module doc)."""
    geom = leg_geometry()
    series = {**legs.angles, "pelvis_yaw": np.unwrap(legs.yaw)}
    diffs = {k: np.degrees(np.abs(np.diff(v))) for k, v in series.items()}
    out = []
    for k, st in enumerate(walk.steps):
        a, b = st.start, st.end
        jump, name = max((float(d[a:b].max()), n) for n, d in diffs.items())
        i = a + int(np.argmax(diffs[name][a:b]))
        swing = "l" if st.side == "left" else "r"
        yaw = walk.yaw[a : b + 1]
        demand = np.degrees(np.abs(_wrap(yaw - st.stance[2]))).max()
        lift_dist = np.nan
        if k > 0:  # the swing foot lifts off the previous step's stance footprint
            ito = a + round(TOE_OFF * (b - a))
            sgn = 1.0 if swing == "l" else -1.0
            y = walk.yaw[ito]
            hip = walk.xy[ito] + sgn * geom.hip_y * np.array([-np.sin(y), np.cos(y)])
            lift_dist = float(np.linalg.norm(np.asarray(walk.steps[k - 1].stance[:2]) - hip))
        role = "pelvis" if name == "pelvis_yaw" else "swing" if f"_{swing}" in name else "stance"
        out.append(
            {
                "step": k,
                "jump": jump,
                "joint": name,
                "role": role,
                "phase": (i - a) / (b - a),
                "before": float(np.degrees(series[name][i])),
                "length": float(np.linalg.norm(walk.xy[b] - walk.xy[a])),
                "turn": float(np.degrees(abs(np.unwrap(yaw)[-1] - np.unwrap(yaw)[0]))),
                "hip_rot_demand": float(demand),
                "lift_dist": lift_dist,
            }
        )
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", default="0-5", help="plan seeds, 'a-b' inclusive")
    ap.add_argument("--n", type=int, default=5, help="walks per route and seed")
    a = ap.parse_args()
    s0, s1 = (int(x) for x in a.seeds.split("-"))
    model = default_model(progress=False)
    rot_range = max(abs(x) for x in ROM_DEG["hip_rot"])
    steps, jumpy = [], {}
    for seed in range(s0, s1 + 1):
        k = 0
        for scene, start, goal in LEG_ROUTES:
            wp = load_workplace(ROOT / "scenes" / f"{scene}.xml")
            for walk in plan_walks(wp, start, goal, model, n=a.n, seed=seed):
                rows = step_jumps(walk, legs_from_walk(walk))
                for r in rows:
                    r.update(seed=seed, walk=k, route=f"{scene} {start}->{goal}")
                steps += rows
                if any(r["jump"] > MAX_STEP_DEG for r in rows):
                    jumpy[(seed, k)] = walk
                k += 1
    bad = [r for r in steps if r["jump"] > MAX_STEP_DEG]
    print(f"steps whose legs jump more than {MAX_STEP_DEG} deg between two samples:")
    print(
        "seed walk step  jump  joint          leg     phase  before  length  turn  "
        "hip-rot demand  lift-off dist"
    )
    for r in bad:
        print(
            f"{r['seed']:4d} {r['walk']:4d} {r['step']:4d} {r['jump']:5.1f}  {r['joint']:13s}  "
            f"{r['role']:6s}  {r['phase']:5.2f}  {r['before']:6.1f}  {r['length']:5.2f} m "
            f"{r['turn']:5.1f}  {r['hip_rot_demand']:9.1f} deg  {r['lift_dist']:8.3f} m"
        )
    n_walks = len({(r["seed"], r["walk"]) for r in steps})
    over = [r for r in steps if r["hip_rot_demand"] > rot_range]
    print(
        f"\n{n_walks} walks, {len(steps)} steps: {len(bad)} steps in {len(jumpy)} walks jump; "
        f"{len(over)} steps in {len({(r['seed'], r['walk']) for r in over})} walks demand more "
        f"stance hip rotation than the range ({rot_range:.0f} deg), "
        f"{sum(r['jump'] > MAX_STEP_DEG for r in over)} of them jump"
    )
    demand = np.array([r["hip_rot_demand"] for r in steps])
    q50, q90, q99 = np.percentile(demand, [50, 90, 99])
    print(
        f"hip-rotation demand per step: median {q50:.1f}, 90th percentile {q90:.1f}, "
        f"99th {q99:.1f}, max {demand.max():.1f} deg; of the jumping steps: "
        + ", ".join(f"{r['hip_rot_demand']:.0f}" for r in bad)
    )
    print("\ncontrol: the jumping walks' largest jump with and without the spin turns")
    for (seed, k), walk in jumpy.items():
        with_spin = max(r["jump"] for r in step_jumps(walk, legs_from_walk(walk)))
        with mock.patch("mjwalk.body.legs.synthesis.spin_turns", lambda *x, **kw: {}):
            without = max(r["jump"] for r in step_jumps(walk, legs_from_walk(walk)))
        print(f"  seed {seed} walk {k}: {with_spin:.1f} deg with, {without:.1f} deg without")


if __name__ == "__main__":
    main()
