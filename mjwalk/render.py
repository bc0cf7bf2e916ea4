"""Offscreen video of a Timeline: tracking or top camera, the planned path drawn into the scene.

Importing this module selects a headless OpenGL backend (:func:`mjwalk._gl.ensure_headless_backend`:
a ``MUJOCO_GL`` the user set, else ``egl`` when libEGL loads, else ``osmesa`` when libOSMesa
loads), also when mujoco was imported before. If no backend works, rendering raises an
MjwalkError that names the Debian package to install (``libegl1`` or ``libosmesa6``).

World frame: metres, z up; image pixels (u right, v down) from the top-left corner.
"""

from __future__ import annotations

import os

from mjwalk._gl import available_backend, ensure_headless_backend

#: the backend chosen at import ("none" when neither EGL nor OSMesa loads).
_SELECTED = ensure_headless_backend()


import mujoco  # noqa: E402
import numpy as np  # noqa: E402

from mjwalk._io import atomic_path  # noqa: E402
from mjwalk.body.humanoid import HUMAN_GROUP  # noqa: E402
from mjwalk.errors import InputError, MjwalkError  # noqa: E402
from mjwalk.timeline.timeline import Timeline  # noqa: E402

#: Colour of the drawn path (RGBA) and of the drawn footprints (left, right).
PATH_RGBA = np.array([1.0, 0.55, 0.0, 1.0], dtype=np.float32)
FOOT_RGBA = (
    np.array([0.9, 0.2, 0.2, 0.9], dtype=np.float32),
    np.array([0.2, 0.4, 0.95, 0.9], dtype=np.float32),
)
CAMERAS = ("track", "top")


def _renderer(model: mujoco.MjModel, size: tuple[int, int]) -> mujoco.Renderer:
    width, height = size
    model.vis.global_.offwidth = max(int(model.vis.global_.offwidth), int(width))
    model.vis.global_.offheight = max(int(model.vis.global_.offheight), int(height))
    try:
        return mujoco.Renderer(model, height=int(height), width=int(width))
    except Exception as exc:
        backend = os.environ.get("MUJOCO_GL", "")
        avail = available_backend()
        if backend in ("", "glfw") and avail != "none":
            raise MjwalkError(
                f"offscreen rendering failed: MUJOCO_GL={backend or 'unset'} uses GLFW, which "
                f"needs a display ({exc}); run with MUJOCO_GL={avail} set in the environment "
                f"({avail} is available here)"
            ) from exc
        hint = {
            "egl": "install the Debian package libegl1 (and a Mesa EGL driver, libegl-mesa0), "
            "or set MUJOCO_GL=osmesa with libosmesa6 installed",
            "osmesa": "install the Debian package libosmesa6, or set MUJOCO_GL=egl with libegl1",
        }.get(
            backend,
            "install the Debian package libegl1 (MUJOCO_GL=egl) or libosmesa6 (MUJOCO_GL=osmesa)",
        )
        raise MjwalkError(
            f"offscreen rendering failed (MUJOCO_GL={backend or 'unset'}): {exc}; {hint}"
        ) from exc


def camera_for(timeline: Timeline, frame: int, camera: str, size=(640, 480)) -> mujoco.MjvCamera:
    """The free camera of ``camera`` ("track" or "top") at ``frame``.

    ``track`` looks at the pelvis from 3.5 m, 15 deg above, from the walker's left side (relative
    to the start heading of the walk). ``top`` looks straight down on the whole walk (path and
    the humanoid's whole extent), +x to the right and +y up in the image.
    """
    if camera not in CAMERAS:
        raise MjwalkError(f"render: unknown camera {camera!r}; use one of {CAMERAS}")
    cam = mujoco.MjvCamera()
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    root = timeline.root()
    if camera == "track":
        r = timeline.jointmap.root
        q = timeline.qpos[0, r + 3 : r + 7]
        yaw0 = 2 * np.arctan2(q[3], q[0])
        cam.lookat[:] = [root[frame, 0], root[frame, 1], 0.9 * root[frame, 2]]
        cam.distance = 3.5
        cam.elevation = -15.0
        cam.azimuth = float(np.rad2deg(yaw0)) - 90.0
    else:
        lo = root[:, :2].min(0) - 1.0
        hi = root[:, :2].max(0) + 1.0
        centre = 0.5 * (lo + hi)
        w, h = size
        fovy = np.deg2rad(timeline.model.vis.global_.fovy)
        half = max(0.5 * (hi[1] - lo[1]), 0.5 * (hi[0] - lo[0]) * h / w)
        cam.lookat[:] = [centre[0], centre[1], 0.0]
        cam.distance = float(half / np.tan(fovy / 2))
        cam.elevation = -90.0
        cam.azimuth = 90.0
    return cam


