"""Bad input fails fast with a named error (issue 17, item 1).

Every command-line case asserts the message names the problem, the exit status (2, as argparse
and ``mjwalk: error:`` both give), that the work functions were never called (they are replaced
by sentinels that fail the test) and took less than :data:`FAST` seconds, and that no output
file was left behind. The Python API cases assert the named error type and message.
"""

from __future__ import annotations

import dataclasses
import importlib
import time

import numpy as np
import pytest

from mjwalk import cli
from mjwalk.errors import CycleSpecError, InputError, ModelFileError, SceneError

#: A refusal happens before any work: scene loading and argument checks only (seconds on a
#: loaded 2-core machine; planning, training, simulating or rendering take far longer).
FAST = 10.0

WORK = (
    "mjwalk.plan.grid.plan_grid",
    "mjwalk.plan.walks.plan_walks",
    "mjwalk.cycle.simulate.prepare",
    "mjwalk.cycle.simulate.simulate_cycles",
    "mjwalk.render.render_video",
    "mjwalk.gait.training.train_model_file",
)


class WorkStarted(AssertionError):
    pass


@pytest.fixture
def no_work(monkeypatch):
    """Replace every work function with a sentinel that fails the test when called."""

    def sentinel(name):
        def fail(*args, **kwargs):
            raise WorkStarted(f"{name} was called before the bad input was refused")

        return fail

    # import every module first: a module imported while another's function is patched would
    # bind the sentinel for good (mjwalk.cycle.context takes plan_grid by name)
    for target in WORK:
        importlib.import_module(target.rsplit(".", 1)[0])
    for target in WORK:
        monkeypatch.setattr(target, sentinel(target))


def refused(argv, capsys, tmp_path=None) -> str:
    """Run the CLI on ``argv``; assert exit status 2 within FAST seconds and no new file in
    ``tmp_path``; return stderr."""
    before = set(tmp_path.rglob("*")) if tmp_path is not None else set()
    t0 = time.perf_counter()
    try:
        code = cli.main([str(a) for a in argv])
    except SystemExit as exc:  # argparse's refusals
        code = exc.code
    seconds = time.perf_counter() - t0
    err = capsys.readouterr().err
    assert code == 2, err
    assert seconds < FAST, f"refused after {seconds:.1f} s"
    assert "Traceback" not in err
    if tmp_path is not None:
        assert set(tmp_path.rglob("*")) == before, "an output file was left behind"
    return err


# ------------------------------------------------------------------ points


def test_negative_coordinates_are_accepted(capsys, scenes_dir, tmp_path):
    png = tmp_path / "plan.png"
    code = cli.main(
        ["plan", "station", "--from", "-2.5,-1.5", "--to", "stand_car1", "--n", "0"]
        + ["--png", str(png)]
    )
    out = capsys.readouterr().out
    assert code == 0
    assert "grid A*  -2.5,-1.5 -> stand_car1" in out
    assert png.stat().st_size > 0


