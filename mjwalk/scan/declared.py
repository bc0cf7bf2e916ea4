"""What a scan file declares (its point count and encoding) checked against what it holds.

Open3D and laspy trust a file's header: a PLY, PCD or PTS file declaring more points than it
holds comes back from ``open3d.io.read_point_cloud`` padded with uninitialised memory (zeros,
denormals or 1e+200 values, measured with Open3D 0.19), a header declaring 1e9 points makes it
allocate 24 GB before reading a byte, and an ASCII PLY value RPly cannot parse (``inf``,
``nan``) ends the read there with the rest of the points left uninitialised. The headers are a
few lines of text (PLY: Turk 1994, the Stanford format; PCD v0.7: the Point Cloud Library's
file format; LAS 1.4: ASPRS R15 §2.3), so they are read here and the declared count compared
with the rows (text) or the bytes (binary) the file holds before any reader allocates.
"""

from __future__ import annotations

import math
import os
import re
from dataclasses import dataclass
from pathlib import Path

from mjwalk.errors import ScanError

#: Bytes of one value of each PLY property type (PLY format, Turk 1994).
PLY_TYPES = {
    "char": 1,
    "uchar": 1,
    "int8": 1,
    "uint8": 1,
    "short": 2,
    "ushort": 2,
    "int16": 2,
    "uint16": 2,
    "int": 4,
    "uint": 4,
    "int32": 4,
    "uint32": 4,
    "float": 4,
    "float32": 4,
    "double": 8,
    "float64": 8,
}
#: A header longer than this is not a point-cloud header (PLY and PCD headers are lines of
#: text; comments included they rarely reach a kilobyte).
MAX_HEADER = 1 << 16
#: Text bodies are scanned in blocks of this many bytes.
_BLOCK = 1 << 24
#: A token that is not a finite number in a text body: nan, inf, infinity (any case).
_NON_FINITE = re.compile(rb"(?i)\b[-+]?(nan|inf|infinity)\b")


@dataclass(frozen=True)
class Declared:
    """What a header declares: ``encoding`` (ascii, binary, ...), ``count`` points,
    ``header_lines`` lines before the body, ``columns`` the vertex properties in order (PLY),
    ``first_bad_row`` the first text row holding nan/inf (None: none, or binary), and
    ``viewpoint`` the sensor position a PCD header's VIEWPOINT gives (file units and axes;
    None: no such line or not three finite numbers)."""

    encoding: str
    count: int
    header_lines: int
    columns: tuple[str, ...] = ()
    first_bad_row: int | None = None
    viewpoint: tuple[float, float, float] | None = None


def _header(path: Path, end: bytes, what: str) -> tuple[list[str], int]:
    """The header lines of ``path`` up to and including the line starting with ``end``, and
    the byte offset of the body."""
    with open(path, "rb") as fh:
        head = fh.read(MAX_HEADER)
    pos = 0
    lines: list[str] = []
    while True:
        nl = head.find(b"\n", pos)
        if nl < 0:
            raise ScanError(
                f"{path}: no {end.decode()!r} line in the first {MAX_HEADER // 1024} kB: "
                f"not a complete {what} header"
            )
        line = head[pos:nl].decode("ascii", errors="replace").strip()
        lines.append(line)
        pos = nl + 1
        if line.split(" ", 1)[0] == end.decode():
            return lines, pos


def _text_rows(path: Path, offset: int) -> tuple[int, int | None]:
    """Non-blank lines of ``path`` after byte ``offset``, and the 0-based index among them of
    the first line holding a non-finite token (None: none). Reads in blocks."""
    rows = 0
    first_bad: int | None = None
    with open(path, "rb") as fh:
        fh.seek(offset)
        rest = b""
        while True:
            block = fh.read(_BLOCK)
            data = rest + block
            if not block:
                lines = [data] if data.strip() else []
                rest = b""
            else:
                cut = data.rfind(b"\n") + 1
                lines, rest = data[:cut].split(b"\n"), data[cut:]
            for ln in lines:
                if not ln.strip():
                    continue
                if first_bad is None and _NON_FINITE.search(ln):
                    first_bad = rows
                rows += 1
            if not block:
                return rows, first_bad


def _declared(path: Path, n: int, what: str, held: str) -> ScanError:
    return ScanError(
        f"{path}: the header declares {n} {what} but the file holds {held} "
        "(a truncated file or a wrong count in the header); nothing was read"
    )


def _more(path: Path, points: int, width: int, height: int, held: str) -> ScanError:
    return ScanError(
        f"{path}: the PCD header declares POINTS {points} (WIDTH x HEIGHT = {width} x {height}) "
        f"but the file holds {held} (a wrong count in the header, or points appended after it "
        "was written); nothing was read"
    )


