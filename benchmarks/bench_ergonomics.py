"""Capture vs reproduction: RULA and the continuous exposure angles (upper-arm elevation,
trunk flexion) of the shared raise-hand clips' own joint positions against those of mjwalk's
humanoid reproducing the same reaches.

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

Printed too (issue 49, deliverable 5): the angles :mod:`mjwalk.ergonomics.exposure` judges,
measured the same way on both, from rest to the reach's end (capture: the movement's last frame;
reproduction: the first frame of the hold): the moving arm's elevation from the vertical, its
angle from the trunk, and the trunk's flexion. Per measure the median absolute difference
(reproduction minus capture) with its interquartile range (P25-P75 of the absolute
differences) and the median signed difference, at the reach's end (one value per clip) and over
the whole reach (21 steps of normalised time per clip, pooled); then, per style, the arm's
elevation at the end and at rest.

Measured 2026-12-03 (same command, all 512 clips, 21 s): upper-arm elevation at the reach's end
5.9 deg (IQR 3.0-22.2), signed +3.2: the issue's target (<= 10 deg) is met; over the whole reach
10.3 (4.8-19.3), signed +5.8; the upper arm's angle from the trunk at the end 10.1 (6.3-23.7);
trunk flexion at the end 2.6 (1.7-3.7), over the reach 1.6 (0.8-2.6). Where they differ: the
feminine clips (a quarter of them, the upper quartile of the differences) raise the hand only to
about the shoulder's height with the elbow flexed and the upper arm low (median elevation 15 deg
at the end), where the reach model raises the upper arm to about 40 deg to put the hand at the
same point (the arm is redundant for a hand position; the model's choice, not a measuring
error); the other styles agree within 0-7 deg at the end. At rest the actors' arms hang
10-17 deg (medians by style) out from the vertical, the humanoid's 1-2 deg: that offset is most
of the whole-reach difference early in the movement. The actors lean back 2-6 deg while raising
the hand; the humanoid stands upright (trunk 0 deg). Elevation from the vertical and from the
trunk differ by the trunk's lean only, a few degrees here.

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
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
#: The moving arm.
Side = Literal["left", "right"]
#: The issue's target for the upper arm's elevation at the reach's end: median absolute
#: difference, reproduction vs capture, at most this many degrees (issue 49, deliverable 5).
ELEVATION_TARGET_DEG = 10.0
#: Seconds the reproduction holds the hand on the target (as before: the reach's end is the
#: first frame of this hold).
HOLD_S = 0.2
#: Steps of normalised time a reach is compared at (every 5 % of the movement).
N_TIME = 21

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


def capture_scores(take, side: Side) -> tuple[int, int, np.ndarray, np.ndarray, float]:
    """(peak RULA, peak upper-arm score, end hand rel. shoulder in the first frame's body frame,
    start hand likewise, clip arm length) of one clip's raising movement."""
    c = capture(take, side)
    assert c.end is not None and c.start is not None
    return c.rula, c.upper_arm, c.end, c.start, c.length


@dataclass
class Reach:
    """One raising movement, captured or reproduced: its peak RULA and upper-arm score, and
    per frame (from rest to the reach's end) the moving arm's elevation from the vertical
    (:attr:`mjwalk.ergonomics.angles.BodyAngles.upper_arm_elevation`, the angle
    :mod:`mjwalk.ergonomics.exposure` judges), its angle from the trunk's downward axis
    (``upper_arm_angle``, unsigned) and the trunk's flexion, degrees; for a capture also the
    end and start hand positions and the arm's length (``end``, ``start``, ``length``)."""

    rula: int
    upper_arm: int
    elevation: np.ndarray
    arm_to_trunk: np.ndarray
    trunk_flexion: np.ndarray
    end: np.ndarray | None = None
    start: np.ndarray | None = None
    length: float = 0.0


def _reach_of(ang, side: Side, **kw) -> Reach:
    """A :class:`Reach` of some frames' body angles, scored for the moving arm ``side``."""
    from mjwalk.ergonomics import rula

    s = 0 if side == "left" else 1
    return Reach(
        int(rula.rula(ang, s).max()),
        int(rula.part_scores(ang, s).upper_arm.max()),
        ang.upper_arm_elevation[:, s].copy(),
        np.abs(ang.upper_arm_angle[:, s]),
        ang.trunk_flexion.copy(),
        **kw,
    )


