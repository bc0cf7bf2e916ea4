"""Laser scans -> MJCF scenes (mjwalk.scan): synthetic round trips, real scans, bad input."""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

import mujoco
import numpy as np
import pytest

from mjwalk.errors import MjwalkError, ScanError
from mjwalk.plan.options import PlannerOptions
from mjwalk.scan import ScanOptions, build_scene, read_scan, scan_to_scene
from mjwalk.scan.raycast import synthetic_scan
from mjwalk.scan.read import Station
from mjwalk.scan.scene import write_scene
from mjwalk.world import load_workplace

# ---------------------------------------------------------------- small synthetic clouds


def _room_cloud(seed: int = 0, spacing: float = 0.03) -> np.ndarray:
    """A 4 x 3 m room, floor at z = 0, 2.5 m walls, a 0.6 x 0.4 x 0.9 m box at (1, 1), a
    ceiling lamp at 2.3 m; points every ``spacing`` metres with 3 mm noise. Metres, z up."""
    rng = np.random.default_rng(seed)
    s = spacing
    gx, gy = np.meshgrid(np.arange(0, 4, s), np.arange(0, 3, s))
    floor = np.column_stack([gx.ravel(), gy.ravel(), np.zeros(gx.size)])
    box_free = ~((np.abs(floor[:, 0] - 1.0) < 0.3) & (np.abs(floor[:, 1] - 1.0) < 0.2))
    parts = [floor[box_free]]
    h = np.arange(0, 2.5, s)
    for x in (0.0, 4.0):
        yy, zz = np.meshgrid(np.arange(0, 3, s), h)
        parts.append(np.column_stack([np.full(yy.size, x), yy.ravel(), zz.ravel()]))
    for y in (0.0, 3.0):
        xx, zz = np.meshgrid(np.arange(0, 4, s), h)
        parts.append(np.column_stack([xx.ravel(), np.full(xx.size, y), zz.ravel()]))
    bx, by = np.meshgrid(np.arange(0.7, 1.3, s), np.arange(0.8, 1.2, s))
    parts.append(np.column_stack([bx.ravel(), by.ravel(), np.full(bx.size, 0.9)]))
    bz = np.arange(0, 0.9, s)
    for x in (0.7, 1.3):
        yy, zz = np.meshgrid(np.arange(0.8, 1.2, s), bz)
        parts.append(np.column_stack([np.full(yy.size, x), yy.ravel(), zz.ravel()]))
    for y in (0.8, 1.2):
        xx, zz = np.meshgrid(np.arange(0.7, 1.3, s), bz)
        parts.append(np.column_stack([xx.ravel(), np.full(xx.size, y), zz.ravel()]))
    lx, ly = np.meshgrid(np.arange(2.5, 3.5, s), np.arange(1.0, 2.0, s))
    parts.append(np.column_stack([lx.ravel(), ly.ravel(), np.full(lx.size, 2.3)]))
    pts = np.vstack(parts)
    return pts + rng.normal(0, 0.003, pts.shape)


def _deck_scan():
    """A 8 x 6 m floor, its right half a 0.6 m deck; scanners 1.5 m over the floor and over
    the deck (0.5 deg rays), their rows of the cloud. Metres, z up, floor at z = 0."""
    xml = """<mujoco><worldbody><geom type="plane" size="4 3 0.1"/>
    <geom type="box" pos="2 0 0.3" size="2 3 0.3"/></worldbody></mujoco>"""
    model = mujoco.MjModel.from_xml_string(xml)
    spots = [(-2.0, 0.0, 1.5), (2.0, 0.0, 2.1)]
    clouds = [
        synthetic_scan(model, [p], step_deg=0.5, tilt_deg=0.0, floor_height=0.0, seed=k).points
        for k, p in enumerate(spots)
    ]
    return np.vstack(clouds), np.array(spots), np.cumsum([0] + [len(c) for c in clouds])


def _tilt(pts: np.ndarray, deg: float, lift: float) -> np.ndarray:
    t = np.radians(deg)
    rot = np.array([[1, 0, 0], [0, np.cos(t), -np.sin(t)], [0, np.sin(t), np.cos(t)]])
    return pts @ rot.T + [0, 0, lift]


def _write_xyz(path, pts):
    np.savetxt(path, pts, fmt="%.5f")
    return path


