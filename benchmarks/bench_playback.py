"""Playback and rendering speed: frames per second of ``iter_frames`` (kinematics only, target
>= 1000) and of offscreen rendering at 640x480 (target >= 30).

Run: python benchmarks/bench_playback.py
"""

from __future__ import annotations

import os
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco

from mjwalk.plan.synthetic import synthetic_walk
from mjwalk.timeline import collision_report, iter_frames, timeline_from_walk

SCENE = Path(__file__).parents[1] / "scenes" / "open_floor.xml"


def main() -> None:
    walk = synthetic_walk(n_steps=20)
    scene = (
        SCENE
        if SCENE.exists()
        else mujoco.MjSpec.from_string(
            '<mujoco><worldbody><geom name="floor" type="plane" size="20 20 .1"/>'
            "</worldbody></mujoco>"
        )
    )
    t0 = time.perf_counter()
    tl = timeline_from_walk(walk, scene, fps=30)
    print(
        f"timeline_from_walk: {walk.duration:.1f} s walk, {tl.n_frames} frames "
        f"in {time.perf_counter() - t0:.3f} s"
    )
    t0 = time.perf_counter()
    for _ in range(5):
        for _ in iter_frames(tl):
            pass
    dt = time.perf_counter() - t0
    print(f"playback (mj_kinematics per frame): {5 * tl.n_frames / dt:.0f} fps (target >= 1000)")
    t0 = time.perf_counter()
    collision_report(tl)
    dt = time.perf_counter() - t0
    print(f"collision_report: {tl.n_frames / dt:.0f} frames/s")
    from mjwalk.render import render_frames

    n = 60
    station = SCENE.parent / "assembly_station.xml"
    for label, t in (("open floor", tl), ("station", timeline_from_walk(walk, station, fps=30))):
        if t is not tl and not station.exists():
            continue
        for cam in ("track", "top"):
            t0 = time.perf_counter()
            for _ in render_frames(t, cam, size=(640, 480), frames=range(n)):
                pass
            dt = time.perf_counter() - t0
            print(
                f"rendering 640x480 ({os.environ.get('MUJOCO_GL')}, {label}, {cam} camera, "
                f"path drawn): {n / dt:.1f} fps (target >= 30, ratio {n / dt / 30:.2f})"
            )


if __name__ == "__main__":
    main()
