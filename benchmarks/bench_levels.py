"""Stair and ramp gait per walker profile beside the cited norms (issue 47, deliverable 3).

Run: python3 benchmarks/bench_levels.py [--draws 400] [--seed 47]

For every walker preset (mjwalk.gait.walker.PRESETS), ``--draws`` operators drawn as the cycle
draws them (mjwalk.cycle.population), on the issue's stair (0.17 m risers, 0.28 m treads, six
risers to the 1.02 m mezzanine) and ramp (5.5 deg to the 0.34 m platform): the group mean (and
5th-95th percentiles) of the time per step, the cadence and the speeds, and the time for the
flight and the ramp, printed beside the cited norms (Fruin 1971 stair speeds along the slope;
Oh-Park et al. 2011 per-step stair times of adults of 70 and over). The planning cost against
flat walks is another engineer's part (the planner over levels) and is not measured here.

Measured (400 walkers per group, seed 47, 2 s): group-mean speed along the slope up / down,
m/s: adult 0.575 / 0.725, older_adult 0.518 / 0.653, fatigued 0.517 / 0.652 (all inside
Fruin's 0.485-0.67 / 0.595-1.01), brisk 0.686 / 0.864 (up above Fruin's fastest group mean,
as hurrying walkers should be); elderly time per step 0.866 s up / 0.686 s down (inside
Oh-Park's 0.70-1.07 / 0.66-1.23 s). The six-riser flight: adult 3.5 s up, 2.8 s down; elderly
5.2 s / 4.1 s. The 5.5 deg ramp: adult 1.00 m/s up (0.71 of level), 1.40 m/s down.
"""

from __future__ import annotations

import argparse
import math

import numpy as np

from mjwalk.cycle.population import Population, preset_group
from mjwalk.gait.slope import slope_gait
from mjwalk.gait.stairs import (
    FRUIN_DOWN_SPEED,
    FRUIN_UP_SPEED,
    OH_PARK_DOWN_STEP_TIME,
    OH_PARK_UP_STEP_TIME,
    StairGeometry,
    stair_gait,
)
from mjwalk.gait.walker import PRESETS

STAIR = StairGeometry(0.17, 0.28)
RISERS = 6
RAMP_DEG = 5.5
RAMP_RISE = 0.34


def _stats(values: list[float]) -> str:
    a = np.asarray(values)
    lo, hi = np.percentile(a, [5, 95])
    return f"{a.mean():.3f} ({lo:.3f}-{hi:.3f})".ljust(22)


def _norm(group: str, direction: str) -> str:
    if group == "elderly":
        lo, hi = OH_PARK_UP_STEP_TIME if direction == "up" else OH_PARK_DOWN_STEP_TIME
        return f"step {lo:.2f}-{hi:.2f} s (Oh-Park 2011, 70+)"
    lo, hi = FRUIN_UP_SPEED if direction == "up" else FRUIN_DOWN_SPEED
    return f"slope speed {lo:.3f}-{hi:.3f} m/s (Fruin 1971)"


def stair_table(draws: int, seed: int) -> None:
    """Print the stair figures per preset and direction.

    Args:
        draws: walkers per preset.
        seed: the draws' seed.
    """
    print(
        f"\nStair {STAIR.riser} m / {STAIR.tread} m ({math.degrees(STAIR.pitch):.1f} deg), "
        f"{RISERS} risers; mean (5th-95th percentile) over {draws} walkers per group"
    )
    head = (
        f"{'group':12} {'dir':4} {'step time s':22} {'cadence /min':22} "
        f"{'slope speed m/s':22} {'horiz m/s':22} {'flight s':22} norm"
    )
    print(head)
    print("-" * len(head))
    for group in PRESETS:
        pop = Population((preset_group(group),))
        rng = np.random.default_rng(seed)
        walkers = [pop.draw(rng) for _ in range(draws)]
        for d in ("up", "down"):
            gaits = [stair_gait(w, STAIR, d) for w in walkers]
            print(
                f"{group:12} {d:4} {_stats([g.step_time for g in gaits])} "
                f"{_stats([g.cadence * 60 for g in gaits])} "
                f"{_stats([g.slope_speed for g in gaits])} "
                f"{_stats([g.horizontal_speed for g in gaits])} "
                f"{_stats([g.flight(RISERS).duration for g in gaits])} {_norm(group, d)}"
            )


def ramp_table(draws: int, seed: int) -> None:
    """Print the ramp figures per preset, level, up and down.

    Args:
        draws: walkers per preset.
        seed: the draws' seed.
    """
    run = RAMP_RISE / math.tan(math.radians(RAMP_DEG))
    print(
        f"\nRamp {RAMP_DEG} deg, {run:.2f} m run to the {RAMP_RISE} m platform; norms: "
        "Tobler 1993 speed factor (capped at 1 downhill), Franz & Kram 2012 downhill cadence"
    )
    head = (
        f"{'group':12} {'slope':6} {'speed m/s':22} {'step length m':22} "
        f"{'cadence /min':22} {'ramp time s':22}"
    )
    print(head)
    print("-" * len(head))
    for group in PRESETS:
        pop = Population((preset_group(group),))
        rng = np.random.default_rng(seed)
        walkers = [pop.draw(rng) for _ in range(draws)]
        for deg in (0.0, RAMP_DEG, -RAMP_DEG):
            gaits = [slope_gait(w, math.radians(deg)) for w in walkers]
            print(
                f"{group:12} {deg:+6.1f} {_stats([g.speed for g in gaits])} "
                f"{_stats([g.step_length for g in gaits])} "
                f"{_stats([g.cadence * 60 for g in gaits])} "
                f"{_stats([g.duration(run) for g in gaits])}"
            )


def main() -> None:
    """Print both tables."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--draws", type=int, default=400)
    ap.add_argument("--seed", type=int, default=47)
    args = ap.parse_args()
    stair_table(args.draws, args.seed)
    ramp_table(args.draws, args.seed)


if __name__ == "__main__":
    main()
