"""mjwalk.scan.declared: headers checked against the bodies that follow them."""

from __future__ import annotations

import pytest

from mjwalk.errors import ScanError
from mjwalk.scan.declared import check_pcd, check_ply, check_read_count

PLY = (
    "ply\nformat ascii 1.0\nelement vertex {n}\n"
    "property float x\nproperty float y\nproperty float z\nend_header\n"
)


def test_ascii_ply_counts(tmp_path):
    good = tmp_path / "good.ply"
    good.write_text(PLY.format(n=2) + "0 0 0\n1 1 1\n")
    d = check_ply(good)
    assert (d.encoding, d.count, d.columns) == ("ascii", 2, ("x", "y", "z"))
    short = tmp_path / "short.ply"
    short.write_text(PLY.format(n=5) + "0 0 0\n1 1 1\n")
    with pytest.raises(ScanError, match=r"short\.ply"):
        check_ply(short)


def test_pcd_viewpoint(tmp_path):
    pcd = tmp_path / "a.pcd"
    pcd.write_text(
        "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
        "VIEWPOINT 1 2 3 1 0 0 0\nPOINTS 2\nDATA ascii\n0 0 0\n1 1 1\n"
    )
    d = check_pcd(pcd)
    assert d.count == 2 and d.viewpoint == (1.0, 2.0, 3.0)


def test_fewer_points_read_than_declared(tmp_path):
    check_read_count(tmp_path / "a.laz", 10, 10)
    with pytest.raises(ScanError, match=r"a\.laz"):
        check_read_count(tmp_path / "a.laz", 10, 7)
