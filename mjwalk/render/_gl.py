"""Choose MuJoCo's headless OpenGL backend when rendering needs it.

MuJoCo picks its OpenGL backend from ``MUJOCO_GL`` when ``mujoco`` is first imported (GLFW, which
needs a display, when it is unset). ``import mjwalk`` changes nothing; :mod:`mjwalk.render` calls
:func:`ensure_headless_backend` when it is imported: it keeps a ``MUJOCO_GL`` the user set, else
picks ``egl`` when libEGL loads, else ``osmesa`` when libOSMesa loads, sets ``MUJOCO_GL`` to it
and, if mujoco was already imported (by the scene or planning stages, say), swaps that backend's
context class into mujoco's renderer, so offscreen rendering works in either import order.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import sys

#: Headless backends in order of preference and the libraries that must load for each.
_BACKENDS = (("egl", ("libEGL.so.1", "EGL")), ("osmesa", ("libOSMesa.so.8", "OSMesa")))
#: mujoco's modules that hold the selected ``GLContext`` (mujoco 3.x and 4.x).
_CONTEXT_MODULES = ("mujoco.rendering.classic.gl_context", "mujoco.gl_context", "mujoco")


def available_backend() -> str:
    """The headless backend that loads here (``"egl"``, ``"osmesa"``) or ``"none"``; no side
    effects."""
    for backend, libs in _BACKENDS:
        for lib in libs:
            name = lib if lib.startswith("lib") else ctypes.util.find_library(lib)
            if not name:
                continue
            try:
                ctypes.CDLL(name)
            except OSError:
                continue
            return backend
    return "none"


def _swap_context(backend: str) -> None:
    """Make an already imported mujoco create ``backend`` contexts (its renderer looks the
    context class up on its gl_context module at construction)."""
    if backend == "egl":
        from mujoco.egl import GLContext  # deferred: loads libEGL; only the chosen backend
    elif backend == "osmesa":
        from mujoco.osmesa import GLContext  # deferred: loads libOSMesa; only the chosen one
    else:
        return
    for name in _CONTEXT_MODULES:
        mod = sys.modules.get(name)
        if mod is not None and hasattr(mod, "GLContext"):
            setattr(mod, "GLContext", GLContext)  # noqa: B010  (a module attribute)


def ensure_headless_backend() -> str:
    """Select a headless OpenGL backend for offscreen rendering; return the choice.

    Order: a user-set ``MUJOCO_GL`` (left as it is); ``egl`` if libEGL loads; ``osmesa`` if
    libOSMesa loads; otherwise ``"none"`` (rendering will then fail with a clear error).
    Sets ``MUJOCO_GL`` (and, for OSMesa, ``PYOPENGL_PLATFORM``) only when it chooses.
    """
    if os.environ.get("MUJOCO_GL"):
        return os.environ["MUJOCO_GL"]
    backend = available_backend()
    if backend == "none":
        return backend
    os.environ["MUJOCO_GL"] = backend
    if backend == "osmesa":
        os.environ.setdefault("PYOPENGL_PLATFORM", "osmesa")
    if "mujoco" in sys.modules:
        _swap_context(backend)
    return backend
