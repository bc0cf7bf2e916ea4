"""Other horizontal surfaces one could stand on are reported with their heights (issue 40,
deliverable 3): levels stay single."""

from __future__ import annotations

import numpy as np
import pytest
from test_scene import _room_cloud, _tilt

from mjwalk import cli
from mjwalk.scan import build_scene


def _room_with_platform(height: float = 0.2) -> np.ndarray:
    """The 4 x 3 m test room with a 1.2 x 1.0 m platform ``height`` m high at x 2.4-3.6,
    y 0.3-1.3 (its top and sides scanned, the floor under it not)."""
    pts = _room_cloud(spacing=0.03)
    under = (pts[:, 0] > 2.4) & (pts[:, 0] < 3.6) & (pts[:, 1] > 0.3) & (pts[:, 1] < 1.3)
    pts = pts[~(under & (np.abs(pts[:, 2]) < 0.02))]
    gx, gy = np.meshgrid(np.arange(2.4, 3.6, 0.03), np.arange(0.3, 1.3, 0.03))
    top = np.column_stack([gx.ravel(), gy.ravel(), np.full(gx.size, height)])
    rng = np.random.default_rng(1)
    return np.vstack([pts, top + rng.normal(0, 0.003, top.shape)])


def test_platform_is_reported_with_its_height_and_the_small_box_top_is_not():
    pts = _tilt(_room_with_platform(0.2), 1.0, -0.5)
    lv = build_scene(pts, source="room").levelling
    assert len(lv.surfaces) == 1  # the 0.6 x 0.4 m box top (0.24 m²) is below STAND_AREA
    s = lv.surfaces[0]
    assert s.height == pytest.approx(0.2, abs=0.02)
    assert s.area == pytest.approx(1.2, abs=0.35)  # whole voxels along its edges
    assert s.x == pytest.approx(3.0, abs=0.15)


def test_cli_prints_the_surfaces(tmp_path, capsys):
    src = tmp_path / "room.xyz"
    np.savetxt(src, _room_with_platform(0.35), fmt="%.4f")
    assert cli.main(["scan", str(src), "-o", str(tmp_path / "r.xml")]) == 0
    out = capsys.readouterr().out
    assert "other horizontal surfaces one could stand on" in out and "+0.35 m" in out
