# ruff: noqa: F811  (the fixtures imported from test_bad_input are pytest arguments)
"""Bad input of issue 36 (cycle files, scenes, meshes, walk files, seeds, output paths, write
failures): each is refused before any work with one line naming the problem, exit status 2
and no file left behind, or handled correctly where it is valid input.

The helpers (:func:`refused`, the ``no_work`` sentinels, the planned ``station_walk``) are the
ones of ``test_bad_input.py``. Inputs are small and built in each test.
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys
import zipfile

import numpy as np
import pytest
from test_bad_input import no_work, refused, station_walk  # noqa: F401 (fixtures)

from mjwalk import cli
from mjwalk.errors import CycleSpecError, InputError, ModelFileError, SceneError, WriteError


def _spec(tmp_path, scenes_dir, text: str | None = None, extra: str = "", name="cycle.toml"):
    """The station's cycle file with an absolute scene path (and ``extra`` appended)."""
    if text is None:
        text = (scenes_dir / "assembly_station.toml").read_text()
    text = text.replace(
        'scene = "assembly_station.xml"', f'scene = "{scenes_dir}/assembly_station.xml"'
    )
    path = tmp_path / name
    path.write_text(text + extra, encoding="utf-8")
    return path


# ------------------------------------------------------------------ 1, 2: cycle files


@pytest.mark.parametrize(
    "value",
    ["[" * 1000 + "]" * 1000, "{a = " * 1000 + "1" + "}" * 1000],
    ids=["arrays", "inline-tables"],
)
def test_deeply_nested_toml_names_its_key(value, tmp_path, scenes_dir, capsys, no_work):
    spec = _spec(tmp_path, scenes_dir, extra="")
    spec.write_text(f"deep = {value}\n" + spec.read_text())
    err = refused(["simulate", spec, "--out", tmp_path / "out"], capsys, tmp_path)
    assert f"{spec}:1: key 'deep' is nested more than 8 levels deep" in err
    assert "RecursionError" not in err


def test_oversized_name_is_refused_with_its_key(tmp_path, scenes_dir, capsys, no_work):
    text = (scenes_dir / "assembly_station.toml").read_text()
    spec = _spec(tmp_path, scenes_dir, text=f'name = "{"n" * 300}"\n' + text.replace("name =", "#"))
    err = refused(["simulate", spec, "--out", tmp_path / "out"], capsys, tmp_path)
    assert "key 'name' at the top level: a text of 300 characters" in err
    assert "at most 256" in err
    assert len(err) < 400  # the name itself is not echoed
    huge = _spec(tmp_path, scenes_dir, extra="# " + "x" * (2 << 20) + "\n", name="huge.toml")
    err = refused(["simulate", huge, "--out", tmp_path / "out"], capsys, tmp_path)
    assert "more than a cycle spec file can be (1 MiB at most)" in err


def test_oversized_key_in_a_task(tmp_path, scenes_dir):
    from mjwalk.cycle.spec import load_cycle_spec

    spec = _spec(tmp_path, scenes_dir, extra=f'\n[[task]]\nkind = "wait"\n{"k" * 500} = 1\n')
    with pytest.raises(CycleSpecError, match=r"a text of 500 characters") as info:
        load_cycle_spec(spec)
    assert len(str(info.value)) < 400


