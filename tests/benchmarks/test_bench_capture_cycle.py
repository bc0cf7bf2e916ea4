"""benchmarks/bench_capture_cycle.py: bad input stops it with a clear error (exit status 2),
and the cycle copy it simulates names both arms' models."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from mjwalk.errors import MjwalkError

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
bench = pytest.importorskip("bench_capture_cycle")


def test_bad_input_is_named(tmp_path, capsys):
    assert bench.main(["--data", str(tmp_path), "--runs", "0"]) == 2
    assert "--runs must be >= 1, got 0" in capsys.readouterr().err
    assert bench.main(["--data", str(tmp_path)]) == 2
    assert "no raise-up-left/right-hand clips" in capsys.readouterr().out
    (tmp_path / "x_raise-up-left-hand_a_001.bvh").write_text("garbage\n")
    assert bench.main(["--data", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("bench_capture_cycle: error:") and "x_raise-up-left-hand_a_001" in err


def test_the_capture_cycle_runs_both_arms_models(tmp_path, scenes_dir):
    from mjwalk.arms import reachgen
    from mjwalk.arms.reach import ReachModel
    from mjwalk.cycle.context import context_of
    from mjwalk.cycle.spec import load_cycle_spec

    data = reachgen.generate("endpoints", 30, np.random.default_rng(0))
    model = ReachModel(data.lengths, dcs={"rng": 0}).fit(data.constraints, data.directions)
    model.save(tmp_path / "l.npz")
    model.save(tmp_path / "r.npz")
    spec = bench.capture_spec(
        scenes_dir / "assembly_station.toml", tmp_path / "l.npz", tmp_path / "r.npz"
    )
    assert spec.reach_model == str(tmp_path / "l.npz")
    assert spec.reach_model_right == str(tmp_path / "r.npz")
    assert spec.tasks == load_cycle_spec(scenes_dir / "assembly_station.toml").tasks
    # the context the runs get has both models, not the file's defaults
    ctx = context_of(spec)
    assert ctx.reach_model.n_neurons == model.n_neurons
    assert ctx.reach_model_right is not None
    # a model of the wrong kind is named before any work
    (tmp_path / "bad.npz").write_bytes(b"not a model")
    with pytest.raises(MjwalkError, match="reach_right"):
        bench.capture_spec(
            scenes_dir / "assembly_station.toml", tmp_path / "l.npz", tmp_path / "bad.npz"
        )
