"""The legs' ankle-range fit stopped at a tolerance (``synthesis.ANKLE_TOL``, issue 50) against
run until no grounded ankle is past its bound (``ANKLE_TOL = 0``, the rule before): what it
changes in the legs of recorded station walks and what it saves, interleaved.

Run: PYTHONPATH=. python3 benchmarks/bench_ankletol.py [--runs 20] [--rounds 5] [--tol 0.01]

``simulate_cycles`` runs ``--runs`` station cycles (seed 0, 1 job, after 2 warm-up cycles:
runs 0 to ``--runs`` - 1) with ``cycle.poses.legs_from_walk`` wrapped to record each walk and
stature. Every recorded walk is synthesised with both tolerances; printed: the largest change
in any joint angle (degrees), in the ankle targets and the pelvis (mm), the highest ankle
flexion of a grounded foot before clipping against the joint's range, and the outer passes of
``_fit_ankles`` (calls of ``reach_deficit``) each way. Then the walks are synthesised
``--rounds`` times each way, alternating which goes first, and the CPU seconds
(``time.process_time``) of each way are divided by the runs: ms a cycle, medians, ratio.

Measured (ankletol50, 20 runs, 140 walks, load ~14 on 2 cores): largest change 0.058 degree in
any joint angle, 0.075 mm in the ankle targets, 0 in the pelvis; correcting rounds per leg and
pass (560 fits) 490 x 8 and 70 x 0 -> 97 x 8, 252 x 0, the rest 1-7 (3920 -> 1836 rounds);
_fit_ankles 2 passes in all 140 walks both ways; legs 16.26 -> 15.43, 14.47 -> 13.03 and
15.44 -> 14.22 ms a cycle in three runs (ratios 0.95, 0.90, 0.92).
"""

from __future__ import annotations

import argparse
import collections
import statistics

import numpy as np
from bench_synthloop import _record, synth_cpu  # the station walks, recorded as the legs meet them

from mjwalk.body.humanoid import ROM_DEG
from mjwalk.body.legs import pitchfit
from mjwalk.body.legs import synthesis as syn


def _legs(walks: list[tuple], tol: float) -> tuple[list, collections.Counter, collections.Counter]:
    """Each walk's LegMotion with ``ANKLE_TOL = tol``, the count of _fit_ankles' passes and of
    the compiled fits' correcting rounds (per leg and pass)."""
    syn.ANKLE_TOL = tol
    passes: collections.Counter = collections.Counter()
    rounds: collections.Counter = collections.Counter()
    deficit0, fit0, rounds0 = syn.reach_deficit, syn._fit_ankles, pitchfit._fit_rounds
    calls = [0]

    def counted(*a):
        done = rounds0(*a)
        rounds[done] += 1
        return done

    def deficit(*a, **k):
        calls[0] += 1
        return deficit0(*a, **k)

    def fit(*a, **k):
        calls[0] = 0
        fit0(*a, **k)
        passes[calls[0]] += 1

    syn.reach_deficit, syn._fit_ankles, pitchfit._fit_rounds = deficit, fit, counted
    try:
        out = [syn.legs_from_walk(w, s) for w, s in walks]
    finally:
        syn.reach_deficit, syn._fit_ankles, pitchfit._fit_rounds = deficit0, fit0, rounds0
    return out, passes, rounds


def _compare(a: list, b: list) -> dict[str, float]:
    """Largest differences between two lists of LegMotion, degrees and mm."""
    d = {"angle_deg": 0.0, "ankle_mm": 0.0, "root_mm": 0.0, "pitch_deg": 0.0}
    for x, y in zip(a, b, strict=True):
        for k in x.angles:
            d["angle_deg"] = max(
                d["angle_deg"], np.rad2deg(np.abs(x.angles[k] - y.angles[k]).max())
            )
        for k in x.ankle:
            d["ankle_mm"] = max(d["ankle_mm"], 1e3 * np.abs(x.ankle[k] - y.ankle[k]).max())
            d["pitch_deg"] = max(d["pitch_deg"], np.rad2deg(np.abs(x.pitch[k] - y.pitch[k]).max()))
        d["root_mm"] = max(d["root_mm"], 1e3 * np.abs(x.root - y.root).max())
    return d


def _at_limit(legs: list) -> int:
    """Samples whose synthesised (clipped) ankle flexion sits at the range's top."""
    top = np.deg2rad(ROM_DEG["ankle_flex"][1])
    return sum(int((m.angles[f"ankle_{s}_flex"] >= top).sum()) for m in legs for s in "lr")


def _highest_flex(legs: list) -> float:
    """The highest ankle flexion (degrees) in the synthesised (clipped) angles."""
    return max(float(np.rad2deg(m.angles[f"ankle_{s}_flex"].max())) for m in legs for s in "lr")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=20)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--tol", type=float, default=syn.ANKLE_TOL)
    args = ap.parse_args()
    tol0 = syn.ANKLE_TOL
    walks = _record(args.runs)
    old, p_old, r_old = _legs(walks, 0.0)
    new, p_new, r_new = _legs(walks, args.tol)
    print(f"{len(walks)} walks in {args.runs} cycles; tolerance {args.tol} deg")
    print("largest change:", {k: round(v, 5) for k, v in _compare(old, new).items()})
    print(f"ankle flexion range {ROM_DEG['ankle_flex']} deg; highest synthesised "
          f"{_highest_flex(old):.4f} (tol 0) / {_highest_flex(new):.4f} (tol); samples at "
          f"its top {_at_limit(old)} / {_at_limit(new)}")  # fmt: skip
    print(f"correcting rounds per leg and pass: tol 0 {dict(sorted(r_old.items()))}, "
          f"tol {dict(sorted(r_new.items()))}")  # fmt: skip
    print(f"_fit_ankles passes: tol 0 {dict(sorted(p_old.items()))}, "
          f"tol {dict(sorted(p_new.items()))}")  # fmt: skip
    ms = {0.0: [], args.tol: []}
    for r in range(args.rounds):
        order = (0.0, args.tol) if r % 2 == 0 else (args.tol, 0.0)
        for t in order:
            syn.ANKLE_TOL = t
            ms[t].append(synth_cpu(walks) / args.runs * 1e3)
        print(f"round {r}: tol 0 {ms[0.0][-1]:.2f} ms a cycle, tol {ms[args.tol][-1]:.2f}")
    a, b = statistics.median(ms[0.0]), statistics.median(ms[args.tol])
    print(f"median: tol 0 {a:.2f} ms a cycle, tol {args.tol} {b:.2f} ms (ratio {b / a:.3f})")
    syn.ANKLE_TOL = tol0


if __name__ == "__main__":
    main()