def test_utf8_bom_is_accepted(tmp_path, scenes_dir, capsys):
    spec = _spec(tmp_path, scenes_dir)
    spec.write_bytes(b"\xef\xbb\xbf" + spec.read_bytes())
    code = cli.main(["simulate", str(spec), "--out", str(tmp_path / "out"), "--dry-run"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert "checked; nothing simulated" in captured.out


def test_single_task_table_cites_its_line(tmp_path, scenes_dir, capsys, no_work):
    spec = tmp_path / "cycle.toml"
    spec.write_text(
        f'# a cycle\nscene = "{scenes_dir}/assembly_station.xml"\nstart = "stand_rack2"\n\n'
        '[task]\nkind = "walk"\nsite = "stand_car1"\n'
    )
    err = refused(["simulate", spec, "--out", tmp_path / "out"], capsys, tmp_path)
    assert f"{spec}:5: [task] is one table; write [[task]]" in err
    # [task] followed by [[task]]: TOML's own error, with the [task] line named
    text = (scenes_dir / "assembly_station.toml").read_text().replace("[[task]]", "[task]", 1)
    mixed = _spec(tmp_path, scenes_dir, text=text, name="mixed.toml")
    line = 1 + text[: text.index("[task]")].count("\n")
    err = refused(["simulate", mixed, "--out", tmp_path / "out"], capsys, tmp_path)
    assert f"[task] at line {line} is one table: write [[task]] for every task" in err


def test_folders_are_named_as_folders(tmp_path, scenes_dir, capsys, no_work):
    folder = tmp_path / "folder"
    folder.mkdir()
    err = refused(["simulate", folder, "--out", tmp_path / "out"], capsys, tmp_path)
    assert f"{folder} is a folder, not a cycle spec file" in err
    argv = ["plan", folder, "--from", "1,1", "--to", "2,2"]
    assert f"{folder} is a folder, not an MJCF scene file" in refused(argv, capsys, tmp_path)
    spec = _spec(tmp_path, scenes_dir)
    spec.write_text(spec.read_text().replace(f"{scenes_dir}/assembly_station.xml", str(folder)))
    err = refused(["simulate", spec, "--out", tmp_path / "out"], capsys, tmp_path)
    assert "key 'scene' at the top level: " in err and "is a folder, not a file" in err


# ------------------------------------------------------------------ dry run: reachability

WALLED = """<mujoco model="walled"><worldbody>
  <geom name="floor" type="plane" size="3 2 0.1"/>
  <geom name="wall" type="box" size="0.1 2 1" pos="0 0 1"/>
  <site name="left" pos="-1.5 0 0"/><site name="right" pos="1.5 0 0"/>
  <site name="left2" pos="-1.5 1 0"/>
</worldbody></mujoco>
"""


def test_dry_run_finds_an_unreachable_walk(tmp_path, capsys):
    (tmp_path / "walled.xml").write_text(WALLED)
    spec = tmp_path / "cycle.toml"
    spec.write_text(
        'scene = "walled.xml"\nstart = "left"\n\n[[task]]\nkind = "walk"\nsite = "left2"\n\n'
        '[[task]]\nkind = "walk"\nsite = "right"\n'
    )
    out = tmp_path / "out"
    err = refused(["simulate", spec, "--out", out, "--dry-run"], capsys, tmp_path)
    assert f"{spec}:10: key 'site' in task 2: no walkable route from 'left2' to 'right'" in err
    assert "unreachable" in err


# ------------------------------------------------------------------ 3: floors


def test_huge_floor_is_refused_naming_it(tmp_path, capsys, no_work):
    scene = tmp_path / "big.xml"
    scene.write_text(
        '<mujoco><worldbody><geom name="hall_floor" type="plane" size="1e6 1e6 0.1"/>'
        '<site name="a" pos="0 0 0"/><site name="b" pos="1 0 0"/></worldbody></mujoco>'
    )
    err = refused(["plan", scene, "--from", "a", "--to", "b", "--n", "0"], capsys, tmp_path)
    assert "the floor 'hall_floor' spans 2e+06 x 2e+06 m" in err
    assert "at most 1e+08 clearance-grid nodes (200 x 200 m at 0.02 m)" in err


def _write_box_stl(path, extents):
    import trimesh

    trimesh.creation.box(extents=extents).export(path)


def test_scene_import_refuses_a_huge_mesh_before_writing(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(
        "mjwalk.world.meshimport.convex_parts", lambda *a, **k: pytest.fail("decomposed")
    )
    stl = tmp_path / "box.stl"
    _write_box_stl(stl, [1e9, 1.0, 1.0])
    before = set(tmp_path.iterdir())
    code = cli.main(["scene-import", str(stl), "-o", str(tmp_path / "out.xml")])
    err = capsys.readouterr().err
    assert code == 2 and "Traceback" not in err
    assert "the floor 'floor' spans 1e+09 x 5 m" in err and "another --units?" in err
    assert set(tmp_path.iterdir()) == before


# ------------------------------------------------------------------ 4: seeds


@pytest.mark.parametrize(
    "argv",
    [
        ["simulate", "station", "--seed", "-1", "--out", "{o}"],
        ["simulate", "station", "--seed", "-1", "--out", "{o}", "--dry-run"],
        ["plan", "station", "--from", "stand_rack2", "--to", "stand_car1", "--seed", "-1"],
        ["train", "--virtual", "2", "--seed", "-1", "-o", "{o}/m.npz"],
    ],
)
def test_negative_seed_is_refused_everywhere(argv, tmp_path, capsys, no_work):
    argv = [a.format(o=tmp_path / "out") for a in argv]
    err = refused(argv, capsys, tmp_path)
    assert "argument --seed: the seed must be a whole number >= 0, got -1" in err


def test_api_names_a_bad_seed_or_rng(scenes_dir):
    from mjwalk.cycle.simulate import simulate_cycle, simulate_cycles
    from mjwalk.plan.walks import plan_walk, plan_walks
    from mjwalk.world import shared_workplace

    wp = shared_workplace(scenes_dir / "assembly_station.xml")
    spec = scenes_dir / "assembly_station.toml"
    cases = [
        (lambda: plan_walks(wp, "stand_rack2", "stand_car1", object(), n=1, seed=-1), "seed"),
        (lambda: plan_walks(wp, "stand_rack2", "stand_car1", object(), n=1, seed=1.5), "seed"),
        (lambda: plan_walk(wp, "stand_rack2", "stand_car1", object(), rng="abc"), "rng"),
        (lambda: plan_walk(wp, "stand_rack2", "stand_car1", object(), rng=-3), "rng"),
        (lambda: simulate_cycles(spec, runs=1, seed=-1), "seed"),
        (lambda: simulate_cycle(spec, rng=-1), "rng"),
        (lambda: simulate_cycle(spec, rng="seed"), "rng"),
    ]
    for call, arg in cases:
        with pytest.raises(InputError, match=rf"^\w+: {arg} must be a"):
            call()


# ------------------------------------------------------------------ 8: output paths


def test_scene_import_output_checked_before_work(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(
        "mjwalk.world.meshimport.convex_parts", lambda *a, **k: pytest.fail("decomposed")
    )
    stl = tmp_path / "box.stl"
    _write_box_stl(stl, [1.0, 1.0, 1.0])
    folder = tmp_path / "scene.xml"
    folder.mkdir()
    blocker = tmp_path / "blocker"
    blocker.write_text("a file")
    for out, message in (
        (folder, f"-o/--output '{folder}' is a folder; give a file name"),
        (blocker / "s.xml", f"'{blocker}' is a file, not a folder"),
        (tmp_path / "scene.txt", "unsupported file type ('.txt'); use one of .xml"),
    ):
        err = refused(["scene-import", stl, "-o", out], capsys, tmp_path)
        assert message in err


def test_render_output_that_is_a_folder(station_walk, tmp_path, capsys, no_work):
    folder = tmp_path / "v.mp4"
    folder.mkdir()
    err = refused(["render", station_walk, "--scene", "station", "-o", folder], capsys, tmp_path)
    assert f"-o/--output '{folder}' is a folder; give a file name" in err


# ------------------------------------------------------------------ 10: open concave meshes


def _prism(ring, height):
    """A closed prism (outward normals) over a simple CCW polygon ``ring``, as a trimesh."""
    import shapely
    import trimesh

    ring = np.asarray(ring, float)
    n = len(ring)
    index = {tuple(p): i for i, p in enumerate(ring)}
    faces = []
    for tri in shapely.get_parts(shapely.constrained_delaunay_triangles(shapely.Polygon(ring))):
        c = [index[tuple(p)] for p in np.asarray(tri.exterior.coords)[:3]]
        p = ring[c]
        if (p[1, 0] - p[0, 0]) * (p[2, 1] - p[0, 1]) < (p[2, 0] - p[0, 0]) * (p[1, 1] - p[0, 1]):
            c = c[::-1]
        faces += [[c[0] + n, c[1] + n, c[2] + n], [c[0], c[2], c[1]]]
    for i in range(n):
        j = (i + 1) % n
        faces += [[i, j, j + n], [i, j + n, i + n]]
    verts = np.vstack([np.c_[ring, np.zeros(n)], np.c_[ring, np.full(n, height)]])
    return trimesh.Trimesh(verts, np.array(faces))


#: A U in plan (3 x 2 m, its 1 m wide inside open towards +y), 1 m high.
U_RING = [(0, 0), (3, 0), (3, 2), (2, 2), (2, 0.5), (1, 0.5), (1, 2), (0, 2)]


def _open_meshes():
    import trimesh

    u = _prism(U_RING, 1.0)
    missing = u.copy()
    missing.update_faces(np.arange(len(missing.faces)) != 3)
    inverted = u.copy()
    inverted.invert()
    a = trimesh.creation.box(bounds=[[0, 0, 0], [1, 1, 1]])
    b = trimesh.creation.box(bounds=[[1, 1, 0], [2, 2, 1]])
    edge = trimesh.util.concatenate([a, b])
    edge.merge_vertices()
    # a point of free floor each mesh's convex hull covers (the U's inside, the boxes' gap)
    return {
        "u-missing-triangle": (missing, (1.5, 1.5, 0.5)),
        "u-inverted-normals": (inverted, (1.5, 1.5, 0.5)),
        "boxes-sharing-an-edge": (edge, (0.5, 1.5, 0.5)),
    }


@pytest.mark.parametrize("case", list(_open_meshes()))
def test_open_concave_meshes_are_decomposed(case, tmp_path):
    import mujoco
    from scipy.spatial import Delaunay

    from mjwalk.world.meshimport import geom_mesh_world, import_scene

    mesh, free = _open_meshes()[case]
    assert not mesh.is_volume  # the defect's input: not a closed volume
    stl = tmp_path / "part.stl"
    mesh.export(stl)
    out = tmp_path / "scene.xml"
    result = import_scene(stl, out)
    assert result.parts.get("part", 0) >= 2
    model = mujoco.MjModel.from_xml_path(str(out))
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    meshes = [g for g in range(model.ngeom) if model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH]
    assert len(meshes) == result.parts["part"]
    for g in meshes:  # MuJoCo collides each part's convex hull: none may cover the point
        verts = geom_mesh_world(model, data, g)[0]
        assert Delaunay(verts).find_simplex(np.array(free)) < 0, model.geom(g).name


# ------------------------------------------------------------------ 11: threshold


@pytest.mark.parametrize("value", ["0", "-1", "2"])
def test_scene_import_threshold_is_range_checked(value, tmp_path, capsys):
    stl = tmp_path / "box.stl"
    _write_box_stl(stl, [1.0, 1.0, 1.0])
    err = refused(["scene-import", stl, "-o", tmp_path / "s.xml", "--threshold", value], capsys)
    assert f"--threshold {float(value)!r}: CoACD's concavity threshold must lie in [0.01, 1]" in err
    assert not (tmp_path / "s.xml").exists()


def test_nan_vertex_is_named(tmp_path, capsys):
    obj = tmp_path / "nan.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 nan\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n")
    err = refused(["scene-import", obj, "-o", tmp_path / "s.xml"], capsys, tmp_path)
    assert "vertex 3 (of 4) is not finite: [0.0, 1.0, nan]" in err


# ------------------------------------------------------------------ 12, 13: walk files, fps


def _edited(walk_path, tmp_path, **changes):
    """A copy of a walk file with arrays replaced (``changes``: name -> function of the array)."""
    with np.load(walk_path, allow_pickle=False) as z:
        arrays = {k: z[k] for k in z.files}
    for name, fn in changes.items():
        arrays[name] = fn(arrays[name])
    out = tmp_path / "edited.npz"
    np.savez(out, **arrays)
    return out


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"xy": lambda a: a[:-5]}, "xy must have shape ("),
        ({"t": lambda a: a[::-1].copy()}, "t must start at 0 s"),
        ({"t": lambda a: np.r_[a[:3], a[1], a[4:]]}, "t must increase: sample 3"),
        ({"t": lambda a: a * 1e6}, "longer than 3600 s"),
        ({"step_range": lambda a: a + 10_000}, "step 0: samples"),
        ({"yaw": lambda a: np.r_[np.nan, a[1:]]}, "yaw must hold finite numbers"),
        ({"xy": lambda a: a + 1e9}, "the walk leaves the floor of 'assembly_station'"),
    ],
)
def test_edited_walk_files_are_refused(
    changes,
    message,
    station_walk,
    tmp_path,
    capsys,
    no_work,
):
    walk = _edited(station_walk, tmp_path, **changes)
    out = tmp_path / "v.mp4"
    err = refused(["render", walk, "--scene", "station", "-o", out, "--quiet"], capsys, tmp_path)
    assert message in err