def test_small_room_levels_and_finds_the_box(tmp_path):
    pts = _tilt(_room_cloud(), 1.5, -1.234)
    scene = build_scene(pts, source="room")
    assert abs(scene.levelling.tilt_deg - 1.5) < 0.05
    out = write_scene(scene, tmp_path / "room.xml")
    wp = load_workplace(out)
    # The box is an obstacle, the lamp at 2.3 m is not, the middle of the room is free.
    assert wp.clearance(np.array([1.0, 1.0])) < 0
    assert wp.walk_clearance(np.array([3.0, 1.5])) > 0.5
    assert wp.walk_clearance(np.array([1.0, 2.2])) == pytest.approx(0.8 - 0.0, abs=0.04)
    # The transform in the MJCF maps a scan point of the floor to z = 0.
    m = scene.matrix
    p = m @ np.array([*pts[0], 1.0])
    assert abs(p[2]) < 0.02
    assert "mjwalk_scan_transform" in out.read_text()


@pytest.mark.parametrize(("units", "up"), [("cm", "+z"), ("m", "+y"), ("mm", "-y")])
def test_units_and_up_axes(tmp_path, units, up):
    from mjwalk.scan.read import UNITS, UP_AXES

    pts = _room_cloud(spacing=0.04)
    raw = pts @ UP_AXES[up] / UNITS[units]  # what a file in those units and axes holds
    path = _write_xyz(tmp_path / "room.xyz", raw)
    out = tmp_path / "room.xml"
    scene = scan_to_scene(path, out, ScanOptions(units=units, up=up))
    assert scene.levelling.tilt_deg < 0.1
    wp = load_workplace(out)
    assert wp.floor_bounds[2] - wp.floor_bounds[0] == pytest.approx(4.0, abs=0.05)


def test_sites_from_toml(tmp_path):
    pts = _room_cloud(spacing=0.04)
    path = _write_xyz(tmp_path / "room.xyz", pts)
    sites = tmp_path / "sites.toml"
    sites.write_text("[site.door]\nxy = [3.5, 0.5]\nyaw = 90\n[site.box]\nscan = [1.0, 1.6, 0.0]\n")
    scan_to_scene(path, tmp_path / "room.xml", sites=sites)
    wp = load_workplace(tmp_path / "room.xml")
    assert wp.station("door").yaw == pytest.approx(np.pi / 2)
    assert np.allclose(wp.station("box").xy, [1.0, 1.6], atol=0.01)
    bad = tmp_path / "bad.toml"
    bad.write_text("[site.wall]\nxy = [1.0, 1.0]\n")  # inside the box
    with pytest.raises(ScanError, match="not on the scanned floor"):
        scan_to_scene(path, tmp_path / "other.xml", sites=bad)
    assert not (tmp_path / "other.xml").exists()


# ---------------------------------------------------------------------------- bad input


def _empty_ply(path):
    path.write_text(
        "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
        "property float y\nproperty float z\nend_header\n"
    )
    return path


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (lambda d: _empty_ply(d / "empty.ply"), "empty"),
        (
            lambda d: _write_xyz(
                d / "wall.xyz",
                np.column_stack(
                    [np.zeros(4000), *np.random.default_rng(0).uniform(0, 3, (2, 4000))]
                ),
            ),
            "no floor",
        ),
        (
            lambda d: _write_xyz(
                d / "nan.xyz", np.vstack([_room_cloud(spacing=0.08), [[np.nan, 0, 0]]])
            ),
            "NaN",
        ),
        (lambda d: _write_xyz(d / "mm.xyz", 1000 * _room_cloud(spacing=0.08)), "mm"),
        (
            lambda d: (d / "notes.ply").write_text("hello, not a cloud\n") and d / "notes.ply",
            "not a PLY",
        ),
        (
            lambda d: (d / "notes.xyz").write_text("the quick brown fox\n") and d / "notes.xyz",
            "not a text point cloud",
        ),
        (lambda d: (d / "x.pcd").write_bytes(b"\x00\x01garbage") and d / "x.pcd", "not a PCD"),
        (lambda d: (d / "x.e57").write_bytes(b"garbage") and d / "x.e57", "not an E57"),
        (lambda d: (d / "x.laz").write_bytes(b"garbage") and d / "x.laz", "not a LAS"),
        (lambda d: (d / "x.docx").write_bytes(b"garbage") and d / "x.docx", "unknown"),
    ],
    ids=[
        "empty",
        "no-floor",
        "nan",
        "millimetres",
        "not-ply",
        "not-xyz",
        "not-pcd",
        "not-e57",
        "not-laz",
        "unknown-suffix",
    ],
)
def test_bad_input_is_a_named_error_and_writes_nothing(tmp_path, make, match):
    src = make(tmp_path)
    out = tmp_path / "out" / "scene.xml"
    with pytest.raises(ScanError, match=match):
        scan_to_scene(src, out)
    assert not out.exists()
    assert issubclass(ScanError, MjwalkError)


