"""Capture vs reproduction: RULA of the shared raise-hand clips' own joint positions against
RULA of mjwalk's humanoid reproducing the same reaches.

For every clip (``bandai-raise-hand``, left and right arm; README in the shared data folder):

* capture: the clip's joints (Bandai BVH, mjwalk's BVH reader and forward kinematics, metres,
  z up) scored frame by frame over the raising movement (from rest to the first stop of the
  hand, :func:`mjwalk.arms.armrep.movement_span`, as bench_reach aligns it) by
  :func:`mjwalk.ergonomics.angles.angles_from_points` and RULA (the moving arm's side, no load);
  the clip's score is the movement's peak;
* reproduction: the station cycle's humanoid (1.75 m, standing, arms hanging: the clips' start
  posture) reaches with the same arm, through the cycle's own reach
  (:func:`mjwalk.cycle.reaching.reach_frames`: the default PCA + DCS reach model and its
  approach), for the clip's end hand position: the hand's end relative to the shoulder in the
  body frame of the clip's first frame, scaled by the humanoid's arm length over the clip's
  (geometric similarity, as mjwalk scales reach targets); scored the same way, joint positions
  by MuJoCo's forward kinematics (the wrist and forearm angles left out, as the capture has
  none). Its score is the movement's peak.

Printed: the share of clips whose capture and reproduction RULA agree within one point (the
issue's criterion: >= 80 %), exactly, and the same for the upper-arm part score alone, with the
mean difference (reproduction minus capture) and the RULA of both by side.

Measured 2026-12-01 (``python benchmarks/bench_ergonomics.py --data /work/shared/data``, all
512 clips, 71 s): RULA within one point on 90.4 % of clips (criterion >= 80 %), equal on
45.3 %, mean difference (reproduction - capture) -0.42; the upper-arm score alone within one
point on 77.0 %, equal on 41.0 %, mean +0.21. Capture RULA median 4 (range 2-7: the clips' own
trunk and neck lean in), reproduction median 3 (range 3-4: the humanoid stands upright). Many
clips raise the hand in front with the elbow flexed and the upper arm low, where the reach
model raises the upper arm further: the upper-arm score is where the two differ most.

Run from the repo root:  python benchmarks/bench_ergonomics.py --data ../shared/data
    [--max-clips N]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

#: Bandai joints -> the points of mjwalk.ergonomics.angles.
BANDAI = {
    "pelvis": "Hips", "neck": "Neck", "head": "Head", "shoulder_l": "UpperArm_L",
    "shoulder_r": "UpperArm_R", "elbow_l": "LowerArm_L", "elbow_r": "LowerArm_R",
    "wrist_l": "Hand_L", "wrist_r": "Hand_R", "hip_l": "UpperLeg_L", "hip_r": "UpperLeg_R",
    "knee_l": "LowerLeg_L", "knee_r": "LowerLeg_R", "ankle_l": "Foot_L", "ankle_r": "Foot_R",
}  # fmt: skip


def find_data(arg: str | None) -> Path | None:
    """The raise-hand folder: ``--data``, ``$MJWALK_SHARED_DATA`` or ../shared/data (the folder
    itself or one holding ``bandai-raise-hand/``)."""
    for cand in (arg, os.environ.get("MJWALK_SHARED_DATA"), str(ROOT.parent / "shared" / "data")):
        if not cand:
            continue
        p = Path(cand)
        for d in (p, p / "bandai-raise-hand"):
            if d.is_dir() and any(d.glob("*raise-up-*-hand*.bvh")):
                return d
    return None


def capture_scores(take, side: str) -> tuple[int, int, np.ndarray, np.ndarray, float]:
    """(peak RULA, peak upper-arm score, end hand rel. shoulder in the first frame's body frame,
    start hand likewise, clip arm length) of one clip's raising movement."""
    from mjwalk.arms.armcapture import arm_chain
    from mjwalk.arms.armrep import movement_span
    from mjwalk.ergonomics import rula
    from mjwalk.ergonomics.angles import angles_from_points

    chain = arm_chain(take, side, "bandai", hand=True)  # shoulder, elbow, wrist, hand end
    rel = chain[:, -1] - chain[:, 0]
    a, b = movement_span(rel, until=int(np.argmax(rel[:, 2])))
    pts = {k: take.joints[v][a : b + 1] for k, v in BANDAI.items()}
    ang = angles_from_points(pts)
    s = 0 if side == "left" else 1
    score = int(rula.rula(ang, s).max())
    ua = int(rula.part_scores(ang, s).upper_arm.max())
    yaw = float(take.pelvis_yaw[0])
    c, si = np.cos(-yaw), np.sin(-yaw)
    rz = np.array([[c, -si, 0.0], [si, c, 0.0], [0.0, 0.0, 1.0]])
    length = float(np.linalg.norm(np.diff(chain[a], axis=0), axis=1).sum())
    return score, ua, rz @ rel[b], rz @ rel[a], length


