"""Offscreen rendering: frames are not blank, the humanoid shows where the camera projects it.

Whether this machine can render at all is decided once, before any test runs
(:func:`_no_gl_reason`: the backend mjwalk selects, :mod:`mjwalk.render._gl`, and one OpenGL context
made with it by mujoco alone); the module is skipped, with the reason, only when it cannot. Past
that, a render that fails (an MjwalkError included) fails its test.
"""

from __future__ import annotations

import os

os.environ.setdefault("MUJOCO_GL", "egl")

import mujoco
import numpy as np
import pytest

from mjwalk.errors import MjwalkError
from mjwalk.plan.synthetic import synthetic_walk as make_walk
from mjwalk.render import _ffmpeg
from mjwalk.render import video as render
from mjwalk.render._gl import available_backend
from mjwalk.timeline import timeline_from_walk


def _no_gl_reason() -> str | None:
    """Why no OpenGL context can render here (None: one can). Importing mjwalk.render above
    selected the backend (a user's MUJOCO_GL, else EGL, else OSMesa); the probe makes a 16 x 16
    context and MuJoCo's rendering context of an empty model in it with mujoco alone, so no
    mjwalk rendering code is under test in it."""
    backend = os.environ.get("MUJOCO_GL", "none")
    if backend == "none":
        return "no headless OpenGL backend: neither EGL nor OSMesa loads here"
    ctx = None
    try:
        ctx = mujoco.GLContext(16, 16)
        ctx.make_current()
        model = mujoco.MjModel.from_xml_string("<mujoco/>")
        mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_100).free()
    except Exception as exc:  # each backend raises its own (EGL, OSMesa, GLFW) error types
        return f"MUJOCO_GL={backend}: no OpenGL context renders here ({type(exc).__name__}: {exc})"
    finally:
        if ctx is not None:
            ctx.free()
    return None


NO_GL = _no_gl_reason()
pytestmark = pytest.mark.skipif(NO_GL is not None, reason=NO_GL or "")

SCENE = """<mujoco><worldbody><geom name="floor" type="plane" size="10 10 .1" rgba=".2 .6 .2 1"/>
<light pos="0 0 6" dir="0 0 -1" directional="true"/></worldbody></mujoco>"""


@pytest.fixture(scope="module")
def timeline():
    walk = make_walk(n_steps=5, radius=3.0)
    return timeline_from_walk(walk, mujoco.MjSpec.from_string(SCENE), fps=30)


