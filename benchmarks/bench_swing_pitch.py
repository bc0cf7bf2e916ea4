"""The swing foot's angle to the floor (pitch, + toes up) over the gait cycle: its least value
after toe-off (early swing, toes down), when in the cycle it comes, the pitch at toe-off and the
swing ankle's least angle (its plantarflexion peak), over a cycle's walks, beside the cited
figures.

Run from the repository root: ``PYTHONPATH=. python3 benchmarks/bench_swing_pitch.py
[--toml scenes/assembly_station.toml] [--cycles N] [--synthetic]``

Walks: ``simulate_cycle`` of the cycle file, runs 0..N-1, seed 0 (no collisions, no
ergonomics), each walk's legs from :func:`~mjwalk.body.legs.legs_from_walk` at the run's
operator stature (as :mod:`bench_swing_ankle` and :mod:`bench_swing_back` take them);
``--synthetic``: straight :func:`~mjwalk.plan.synthetic.synthetic_walk` s of 8 steps at 1.55,
1.75 and 1.95 m. Per step (chord at least 0.05 m, so no turn on the spot): the swing foot's
``LegMotion.pitch`` from its toe-off (the last double-support sample) to its landing, in degrees;
the gait-cycle instant of a step phase ``phi`` is ``50 + 50 phi`` % (the swing leg's heel strike
at 0 %, its toe-off at 60 %, as the synthesis times it); the ankle is ``ankle_<side>_flex``,
+ dorsiflexion. Printed per step position (first / middle / last of a walk; on a walk over
levels, steps whose stance and landing surfaces differ apart, "level"): count and the median
[min, max] of each figure.

Cited: the foot's angle to the floor is the shank's angle from the vertical plus the ankle's
(sagittal plane); with the Winter 1991 ensemble's hip and knee of
:data:`~mjwalk.body.legs.reference.WINTER_GAIT` and its ankle peaking at about 15-20 deg
plantarflexion at toe-off (Winter 1991, natural cadence; cited so in
:mod:`bench_swing_ankle`), the foot is about 55-65 deg toes down from toe-off into initial
swing. The table's own "pitch" row (after Perry & Burnfield 2010) reaches only -50 deg at 65 %,
which with the same hip and knee leaves the ankle at -3 deg: it is not Winter's ankle.
Capture (bandai-walk ``dataset-2_walk_<style>``, every clip, both legs,
:func:`~mjwalk.body.legs.analysis.gait_cycles`' pitch): least foot pitch median -69.7 deg
(p10-p90 -73.4 to -66.0) at 69 % in 224 "normal" cycles; masculine -66.7, feminine -80.4,
youthful -83.8.

Measured at b2485d0 (``--synthetic --cycles 5``; median [min, max]): synthetic middle steps
least pitch -69.3 [-69.3, -59.5] at 69.7 %, toe-off -43.4, least ankle -14.0; station runs 0-4
(195 steps) middle steps -69.3 [-79.4, -39.0] at 69.9 %, toe-off -37.7 at 59.7 %, least ankle
-14.1; first steps (from standing) -29.4; ``--toml scenes/multilevel_station.toml --cycles 3``
(223 steps) middle -69.3 [-76.7, -14.0], steps onto another level -48.9 [-70.6, -20.6]. The
Winter table's swing pitch instead (``warp_reference`` with the pitch landmarks at 65 and 80 %
left on the table): middle steps -54.8 with the ankle dorsiflexed up to 24 deg in the table at
79 %, the synthesis's knee moved 13 deg, its hip 7 deg, the pelvis 8 mm: wider than the feet.
The pitch raised after toe-off only (a sin² bump of up to 11 deg over 60-90 %, stance and
pelvis unchanged; table minimum -61.8): middle steps -62.4 at 68.2 %, the swing ankle's least
-8.0 instead of -14.0 (further from Winter's 15-20 deg), swing knee moved 6 deg, ankle target
23 mm. With this hip and knee a foot at -50 to -60 needs an ankle near neutral in early swing.
Other capture: CMU subject 35, ``35_01`` (3 cycles), -75.2 to -76.7 at 68-69 %.
"""

from __future__ import annotations

import argparse

import numpy as np

