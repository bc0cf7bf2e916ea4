"""Motion-capture import: BVH and ASF/AMC to :class:`Take` (120 Hz, metres, z up)."""

from mjwalk.mocap.bvh import Bvh, bvh_forward_kinematics, load_bvh, parse_bvh
from mjwalk.mocap.skeletons import BANDAI, CMU, CMU_BVH, SKELETONS, SkeletonMap, get_skeleton
from mjwalk.mocap.take import TAKE_FPS, Take

__all__ = [
    "BANDAI",
    "CMU",
    "CMU_BVH",
    "SKELETONS",
    "TAKE_FPS",
    "Bvh",
    "SkeletonMap",
    "Take",
    "bvh_forward_kinematics",
    "get_skeleton",
    "load_bvh",
    "parse_bvh",
]