def test_walk_file_with_disagreeing_step_arrays(station_walk, tmp_path):
    from mjwalk.plan.walkpath import WalkPath

    walk = _edited(station_walk, tmp_path, step_side=lambda a: a[:-1])
    with pytest.raises(ModelFileError, match="the step arrays disagree"):
        WalkPath.load(walk)


def test_fps_is_bounded(station_walk, tmp_path, capsys, no_work):
    argv = ["render", station_walk, "--scene", "station", "-o", tmp_path / "v.mp4"]
    err = refused([*argv, "--fps", "1e9"], capsys, tmp_path)
    assert "argument --fps: must be a frame rate above 0 and at most 240 frames per second" in err


def test_fps_is_bounded_in_the_api(tmp_path):
    from mjwalk.render import render_video

    with pytest.raises(InputError, match="render_video: fps must be a frame rate"):
        render_video(type("T", (), {"fps": 30.0})(), tmp_path / "v.mp4", fps=1e9)
    assert list(tmp_path.iterdir()) == []


# ------------------------------------------------------------------ 14: write failures


def _limited(argv, limit_bytes, cwd):
    """Run ``python -m mjwalk argv`` with files limited to ``limit_bytes`` (a full disk)."""

    def limit():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))

    return subprocess.run(
        [sys.executable, "-m", "mjwalk", *map(str, argv)],
        preexec_fn=limit,
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=600,
    )


