"""Offscreen video of a Timeline: tracking or top camera, the planned path drawn into the scene.

Importing this module selects a headless OpenGL backend
(:func:`mjwalk.render._gl.ensure_headless_backend`: a ``MUJOCO_GL`` the user set, else ``egl``
when libEGL loads, else ``osmesa`` when libOSMesa loads), also when mujoco was imported before.
If no backend works, rendering raises an MjwalkError that names the Debian package to install
(``libegl1`` or ``libosmesa6``).

World frame: metres, z up; image pixels (u right, v down) from the top-left corner.
"""

from __future__ import annotations

import os
import queue
import threading

from mjwalk.render._gl import available_backend, ensure_headless_backend

#: the backend chosen at import ("none" when neither EGL nor OSMesa loads).
_SELECTED = ensure_headless_backend()


import mujoco  # noqa: E402
import numpy as np  # noqa: E402
from tqdm import tqdm  # noqa: E402

from mjwalk._args import check_fps  # noqa: E402
from mjwalk._io import atomic_path  # noqa: E402
from mjwalk.body.humanoid import HUMAN_GROUP  # noqa: E402
from mjwalk.errors import InputError, MjwalkError  # noqa: E402
from mjwalk.render._ffmpeg import FfmpegWriter  # noqa: E402
from mjwalk.render.pathgeoms import (  # noqa: E402
    add_path_geoms,
    path_geoms,
)
from mjwalk.render.viewpoint import (  # noqa: E402
    LOOKAT_HEIGHT,
    TRACK_DISTANCE,
    TRACK_ELEVATION,
    TrackView,
    preferred_azimuth,
    track_view,
)
from mjwalk.timeline.parts import PartTrack  # noqa: E402
from mjwalk.timeline.timeline import Timeline  # noqa: E402

CAMERAS = ("track", "top")


def camera_for(
    timeline: Timeline,
    frame: int,
    camera: str,
    size=(640, 480),
    view: TrackView | None = None,
) -> mujoco.MjvCamera:
    """The free camera of ``camera`` ("track" or "top") at ``frame``.

    ``track`` looks at the pelvis from :data:`~mjwalk.render.viewpoint.TRACK_DISTANCE` (3.5 m), from
    the azimuth and elevation of ``view`` (:func:`~mjwalk.render.viewpoint.track_view`) or, without
    one, from 15 deg above on the walker's left side (relative to the start heading of the
    walk). ``top`` looks straight down on the whole walk (path and the humanoid's whole
    extent), +x to the right and +y up in the image.

    Args:
        timeline: the poses to film.
        frame: the frame's index.
        camera: ``"track"`` or ``"top"``.
        size: image (width, height), pixels (the top camera's framing).
        view: the tracking camera's angles per frame, or None.

    Returns:
        The free camera.
    """
    if camera not in CAMERAS:
        raise MjwalkError(f"render: unknown camera {camera!r}; use one of {CAMERAS}")
    cam = mujoco.MjvCamera()
    _set_camera(cam, timeline, frame, camera, size, view)
    return cam


def _set_camera(cam, timeline: Timeline, frame: int, camera: str, size, view) -> None:
    """Write the free camera of :func:`camera_for` into ``cam``."""
    cam.type = mujoco.mjtCamera.mjCAMERA_FREE
    r = timeline.jointmap.root
    if camera == "track":
        x, y, z = timeline.qpos[frame, r : r + 3]
        cam.lookat[:] = [x, y, LOOKAT_HEIGHT * z]
        cam.distance = TRACK_DISTANCE
        if view is None:
            cam.elevation = TRACK_ELEVATION
            cam.azimuth = preferred_azimuth(timeline)
        else:
            cam.elevation = float(view.elevation[frame])
            cam.azimuth = float(view.azimuth[frame])
    else:
        root = timeline.root()
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