def check_ply(path: Path) -> Declared:
    """Check a PLY file's declared element counts against its body.

    Args:
        path: the PLY file.

    Returns:
        What the header declares (encoding, vertex count, header lines, vertex columns, first
        text row holding nan/inf).

    Raises:
        ScanError: the body holds fewer rows (ASCII) or bytes (binary) than the header declares.
    """
    lines, body = _header(path, b"end_header", "PLY")
    fmt = ""
    elements: list[tuple[str, int, int, bool]] = []  # name, count, min row bytes, has lists
    columns: list[str] = []
    for ln in lines:
        words = ln.split()
        if not words:
            continue
        if words[0] == "format" and len(words) >= 2:
            fmt = words[1]
        elif words[0] == "element":
            try:
                count = int(words[2])
            except (IndexError, ValueError):
                raise ScanError(f"{path}: bad PLY element line {ln!r}") from None
            if count < 0:
                raise ScanError(f"{path}: negative PLY element count in {ln!r}")
            elements.append((words[1], count, 0, False))
        elif words[0] == "property" and elements:
            name, count, size, lists = elements[-1]
            if len(words) >= 2 and words[1] == "list":
                size += PLY_TYPES.get(words[2], 0) if len(words) > 2 else 0
                lists = True
            elif len(words) >= 2:
                if words[1] not in PLY_TYPES:
                    raise ScanError(f"{path}: unknown PLY property type in {ln!r}")
                size += PLY_TYPES[words[1]]
                if name == "vertex" and len(words) >= 3:
                    columns.append(words[2])
            elements[-1] = (name, count, size, lists)
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise ScanError(f"{path}: unknown PLY format {fmt!r} (ascii or binary_*_endian)")
    vertices = next((c for name, c, _, _ in elements if name == "vertex"), None)
    if vertices is None:
        raise ScanError(f"{path}: the PLY header declares no 'element vertex'")
    if fmt == "ascii":
        rows, bad = _text_rows(path, body)
        need = sum(c for _, c, _, _ in elements)
        if rows < need:
            raise _declared(
                path, vertices, "vertices" if need == vertices else "rows", f"{rows} rows"
            )
        return Declared(fmt, vertices, len(lines), tuple(columns), bad)
    held = os.path.getsize(path) - body
    need = sum(c * size for _, c, size, _ in elements)  # list rows at their least (no items)
    if held < need:
        row = next(size for name, _, size, _ in elements if name == "vertex")
        about = f"{held} bytes after its header (room for {held // max(row, 1)} vertices)"
        raise _declared(path, vertices, f"vertices of {row} bytes", about)
    return Declared(fmt, vertices, len(lines), tuple(columns))


def _pcd_viewpoint(words: list[str]) -> tuple[float, float, float] | None:
    """The translation of a PCD VIEWPOINT line (tx ty tz qw qx qy qz), or None."""
    try:
        xyz = tuple(float(w) for w in words[:3])
    except ValueError:
        return None
    if len(xyz) != 3 or not all(map(math.isfinite, xyz)):
        return None
    return xyz


def check_pcd(path: Path) -> Declared:
    """Check a PCD file's POINTS (and WIDTH x HEIGHT) against its body.

    PCD stores missing returns as nan, which Open3D reads as NaN.

    Args:
        path: the PCD file.

    Returns:
        What the header declares (DATA encoding, point count, header lines, first text row
        holding nan/inf, the VIEWPOINT position in file units and axes or None).

    Raises:
        ScanError: an incomplete header, POINTS unequal to WIDTH x HEIGHT, a short body, or a body
            holding more points than declared (Open3D would read only the declared ones): ASCII
            rows, or at least one whole point's bytes beyond the declared ones in a binary body.
    """
    lines, body = _header(path, b"DATA", "PCD")
    fields: dict[str, list[str]] = {}
    for ln in lines:
        words = ln.split()
        if words and not words[0].startswith("#"):
            fields[words[0].upper()] = words[1:]
    try:
        size = [int(v) for v in fields.get("SIZE", [])]
        count = [int(v) for v in fields.get("COUNT", ["1"] * len(size))]
        width = int(fields["WIDTH"][0])
        height = int(fields.get("HEIGHT", ["1"])[0])
        points = int(fields.get("POINTS", [str(width * height)])[0])
        data = fields["DATA"][0].lower()
    except (KeyError, IndexError, ValueError) as exc:
        raise ScanError(
            f"{path}: incomplete PCD header ({exc!r} missing or not a number)"
        ) from None
    if points != width * height or points < 0:
        raise ScanError(
            f"{path}: the PCD header declares POINTS {points} but WIDTH x HEIGHT = "
            f"{width} x {height} = {width * height}; nothing was read"
        )
    viewpoint = _pcd_viewpoint(fields.get("VIEWPOINT", []))
    row = sum(s * c for s, c in zip(size, count, strict=False))
    held = os.path.getsize(path) - body
    if data == "ascii":
        rows, bad = _text_rows(path, body)
        if rows < points:
            raise _declared(path, points, "points", f"{rows} rows")
        if rows > points:
            raise _more(path, points, width, height, f"{rows} rows")
        return Declared(data, points, len(lines), first_bad_row=bad, viewpoint=viewpoint)
    if data == "binary":
        if held < points * row:
            raise _declared(
                path,
                points,
                f"points of {row} bytes",
                f"{held} bytes after its header (room for {held // max(row, 1)} points)",
            )
        if row > 0 and held - points * row >= row:
            more = f"{held} bytes after its header, room for {held // row} points of {row} bytes"
            raise _more(path, points, width, height, more)
        return Declared(data, points, len(lines), viewpoint=viewpoint)
    if data == "binary_compressed":
        with open(path, "rb") as fh:
            fh.seek(body)
            sizes = fh.read(8)
        if len(sizes) < 8:
            raise _declared(path, points, "points", "no compressed data")
        packed = int.from_bytes(sizes[:4], "little")
        unpacked = int.from_bytes(sizes[4:], "little")
        if unpacked != points * row or held - 8 < packed:
            raise _declared(
                path,
                points,
                f"points of {row} bytes ({points * row} bytes unpacked)",
                f"{unpacked} bytes unpacked in {held - 8} of its declared {packed} packed bytes",
            )
        return Declared(data, points, len(lines), viewpoint=viewpoint)
    raise ScanError(f"{path}: unknown PCD DATA {data!r} (ascii, binary, binary_compressed)")


