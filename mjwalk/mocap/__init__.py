"""Motion-capture import: BVH and ASF/AMC to :class:`Take` (120 Hz, metres, z up)."""

from mjwalk.mocap.take import TAKE_FPS, Take

__all__ = ["TAKE_FPS", "Take"]