@pytest.mark.parametrize(
    ("point", "message"),
    [
        ("1.2.3,0", "'1.2.3' is not a number"),
        ("nan,0", "coordinates must be finite numbers, got 'nan'"),
        ("inf,-inf", "coordinates must be finite numbers, got 'inf'"),
        ("1,2,3", "expected 2 comma-separated numbers"),
        ("1e9,1e9", "is off the floor"),
        ("stand_rak2", "no site named 'stand_rak2'; did you mean stand_rack2"),
        ("1,1", "inside obstacle 'car_body'"),
    ],
)
def test_bad_points(point, message, capsys, no_work, tmp_path):
    err = refused(["plan", "station", "--from", point, "--to", "stand_car1"], capsys, tmp_path)
    assert message in err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--radius", "-1"], "argument --radius: must be a positive number, got -1"),
        (["--radius", "nan"], "argument --radius: 'nan' is not a finite number"),
        (["--n", "-3"], "argument --n: must be 0 or more, got -3"),
        (["--n", "two"], "argument --n: 'two' is not a whole number"),
        (["--png", "out.xyz"], "--png 'out.xyz': unsupported file type ('.xyz')"),
        (["--png", "plan"], "--png 'plan': unsupported file type (no extension)"),
        (["--cost", "time"], "argument --cost: invalid choice: 'time'"),
    ],
)
def test_bad_plan_options(argv, message, capsys, no_work, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    err = refused(
        ["plan", "station", "--from", "stand_rack2", "--to", "stand_car1", *argv], capsys, tmp_path
    )
    assert message in err


def test_api_refuses_non_finite_points(scenes_dir):
    from mjwalk.gait.default import default_model
    from mjwalk.plan.grid import plan_grid
    from mjwalk.plan.hybrid import HybridPlanner
    from mjwalk.plan.walks import plan_walks
    from mjwalk.world import shared_workplace

    wp = shared_workplace(scenes_dir / "assembly_station.xml")
    model = default_model()
    calls = [
        lambda: wp.point((np.nan, 0.0)),
        lambda: wp.point("nan,0"),
        lambda: wp.clearance(np.array([[0.0, 0.0], [np.nan, 1.0]])),
        lambda: wp.walk_clearance(np.array([np.inf, 0.0])),
        lambda: plan_grid(wp, (np.nan, 0.0), "stand_car1"),
        lambda: plan_grid(wp, "stand_rack2", (np.inf, 1.0)),
        lambda: plan_walks(wp, (np.nan, 0.0), "stand_car1", model, n=1),
        lambda: HybridPlanner(wp, (0.0, np.inf), model),
        lambda: HybridPlanner(wp, "stand_car1", model).plan((1.0, 2.0, np.nan), 0),
        lambda: HybridPlanner(wp, "stand_car1", model).plan("1,2,nan", 0),
    ]
    for call in calls:
        with pytest.raises(InputError, match="finite"):
            call()
    # InputError is also a ValueError: callers that caught the raw error keep working
    assert issubclass(InputError, ValueError)


def test_api_refuses_bad_radius_and_count(scenes_dir):
    from mjwalk.plan.grid import plan_grid
    from mjwalk.plan.walks import plan_walks
    from mjwalk.world import shared_workplace

    wp = shared_workplace(scenes_dir / "assembly_station.xml")
    for radius in (-1.0, 0.0, float("nan")):
        with pytest.raises(InputError, match="body radius must be a positive number"):
            plan_grid(wp, "stand_rack2", "stand_car1", radius=radius)
    with pytest.raises(InputError, match="n must be a whole number of walks >= 0, got -3"):
        plan_walks(wp, "stand_rack2", "stand_car1", model=object(), n=-3)
    assert plan_walks(wp, "stand_rack2", "stand_car1", model=object(), n=0) == []


# ------------------------------------------------------------------ output paths


def test_out_that_is_a_file(capsys, no_work, tmp_path):
    out = tmp_path / "report"
    out.write_text("not a folder")
    err = refused(["simulate", "station", "--out", out, "--runs", "2"], capsys, tmp_path)
    assert f"--out '{out}' is a file, not a folder" in err
    assert out.read_text() == "not a folder"


@pytest.mark.parametrize(
    ("argv", "option"),
    [
        (["simulate", "station", "--out", "{f}/out"], "--out"),
        (
            ["plan", "station", "--from", "stand_rack2", "--to", "stand_car1"]
            + ["--png", "{f}/p.png"],
            "--png",
        ),
        (
            ["plan", "station", "--from", "stand_rack2", "--to", "stand_car1"]
            + ["--save", "{f}/walk"],
            "--save",
        ),
        (["render", "{w}", "--scene", "station", "-o", "{f}/v.mp4"], "-o/--output"),
        (["train", "--virtual", "2", "-o", "{f}/m.npz"], "-o/--output"),
    ],
)
def test_output_under_a_file_is_unwritable(argv, option, capsys, no_work, tmp_path):
    blocker = tmp_path / "blocker"
    blocker.write_text("a file where a folder should be")
    walk = tmp_path / "walk.npz"
    walk.write_bytes(b"")
    argv = [a.format(f=blocker, w=walk) for a in argv]
    err = refused(argv, capsys, tmp_path)
    assert option in err
    assert f"'{blocker}' is a file, not a folder, so nothing can be written under it" in err


def test_unwritable_folder(capsys, no_work, tmp_path):
    import os

    if os.geteuid() == 0:
        pytest.skip("root writes into read-only folders")
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        err = refused(["simulate", "station", "--out", locked / "out"], capsys, tmp_path)
        assert f"the folder '{locked}' is not writable" in err
    finally:
        locked.chmod(0o700)


def test_render_refuses_non_mp4_and_bad_sizes(capsys, no_work, tmp_path):
    walk = tmp_path / "walk.npz"
    walk.write_bytes(b"")
    base = ["render", str(walk), "--scene", "station", "-o"]
    err = refused([*base, str(tmp_path / "v.avi")], capsys, tmp_path)
    assert "unsupported file type ('.avi'); use one of .mp4" in err
    for opt, value in (("--width", "0"), ("--height", "-480"), ("--width", "641")):
        err = refused([*base, str(tmp_path / "v.mp4"), opt, value], capsys, tmp_path)
        assert f"argument {opt}: must be an even number of pixels from 16 to 8192" in err
    err = refused([*base, str(tmp_path / "v.mp4"), "--fps", "0"], capsys, tmp_path)
    assert "argument --fps: must be a frame rate above 0 and at most 240" in err


# ------------------------------------------------------------------ walks and scenes


@pytest.fixture(scope="module")
def station_walk(tmp_path_factory, scenes_dir):
    from mjwalk.gait.default import default_model
    from mjwalk.plan.walks import plan_walks
    from mjwalk.world import shared_workplace

    wp = shared_workplace(scenes_dir / "assembly_station.xml")
    walk = plan_walks(wp, "stand_rack2", "stand_car1", default_model(), n=1, seed=3)[0]
    path = tmp_path_factory.mktemp("walk") / "w.npz"
    walk.save(path)
    return path


def test_walk_records_its_scene(station_walk, scenes_dir):
    from mjwalk.plan.grid import plan_grid
    from mjwalk.plan.walkpath import WalkPath
    from mjwalk.world import load_workplace

    wp = load_workplace(scenes_dir / "assembly_station.xml")
    walk = WalkPath.load(station_walk)
    assert walk.meta["scene"] == "assembly_station"
    assert walk.meta["scene_fingerprint"] == wp.fingerprint
    assert plan_grid(wp, "stand_rack2", "stand_car1").meta["scene_fingerprint"] == wp.fingerprint
    walk.check_scene(wp)  # same scene: passes
    # the fingerprint is of the geometry: the same scene elsewhere matches, a moved rack not
    assert load_workplace(scenes_dir / "corridor.xml").fingerprint != wp.fingerprint


def test_fingerprint_follows_obstacle_geometry(scenes_dir, tmp_path):
    from mjwalk.world import load_workplace

    text = (scenes_dir / "assembly_station.xml").read_text()
    (tmp_path / "copy.xml").write_text(text)
    pillar = '<geom name="stray_box" type="box" size="0.1 0.1 0.5" pos="3.5 2.5 0.5"/>'
    (tmp_path / "moved.xml").write_text(text.replace("</worldbody>", pillar + "</worldbody>"))
    a = load_workplace(scenes_dir / "assembly_station.xml").fingerprint
    assert load_workplace(tmp_path / "copy.xml").fingerprint == a
    assert load_workplace(tmp_path / "moved.xml").fingerprint != a


def test_render_in_another_scene_is_refused(station_walk, capsys, no_work, tmp_path):
    out = tmp_path / "v.mp4"
    err = refused(
        ["render", station_walk, "--scene", "corridor", "-o", out, "--quiet"], capsys, tmp_path
    )
    assert "planned in scene 'assembly_station'" in err
    assert "not in 'corridor'" in err
    assert "--force" in err


def test_render_in_another_scene_with_force(station_walk, capsys, monkeypatch, tmp_path):
    calls = []
    monkeypatch.setattr("mjwalk.render.render_video", lambda tl, path, **kw: calls.append(path))
    out = tmp_path / "v.mp4"
    argv = ["render", str(station_walk), "--scene", "corridor", "-o", str(out), "--force"]
    assert cli.main(argv) == 0
    assert calls == [out]


def test_check_collisions_in_another_scene(station_walk, scenes_dir):
    from mjwalk.plan.walkpath import WalkPath
    from mjwalk.timeline import check_collisions

    walk = WalkPath.load(station_walk)
    with pytest.raises(SceneError, match="planned in scene 'assembly_station'"):
        check_collisions(walk, scenes_dir / "open_floor.xml")
    assert isinstance(check_collisions(walk, scenes_dir / "open_floor.xml", force=True), list)


def test_render_video_api_refuses_empty_frames(tmp_path):
    from mjwalk.render import render_video

    out = tmp_path / "v.mp4"
    timeline = type("T", (), {"fps": 30.0})()
    with pytest.raises(InputError, match="width and height must be even numbers of pixels"):
        render_video(timeline, out, size=(0, 480))
    assert not out.exists()


# ------------------------------------------------------------------ scenes


def test_tilted_floor_is_named(tmp_path):
    from mjwalk.world import load_workplace

    scene = tmp_path / "tilted.xml"
    scene.write_text(
        '<mujoco><worldbody><geom name="floor" type="plane" size="4 3 0.1" euler="10 0 0"/>'
        '<geom name="box" type="box" size="0.2 0.2 0.5" pos="1 1 0.5"/></worldbody></mujoco>'
    )
    with pytest.raises(SceneError, match=r"plane 'floor' is tilted 10\.0 deg from horizontal"):
        load_workplace(scene)


# ------------------------------------------------------------------ cycle files


def _spec_with(tmp_path, scenes_dir, extra: str):
    text = (scenes_dir / "assembly_station.toml").read_text()
    text = text.replace(
        'scene = "assembly_station.xml"', f'scene = "{scenes_dir}/assembly_station.xml"'
    )
    path = tmp_path / "cycle.toml"
    path.write_text(text + extra)
    return path


def test_huge_duration_is_refused(tmp_path, scenes_dir, capsys, no_work):
    from mjwalk.cycle.spec import load_cycle_spec

    spec = _spec_with(tmp_path, scenes_dir, '\n[[task]]\nkind = "wait"\nduration = 1e12\n')
    with pytest.raises(
        CycleSpecError, match=r"'duration' in task \d+ must be between 0 and 3600 s"
    ):
        load_cycle_spec(spec)
    out = tmp_path / "out"
    err = refused(["simulate", spec, "--out", out], capsys, tmp_path)
    assert "must be between 0 and 3600 s, got 1e+12" in err
    two = '\n[[task]]\nkind = "wait"\nduration = 2000\n' * 2
    with pytest.raises(CycleSpecError, match=r"durations add up to 4\d{3}(\.\d+)? s, more than"):
        load_cycle_spec(_spec_with(tmp_path, scenes_dir, two))


def test_huge_duration_in_a_python_spec(scenes_dir):
    from mjwalk.cycle.simulate import simulate_cycle
    from mjwalk.cycle.spec import load_cycle_spec

    spec = load_cycle_spec(scenes_dir / "assembly_station.toml")
    tasks = [*spec.tasks, dataclasses.replace(spec.tasks[-1], kind="wait", duration=1e12)]
    t0 = time.perf_counter()
    with pytest.raises(CycleSpecError, match="durations add up to 1e\\+12 s"):
        simulate_cycle(dataclasses.replace(spec, tasks=tasks), 0)
    assert time.perf_counter() - t0 < 60  # refused before the timeline, not a MemoryError


# ------------------------------------------------------------------ model files and capture


def test_corrupt_model_file(tmp_path, capsys, no_work):
    from mjwalk.gait.model import StepModel

    junk = tmp_path / "model.npz"
    junk.write_bytes(np.random.default_rng(0).bytes(3000))
    with pytest.raises(ModelFileError) as info:
        StepModel.load(junk)
    assert "not an mjwalk step-model file" in str(info.value)
    assert "allow_pickle" not in str(info.value)
    pickled = tmp_path / "pickled.npz"
    np.savez(pickled, header=np.array([{"format": 1}], dtype=object))
    with pytest.raises(ModelFileError, match="holds Python objects") as info:
        StepModel.load(pickled)
    assert "allow_pickle" not in str(info.value)
    argv = ["plan", "station", "--from", "stand_rack2", "--to", "stand_car1", "--model", junk]
    err = refused(argv, capsys, tmp_path)
    assert "not an mjwalk step-model file" in err


def _capture_shaped_reach_model(path):
    """A small reach model shaped like one trained on capture raises (mjwalk.arm_movements):
    9 constraint values (start elbow, start hand, end hand), 2 segments (no hand)."""
    from mjwalk.arms import reachgen
    from mjwalk.arms.reach import ReachModel

    data = reachgen.generate("endpoints", 30, np.random.default_rng(0))
    elbow = data.directions[:, 0, 0] * data.lengths[0]
    C = np.c_[elbow, data.constraints]
    model = ReachModel(data.lengths[:2], dcs={"rng": 0, "max_neurons": 4})
    model.fit(C, data.directions[:, :, :2])
    model.save(path)
    return model


def test_reach_model_of_another_kind_is_refused(tmp_path, scenes_dir, capsys, no_work):
    from mjwalk.cycle.spec import load_cycle_spec

    _capture_shaped_reach_model(tmp_path / "raise.npz")
    spec = _spec_with(tmp_path, scenes_dir, "")
    spec.write_text(spec.read_text().replace('reach = "default"', 'reach = "raise.npz"'))
    with pytest.raises(CycleSpecError, match=r"key 'reach' in \[models\]: .*raise.npz: a scene"):
        load_cycle_spec(spec)
    err = refused(["simulate", spec, "--out", tmp_path / "out"], capsys, tmp_path)
    assert "this one takes 9 inputs and has 2 segments" in err
    assert "mjwalk.arm_movements" in err  # says what kind of model it is
    (tmp_path / "raise.npz").write_bytes(np.random.default_rng(0).bytes(3000))
    err = refused(["simulate", spec, "--out", tmp_path / "out"], capsys, tmp_path)
    assert "key 'reach' in [models]" in err and "not an mjwalk reach-model file" in err


def test_too_few_steps_names_the_minimum():
    from mjwalk.gait.default import train_model
    from mjwalk.gait.model import MIN_STEPS

    with pytest.raises(Exception, match=f"only 0 steps found in 0 takes; .* at least {MIN_STEPS}"):
        train_model([])


def test_train_bad_pca_variance(capsys, no_work, tmp_path):
    for value in ("0", "1.5", "nan"):
        err = refused(
            ["train", "--virtual", "2", "--pca-variance", value, "-o", tmp_path / "m.npz"],
            capsys,
            tmp_path,
        )
        assert "argument --pca-variance" in err


# ------------------------------------------------------------------ seeds


def test_runs_record_their_seed_and_rerun_alone(scenes_dir, tmp_path):
    import csv

    from mjwalk.cycle.simulate import simulate_cycle, simulate_cycles
    from mjwalk.report import write_report

    spec = scenes_dir / "assembly_station.toml"
    batch = simulate_cycles(spec, runs=3, seed=5, n_jobs=1, collisions=False, only=[1, 2])
    assert [(r.run, r.seed, r.entropy) for r in batch] == [(1, 5, [5, 1]), (2, 5, [5, 2])]
    # run 2 alone, from its recorded entropy, is the same cycle
    again = simulate_cycle(
        batch[1].spec,
        np.random.default_rng(np.random.SeedSequence(batch[1].entropy)),
        collisions=False,
    )
    assert again.cycle_time == batch[1].cycle_time
    assert [w.length for w in again.walks] == [w.length for w in batch[1].walks]
    path = write_report(batch, tmp_path / "report", baseline={})["cycles"]
    rows = list(csv.DictReader(path.open()))
    assert [(r["run"], r["seed"]) for r in rows] == [("1", "5"), ("2", "5")]
    with pytest.raises(InputError, match=r"run indices must lie in 0\.\.2"):
        simulate_cycles(spec, runs=3, seed=5, only=[3])


def test_only_run_out_of_range(capsys, no_work, tmp_path):
    err = refused(
        ["simulate", "station", "--runs", "3", "--only-run", "3", "--out", tmp_path / "o"],
        capsys,
        tmp_path,
    )
    assert "--only-run 3: runs are numbered 0 to 2 (--runs 3)" in err
    for opt, value, message in (
        ("--runs", "0", "must be at least 1"),
        ("--jobs", "0", "must be a number of processes >= 1, or -1"),
    ):
        err = refused(
            ["simulate", "station", opt, value, "--out", tmp_path / "o"], capsys, tmp_path
        )
        assert f"argument {opt}: {message}" in err