def _errors(stderr: str) -> list[str]:
    """stderr's lines but those a cold compile cache adds: the notice that the kernels are being
    compiled, and the warnings of kernels whose compiled code could not be cached (the file size
    limit stops those writes too when this process is the first to compile them,
    tests/test_jit.py; they run regardless)."""
    return [
        line
        for line in stderr.strip().splitlines()
        if "could not cache the compiled" not in line and not line.startswith("[mjwalk] compiling")
    ]


# the fast tier's longest (52 s in a quiet warm run: under the 20 000-block file limit its two
# processes cannot write numba's cache and compile planner and renderer afresh): its 5 min budget
@pytest.mark.slow
def test_write_failure_names_the_file(tmp_path, station_walk):
    png = tmp_path / "plan.png"
    argv = ["plan", "station", "--from", "stand_rack2", "--to", "stand_car1", "--n", "0"]
    r = _limited([*argv, "--png", png], 20_000, tmp_path)
    assert r.returncode == 2, r.stderr
    lines = _errors(r.stderr)
    assert len(lines) == 1, r.stderr
    assert lines[0].startswith(f"mjwalk: error: cannot write {png}: File too large")
    video = tmp_path / "v.mp4"
    argv = ["render", station_walk, "--scene", "station", "-o", video, "--quiet"]
    r = _limited(argv, 20_000, tmp_path)
    assert r.returncode == 2, r.stderr
    assert len(_errors(r.stderr)) == 1, r.stderr
    assert f"mjwalk: error: cannot write {video}: ffmpeg stopped writing it" in r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_atomic_path_leaves_nothing_on_failure(tmp_path):
    import errno

    from mjwalk._io import atomic_path

    target = tmp_path / "out" / "report.json"  # its folder is made, and removed again
    with pytest.raises(WriteError, match=rf"cannot write {target}: No space left on device"):
        with atomic_path(target) as tmp:
            tmp.write_text(json.dumps({"a": 1}))
            raise OSError(errno.ENOSPC, "No space left on device")
    with pytest.raises(RuntimeError):
        with atomic_path(target) as tmp:
            tmp.write_text("half")
            raise RuntimeError("killed mid-write")
    assert list(tmp_path.iterdir()) == []
    assert issubclass(WriteError, OSError)