def project(renderer: mujoco.Renderer, points: np.ndarray) -> np.ndarray:
    """(N, 2) pixel coordinates (u right, v down) of world points (N, 3) in the last rendered
    view of ``renderer`` (after ``update_scene``), from its OpenGL camera frustum.

    Args:
        renderer: a renderer (or :class:`Offscreen`) whose scene was updated.
        points: world points (N, 3), metres.

    Returns:
        (N, 2) pixel coordinates.
    """
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


class Offscreen:
    """An offscreen OpenGL context of exactly ``width`` x ``height`` pixels with its scene.

    Unlike :class:`mujoco.Renderer`, :meth:`read_into` reads the frame into a caller's buffer
    with no allocation and no flip (OpenGL's rows run bottom-up), and the framebuffer is
    sized to the image, not to the model's ``offwidth`` x ``offheight`` (1280 x 960 in the
    station scene). ``scene``, ``width`` and ``height`` are what :func:`project` reads.

    Args:
        model: the compiled model (its visual options are restored after the context is made).
        size: (width, height) in pixels.
        fast: no multisampling, shadows or reflections (software OpenGL: see
            :func:`render_frames`).
    """

    def __init__(self, model: mujoco.MjModel, size: tuple[int, int], fast: bool = True):
        width, height = int(size[0]), int(size[1])
        if width < 1 or height < 1:
            raise MjwalkError(f"render: image size must be positive, got {width}x{height}")
        self.model = model
        self.width, self.height = width, height
        self.rect = mujoco.MjrRect(0, 0, width, height)
        self.scene = mujoco.MjvScene(model, maxgeom=10000)
        self._gl = None
        self._con = None
        g, q = model.vis.global_, model.vis.quality
        saved = (int(g.offwidth), int(g.offheight), int(q.offsamples))
        g.offwidth, g.offheight = width, height
        if fast:  # multisampling costs ~4x on software OpenGL (llvmpipe)
            q.offsamples = 0
        try:
            self._gl = mujoco.GLContext(width, height)
            self._gl.make_current()
            self._con = mujoco.MjrContext(model, mujoco.mjtFontScale.mjFONTSCALE_150.value)
            mujoco.mjr_setBuffer(mujoco.mjtFramebuffer.mjFB_OFFSCREEN.value, self._con)
        except Exception as exc:
            self.close()
            raise _gl_error(exc) from exc
        finally:
            g.offwidth, g.offheight, q.offsamples = saved
        if fast:  # shadows and reflections cost much of the rest
            self.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = False
            self.scene.flags[mujoco.mjtRndFlag.mjRND_REFLECTION] = False

    def read_into(self, buf: np.ndarray) -> np.ndarray:
        """Draw the scene and read the RGB frame into ``buf`` ((H, W, 3) uint8, C-contiguous),
        rows bottom-up as OpenGL stores them (``buf[::-1]`` is the image).

        Args:
            buf: the (H, W, 3) uint8 buffer to fill.

        Returns:
            ``buf``.
        """
        assert self._gl is not None
        self._gl.make_current()
        mujoco.mjr_render(self.rect, self.scene, self._con)
        mujoco.mjr_readPixels(buf, None, self.rect, self._con)
        return buf

    def render(self) -> np.ndarray:
        """Draw the scene; a new (H, W, 3) uint8 image, rows top-down.

        Returns:
            The image, (H, W, 3) uint8, rows top-down.
        """
        buf = np.empty((self.height, self.width, 3), np.uint8)
        return np.ascontiguousarray(self.read_into(buf)[::-1])

    def close(self) -> None:
        """Free the OpenGL resources (idempotent)."""
        if self._con is not None and self._gl is not None:
            self._gl.make_current()
            self._con.free()
            self._con = None
        if self._gl is not None:
            self._gl.free()
            self._gl = None

    def __enter__(self) -> Offscreen:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _gl_error(exc: Exception) -> MjwalkError:
    """The MjwalkError that names the missing OpenGL piece behind ``exc``."""
    backend = os.environ.get("MUJOCO_GL", "")
    avail = available_backend()
    if backend in ("", "glfw") and avail != "none":
        return MjwalkError(
            f"offscreen rendering failed: MUJOCO_GL={backend or 'unset'} uses GLFW, which "
            f"needs a display ({exc}); run with MUJOCO_GL={avail} set in the environment "
            f"({avail} is available here)"
        )
    hint = {
        "egl": "install the Debian package libegl1 (and a Mesa EGL driver, libegl-mesa0), "
        "or set MUJOCO_GL=osmesa with libosmesa6 installed",
        "osmesa": "install the Debian package libosmesa6, or set MUJOCO_GL=egl with libegl1",
    }.get(
        backend,
        "install the Debian package libegl1 (MUJOCO_GL=egl) or libosmesa6 (MUJOCO_GL=osmesa)",
    )
    return MjwalkError(
        f"offscreen rendering failed (MUJOCO_GL={backend or 'unset'}): {exc}; {hint}"
    )


