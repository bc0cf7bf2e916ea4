"""Video and figures: offscreen video of a timeline (:mod:`~mjwalk.render.video`), where the
tracking camera stands (:mod:`~mjwalk.render.viewpoint`), top-view plots and the report's charts
(:mod:`~mjwalk.render.plot`), and the headless OpenGL backend (:mod:`mjwalk.render._gl`).

Importing this package selects a headless OpenGL backend, as :mod:`mjwalk.render.video` says.
"""

from mjwalk.render.video import CAMERAS, render_frames, render_video, video_frames

__all__ = ["CAMERAS", "render_frames", "render_video", "video_frames"]