def capture(take, side: Side) -> Reach:
    """One clip's raising movement (from rest to the hand's first stop) as a :class:`Reach`."""
    from mjwalk.arms.armcapture import arm_chain
    from mjwalk.arms.armrep import movement_span
    from mjwalk.ergonomics.angles import angles_from_points

    chain = arm_chain(take, side, "bandai", hand=True)  # shoulder, elbow, wrist, hand end
    rel = chain[:, -1] - chain[:, 0]
    a, b = movement_span(rel, until=int(np.argmax(rel[:, 2])))
    pts = {k: take.joints[v][a : b + 1] for k, v in BANDAI.items()}
    ang = angles_from_points(pts)
    yaw = float(take.pelvis_yaw[0])
    c, si = np.cos(-yaw), np.sin(-yaw)
    rz = np.array([[c, -si, 0.0], [si, c, 0.0], [0.0, 0.0, 1.0]])
    length = float(np.linalg.norm(np.diff(chain[a], axis=0), axis=1).sum())
    return _reach_of(ang, side, end=rz @ rel[b], start=rz @ rel[a], length=length)


def reproduce(ctx, side: Side, end_body: np.ndarray, clip_len: float) -> tuple[int, int]:
    """(peak RULA, peak upper-arm score) of the humanoid reaching the scaled end position."""
    r = reproduction(ctx, side, end_body, clip_len)
    return r.rula, r.upper_arm


def reproduction(ctx, side: Side, end_body: np.ndarray, clip_len: float) -> Reach:
    """The humanoid reaching the scaled end position (module docstring) as a :class:`Reach`:
    scored over the reach, hold and return (the peaks), its angles from rest to the reach's
    end (the first frame of the hold)."""
    import mujoco

    from mjwalk.arms.chain import arm_segment_lengths
    from mjwalk.cycle.poses import standing_pose
    from mjwalk.cycle.reaching import ReachPace, reach_frames
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
    pace = ReachPace(HOLD_S, 30.0)
    frames = reach_frames(ctx, q0, target, np.array([0.0, 0.0, -0.05]), pace, side)[0]
    ang = angles_from_qpos(m, jm, frames)
    ang.wrist_flexion[:] = 0.0  # the capture has no hand orientation: score both alike
    ang.wrist_deviation[:] = 0.0
    ang.wrist_twist[:] = 0.0
    whole = _reach_of(ang, side)
    end = reach_end(frames, round(HOLD_S * pace.fps))
    out = _reach_of(ang.frames(slice(0, end + 1)), side)
    return Reach(whole.rula, whole.upper_arm, out.elevation, out.arm_to_trunk, out.trunk_flexion)


def reach_end(frames: np.ndarray, n_hold: int) -> int:
    """The reach's last frame: the first of the ``n_hold`` + 1 equal frames of the hold
    (:func:`mjwalk.cycle.reaching.reach_frames` repeats the reach's end pose); the frame
    before the return's first when none is found."""
    same = np.all(np.abs(np.diff(frames, axis=0)) < 1e-12, axis=1)  # frame k equals k + 1
    for k in range(len(same) - n_hold + 1):
        if same[k : k + n_hold].all():
            return k
    return len(frames) // 2


def resampled(x: np.ndarray, n: int = N_TIME) -> np.ndarray:
    """``x`` (F,) at ``n`` equal steps of normalised time from its first frame to its last
    (linear interpolation), so a capture and its reproduction of other lengths line up."""
    x = np.asarray(x, dtype=float)
    return np.interp(np.linspace(0.0, 1.0, n), np.linspace(0.0, 1.0, len(x)), x)


def differences(cap: Reach, rep: Reach) -> dict[str, np.ndarray]:
    """Reproduction minus capture, degrees: at the reach's end (one value) and over the whole
    reach (:data:`N_TIME` values at equal steps of normalised time) of the arm's elevation
    from the vertical, its angle from the trunk and the trunk's flexion."""
    out = {}
    for name in ("elevation", "arm_to_trunk", "trunk_flexion"):
        c, r = getattr(cap, name), getattr(rep, name)
        out[f"{name} end"] = np.array([r[-1] - c[-1]])
        out[f"{name} reach"] = resampled(r) - resampled(c)
    return out