# ------------------------------------------------------------------ 15: a site named like x,y


def test_a_site_named_like_coordinates_wins(tmp_path, capsys):
    from mjwalk.world import load_workplace

    scene = tmp_path / "sites.xml"
    scene.write_text(
        '<mujoco><worldbody><geom name="floor" type="plane" size="3 3 0.1"/>'
        '<site name="1.5,2" pos="-1 -1 0"/><site name="b" pos="1 -1 0"/></worldbody></mujoco>'
    )
    wp = load_workplace(scene)
    assert wp.point("1.5,2").tolist() == [-1.0, -1.0]  # the site, not (1.5, 2)
    assert wp.point("1.5,1").tolist() == [1.5, 1.0]  # no such site: coordinates
    code = cli.main(["plan", str(scene), "--from", "1.5,2", "--to", "b", "--n", "0"])
    out = capsys.readouterr().out
    length = float(out.split("length ")[1].split(" m")[0])
    # from the site (-1, -1) to b: 2 m (the grid route within a cell of it); from the point
    # (1.5, 2) it would be 3.04 m
    assert code == 0 and 2.0 <= length < 2.1, out
    with pytest.raises(SystemExit):
        cli.main(["plan", "--help"])
    assert "a site whose name reads as X,Y wins" in " ".join(capsys.readouterr().out.split())


