"""Video rendering speed: the drawing + encoding loop before this change vs now, same process.

Renders the main job's video (``mjwalk simulate scenes/assembly_station.toml --video``: run 0
of seed 0, 640x480, 30 frames/s, H.264) with

- ``old``: the loop as it was (``mujoco.Renderer`` with the model's 1280x960 framebuffer,
  ``update_scene`` then ~400 path boxes added in Python, ``render()`` allocating and flipping
  every frame, ``imageio`` ``append_data`` in the drawing thread), fixed camera;
- ``new, fixed camera``: :func:`mjwalk.render.render_video` with the same camera (checks the
  frames are pixel-identical to the old loop's);
- ``new, clear view``: :func:`mjwalk.render.render_video` as the CLI runs it (tracking camera
  chosen by :func:`mjwalk.render.viewpoint.track_view`, its cost included).

Prints frames/s (wall clock; the goal is >= 30) and CPU milliseconds per frame (this process,
all threads, plus the ffmpeg child: robust to other load on the machine), and the ratios.

Run: MUJOCO_GL=egl PYTHONPATH=. python3 benchmarks/bench_render.py [--frames 600] [--full]
(``--full`` renders the whole cycle, 2645 frames, with the new loop: the main job's figure.)
"""

from __future__ import annotations

import argparse
import os
import resource
import tempfile
import time
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco
import numpy as np

from mjwalk.body.humanoid import HUMAN_GROUP
from mjwalk.render import video as render
from mjwalk.render.viewpoint import fixed_view

ROOT = Path(__file__).parents[1]


def station_timeline():
    """The main job's video timeline: run 0 of seed 0, as ``mjwalk simulate --video``."""
    from mjwalk.cycle.simulate import prepare, simulate_cycle
    from mjwalk.cycle.spec import load_cycle_spec

    ctx = prepare(load_cycle_spec(ROOT / "scenes" / "assembly_station.toml"))
    rng = np.random.default_rng(np.random.SeedSequence([0, 0]))
    return simulate_cycle(ctx, rng, keep_timeline=True, collisions=False).timeline


def old_frames(tl, frames, size=(640, 480)):
    """The drawing loop before this change (fixed camera), yielding new top-down images."""
    model = tl.model
    model.vis.global_.offwidth = max(int(model.vis.global_.offwidth), size[0])
    model.vis.global_.offheight = max(int(model.vis.global_.offheight), size[1])
    samples = int(model.vis.quality.offsamples)
    model.vis.quality.offsamples = 0
    try:
        renderer = mujoco.Renderer(model, height=size[1], width=size[0])
    finally:
        model.vis.quality.offsamples = samples
    data = mujoco.MjData(model)
    opt = mujoco.MjvOption()
    opt.geomgroup[HUMAN_GROUP] = 1
    renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = False
    renderer.scene.flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = False
    geoms = render.path_geoms(tl)
    try:
        for i in frames:
            data.qpos[:] = tl.qpos[i]
            mujoco.mj_kinematics(model, data)
            renderer.update_scene(data, render.camera_for(tl, i, "track"), scene_option=opt)
            render.add_path_geoms(renderer.scene, geoms)
            yield i, renderer.render()
    finally:
        renderer.close()


def old_video(tl, path, frames, fps=30.0):
    import imageio.v2 as imageio

    writer = imageio.get_writer(
        str(path), format="FFMPEG", fps=fps, codec="libx264", macro_block_size=1, quality=7
    )
    try:
        for _, img in old_frames(tl, frames):
            writer.append_data(img)
    finally:
        writer.close()


def new_video(tl, path, frames, view, fps=30.0):
    """render_video on a timeline cut to ``frames`` (consecutive frames from 0)."""
    cut = type(tl)(**{**tl.__dict__, "qpos": tl.qpos[: len(frames)], "t": tl.t[: len(frames)]})
    if view is not None:
        view = type(view)(
            **{
                **view.__dict__,
                "azimuth": view.azimuth[: len(frames)],
                "elevation": view.elevation[: len(frames)],
            }
        )
    render.render_video(cut, path, "track", (640, 480), fps=fps, progress=False, view=view)


def timed(fn, n):
    """(frames/s wall, CPU ms per frame incl. child processes) of fn()."""
    r0 = resource.getrusage(resource.RUSAGE_SELF)
    c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    fn()
    dt = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_SELF)
    c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = sum(
        getattr(b, f) - getattr(a, f)
        for a, b in ((r0, r1), (c0, c1))
        for f in ("ru_utime", "ru_stime")
    )
    return n / dt, 1000 * cpu / n


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frames", type=int, default=600, help="frames per compared run")
    ap.add_argument("--full", action="store_true", help="also the whole cycle, new loop")
    args = ap.parse_args()
    print(
        f"MUJOCO_GL={os.environ['MUJOCO_GL']}, load average {os.getloadavg()[0]:.1f} "
        f"on {os.cpu_count()} cores"
    )
    tl = station_timeline()
    n = min(args.frames, tl.n_frames)
    frames = np.arange(n)
    print(f"station cycle: {tl.n_frames} frames at {tl.fps:g} fps; comparing the first {n}")

    # pixel identity for the fixed camera (a sample of frames)
    fixed = fixed_view(tl)
    pick = frames[:: max(1, n // 20)]
    old = dict(old_frames(tl, pick))
    new = {i: img for i, img, _ in render.render_frames(tl, "track", frames=pick, view=fixed)}
    same = sum(np.array_equal(old[i], new[i]) for i in pick)
    print(f"fixed camera, old vs new loop: {same}/{len(pick)} sampled frames pixel-identical")

    t0 = time.perf_counter()
    view = render.track_view(tl)
    t_view = time.perf_counter() - t0
    print(
        f"track_view (sight lines, whole cycle): {t_view:.2f} s; samples with feet in sight: "
        f"{view.visible[:, 3:].all(1).mean():.1%} (fixed camera "
        f"{view.visible_preferred[:, 3:].all(1).mean():.1%}), all targets "
        f"{view.visible.all(1).mean():.1%} ({view.visible_preferred.all(1).mean():.1%})"
    )
    with tempfile.TemporaryDirectory() as tmp:
        a, b, c = (Path(tmp) / f"{k}.mp4" for k in "abc")
        runs = {}
        for label, fn in (
            ("old loop, fixed camera", lambda: old_video(tl, a, frames)),
            ("new loop, fixed camera", lambda: new_video(tl, b, frames, fixed)),
            ("new loop, clear view (+track_view)", lambda: new_video(tl, c, frames, None)),
        ):
            runs[label] = timed(fn, n)
        base_fps, base_cpu = runs["old loop, fixed camera"]
        for label, (fps, cpu) in runs.items():
            print(
                f"640x480 + H.264, {label:36s}: {fps:5.1f} frames/s (x{fps / base_fps:.2f}), "
                f"CPU {cpu:5.1f} ms/frame (x{cpu / base_cpu:.2f})"
            )
        sizes = ", ".join(f"{p.stat().st_size / 1e3:.0f} kB" for p in (a, b, c))
        print(f"video sizes (old, new fixed, new clear view): {sizes}")
        if args.full:
            fps, cpu = timed(
                lambda: render.render_video(
                    tl, Path(tmp) / "full.mp4", "track", (640, 480), fps=30, progress=False
                ),
                tl.n_frames,
            )
            print(
                f"main job's video ({tl.n_frames} frames, clear view, new loop): {fps:.1f} "
                f"frames/s, {tl.n_frames / fps:.0f} s, CPU {cpu:.1f} ms/frame "
                f"(goal >= 30 frames/s)"
            )


if __name__ == "__main__":
    main()