def agreement(diffs: list[dict[str, np.ndarray]]) -> dict[str, dict[str, float]]:
    """Per measure, over all clips (and the reach's time steps, pooled): the median absolute
    difference, its interquartile range (P25, P75 of the absolute differences), the median
    signed difference and the number of values.

    Args:
        diffs: :func:`differences` of each clip.

    Returns:
        ``{measure: {"median", "p25", "p75", "signed", "n"}}``, degrees.
    """
    out = {}
    for key in diffs[0] if diffs else ():
        d = np.concatenate([x[key] for x in diffs])
        a = np.abs(d)
        p25, med, p75 = (float(v) for v in np.percentile(a, [25, 50, 75]))
        out[key] = {
            "median": med,
            "p25": p25,
            "p75": p75,
            "signed": float(np.median(d)),
            "n": len(d),
        }
    return out


def print_agreement(agree: dict[str, dict[str, float]]) -> None:
    """Print :func:`agreement`'s lines, the upper arm's end against the issue's target."""
    names = {
        "elevation": "upper-arm elevation (from the vertical)",
        "arm_to_trunk": "upper arm from the trunk",
        "trunk_flexion": "trunk flexion",
    }
    print(
        "angles, reproduction vs capture: median |difference| (IQR of |difference|), "
        "median signed difference, deg"
    )
    for key, v in agree.items():
        name, where = key.rsplit(" ", 1)
        target = ""
        if key == "elevation end":
            ok = "met" if v["median"] <= ELEVATION_TARGET_DEG else "NOT met"
            target = f"  (target <= {ELEVATION_TARGET_DEG:.0f}: {ok})"
        at = "at the reach's end" if where == "end" else "over the whole reach"
        print(
            f"  {names[name]}, {at}: {v['median']:.1f} ({v['p25']:.1f}-{v['p75']:.1f}), "
            f"signed {v['signed']:+.1f}, n {v['n']}{target}"
        )


def style_of(path: Path) -> str:
    """The clip's style from its file name (``..._raise-up-left-hand_<style>_001.bvh``)."""
    parts = path.stem.split("_")
    return parts[-2] if len(parts) >= 3 else "?"


def print_styles(by_style: dict[str, list[tuple[Reach, Reach]]]) -> None:
    """Per style: the upper arm's elevation at the reach's end (capture and reproduction
    medians, median |difference|), its elevation at rest (the movement's first frame) and the
    capture's elbow-driven share: where they differ, and why."""
    print("by style, upper-arm elevation from the vertical (medians, deg):")
    for style, pairs in sorted(by_style.items()):
        ce = np.array([c.elevation[-1] for c, _ in pairs])
        re_ = np.array([r.elevation[-1] for _, r in pairs])
        c0 = np.array([c.elevation[0] for c, _ in pairs])
        r0 = np.array([r.elevation[0] for _, r in pairs])
        print(f"  {style}: {len(pairs)} clips, at the end capture {np.median(ce):.1f}, "
              f"reproduction {np.median(re_):.1f}, |difference| {np.median(np.abs(re_ - ce)):.1f}; "
              f"at rest capture {np.median(c0):.1f}, reproduction {np.median(r0):.1f}")  # fmt: skip


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", help="shared data folder (or bandai-raise-hand itself)")
    ap.add_argument("--max-clips", type=int, default=None, help="clips per side (default all)")
    ap.add_argument("--stride", type=int, default=1, help="every STRIDE-th clip (default 1)")
    args = ap.parse_args(argv)
    if args.stride < 1 or (args.max_clips is not None and args.max_clips < 1):
        print("bench_ergonomics: --stride and --max-clips must be >= 1", file=sys.stderr)
        return 2
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
    diffs: list[dict[str, np.ndarray]] = []
    by_style: dict[str, list[tuple[Reach, Reach]]] = {}
    sides: tuple[Side, Side] = ("left", "right")
    for side in sides:
        files = sorted(data.glob(f"*raise-up-{side}-hand*.bvh"))[:: args.stride][: args.max_clips]
        for f in files:
            take = load_bvh(f, "bandai")
            c = capture(take, side)
            assert c.end is not None
            r = reproduction(ctx, side, c.end, c.length)
            rows.append((side, c.rula, r.rula, c.upper_arm, r.upper_arm))
            diffs.append(differences(c, r))
            by_style.setdefault(style_of(f), []).append((c, r))
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
    print_agreement(agreement(diffs))
    print_styles(by_style)
    return 0


if __name__ == "__main__":
    sys.exit(main())