def check_pts(path: Path) -> Declared:
    """Check a PTS file's leading point count against its rows.

    Args:
        path: the PTS file.

    Returns:
        What it declares (ascii, the count, one header line, first row holding nan/inf).

    Raises:
        ScanError: no leading count, or fewer rows than it says.
    """
    with open(path, "rb") as fh:
        first = fh.readline()
        body = len(first)
    try:
        count = int(first.split()[0])
    except (IndexError, ValueError):
        raise ScanError(
            f"{path}: a PTS file starts with its point count, got {first[:40]!r}"
        ) from None
    rows, bad = _text_rows(path, body)
    if rows < count:
        raise _declared(path, count, "points", f"{rows} rows")
    return Declared("ascii", count, 1, first_bad_row=bad)


def check_e57(path: Path) -> None:
    """Refuse an E57 file shorter than the physical length its header declares (ASTM
    E2807 §8.2: bytes 16-23 of the file, little-endian), before libE57 reads it.

    Args:
        path: the E57 file.

    Raises:
        ScanError: a file shorter than its header, or than the length it declares.
    """
    with open(path, "rb") as fh:
        head = fh.read(24)
    if len(head) < 24:
        raise ScanError(f"{path}: {len(head)} bytes, shorter than an E57 file header (48 bytes)")
    declared = int.from_bytes(head[16:24], "little")
    held = os.path.getsize(path)
    if held < declared:
        raise ScanError(
            f"{path}: the E57 header declares a file of {declared} bytes but it holds {held} "
            "(a truncated file); nothing was read"
        )


def check_las(path: Path) -> int:
    """Check an uncompressed LAS file's point count against its size.

    LAS 1.4 §2.3: the point records start at ``offset_to_point_data``,
    ``point_data_record_length`` bytes each. LAZ is checked after reading
    (:func:`check_read_count`).

    Args:
        path: the LAS or LAZ file.

    Returns:
        The declared point count.
    """
    import laspy  # deferred: laspy is optional (LAS/LAZ only)

    try:
        with laspy.open(str(path)) as fh:
            header = fh.header
    except (laspy.errors.LaspyException, OSError, ValueError) as exc:
        raise ScanError(f"{path}: unreadable LAS/LAZ header: {exc}") from exc
    count = int(header.point_count)
    if path.suffix.lower() == ".las" and not header.are_points_compressed:
        row = int(header.point_format.size)
        held = os.path.getsize(path) - int(header.offset_to_point_data)
        if held < count * row:
            raise _declared(
                path,
                count,
                f"points of {row} bytes",
                f"{max(held, 0) // row} whole records ({max(held, 0)} bytes)",
            )
    return count


def check_read_count(path: Path, declared: int, read: int, what: str = "points") -> None:
    """Refuse a file whose reader returned fewer points than its header declares.

    Args:
        path: the file, named in the error.
        declared: the count its header declares.
        read: the count the reader returned.
        what: what is counted, for the message.

    Raises:
        ScanError: ``read`` < ``declared``.
    """
    if read < declared:
        raise _declared(path, declared, what, f"{read} readable {what}")
