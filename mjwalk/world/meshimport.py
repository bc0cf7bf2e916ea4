"""Concave meshes: their true floor footprint, and convex parts MuJoCo can collide with.

MuJoCo collides a mesh geom as its convex hull, and :func:`mjwalk.world.footprint.geom_footprint`
projects that hull. An L- or U-shaped bench, or a car body with an open door, is concave: the
planner would see it filled in. Two remedies that agree with each other:

- :func:`mesh_footprints`: the footprint of a mesh geom from its triangles cut by the obstacle
  band (trimesh slices them, shapely unites their projections and the band's cross-sections),
  cut into convex pieces (constrained Delaunay triangles of the simplified outline) the
  clearance field takes as ordinary convex footprints. ``load_workplace`` uses it for every
  mesh geom whose band footprint is concave.
- :func:`import_scene` (``mjwalk scene-import``): each concave mesh geom of an MJCF scene (or a
  bare mesh file, put on a floor) is replaced by its CoACD convex decomposition (Wei et al.
  2022, collision-aware concavity), written inline as mesh assets, so MuJoCo's collision and
  the planner's footprints (the union of the parts' footprints) are the same shape.

A mesh can be concave in elevation too: a stair and its landing modelled as one mesh (CAD exports
do this) has a convex footprint, but its convex hull is a wedge over the nosings, so the treads
are hidden under it (:func:`hidden_walk_faces`): ``load_workplace`` warns
(:class:`HiddenWalkFaceWarning`) and ``scene-import`` decomposes such a mesh, finely enough that
every tread is a part's top: exactly where the mesh has no overhang
(:func:`mjwalk.world.meshextrude.extruded_parts`, each upward face extruded down to the base),
else by CoACD, warning (:class:`ApproximateImportWarning`) where a walk face is no part's top
within ``norms.STAIR_TOLERANCE``.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from pathlib import Path

import mujoco
import numpy as np

from mjwalk._args import check_output_file
from mjwalk._io import atomic_path
from mjwalk.errors import InputError, SceneError
from mjwalk.world.floor import check_floor_size
from mjwalk.world.footprint import Footprint
from mjwalk.world.hiddenfaces import HiddenWalkFaceWarning, hidden_walk_faces
from mjwalk.world.meshextrude import approximate_walk_faces, extruded_parts
from mjwalk.world.norms import STAIR_TOLERANCE
from mjwalk.world.units import UNITS, UP_AXES

#: A band footprint is concave when its convex hull exceeds it by more than this share of the
#: hull's area (below, the hull footprint is as good and cheaper).
CONCAVE_SHARE = 0.01
#: Outline simplification before cutting into convex pieces, metres (well below the 2 cm
#: clearance grid).
SIMPLIFY_TOL = 0.002
#: CoACD's concavity threshold range (the range its README gives, 0.01 to 1; Wei et al. 2022):
#: the decomposition cuts until every part is within this share of the bounding-box diagonal
#: of convex, which 0 or less never allows (``--threshold 0`` was still cutting after 120 s).
THRESHOLD_RANGE = (0.01, 1.0)
#: CoACD's threshold for a mesh concave in plan (4 cm on a 2 m bench).
DEFAULT_THRESHOLD = 0.02
#: CoACD's threshold for a mesh with walk faces under its hull: the range's least. A tread must
#: be a part's top to within ``norms.STAIR_TOLERANCE`` (5 mm); relative to the bounding-box
#: diagonal of anything a person stands on (at least a 0.26 x 0.6 m tread's, 0.65 m) that is
#: below 0.008, finer than CoACD allows, so the finest it allows.
ELEVATION_THRESHOLD = THRESHOLD_RANGE[0]
#: Mesh file suffixes trimesh reads for scene-import.
MESH_SUFFIXES = (".stl", ".obj", ".ply", ".glb", ".gltf", ".off")


class ApproximateImportWarning(UserWarning):
    """A decomposed mesh's walk face is no convex part's top within ``norms.STAIR_TOLERANCE``."""


def _band_polygon(verts: np.ndarray, faces: np.ndarray, z0: float, z1: float):
    """The projection onto z = 0 of the mesh surface between heights z0 and z1, plus its
    cross-sections there, as one shapely geometry (world metres); None when empty."""
    import shapely  # deferred: shapely is slow to import; only concave meshes need it
    import trimesh  # deferred: trimesh is slow to import; only meshes need it
    from trimesh.intersections import slice_faces_plane  # deferred: trimesh is slow to import

    if verts[:, 2].max() < z0 or verts[:, 2].min() > z1:
        return None
    v, f = verts, faces
    for origin, normal in (((0, 0, z0), (0, 0, 1)), ((0, 0, z1), (0, 0, -1))):
        if len(f) == 0:
            break
        v, f = slice_faces_plane(v, f, plane_normal=normal, plane_origin=origin)[:2]
    pieces = []
    if len(f):
        tri = v[f][:, :, :2]
        area = 0.5 * np.abs(
            (tri[:, 1, 0] - tri[:, 0, 0]) * (tri[:, 2, 1] - tri[:, 0, 1])
            - (tri[:, 2, 0] - tri[:, 0, 0]) * (tri[:, 1, 1] - tri[:, 0, 1])
        )
        tri = tri[area > 1e-10]
        pieces.extend(shapely.polygons(tri))
    mesh = trimesh.Trimesh(verts, faces, process=False)
    for z in (z0, z1):
        if verts[:, 2].min() < z < verts[:, 2].max():
            sec = mesh.section(plane_origin=(0, 0, z), plane_normal=(0, 0, 1))
            if sec is not None:
                try:
                    planar, _ = sec.to_2D(to_2D=np.eye(4))
                    pieces.extend(planar.polygons_full)
                except (ValueError, IndexError):  # open cross-section: the triangles suffice
                    pass
    if not pieces:
        return None
    # A hair of buffer closes the slivers between triangles that share edges only up to
    # floating-point rounding.
    union = shapely.union_all([shapely.buffer(p, 1e-6) for p in pieces])
    return union if not union.is_empty else None


def mesh_footprints(
    verts: np.ndarray, faces: np.ndarray, z0: float, z1: float, name: str, geom_id: int
) -> list[Footprint] | None:
    """Convex pieces of a mesh's band footprint.

    Args:
        verts: (V, 3) vertices, world metres.
        faces: (F, 3) vertex indices.
        z0: the band's bottom, world z, metres.
        z1: the band's top, world z, metres.
        name: the geom's name, given to each piece.
        geom_id: the geom's id, given to each piece.

    Returns:
        Triangles of the band footprint (simplified, constrained Delaunay), or None when the
        footprint is convex (to within :data:`CONCAVE_SHARE`) or empty, so the caller keeps
        the hull footprint.
    """
    import shapely  # deferred: shapely is slow to import; only concave meshes need it

    poly = _band_polygon(verts, faces, z0, z1)
    if poly is None or poly.area <= 0:
        return None
    hull = poly.convex_hull
    if hull.area - poly.area <= CONCAVE_SHARE * hull.area:
        return None
    poly = shapely.simplify(poly, SIMPLIFY_TOL)
    tris = shapely.constrained_delaunay_triangles(poly)
    out = []
    for t in shapely.get_parts(tris):
        xy = np.asarray(t.exterior.coords)[:-1]
        if len(xy) < 3:
            continue
        cross = (xy[1, 0] - xy[0, 0]) * (xy[2, 1] - xy[0, 1]) - (xy[2, 0] - xy[0, 0]) * (
            xy[1, 1] - xy[0, 1]
        )
        if abs(cross) < 1e-12:
            continue
        out.append(Footprint(name, geom_id, xy if cross > 0 else xy[::-1].copy()))
    return out or None


def geom_mesh_world(model: mujoco.MjModel, data: mujoco.MjData, g: int):
    """A mesh geom's vertices in the world.

    Args:
        model: the compiled scene.
        data: its data, kinematics done.
        g: the mesh geom's id.

    Returns:
        (vertices (V, 3) world metres, faces (F, 3)).
    """
    mesh = int(model.geom_dataid[g])
    va, vn = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
    fa, fn = model.mesh_faceadr[mesh], model.mesh_facenum[mesh]
    local = np.asarray(model.mesh_vert[va : va + vn], dtype=float)
    faces = np.asarray(model.mesh_face[fa : fa + fn], dtype=np.int64)
    rot = data.geom_xmat[g].reshape(3, 3)
    return local @ rot.T + data.geom_xpos[g], faces


def concave_mesh_footprints(
    model: mujoco.MjModel, data: mujoco.MjData, g: int, z0: float, z1: float, warn: bool = True
) -> list[Footprint] | None:
    """:func:`mesh_footprints` of a mesh geom.

    Args:
        model: the compiled scene.
        data: its data, kinematics done.
        g: the geom id.
        z0: the band's bottom, world z, metres.
        z1: the band's top, world z, metres.

        warn: whether to look for walk faces its hull hides and warn of them (once per scene:
            a level's band of the same mesh is not looked at again).

    Returns:
        The convex pieces, or None when the geom is not a mesh or not concave.

    Warns:
        HiddenWalkFaceWarning: the mesh has walk faces under its convex hull (a stair as one
            mesh), which MuJoCo collides with: ``mjwalk scene-import`` decomposes it.
    """
    if int(model.geom_type[g]) != mujoco.mjtGeom.mjGEOM_MESH:
        return None
    verts, faces = geom_mesh_world(model, data, g)
    name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) or f"geom{g}"
    hidden = hidden_walk_faces(verts, faces) if warn else []
    if hidden:
        heights = ", ".join(f"{h.z:.3f}" for h in hidden)
        warnings.warn(
            f"mesh geom {name!r} has {len(hidden)} face(s) to stand on under its convex hull "
            f"(at z {heights} m), which MuJoCo collides with instead of the mesh: they are no "
            "walk surfaces; run `mjwalk scene-import` on the scene to decompose it",
            HiddenWalkFaceWarning,
            stacklevel=2,
        )
    return mesh_footprints(verts, faces, z0, z1, name, g)


def _plan_concave(verts: np.ndarray, faces: np.ndarray) -> bool:
    """Whether the top view of a mesh's triangles falls short of its convex hull's area by
    more than CONCAVE_SHARE (the test for meshes that enclose no volume)."""
    import shapely  # deferred: shapely is slow to import; only concave meshes need it

    tri = verts[faces][:, :, :2]
    area = 0.5 * np.abs(
        (tri[:, 1, 0] - tri[:, 0, 0]) * (tri[:, 2, 1] - tri[:, 0, 1])
        - (tri[:, 2, 0] - tri[:, 0, 0]) * (tri[:, 1, 1] - tri[:, 0, 1])
    )
    tri = tri[area > 1e-10]
    if not len(tri):
        return False
    plan = shapely.union_all([shapely.buffer(p, 1e-6) for p in shapely.polygons(tri)])
    hull = plan.convex_hull.area
    return hull - plan.area > CONCAVE_SHARE * hull


def concave_mesh(
    verts: np.ndarray, faces: np.ndarray, rot: np.ndarray | None = None, hidden: bool | None = None
) -> tuple[np.ndarray, np.ndarray] | None:
    """The mesh to decompose when a mesh is concave, else None.

    A mesh with walk faces under its hull (:func:`~mjwalk.world.hiddenfaces.hidden_walk_faces`:
    a stair as one mesh) is concave in elevation. A closed volume is concave when its volume
    falls short of its hull's by more than CONCAVE_SHARE. A mesh that is not one (a missing
    triangle, faces wound inwards: common in exported CAD) is first repaired with trimesh
    (``fix_normals``, ``fill_holes``) and judged as a volume when that closes it; one that
    stays open or non-manifold (two boxes sharing an edge) is judged by its top view, so MuJoCo
    never collides the convex hull of a U whose inside is free.

    Args:
        verts: (V, 3) vertices in the mesh frame, metres.
        faces: (F, 3) vertex indices.
        rot: (3, 3) the mesh frame's rotation in the world, for the top view (None: identity).
        hidden: whether it has walk faces under its hull, when the caller knows (None: found
            here).

    Returns:
        (vertices, faces) to decompose (the repaired mesh where the repair closed it), or None.
    """
    import trimesh  # deferred: trimesh is slow to import; only meshes need it

    mesh = trimesh.Trimesh(verts, faces, process=True)
    world = verts if rot is None else verts @ np.asarray(rot).T
    if hidden is None:
        hidden = bool(hidden_walk_faces(world, faces))
    if not mesh.is_volume:
        fixed = mesh.copy()
        trimesh.repair.fix_normals(fixed)
        trimesh.repair.fill_holes(fixed)
        if not fixed.is_volume:
            return (verts, faces) if hidden or _plan_concave(world, faces) else None
        mesh = fixed
    hull = mesh.convex_hull.volume
    if hidden or hull - abs(mesh.volume) > CONCAVE_SHARE * hull:
        return np.asarray(mesh.vertices, float), np.asarray(mesh.faces, np.int64)
    return None


def convex_parts(
    verts: np.ndarray, faces: np.ndarray, threshold: float = DEFAULT_THRESHOLD, seed: int = 0
) -> list[tuple[np.ndarray, np.ndarray]]:
    """CoACD convex decomposition of a mesh.

    Args:
        verts: (V, 3) vertices, metres.
        faces: (F, 3) vertex indices.
        threshold: CoACD's concavity bound relative to the mesh's bounding-box diagonal
            (:data:`DEFAULT_THRESHOLD`: 4 cm on a 2 m bench, below the planner's 0.25 m body
            radius by an order).
        seed: CoACD's seed.

    Returns:
        The convex parts, (vertices (V_k, 3), faces (F_k, 3)) each.
    """
    import coacd  # deferred: coacd is slow to import; only scene-import needs it

    coacd.set_log_level("error")
    parts = coacd.run_coacd(
        coacd.Mesh(np.asarray(verts, float), np.asarray(faces, np.int32)),
        threshold=threshold,
        seed=seed,
    )
    return [(np.asarray(v, float), np.asarray(f, np.int64)) for v, f in parts]


def decompose(
    verts: np.ndarray,
    faces: np.ndarray,
    threshold: float = DEFAULT_THRESHOLD,
    seed: int = 0,
    rot: np.ndarray | None = None,
) -> list[tuple[np.ndarray, np.ndarray]]:
    """Convex parts of a concave mesh: a closed volume without overhangs exactly
    (:func:`~mjwalk.world.meshextrude.extruded_parts`); else each closed body of a mesh made
    of several (a CAD export of touching boxes: a stair's steps and its landing) on its own, a
    convex body as itself (to within CONCAVE_SHARE of its hull's volume) and a concave one
    exactly or by :func:`convex_parts`; a mesh that is not several closed bodies by
    :func:`convex_parts` whole.

    Args:
        verts: (V, 3) vertices in the mesh frame, metres.
        faces: (F, 3) vertex indices.
        threshold: CoACD's concavity threshold (see :func:`convex_parts`).
        seed: CoACD's seed.
        rot: (3, 3) the mesh frame's rotation in the world, whose z is "down" for the exact
            decomposition (None: identity).

    Returns:
        The convex parts, (vertices (V_k, 3), faces (F_k, 3)) each.
    """
    import trimesh  # deferred: trimesh is slow to import; only meshes need it

    rot = np.eye(3) if rot is None else np.asarray(rot, float)

    def exact_or_coacd(v: np.ndarray, f: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
        parts = extruded_parts(v @ rot.T, f)
        if parts is None:
            return convex_parts(v, f, threshold, seed)
        return [(pv @ rot, pf) for pv, pf in parts]  # back to the mesh frame

    mesh = trimesh.Trimesh(verts, faces, process=True)
    bodies = mesh.split(only_watertight=True)
    if len(bodies) < 2 or sum(len(b.faces) for b in bodies) != len(mesh.faces):
        return exact_or_coacd(np.asarray(verts, float), np.asarray(faces, np.int64))
    out = []
    for body in bodies:
        bv, bf = np.asarray(body.vertices, float), np.asarray(body.faces, np.int64)
        hull = body.convex_hull.volume
        if hull - abs(body.volume) <= CONCAVE_SHARE * hull:
            out.append((bv, bf))
        else:
            out.extend(exact_or_coacd(bv, bf))
    return out


@dataclass
class ImportResult:
    """What :func:`import_scene` wrote: ``parts`` maps each decomposed geom to its part count."""

    output: Path
    parts: dict[str, int] = field(default_factory=dict)
    files: list[Path] = field(default_factory=list)
    mesh_dir: str = "inline"


def check_threshold(threshold: float | None, what: str = "threshold") -> None:
    """Refuse a concavity threshold outside CoACD's range.

    Args:
        threshold: the value given (None: the defaults, accepted).
        what: its name in the message.

    Raises:
        InputError: not a number within :data:`THRESHOLD_RANGE`.
    """
    lo, hi = THRESHOLD_RANGE
    if threshold is None:
        return
    if isinstance(threshold, bool) or not (
        isinstance(threshold, int | float) and lo <= threshold <= hi
    ):
        raise InputError(
            f"{what} {threshold!r}: CoACD's concavity threshold must lie in [{lo:g}, {hi:g}] "
            f"(a share of the mesh's bounding-box diagonal; {DEFAULT_THRESHOLD:g} is the default)"
        )


def _mesh_scene_spec(path: Path, units: str, up: str) -> mujoco.MjSpec:
    """An MJCF spec with a floor and the mesh file as one obstacle (its lowest point on the
    floor)."""
    import trimesh  # deferred: trimesh is slow to import; only meshes need it

    if units not in UNITS:
        raise SceneError(f"{path}: unknown units {units!r} (one of {', '.join(UNITS)})")
    key = (up if up.startswith(("+", "-")) else f"+{up}").lower()
    if key not in UP_AXES:
        raise SceneError(f"{path}: unknown up axis {up!r} (one of {', '.join(UP_AXES)})")
    try:
        mesh = trimesh.load(str(path), force="mesh", process=False)
    except Exception as exc:  # trimesh raises many types for unreadable files
        raise SceneError(f"{path}: not a readable mesh: {exc}") from exc
    if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
        raise SceneError(f"{path}: no triangles in the mesh")
    bad = ~np.all(np.isfinite(mesh.vertices), axis=1)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise SceneError(
            f"{path}: vertex {k + 1} (of {len(bad)}) is not finite: "
            f"{np.asarray(mesh.vertices[k]).tolist()} ({int(bad.sum())} such vertices)"
        )
    mesh.process()  # merge duplicate vertices, drop degenerate faces (as trimesh.load does)
    verts = np.asarray(mesh.vertices, float) @ (UP_AXES[key].T * UNITS[units])
    verts[:, 2] -= verts[:, 2].min()
    lo, hi = verts[:, :2].min(axis=0) - 2.0, verts[:, :2].max(axis=0) + 2.0
    spec = mujoco.MjSpec()
    spec.modelname = path.stem
    floor = spec.worldbody.add_geom(
        name="floor", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[*(0.5 * (hi - lo)), 0.05]
    )
    floor.pos = [*(0.5 * (lo + hi)), 0.0]
    m = spec.add_mesh(name=path.stem)
    m.uservert = verts.ravel().tolist()
    m.userface = np.asarray(mesh.faces, np.int64).ravel().tolist()
    spec.worldbody.add_geom(
        name=path.stem, type=mujoco.mjtGeom.mjGEOM_MESH, meshname=path.stem, rgba=[0.6, 0.5, 0.4, 1]
    )
    return spec


def import_scene(
    source: str | Path,
    output: str | Path,
    *,
    units: str = "m",
    up: str = "+z",
    threshold: float | None = None,
) -> ImportResult:
    """Write ``output``: the MJCF (or mesh file) ``source`` with every concave mesh geom
    replaced by its convex parts (inline mesh assets, same body, pose, material and
    collision settings).

    Args:
        source: an MJCF scene (.xml) or a mesh file (:data:`MESH_SUFFIXES`; it becomes one
            mesh geom on a floor of its extent plus 2 m each way).
        output: the MJCF file to write (.xml, atomically).
        units: a mesh file's length unit (:data:`mjwalk.world.units.UNITS`).
        up: a mesh file's up axis (:data:`mjwalk.world.units.UP_AXES`).
        threshold: CoACD's concavity threshold for the meshes not decomposed exactly (see
            :func:`check_threshold`; None:
            :data:`DEFAULT_THRESHOLD`, and :data:`ELEVATION_THRESHOLD` for a mesh with walk
            faces under its hull).

    Returns:
        The output path and the number of convex parts per replaced geom name.

    Warns:
        ApproximateImportWarning: a replaced mesh's walk face is no part's top within
            ``norms.STAIR_TOLERANCE`` (a mesh with overhangs, which CoACD approximates).

    Raises:
        SceneError: an unreadable source or a scene that does not compile, before writing.
    """
    source, output = Path(source), Path(output)
    check_threshold(threshold)
    check_output_file(output, "output", (".xml",))
    spec = _source_spec(source, units, up)
    model = _compile_source(spec, source, units)
    result = ImportResult(output)
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    for g in range(model.ngeom):
        if int(model.geom_type[g]) != mujoco.mjtGeom.mjGEOM_MESH:
            continue
        mesh = int(model.geom_dataid[g])
        va, vn = model.mesh_vertadr[mesh], model.mesh_vertnum[mesh]
        fa, fn = model.mesh_faceadr[mesh], model.mesh_facenum[mesh]
        verts = np.asarray(model.mesh_vert[va : va + vn], float)
        faces = np.asarray(model.mesh_face[fa : fa + fn], np.int64)
        rot = data.geom_xmat[g].reshape(3, 3)
        hidden = bool(hidden_walk_faces(verts @ rot.T, faces))
        concave = concave_mesh(verts, faces, rot, hidden)
        if concave is None:
            continue
        name = model.geom(g).name or f"geom{g}"
        geom = spec.geoms[g]
        if threshold is not None:
            limit = threshold
        elif hidden:
            limit = ELEVATION_THRESHOLD
        else:
            limit = DEFAULT_THRESHOLD
        parts = decompose(*concave, limit, rot=rot)
        pos = data.geom_xpos[g]
        world = [(pv @ rot.T + pos, pf) for pv, pf in parts]
        _warn_approximate(name, verts @ rot.T + pos, faces, world)
        for k, (pv, pf) in enumerate(parts):
            _add_part(spec, model, (g, geom), f"{name}_part{k}", (pv, pf))
        spec.delete(geom)
        result.parts[name] = len(parts)
    try:
        spec.compile()
        xml = spec.to_xml()
    except ValueError as exc:
        raise SceneError(f"{source}: the imported scene does not compile: {exc}") from exc
    with atomic_path(output) as tmp:
        tmp.write_text(xml)
    return result


def _warn_approximate(
    name: str, verts: np.ndarray, faces: np.ndarray, parts: list[tuple[np.ndarray, np.ndarray]]
) -> None:
    """Warn (one line) when a walk face of mesh geom ``name`` (world orientation) is no top of
    its convex ``parts`` within ``norms.STAIR_TOLERANCE``."""
    off = approximate_walk_faces(verts, faces, parts)
    if off:
        worst = max(d for _, d in off)
        warnings.warn(
            f"mesh geom {name!r}: its convex parts miss {len(off)} walk face(s) (at z "
            f"{', '.join(f'{z:.3f}' for z, _ in off)} m) by up to "
            f"{'the whole face' if np.isinf(worst) else f'{worst * 1000:.0f} mm'}, more than "
            f"{STAIR_TOLERANCE * 1000:g} mm: CoACD approximated it (an overhang, or no closed "
            "volume), so its imported levels may be off",
            ApproximateImportWarning,
            stacklevel=3,
        )


def _source_spec(source: Path, units: str, up: str) -> mujoco.MjSpec:
    """The editable spec of ``source`` (an MJCF file, or a mesh file on a floor); SceneError
    on a folder, a missing file, an unknown suffix or malformed MJCF."""
    if source.is_dir():
        raise SceneError(f"{source} is a folder, not a mesh or MJCF scene file")
    if not source.is_file():
        raise SceneError(f"{source}: file not found")
    if source.suffix.lower() in MESH_SUFFIXES:
        spec = _mesh_scene_spec(source, units, up)
    elif source.suffix.lower() == ".xml":
        try:
            spec = mujoco.MjSpec.from_file(str(source))
        except ValueError as exc:
            raise SceneError(f"{source}: not a valid MJCF scene: {exc}") from exc
    else:
        raise SceneError(
            f"{source}: unknown scene format {source.suffix!r} "
            f"(MJCF .xml or a mesh: {', '.join(MESH_SUFFIXES)})"
        )
        # Asset files stay where they are: their folders become absolute.
        for attr in ("meshdir", "texturedir"):
            folder = getattr(spec.compiler, attr, None)
            if folder is not None:
                setattr(spec.compiler, attr, str((source.parent / folder).resolve()) + "/")
    return spec


def _compile_source(spec: mujoco.MjSpec, source: Path, units: str) -> mujoco.MjModel:
    """``spec`` compiled, its floor checked as :func:`~mjwalk.world.floor.check_floor_size`
    does before any work; SceneError naming ``source`` (and the units, for a mesh file)."""
    try:
        model = spec.compile()
    except ValueError as exc:
        raise SceneError(f"{source}: does not compile: {exc}") from exc
    try:
        check_floor_size(model, str(source))  # a floor mjwalk cannot load: refused before work
    except SceneError as exc:
        if source.suffix.lower() not in MESH_SUFFIXES:
            raise
        raise SceneError(
            f"{exc}; the floor is the mesh's extent plus 2 m each way, so the mesh is too "
            f"large in units {units!r} (another --units?)"
        ) from None
    return model


def _add_part(
    spec: mujoco.MjSpec,
    model: mujoco.MjModel,
    source_geom: tuple[int, mujoco.MjsGeom],
    pname: str,
    part: tuple[np.ndarray, np.ndarray],
) -> None:
    """Add one convex part (vertices, faces) of ``source_geom`` (its id in ``model``, its spec
    element) as mesh asset and geom ``pname`` in the geom's body, with its pose, colour,
    collision settings, group and material."""
    pv, pf = part
    g, geom = source_geom
    body = geom.parent
    pm = spec.add_mesh(name=pname)
    pm.uservert = pv.ravel().tolist()
    pm.userface = pf.ravel().tolist()
    pg = body.add_geom(name=pname, type=mujoco.mjtGeom.mjGEOM_MESH, meshname=pname)
    # The part's vertices are in the compiled mesh's frame, which the compiled geom
    # pose places in the body.
    pg.pos = model.geom_pos[g].copy()
    pg.quat = model.geom_quat[g].copy()
    pg.rgba = model.geom_rgba[g].copy()
    pg.contype, pg.conaffinity = int(model.geom_contype[g]), int(model.geom_conaffinity[g])
    pg.group = int(model.geom_group[g])
    if geom.material:
        pg.material = geom.material
