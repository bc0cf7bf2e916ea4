"""Read laser scans into one (N, 3) array of points in metres with z up.

Formats and the library that reads each (no format is parsed here by hand):

- PLY, PCD (ASCII, binary and binary-compressed), XYZ, XYZN, XYZRGB and PTS: Open3D
  (``open3d.io.read_point_cloud``).
- LAS and LAZ: laspy (LAZ through its lazrs backend); the scaled x, y, z.
- E57: pye57; every scan of the file, each moved by its pose into the file's frame; points the
  file marks invalid are left out (as pye57 does).

Units and up axis: E57 is metres by its standard (ASTM E2807); the other formats do not say, so the
caller states them (``units``, ``up``; default metres and +z, the convention of terrestrial
scanners, LAS and E57). A cloud whose height span is implausible for metres is refused with the
likely unit named (:func:`check_units`) instead of becoming a 3 km tall scene.
"""

from __future__ import annotations

import contextlib
import ctypes
import sys
import types
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mjwalk._jit import njit
from mjwalk.errors import ScanError
from mjwalk.scan.declared import (
    Declared,
    check_e57,
    check_las,
    check_pcd,
    check_ply,
    check_pts,
    check_read_count,
)
from mjwalk.scan.limits import check_extent
from mjwalk.world.units import UNITS, UP_AXES

#: Suffixes read by Open3D, and the formats Open3D's reader expects for them.
_OPEN3D = {".ply": "ply", ".pcd": "pcd", ".xyz": "xyz", ".xyzn": "xyzn", ".xyzrgb": "xyzrgb"}
_OPEN3D_PTS = {".pts": "pts"}
SUFFIXES = (*_OPEN3D, *_OPEN3D_PTS, ".las", ".laz", ".e57")
#: Tallest plausible span of an indoor scan in metres (floor to the highest return, after the
#: 0.5/99.5 % percentiles). Tall assembly halls reach about 30 m under the crane rail; a cloud
#: spanning more than this in its stated units is in other units.
MAX_HEIGHT_SPAN = 60.0
#: Smallest plausible span (metres): a scan of a workplace holds at least a person's height.
MIN_HEIGHT_SPAN = 0.3


@dataclass(frozen=True)
class Station:
    """Where a scanner stood and which points it returned: ``viewpoint`` (3,) in the frame of
    the points it goes with (metres, z up, once read), the points ``start:stop`` of that
    cloud, and ``origin`` naming where the position came from (a PCD VIEWPOINT header, an E57
    pose, a synthetic scan)."""

    viewpoint: np.ndarray
    start: int
    stop: int
    origin: str

    def moved(self, pose: np.ndarray, shift: int) -> Station:
        """The station moved into another frame and later rows.

        Args:
            pose: (4, 4) rigid transform applied to the viewpoint.
            shift: rows added before its points (a cloud merged after others).

        Returns:
            The moved station.
        """
        vp = pose[:3, :3] @ self.viewpoint + pose[:3, 3]
        return Station(vp, self.start + shift, self.stop + shift, self.origin)


@dataclass
class ScanCloud:
    """Points of a scan: ``points`` (N, 3) in metres, z up, in the file's frame otherwise.

    ``points = scale * (axes @ (file_point - offset))``: ``scale`` metres per file unit
    (``units``), ``axes`` (3, 3) the rotation of the up axis ``up`` onto +z and ``offset`` (3,)
    the point subtracted first (file units and axes; zeros unless given). ``stations``: the
    scanner positions the file states, in the same frame (empty when it states none).
    """

    source: Path
    points: np.ndarray
    units: str
    up: str
    scale: float
    axes: np.ndarray
    offset: np.ndarray = field(default_factory=lambda: np.zeros(3))
    stations: list[Station] = field(default_factory=list)


def open3d_module():
    """Open3D, imported. Its Linux wheels link libusb-1.0 (for the Azure Kinect) without bundling
    it; the ``libusb-package`` wheel ships that library, loaded here first so a machine without
    Debian's libusb-1.0-0 still imports Open3D. ``import open3d`` also imports its Plotly/Dash
    drawing helpers (Dash, Flask and IPython: 0.4 s of a 0.9 s import), which mjwalk never
    calls: they are left out (:func:`_without_plotly_drawing`)."""
    with _without_plotly_drawing():
        return _import_open3d()


