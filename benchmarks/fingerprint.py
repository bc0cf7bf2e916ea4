"""Fingerprints of mjwalk's outputs for fixed seeds: SHA-256 digests to compare before and after a
behaviour-preserving change (issue 13's restructure).

Compared outputs:
- ``walks``: 20 hybrid-A* walks (default model, seed 0) in each of 3 scenes: sample times,
  positions, headings and every step (side, indices, footprint, stance foot);
- ``legs``: the leg motion (joint angles, root, contacts) of the first 5 walks of each scene;
- ``timeline``: the timeline qpos of the first station walk with swing arms and with gait-pose arms;
- ``cycle``: the timeline qpos, cycle time and contacts of 2 simulated station cycles (rng 0, 1);
- ``simulate``: report.md, report.json, walks.csv, cycles.csv, spaghetti.png and histograms.png of
  ``mjwalk simulate scenes/assembly_station.toml --runs 4 --seed 0`` in a temporary directory
  (the report has no wall-clock fields; the checkout's path, which the report names, is
  replaced by ``<repo>`` so checkouts in different folders compare);
- ``frames``: raw pixels of 10 rendered frames (320x240, track camera) of cycle rng 0 and 2 frames
  of the top camera.

Run: MUJOCO_GL=egl PYTHONPATH=. python3 benchmarks/fingerprint.py > /tmp/fp.txt
(Each line: ``name sha256``; a change in one output changes its line only.)
"""

from __future__ import annotations

import hashlib
import os
import sys
import tempfile
from contextlib import redirect_stdout
from pathlib import Path

import numpy as np

os.environ.setdefault("MUJOCO_GL", "egl")
ROOT = Path(__file__).resolve().parents[1]
SCENES = ROOT / "scenes"
ROUTES = (
    ("assembly_station", "stand_rack2", "stand_car1"),
    ("corridor", "entry", "exit"),
    ("open_floor", "west", "east"),
)


class Digest:
    """SHA-256 over arrays (dtype, shape and bytes) and strings, in order."""

    def __init__(self) -> None:
        self.h = hashlib.sha256()

    def add(self, *items) -> Digest:
        for x in items:
            if isinstance(x, str | bytes):
                self.h.update(x.encode() if isinstance(x, str) else x)
            else:
                a = np.ascontiguousarray(np.asarray(x))
                self.h.update(f"{a.dtype}{a.shape}".encode())
                self.h.update(a.tobytes())
        return self

    def hex(self) -> str:
        return self.h.hexdigest()


def _walk_digest(d: Digest, walk) -> None:
    d.add(walk.t, walk.xy, walk.yaw)
    for s in walk.steps:
        d.add(str(s.side), np.array([s.start, s.end]), s.foot, s.stance)


def _timeline_from_walk():
    try:
        from mjwalk.timeline import timeline_from_walk
    except ImportError:
        from mjwalk.playback import timeline_from_walk
    return timeline_from_walk


def main() -> None:
    from mjwalk.body.legs import legs_from_walk
    from mjwalk.cycle.simulate import simulate_cycle
    from mjwalk.cycle.spec import load_cycle_spec
    from mjwalk.gait.default import default_model
    from mjwalk.plan.walks import plan_walks
    from mjwalk.world import load_workplace

    out: list[tuple[str, str]] = []
    model = default_model(progress=False)
    first = None
    for scene, start, goal in ROUTES:
        wp = load_workplace(SCENES / f"{scene}.xml")
        walks = plan_walks(wp, start, goal, model, n=20, seed=0)
        d = Digest()
        for w in walks:
            _walk_digest(d, w)
        out.append((f"walks/{scene}", d.hex()))
        d = Digest()
        for w in walks[:5]:
            legs = legs_from_walk(w)
            for name in sorted(legs.angles):
                d.add(name, legs.angles[name])
            d.add(legs.t, legs.root, legs.yaw, legs.contact, legs.phase)
            for side in (("l", "left"), ("r", "right")):  # keys "l"/"r" or "left"/"right"
                key = side[0] if side[0] in legs.ankle else side[1]
                d.add(legs.ankle[key], legs.pitch[key])
        out.append((f"legs/{scene}", d.hex()))
        if first is None:
            first = walks[0]

    timeline_from_walk = _timeline_from_walk()
    station = SCENES / "assembly_station.xml"
    tl = timeline_from_walk(first, station, fps=30)
    out.append(("timeline/swing", Digest().add(tl.qpos, tl.t, tl.contact).hex()))
    tl = timeline_from_walk(first, station, fps=30, arms="gaitpose", rng=np.random.default_rng(3))
    out.append(("timeline/gaitpose", Digest().add(tl.qpos).hex()))

    spec = load_cycle_spec(SCENES / "assembly_station.toml")
    cycles = []
    for seed in (0, 1):
        r = simulate_cycle(spec, rng=seed, keep_timeline=True)
        cycles.append(r)
        d = Digest().add(r.timeline.qpos, np.array([r.cycle_time]))
        for c in r.collisions:
            d.add(repr(c))
        for w in r.walks:
            d.add(repr(w.route), np.array([w.length]))
        for task in r.tasks:
            d.add(repr(task))
        out.append((f"cycle/rng{seed}", d.hex()))

    from mjwalk.cli import main as cli_main

    with tempfile.TemporaryDirectory() as tmp:
        with open(os.devnull, "w") as null, redirect_stdout(null):
            cli_main(
                [
                    "simulate",
                    str(SCENES / "assembly_station.toml"),
                    "--runs",
                    "4",
                    "--seed",
                    "0",
                    "--jobs",
                    "1",
                    "--out",
                    tmp,
                    "--quiet",
                ]
            )
        for name in sorted(os.listdir(tmp)):
            data = Path(tmp, name).read_bytes()
            if name.endswith((".md", ".json", ".csv")):  # the report names the scene's path
                data = data.replace(str(ROOT).encode(), b"<repo>")
            out.append((f"simulate/{name}", hashlib.sha256(data).hexdigest()))

    from mjwalk.render import render_frames

    tl = cycles[0].timeline
    idx = np.linspace(0, tl.n_frames - 1, 10).round().astype(int)
    d = Digest()
    for _, img, _ in render_frames(tl, "track", size=(320, 240), frames=idx):
        d.add(img)
    out.append(("frames/track", d.hex()))
    d = Digest()
    for _, img, _ in render_frames(tl, "top", size=(320, 240), frames=idx[[2, 7]]):
        d.add(img)
    out.append(("frames/top", d.hex()))

    for name, h in out:
        print(f"{name} {h}")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