def reproduce(ctx, side: str, end_body: np.ndarray, clip_len: float) -> tuple[int, int]:
    """(peak RULA, peak upper-arm score) of the humanoid reaching the scaled end position."""
    import mujoco

    from mjwalk.arms.chain import arm_segment_lengths
    from mjwalk.cycle.poses import standing_pose
    from mjwalk.cycle.reaching import ReachPace, reach_frames
    from mjwalk.ergonomics import rula
    from mjwalk.ergonomics.angles import angles_from_qpos

    m, jm = ctx.model, ctx.jointmap
    q0 = standing_pose(ctx, 0.0, 0.0, 0.0)  # facing +x: body frame = world axes
    data = mujoco.MjData(m)
    data.qpos[:] = q0
    mujoco.mj_kinematics(m, data)
    tag = "l" if side == "left" else "r"
    shoulder = data.xpos[m.body(f"{jm.prefix}upper_arm_{tag}").id].copy()
    scale = arm_segment_lengths(ctx.spec.stature).sum() / clip_len
    target = shoulder + end_body * scale
    frames = reach_frames(ctx, q0, target, np.array([0.0, 0.0, -0.05]), ReachPace(0.2, 30.0), side)[
        0
    ]
    ang = angles_from_qpos(m, jm, frames)
    ang.wrist_flexion[:] = 0.0  # the capture has no hand orientation: score both alike
    ang.wrist_deviation[:] = 0.0
    ang.wrist_twist[:] = 0.0
    s = 0 if side == "left" else 1
    return int(rula.rula(ang, s).max()), int(rula.part_scores(ang, s).upper_arm.max())


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", help="shared data folder (or bandai-raise-hand itself)")
    ap.add_argument("--max-clips", type=int, default=None, help="clips per side (default all)")
    args = ap.parse_args(argv)
    data = find_data(args.data)
    if data is None:
        print("bench_ergonomics: no bandai-raise-hand clips found (--data)", file=sys.stderr)
        return 2
    from mjwalk.cycle.context import context_of
    from mjwalk.cycle.spec import load_cycle_spec
    from mjwalk.mocap.bvh import load_bvh

    ctx = context_of(load_cycle_spec(ROOT / "scenes" / "assembly_station.toml"))
    t0 = time.perf_counter()
    rows = []
    for side in ("left", "right"):
        files = sorted(data.glob(f"*raise-up-{side}-hand*.bvh"))[: args.max_clips]
        for f in files:
            take = load_bvh(f, "bandai")
            cap, cap_ua, end, _, length = capture_scores(take, side)
            rep, rep_ua = reproduce(ctx, side, end, length)
            rows.append((side, cap, rep, cap_ua, rep_ua))
    n = len(rows)
    d = np.array([r[2] - r[1] for r in rows])
    du = np.array([r[4] - r[3] for r in rows])
    print(f"{data}: {n} clips ({time.perf_counter() - t0:.0f} s)")
    print(
        f"RULA, reproduction vs capture: within one point {np.mean(np.abs(d) <= 1):.1%} of clips "
        f"(criterion >= 80 %), equal {np.mean(d == 0):.1%}, mean difference {d.mean():+.2f}"
    )
    print(
        f"upper-arm score: within one point {np.mean(np.abs(du) <= 1):.1%}, equal "
        f"{np.mean(du == 0):.1%}, mean difference {du.mean():+.2f}"
    )
    for side in ("left", "right"):
        sel = [r for r in rows if r[0] == side]
        if sel:
            cap = np.array([r[1] for r in sel])
            rep = np.array([r[2] for r in sel])
            near = np.mean(np.abs(rep - cap) <= 1)
            print(
                f"  {side}: {len(sel)} clips, RULA capture median {np.median(cap):.0f} "
                f"(range {cap.min()}-{cap.max()}), reproduction median {np.median(rep):.0f} "
                f"(range {rep.min()}-{rep.max()}); within one point {near:.1%}"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
