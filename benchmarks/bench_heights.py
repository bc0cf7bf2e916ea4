"""Picks from every height a workplace puts parts at, with either hand and with both.

The two-handed station (scenes/assembly_station_2h.xml) with its box on bench a at each
``--heights`` (metres, the box's centre and grip sites; below 1.05 m the bench is lowered into
a pallet under it, above it the box stands on a shelf board 10 cm under its centre), picked by
the 1.75 m humanoid from the stand site with the left hand, the right hand or both. Prints per
height and hand: the largest hand error at the target (mm; more than 10 mm is reported by
``mjwalk simulate`` as short of the target), the humanoid-vs-scene contact frames (MuJoCo's
collision check), the pick's duration (s; a stoop below the knee or a crouch adds MTM-1's bend
and arise) and how the operator got there (``stand``, ``bend`` or ``crouch``).

First run 2026-11-28 (``python benchmarks/bench_heights.py``, 35 s), at the code of that
session's end: from 0.16 m (a pallet on the floor: a crouch) to 1.05 m every pick, with
either hand and with both, ends on its target without contact; 0.45 m takes a stoop (with
both hands 5.8 s: the grips below the knee, MTM-1's bend and arise); from a shelf board at
1.55 and 1.85 m the one-handed picks are clear and the two-handed ones touch the board
(48 and 118 contact frames: the hands come onto the grips over the board's front edge from
in front and above, and the forearms, sloping up to them, go through the edge); at 1.95 m
the one-handed picks touch it too (63 frames); at 2.05 m (the hand's target 2.11 m up, near
the 1.75 m operator's 2.2 m reach) the hands end 20-95 mm short, reported by ``mjwalk
simulate`` as short of the target. At that session's start a two-handed pick from a 0.35 m
pallet ended 332 mm short and a one-handed pick 1.95 m up 1.3 m off, neither warned about.

Later on 2026-11-28, two-handed picks from a shelf: the hands lie on the box's
sides pointing along their approach (in and down over the board's edge), turned to it on the
way to the pre-grasp point, and a box lifted off a board is pulled back clear of its edge
before it is lowered (``mjwalk.cycle.reaching._held_move``). Both hands at 1.55 m: 48 -> 0
contact frames, 3.77 -> 3.97 s; 1.85 m: 118 -> 0, 8.70 -> 4.50 s (the long pick was the hands
turning from the reach model's upward direction onto the grips: a long path of the hand);
1.95 m: 385 -> 8; 2.05 m: on the grips (95 mm short before), 455 contact frames, 10.5 s (a
target beyond the arms' reach: the arm straight overhead, its shoulder angles wound round).
One-handed picks unchanged (1.95 m: 63 and 62 frames, the forearm over the board's edge while
the hand holds the part). Placing on a shelf as high over bench b
(``tests/cycle/test_two_hands.py``): 1.85 m, pick and place 108 + 59 -> 0 contact frames.

Run from the repo root:  python benchmarks/bench_heights.py [--heights 0.16,0.45,1.85]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from collections import Counter
from pathlib import Path

import numpy as np

from mjwalk.cycle.simulate import prepare, simulate_cycle
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import MjwalkError

ROOT = Path(__file__).resolve().parents[1]
HEIGHTS = (0.16, 0.45, 0.75, 1.05, 1.55, 1.85, 1.95, 2.05)
HANDS = ("left", "right", "both")
#: Bench a of scenes/assembly_station_2h.xml (top 0.95 m, the box's centre at 1.05 m); bench
#: b's geoms are the same with its name.
BENCH = (
    '<geom name="bench_a_top" type="box" size="0.35 0.25 0.02" pos="0 0 0.93" material="shelf"/>\n'
    '      <geom name="bench_a_leg" type="box" size="0.3 0.2 0.455" pos="0 0 0.455" '
    'material="rack"/>'
)
#: Where each bench's box (centre and grip sites; bench a's box geom too) lies across the
#: bench (local y, m); at x 0 and -+0.2, 1.05 m up.
BOX_Y = {"bench_a": "-0.1", "bench_b": "0.1"}


def box_at(xml: str, bench: str, height: float) -> str:
    """``xml`` (scenes/assembly_station_2h.xml) with the box of ``bench`` ("bench_a" or
    "bench_b": its centre and grip sites) ``height`` metres up: below 1.05 m on a pallet (or
    lower bench) whose top is 10 cm under the box's centre, above it on a shelf board there
    over the bench."""
    old = BENCH.replace("bench_a", bench)
    if bench not in BOX_Y or old not in xml:
        raise MjwalkError(f"scenes/assembly_station_2h.xml: {bench} is not where this expects it")
    top = height - 0.10
    if top < 0.95:  # a pallet (or lower bench) under the box
        half = max((top - 0.04) / 2.0, 0.005)
        new = (
            f'<geom name="{bench}_top" type="box" size="0.35 0.25 0.02" pos="0 0 {top - 0.02}" '
            'material="shelf"/>\n'
            f'      <geom name="{bench}_leg" type="box" size="0.3 0.2 {half}" pos="0 0 {half}" '
            'material="rack"/>'
        )
    else:  # the bench, and a shelf board under the box
        new = old + (
            f'\n      <geom name="{bench}_shelf" type="box" size="0.35 0.25 0.02" '
            f'pos="0 0 {top - 0.02}" material="shelf"/>'
        )
    xml = xml.replace(old, new)
    y = BOX_Y[bench]
    for x in ("0", "-0.2", "0.2"):
        xml = xml.replace(f'pos="{x} {y} 1.05"', f'pos="{x} {y} {height:.3f}"')
    if xml.count(f" {y} {height:.3f}") < 3:
        raise MjwalkError(f"scenes/assembly_station_2h.xml: {bench}'s box is not where expected")
    return xml


def write_workplace(folder: Path, height: float, hand: str) -> Path:
    """The station with bench a's box (centre and grips) ``height`` metres up (:func:`box_at`)
    and a cycle file picking it with ``hand``; returns the cycle file."""
    xml = box_at((ROOT / "scenes" / "assembly_station_2h.xml").read_text(), "bench_a", height)
    (folder / "heights.xml").write_text(xml)
    (folder / "heights.toml").write_text(
        'scene = "heights.xml"\nstart = "stand_bench_a"\n[humanoid]\nstature = 1.75\n'
        f'[[task]]\nkind = "pick"\nsite = "bench_a_box"\nhand = "{hand}"\npart = "box"\n'
    )
    return folder / "heights.toml"


def pick(height: float, hand: str, seed: int = 0) -> dict:
    """One pick from ``height`` (m) with ``hand``: hand error (m), contact frames, duration
    (s), posture (stand, bend or crouch) and the scene geoms touched most."""
    with tempfile.TemporaryDirectory() as tmp:
        ctx = prepare(load_cycle_spec(write_workplace(Path(tmp), height, hand)))
        res = simulate_cycle(ctx, rng=seed, keep_timeline=True)
    jm = ctx.jointmap
    qpos = res.timeline.qpos
    z = qpos[:, jm.root + 2]
    bend = qpos[:, jm.adr("lumbar_flex")] + qpos[:, jm.adr("thoracic_flex")]
    posture = (
        "crouch"
        if z.min() < z[0] - 0.02
        else "bend"
        if bend.max() - bend[0] > np.radians(5.0)
        else "stand"
    )
    (arm,) = res.arms
    geoms = Counter(c.scene_geom for c in res.collisions)
    return {
        "error": arm.hand_error,
        "contacts": len(res.collisions),
        "touching": ", ".join(g for g, _ in geoms.most_common(2)) or "-",
        "duration": res.tasks[0].duration,
        "posture": posture,
    }


def _heights(text: str) -> tuple[float, ...]:
    """An argparse type: comma-separated heights in metres, each in (0.1, 2.5)."""
    try:
        out = tuple(float(x) for x in text.split(","))
    except ValueError:
        out = ()
    if not out or not all(0.1 < h < 2.5 for h in out):
        raise argparse.ArgumentTypeError(f"heights in metres between 0.1 and 2.5, got {text!r}")
    return out


def _hands(text: str) -> tuple[str, ...]:
    """An argparse type: comma-separated hands out of left, right, both."""
    out = tuple(text.split(","))
    if not out or not set(out) <= set(HANDS):
        raise argparse.ArgumentTypeError(f"hands out of {', '.join(HANDS)}, got {text!r}")
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--heights", type=_heights, default=HEIGHTS, help="metres, comma-separated")
    ap.add_argument("--hands", type=_hands, default=HANDS, help="left,right,both")
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args(argv)
    print(
        "height [m]  hand   hand error [mm]  contact frames  pick [s]  posture  touching",
        flush=True,
    )
    for height in a.heights:
        for hand in a.hands:
            r = pick(height, hand, a.seed)
            print(
                f"{height:10.2f}  {hand:<5}  {1000 * r['error']:15.1f}  {r['contacts']:14d}  "
                f"{r['duration']:8.2f}  {r['posture']:<7}  {r['touching']}",
                flush=True,
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
