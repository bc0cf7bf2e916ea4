"""Concave mesh obstacles: true band footprint for the planner, CoACD parts for MuJoCo."""

from __future__ import annotations

import dataclasses
import warnings
from pathlib import Path

import mujoco
import numpy as np
import pytest
import shapely

from mjwalk.errors import PlanningError, SceneError
from mjwalk.plan.grid import plan_grid
from mjwalk.world import build_clearance, geom_footprint, load_workplace
from mjwalk.world.hiddenfaces import HiddenWalkFaceWarning
from mjwalk.world.meshimport import import_scene


def _extrude(poly: shapely.Polygon, height: float) -> tuple[np.ndarray, np.ndarray]:
    """A closed prism mesh (vertices, outward faces) of a simple polygon, z from 0 to height."""
    ext = np.asarray(shapely.orient_polygons(poly).exterior.coords)[:-1]
    n = len(ext)
    verts = np.vstack([np.c_[ext, np.zeros(n)], np.c_[ext, np.full(n, height)]])
    index = {tuple(p): i for i, p in enumerate(ext.round(9))}
    faces = []
    for t in shapely.get_parts(shapely.constrained_delaunay_triangles(poly)):
        c = np.asarray(t.exterior.coords)[:-1]
        ids = [index[tuple(p)] for p in c.round(9)]
        if (c[1, 0] - c[0, 0]) * (c[2, 1] - c[0, 1]) - (c[2, 0] - c[0, 0]) * (
            c[1, 1] - c[0, 1]
        ) < 0:
            ids = ids[::-1]
        faces += [[ids[2], ids[1], ids[0]], [i + n for i in ids]]
    for i in range(n):
        j = (i + 1) % n
        faces += [[i, j, j + n], [i, j + n, i + n]]
    return verts, np.array(faces)


#: A U-shaped bench, 2.2 x 2.0 m, 0.9 m high, arms 0.4 m thick: the inside is 1.4 m wide and
#: 1.6 m deep, open towards +y. Placed with its base on y in [-1.0, -0.6].
U_BENCH = shapely.Polygon(
    [(0, 0), (2.2, 0), (2.2, 2.0), (1.8, 2.0), (1.8, 0.4), (0.4, 0.4), (0.4, 2.0), (0, 2.0)]
)
INSIDE = np.array([0.0, 0.0])  # in the U, 0.7 m from either arm, 0.6 m from the base
OUTSIDE = np.array([0.0, -2.3])  # behind the base


@pytest.fixture
def u_scene(tmp_path):
    v, f = _extrude(U_BENCH, 0.9)
    xml = f"""<mujoco>
  <asset><mesh name="u" vertex="{" ".join(f"{x:.6g}" for x in v.ravel())}"
               face="{" ".join(str(i) for i in f.ravel())}"/></asset>
  <worldbody>
    <geom name="floor" type="plane" size="3 3 0.05"/>
    <geom name="bench" type="mesh" mesh="u" pos="-1.1 -1.0 0"/>
  </worldbody>
</mujoco>"""
    path = tmp_path / "ubench.xml"
    path.write_text(xml)
    return path


def test_concave_mesh_gets_its_true_footprint(u_scene):
    wp = load_workplace(u_scene)
    assert len(wp.obstacles) > 1 and {f.name for f in wp.obstacles} == {"bench"}
    # In the U: 0.7 m to the arms; the hull would put the point inside the bench.
    assert wp.clearance(INSIDE) == pytest.approx(0.6, abs=0.005)
    assert wp.clearance(np.array([0.0, -0.8])) < 0  # the base itself
    assert wp.clearance(np.array([0.9, 0.0])) < 0  # an arm


def test_walk_into_the_u_is_planned_and_refused_with_the_hull(u_scene):
    wp = load_workplace(u_scene)
    route = plan_grid(wp, OUTSIDE, INSIDE, radius=0.25)
    assert route.length > 3.0  # around an arm and in through the open side
    # The same scene with the bench reduced to its convex hull refuses the goal.
    model = wp.model
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    hull = geom_footprint(model, data, model.geom("bench").id, 0.05, 2.0)
    hulled = dataclasses.replace(
        wp, obstacles=[hull], clearance=build_clearance([hull], wp.floor_bounds)
    )
    with pytest.raises(PlanningError, match="inside obstacle"):
        plan_grid(hulled, OUTSIDE, INSIDE, radius=0.25)