@contextlib.contextmanager
def _without_plotly_drawing():
    """While Open3D is first imported, ``open3d.visualization.draw_plotly`` is a stub: any
    function taken from it says that mjwalk loaded Open3D without its Plotly drawing (the stub
    stays: import open3d before mjwalk's scan reader to have the real one)."""
    name = "open3d.visualization.draw_plotly"
    if "open3d" in sys.modules or name in sys.modules:
        yield
        return
    stub = types.ModuleType(name)

    def __getattr__(attr: str):
        if attr.startswith("__"):
            raise AttributeError(attr)

        def unavailable(*args, **kwargs):
            raise ImportError(
                f"open3d.visualization.{attr}: mjwalk imported Open3D without its Plotly "
                "drawing (Dash); import open3d before mjwalk's scan reader to use it"
            )

        return unavailable

    stub.__getattr__ = __getattr__  # type: ignore[method-assign]
    sys.modules[name] = stub
    yield


def _import_open3d():
    try:
        import open3d  # deferred: open3d is optional and slow to import
    except ImportError as exc:
        if "libusb" not in str(exc):
            raise ScanError(f"Open3D cannot be imported: {exc}") from exc
        try:
            import libusb_package  # deferred: optional, only when open3d lacks libusb

            ctypes.CDLL(str(libusb_package.get_library_path()), mode=ctypes.RTLD_GLOBAL)
            import open3d  # deferred: open3d is optional and slow to import
        except (ImportError, OSError) as exc2:
            raise ScanError(
                f"Open3D needs libusb-1.0 ({exc2}); pip install libusb-package "
                "or apt-get install libusb-1.0-0"
            ) from exc2
    return open3d


def _sniff(path: Path, suffix: str) -> None:
    """Refuse a file that is not of the format its suffix names (Open3D would print a warning
    and return an empty cloud)."""
    with open(path, "rb") as fh:
        head = fh.read(4096)
    if not head:
        raise ScanError(f"{path}: empty file, not a point cloud")
    if suffix == ".ply" and not head.startswith(b"ply"):
        raise ScanError(f"{path}: not a PLY file (it does not start with 'ply')")
    if suffix == ".pcd" and not (b"FIELDS" in head and b"DATA" in head):
        raise ScanError(f"{path}: not a PCD file (no FIELDS/DATA header)")
    if suffix == ".las" or suffix == ".laz":
        if not head.startswith(b"LASF"):
            raise ScanError(f"{path}: not a LAS/LAZ file (no LASF signature)")
    if suffix == ".e57" and not head.startswith(b"ASTM-E57"):
        raise ScanError(f"{path}: not an E57 file (no ASTM-E57 signature)")
    if suffix in (".xyz", ".xyzn", ".xyzrgb", ".pts"):
        lines = [ln for ln in head.split(b"\n")[:-1] if ln.strip() and not ln.startswith(b"#")]
        rows = lines[1:4] if suffix == ".pts" else lines[:3]
        try:
            ok = bool(rows) and all(len(ln.split()) >= 3 for ln in rows)
            [float(v) for ln in rows for v in ln.split()[:3]]
        except ValueError:
            ok = False
        if not ok:
            raise ScanError(f"{path}: not a text point cloud (rows of 'x y z ...' numbers)")


#: A raw station: the viewpoint (3,) in the file's units and axes, its origin, and how many
#: of the file's rows (in order) it returned.
_RawStation = tuple[np.ndarray, str, int]