def test_top_view_humanoid_at_projected_pixels(timeline):
    tl = timeline
    frames = [0, tl.n_frames // 2, tl.n_frames - 1]
    away = tl.qpos.copy()
    away[:, tl.jointmap.root + 2] -= 50.0  # same views (camera from x, y), humanoid under the floor
    bg_tl = type(tl)(**{**tl.__dict__, "qpos": away})
    fg = render_list(tl, frames)
    bg = render_list(bg_tl, frames, project_from=tl)
    for (img, (uv, top)), (img0, _) in zip(fg, bg, strict=True):
        assert img.std() > 5  # not blank
        mask = np.abs(img.astype(int) - img0.astype(int)).sum(-1) > 40
        assert mask.sum() > 300, "humanoid not visible"
        ys, xs = np.nonzero(mask)
        # perspective: the standing body spans the image segment from the projection of the
        # floor point under the pelvis (uv) to that of the head height above it (top); the
        # blob's centroid lies close to that segment, and the body covers the segment's middle
        c = np.array([xs.mean(), ys.mean()])
        seg = top - uv
        lam = np.clip((c - uv) @ seg / (seg @ seg), 0, 1)
        assert np.linalg.norm(c - (uv + lam * seg)) < 25
        u, v = np.round(uv + 0.5 * seg).astype(int)
        assert 15 <= u < img.shape[1] - 15 and 15 <= v < img.shape[0] - 15
        assert mask[v - 15 : v + 15, u - 15 : u + 15].mean() > 0.3


def render_list(tl, frames, project_from=None):
    out = []
    src = project_from or tl
    for i, img, r in render.render_frames(tl, "top", frames=frames, draw_path=False):
        x, y = src.root()[i][:2]
        uv = render.project(r, np.array([[x, y, 0.0], [x, y, 1.75]]))
        out.append((img.copy(), uv))
    return out


def test_track_view_and_path_drawn(timeline):
    tl = timeline
    ((_, with_path, _),) = list(render.render_frames(tl, "top", frames=[10]))
    ((_, without, _),) = list(render.render_frames(tl, "top", frames=[10], draw_path=False))
    ((_, track, r),) = list(render.render_frames(tl, "track", frames=[10]))
    uv = render.project(r, tl.root()[10][None])[0]
    drawn = np.abs(with_path.astype(int) - without.astype(int)).sum(-1) > 40
    assert drawn.sum() > 500  # the path and footprints add pixels
    # drawn pixels are reddish (orange path, red/blue footprints), not the green floor
    assert (with_path[drawn][:, 1] < with_path[drawn][:, [0, 2]].max(1) + 10).mean() > 0.8
    assert track.std() > 5
    assert abs(uv[0] - 320) < 2 and abs(uv[1] - 240) < 60  # tracking camera centres the pelvis


def test_render_video_atomic(tmp_path, timeline):
    import imageio.v2 as imageio

    short = type(timeline)(**{**timeline.__dict__, "qpos": timeline.qpos[:8], "t": timeline.t[:8]})
    out = tmp_path / "walk.mp4"
    render.render_video(short, out, camera="top", size=(320, 240), progress=False)
    assert out.exists() and list(tmp_path.iterdir()) == [out]
    frames = imageio.mimread(out)
    assert len(frames) == 8 and frames[0].shape == (240, 320, 3)
    with pytest.raises(MjwalkError, match="camera"):
        render.render_video(short, tmp_path / "x.mp4", camera="side")
    assert not (tmp_path / "x.mp4").exists()


@pytest.mark.slow  # among the fast tier's 4 longest (84-222 s in a loaded run): its 5 min budget
@pytest.mark.skipif(
    available_backend() == "none",
    reason="neither EGL nor OSMesa loads here (this test renders with MUJOCO_GL unset)",
)
def test_renders_headless_when_mujoco_was_imported_first():
    """MUJOCO_GL unset and mujoco imported before mjwalk.render (the scene and planning stages
    import it): importing mjwalk.render selects the headless backend and swaps its context into
    the loaded mujoco, so rendering works without a display."""
    import subprocess
    import sys

    code = (
        "import os, mujoco, numpy as np\n"
        "assert 'MUJOCO_GL' not in os.environ\n"
        "from mjwalk.plan.synthetic import synthetic_walk\n"
        "from mjwalk.timeline import timeline_from_walk\n"
        f"spec = mujoco.MjSpec.from_string({SCENE!r})\n"
        "tl = timeline_from_walk(synthetic_walk(n_steps=2), spec)\n"
        "import mjwalk.render as r\n"
        "(_, img, _), = list(r.render_frames(tl, 'top', size=(64, 48), frames=[0]))\n"
        "print(os.environ['MUJOCO_GL'], img.shape, int(img.std() > 1))\n"
    )
    env = {k: v for k, v in os.environ.items() if k not in ("MUJOCO_GL", "PYOPENGL_PLATFORM")}
    env.pop("DISPLAY", None)
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300
    )
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split() == [available_backend(), "(48,", "64,", "3)", "1"]


