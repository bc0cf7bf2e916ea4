"""CPU cost per station cycle of the parts issue 50's last profile named (the turn frames'
contact check, the cycle's final contact check and its compiled kinematics, the ergonomics'
body poses, the planner built per walk), timed without a profiler.

Run: PYTHONPATH=. python3 benchmarks/bench_cycle_parts.py [--runs 20] [--repeat 5]

``simulate_cycles`` runs ``--runs`` station cycles in this process (seed 0, 1 job, after 3
warm-up cycles) with the parts wrapped to record their inputs; each part is then run again
alone on those inputs ``--repeat`` times and its CPU seconds (``time.process_time``) are
divided by the runs. cProfile's per-call overhead (several microseconds a call) inflates parts
made of many small calls several times over (a 30-run profile gave the turn frames' check
4.7 ms a run; alone it takes about 0.6 ms), so the shares printed here, not a profile's, say
what a change to a part can save. Prints one line per part: ms per cycle and its share of the
cycle's CPU time; then the legs (``legs_from_walk``) by step, exclusive CPU time measured in
the cycles themselves (each named function of ``mjwalk.body.legs.synthesis`` wrapped where
synthesis calls it; a call's time less its wrapped callees').
"""

from __future__ import annotations

import argparse
import collections
import time

import numpy as np

from mjwalk.body.legs import synthesis as syn
from mjwalk.cycle import context as cx
from mjwalk.cycle import poses
from mjwalk.cycle import simulate as sim
from mjwalk.ergonomics import angles as an
from mjwalk.timeline import collisions as col
from mjwalk.timeline.geomposes import geom_poses

SPEC = "scenes/assembly_station.toml"

#: The legs' steps timed (names bound in mjwalk.body.legs.synthesis).
LEG_STEPS = (
    "legs_from_walk", "_start", "landing_pitches", "_synth_step", "_stance_leg", "stance_knee",
    "swing_foot_compiled", "pelvis_height", "spin_turns", "_fit_ankles", "fit_ankle_range",
    "reach_deficit", "_clear_floor", "hip_world", "foot_lowest", "lift_to_levels",
)  # fmt: skip


def _wrap_legs(acc: collections.defaultdict) -> dict:
    """Wrap :data:`LEG_STEPS` in synthesis to add their exclusive CPU seconds to ``acc``;
    returns the originals."""
    stack: list[float] = []
    kept = {n: getattr(syn, n) for n in LEG_STEPS if hasattr(syn, n)}

    def wrap(name, f):
        def g(*a, **k):
            t0 = time.process_time()
            stack.append(0.0)
            try:
                return f(*a, **k)
            finally:
                dt = time.process_time() - t0
                acc[name] += dt - stack.pop()
                if stack:
                    stack[-1] += dt

        return g

    for name, f in kept.items():
        setattr(syn, name, wrap(name, f))
    return kept


def _record(runs: int) -> tuple[dict, float]:
    """Run the cycles with the parts wrapped; their inputs and the cycles' CPU seconds."""
    seen: dict = {"turns": [], "final": [], "planners": []}
    turn0, final0, make0 = poses.frame_contacts, sim.collision_report, cx.Planners._make

    def turns(ctx, frames, fps=30.0):
        seen["turns"].append((ctx, frames.copy(), fps))
        return turn0(ctx, frames, fps)

    def final(timeline, **kw):
        seen["final"].append(timeline)
        return final0(timeline, **kw)

    def make(self, key):
        seen["planners"].append((self, key))
        return make0(self, key)

    wrapped: list[tuple] = [(poses, "frame_contacts", turns, turn0)]
    wrapped += [(sim, "collision_report", final, final0), (cx.Planners, "_make", make, make0)]
    for owner, name, f, _ in wrapped:
        setattr(owner, name, f)
    legs: collections.defaultdict = collections.defaultdict(float)
    kept = _wrap_legs(legs)
    try:
        sim.simulate_cycles(SPEC, 3, seed=99, n_jobs=1)  # warm: models, compiled code
        for v in seen.values():
            v.clear()
        legs.clear()
        t0 = time.process_time()
        sim.simulate_cycles(SPEC, runs, seed=0, n_jobs=1)
        cpu = time.process_time() - t0
    finally:
        for owner, name, _, f in wrapped:
            setattr(owner, name, f)
        for name, f in kept.items():
            setattr(syn, name, f)
    seen["legs"] = legs
    return seen, cpu


def _cpu(f, repeat: int) -> float:
    """CPU seconds of one call of ``f`` (mean of ``repeat``)."""
    t0 = time.process_time()
    for _ in range(repeat):
        f()
    return (time.process_time() - t0) / repeat


def main() -> None:
    """Print each part's CPU milliseconds per cycle and share of the cycle."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    seen, cpu = _record(args.runs)
    final = seen["final"]

    def fresh(t):
        q = np.asarray(t.qpos)
        return q[~col.repeats(q)]

    def candidates():
        for t in final:
            human = t.model.geom_group == col.HUMAN_GROUP
            col.candidate_frames(t.model, fresh(t), human, col.floor_geoms(t.model), 0.01)

    def final_poses():
        for t in final:
            geom_poses(t.model, fresh(t), np.flatnonzero(t.model.geom_group == col.HUMAN_GROUP))

    parts = {
        "turn frames' contact check (a)": lambda: [
            poses.frame_contacts(c, f, fps) for c, f, fps in seen["turns"]
        ],
        "final contact check (a)": lambda: [col.collision_report(t) for t in final],
        "  its broad phase": candidates,
        "  its geom poses (shareable, e)": final_poses,
        "ergonomics' body poses (e)": lambda: [
            an.body_frames(t.model, t.jointmap, t.qpos, list(an._BODY_POINTS)) for t in final
        ],
        "ergonomics' angles (all)": lambda: [an.angles_from_timeline(t) for t in final],
        "planners built per walk (d)": lambda: [
            cx.Planners._make(p, k) for p, k in seen["planners"]
        ],
    }
    per = cpu / args.runs
    print(f"cycle: {1e3 * per:.1f} ms CPU ({args.runs} runs, {len(seen['planners'])} planners)")
    for name, f in parts.items():
        ms = 1e3 * _cpu(f, args.repeat) / args.runs
        print(f"{name:34s} {ms:6.2f} ms  {100 * ms / (1e3 * per):5.1f} %")
    print("legs by step (exclusive; timed in the cycles, wrappers included):")
    for name, sec in sorted(seen["legs"].items(), key=lambda kv: -kv[1]):
        ms = 1e3 * sec / args.runs
        print(f"  {name:32s} {ms:6.2f} ms  {100 * ms / (1e3 * per):5.1f} %")


if __name__ == "__main__":
    main()
