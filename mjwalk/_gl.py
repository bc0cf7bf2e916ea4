"""Choose MuJoCo's headless OpenGL backend before mujoco is first imported.

``mjwalk/__init__.py`` calls :func:`select_gl_backend` first thing, so any program that imports
mjwalk before mujoco renders offscreen with EGL (or OSMesa) without setting ``MUJOCO_GL``.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os


def _probe_only() -> str:
    """The backend :func:`select_gl_backend` would choose, without touching the environment."""
    saved = os.environ.get("MUJOCO_GL")
    saved_py = os.environ.get("PYOPENGL_PLATFORM")
    os.environ.pop("MUJOCO_GL", None)
    try:
        return select_gl_backend()
    finally:
        for key, val in (("MUJOCO_GL", saved), ("PYOPENGL_PLATFORM", saved_py)):
            if val is None:
                os.environ.pop(key, None)
            else:
                os.environ[key] = val


def select_gl_backend() -> str:
    """Set ``MUJOCO_GL`` (if unset) to a headless backend that loads here; return the choice.

    Order: a user-set ``MUJOCO_GL``; ``egl`` if libEGL loads; ``osmesa`` if libOSMesa loads;
    otherwise ``"none"`` (rendering will then fail with a clear error). Has no effect on an
    already imported mujoco.
    """
    if os.environ.get("MUJOCO_GL"):
        return os.environ["MUJOCO_GL"]
    for backend, libs in (
        ("egl", ("libEGL.so.1", "EGL")),
        ("osmesa", ("libOSMesa.so.8", "OSMesa")),
    ):
        for lib in libs:
            name = lib if lib.startswith("lib") else ctypes.util.find_library(lib)
            if not name:
                continue
            try:
                ctypes.CDLL(name)
            except OSError:
                continue
            os.environ["MUJOCO_GL"] = backend
            if backend == "osmesa":
                os.environ.setdefault("PYOPENGL_PLATFORM", "osmesa")
            return backend
    return "none"