def test_fixed_camera_frames_identical_to_mujoco_renderer(timeline):
    """The fast loop (own context sized to the image, path geoms kept in the scene's first
    slots, reused buffers) draws exactly what mujoco.Renderer + update_scene + the path added
    after it drew before."""
    from mjwalk.body.humanoid import HUMAN_GROUP
    from mjwalk.render.viewpoint import fixed_view

    tl = timeline
    frames = [0, tl.n_frames // 3, tl.n_frames - 1]
    new = [img for _, img, _ in render.render_frames(tl, frames=frames, view=fixed_view(tl))]
    model = tl.model
    samples = int(model.vis.quality.offsamples)
    model.vis.quality.offsamples = 0
    try:
        ref = mujoco.Renderer(model, height=480, width=640)
    finally:
        model.vis.quality.offsamples = samples
    ref.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = False
    ref.scene.flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = False
    opt = mujoco.MjvOption()
    opt.geomgroup[HUMAN_GROUP] = 1
    data = mujoco.MjData(model)
    geoms = render.path_geoms(tl)
    try:
        for i, img in zip(frames, new, strict=True):
            data.qpos[:] = tl.qpos[i]
            mujoco.mj_kinematics(model, data)
            ref.update_scene(data, render.camera_for(tl, i, "track"), scene_option=opt)
            render.add_path_geoms(ref.scene, geoms)
            assert np.array_equal(ref.render(), img)
    finally:
        ref.close()


def test_render_video_drawing_error_leaves_no_file(tmp_path, timeline, monkeypatch):
    short = type(timeline)(**{**timeline.__dict__, "qpos": timeline.qpos[:6], "t": timeline.t[:6]})

    def broken(cam, tl, frame, *args):
        if frame == 3:
            raise RuntimeError("camera broke")
        return set_camera(cam, tl, frame, *args)

    set_camera = render._set_camera
    monkeypatch.setattr(render, "_set_camera", broken)
    out = tmp_path / "walk.mp4"
    with pytest.raises(MjwalkError, match="camera broke"):
        render.render_video(short, out, camera="top", size=(160, 120), progress=False)
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(MjwalkError, match="size"):
        render.render_video(short, out, size=(0, 480), progress=False)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    "ending, why",
    [
        ("echo '[out#0/mp4 @ 0x1] Error writing trailer: File too large' >&2; exit 1",
         "Error writing trailer: File too large"),
        ("kill -XFSZ $$", "killed by SIGXFSZ"),
    ],
    ids=["error", "signal"],
)  # fmt: skip
def test_an_ffmpeg_failing_after_the_last_frame_leaves_no_video(
    tmp_path, timeline, monkeypatch, ending, why
):
    """ffmpeg may read every frame and fail only while it flushes the encoder and writes the
    file's index (a file size limit reached then: the race CI met, where a cut 20 kB mp4 was
    renamed into place as finished). Its exit status is checked, so the write fails and no
    file is left. A stand-in ffmpeg reads all frames, then ends as the real one can."""
    short = type(timeline)(**{**timeline.__dict__, "qpos": timeline.qpos[:4], "t": timeline.t[:4]})
    fake = tmp_path / "bin" / "ffmpeg"
    fake.parent.mkdir()
    fake.write_text(f"#!/bin/sh\ncat > /dev/null\n{ending}\n")
    fake.chmod(0o755)
    monkeypatch.setattr(_ffmpeg.imageio_ffmpeg, "get_ffmpeg_exe", lambda: str(fake))
    out = tmp_path / "out" / "walk.mp4"
    with pytest.raises(OSError, match=f"cannot write {out}: ffmpeg stopped writing it: {why}"):
        render.render_video(short, out, camera="top", size=(32, 24), progress=False)
    assert not (tmp_path / "out").exists()


def test_an_ffmpeg_failing_while_frames_are_sent_names_why(tmp_path, timeline, monkeypatch):
    """An ffmpeg that stops reading before the last frame (here: at once, with a message)
    breaks the pipe; the error names ffmpeg's reason as at the end of the file, and no file
    is left. Frames of 320x240 (230 kB) overfill the pipe's buffer, so the write itself fails."""
    short = type(timeline)(**{**timeline.__dict__, "qpos": timeline.qpos[:4], "t": timeline.t[:4]})
    fake = tmp_path / "bin" / "ffmpeg"
    fake.parent.mkdir()
    fake.write_text("#!/bin/sh\necho '[out#0/mp4 @ 0x1] No space left on device' >&2\nexit 1\n")
    fake.chmod(0o755)
    monkeypatch.setattr(_ffmpeg.imageio_ffmpeg, "get_ffmpeg_exe", lambda: str(fake))
    out = tmp_path / "out" / "walk.mp4"
    with pytest.raises(
        OSError, match=f"cannot write {out}: ffmpeg stopped writing it: No space left on device"
    ):
        render.render_video(short, out, camera="top", size=(320, 240), progress=False)
    assert not (tmp_path / "out").exists()