def test_a_mesh_whose_band_cuts_it_in_several_loops_loads(tmp_path):
    """One mesh of two 0.4 m pillars 1.6 m apart (a frame's legs, a table's): its band cuts it
    in two loops, which trimesh sorts with an R-tree (the ``rtree`` dependency; without it
    ``load_workplace`` ended in ModuleNotFoundError). The gap between them stays free."""
    parts = [_extrude(shapely.box(x, -0.2, x + 0.4, 0.2), 1.0) for x in (-1.2, 0.8)]
    v = np.vstack([parts[0][0], parts[1][0]])
    f = np.vstack([parts[0][1], parts[1][1] + len(parts[0][0])])
    path = tmp_path / "pillars.xml"
    path.write_text(f"""<mujoco>
  <asset><mesh name="p" vertex="{" ".join(f"{x:.6g}" for x in v.ravel())}"
               face="{" ".join(str(i) for i in f.ravel())}"/></asset>
  <worldbody>
    <geom name="floor" type="plane" size="3 3 0.05"/>
    <geom name="pillars" type="mesh" mesh="p"/>
  </worldbody>
</mujoco>""")
    wp = load_workplace(path, cache=False)
    assert wp.clearance(np.array([0.0, 0.0])) == pytest.approx(0.8, abs=0.005)
    assert wp.clearance(np.array([1.0, 0.0])) < 0 and wp.clearance(np.array([-1.0, 0.0])) < 0


@pytest.mark.slow
def test_imported_u_bench_walk_is_collision_free_in_mujoco(u_scene, tmp_path):
    """scene-import decomposes the bench (CoACD); walks planned into the U keep the body
    radius by MuJoCo's own distance to the convex parts it collides with."""
    from mjwalk.gait.default import default_model
    from mjwalk.plan.walks import plan_walks
    from mjwalk.world.probe import ClearanceProbe, path_clearance

    out = tmp_path / "imported.xml"
    result = import_scene(u_scene, out)
    assert result.parts["bench"] >= 3
    wp = load_workplace(out)
    assert all(f.name.startswith("bench_part") for f in wp.obstacles)
    # The parts' union is the U to within CoACD's tolerance.
    assert wp.clearance(INSIDE) == pytest.approx(0.6, abs=0.05)
    probe = ClearanceProbe(wp)
    walks = plan_walks(wp, OUTSIDE, INSIDE, default_model(progress=False), n=3, seed=0)
    assert len(walks) == 3
    for w in walks:
        assert path_clearance(probe, w.xy, spacing=0.02).min() >= 0.25 - 0.005
    # The raw scene's MuJoCo geometry is the hull: the same walks would collide with it.
    raw_probe = ClearanceProbe(load_workplace(u_scene))
    assert path_clearance(raw_probe, walks[0].xy, spacing=0.02).min() < 0


def test_scene_import_of_a_mesh_file(tmp_path):
    import trimesh

    v, f = _extrude(U_BENCH, 0.9)
    stl = tmp_path / "bench.stl"
    trimesh.Trimesh(v * 1000.0, f).export(stl)  # millimetres, as CAD exports
    out = tmp_path / "bench.xml"
    result = import_scene(stl, out, units="mm")
    assert result.parts["bench"] >= 3
    wp = load_workplace(out)
    # Placed as in the file: the U's inside centre is at (1.1, 1.2).
    assert wp.clearance(np.array([1.1, 1.2])) == pytest.approx(0.7, abs=0.05)


def test_scene_import_bad_input(tmp_path):
    bad = tmp_path / "x.stl"
    bad.write_text("not a mesh")
    with pytest.raises(SceneError):
        import_scene(bad, tmp_path / "o.xml")
    (tmp_path / "x.txt").write_text("x")
    with pytest.raises(SceneError, match="unknown scene format"):
        import_scene(tmp_path / "x.txt", tmp_path / "o.xml")
    assert not (tmp_path / "o.xml").exists()


#: A 0.51 m platform reached by three 0.17 m risers and 0.28 m treads, 1 m wide: its profile in
#: the x-z plane (stair from x = 0, platform to x = 2.84).
STAIR_PROFILE = shapely.Polygon(
    [(0, 0), (2.84, 0), (2.84, 0.51), (0.56, 0.51), (0.56, 0.34), (0.28, 0.34), (0.28, 0.17)]
    + [(0, 0.17)]
)


