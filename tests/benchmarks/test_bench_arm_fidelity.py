"""benchmarks/bench_arm_fidelity.py: bad input is named (exit status 2), and on the station the
humanoid's hand follows the reach model's planned path with no joint asked beyond its range."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
bench = pytest.importorskip("bench_arm_fidelity")


def test_bad_input_is_named(tmp_path, capsys):
    assert bench.main(["--seeds", "0"]) == 2
    assert "--seeds must be >= 1, got 0" in capsys.readouterr().err
    assert bench.main(["--cycle", str(tmp_path / "none.toml")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("bench_arm_fidelity: error:") and "none.toml" in err


def test_the_hand_follows_the_planned_path(scenes_dir, capsys):
    """Seed 0 of the station, 14 reaches: the hand within 1 mm of the model's path (the
    generator's wrist hung beyond its range before: median 52 mm, max 155 mm off)."""
    assert bench.main(["--cycle", str(scenes_dir / "assembly_station.toml"), "--seeds", "1"]) == 0
    out = capsys.readouterr().out
    worst = float(re.search(r"planned path, mm: .*max (\d+)", out).group(1))
    assert worst <= 1.0, out
    assert "beyond their ranges (reaches): none" in out
    # the wrist rarely needs its range's edge (turned there, not past it: wrist_in_range);
    # 16.5 % / 8.2 % of frames with the generator before 2026-11-27, 0.2 % of deviation with
    # the default model trained up to a top shelf (reach model v7); 1.1 % of flexion (20 of
    # 1761 frames) since the walks steer back to their guide (issue 48 moved seed 0's stands a
    # little): a guard against the generator's 16.5 %, not a published limit
    flex, dev = map(float, re.search(r"flexion ([\d.]+)%, deviation ([\d.]+)%", out).groups())
    assert flex <= 2.0 and dev <= 2.0, out
