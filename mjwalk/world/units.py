"""Units and up axes of imported geometry (CAD meshes and laser scans): what ``units`` and ``up``
mean when a file's coordinates are read into mjwalk's world frame (metres, z up)."""

from __future__ import annotations

import numpy as np

#: Length units accepted for ``units``: metres per unit.
UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254, "ft": 0.3048}
#: Up axes accepted for ``up``: the rotation taking file coordinates to z-up coordinates
#: (right-handed; for +y up, the file's -z becomes +y, as glTF/Blender exports are converted).
UP_AXES = {
    "+z": np.eye(3),
    "-z": np.diag([1.0, -1.0, -1.0]),
    "+y": np.array([[1.0, 0, 0], [0, 0, -1.0], [0, 1.0, 0]]),
    "-y": np.array([[1.0, 0, 0], [0, 0, 1.0], [0, -1.0, 0]]),
    "+x": np.array([[0, 0, -1.0], [0, 1.0, 0], [1.0, 0, 0]]),
    "-x": np.array([[0, 0, 1.0], [0, 1.0, 0], [-1.0, 0, 0]]),
}
