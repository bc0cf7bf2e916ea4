"""The swing ankle's angle at toe-off, after toe-off, at mid-swing and at heel strike: a walk's
first step (from standing) and a steady step, per stature, beside the cited figures.

Run from the repository root: ``PYTHONPATH=. python3 benchmarks/bench_swing_ankle.py
[--statures 1.55 1.75 1.95] [--cycles N]``

Walks: :func:`~mjwalk.plan.synthetic.synthetic_walk` of 8 steps, its step length scaled with
stature (0.65 m at 1.75 m: an assumption, step length in proportion to leg length), legs from
:func:`~mjwalk.body.legs.legs_from_walk` at that stature; with ``--cycles N`` also the first
steps of the station cycle's runs 0..N-1 (``scenes/assembly_station.toml``, seed 0, each run's
operator stature). The ankle is ``ankle_<side>_flex`` of the swing leg, degrees, + dorsiflexion.
Events: toe-off the last double-support sample of the step; *early swing* the least and the
largest angle from toe-off to step phase 0.4 (gait cycle 70 %); mid-swing step phase 0.6 (gait
cycle 80 %); heel strike the step's last sample.

Cited, steady gait (the swing leg's ankle): about 20 deg plantarflexion at toe-off (cycle
~62 %), dorsiflexing in initial swing to neutral by mid-swing and neutral through terminal
swing to initial contact (Perry & Burnfield, "Gait Analysis", 2nd ed., 2010, the ankle in
pre-swing and swing, quoted from memory; the same figures in the lecture notes
slideplayer.com/5345284 "Biomechanics foot ankle": pre-swing "ankle to 20 degrees PF",
mid-swing "ankle in neutral", terminal swing "still in neutral"; podiapaedia.org "Angular
kinematics of gait": 25 deg plantarflexion at toe-off, then rapid dorsiflexion). Gait
initiation: the swing heel comes off the floor before its toes (the events "swing heel-off"
and "swing toe-off" of gait-initiation studies, e.g. the figure legend of PMC5366317); no
published first-step ankle angle was found with the search tool, so the first step is judged
against the steady swing (at most neutral after toe-off, neutral at mid-swing) and its own
standing angle.

Measured (``--cycles 10``, 879469c -> gait47, both in one session): synthetic first steps at
1.55/1.75/1.95 m, toe-off 12.3/12.5/12.6 -> 5.7 deg (standing 5.0), early-swing peak
15.8-16.1 -> 12.3-12.4, mid-swing 2.9 -> 3.1-3.2, heel strike 16.2 both; steady steps
unchanged (toe-off 0, least -14.0 at step phase 0.38 as the reference's own ankle, mid-swing
-1.9, heel strike 7.4: the bandai-calibrated reference's heel-strike ankle is about +7).
Station first steps (70), median [range]: toe-off 12.3 [10.3, 13.1] -> -0.2 [-2.9, 2.8],
early-swing peak 13.7 -> 8.2 [3.9, 10.0], mid-swing 1.9 -> 2.4, heel strike 15.3 both.
"""

from __future__ import annotations

import argparse

import numpy as np

from mjwalk.body.legs import legs_from_walk
from mjwalk.plan.synthetic import synthetic_walk

#: Step phase of mid-swing (gait cycle 80 %) and the end of early swing (70 %).
MID_SWING, EARLY_END = 0.6, 0.4


def step_ankle(walk, legs, k: int) -> tuple[float, ...]:
    """Step ``k``'s swing ankle (degrees): at its start, toe-off, least and largest from
    toe-off to the end of early swing, mid-swing, heel strike."""
    st = walk.steps[k]
    a, b = st.start, st.end
    ph, c = legs.phase[a : b + 1], legs.contact[a : b + 1]
    ank = np.rad2deg(legs.angles[f"ankle_{st.side[0]}_flex"][a : b + 1])
    to = int(np.flatnonzero(c != 2).min()) - 1
    early = ank[to : max(int(np.searchsorted(ph, EARLY_END)), to + 1)]
    mid = int(np.argmin(np.abs(ph - MID_SWING)))
    return (float(ank[0]), float(ank[to]), float(early.min()), float(early.max()), float(ank[mid]),
            float(ank[-1]))  # fmt: skip


def synthetic(statures) -> None:
    """Print the first and a steady step's figures per stature."""
    print("stature step     start toe-off early-min early-max mid-swing heel-strike (deg, + dorsi)")
    for s in statures:
        w = synthetic_walk(n_steps=8, step_len=0.65 * s / 1.75)
        legs = legs_from_walk(w, s)
        for name, k in (("first", 0), ("steady", 3)):
            v = step_ankle(w, legs, k)
            print(f"{s:.2f}   {name:7s}" + "".join(f"{x:9.1f}" for x in v))
    print(
        "cited steady: toe-off ~-20 (the swing's least), early swing rising to 0, mid-swing 0, "
        "heel strike 0"
    )


def station(n: int) -> None:
    """Print the station runs' first steps' figures (median and range)."""
    from mjwalk.cycle.context import prepare
    from mjwalk.cycle.seeding import run_generator
    from mjwalk.cycle.simulate import simulate_cycle
    from mjwalk.cycle.spec import load_cycle_spec

    ctx = prepare(load_cycle_spec("scenes/assembly_station.toml"))
    rows = []
    for k in range(n):
        r = simulate_cycle(ctx, run_generator(0, k), run=k, collisions=False, ergonomics=False)
        stature = r.operator.stature if r.operator is not None else ctx.spec.stature
        for w in r.walks:
            rows.append(step_ankle(w.path, legs_from_walk(w.path, stature), 0))
    v = np.array(rows)
    print(f"station runs 0-{n - 1}, {len(v)} first steps: median [min, max]")
    for j, name in enumerate(
        ("start", "toe-off", "early-min", "early-max", "mid-swing", "heel-strike")
    ):
        print(
            f"  {name:11s} {np.median(v[:, j]):6.1f} [{v[:, j].min():6.1f}, {v[:, j].max():6.1f}]"
        )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--statures", type=float, nargs="+", default=[1.55, 1.75, 1.95])
    ap.add_argument("--cycles", type=int, default=0)
    a = ap.parse_args()
    synthetic(a.statures)
    if a.cycles:
        station(a.cycles)


if __name__ == "__main__":
    main()