def project(renderer: mujoco.Renderer, points: np.ndarray) -> np.ndarray:
    """(N, 2) pixel coordinates (u right, v down) of world points (N, 3) in the last rendered
    view of ``renderer`` (after ``update_scene``), from its OpenGL camera frustum."""
    scn = renderer.scene
    gl = scn.camera[0]
    pos, fwd, up = np.array(gl.pos), np.array(gl.forward), np.array(gl.up)
    if len(scn.camera) > 1:  # stereo off: both cameras equal; average to be safe
        pos = 0.5 * (pos + np.array(scn.camera[1].pos))
    right = np.cross(fwd, up)
    d = np.atleast_2d(points) - pos
    x, y, z = d @ right, d @ up, d @ fwd
    near = gl.frustum_near
    xn, yn = near * x / z, near * y / z
    # frustum_width 0 means "from the viewport aspect ratio" (as mjr_render does)
    half = gl.frustum_width or 0.5 * (gl.frustum_top - gl.frustum_bottom) * renderer.width / (
        renderer.height
    )
    left, rightb = gl.frustum_center - half, gl.frustum_center + half
    u = renderer.width * (xn - left) / (rightb - left)
    v = renderer.height * (gl.frustum_top - yn) / (gl.frustum_top - gl.frustum_bottom)
    return np.column_stack([u, v])


def _yaw_mat(yaw: np.ndarray) -> np.ndarray:
    """(N, 9) row-major rotation matrices about z by ``yaw`` (radians)."""
    c, s = np.cos(yaw), np.sin(yaw)
    z, o = np.zeros_like(c), np.ones_like(c)
    return np.column_stack([c, -s, z, s, c, z, z, z, o])


def path_geoms(timeline: Timeline, width: float = 0.02, spacing: float = 0.05) -> list[tuple]:
    """The planned path and footprints as flat boxes, ``(size, pos, mat, rgba)`` per geom.

    The path is resampled every ``spacing`` metres of arc length (at most 400 segments), each
    segment a box ``width`` wide and 2 mm thick lying 3 mm above the floor; each footprint a
    0.24 x 0.09 m box. Flat boxes have 12 triangles where capsules have hundreds, and the list is
    computed once per timeline: drawing it costs about 1 ms per frame instead of about 10 ms.
    """
    walk = timeline.walk
    if walk is None:
        return []
    pts = np.asarray(walk.xy, dtype=float)
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    geoms: list[tuple] = []
    if arc[-1] > 1e-6:
        n = int(np.clip(np.ceil(arc[-1] / spacing), 1, 400))
        s = np.linspace(0.0, arc[-1], n + 1)
        xy = np.column_stack([np.interp(s, arc, pts[:, 0]), np.interp(s, arc, pts[:, 1])])
        a, b = xy[:-1], xy[1:]
        d = b - a
        half = 0.5 * np.linalg.norm(d, axis=1) + 0.5 * width  # overlap hides the joints
        mid = 0.5 * (a + b)
        mats = _yaw_mat(np.arctan2(d[:, 1], d[:, 0]))
        for k in range(len(a)):
            geoms.append(
                (
                    np.array([half[k], 0.5 * width, 0.001]),
                    np.array([mid[k, 0], mid[k, 1], 0.003]),
                    mats[k],
                    PATH_RGBA,
                )
            )
    for st in walk.steps:
        x, y, yaw = st.foot
        c, s_ = np.cos(yaw), np.sin(yaw)
        geoms.append(
            (
                np.array([0.12, 0.045, 0.002]),
                np.array([x + 0.03 * c, y + 0.03 * s_, 0.002]),
                _yaw_mat(np.array([yaw]))[0],
                FOOT_RGBA[st.side == "right"],
            )
        )
    return geoms


