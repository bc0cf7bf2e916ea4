"""Bad scans and scan options become named errors before any work (issue 36, items 5-9, 14 and
the scan's misleading messages); valid but unusual scans give the right scene.

Each CLI case runs ``mjwalk scan`` and asserts exit status 2, one line on stderr naming the
problem in the command line's own syntax, no traceback, and no file (output or temporary) left
in the folder. Inputs are small clouds built here.
"""

from __future__ import annotations

import errno
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from test_scene import _room_cloud, _tilt, _write_xyz

from mjwalk import cli
from mjwalk.errors import ScanError
from mjwalk.scan import ScanOptions, build_scene, read_scan

ROOT = Path(__file__).resolve().parents[2]


def _ply_ascii(path: Path, pts, declared: int | None = None, cells=None) -> Path:
    """An ASCII PLY of ``pts`` (its rows as text ``cells`` when given), declaring
    ``declared`` vertices (default: the rows it holds)."""
    rows = cells if cells is not None else [" ".join(f"{v:.5f}" for v in p) for p in pts]
    n = len(rows) if declared is None else declared
    head = (
        f"ply\nformat ascii 1.0\nelement vertex {n}\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n"
    )
    path.write_text(head + "\n".join(rows) + "\n")
    return path


def _pcd_ascii(path: Path, pts, declared: int) -> Path:
    head = (
        "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\n"
        f"TYPE F F F\nCOUNT 1 1 1\nWIDTH {declared}\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n"
        f"POINTS {declared}\nDATA ascii\n"
    )
    path.write_text(head + "\n".join(" ".join(f"{v:.5f}" for v in p) for p in pts) + "\n")
    return path


def _scan(argv, capsys, tmp_path, code=2) -> str:
    """Run ``mjwalk scan``; assert the exit status, no traceback and (when refused) one line
    on stderr and no new file under ``tmp_path``. Returns stderr (or stdout when it ran)."""
    before = set(tmp_path.rglob("*"))
    try:
        got = cli.main(["scan", *map(str, argv)])
    except SystemExit as exc:  # argparse's refusals
        got = exc.code
    out, err = capsys.readouterr()
    assert got == code, err
    assert "Traceback" not in err
    if code == 2:
        assert set(tmp_path.rglob("*")) == before, "a file was left behind"
        lines = [ln for ln in err.splitlines() if ln.startswith("mjwalk")]
        assert len(lines) == 1, err
        return err
    return out


@pytest.fixture
def room(tmp_path) -> np.ndarray:
    """The 4 x 3 m test room (a 0.6 x 0.4 x 0.9 m box at (1, 1)), 4 cm spacing, tilted 1°."""
    return _tilt(_room_cloud(spacing=0.04), 1.0, 0.3)


# ------------------------------------------------------------- 5: declared counts, inf


def test_inf_in_an_ascii_ply_is_refused_and_dropped_on_request(room, tmp_path, capsys):
    """RPly stops at 'inf' and Open3D returned the rest as uninitialised memory."""
    cells = [" ".join(f"{v:.5f}" for v in p) for p in room]
    cells[7] = "1.0 inf 0.5"
    src = _ply_ascii(tmp_path / "inf.ply", None, cells=cells)
    out = tmp_path / "s.xml"
    err = _scan([src, "-o", out], capsys, tmp_path)
    assert "vertex 7 (line 15) holds a NaN or infinite value" in err
    assert "--drop-invalid" in err
    text = _scan([src, "-o", out, "--drop-invalid"], capsys, tmp_path, code=0)
    assert f"{len(room) - 1} points" in text
    from mjwalk.world import load_workplace

    wp = load_workplace(out)
    assert wp.clearance(np.array([1.0, 1.0])) < 0  # the box is still there


