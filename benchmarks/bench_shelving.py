"""Contacts of reaches into a shelving rack with compartments: the station's rack 1 given a
shelf at 0.7 m and one at 1.5 m, a pick from the top shelf, a place into the low compartment
(0.72-0.98 m, 20 cm deep), a pick from the far corner of the middle compartment with the right
hand and a place on the top shelf (a workplace unlike the shipped station, whose targets are
all on open shelves).

Prints, over ``--runs`` cycles of the station's workforce: contact frames (humanoid vs scene,
MuJoCo's collision check), runs with any contact, the largest hand error and the contacts per
task and body part.

First run 2026-11-28, 20 runs, seed 0 (``python benchmarks/bench_shelving.py``): with the code
of that session's start (4ed9cff) 2324 contact frames, every run touching (thumb, forearm and
palm through the low compartment's upper shelf, the forearm and palm over the top shelf's
edge, the head into the top shelf when stooping for the compartment); with the wrist's least
turn, the approach rising only as far as the space under a shelf allows, and crouching for the
low compartment: 133 frames in 5 runs (the forearm over the top shelf's edge, the right
forearm or palm on the rack's upright reaching into the far corner), median cycle 16.3 ->
16.9 s (the crouch and rise take MTM-1's bend and arise). With the default reach model
trained up to a top shelf (reach model v7, reachgen.END_BOX): 65 frames in 3 runs, median
cycle 17.3 s.

Run: python benchmarks/bench_shelving.py [--runs 20] [--seed 0]
"""

from __future__ import annotations

import argparse
import collections
import sys
import tempfile
from pathlib import Path

import numpy as np

from mjwalk.cycle.simulate import simulate_cycles
from mjwalk.cycle.spec import load_cycle_spec
from mjwalk.errors import MjwalkError

ROOT = Path(__file__).resolve().parents[1]
ANCHOR = '<site name="stand_rack1"'
SHELVES = """<geom name="rack1_shelf_top" type="box" size="0.4 0.25 0.02" pos="0 0 1.5"
            material="shelf"/>
      <geom name="rack1_shelf_mid" type="box" size="0.4 0.25 0.02" pos="0 0 0.7"
            material="shelf"/>
      <site name="rack1_high" pos="0.0 0.05 1.56" size="0.02" rgba="0 1 0 1"/>
      <site name="rack1_waist" pos="0.1 0.05 0.76" size="0.02" rgba="0 1 0 1"/>
      <site name="rack1_far" pos="-0.25 -0.1 1.08" size="0.02" rgba="0 1 0 1"/>
      """
CYCLE = """name = "shelving rack"
scene = "shelving.xml"
start = "stand_rack2"
[population]
mix = { adult = 0.65, older_adult = 0.15, fatigued = 0.20 }
[[task]]
kind = "walk"
site = "stand_rack1"
[[task]]
kind = "pick"
site = "rack1_high"
hand = "left"
[[task]]
kind = "place"
site = "rack1_waist"
hand = "left"
[[task]]
kind = "pick"
site = "rack1_far"
hand = "right"
[[task]]
kind = "place"
site = "rack1_high"
hand = "right"
"""


def write_workplace(folder: Path) -> Path:
    """The shelving scene and its cycle file in ``folder``; returns the cycle file."""
    xml = (ROOT / "scenes" / "assembly_station.xml").read_text()
    if ANCHOR not in xml:
        raise MjwalkError(f"scenes/assembly_station.xml has no {ANCHOR}...> to build on")
    (folder / "shelving.xml").write_text(xml.replace(ANCHOR, SHELVES + ANCHOR, 1))
    (folder / "shelving.toml").write_text(CYCLE)
    return folder / "shelving.toml"


def _count(text: str) -> int:
    """An argparse type: an integer >= 1 (argparse names the option and exits with status 2)."""
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be an integer >= 1, got {text!r}")
    return value


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=_count, default=20, help="cycles to simulate")
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        spec = load_cycle_spec(write_workplace(Path(tmp)))
        results = simulate_cycles(spec, a.runs, a.seed)
    per = collections.Counter()
    frames = 0
    for res in results:
        frames += len(res.collisions)
        for c in res.collisions:
            task = next((t for t in res.tasks if t.start <= c.time <= t.end), None)
            where = f"{task.kind} {task.site}" if task else "?"
            per[(where, c.body_part.split("_")[0], c.scene_geom)] += 1
    err = max(a_.hand_error for r in results for a_ in r.arms)
    print(f"{a.runs} runs of the shelving rack, seed {a.seed}")
    print(f"contact frames {frames}; runs with any {sum(bool(r.collisions) for r in results)}")
    print(f"largest hand error {1000 * err:.1f} mm")
    print("contact frames per task, body part, scene geom:")
    for (where, part, geom), n in per.most_common(10):
        print(f"  {n:5d}  {where:<18} {part:<8} {geom}")
    cycle = np.median([r.cycle_time for r in results])
    print(f"median cycle {cycle:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
