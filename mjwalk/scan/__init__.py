"""Laser scans become plannable MJCF scenes (mocap-based DHM walking in as-built environments §3).

``read`` reads the formats, ``merge`` merges several scans of one hall, ``level`` finds and
levels the floor, ``obstacles`` turns the band above the floor into a floor plan of obstacle
and void boxes, ``scene`` writes the MJCF; :class:`ScanOptions` says how (units, up axis,
resolution, unseen floor...).
"""

from mjwalk.scan.merge import MergedCloud, merge_scans
from mjwalk.scan.read import ScanCloud, read_scan
from mjwalk.scan.scanoptions import ScanOptions
from mjwalk.scan.scene import ScanScene, build_scene, scan_to_scene

__all__ = [
    "MergedCloud",
    "ScanCloud",
    "ScanOptions",
    "ScanScene",
    "build_scene",
    "merge_scans",
    "read_scan",
    "scan_to_scene",
]