class _SceneUpdater:
    """Per-frame scene update with the path geoms kept in the scene's first slots.

    :func:`mujoco.mjv_updateScene` empties the scene, so adding ~400 path boxes after it costs
    ~5 ms of Python per frame. Instead the boxes are written once into slots ``0..k-1`` and
    each frame appends the model's geoms after them (``mjv_addGeoms``), then updates the
    camera and the lights, the same calls in the same order as ``mjv_updateScene`` (MuJoCo
    4.0) for a model without plugins, flexes or skins (others take the general path).
    """

    def __init__(
        self,
        model: mujoco.MjModel,
        scene: mujoco.MjvScene,
        geoms: list[tuple],
        parts: list[PartTrack] | None = None,
    ):
        self.model, self.scene = model, scene
        # handled parts (mjwalk.timeline.parts): geom id -> track, moved in the drawn scene
        self.parts = {model.geom(p.geom).id: p for p in parts or []}
        self.slots: list[tuple[int, int, PartTrack]] | None = None  # scene slot, geom, track
        self.opt = mujoco.MjvOption()
        self.opt.geomgroup[HUMAN_GROUP] = 1  # MuJoCo shows groups 0-2 only by default
        self.geoms = geoms
        self.prefix = bool(geoms) and model.nplugin == 0 and model.nflex == 0 and model.nskin == 0
        self.catmask = mujoco.mjtCatBit.mjCAT_ALL.value
        self.pert = mujoco.MjvPerturb()  # nothing selected: draws nothing, as NULL would
        if self.prefix:
            scene.ngeom = 0
            add_path_geoms(scene, geoms)
            self.n_prefix = scene.ngeom

    def __call__(self, data: mujoco.MjData, cam: mujoco.MjvCamera, frame: int = 0) -> None:
        m, scn = self.model, self.scene
        if self.prefix:
            scn.ngeom = self.n_prefix
            mujoco.mjv_addGeoms(m, data, self.opt, self.pert, self.catmask, scn)
            mujoco.mjv_updateCamera(m, data, cam, scn)
            mujoco.mjv_makeLights(m, data, scn)
        else:
            mujoco.mjv_updateScene(m, data, self.opt, None, cam, self.catmask, scn)
            add_path_geoms(scn, self.geoms)
        if self.parts:
            self._move_parts(frame)

    def _move_parts(self, frame: int) -> None:
        """Draw each handled part where its track puts it in ``frame``."""
        scn = self.scene
        geom = mujoco.mjtObj.mjOBJ_GEOM.value
        if self.slots is None or any(  # the scene slots of the part geoms, found again if moved
            scn.geoms[k].objtype != geom or scn.geoms[k].objid != g for k, g, _ in self.slots
        ):
            self.slots = [
                (k, int(scn.geoms[k].objid), self.parts[int(scn.geoms[k].objid)])
                for k in range(scn.ngeom)
                if scn.geoms[k].objtype == geom and int(scn.geoms[k].objid) in self.parts
            ]
        for k, _, track in self.slots:
            scn.geoms[k].pos[:] = track.pos[frame]
            scn.geoms[k].mat[:] = track.mat[frame]