def test_zip_of_a_walk_with_a_missing_array(station_walk, tmp_path):
    from mjwalk.plan.walkpath import WalkPath

    with np.load(station_walk, allow_pickle=False) as z:
        arrays = {k: z[k] for k in z.files if k != "yaw"}
    np.savez(tmp_path / "w.npz", **arrays)
    assert zipfile.is_zipfile(tmp_path / "w.npz")
    with pytest.raises(ModelFileError, match="not a complete walk-path file \\(no 'yaw'\\)"):
        WalkPath.load(tmp_path / "w.npz")


def test_scene_error_is_raised_for_a_folder_scene(tmp_path):
    from mjwalk.world import load_workplace, shared_workplace

    for fn in (load_workplace, shared_workplace):
        with pytest.raises(SceneError, match="is a folder, not an MJCF scene file"):
            fn(tmp_path)


# ------------------------------------------------------- issue 45: lifts beyond the NIOSH table

TOOL_CYCLE = """name = "tool only"
scene = "{scene}"
start = "stand_rack2"
takt = 90.0

[[task]]
kind = "pick"
site = "rack2_tool"
hand = "right"
part = "tool"
mass = 1.5
coupling = "good"

[[task]]
kind = "carry"
site = "stand_rack3"
route = "T5"
hand = "right"
part = "tool"

[[task]]
kind = "place"
site = "rack3_tool"
hand = "right"
part = "tool"
"""


def test_lifts_beyond_the_frequency_table_are_reported_without_an_index(
    tmp_path, scenes_dir, capsys
):
    """Issue 45: the station's tool picked, carried and placed, cycles back to back (2 lifts in
    about 7.5 s, some 16 lifts/min): Table 5 has no frequency multiplier there. Before:
    lifting_index=inf, rwl_kg=0.000, 'LI P50 nan | LI P95 nan' beside 'cycles LI>1 100 %' and
    numpy's 'invalid value encountered in scalar subtract'. Now every file says that the lifts
    have no index and why, and nothing warns."""
    import csv
    import warnings

    spec = tmp_path / "tool.toml"
    spec.write_text(TOOL_CYCLE.format(scene=scenes_dir / "assembly_station.xml"))
    out = tmp_path / "out"
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        code = cli.main(["simulate", str(spec), "--runs", "2", "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 0, err
    assert "RuntimeWarning" not in err
    rows = list(csv.DictReader((out / "ergonomics.csv").open()))
    lifts = [r for r in rows if r["kind"] in ("pick", "place")]
    assert len(lifts) == 4
    for r in lifts:
        assert float(r["lifts_per_min"]) > 11  # beyond the long-duration column (V >= 75 cm)
        assert r["lifting_index"] == "" and r["rwl_kg"] == "0.000"
        assert r["lifting_index_note"].startswith("no lifting index: lifting frequency")
        assert "Table 5" in r["lifting_index_note"]
    md = (out / "report.md").read_text()
    section = md[md.index("## Ergonomics") :]
    assert "nan" not in section and "inf" not in section.replace("information", "")
    assert "No NIOSH lifting index for 4 of 4 lifts (2 of 2 cycles with lifts" in section
    overall = json.loads((out / "report.json").read_text())["ergonomics"]["overall"]
    assert overall["lifting_index"]["n"] == 0 and overall["cycles_li_over_1"]["share"] is None
    w = overall["lifting_index_not_computed"]
    assert (w["lifts"], w["cycles"]["k"]) == (4, 2)
    assert all("beyond the NIOSH frequency table" in k for k in w["limits"])
