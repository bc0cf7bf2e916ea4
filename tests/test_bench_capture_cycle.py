"""benchmarks/bench_capture_cycle.py: bad input stops it with a clear error (exit status 2),
and the cycle copy it simulates names both arms' models."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
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


def test_the_cycle_copy_names_both_arms_models(tmp_path, scenes_dir):
    from mjwalk.arms import reachgen
    from mjwalk.arms.reach import ReachModel
    from mjwalk.cycle.spec import load_cycle_spec

    data = reachgen.generate("endpoints", 30, np.random.default_rng(0))
    model = ReachModel(data.lengths, dcs={"rng": 0}).fit(data.constraints, data.directions)
    model.save(tmp_path / "l.npz")
    model.save(tmp_path / "r.npz")
    cycle = bench.with_models(
        scenes_dir / "assembly_station.toml", tmp_path, tmp_path / "l.npz", tmp_path / "r.npz"
    )
    spec = load_cycle_spec(cycle)
    assert spec.reach_model == str(tmp_path / "l.npz")
    assert spec.reach_model_right == str(tmp_path / "r.npz")
    assert spec.scene == scenes_dir / "assembly_station.xml"
    assert len(spec.tasks) == len(load_cycle_spec(scenes_dir / "assembly_station.toml").tasks)