from mjwalk.body.legs import legs_from_walk

#: Step phase of the end of early swing (gait cycle 70 %), as :mod:`bench_swing_ankle`'s.
EARLY_END = 0.4


def step_pitches(walk, legs, min_chord: float = 0.05) -> list[tuple]:
    """Per step of ``walk``: (where, least swing pitch after toe-off (deg), its gait-cycle
    instant (%), pitch at toe-off (deg), toe-off instant (%), least swing ankle from toe-off to
    the end of early swing (deg))."""
    out = []
    n_steps = len(walk.steps)
    for k, st in enumerate(walk.steps):
        a, b = st.start, st.end
        if float(np.hypot(*(walk.xy[b] - walk.xy[a]))) < min_chord / 2:
            continue
        side = "left" if st.side == "left" else "right"
        ph, c = legs.phase[a : b + 1], legs.contact[a : b + 1]
        p = np.rad2deg(legs.pitch[side][a : b + 1])
        ank = np.rad2deg(legs.angles[f"ankle_{side[0]}_flex"][a : b + 1])
        single = np.flatnonzero(c != 2)
        to = int(single.min()) - 1 if len(single) else 0
        to = max(to, 0)
        j = to + int(np.argmin(p[to:]))
        early = ank[to : max(int(np.searchsorted(ph, EARLY_END)), to + 1)]
        where = "first" if k == 0 else "last" if k == n_steps - 1 else "middle"
        if abs(st.foot_z - st.stance_z) > 1e-3:
            where = "level"
        out.append((where, float(p[j]), 50 + 50 * float(ph[j]), float(p[to]),
                    50 + 50 * float(ph[to]), float(early.min())))  # fmt: skip
    return out


def cycle_rows(toml: str, cycles: int) -> list[tuple]:
    """:func:`step_pitches` over every walk of the cycle's runs 0..cycles-1, seed 0."""
    from mjwalk.cycle.context import prepare
    from mjwalk.cycle.seeding import run_generator
    from mjwalk.cycle.simulate import simulate_cycle
    from mjwalk.cycle.spec import load_cycle_spec

    ctx = prepare(load_cycle_spec(toml))
    rows = []
    for k in range(cycles):
        r = simulate_cycle(ctx, run_generator(0, k), run=k, collisions=False, ergonomics=False)
        stature = r.operator.stature if r.operator is not None else ctx.spec.stature
        for w in r.walks:
            rows += step_pitches(w.path, legs_from_walk(w.path, stature))
    return rows


def synthetic_rows() -> list[tuple]:
    """:func:`step_pitches` of straight synthetic walks at three statures."""
    from mjwalk.plan.synthetic import synthetic_walk

    rows = []
    for s in (1.55, 1.75, 1.95):
        w = synthetic_walk(n_steps=8, step_len=0.65 * s / 1.75)
        rows += step_pitches(w, legs_from_walk(w, s))
    return rows


def report(rows: list[tuple], title: str) -> None:
    """Print the rows' figures per step position."""
    print(f"{title}: {len(rows)} steps; degrees and % of the gait cycle, median [min, max]")
    names = ("least pitch", "at %", "toe-off pitch", "toe-off %", "least ankle")
    print("steps      n " + "".join(f"{x:>24s}" for x in names))
    for where in ("first", "middle", "last", "level", "all"):
        sel = [r for r in rows if where in ("all", r[0])]
        if not sel:
            continue
        v = np.array([r[1:] for r in sel])
        cells = "".join(f"{np.median(c):8.1f} [{c.min():6.1f},{c.max():6.1f}]" for c in v.T)
        print(f"{where:6s} {len(sel):5d} {cells}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--toml", default="scenes/assembly_station.toml")
    ap.add_argument("--cycles", type=int, default=5, help="runs 0..N-1, seed 0 (0: none)")
    ap.add_argument("--synthetic", action="store_true")
    a = ap.parse_args()
    if a.synthetic:
        report(synthetic_rows(), "synthetic straight walks, 1.55/1.75/1.95 m")
    if a.cycles:
        report(cycle_rows(a.toml, a.cycles), f"{a.toml}, runs 0-{a.cycles - 1}")


if __name__ == "__main__":
    main()
