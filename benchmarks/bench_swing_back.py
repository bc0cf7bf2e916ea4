"""How far the swing ankle moves back after toe-off, over the station cycle's steps.

Run from the repository root: ``PYTHONPATH=. python3 benchmarks/bench_swing_back.py [--cycles N]``

Walks: ``simulate_cycle`` of ``scenes/assembly_station.toml``, runs 0..N-1, seed 0 (no
collisions, no ergonomics), each walk's legs from :func:`~mjwalk.body.legs.legs_from_walk` at the
run's operator stature. For every step: the swing ankle's target (``LegMotion.ankle``) projected
on the step's ankle chord (its position at the step's start to its landing), from the toe-off
sample (the last double-support sample) to the landing. Two figures per step, centimetres:

- *back*: how far the ankle comes behind its toe-off position (toe-off minus the lowest later
  projection, 0 if never behind);
- *drawdown*: the largest fall of the projection below its running maximum after toe-off (any
  backward move, also one after some forward progress), up to mid-swing (step phase
  ``MID_SWING``) and over the whole swing (the landing approach included: in the station's
  steps a retraction of up to 4 cm between step phases 0.86 and 0.99, not toe-off's cause).

People's swing foot moves forward from toe-off to heel strike (Winter 1992, "Foot trajectory in
human gait: a precise and multifactorial motor control task", Phys. Ther. 72(1), 45-53: the
abstract gives the heel's forward velocity at heel contact, 0.87 m/s; the forward heel and toe
trajectories through swing are quoted from memory, not checked); so both should be 0. Steps
whose chord is under ``--min-chord`` (turns on the spot) are left out: their direction is not
defined by the chord. Printed per step position (first / middle / last step of a
walk, all): count, median, p95, max of both figures and the share of steps with back > 1 cm.

Measured (``--cycles 20``, 757 steps on this machine; back median / p95 / max, cm): at a196e73
first steps 7.76 / 8.63 / 9.06 (100 % over 1 cm), middle 0.00 / 4.60 / 8.59 (17 %), last
0.00 / 1.29 / 7.48 (6 %); drawdown to mid-swing, all steps, p95 9.12, max 10.10. The cause: the
swing's chord progress started at the lift-off footprint while the heel rise had already carried
the ankle 7-9 cm ahead of it. Since the progress is bounded below by the toe-off ankle's going on
at its toe-off speed (``legs.steps._reference_swing`` and its twin ``legs.swing._swing_late``,
handed over through a soft maximum): back 0 in every step; drawdown to mid-swing p95 0.00, max
5.26 (one middle step); over the whole swing the landing approach's is left (all steps median
0.75, p95 3.95, max 7.43; before 1.56 / 9.12 / 10.10).
"""

from __future__ import annotations

import argparse

import numpy as np

from mjwalk.body.legs import legs_from_walk
from mjwalk.body.legs.steps import SWING_KEYS

#: Mid-swing, step phase: the middle swing key (cycle 80 %).
MID_SWING = SWING_KEYS[2]


def swing_backs(walk, legs, min_chord: float = 0.05) -> list[tuple[str, float, float, float]]:
    """Per step of ``walk`` (chord at least ``min_chord`` m): (where, back, drawdown to
    mid-swing, drawdown), metres: where "first" / "middle" / "last"; the figures as in the
    module doc."""
    out = []
    n_steps = len(walk.steps)
    for k, st in enumerate(walk.steps):
        a, b = st.start, st.end
        ankle = legs.ankle["left" if st.side == "left" else "right"][a : b + 1, :2]
        chord = ankle[-1] - ankle[0]
        length = float(np.hypot(*chord))
        if length < min_chord:
            continue
        ds = legs.contact[a : b + 1] == 2
        ito = int(np.argmin(ds)) - 1 if not ds.all() else len(ds) - 1
        ito = max(ito, 0)
        d = (ankle[ito:] - ankle[0]) @ (chord / length)
        back = max(0.0, float(d[0] - d.min()))
        fall = np.maximum.accumulate(d) - d
        mid = np.arange(ito, len(ds)) <= MID_SWING * (b - a)
        where = "first" if k == 0 else "last" if k == n_steps - 1 else "middle"
        out.append((where, back, float(fall[mid].max()), float(fall.max())))
    return out


def station_rows(cycles: int, min_chord: float) -> list[tuple[str, float, float, float]]:
    """:func:`swing_backs` over every walk of the station cycle's runs 0..cycles-1, seed 0."""
    from mjwalk.cycle.context import prepare
    from mjwalk.cycle.seeding import run_generator
    from mjwalk.cycle.simulate import simulate_cycle
    from mjwalk.cycle.spec import load_cycle_spec

    ctx = prepare(load_cycle_spec("scenes/assembly_station.toml"))
    rows = []
    for k in range(cycles):
        r = simulate_cycle(ctx, run_generator(0, k), run=k, collisions=False, ergonomics=False)
        stature = r.operator.stature if r.operator is not None else ctx.spec.stature
        for w in r.walks:
            rows += swing_backs(w.path, legs_from_walk(w.path, stature), min_chord)
    return rows


def _figs(x: np.ndarray, w: int) -> str:
    """Median, p95 and max of ``x``, the median ``w`` wide."""
    return f"{np.median(x):{w}.2f} {np.percentile(x, 95):5.2f} {x.max():5.2f}"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cycles", type=int, default=20, help="station runs 0..N-1, seed 0")
    ap.add_argument("--min-chord", type=float, default=0.05, help="shortest step chord, m")
    a = ap.parse_args()
    rows = station_rows(a.cycles, a.min_chord)
    print(f"{a.cycles} station cycles, {len(rows)} steps (chord >= {a.min_chord} m); cm")
    print(
        "steps      n   back: median  p95   max >1cm   to mid-swing: median  p95   max"
        "   whole swing: median  p95   max"
    )
    for where in ("first", "middle", "last", "all"):
        sel = [r for r in rows if where in ("all", r[0])]
        if not sel:
            continue
        back, early, draw = (100 * np.array([r[j] for r in sel]) for j in (1, 2, 3))
        print(
            f"{where:6s} {len(sel):5d} {_figs(back, 11)} {100 * np.mean(back > 1):3.0f}% "
            f"{_figs(early, 19)} {_figs(draw, 18)}"
        )


if __name__ == "__main__":
    main()