def _stair_scene(tmp_path, kind: str):
    """The stair and its platform as ONE mesh geom: "bodies", touching boxes (a CAD export of
    several bodies, not a manifold), or "manifold", the profile extruded (a closed volume)."""
    import trimesh

    if kind == "bodies":
        boxes = []
        for x0, x1, h in (
            (0, 0.28, 0.17),
            (0.28, 0.56, 0.34),
            (0.56, 0.84, 0.51),
            (0.84, 2.84, 0.51),
        ):
            b = trimesh.creation.box(extents=[x1 - x0, 1.0, h])
            b.apply_translation([(x0 + x1) / 2, 0, h / 2])
            boxes.append(b)
        mesh = trimesh.util.concatenate(boxes)
    else:
        v, f = _extrude(STAIR_PROFILE, 1.0)
        mesh = trimesh.Trimesh(np.c_[v[:, 0], v[:, 2] - 0.5, v[:, 1]], f[:, ::-1])
        assert mesh.is_volume
    mesh.export(tmp_path / "stair.stl")
    path = tmp_path / "stair.xml"
    path.write_text(
        """<mujoco><asset><mesh name="stair" file="stair.stl"/></asset><worldbody>
  <geom name="floor" type="plane" size="6 4 0.1"/>
  <geom name="stairmesh" type="mesh" mesh="stair"/>
  <site name="a" pos="-2 0 0"/><site name="b" pos="2.3 0 0.51"/>
</worldbody></mujoco>"""
    )
    return path


def _hidden_warnings(path) -> list[str]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        load_workplace(path)
    return [str(w.message) for w in caught if issubclass(w.category, HiddenWalkFaceWarning)]


@pytest.mark.parametrize("kind", ["bodies", "manifold"])
def test_a_one_mesh_stair_warns_that_its_treads_are_under_its_hull(tmp_path, kind):
    (msg,) = _hidden_warnings(_stair_scene(tmp_path, kind))
    assert "'stairmesh'" in msg and "mjwalk scene-import" in msg and "0.170, 0.340" in msg
    assert "\n" not in msg


def test_no_hidden_face_warning_for_a_convex_mesh_or_the_u_bench(tmp_path, u_scene):
    assert _hidden_warnings(u_scene) == []
    path = tmp_path / "box.xml"
    path.write_text(
        """<mujoco><asset><mesh name="m" vertex="0 0 0 2 0 0 2 1 0 0 1 0 0 0 .5 2 0 .5 2 1 .5
  0 1 .5"/></asset><worldbody><geom name="floor" type="plane" size="4 4 0.1"/>
  <geom name="box" type="mesh" mesh="m"/></worldbody></mujoco>"""
    )
    assert _hidden_warnings(path) == []


@pytest.mark.parametrize("kind", ["bodies", "manifold"])
def test_imported_one_mesh_stair_has_its_treads_and_stair(tmp_path, kind):
    """scene-import decomposes the stair (concave in elevation, not in plan): each tread and
    the platform is a part's top at its true height, joined to the floor by a stair."""
    out = tmp_path / "imported.xml"
    result = import_scene(_stair_scene(tmp_path, kind), out)
    # four closed bodies; the manifold exactly, its last tread and platform one plane: one part
    assert result.parts["stairmesh"] == (4 if kind == "bodies" else 3)
    assert _hidden_warnings(out) == []
    graph = load_workplace(out).levels
    heights = [lv.height for lv in graph.levels]
    assert heights == pytest.approx([0.0, 0.17, 0.34, 0.51], abs=0.002)
    (link,) = graph.links
    assert link.kind == "stair" and (link.lower, link.upper) == (0, 3)
    assert link.risers == pytest.approx([0.17] * 3, abs=0.002)
    assert link.tread == pytest.approx(0.28, abs=0.005)


@pytest.mark.slow
def test_walk_up_the_imported_one_mesh_stair_touches_nothing(tmp_path):
    """Floor -> platform over the imported stair: planned, and its animated timeline has no
    contact with the parts (the raw mesh's hull would hold the feet 0.14 m deep)."""
    from mjwalk.plan.walks import plan_walk
    from mjwalk.timeline import collision_report, timeline_from_walk

    out = tmp_path / "imported.xml"
    import_scene(_stair_scene(tmp_path, "bodies"), out)
    walk = plan_walk(load_workplace(out), "a", "b", rng=0)
    assert walk.z is not None and walk.z.max() == pytest.approx(0.51, abs=0.002)
    assert collision_report(timeline_from_walk(walk, out)) == []