def _read_open3d(
    path: Path, suffix: str, drop_invalid: bool
) -> tuple[np.ndarray, list[_RawStation]]:
    """Points of a PLY, PCD, XYZ* or PTS file through Open3D, after the declared count is
    checked against the file (:mod:`.declared`): Open3D pads a short file with uninitialised
    memory and stops an ASCII PLY at the first value RPly cannot parse (nan, inf)."""
    declared = None
    if suffix == ".ply":
        declared = check_ply(path)
    elif suffix == ".pcd":
        declared = check_pcd(path)
    elif suffix == ".pts":
        declared = check_pts(path)
    if suffix == ".ply" and declared is not None and declared.first_bad_row is not None:
        line = declared.header_lines + declared.first_bad_row + 1
        if not drop_invalid:
            raise ScanError(
                f"{path}: vertex {declared.first_bad_row} (line {line}) holds a NaN or infinite "
                "value (pass --drop-invalid, or drop_invalid=True, to leave such points out)"
            )
        return _ascii_ply_xyz(path, declared), []
    o3d = open3d_module()
    fmt = {**_OPEN3D, **_OPEN3D_PTS}[suffix]
    cloud = o3d.io.read_point_cloud(
        str(path), format=fmt, remove_nan_points=False, remove_infinite_points=False
    )
    pts = np.asarray(cloud.points, dtype=np.float64)
    if declared is not None:
        check_read_count(path, declared.count, len(pts))
    if declared is not None and declared.viewpoint is not None:
        return pts, [(np.array(declared.viewpoint), "PCD VIEWPOINT header", len(pts))]
    return pts, []


def _ascii_ply_xyz(path: Path, declared: Declared) -> np.ndarray:
    """x, y, z of an ASCII PLY whose vertex rows hold nan/inf, read by NumPy (which parses
    them; RPly does not). The vertex element must come first, as every point-cloud PLY has it."""
    try:
        cols = [declared.columns.index(c) for c in ("x", "y", "z")]
    except ValueError:
        raise ScanError(f"{path}: the PLY vertex has no x, y and z properties") from None
    try:
        return np.loadtxt(
            path,
            skiprows=declared.header_lines,
            max_rows=declared.count,
            usecols=cols,
            comments=None,
            ndmin=2,
        )
    except ValueError as exc:
        raise ScanError(f"{path}: unreadable ASCII PLY vertex rows: {exc}") from exc


def read_points_raw(path: Path, *, drop_invalid: bool = False) -> np.ndarray:
    """A file's points as stored.

    Args:
        path: the scan file.
        drop_invalid: read an ASCII PLY without its NaN rows (else they are refused).

    Returns:
        (N, 3) float64 points in file units and axes, NaNs kept unless an ASCII PLY holds them.
    """
    return _read_with_stations(path, drop_invalid)[0]


def _read_with_stations(path: Path, drop_invalid: bool) -> tuple[np.ndarray, list[_RawStation]]:
    """:func:`read_points_raw`'s points and the scanner positions the file states: a PCD's
    VIEWPOINT, each E57 scan's pose translation (file units and axes)."""
    suffix = path.suffix.lower()
    if path.is_dir():
        raise ScanError(f"{path} is a folder, not a scan file (give the scan files in it)")
    if suffix not in SUFFIXES:
        raise ScanError(
            f"{path}: unknown point-cloud format {suffix!r} (read: {', '.join(SUFFIXES)})"
        )
    if not path.is_file():
        raise ScanError(f"{path}: scan file not found")
    _sniff(path, suffix)
    if suffix in _OPEN3D or suffix in _OPEN3D_PTS:
        return _read_open3d(path, suffix, drop_invalid)
    if suffix in (".las", ".laz"):
        import laspy  # deferred: laspy is optional (LAS/LAZ only)

        declared = check_las(path)
        try:
            las = laspy.read(str(path))
        except Exception as exc:  # laspy's and lazrs' own error types, and numpy's
            raise ScanError(
                f"{path}: unreadable LAS/LAZ file (header declares {declared} points): {exc}"
            ) from exc
        check_read_count(path, declared, len(las.points))
        return np.column_stack([las.x, las.y, las.z]).astype(np.float64), []
    import pye57  # deferred: pye57 is optional (E57 only)

    check_e57(path)
    try:
        e57 = pye57.E57(str(path))
        parts = []
        stations: list[_RawStation] = []
        for i in range(e57.scan_count):
            scan = e57.read_scan(i, ignore_missing_fields=True, transform=True)
            xyz = np.column_stack([scan["cartesianX"], scan["cartesianY"], scan["cartesianZ"]])
            parts.append(xyz)
            # read_scan(transform=True) moves the points by this pose: its translation is
            # where the scanner stood, in the file's frame.
            vp = np.asarray(e57.get_header(i).translation, dtype=np.float64)
            if vp.shape == (3,) and np.isfinite(vp).all():
                stations.append((vp, f"E57 pose of scan {i}", len(xyz)))
            else:
                stations.append((np.full(3, np.nan), "", len(xyz)))
    except ScanError:
        raise
    except Exception as exc:  # pye57 raises libE57's own exception types
        raise ScanError(f"{path}: unreadable E57 file: {exc}") from exc
    return (np.vstack(parts) if parts else np.empty((0, 3))), stations


