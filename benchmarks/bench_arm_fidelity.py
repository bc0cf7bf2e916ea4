"""Does the humanoid's arm do what the reach model planned? Per reach of a cycle:

* how far the humanoid's hand end leaves the model's planned hand path (the trajectory's poses
  after the humanoid's joint ranges, forward kinematics in MuJoCo, against the model's own hand
  ends; the frame of the shoulder before the reach, metres);
* which arm joints the model's poses ask beyond their ranges (clipped when played back);
* the share of arm-task frames with a wrist joint at a range limit, and the hand error at the
  target.

Measured 2026-11-27 (``python benchmarks/bench_arm_fidelity.py``: scenes/assembly_station.toml,
seeds 0-2, 42 reaches). With the reach generator before that day's change (the hand hanging
from a supinated forearm, the elbow swung in): the hand left the planned path by median 52 mm,
max 155 mm; every reach asked the wrist beyond its flexion range, 18 beyond its deviation
range; wrist at a range limit in 16.5 % / 8.2 % of arm-task frames (flexion / deviation). After
(the wrist in its functional range, the elbow out, the hand along its approach): 0 mm, no
joint clipped, 0 % / 0 %; hand errors 0 both times.

Run from the repo root:  python benchmarks/bench_arm_fidelity.py [--cycle FILE] [--seeds N]
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter
from pathlib import Path

import mujoco
import numpy as np

import mjwalk.cycle.reaching as reaching
from mjwalk.arms.chain import arm_frames, arm_joint_angles, end_effector
from mjwalk.arms.reach import humanoid_arm
from mjwalk.conventions import side_prefix
from mjwalk.cycle.context import context_of
from mjwalk.cycle.simulate import simulate_cycle
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import MjwalkError

ROOT = Path(__file__).resolve().parents[1]


def path_deviation(ctx, q0: np.ndarray, side: str, directions: np.ndarray) -> tuple[float, list]:
    """Largest distance (m) of the humanoid's hand end from the model's planned hand ends over
    the trajectory's poses (shoulder frame of ``q0``, model size over the scale), and the joints
    those poses ask beyond their ranges."""
    m, jm = ctx.model, ctx.jointmap
    data = mujoco.MjData(m)
    data.qpos[:] = q0
    mujoco.mj_kinematics(m, data)
    ua = m.body(f"{jm.prefix}upper_arm_{side_prefix(side)}").id
    shoulder, frame = data.xpos[ua].copy(), data.xmat[ua].reshape(3, 3).copy()
    scale, lengths = humanoid_arm(ctx.reach_model_for(side), ctx.spec.stature)
    rows, clipped = arm_frames(
        q0, jm, arm_joint_angles(directions, side), side, np.linspace(0, 1, len(directions))
    )
    plan = end_effector(directions, lengths) / scale
    worst = 0.0
    for row, p in zip(rows, plan, strict=True):
        data.qpos[:] = row
        mujoco.mj_kinematics(m, data)
        tip = reaching.hand_tip(data, m, jm, side, lengths[2] / scale)
        worst = max(worst, float(np.linalg.norm(frame.T @ (tip - shoulder) - p)))
    return worst, clipped


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cycle", default=str(ROOT / "scenes" / "assembly_station.toml"))
    ap.add_argument("--seeds", type=int, default=3, help="cycles of seeds 0..N-1")
    args = ap.parse_args(argv)
    if args.seeds < 1:
        print(f"bench_arm_fidelity: error: --seeds must be >= 1, got {args.seeds}", file=sys.stderr)
        return 2
    try:
        ctx = context_of(load_cycle_spec(args.cycle))
    except MjwalkError as exc:
        print(f"bench_arm_fidelity: error: {exc}", file=sys.stderr)
        return 2
    real = reaching.reach_frames
    seen: list[tuple[float, list]] = []

    def spy(op, q0, target_w, approach_w, pace, side="left", face=None, **kw):
        out = real(op, q0, target_w, approach_w, pace, side, face, **kw)
        # a leaning reach's shoulder is not q0's (none at the station)
        if not kw.get("lowering", reaching.STANDING).lean:
            seen.append(path_deviation(op, q0, side, out[2].directions))
        return out

    reaching.reach_frames = spy
    at_limit: Counter = Counter()
    frames = 0
    errors = []
    try:
        for seed in range(args.seeds):
            r = simulate_cycle(ctx, seed, keep_timeline=True, collisions=False)
            tl, jm = r.timeline, r.timeline.jointmap
            hands = {a.task: a.hand for a in r.arms}
            errors += [a.hand_error for a in r.arms]
            for task in r.tasks:
                if task.index not in hands:
                    continue
                p = side_prefix("right" if hands[task.index] == "right" else "left")
                lo, hi = round(task.start * tl.fps), round(task.end * tl.fps)
                frames += hi - lo
                for joint in ("flex", "dev"):
                    name = f"wrist_{p}_{joint}"
                    v = tl.qpos[lo:hi, jm.adr(name)]
                    a, b = jm.limits(name)
                    at_limit[joint] += int(np.sum((v <= a + 1e-6) | (v >= b - 1e-6)))
    finally:
        reaching.reach_frames = real
    dev = np.array([d for d, _ in seen]) * 1000
    clipped = Counter(c for _, cs in seen for c in cs)
    print(f"{Path(args.cycle).name}, seeds 0-{args.seeds - 1}: {len(seen)} reaches")
    print(
        f"hand off the planned path, mm: median {np.median(dev):.0f}, "
        f"p90 {np.percentile(dev, 90):.0f}, max {dev.max():.0f}"
    )
    print(f"joints the model's poses ask beyond their ranges (reaches): {dict(clipped) or 'none'}")
    print(
        f"wrist at a range limit: flexion {at_limit['flex'] / max(frames, 1):.1%}, "
        f"deviation {at_limit['dev'] / max(frames, 1):.1%} of {frames} arm-task frames"
    )
    print(f"hand error at the target, mm: max {max(errors) * 1000:.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
