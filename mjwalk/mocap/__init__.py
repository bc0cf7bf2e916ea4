"""Motion-capture import: BVH and ASF/AMC to :class:`Take` (120 Hz, metres, z up)."""

from mjwalk.mocap.asf import (
    CMU_AMC_FPS,
    Asf,
    AsfBone,
    amc_forward_kinematics,
    load_amc,
    parse_amc,
    parse_asf,
)
from mjwalk.mocap.bvh import Bvh, bvh_forward_kinematics, load_bvh, parse_bvh
from mjwalk.mocap.skeletons import BANDAI, CMU, CMU_BVH, SKELETONS, SkeletonMap, get_skeleton
from mjwalk.mocap.take import TAKE_FPS, Take

__all__ = [
    "BANDAI",
    "CMU",
    "CMU_AMC_FPS",
    "CMU_BVH",
    "SKELETONS",
    "TAKE_FPS",
    "Asf",
    "AsfBone",
    "Bvh",
    "SkeletonMap",
    "Take",
    "amc_forward_kinematics",
    "bvh_forward_kinematics",
    "get_skeleton",
    "load_amc",
    "load_bvh",
    "parse_amc",
    "parse_asf",
    "parse_bvh",
]