def render_frames(
    timeline: Timeline,
    camera: str = "track",
    size: tuple[int, int] = (640, 480),
    frames=None,
    draw_path: bool = True,
    progress: bool = False,
    fast: bool = True,
    view: TrackView | None = None,
):
    """Yield ``(frame_index, rgb image (H, W, 3) uint8, renderer)`` for the timeline's frames.

    Each image is a new array, rows top-down. ``fast`` turns multisampling, shadows and
    reflections off (about 8x faster on software OpenGL: 640x480 at ~25 fps instead of ~3 on
    this project's 2-core test machine). The ``track`` camera follows :func:`track_view`
    (a clear line of sight to the legs), computed here unless ``view`` is given.

    Args:
        timeline: the poses to film.
        camera: ``"track"`` or ``"top"``.
        size: image (width, height), pixels.
        frames: the frame indices to draw (None: all).
        draw_path: draw the planned path and footprints.
        progress: show a progress bar.
        fast: no multisampling, shadows or reflections.
        view: the tracking camera's angles per frame (None: computed).
    """
    for i, r in _scenes(timeline, camera, size, frames, draw_path, progress, fast, view):
        yield i, r.render(), r


def _scenes(timeline, camera, size, frames, draw_path, progress, fast, view):
    """Yield ``(frame_index, Offscreen)`` with the scene of each frame ready to draw."""
    if camera not in CAMERAS:
        raise MjwalkError(f"render: unknown camera {camera!r}; use one of {CAMERAS}")
    model = timeline.model
    idx = range(timeline.n_frames) if frames is None else frames
    if camera == "track" and view is None:
        view = track_view(timeline)
    geoms = path_geoms(timeline) if draw_path else []
    with Offscreen(model, size, fast=fast) as r:
        update = _SceneUpdater(model, r.scene, geoms, timeline.parts)
        data = mujoco.MjData(model)
        cam = mujoco.MjvCamera()
        for i in tqdm(idx, disable=not progress, desc="render", unit="frame"):
            data.qpos[:] = timeline.qpos[i]
            mujoco.mj_kinematics(model, data)
            _set_camera(cam, timeline, int(i), camera, size, view)
            update(data, cam, int(i))
            yield int(i), r


#: Drawing threads of :func:`render_video`, each with its own OpenGL context: while one
#: waits for Mesa's rasterizer threads to finish its frame, the other prepares the next
#: (software OpenGL does the vertex work in the calling thread). Two fill both cores of the
#: 2-core test machine with the encoder.
N_DRAWERS = 2
#: Frame buffers per drawing thread: a drawer runs at most this many frames ahead of the
#: encoder (640x480x3 bytes each).
N_BUFFERS = 2


def video_frames(timeline: Timeline, fps: float) -> np.ndarray:
    """Indices of the timeline frames shown at ``fps`` frames per second, in real time.

    Args:
        timeline: the timeline (its duration in seconds and its frame rate).
        fps: the video's frame rate, frames per second.

    Returns:
        (n,) int indices into the timeline's frames, ``round(k / fps * timeline.fps)`` clipped
        to the last frame, for k = 0 ... floor(duration * fps).
    """
    n_out = max(1, int(np.floor(timeline.duration * fps + 1e-9)) + 1)
    return np.clip(
        np.round(np.arange(n_out) / fps * timeline.fps).astype(int), 0, timeline.n_frames - 1
    )