def test_nan_points_can_be_dropped(tmp_path):
    src = _write_xyz(tmp_path / "nan.xyz", np.vstack([_room_cloud(spacing=0.05), [[np.nan, 0, 0]]]))
    scene = scan_to_scene(src, tmp_path / "s.xml", ScanOptions(drop_invalid=True))
    assert scene.n_points == len(_room_cloud(spacing=0.05))


def test_cli_scan_reports_errors_without_traceback(tmp_path, capsys):
    from mjwalk.cli import main

    bad = tmp_path / "x.ply"
    bad.write_text("not a cloud")
    assert main(["scan", str(bad), "-o", str(tmp_path / "s.xml")]) == 2
    assert "not a PLY" in capsys.readouterr().err
    good = _write_xyz(tmp_path / "room.xyz", _tilt(_room_cloud(spacing=0.04), 1.0, 0.7))
    assert main(["scan", str(good), "-o", str(tmp_path / "s.xml")]) == 0
    assert "transform" in capsys.readouterr().out


# ------------------------------------------------- round trip through MuJoCo's ray casting

#: Scanner positions in the station (x, y, height), chosen so every obstacle is seen from two
#: sides at least, as a survey would place them.
STATION_SCANNERS = [(-3.6, -1.2, 1.5), (3.7, -2.6, 1.5), (0.2, -1.2, 1.5), (0.0, 2.75, 1.5)]


@pytest.fixture(scope="module")
def station_round_trip(tmp_path_factory, scenes_dir):
    from mjwalk.world.workplace import load_model

    src = scenes_dir / "assembly_station.xml"
    scan = synthetic_scan(
        load_model(src),
        STATION_SCANNERS,
        step_deg=0.3,
        noise=0.005,
        tilt_deg=1.5,
        floor_height=-1.37,
        seed=0,
    )
    orig = load_workplace(src)
    from mjwalk.scan.scene import _Site

    sites = [
        _Site(n, tuple(orig.station(n).xy), None, 0.0)
        for n in ("stand_rack2", "stand_car1", "stand_rack1")
    ]
    scene = build_scene(scan.points, source="station scan", sites=sites)
    out = write_scene(scene, tmp_path_factory.mktemp("scan") / "station_scan.xml")
    return orig, load_workplace(out), scene


@pytest.mark.slow
def test_round_trip_clearance_within_3cm(station_round_trip):
    """Synthetic scan of the station (4 scanners, 0.3° rays, 5 mm range noise, 1.5° tilt,
    floor at -1.37 m) -> scene: the walk clearance (obstacles and floor edge) of the
    reconstruction is within 3 cm of the original's at >= 95 % of the free floor's nodes
    (measured 95.0 %; the misses are the parts no scanner saw: the car body's top behind its
    cabin, the far side of the pillar); the floor is found within a 2 cm cell and levelled to
    0.01°."""
    orig, rec, scene = station_round_trip
    assert abs(scene.levelling.tilt_deg - 1.5) < 0.01
    # the floor's edge is placed at the centres of its outermost 2 cm cells, and the 5 mm range
    # noise carries a few floor points past the walls: within one cell (open3d-cpu 0.20 on
    # numpy 2.4: -4.0134 for -4.0, one cell out)
    assert np.allclose(rec.floor_bounds, orig.floor_bounds, atol=0.02)
    gx, gy = orig.clearance.grid_xy()
    xy = np.stack(np.meshgrid(gx, gy), -1).reshape(-1, 2)
    wo = orig.walk_clearance(xy)
    wr = rec.walk_clearance(xy)
    free = wo > 0
    share = float((np.abs(wr[free] - wo[free]) <= 0.03).mean())
    assert share >= 0.95, share
    # Inside the original's obstacles the reconstruction is mostly no walkable floor either
    # (measured 93 %: the rest is under the car body's east end, whose top no scanner saw and
    # whose floor the scanners saw between the wheels).
    inside = orig.clearance(xy) < -0.05
    assert (wr[inside] < 0.05).mean() > 0.9