def _draw_path(scn: mujoco.MjvScene, geoms: list[tuple]) -> None:
    """Append precomputed :func:`path_geoms` to the scene as user geoms (as many as fit)."""
    box = mujoco.mjtGeom.mjGEOM_BOX
    for size, pos, mat, rgba in geoms:
        if scn.ngeom >= scn.maxgeom:
            break
        mujoco.mjv_initGeom(scn.geoms[scn.ngeom], box, size, pos, mat, rgba)
        scn.ngeom += 1


def render_frames(
    timeline: Timeline,
    camera: str = "track",
    size: tuple[int, int] = (640, 480),
    frames=None,
    draw_path: bool = True,
    progress: bool = False,
    fast: bool = True,
):
    """Yield ``(frame_index, rgb image (H, W, 3) uint8, renderer)`` for the timeline's frames.

    ``fast`` turns multisampling, shadows and reflections off (about 8x faster on software
    OpenGL: 640x480 at ~25 fps instead of ~3 on this project's 2-core test machine)."""
    from tqdm import tqdm

    model = timeline.model
    samples = int(model.vis.quality.offsamples)
    if fast:  # multisampling costs ~4x on software OpenGL (llvmpipe)
        model.vis.quality.offsamples = 0
    try:
        renderer = _renderer(model, size)
    finally:
        model.vis.quality.offsamples = samples
    data = mujoco.MjData(model)
    idx = range(timeline.n_frames) if frames is None else frames
    opt = mujoco.MjvOption()
    opt.geomgroup[HUMAN_GROUP] = 1  # MuJoCo shows groups 0-2 only by default
    if fast:  # ... and much of the rest on shadows and reflections
        renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = False
        renderer.scene.flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = False
    geoms = path_geoms(timeline) if draw_path else []
    try:
        for i in tqdm(idx, disable=not progress, desc="render", unit="frame"):
            data.qpos[:] = timeline.qpos[i]
            mujoco.mj_kinematics(model, data)
            renderer.update_scene(data, camera_for(timeline, i, camera, size), scene_option=opt)
            _draw_path(renderer.scene, geoms)
            yield i, renderer.render(), renderer
    finally:
        renderer.close()


def render_video(
    timeline: Timeline,
    path: str | os.PathLike,
    camera: str = "track",
    size: tuple[int, int] = (640, 480),
    fps: float | None = None,
    progress: bool = True,
    draw_path: bool = True,
) -> None:
    """Render the timeline offscreen to an mp4 (H.264 via imageio-ffmpeg), atomically.

    Args:
        timeline: the poses to show.
        path: output video file (written to a temporary file, renamed on success).
        camera: ``"track"`` (follows the pelvis) or ``"top"`` (whole walk from above).
        size: (width, height) in pixels.
        fps: video frame rate; defaults to the timeline's; frames are picked to keep real time.
        progress: show a tqdm progress bar.
        draw_path: draw the planned path and footprints into the scene.
    """
    import imageio.v2 as imageio

    if camera not in CAMERAS:
        raise MjwalkError(f"render_video: unknown camera {camera!r}; use one of {CAMERAS}")
    width, height = (int(v) for v in size)
    if min(width, height) < 16 or width % 2 or height % 2:
        raise InputError(
            f"render_video: size {width}x{height}: width and height must be even numbers of "
            "pixels, at least 16 (H.264)"
        )
    fps = float(timeline.fps if fps is None else fps)
    if not (np.isfinite(fps) and fps > 0):
        raise InputError(f"render_video: fps must be a positive number, got {fps!r}")
    n_out = max(1, int(np.floor(timeline.duration * fps + 1e-9)) + 1)
    frames = np.clip(
        np.round(np.arange(n_out) / fps * timeline.fps).astype(int), 0, timeline.n_frames - 1
    )
    with atomic_path(path, suffix=".mp4") as tmp:
        writer = imageio.get_writer(
            str(tmp), format="FFMPEG", fps=fps, codec="libx264", macro_block_size=1, quality=7
        )
        try:
            for _, img, _ in render_frames(timeline, camera, size, frames, draw_path, progress):
                writer.append_data(img)
        finally:
            writer.close()