class _Drawer:
    """One drawing thread of :func:`render_video`: draws every ``n``-th frame from ``first``
    into its own preallocated buffers (rows bottom-up) and hands ``(frame, buffer index)`` to
    the encoder through ``done``; a buffer is reused once the encoder gives its index back
    through ``free``. An exception is handed over instead of a frame."""

    def __init__(self, timeline, camera, size, frames, geoms, view, lock):
        self.args = (timeline, camera, size, frames, geoms, view, lock)
        w, h = int(size[0]), int(size[1])
        self.bufs = [np.empty((h, w, 3), np.uint8) for _ in range(N_BUFFERS)]
        self.free: queue.Queue = queue.Queue()
        self.done: queue.Queue = queue.Queue()
        for b in range(N_BUFFERS):
            self.free.put(b)
        self.thread = None
        self.stopping = False

    def start(self) -> None:
        self.thread = threading.Thread(target=self._run, name="mjwalk-draw", daemon=True)
        self.thread.start()

    def stop(self) -> None:
        """Let the thread finish (it exits at its next wait for a buffer)."""
        self.stopping = True
        self.free.put(None)
        if self.thread is not None:
            self.thread.join()

    def _run(self) -> None:
        timeline, camera, size, frames, geoms, view, lock = self.args
        try:
            with lock:  # Offscreen briefly changes the model's visual options
                r = Offscreen(timeline.model, size)
            with r:
                update = _SceneUpdater(timeline.model, r.scene, geoms, timeline.parts)
                data = mujoco.MjData(timeline.model)
                cam = mujoco.MjvCamera()
                for i in frames:
                    b = self.free.get()
                    if b is None or self.stopping:
                        return
                    data.qpos[:] = timeline.qpos[i]
                    mujoco.mj_kinematics(timeline.model, data)
                    _set_camera(cam, timeline, int(i), camera, size, view)
                    update(data, cam, int(i))
                    r.read_into(self.bufs[b])
                    self.done.put((int(i), b))
        except BaseException as exc:  # handed to the encoding thread
            self.done.put(exc)


def render_video(
    timeline: Timeline,
    path: str | os.PathLike,
    camera: str = "track",
    size: tuple[int, int] = (640, 480),
    fps: float | None = None,
    progress: bool = True,
    draw_path: bool = True,
    view: TrackView | None = None,
) -> None:
    """Render the timeline offscreen to an mp4 (H.264 via imageio-ffmpeg), atomically.

    :data:`N_DRAWERS` threads draw alternate frames, each in its own OpenGL context, while
    this thread puts the frames in order and feeds them to ffmpeg
    (:class:`~mjwalk.render._ffmpeg.FfmpegWriter`), so drawing, rasterizing and encoding
    overlap instead of adding up.

    Args:
        timeline: the poses to show.
        path: output video file (written to a temporary file, renamed on success).
        camera: ``"track"`` (follows the pelvis with a clear view of the legs, see
            :func:`~mjwalk.render.viewpoint.track_view`) or ``"top"`` (whole walk from above).
        size: (width, height) in pixels.
        fps: video frame rate; defaults to the timeline's; frames are picked to keep real time.
        progress: show a tqdm progress bar.
        draw_path: draw the planned path and footprints into the scene.
        view: the tracking camera's viewpoints (computed when None).
    """
    if camera not in CAMERAS:
        raise MjwalkError(f"render_video: unknown camera {camera!r}; use one of {CAMERAS}")
    w, h = (int(v) for v in size)
    if min(w, h) < 16 or w % 2 or h % 2:
        raise InputError(
            f"render_video: size {w}x{h}: width and height must be even numbers of "
            "pixels, at least 16 (H.264)"
        )
    fps = check_fps(timeline.fps if fps is None else fps, "render_video: fps must be")
    frames = video_frames(timeline, fps)
    if camera == "track" and view is None:
        view = track_view(timeline)
    geoms = path_geoms(timeline) if draw_path else []
    lock = threading.Lock()
    n = min(N_DRAWERS, len(frames))
    drawers = [_Drawer(timeline, camera, (w, h), frames[k::n], geoms, view, lock) for k in range(n)]
    with atomic_path(path, suffix=".mp4") as tmp:
        video = FfmpegWriter(tmp, (w, h), fps)
        finished = False
        try:
            for d in drawers:
                d.start()
            for k in tqdm(range(len(frames)), disable=not progress, desc="render", unit="frame"):
                d = drawers[k % n]
                got = d.done.get()
                if isinstance(got, BaseException):
                    if isinstance(got, MjwalkError):
                        raise got
                    raise MjwalkError(f"render_video: drawing failed: {got}") from got
                video.write_bottom_up(d.bufs[got[1]])
                d.free.put(got[1])
            finished = True
        finally:
            for d in drawers:
                d.stop()
            video.close(ok=finished)