@pytest.mark.slow
def test_walks_planned_in_the_reconstruction_keep_the_body_radius_in_the_original(
    station_round_trip,
):
    from mjwalk.gait.default import default_model
    from mjwalk.plan.walks import plan_walks
    from mjwalk.world.probe import ClearanceProbe, path_clearance

    orig, rec, _ = station_round_trip
    probe = ClearanceProbe(orig)
    model = default_model(progress=False)
    for a, b in (("stand_rack2", "stand_car1"), ("stand_rack1", "stand_rack2")):
        for walk in plan_walks(rec, a, b, model, n=3, seed=3, options=PlannerOptions(radius=0.25)):
            assert path_clearance(probe, walk.xy, spacing=0.02).min() >= 0.25 - 0.005


# ------------------------------------------------------------------------- real scans


def _obstacle_iou(p, q) -> float:
    """Intersection over union of two floor plans' obstacle cells on the world grid they share
    (their rectangles may differ by a cell where one saw a hair more floor)."""
    r = p.resolution
    ox, oy = round((q.x0 - p.x0) / r), round((q.y0 - p.y0) / r)  # q's origin in p's cells
    lo = np.minimum((0, 0), (oy, ox))
    hi = np.maximum(p.obstacles.shape, (oy + q.obstacles.shape[0], ox + q.obstacles.shape[1]))
    a = np.zeros(tuple(hi - lo), bool)
    b = np.zeros_like(a)
    a[-lo[0] : -lo[0] + p.obstacles.shape[0], -lo[1] : -lo[1] + p.obstacles.shape[1]] = (
        p.obstacles > 0
    )
    qy, qx = oy - lo[0], ox - lo[1]
    b[qy : qy + q.obstacles.shape[0], qx : qx + q.obstacles.shape[1]] = q.obstacles > 0
    return float((a & b).sum() / max((a | b).sum(), 1))


def _floor_tilt_deg(pts: np.ndarray) -> float:
    """Tilt of the levelled floor: least squares z = ax + by + c over points within 5 cm of
    z = 0, trimmed to 2 cm then 1 cm of the fit."""
    sel = pts[np.abs(pts[:, 2]) < 0.05]
    for tol in (0.02, 0.01, None):
        a = np.column_stack([sel[:, :2], np.ones(len(sel))])
        coef = np.linalg.lstsq(a, sel[:, 2], rcond=None)[0]
        if tol is None:
            break
        sel = sel[np.abs(sel[:, 2] - a @ coef) < tol]
    return float(np.degrees(np.arctan(np.hypot(*coef[:2]))))