@pytest.mark.parametrize("factor", [10, 31_882])  # 10x the rows; 1e9 vertices
def test_ply_declaring_more_vertices_than_it_holds(room, tmp_path, capsys, factor):
    src = _ply_ascii(tmp_path / "more.ply", room, declared=factor * len(room))
    err = _scan([src, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert f"declares {factor * len(room)} vertices but the file holds {len(room)} rows" in err


def test_binary_ply_declaring_1e9_vertices_is_refused_before_allocating(room, tmp_path, capsys):
    body = room.astype("<f4").tobytes()
    src = tmp_path / "big.ply"
    src.write_bytes(
        b"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
        b"property float y\nproperty float z\nend_header\n" + body
    )
    err = _scan([src, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert "declares 1000000000 vertices of 12 bytes" in err
    assert f"room for {len(room)} vertices" in err


def test_pcd_declaring_more_points_than_rows(room, tmp_path, capsys):
    src = _pcd_ascii(tmp_path / "more.pcd", room, declared=1_000_000)
    err = _scan([src, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert f"declares 1000000 points but the file holds {len(room)} rows" in err
    assert "0 m in height" not in err


def test_pcd_declaring_fewer_points_than_rows(room, tmp_path, capsys):
    """Issue 45: POINTS 100 (and WIDTH 100) over all the rows: Open3D read the first 100, which
    were then refused for the cloud's height; the count is named instead."""
    src = _pcd_ascii(tmp_path / "fewer.pcd", room, declared=100)
    err = _scan([src, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert (
        f"declares POINTS 100 (WIDTH x HEIGHT = 100 x 1) but the file holds {len(room)} rows" in err
    )
    assert "in height" not in err


def _binary_pcd(path: Path, pts, declared: int | None = None) -> Path:
    """A binary PCD of ``pts`` (written by Open3D) whose POINTS and WIDTH say ``declared``."""
    from mjwalk.scan.read import open3d_module

    o3d = open3d_module()
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(pts))
    o3d.io.write_point_cloud(str(path), cloud, write_ascii=False)
    if declared is not None:
        data = path.read_bytes()
        cut = data.index(b"DATA binary\n")
        head = data[:cut].replace(f"WIDTH {len(pts)}\n".encode(), f"WIDTH {declared}\n".encode())
        head = head.replace(f"POINTS {len(pts)}\n".encode(), f"POINTS {declared}\n".encode())
        path.write_bytes(head + data[cut:])
    return path


def test_binary_pcd_declaring_fewer_points_than_it_holds(room, tmp_path, capsys):
    src = _binary_pcd(tmp_path / "fewer.pcd", room, declared=100)
    err = _scan([src, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert "declares POINTS 100 (WIDTH x HEIGHT = 100 x 1)" in err
    assert f"{12 * len(room)} bytes after its header, room for {len(room)} points of 12" in err
    ok = read_scan(_binary_pcd(tmp_path / "ok.pcd", room))  # as written: read in full
    assert ok.points.shape == room.shape


def test_shared_pcl_scan_with_a_header_declaring_100_points(shared_data, tmp_path, capsys):
    """The shared PCL room scan as ASCII, its header saying 100 points over all its rows."""
    from mjwalk.scan.read import open3d_module

    o3d = open3d_module()
    src = shared_data / "scans" / "pcl-room-scan" / "room_scan1.pcd"
    pts = np.asarray(o3d.io.read_point_cloud(str(src)).points)
    pts = pts[np.isfinite(pts).all(axis=1)]
    bad = _pcd_ascii(tmp_path / "room100.pcd", pts, declared=100)
    err = _scan([bad, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert (
        f"declares POINTS 100 (WIDTH x HEIGHT = 100 x 1) but the file holds {len(pts)} rows" in err
    )


@pytest.mark.parametrize("compressed", [False, True])
def test_binary_pcd_cut_short(room, tmp_path, capsys, compressed):
    from mjwalk.scan.read import open3d_module

    full = tmp_path / "full.pcd"
    o3d = open3d_module()
    o3d.io.write_point_cloud(
        str(full),
        o3d.geometry.PointCloud(o3d.utility.Vector3dVector(room)),
        write_ascii=False,
        compressed=compressed,
    )
    cut = tmp_path / "cut.pcd"
    cut.write_bytes(full.read_bytes()[: -12 * 1000])
    full.unlink()
    err = _scan([cut, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert f"declares {len(room)} points of 12 bytes" in err


def test_pts_declaring_more_points_than_rows(room, tmp_path, capsys):
    src = tmp_path / "more.pts"
    src.write_text(f"{2 * len(room)}\n" + "\n".join(" ".join(map(str, p)) for p in room) + "\n")
    err = _scan([src, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert f"declares {2 * len(room)} points but the file holds {len(room)} rows" in err


def test_valid_ascii_ply_and_pcd_still_read(room, tmp_path):
    for src in (
        _ply_ascii(tmp_path / "ok.ply", room),
        _pcd_ascii(tmp_path / "ok.pcd", room, len(room)),
    ):
        cloud = read_scan(src)
        assert cloud.points.shape == room.shape
        assert np.allclose(cloud.points, room, atol=1e-4)


# ------------------------------------------------------------------- 6: truncated files


def test_las_cut_at_a_record_boundary(room, tmp_path, capsys):
    from test_scene import _write_format

    full = _write_format(tmp_path / "full.las", room)
    import laspy

    header = laspy.read(str(full)).header
    keep = header.offset_to_point_data + 20_000 * header.point_format.size
    cut = tmp_path / "cut.las"
    cut.write_bytes(full.read_bytes()[:keep])
    full.unlink()
    err = _scan([cut, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert f"declares {len(room)} points of {header.point_format.size} bytes" in err
    assert "20000 whole records" in err


def test_laz_cut_short(room, tmp_path, capsys):
    from test_scene import _write_format

    full = _write_format(tmp_path / "full.laz", room)
    cut = tmp_path / "cut.laz"
    data = full.read_bytes()
    cut.write_bytes(data[: len(data) * 2 // 3])
    full.unlink()
    err = _scan([cut, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert f"header declares {len(room)} points" in err


def test_e57_cut_short(room, tmp_path, capsys):
    from test_scene import _write_format

    full = _write_format(tmp_path / "full.e57", room)
    data = full.read_bytes()
    cut = tmp_path / "cut.e57"
    cut.write_bytes(data[: len(data) * 9 // 10])
    full.unlink()
    err = _scan([cut, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert f"declares a file of {len(data)} bytes but it holds {len(data) * 9 // 10}" in err


# ---------------------------------------------------- 7: range, stray points, upside down


def test_one_point_at_1e9_is_named_as_stray(room, tmp_path, capsys):
    src = _write_xyz(tmp_path / "stray.xyz", np.vstack([room, [[1e9, 1.0, 1.0]]]))
    err = _scan([src, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert "spans 1e+09 m along x" in err
    assert "1 stray point(s)" in err


def test_cloud_offset_by_1e9_names_the_offset_and_runs_with_it(room, tmp_path, capsys):
    off = np.array([1e9, -2e9, 1e9])
    src = tmp_path / "far.xyz"
    np.savetxt(src, room + off, fmt="%.4f")
    out = tmp_path / "s.xml"
    err = _scan([src, "-o", out], capsys, tmp_path)
    assert "beyond 1e+07 m" in err
    assert "--offset=1000000000,-2000000000,1000000000" in err
    text = _scan(
        [src, "-o", out, "--offset=1000000000,-2000000000,1000000000"], capsys, tmp_path, 0
    )
    near = build_scene(room, source="near").levelling.tilt_deg
    assert f"floor tilt {near:.3f} deg removed" in text
    # The transform in the scene still takes a scan-file point to the scene.
    scene = build_scene(room + off, ScanOptions(offset=off), source="far")
    p = scene.matrix @ np.array([*(room[0] + off), 1.0])
    assert abs(p[2] - 0.0) < 0.03  # a floor point


def test_georeferenced_cloud_levels_in_a_local_frame():
    """UTM-sized coordinates (5.4e6 m) level as precisely as the same cloud at the origin."""
    room = _tilt(_room_cloud(spacing=0.04), 1.0, 0.3)
    near = build_scene(room, source="near").levelling
    far = build_scene(room + [512_000.0, 9_400_000.0, 230.0], source="far").levelling
    assert far.tilt_deg == pytest.approx(near.tilt_deg, abs=1e-6)


def test_upside_down_cloud_is_named_with_the_flag(room, tmp_path, capsys):
    src = _write_xyz(tmp_path / "flipped.xyz", room * [1, -1, -1])
    out = tmp_path / "s.xml"
    err = _scan([src, "-o", out], capsys, tmp_path)
    assert "upside down" in err and "pass --up=-z" in err
    _scan([src, "-o", out, "--up=-z"], capsys, tmp_path, code=0)
    from mjwalk.world import load_workplace

    # --up=-z turns the file by 180° about x (diag(1, -1, -1)): the box is back at (1, 1)
    assert load_workplace(out).clearance(np.array([1.0, 1.0])) < 0


# ---------------------------------------------------------------- 8, 9, 14: CLI options


@pytest.fixture
def no_scan_work(monkeypatch):
    """Reading a scan fails the test: the refusal must come first."""

    def fail(*args, **kwargs):
        raise AssertionError("the scan was read before the bad option was refused")

    monkeypatch.setattr("mjwalk.scan.merge.read_scan", fail)


def test_output_that_is_a_folder_or_under_a_file(room, tmp_path, capsys, no_scan_work):
    src = _write_xyz(tmp_path / "room.xyz", room)
    (tmp_path / "dir").mkdir()
    err = _scan([src, "-o", tmp_path / "dir"], capsys, tmp_path)
    assert "-o/--output" in err and "is a folder" in err
    err = _scan([src, "-o", tmp_path / "room.xyz" / "s.xml"], capsys, tmp_path)
    assert "is a file, not a folder" in err


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_output_in_a_read_only_folder(room, tmp_path, capsys, no_scan_work):
    src = _write_xyz(tmp_path / "room.xyz", room)
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        err = _scan([src, "-o", ro / "s.xml"], capsys, tmp_path)
        assert "not writable" in err
    finally:
        ro.chmod(0o700)


@pytest.mark.parametrize("value", ["0", "-1", "100", "nan", "0.001"])
def test_resolution_out_of_range(room, tmp_path, capsys, no_scan_work, value):
    src = _write_xyz(tmp_path / "room.xyz", room)
    err = _scan([src, "-o", tmp_path / "s.xml", "--resolution", value], capsys, tmp_path)
    assert "--resolution" in err
    assert "outside 0.005-0.1 m" in err
    assert "no floor found" not in err


def test_resolution_out_of_range_in_python(room):
    with pytest.raises(ScanError, match="resolution 0 m is outside"):
        build_scene(room, ScanOptions(resolution=0))


def test_floor_plan_too_large_names_a_resolution():
    """A 1.8 km long shed at 5 mm: 1e11 cells; refused before the floor search."""
    rng = np.random.default_rng(0)
    pts = np.column_stack([rng.uniform(0, 1800, 5000), rng.uniform(0, 60, 5000), np.zeros(5000)])
    pts[:2500, 2] = rng.uniform(0, 3, 2500)
    with pytest.raises(ScanError, match=r"cells .*use --resolution 0\.06\d* or coarser"):
        build_scene(pts, ScanOptions(resolution=0.005))


def test_write_failure_is_one_line_naming_the_file(room, tmp_path, capsys, monkeypatch):
    src = _write_xyz(tmp_path / "room.xyz", room)
    out = tmp_path / "s.xml"

    def full(self, *args, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(Path, "write_text", full)
    err = _scan([src, "-o", out], capsys, tmp_path)
    assert f"cannot write {out}: No space left on device" in err


def test_file_size_limit_in_a_real_process(room, tmp_path):
    """``ulimit -f`` as in the issue: Python ignores SIGXFSZ, the write fails with EFBIG."""
    import resource

    src = _write_xyz(tmp_path / "room.xyz", room)
    out = tmp_path / "out" / "s.xml"
    out.parent.mkdir()

    def limit():  # 512 bytes: the scene is larger
        resource.setrlimit(resource.RLIMIT_FSIZE, (512, 512))

    env = dict(os.environ, PYTHONPATH=str(ROOT), MUJOCO_GL="egl")
    proc = subprocess.run(
        [sys.executable, "-m", "mjwalk", "scan", str(src), "-o", str(out)],
        capture_output=True,
        text=True,
        env=env,
        preexec_fn=limit,
        timeout=600,
    )
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    assert f"cannot write {out}: File too large" in proc.stderr
    assert list(out.parent.iterdir()) == []


def test_deeply_nested_sites_toml_names_the_key(room, tmp_path, capsys):
    src = _write_xyz(tmp_path / "room.xyz", room)
    sites = tmp_path / "sites.toml"
    sites.write_text("[site.door]\nxy = " + "[" * 2000 + "]" * 2000 + "\n")
    err = _scan([src, "-o", tmp_path / "s.xml", "--sites", sites], capsys, tmp_path)
    assert f"{sites}:2: key 'xy' is nested more than" in err


# ---------------------------------------------------------------- misleading messages


def _sparse_floor(density: float, seed: int = 0) -> np.ndarray:
    """A 6 x 6 m floor with ``density`` random points per m² and a 6 x 2.5 m wall."""
    rng = np.random.default_rng(seed)
    n = int(36 * density)
    floor = np.column_stack([rng.uniform(0, 6, (n, 2)), rng.normal(0, 0.003, n)])
    wall = np.column_stack([rng.uniform(0, 6, 4000), np.zeros(4000), rng.uniform(0, 2.5, 4000)])
    return np.vstack([floor, wall])


def test_floor_at_6cm_spacing_is_found():
    """250 points/m² (6 cm spacing) said 'largest horizontal surface 0.07 m²': the 0.1 m
    voxels were too sparse, and the search stopped there although no one surface was a
    floor. Now it goes on to larger voxels and finds the whole floor."""
    scene = build_scene(_sparse_floor(250))
    assert scene.levelling.floor_area > 30.0
    assert scene.levelling.tilt_deg < 0.2


def test_too_sparse_floor_names_the_points_per_voxel_rule():
    with pytest.raises(ScanError) as info:
        build_scene(_sparse_floor(12))
    msg = str(info.value)
    assert "too sparse for local-PCA normals" in msg
    assert "fewer than the 5 points a normal needs" in msg


def test_millimetre_cloud_names_units_mm(tmp_path, capsys):
    src = _write_xyz(tmp_path / "mm.xyz", 1000 * _room_cloud(spacing=0.08))
    err = _scan([src, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert "pass --units mm" in err
    assert "units='cm'" not in err


def test_centimetre_cloud_names_units_cm(tmp_path, capsys):
    src = _write_xyz(tmp_path / "cm.xyz", 100 * _room_cloud(spacing=0.08))
    err = _scan([src, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert "pass --units cm" in err


# ------------------------------------------------- issue 45: folders and poses named


@pytest.mark.parametrize("name", ["scans.ply", "scans"])
def test_a_folder_given_as_a_scan_file_is_named_a_folder(room, tmp_path, capsys, name):
    folder = tmp_path / name
    folder.mkdir()
    err = _scan([folder, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert f"{folder} is a folder, not a scan file" in err
    assert "not found" not in err and "unknown point-cloud format" not in err


def _two_scans_and_poses(tmp_path: Path, room, pose) -> list:
    a = _write_xyz(tmp_path / "a.xyz", room)
    b = _write_xyz(tmp_path / "b.xyz", room)
    (tmp_path / "p.json").write_text(json.dumps({"b.xyz": pose}))  # NaN written as NaN
    return [a, b, "-o", tmp_path / "s.xml", "--poses", tmp_path / "p.json"]


@pytest.mark.parametrize(
    ("entry", "value"), [(float("nan"), "nan"), (float("inf"), "inf"), (None, "nan")],
    ids=["nan", "inf", "null"],
)  # fmt: skip
def test_a_pose_with_a_non_finite_entry_names_it(
    room, tmp_path, capsys, no_scan_work, entry, value
):
    pose = np.eye(4).tolist()
    pose[1][2] = entry
    err = _scan(_two_scans_and_poses(tmp_path, room, pose), capsys, tmp_path)
    assert f"p.json: pose of 'b.xyz': entry {value} at row 2, column 3" in err
    assert "is not a finite number" in err and "got (4, 4)" not in err


def test_a_folder_given_as_the_poses_file(room, tmp_path, capsys, no_scan_work):
    argv = _two_scans_and_poses(tmp_path, room, np.eye(4).tolist())
    (tmp_path / "p.json").unlink()
    (tmp_path / "p.json").mkdir()
    err = _scan(argv, capsys, tmp_path)
    assert "p.json is a folder, not a poses file" in err