def _one_mesh_scene(tmp_path, profile: list[tuple[float, float]], width: float) -> Path:
    """A closed mesh (the (x, z) ``profile`` extruded ``width`` along y) turned 20 deg about z
    and moved, on a floor, as one mesh geom "stairmesh"; sites at the floor and the top."""
    import trimesh

    v, f = _extrude(shapely.Polygon(profile), width)
    mesh = trimesh.Trimesh(np.c_[v[:, 0], v[:, 2] - width / 2, v[:, 1]], f[:, ::-1])
    assert mesh.is_volume
    mesh.export(tmp_path / "stair.stl")
    top = max(z for _, z in profile)
    far = np.array([max(x for x, _ in profile) - 0.7, 0.0])
    c, s = np.cos(np.radians(20)), np.sin(np.radians(20))
    b = [0.3 + c * far[0], 0.2 + s * far[0]]
    path = tmp_path / "stair.xml"
    path.write_text(
        f"""<mujoco><asset><mesh name="stair" file="stair.stl"/></asset><worldbody>
  <geom name="floor" type="plane" size="15 8 0.1"/>
  <geom name="stairmesh" type="mesh" mesh="stair" pos="0.3 0.2 0" euler="0 0 20"/>
  <site name="a" pos="-2 0 0"/><site name="b" pos="{b[0]:.4f} {b[1]:.4f} {top}"/>
</worldbody></mujoco>"""
    )
    return path


def _stair(platform: float) -> list[tuple[float, float]]:
    """STAIR_PROFILE with a platform ``platform`` long (x, z)."""
    pts = list(STAIR_PROFILE.exterior.coords)[:-1]
    return [(x if x < 2.0 else 0.84 + platform, z) for x, z in pts]


@pytest.mark.parametrize(("platform", "width"), [(10.0, 1.0), (2.0, 3.0)])
def test_a_clean_one_mesh_stair_imports_exactly(tmp_path, platform, width):
    """A closed one-mesh stair without overhangs is decomposed exactly (each tread extruded to
    the base): CoACD found only the floor on the 10 m platform and split tread 1 of the 3 m
    wide stair into two levels."""
    out = tmp_path / "imported.xml"
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # nothing approximate
        result = import_scene(_one_mesh_scene(tmp_path, _stair(platform), width), out)
    assert result.parts["stairmesh"] == 3  # the last tread and the platform: one plane
    graph = load_workplace(out).levels
    assert [lv.height for lv in graph.levels] == pytest.approx([0.0, 0.17, 0.34, 0.51], abs=1e-3)
    (link,) = graph.links
    assert link.kind == "stair" and (link.lower, link.upper) == (0, 3)
    assert link.risers == pytest.approx([0.17] * 3, abs=1e-3)
    assert link.tread == pytest.approx(0.28, abs=1e-3)


def test_a_shelf_as_one_mesh_keeps_coacd_and_says_it_is_approximate(tmp_path):
    """A shelf's boards overhang each other: no exact decomposition; CoACD's parts miss the
    middle board's top by more than 5 mm, and the import says so in one line."""
    from mjwalk.world.meshimport import ApproximateImportWarning

    shelf = [(0, 0), (1.0, 0), (1.0, 0.03), (0.05, 0.03), (0.05, 0.8), (1.0, 0.8), (1.0, 0.83)]
    shelf += [(0.05, 0.83), (0.05, 1.6), (1.0, 1.6), (1.0, 1.63), (0, 1.63)]
    with pytest.warns(ApproximateImportWarning) as caught:
        result = import_scene(_one_mesh_scene(tmp_path, shelf, 1.2), tmp_path / "out.xml")
    assert result.parts["stairmesh"] >= 2
    (msg,) = [str(w.message) for w in caught if w.category is ApproximateImportWarning]
    assert "'stairmesh'" in msg and "0.830" in msg and "\n" not in msg


@pytest.mark.slow
def test_walk_up_the_imported_10_m_platform_stair_touches_nothing(tmp_path):
    """Floor -> 10 m platform over the exactly imported one-mesh stair: planned, at the
    platform's height, and its animated timeline has no contact."""
    from mjwalk.plan.walks import plan_walk
    from mjwalk.timeline import collision_report, timeline_from_walk

    out = tmp_path / "imported.xml"
    import_scene(_one_mesh_scene(tmp_path, _stair(10.0), 1.0), out)
    walk = plan_walk(load_workplace(out), "a", "b", rng=0)
    assert walk.z is not None and walk.z.max() == pytest.approx(0.51, abs=0.002)
    assert collision_report(timeline_from_walk(walk, out)) == []