@pytest.mark.slow
@pytest.mark.parametrize(
    ("rel", "overhead"),
    [
        ("scans/pcl-room-scan/room_scan1.pcd", 2.5),
        ("scans/e57-pump-room/pumpAVisualReferenceImage.e57", 2.5),
    ],
    ids=["pcl-room", "e57-pump-room"],
)
def test_real_scan(shared_data, tmp_path, rel, overhead):
    from mjwalk.gait.default import default_model
    from mjwalk.plan.walks import plan_walks
    from mjwalk.render.plot import save_plan_png
    from mjwalk.world.probe import ClearanceProbe, path_clearance

    src = shared_data / rel
    out = tmp_path / "scene.xml"
    scene = scan_to_scene(src, out)
    cloud = read_scan(src)
    levelled = scene.levelling.apply(cloud.points)
    assert _floor_tilt_deg(levelled) < 0.2
    wp = load_workplace(out)
    inside = wp.on_floor(levelled[:, :2])
    # Obstacles: the band's points (pumps, pads, pipes, furniture, walls) are covered.
    band = inside & (levelled[:, 2] > 0.1) & (levelled[:, 2] < 1.9)
    assert (wp.walk_clearance(levelled[band, :2]) < 0.05).mean() > 0.95
    # Overhead structure (pipework, ceiling) is there but is no obstacle: the scene made
    # without every point above the band has the same obstacles, box for box.
    above = levelled[:, 2] > overhead
    assert (above & inside).sum() > 500
    keep = levelled[:, 2] <= 2.0
    rows = np.concatenate([[0], np.cumsum(keep)])  # the stations' rows among those kept
    stations = [
        dataclasses.replace(s, start=int(rows[s.start]), stop=int(rows[s.stop]))
        for s in cloud.stations
    ]
    assert stations  # both files state where their scanner stood
    without = build_scene(cloud.points[keep], source="no overhead", stations=stations)
    iou = _obstacle_iou(without.plan, scene.plan)
    print(f"{src.name}: obstacle IoU with/without overhead points {iou:.4f}")
    assert iou > 0.97
    # A walk across the room: between the two free nodes farthest apart along x.
    from scipy import ndimage

    gx, gy = wp.clearance.grid_xy()
    xy = np.stack(np.meshgrid(gx, gy), -1)
    for roomy in (0.55, 0.45, 0.35):  # free floor with room to turn, in one piece
        lab, n = ndimage.label(wp.walk_clearance(xy) > roomy)
        main = lab == 1 + int(np.argmax(ndimage.sum(lab > 0, lab, np.arange(1, n + 1))))
        free = xy[main][:: max(1, int(main.sum()) // 800)]
        far = np.linalg.norm(free[:, None] - free[None], axis=-1)
        i, j = np.unravel_index(np.argmax(far), far.shape)  # the two nodes farthest apart
        start, goal = free[i], free[j]
        if far[i, j] > 2.0:
            break
    assert np.linalg.norm(goal - start) > 2.0
    walks = plan_walks(wp, start, goal, default_model(progress=False), n=3, seed=0)
    assert len(walks) == 3
    assert all(w.length >= np.linalg.norm(goal - start) - 0.3 for w in walks)
    probe = ClearanceProbe(wp)
    for w in walks:
        assert path_clearance(probe, w.xy, spacing=0.05).min() >= 0.24
    png = Path(os.environ.get("MJWALK_SCAN_PNG_DIR", tmp_path)) / f"walk_{src.stem}.png"
    save_plan_png(png, wp, walks, title=f"{src.name}: walk across")
    assert png.stat().st_size > 10_000


def _write_format(path, pts):
    """Write ``pts`` (metres) in the format of ``path``'s suffix with the readers' libraries."""
    suffix = path.suffix
    if suffix in (".ply", ".pcd"):
        from mjwalk.scan.read import open3d_module

        o3d = open3d_module()
        cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(pts))
        o3d.io.write_point_cloud(str(path), cloud, write_ascii=False, compressed=suffix == ".pcd")
    elif suffix in (".las", ".laz"):
        import laspy

        header = laspy.LasHeader(point_format=3, version="1.2")
        header.offsets = pts.min(axis=0)
        header.scales = [0.001, 0.001, 0.001]
        las = laspy.LasData(header)
        las.x, las.y, las.z = pts[:, 0], pts[:, 1], pts[:, 2]
        las.write(str(path))
    elif suffix == ".e57":
        import pye57

        with pye57.E57(str(path), mode="w") as e57:
            e57.write_scan_raw(
                {"cartesianX": pts[:, 0], "cartesianY": pts[:, 1], "cartesianZ": pts[:, 2]}
            )
    return path


@pytest.mark.parametrize("suffix", [".ply", ".pcd", ".las", ".laz", ".e57"])
def test_formats_read_by_their_libraries(tmp_path, suffix):
    """Binary PLY, binary-compressed PCD (Open3D), LAS and LAZ (laspy, lazrs), E57 (pye57) of
    a tilted room far from the origin (georeferenced LAS-like x, y) give the same scene."""
    far = suffix in (".las", ".laz")
    offset = np.array([512_000.0, 5_400_000.0, 230.0]) if far else np.zeros(3)
    pts = _tilt(_room_cloud(spacing=0.04), 1.2, -0.8) + offset
    src = _write_format(tmp_path / f"room{suffix}", pts)
    scene = scan_to_scene(src, tmp_path / "room.xml")
    assert abs(scene.levelling.tilt_deg - 1.2) < 0.05
    wp = load_workplace(tmp_path / "room.xml")
    x0, y0, x1, y1 = np.asarray(wp.floor_bounds) - np.resize(np.asarray(offset)[:2], 4)
    assert x1 - x0 == pytest.approx(4.0, abs=0.05)
    assert y1 - y0 == pytest.approx(3.0 * np.cos(np.radians(1.2)), abs=0.05)


def test_a_cloud_read_upside_down_is_refused_by_its_stations():
    pts, spots, rows = _deck_scan()
    stations = [
        Station(p, int(a), int(b), "test")
        for p, a, b in zip(spots, rows[:-1], rows[1:], strict=True)
    ]
    build_scene(pts, stations=stations, source="deck")
    flip = np.array([1.0, -1.0, -1.0])
    upside = [dataclasses.replace(s, viewpoint=s.viewpoint * flip) for s in stations]
    with pytest.raises(ScanError, match=r"deck: .* above every scanner .* pass --up=-z"):
        build_scene(pts * flip, stations=upside, source="deck")
    build_scene(pts * flip, stations=upside[:0], source="deck")  # no station: counts accept
