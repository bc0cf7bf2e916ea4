"""Crossed steps: how often a landing foot crosses over the stance foot, planned against capture.

Run from the repository root:
``python benchmarks/bench_crossover.py [--cycles N] [--data DIR] [--virtual SUBJECTS]``
(``--data``: the bandai-walk folder, default ``../shared/data/bandai-walk`` or
``$MJWALK_SHARED_DATA/bandai-walk``; ``--cycles 0`` skips the planned walks; ``--virtual 0`` skips
the virtual corpus the default step model trains on).

A step is *crossed* when its landing foot lands on the stance foot's far side: its lateral offset
from the stance foot, in the frame of the two feet's mean yaw and signed toward the swing side
(left of the stance foot for a left step), is below 0. Its turn is the landing foot's yaw minus
the stance foot's: toward the swing side a *step turn* (people widen the base), toward the stance
foot a *spin turn* (a crossover is normal there: Hase & Stein 1999; Taylor et al. 2005); under
5 deg *straight*. Steps are first (gait initiation), last (termination) or middle. Capture steps
come from the project's own segmentation (``gait/segment.py``) of the Bandai clips and of the
virtual corpus (``generate_corpus(12, 0)``, what the default model trains on); planned steps from
``simulate_cycle`` of the assembly station, runs 0..N-1, seed 0. Three frames are printed: the
feet's mean yaw (the issue's measure; the capture's ankle->toe yaws are noisy and toe-out puts
most steps outside the 5 deg "straight" band), the step's pelvis chord with the stride turn
(half the landing foot's yaw change since it last stood: toe-out cancels), and the pelvis's
heading at the step's end.

Measured (``python3 benchmarks/bench_crossover.py``, 100 cycles), crossed share, pelvis chord
and stride turn (all / first / middle / last; straight, step turn, spin turn):
- capture, Bandai, 3660 steps: 11.9 / 6.2 / 12.0 / 11.4 % (5 of 44); 4.8 % (p1 -2.0 cm),
  3.2 % (p1 -2.5 cm), 43.6 % (p1 -21.7 cm). Without the catwalk-like feminine style the
  straight and step-turn steps cross 0.0-2.0 %.
- virtual corpus the default model trains on, 25037 steps: 13.2 / 4.0 / 15.9 / 0.0 %;
  0.2 %, 1.3 %, 61.4 %.
- planned on main (0d9e8e6), 4028 steps: 11.8 / 5.9 / 11.7 / 18.3 %;
  7.7 % (last steps 10.9 %), 2.3 % (last 7.7 %), 30.3 %; feet's mean yaw: 9.6 / 0 / 9.6 / 19.3 %.
- planned with a step-check rule tried and not merged (a step may cross the stance foot no
  farther than the capture's p1 for its turn type: 2.0 / 2.5 / 21.7 cm), 3982 steps:
  11.2 / 6.4 / 11.0 / 16.4 %; 5.5 % (last 7.5 %, p1 -1.7 cm),
  1.9 % (last 5.6 %), 30.5 %; feet's mean yaw: 9.0 / 0.1 / 9.1 / 17.3 %.
Only the planned last steps cross clearly more than the step model's training data (0 of its
2447 terminations cross); the Bandai clips' last cut steps (44) are full steps, not closing
steps, and cannot settle it. Refusing closing steps whose feet end crossed in their own mean
yaw (tried: 19.3 -> 5.9 % of last steps) made station run 93's T4 walk loop (2.45x grid A*):
not kept. The rule itself was not merged either: it left the last steps at 16.4 % and took
the own humanoid's T4 p99 over grid A* from 1.24 to 1.35 (one wider arc, 1.37).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np

DATA = (
    Path(os.environ["MJWALK_SHARED_DATA"]) / "bandai-walk"
    if os.environ.get("MJWALK_SHARED_DATA")
    else Path(__file__).resolve().parents[2] / "shared" / "data" / "bandai-walk"
)
STRAIGHT_DEG = 5.0
TURN_BINS = (5.0, 15.0, 30.0, 45.0, 90.0, 180.0)


def wrap(a):
    """Angles wrapped into [-pi, pi)."""
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


def step_table(sides, foot, stance, frame=None, turn=None) -> tuple[np.ndarray, np.ndarray]:
    """(lateral offset toward the swing side, metres; turn toward the swing side, degrees) per step.

    ``foot`` and ``stance``: (N, 3) x, y (metres) and yaw (radians from +x, CCW). ``frame``: the
    heading (radians) the lateral offset is measured across, default the feet's mean yaw; ``turn``:
    the turn (radians, CCW), default the landing foot's yaw minus the stance foot's.
    """
    foot, stance = np.asarray(foot, float), np.asarray(stance, float)
    sign = np.where(np.asarray(sides) == "left", 1.0, -1.0)
    raw = wrap(foot[:, 2] - stance[:, 2])
    mean = stance[:, 2] + 0.5 * raw if frame is None else np.asarray(frame, float)
    turn = raw if turn is None else np.asarray(turn, float)
    d = foot[:, :2] - stance[:, :2]
    lateral = -np.sin(mean) * d[:, 0] + np.cos(mean) * d[:, 1]
    return sign * lateral, sign * np.degrees(turn)


def report(name: str, lat: np.ndarray, turn: np.ndarray, where: np.ndarray) -> None:
    """Print the crossed-step figures of one source."""
    n = lat.size
    crossed = lat < 0

    def pct(m: np.ndarray) -> str:
        share = 100 * crossed[m].mean() if m.any() else np.nan
        return f"{crossed[m].sum():4d}/{m.sum():5d} {share:5.1f} %"

    print(f"\n{name}: {pct(np.ones(n, bool))} crossed")
    for w in ("first", "middle", "last"):
        print(f"  {w:7s} {pct(where == w)}")
    straight = np.abs(turn) < STRAIGHT_DEG
    kinds = {"straight": straight, "step turn": ~straight & (turn > 0)}
    kinds["spin turn"] = ~straight & (turn < 0)
    for k, m in kinds.items():
        mid, last = m & (where == "middle"), m & (where == "last")
        c = lat[m & crossed]
        q = np.percentile(lat[m], [1, 5]) * 100 if m.any() else (np.nan, np.nan)
        med = f"{100 * np.median(c):5.1f}" if c.size else "  -  "
        print(
            f"  {k:9s} all {pct(m)}  middle {pct(mid)}  last {pct(last)}  crossed median "
            f"{med} cm; lateral p1 {q[0]:5.1f} p5 {q[1]:5.1f} cm"
        )
    lo = 0.0
    for hi in TURN_BINS:
        m = (np.abs(turn) >= lo) & (np.abs(turn) < hi)
        s, p = m & (turn > 0), m & (turn < 0)
        print(f"  |turn| {lo:3.0f}-{hi:3.0f} deg: step turn {pct(s)}  spin turn {pct(p)}")
        lo = hi
    c = lat[crossed] * 100
    if c.size:
        q = np.percentile(c, [50, 10])
        print(
            f"  crossed: median {q[0]:.1f} cm, p10 {q[1]:.1f} cm, beyond 5 cm "
            f"{(c < -5).sum()} ({100 * (c < -5).mean() * crossed.mean():.1f} % of all)"
        )


def stride_turn(foot, stance, prev_stance) -> np.ndarray:
    """Turn of the line of progression over each step, radians CCW: half the landing foot's yaw
    change since it last stood (the previous step's stance foot), so toe-out cancels; the
    landing foot's yaw minus the stance foot's where there is no previous step (NaN rows)."""
    half = 0.5 * wrap(foot[:, 2] - prev_stance[:, 2])
    return np.where(np.isnan(half), wrap(foot[:, 2] - stance[:, 2]), half)


def capture_steps(steps) -> tuple:
    """Sides, feet (step frame turned to x forward, y left, yaw from +x), first/middle/last,
    pelvis chord heading and stride turn of segmented :class:`Step` s (same step frame)."""
    sides = np.array([s.side for s in steps])
    # Step frame: x right, y forward, yaw CCW from +y -> x forward, y left, yaw from +x.
    f = np.array([[s.footprint[1], -s.footprint[0], s.footprint[2]] for s in steps])
    st = np.array([[s.stance[1], -s.stance[0], s.stance[2]] for s in steps])
    chord = np.array([np.arctan2(-s.pelvis[-1, 0], s.pelvis[-1, 1]) for s in steps])
    facing = np.array([s.yaw[-1] for s in steps])
    # The previous step's stance foot in this step's frame: both frames' yaw0 from the pelvis
    # yaw of the step's first sample (``yaw`` is relative to it; the take's own is not kept).
    key = {(s.take, s.index): i for i, s in enumerate(steps)}
    prev = np.full_like(st, np.nan)
    for i, s in enumerate(steps):
        j = key.get((s.take, s.index - 1))
        if j is not None and steps[j].side != s.side:
            y0 = steps[j].meta["yaw0"] - s.meta["yaw0"]
            prev[i, 2] = steps[j].stance[2] + y0
    where = np.array(
        [
            "first"
            if s.meta.get("initiation")
            else "last"
            if s.meta.get("termination")
            else "middle"
            for s in steps
        ]
    )
    return sides, f, st, where, chord, stride_turn(f, st, prev), facing


def segment_with_yaw(takes) -> list:
    """Segmented steps of ``takes``, each with its first sample's pelvis yaw in ``meta["yaw0"]``."""
    from mjwalk.gait.segment import segment_takes

    pelvis_yaw = {t.name: t.pelvis_yaw for t in takes}
    steps, _ = segment_takes(takes)
    for s in steps:
        s.meta["yaw0"] = float(pelvis_yaw[s.take][s.meta["start_frame"]])
    return steps


def planned_steps(cycles: int) -> tuple:
    """Sides, feet and first/middle/last of the station cycle's planned walks, runs 0..N-1."""
    from mjwalk.cycle.context import prepare
    from mjwalk.cycle.seeding import run_generator
    from mjwalk.cycle.simulate import simulate_cycle
    from mjwalk.cycle.spec import load_cycle_spec

    ctx = prepare(load_cycle_spec("scenes/assembly_station.toml"))
    sides, f, st, where, chord, prev, facing = [], [], [], [], [], [], []
    for k in range(cycles):
        r = simulate_cycle(ctx, run_generator(0, k), run=k, collisions=False, ergonomics=False)
        for w in r.walks:
            steps, xy = w.path.steps, w.path.xy
            for i, s in enumerate(steps):
                sides.append(s.side)
                f.append(s.foot)
                st.append(s.stance)
                where.append("first" if i == 0 else "last" if i == len(steps) - 1 else "middle")
                d = xy[s.end] - xy[s.start]
                chord.append(np.arctan2(d[1], d[0]))
                facing.append(w.path.yaw[s.end])
                prev.append(steps[i - 1].stance if i else np.full(3, np.nan))
    f, st = np.array(f), np.array(st)
    turn = stride_turn(f, st, np.array(prev))
    return np.array(sides), f, st, np.array(where), np.array(chord), turn, np.array(facing)


def report_all(name: str, sides, f, st, where, chord, turn, facing) -> None:
    """The figures of one source in the feet's mean-yaw frame with the feet's yaw difference as
    the turn (the issue's measure), across the pelvis chord with the stride turn, and (last
    steps: the stance the walker stands in) across the pelvis's heading at the step's end."""
    report(
        f"{name}, feet's mean yaw, turn = landing - stance yaw", *step_table(sides, f, st), where
    )
    lat, tr = step_table(sides, f, st, chord, turn)
    report(f"{name}, across the pelvis chord, stride turn", lat, tr, where)
    lat, tr = step_table(sides, f, st, facing, turn)
    report(f"{name}, across the pelvis's end heading, stride turn", lat, tr, where)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cycles", type=int, default=100)
    ap.add_argument("--data", type=Path, default=DATA, help="bandai-walk folder")
    ap.add_argument("--virtual", type=int, default=12, help="virtual corpus subjects (0: skip)")
    args = ap.parse_args()
    if args.data.is_dir():
        from mjwalk.mocap.bvh import load_bvh

        takes = [load_bvh(f) for f in sorted(args.data.glob("*.bvh"))]
        steps = segment_with_yaw(takes)
        report_all("capture (Bandai walk clips)", *capture_steps(steps))
        for style in ("normal", "masculine", "feminine", "youthful"):
            some = [s for s in steps if f"_{style}_" in s.take or f"_{style}_" in s.meta["file"]]
            report_all(f"capture, {style}", *capture_steps(some))
    else:
        print(f"no capture at {args.data}")
    if args.virtual:
        from mjwalk.gait.corpus import generate_corpus

        steps = segment_with_yaw(generate_corpus(args.virtual, 0))
        report_all(f"virtual corpus ({args.virtual} subjects)", *capture_steps(steps))
    if args.cycles:
        report_all(f"planned (station, {args.cycles} cycles)", *planned_steps(args.cycles))


if __name__ == "__main__":
    main()
