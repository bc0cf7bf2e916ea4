"""Would a per-person turn strategy widen the station's route spread? (issue 48, item 4;
docs/decisions/113).

Run: python3 benchmarks/bench_turn_spread.py [--cycles 200] [--seed 0]

A walker standing at its work turns all but a residual of 30-60 deg on the spot and the rest
along its first steps (:mod:`mjwalk.plan.turnsplit`, drawn per walk). A person who habitually
pivots the whole turn on the spot (a spin or pivot turn) or habitually carries the cited
one-step change into the walk (a step turn, Patla et al. 1991's 60 deg) would shift that
direction's lengths; a workforce mixing both would spread them. This measures how far:

1. **Each direction with the residual pinned** (the station cycle's walks,
   ``plan_cycle_walks``, shipped workforce): as shipped (30-60 deg per walk), 0 deg (the
   whole turn on the spot) and 60 deg, each capped as shipped by the floor square to the work's
   front; the median and IQR (m), the IQR/median as a share of agethen2018 Table 1's captured
   route (``share``) and the IQR over the captured IQR in metres (``in m``). The residual is
   pinned by replacing :func:`mjwalk.plan.turnsplit.residual_turn` for the run (its one draw
   still taken, so every other draw stays where it was).
2. **A workforce mixing the two habits**: the lengths of a share p of walkers drawn from the
   60 deg runs and the rest from the 0 deg runs (20 000 resamples), p = 0, 0.25, 0.5, 0.75, 1.
   Each run's operator walks each direction once, so a habit drawn per person or per walk gives
   the same per-direction lengths.
3. **How much of the spread is between operators**: the share of each direction's length
   variance a linear fit on the operator's stature, step length and speed explains (R²), and
   the median per operator group.
"""

from __future__ import annotations

import argparse
import math
import time
from collections import defaultdict
from unittest import mock

import numpy as np
from bench_variability import CAPTURED, ROOT, _q  # the captured Table 1 figures, quartiles

from mjwalk.cycle.simulate import cycle_start, plan_cycle_walks, prepare
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import PlanningError
from mjwalk.plan import turnsplit

#: The pinned residuals (degrees): the whole turn on the spot, and Patla et al.'s larger
#: one-step direction change (the shipped draw's upper end).
PINNED = (0.0, 60.0)
SHARES = (0.0, 0.25, 0.5, 0.75, 1.0)


def _pinned(deg: float):
    """A stand-in for :func:`~mjwalk.plan.turnsplit.residual_turn` that takes its draw and
    returns ``deg`` degrees (radians)."""

    def residual(rng: np.random.Generator) -> float:
        rng.uniform(turnsplit.WALKING_TURN_MIN, turnsplit.WALKING_TURN_MAX)
        return math.radians(deg)

    return residual


def station_walks(cycles: int, seed: int) -> dict[str, list[tuple]]:
    """Per direction ("T2 stand_car1->stand_rack3"): (length m, stature m, step length m,
    speed m/s, group) of each run's walk, each run's operator drawn from the station's
    workforce as ``simulate_cycle`` draws it; a run with an unplannable walk is left out."""
    spec = load_cycle_spec(ROOT / "scenes" / "assembly_station.toml")
    ctx = prepare(spec)
    rows: dict[str, list[tuple]] = defaultdict(list)
    for run in range(cycles):
        rng = np.random.default_rng(np.random.SeedSequence([seed, run]))
        op_rng, _, stand_rng = rng.spawn(3)  # simulate_cycle's operator and start streams
        walker = spec.population.draw(op_rng) if spec.population is not None else None
        try:
            start = cycle_start(ctx, stand_rng, walker)
            walks = plan_cycle_walks(ctx, rng, walker, start, stand_rng)
        except PlanningError:
            continue
        for i, here, goal, path in walks:
            person = (walker.stature, walker.step_length, walker.speed, walker.group)
            rows[f"{spec.tasks[i].route} {here}->{goal}"].append((path.length, *person))
    return rows


def _cells(lengths, route: str) -> str:
    med, iqr = _q(lengths)
    cm, ci = CAPTURED[route]
    return f"{med:>6.2f}{iqr:>7.3f}{100 * (iqr / med) / (ci / cm):>6.0f}%{100 * iqr / ci:>5.0f}%"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cycles", type=int, default=200)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    runs = {"shipped": station_walks(args.cycles, args.seed)}
    for deg in PINNED:
        t0 = time.perf_counter()
        with mock.patch.object(turnsplit, "residual_turn", _pinned(deg)):
            runs[f"{deg:.0f} deg"] = station_walks(args.cycles, args.seed)
        print(f"(residual pinned at {deg:.0f} deg: {time.perf_counter() - t0:.0f} s)")
    keys = sorted(runs["shipped"])
    print(
        f"\nper direction, {args.cycles} cycles: median, IQR (m), share of the captured "
        "IQR/median, IQR in m over the captured"
    )
    print(f"{'route':<30}" + "".join(f"{name:>25}" for name in runs))
    for key in keys:
        route = key.split()[0]
        cells = [_cells(np.array([r[0] for r in runs[m][key]]), route) for m in runs]
        print(f"{key:<30}" + "".join(f"{c:>25}" for c in cells))
    rng = np.random.default_rng(args.seed)
    print("\na workforce mixing the habits: share p turning 60 deg along the first steps")
    print(f"{'route':<30}" + "".join(f"{f'p={p:.2f}':>25}" for p in SHARES))
    for key in keys:
        lo, hi = (np.array([r[0] for r in runs[f"{d:.0f} deg"][key]]) for d in PINNED)
        cells = []
        for p in SHARES:
            pick = rng.random(20000) < p
            mixed = np.where(pick, rng.choice(hi, 20000), rng.choice(lo, 20000))
            cells.append(_cells(mixed, key.split()[0]))
        print(f"{key:<30}" + "".join(f"{c:>25}" for c in cells))
    print("\nbetween operators (shipped): R² of length on stature, step length, speed; medians")
    for key in keys:
        v = runs["shipped"][key]
        length = np.array([r[0] for r in v])
        x = np.array([[1.0, r[1], r[2], r[3]] for r in v])
        beta, *_ = np.linalg.lstsq(x, length, rcond=None)
        r2 = 1.0 - float(np.var(length - x @ beta) / np.var(length))
        groups: dict[str, list[float]] = defaultdict(list)
        for r in v:
            groups[r[4]].append(r[0])
        by = "  ".join(f"{g} {np.median(x):.2f} ({len(x)})" for g, x in sorted(groups.items()))
        print(f"{key:<30} R² {r2:.2f}   {by}")


if __name__ == "__main__":
    main()
