"""The WalkPath (mjwalk.plan.walkpath): its file round trip and its consistency checks."""

from __future__ import annotations

import numpy as np
import pytest

from mjwalk.errors import InputError, ModelFileError
from mjwalk.gait.default import default_model
from mjwalk.plan.synthetic import synthetic_walk
from mjwalk.plan.walkpath import WalkPath
from mjwalk.plan.walks import plan_walk
from mjwalk.world import load_workplace


@pytest.fixture(scope="module")
def model():
    return default_model(progress=False)


def test_walkpath_roundtrip(model, scenes_dir, tmp_path):
    wp = load_workplace(scenes_dir / "assembly_station.xml")
    p = plan_walk(wp, "stand_car1", "stand_rack3", model, rng=1)
    p.save(tmp_path / "walk.npz")
    q = WalkPath.load(tmp_path / "walk.npz")
    np.testing.assert_array_equal(p.xy, q.xy)
    assert [s.side for s in p.steps] == [s.side for s in q.steps]
    assert q.meta["planner"] == "hybrid_astar"
    assert p.length > np.linalg.norm(wp.point("stand_rack3") - wp.point("stand_car1")) - 0.25


def test_walkpath_length_duration_and_footprints():
    w = synthetic_walk(n_steps=4, hold=0.0)
    assert w.duration == pytest.approx(w.t[-1])
    assert w.length == pytest.approx(np.linalg.norm(np.diff(w.xy, axis=0), axis=1).sum())
    fp = w.footprints()
    assert fp.shape == (4, 4)
    assert fp[:, 0].tolist() == [0.0, 1.0, 0.0, 1.0]  # left, right, left, right
    w.validate()  # a consistent walk passes


def test_walkpath_validate_names_the_fault():
    w = synthetic_walk(n_steps=2)
    w.t = w.t[::-1].copy()
    with pytest.raises(InputError, match="edited: t must start at 0"):
        w.validate("edited")
    w = synthetic_walk(n_steps=2)
    w.steps[0].side = "middle"
    with pytest.raises(InputError, match="step 0: side"):
        w.validate()


def test_walkpath_load_refuses_a_foreign_file(tmp_path):
    path = tmp_path / "other.npz"
    np.savez(path, x=np.zeros(3))
    with pytest.raises(ModelFileError):
        WalkPath.load(path)


def test_heights_over_levels_round_trip_and_are_checked(tmp_path):
    flat = synthetic_walk(n_steps=4)
    assert flat.is_flat and not flat.ground.any()
    flat.save(tmp_path / "flat.npz")
    with np.load(tmp_path / "flat.npz") as f:
        assert "z" not in f and "step_z" not in f  # a flat walk's file is as before levels
    up = synthetic_walk(n_steps=4)
    up.z = np.linspace(0.0, 0.34, len(up.t))  # a ramp onto a platform
    up.steps[-1].foot_z = 0.34
    assert not up.is_flat
    up.save(tmp_path / "up.npz")
    back = WalkPath.load(tmp_path / "up.npz")
    np.testing.assert_array_equal(back.ground, up.z)
    assert back.steps[-1].foot_z == 0.34 and back.steps[0].stance_z == 0.0
    up.z = up.z[:-1]
    with pytest.raises(InputError, match="z must have shape"):
        up.validate()