#: The height span a unit is judged by, metres: a workplace storey, about 3 m. Of the units
#: that make a cloud's span plausible, the one bringing it nearest this (on a log scale) is named.
TYPICAL_HEIGHT = 3.0


def check_units(points: np.ndarray, units: str, source: Path | str) -> None:
    """Refuse a cloud whose height span is implausible for an indoor workplace.

    Args:
        points: (N, 3) points, metres after ``units``, z up.
        units: the units the file was read in.
        source: the cloud's name in errors.

    Raises:
        ScanError: the span of 99 % of its heights is outside the plausible range; the message
            names the units that make it plausible (the one nearest a 3 m storey first).
    """
    if len(points) < 10:
        return
    lo, hi = np.percentile(points[:, 2], [0.5, 99.5])
    span = float(hi - lo)
    if MIN_HEIGHT_SPAN <= span <= MAX_HEIGHT_SPAN:
        return
    raw = span / UNITS[units]
    fits = sorted(
        (u for u, f in UNITS.items() if MIN_HEIGHT_SPAN <= raw * f <= MAX_HEIGHT_SPAN),
        key=lambda u: abs(np.log(raw * UNITS[u] / TYPICAL_HEIGHT)),
    )
    if span == 0.0:
        why = "all points at one height: a flat or degenerate cloud, not a room"
    elif fits:
        u = fits[0]
        why = f"in {u} it spans {raw * UNITS[u]:.3g} m: pass --units {u} (units={u!r} in Python)"
    else:
        why = "no length unit makes it a room"
    raise ScanError(
        f"{source}: the cloud spans {raw:.4g} {units} = {span:.4g} m in height (99 % of its "
        f"points), not a plausible indoor scan ({MIN_HEIGHT_SPAN}-{MAX_HEIGHT_SPAN} m); {why}"
    )


def check_options(units: str, up: str, source: Path | str) -> str:
    """Refuse unknown units or up axis, naming the choices.

    Args:
        units: a key of :data:`mjwalk.world.units.UNITS`.
        up: a key of :data:`mjwalk.world.units.UP_AXES` (a bare axis reads as +, any case).
        source: named in errors.

    Returns:
        The up axis's key in :data:`mjwalk.world.units.UP_AXES`.

    Raises:
        ScanError: unknown units or up axis.
    """
    if units not in UNITS:
        raise ScanError(f"{source}: unknown units {units!r} (--units one of {', '.join(UNITS)})")
    key = up if up.startswith(("+", "-")) else f"+{up}"
    if key.lower() not in UP_AXES:
        raise ScanError(f"{source}: unknown up axis {up!r} (--up one of {', '.join(UP_AXES)})")
    return key.lower()


@njit
def _non_finite_rows(raw):
    """How many rows of ``raw`` (N, 3) hold a NaN or infinite coordinate."""
    n = 0
    for k in range(raw.shape[0]):
        if not (np.isfinite(raw[k, 0]) and np.isfinite(raw[k, 1]) and np.isfinite(raw[k, 2])):
            n += 1
    return n


def to_metres_z_up(
    raw: np.ndarray,
    *,
    units: str = "m",
    up: str = "+z",
    source: Path | str = "cloud",
    drop_invalid: bool = False,
    offset: tuple[float, float, float] | np.ndarray | None = None,
) -> tuple[np.ndarray, float, np.ndarray]:
    """Validate raw points and convert them to metres, z up.

    NaN or infinite coordinates are an error unless ``drop_invalid`` (organised clouds mark
    missing returns with NaN; say so explicitly to drop them). The cloud's extent and
    coordinates are checked (:func:`~mjwalk.scan.limits.check_extent`), after its height span
    (:func:`check_units`).

    Args:
        raw: (N, 3) points in the file's units and axes.
        units: the file's length unit.
        up: the file's up axis.
        source: the cloud's name in errors.
        drop_invalid: leave out NaN or infinite rows instead of refusing them.
        offset: (3,) file units and axes, subtracted first (a georeferenced cloud beyond
            :data:`~mjwalk.scan.limits.MAX_COORDINATE`); None: nothing subtracted.

    Returns:
        (points (M, 3) metres z up, scale metres per file unit, axes (3, 3) up-axis rotation):
        ``points = scale * axes @ (raw - offset)``.
    """
    key = check_options(units, up, source)
    raw = np.asarray(raw, dtype=np.float64)
    if raw.ndim != 2 or raw.shape[1] != 3:
        raise ScanError(f"{source}: points must be an (N, 3) array, got shape {raw.shape}")
    if len(raw) == 0:
        raise ScanError(f"{source}: the point cloud is empty")
    bad = _non_finite_rows(raw)  # one compiled pass; the mask only when there are some
    if bad:
        finite = np.isfinite(raw).all(axis=1)
        if not drop_invalid:
            raise ScanError(
                f"{source}: {bad} of {len(raw)} points have NaN or infinite coordinates "
                "(pass drop_invalid=True / --drop-invalid to leave them out)"
            )
        raw = raw[finite]
        if len(raw) == 0:
            raise ScanError(f"{source}: every point has NaN or infinite coordinates")
    if offset is not None:
        off = np.asarray(offset, dtype=np.float64)
        if off.shape != (3,) or not np.isfinite(off).all():
            raise ScanError(
                f"{source}: offset must be 3 finite numbers (file units), got {offset!r}"
            )
        raw = raw - off
    scale = UNITS[units]
    axes = UP_AXES[key]
    pts = raw @ (axes.T * scale) if key != "+z" or scale != 1.0 else raw
    check_units(pts, units, source)  # first: a cloud in mm is also "too large"
    check_extent(pts, source, scale=scale, axes=axes)
    return pts, scale, axes


def read_scan(
    path: str | Path,
    *,
    units: str = "m",
    up: str = "+z",
    drop_invalid: bool = False,
    offset: tuple[float, float, float] | np.ndarray | None = None,
) -> ScanCloud:
    """Read a scan file into metres, z up.

    See the module docstring for formats and options.

    Args:
        path: the scan file.
        units: its length unit when it does not say.
        up: its up axis when it does not say.
        drop_invalid: leave out NaN or infinite points instead of refusing them.
        offset: (3,) subtracted from every point first, file units and axes (None: nothing).

    Returns:
        The cloud: points (N, 3) metres z up, how they were converted, and the scanner stations
        the file states.

    Raises:
        ScanError: unknown suffix, missing file, a file not of its format, a header declaring
            more points than the file holds, no points, NaN points (unless ``drop_invalid``),
            stray points or coordinates beyond range, implausible units, unknown units or up
            axis.
    """
    path = Path(path)
    check_options(units, up, path)
    if path.suffix.lower() == ".e57" and units != "m":
        raise ScanError(f"{path}: E57 coordinates are metres by the standard; --units {units}")
    raw, raw_stations = _read_with_stations(path, drop_invalid)
    kept = np.isfinite(raw).all(axis=1) if raw_stations and drop_invalid else None
    pts, scale, axes = to_metres_z_up(
        raw, units=units, up=up, source=path, drop_invalid=drop_invalid, offset=offset
    )
    off = np.zeros(3) if offset is None else np.asarray(offset, dtype=np.float64)
    stations = []
    start = stop = 0
    for vp, origin, rows in raw_stations:
        n = rows if kept is None else int(kept[stop : stop + rows].sum())
        stop += rows
        if origin:  # a scan of an E57 file without a usable pose has no station
            stations.append(Station(scale * (axes @ (vp - off)), start, start + n, origin))
        start += n
    return ScanCloud(path, pts, units, up, scale, axes, off, stations)
